# src/host/: the commands (main), the headless runner, the terminal, the
# Modbus server, the plot, pacing and the operator script.  Hosts see
# every public header.
HOST_INC := -Isrc/host -Isrc/core -Isrc/dialect/2c42 -Isrc/machine/grinder -Ivm -Idisplay -Iinclude
# the curses front end links into s42 only (not the unit tests or fuzzers)
HOST_MAIN_SRCS := src/host/main.c src/host/tui.c src/host/tui_mrun.c src/host/tui_modbus.c
HOST_LIB_SRCS  := $(filter-out $(HOST_MAIN_SRCS),$(wildcard src/host/*.c))
SRC_MAIN_OBJ   := $(HOST_MAIN_SRCS:%.c=$(BUILD)/%.o)
$(HOST_LIB_SRCS:%.c=$(BUILD)/%.o) $(SRC_MAIN_OBJ): MOD_CPPFLAGS = $(HOST_INC)
# plot.c and lplot.c draw with cairo (the only parts of src/ that need it)
CAIRO_CFLAGS = $(call pkg,CAIRO_CFLAGS,--cflags cairo)
# cairo is loaded with dlopen when a plot is drawn (src/host/cairo_dl.c):
# linking it would load two dozen libraries at every start-up
$(BUILD)/src/host/plot.o $(BUILD)/src/host/lplot.o $(BUILD)/src/host/picture.o $(BUILD)/src/host/cairo_dl.o: MOD_CPPFLAGS = $(HOST_INC) $(CAIRO_CFLAGS)
# tui.c draws with ncursesw
CURSES_CFLAGS = $(call pkg,CURSES_CFLAGS,--cflags ncursesw)
CURSES_LIBS   = $(call pkg,CURSES_LIBS,--libs ncursesw,-lncursesw)
$(BUILD)/src/host/tui.o $(BUILD)/src/host/tui_mrun.o: MOD_CPPFLAGS = $(HOST_INC) $(CURSES_CFLAGS)
LDLIBS += $(CURSES_LIBS)
# modbus.c serves the machine over Modbus TCP with libmodbus
MODBUS_CFLAGS = $(call pkg,MODBUS_CFLAGS,--cflags libmodbus)
MODBUS_LIBS   = $(call pkg,MODBUS_LIBS,--libs libmodbus,-lmodbus)
$(BUILD)/src/host/modbus.o: MOD_CPPFLAGS = $(HOST_INC) $(MODBUS_CFLAGS)
# and answers from its own thread
LDLIBS += $(MODBUS_LIBS) -pthread
