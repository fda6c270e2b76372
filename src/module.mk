# src/: the 2С42 front end, the machine, the session, reports and the CLI.
SRC_SRCS     := $(filter-out src/main.c src/tui.c src/tui_modbus.c,$(wildcard src/*.c))
SRC_OBJS     := $(SRC_SRCS:%.c=$(BUILD)/%.o)
# the curses front end links into s42 only (not the unit tests or fuzzers)
SRC_MAIN_OBJ := $(BUILD)/src/main.o $(BUILD)/src/tui.o $(BUILD)/src/tui_modbus.o
$(SRC_OBJS) $(SRC_MAIN_OBJ): MOD_CPPFLAGS := -Isrc -Ivm -Idisplay -Iinclude
# plot.c draws with cairo (the only part of src/ that needs it)
CAIRO_CFLAGS := $(shell pkg-config --cflags cairo 2>/dev/null)
# cairo is loaded with dlopen when a plot is drawn (src/cairo_dl.c): linking
# it would load two dozen libraries at every start-up
$(BUILD)/src/plot.o $(BUILD)/src/cairo_dl.o: MOD_CPPFLAGS := -Isrc -Ivm -Idisplay -Iinclude $(CAIRO_CFLAGS)
LDLIBS += -ldl
# where `make install` puts the plugins: s42 looks there last
$(BUILD)/src/plugin.o: CPPFLAGS += -DS42_PLUGINDIR='"$(PLUGINDIR)"'
# tui.c draws with ncursesw
CURSES_CFLAGS := $(shell pkg-config --cflags ncursesw 2>/dev/null)
CURSES_LIBS   := $(shell pkg-config --libs ncursesw 2>/dev/null || echo -lncursesw)
$(BUILD)/src/tui.o: MOD_CPPFLAGS := -Isrc -Ivm -Idisplay -Iinclude $(CURSES_CFLAGS)
LDLIBS += $(CURSES_LIBS)
# modbus.c serves the machine over Modbus TCP with libmodbus
MODBUS_CFLAGS := $(shell pkg-config --cflags libmodbus 2>/dev/null)
MODBUS_LIBS   := $(shell pkg-config --libs libmodbus 2>/dev/null || echo -lmodbus)
$(BUILD)/src/modbus.o: MOD_CPPFLAGS := -Isrc -Ivm -Idisplay -Iinclude $(MODBUS_CFLAGS)
# and answers from its own thread
LDLIBS += $(MODBUS_LIBS) -pthread
