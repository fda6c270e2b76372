# src/: the 2С42 front end, the machine, the session, reports and the CLI.
SRC_SRCS     := $(filter-out src/main.c,$(wildcard src/*.c))
SRC_OBJS     := $(SRC_SRCS:%.c=$(BUILD)/%.o)
SRC_MAIN_OBJ := $(BUILD)/src/main.o
$(SRC_OBJS) $(SRC_MAIN_OBJ): MOD_CPPFLAGS := -Isrc -Ivm -Idisplay
# plot.c draws with cairo (the only part of src/ that needs it)
CAIRO_CFLAGS := $(shell pkg-config --cflags cairo 2>/dev/null)
CAIRO_LIBS   := $(shell pkg-config --libs cairo 2>/dev/null || echo -lcairo)
$(BUILD)/src/plot.o: MOD_CPPFLAGS := -Isrc -Ivm -Idisplay $(CAIRO_CFLAGS)
LDLIBS += $(CAIRO_LIBS)
# modbus.c serves the machine over Modbus TCP with libmodbus
MODBUS_CFLAGS := $(shell pkg-config --cflags libmodbus 2>/dev/null)
MODBUS_LIBS   := $(shell pkg-config --libs libmodbus 2>/dev/null || echo -lmodbus)
LDLIBS += $(MODBUS_LIBS)
