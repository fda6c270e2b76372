# src/: the 2С42 front end, the machine, the session, reports and the CLI.
SRC_SRCS     := $(filter-out src/main.c src/tui.c src/tui_modbus.c,$(wildcard src/*.c))
SRC_OBJS     := $(SRC_SRCS:%.c=$(BUILD)/%.o)
# the curses front end links into s42 only (not the unit tests or fuzzers)
SRC_MAIN_OBJ := $(BUILD)/src/main.o $(BUILD)/src/tui.o $(BUILD)/src/tui_modbus.o
$(SRC_OBJS) $(SRC_MAIN_OBJ): MOD_CPPFLAGS := -Isrc -Ivm -Idisplay -Iinclude
# plot.c draws with cairo (the only part of src/ that needs it)
CAIRO_CFLAGS = $(call pkg,CAIRO_CFLAGS,--cflags cairo)
# cairo is loaded with dlopen when a plot is drawn (src/cairo_dl.c): linking
# it would load two dozen libraries at every start-up
$(BUILD)/src/plot.o $(BUILD)/src/cairo_dl.o: MOD_CPPFLAGS = -Isrc -Ivm -Idisplay -Iinclude $(CAIRO_CFLAGS)
LDLIBS += -ldl
# where `make install` puts the plugins: s42 looks there last.  plugin.o is
# rebuilt when PLUGINDIR changes (make install PREFIX=...): the stamp holds
# the value it was built with and is rewritten only when it differs.
$(BUILD)/src/plugin.o: CPPFLAGS += -DS42_PLUGINDIR='"$(PLUGINDIR)"'
$(BUILD)/src/plugin.o: $(BUILD)/src/plugindir.stamp
$(BUILD)/src/plugindir.stamp: FORCE
	@mkdir -p $(@D)
	@echo '$(PLUGINDIR)' | cmp -s - $@ || echo '$(PLUGINDIR)' > $@
.PHONY: FORCE
FORCE:
# tui.c draws with ncursesw
CURSES_CFLAGS = $(call pkg,CURSES_CFLAGS,--cflags ncursesw)
CURSES_LIBS   = $(call pkg,CURSES_LIBS,--libs ncursesw,-lncursesw)
$(BUILD)/src/tui.o: MOD_CPPFLAGS = -Isrc -Ivm -Idisplay -Iinclude $(CURSES_CFLAGS)
LDLIBS += $(CURSES_LIBS)
# modbus.c serves the machine over Modbus TCP with libmodbus
MODBUS_CFLAGS = $(call pkg,MODBUS_CFLAGS,--cflags libmodbus)
MODBUS_LIBS   = $(call pkg,MODBUS_LIBS,--libs libmodbus,-lmodbus)
$(BUILD)/src/modbus.o: MOD_CPPFLAGS = -Isrc -Ivm -Idisplay -Iinclude $(MODBUS_CFLAGS)
# and answers from its own thread
LDLIBS += $(MODBUS_LIBS) -pthread
