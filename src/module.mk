# src/: the 2С42 front end, the machine, the session, reports and the CLI.
SRC_SRCS     := $(filter-out src/main.c,$(wildcard src/*.c))
SRC_OBJS     := $(SRC_SRCS:%.c=$(BUILD)/%.o)
SRC_MAIN_OBJ := $(BUILD)/src/main.o
$(SRC_OBJS) $(SRC_MAIN_OBJ): MOD_CPPFLAGS := -Isrc -Ivm -Idisplay
