# src/host/: the commands (main), the headless runner, the terminal, the
# Modbus server, the plot, pacing and the operator script.  Hosts see
# every public header.
HOST_INC := -Isrc/host -Isrc/core -Isrc/dialect/2c42 -Isrc/machine/grinder -Ivm -Idisplay -Iinclude
# the curses front end links into s42 only (not the unit tests or fuzzers)
HOST_MAIN_SRCS := src/host/main.c src/host/tui.c src/host/tui_mrun.c src/host/tui_modbus.c src/host/curses_dl.c
HOST_LIB_SRCS  := $(filter-out $(HOST_MAIN_SRCS),$(wildcard src/host/*.c))
SRC_MAIN_OBJ   := $(HOST_MAIN_SRCS:%.c=$(BUILD)/%.o)
$(HOST_LIB_SRCS:%.c=$(BUILD)/%.o) $(SRC_MAIN_OBJ): MOD_CPPFLAGS = $(HOST_INC)
# plot.c and its views draw with cairo (the only parts of src/ that need it)
CAIRO_CFLAGS = $(call pkg,CAIRO_CFLAGS,--cflags cairo)
# cairo is loaded with dlopen when a plot is drawn (src/host/cairo_dl.c):
# linking it would load two dozen libraries at every start-up
$(BUILD)/src/host/plot.o $(BUILD)/src/host/plot_planes.o $(BUILD)/src/host/plot_lathe.o $(BUILD)/src/host/picture.o $(BUILD)/src/host/cairo_dl.o: MOD_CPPFLAGS = $(HOST_INC) $(CAIRO_CFLAGS)
# tui.c draws with ncursesw, loaded with dlopen by `s42 tui` alone
# (curses_dl.c): linked, it and libtinfo were mapped by every s42 run.
# Only its headers are needed to build.
CURSES_CFLAGS = $(call pkg,CURSES_CFLAGS,--cflags ncursesw)
$(BUILD)/src/host/tui.o $(BUILD)/src/host/tui_mrun.o $(BUILD)/src/host/curses_dl.o: MOD_CPPFLAGS = $(HOST_INC) $(CURSES_CFLAGS)
# modbus.c serves the machine over Modbus TCP with libmodbus, loaded with
# dlopen when a server opens (modbus_dl.c), so likewise not linked
MODBUS_CFLAGS = $(call pkg,MODBUS_CFLAGS,--cflags libmodbus)
MODBUS_LIBS   = $(call pkg,MODBUS_LIBS,--libs libmodbus,-lmodbus)
$(BUILD)/src/host/modbus.o $(BUILD)/src/host/modbus_dl.o: MOD_CPPFLAGS = $(HOST_INC) $(MODBUS_CFLAGS)
# and answers from its own thread
LDLIBS += -pthread
