# src/dialect/2u22/: the 2У22 front end (lexer, parser, checks, emitter: a
# program of the 16Б16Ф3 lathe's controller into bytecode), its per-block
# record (u22.h), its runtime on the neutral runner (runtime.c: a block as
# the lathe's canonical calls) and its entry in the registry (dialect.c).
# It sees vm/, core's headers and its machine's (src/machine/lathe).
U22_SRCS := $(wildcard src/dialect/2u22/*.c)
U22_INC  := -Isrc/dialect/2u22 -Isrc/core -Isrc/machine/lathe -Ivm
$(U22_SRCS:%.c=$(BUILD)/%.o): MOD_CPPFLAGS = $(U22_INC)
DIALECT_SRCS += $(U22_SRCS)
# registered: the build's dialect list names dialect_2u22
DIALECTS += 2u22
