# tests/: Check unit suites (tests/unit), golden programs (tests/conformance),
# the bundled programs, and the shared conformance cases when ../shared exists.
CHECK_CFLAGS := $(shell pkg-config --cflags check 2>/dev/null)
CHECK_LIBS   := $(shell pkg-config --libs check 2>/dev/null || echo -lcheck)
TEST_SRCS    := $(wildcard tests/unit/*.c)
TEST_OBJS    := $(TEST_SRCS:%.c=$(BUILD)/%.o)
UNIT_BIN     := $(BUILD)/tests/unit/run-unit
$(TEST_OBJS): MOD_CPPFLAGS := -Isrc -Ivm $(CHECK_CFLAGS)

.PHONY: unit-bin
unit-bin: $(UNIT_BIN)
$(UNIT_BIN): $(TEST_OBJS) $(VM_OBJS) $(SRC_OBJS)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(CHECK_LIBS) $(LDLIBS)

unit: $(UNIT_BIN)
	S42_SRCDIR=$(CURDIR) $(UNIT_BIN)

conformance: $(S42)
	$(PYTHON) tests/conformance/run.py --s42 $(S42) tests/conformance/cases

programs: $(S42)
	sh programs/run_expect.sh $(S42) tests/conformance/run.py

shared: $(S42)
	@if [ -d $(SHARED)/conformance/cases ]; then \
	  sh tests/shared.sh $(S42) $(SHARED); \
	else echo "shared: $(SHARED) is not here; the shared conformance cases were skipped"; fi
