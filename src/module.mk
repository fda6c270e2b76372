# src/: one folder per part, each with its own module.mk and include path.
# A folder's objects see only the headers of the folders in its path, so a
# dependency that is not written here does not compile.  The paths say
# what each part may see today; README "How it is built" lists the
# crossings that the dialect seam still has to remove.
include src/core/module.mk
include src/dialect/2c42/module.mk
include src/machine/grinder/module.mk
include src/host/module.mk

# Everything but the hosts that link into s42 alone (the unit tests and the
# fuzzers link these).
SRC_SRCS := $(CORE_SRCS) $(DIALECT_SRCS) $(MACHINE_SRCS) $(HOST_LIB_SRCS)
SRC_OBJS := $(SRC_SRCS:%.c=$(BUILD)/%.o)
# What a test or a tool built outside these folders sees: all of it.
ALL_INC := $(HOST_INC)
LDLIBS += -ldl
