# src/dialect/2c42/: the 2С42 front end -- lexer, parser, checks, emitter --
# its per-block record (kp.h), what a block means to the grinder (kpmach.c:
# the block as canonical machine calls), its runtime on the session
# (runtime.c: the machine work, G20, M19, the dialog, M16, M18) and its
# entry in the registry (dialect.c).  It sees vm/, include/, display/ (the
# 2С42-65 screen), core's headers and its machine's.
C42_SRCS := $(wildcard src/dialect/2c42/*.c)
C42_INC  := -Isrc/dialect/2c42 -Isrc/core -Isrc/machine/grinder -Ivm -Iinclude -Idisplay
$(C42_SRCS:%.c=$(BUILD)/%.o): MOD_CPPFLAGS = $(C42_INC)
DIALECT_SRCS += $(C42_SRCS)
# registered: the build's dialect list names dialect_2c42
DIALECTS += 2c42
