# src/core/: the session (VM stepping, waits, sinks, the plugin host), the
# plugin loader, the restart state, diagnostics, the trace and the dump.
# It sees vm/, include/ and display/; and, until the dialect seam is done,
# the 2С42 front end's headers (the session is its runtime: kp.h) and the
# grinder's (machine.h).
CORE_SRCS := $(wildcard src/core/*.c)
CORE_INC  := -Isrc/core -Ivm -Iinclude -Idisplay -Isrc/dialect/2c42 -Isrc/machine/grinder
$(CORE_SRCS:%.c=$(BUILD)/%.o): MOD_CPPFLAGS = $(CORE_INC)
# where `make install` puts the plugins: s42 looks there last.  plugin.o is
# rebuilt when PLUGINDIR changes (make install PREFIX=...): the stamp holds
# the value it was built with and is rewritten only when it differs.
$(BUILD)/src/core/plugin.o: CPPFLAGS += -DS42_PLUGINDIR='"$(PLUGINDIR)"'
$(BUILD)/src/core/plugin.o: $(BUILD)/src/core/plugindir.stamp
$(BUILD)/src/core/plugindir.stamp: FORCE
	@mkdir -p $(@D)
	@echo '$(PLUGINDIR)' | cmp -s - $@ || echo '$(PLUGINDIR)' > $@
.PHONY: FORCE
FORCE:
