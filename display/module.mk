# display/: the 2С42-65 screen model and its text rendering.  It sees the
# machine's events through the session, never the VM.
DISP_SRCS := $(wildcard display/*.c)
DISP_OBJS := $(DISP_SRCS:%.c=$(BUILD)/%.o)
$(DISP_OBJS): MOD_CPPFLAGS := -Idisplay
