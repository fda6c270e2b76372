# src/dialect/2c42/: the 2С42 front end -- lexer, parser, checks, emitter --
# and its per-block record (kp.h).  It sees vm/, include/ and core's
# headers (diagnostics, the plugin loader for the plugins' words).
DIALECT_SRCS := $(wildcard src/dialect/2c42/*.c)
DIALECT_INC  := -Isrc/dialect/2c42 -Isrc/core -Ivm -Iinclude
$(DIALECT_SRCS:%.c=$(BUILD)/%.o): MOD_CPPFLAGS = $(DIALECT_INC)
