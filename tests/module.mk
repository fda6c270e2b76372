# tests/: Check unit suites (tests/unit), golden programs (tests/conformance),
# the bundled programs, and the shared conformance cases when ../shared exists.
CHECK_CFLAGS := $(shell pkg-config --cflags check 2>/dev/null)
CHECK_LIBS   := $(shell pkg-config --libs check 2>/dev/null || echo -lcheck)
TEST_SRCS    := $(wildcard tests/unit/*.c)
TEST_OBJS    := $(TEST_SRCS:%.c=$(BUILD)/%.o)
UNIT_BIN     := $(BUILD)/tests/unit/run-unit
$(TEST_OBJS): MOD_CPPFLAGS := -Isrc -Ivm -Idisplay $(CHECK_CFLAGS)

.PHONY: unit-bin
unit-bin: $(UNIT_BIN)
$(UNIT_BIN): $(TEST_OBJS) $(VM_OBJS) $(DISP_OBJS) $(SRC_OBJS)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(CHECK_LIBS) $(LDLIBS)

unit: $(UNIT_BIN)
	S42_SRCDIR=$(CURDIR) $(UNIT_BIN)

conformance: $(S42)
	$(PYTHON) tests/conformance/run.py --s42 $(S42) tests/conformance/cases

programs: $(S42)
	sh programs/run_expect.sh $(S42) tests/conformance/run.py

# Inputs that once crashed a fuzzer: each must give a clean status (0-3).
regress: $(S42)
	@$(PYTHON) tests/fuzz/deep.py $(BUILD)/deep
	@n=0; for f in tests/fuzz/regress/* $(BUILD)/deep/*; do \
	  $(S42) run "$$f" --max-blocks 100000 --dump >/dev/null 2>&1; st=$$?; \
	  if [ $$st -gt 3 ]; then echo "FAIL regress $$f: status $$st"; exit 1; fi; n=$$((n+1)); \
	done; echo "regress: $$n passed, 0 failed"
	@$(MB_REPLAY) tests/fuzz/modbus/*

# The Modbus request handler's fuzz harness, replayed without libFuzzer on
# its seeds and on inputs that once crashed it (tests/fuzz/modbus/).
MB_REPLAY := $(BUILD)/tests/fuzz/replay-modbus
$(MB_REPLAY): tests/fuzz/fuzz_modbus.c tests/fuzz/replay.c $(VM_OBJS) $(DISP_OBJS) $(SRC_OBJS)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) -Isrc -Ivm -Idisplay $(WARN) $(CFLAGS) $(LDFLAGS) -o $@ $(filter %.c %.o,$^) $(LDLIBS)
regress: $(MB_REPLAY)
# built with the objects' flags (make asan builds, then tests with plain CFLAGS)
unit-bin: $(MB_REPLAY)

# SIGKILL at many points of a cycle with M15, then restart; damaged states.
restart: $(S42)
	sh tests/restart/run.sh $(S42)

# --realtime paces the run at machine speed (a lower bound on the wall time)
realtime: $(S42)
	sh tests/realtime/run.sh $(S42)

# s42 plot on every bundled program: image size, drawn pixels, valid SVG.
plot: $(S42)
	sh tests/plot/run.sh $(S42)

# The Modbus server: a libmodbus client, malformed frames, mbpoll.
MB_CLIENT := $(BUILD)/tests/modbus/client
$(MB_CLIENT): tests/modbus/client.c vm/errors.h
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) -Ivm $(MODBUS_CFLAGS) $(WARN) $(CFLAGS) $(LDFLAGS) -o $@ $< $(MODBUS_LIBS) -lm
unit-bin: $(MB_CLIENT)
modbus: $(S42) $(MB_CLIENT)
	sh tests/modbus/run.sh $(S42) $(MB_CLIENT)

shared: $(S42)
	@if [ -d $(SHARED)/conformance/cases ]; then \
	  sh tests/shared.sh $(S42) $(SHARED); \
	else echo "shared: $(SHARED) is not here; the shared conformance cases were skipped"; fi

# Fuzzing with libFuzzer (clang): make fuzz FUZZ_SECONDS=60
FUZZ_SECONDS ?= 30
FUZZ_TARGETS := fuzz_program fuzz_operator fuzz_modbus
FUZZ_FLAGS   := -g -O1 -fsanitize=fuzzer,address,undefined -Isrc -Ivm -Idisplay -D_GNU_SOURCE
.PHONY: fuzz fuzz-bin
fuzz-bin: $(FUZZ_TARGETS:%=$(BUILD)/fuzz/%)
FUZZ_SRCS    := $(VM_SRCS) $(DISP_SRCS) $(filter-out src/plot.c,$(SRC_SRCS))
$(BUILD)/fuzz/%: tests/fuzz/%.c $(FUZZ_SRCS)
	@mkdir -p $(@D)
	clang $(FUZZ_FLAGS) -o $@ $< $(FUZZ_SRCS) $(MODBUS_LIBS) -lm
fuzz: fuzz-bin
	@mkdir -p $(BUILD)/fuzz/corpus-program $(BUILD)/fuzz/corpus-operator $(BUILD)/fuzz/corpus-modbus
	@cp tests/fuzz/modbus/* $(BUILD)/fuzz/corpus-modbus/
	@cp programs/*.kp tests/conformance/cases/*/program.kp $(BUILD)/fuzz/corpus-program/ 2>/dev/null || true
	@for f in tests/conformance/cases/*/program.kp; do cp $$f $(BUILD)/fuzz/corpus-program/$$(basename $$(dirname $$f)).kp; done
	@for f in programs/*.operator tests/conformance/cases/*/operator.txt; do [ -f $$f ] && cp $$f $(BUILD)/fuzz/corpus-operator/$$(echo $$f | tr / _); done; true
	$(BUILD)/fuzz/fuzz_program -max_total_time=$(FUZZ_SECONDS) -max_len=4096 -timeout=10 $(BUILD)/fuzz/corpus-program
	$(BUILD)/fuzz/fuzz_operator -max_total_time=$(FUZZ_SECONDS) -max_len=2048 -timeout=10 $(BUILD)/fuzz/corpus-operator
	$(BUILD)/fuzz/fuzz_modbus -max_total_time=$(FUZZ_SECONDS) -max_len=2048 -timeout=10 $(BUILD)/fuzz/corpus-modbus
