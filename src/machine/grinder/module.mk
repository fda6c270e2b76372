# src/machine/grinder/: the simulated ВЗ-208Ф3 (positions, time, the wheel,
# the override, contour-speed limits, travel) and its --machine file, with
# canonical calls that know no language.  It sees vm/'s error codes, core's
# geometry (src/core/geom.h) and the canonical events it reports
# (src/core/canon.h); no other core header is included.
GRINDER_SRCS := $(wildcard src/machine/grinder/*.c)
GRINDER_INC  := -Isrc/machine/grinder -Isrc/core -Ivm
$(GRINDER_SRCS:%.c=$(BUILD)/%.o): MOD_CPPFLAGS = $(GRINDER_INC)
MACHINE_SRCS += $(GRINDER_SRCS)
