# vm/: the neutral bytecode, the VM and the disassembler.  It sees only its
# own headers: no curses, dlfcn, OpenCV or libmodbus.
VM_SRCS := $(wildcard vm/*.c)
VM_OBJS := $(VM_SRCS:%.c=$(BUILD)/%.o)
$(VM_OBJS): MOD_CPPFLAGS := -Ivm
