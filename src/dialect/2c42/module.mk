# src/dialect/2c42/: the 2С42 front end -- lexer, parser, checks, emitter --
# its per-block record (kp.h) and what a block means to the grinder
# (kpmach.c: the block as canonical machine calls).  It sees vm/, include/,
# core's headers (diagnostics, geometry, the plugin loader for the plugins'
# words) and its machine's.
DIALECT_SRCS := $(wildcard src/dialect/2c42/*.c)
DIALECT_INC  := -Isrc/dialect/2c42 -Isrc/core -Isrc/machine/grinder -Ivm -Iinclude
$(DIALECT_SRCS:%.c=$(BUILD)/%.o): MOD_CPPFLAGS = $(DIALECT_INC)
