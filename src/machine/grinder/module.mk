# src/machine/grinder/: the simulated ВЗ-208Ф3 (positions, time, the wheel,
# the override, contour-speed limits, travel) and its --machine file.  It
# sees vm/'s error codes; and, until the canonical machine interface is
# done, the 2С42 block record (kp.h, ast.h) it is handed.
MACHINE_SRCS := $(wildcard src/machine/grinder/*.c)
MACHINE_INC  := -Isrc/machine/grinder -Ivm -Isrc/dialect/2c42
$(MACHINE_SRCS:%.c=$(BUILD)/%.o): MOD_CPPFLAGS = $(MACHINE_INC)
