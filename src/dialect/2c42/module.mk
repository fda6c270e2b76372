# src/dialect/2c42/: the 2С42 front end -- lexer, parser, checks, emitter --
# its per-block record (kp.h), what a block means to the grinder (kpmach.c:
# the block as canonical machine calls), its session (session.c: the VM
# stepped against the grinder with the 2С42's waits, the dialog, teach-in
# and the plugin host of the plugin ABI; its runtime hooks in runtime.c:
# the machine work, G20, M19, the dialog, M16, M18), the plugin loader
# (plugin.c), the M15 restart state (state.c), its trace and dump
# (kpreport.c) and its entry in the registry (dialect.c).  It sees vm/,
# include/, display/ (the 2С42-65 screen), core's headers and its machine's.
C42_SRCS := $(wildcard src/dialect/2c42/*.c)
C42_INC  := -Isrc/dialect/2c42 -Isrc/core -Isrc/machine/grinder -Ivm -Iinclude -Idisplay
$(C42_SRCS:%.c=$(BUILD)/%.o): MOD_CPPFLAGS = $(C42_INC)
DIALECT_SRCS += $(C42_SRCS)
# registered: the build's dialect list names dialect_2c42
DIALECTS += 2c42
# where `make install` puts the plugins: s42 looks there last.  plugin.o is
# rebuilt when PLUGINDIR changes (make install PREFIX=...): the stamp holds
# the value it was built with and is rewritten only when it differs.
$(BUILD)/src/dialect/2c42/plugin.o: CPPFLAGS += -DS42_PLUGINDIR='"$(PLUGINDIR)"'
$(BUILD)/src/dialect/2c42/plugin.o: $(BUILD)/src/dialect/2c42/plugindir.stamp
$(BUILD)/src/dialect/2c42/plugindir.stamp: FORCE
	@mkdir -p $(@D)
	@echo '$(PLUGINDIR)' | cmp -s - $@ || echo '$(PLUGINDIR)' > $@
.PHONY: FORCE
FORCE:
