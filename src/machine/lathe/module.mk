# src/machine/lathe/: the simulated 16Б16Ф3 lathe of the 2У22 (positions
# against machine and part zero, X as a diameter, travel, feed and traverse
# limits, arcs, threads, the spindle's ranges, G96, tools, coolant, time)
# and its --tools file, with canonical calls that know no language.  It
# sees vm/'s error codes, core's geometry (src/core/geom.h) and the
# canonical events it reports (src/core/canon.h); no other core header.
LATHE_SRCS := $(wildcard src/machine/lathe/*.c)
LATHE_INC  := -Isrc/machine/lathe -Isrc/core -Ivm
$(LATHE_SRCS:%.c=$(BUILD)/%.o): MOD_CPPFLAGS = $(LATHE_INC)
MACHINE_SRCS += $(LATHE_SRCS)
