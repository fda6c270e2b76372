# src/core/: what every dialect and host shares and no dialect owns -- the
# neutral runner (mrun.c: a dialect's runtime on the VM, the waits and
# switches, the rows), the canonical calls and their LinuxCNC trace
# (canon.c), the one geometry of arcs and planes (geom.c), diagnostics,
# the one error record, the dialect registry, JSON and machine messages
# (report.c), file reading (atomic.c) and "did you mean" (nearest.c).  It
# sees vm/ and nothing of a dialect or a machine.
CORE_SRCS := $(wildcard src/core/*.c)
CORE_INC  := -Isrc/core -Ivm
$(CORE_SRCS:%.c=$(BUILD)/%.o): MOD_CPPFLAGS = $(CORE_INC)
