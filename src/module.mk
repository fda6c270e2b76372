# src/: one folder per part, each with its own module.mk and include path.
# A folder's objects see only the headers of the folders in its path, so a
# dependency that is not written here does not compile.  The paths say
# what each part may see today; README "How it is built" lists the
# crossings that the dialect seam still has to remove.
include src/core/module.mk
# every dialect's folder registers itself (DIALECTS += NAME): adding one
# edits no file here
include $(sort $(wildcard src/dialect/*/module.mk))
include $(sort $(wildcard src/machine/*/module.mk))
include src/host/module.mk

# Everything but the hosts that link into s42 alone (the unit tests and the
# fuzzers link these).
SRC_SRCS := $(CORE_SRCS) $(DIALECT_SRCS) $(MACHINE_SRCS) $(HOST_LIB_SRCS)
SRC_OBJS := $(SRC_SRCS:%.c=$(BUILD)/%.o) $(BUILD)/gen/dialects.o

# The dialect registry's list, generated from DIALECTS; rewritten only when
# the list changes (the stamp holds it).
$(BUILD)/gen/dialects.stamp: FORCE
	@mkdir -p $(@D)
	@echo '$(DIALECTS)' | cmp -s - $@ || echo '$(DIALECTS)' > $@
$(BUILD)/gen/dialects.c: $(BUILD)/gen/dialects.stamp scripts/gen-dialects.sh
	sh scripts/gen-dialects.sh $(DIALECTS) > $@
$(BUILD)/gen/dialects.o: $(BUILD)/gen/dialects.c
	$(CC) $(CPPFLAGS) -Isrc/core -Ivm $(WARN) $(CFLAGS) -c -o $@ $<
# What a test or a tool built outside these folders sees: all of it.
ALL_INC := $(HOST_INC) -Isrc/machine/lathe -Isrc/dialect/2u22
LDLIBS += -ldl
-include $(BUILD)/gen/dialects.d
