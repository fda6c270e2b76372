# tests/: Check unit suites (tests/unit), golden programs (tests/conformance),
# the bundled programs, and the shared conformance cases when ../shared exists.
CHECK_CFLAGS = $(call pkg,CHECK_CFLAGS,--cflags check)
CHECK_LIBS   = $(call pkg,CHECK_LIBS,--libs check,-lcheck)
TEST_SRCS    := $(wildcard tests/unit/*.c)
TEST_OBJS    := $(TEST_SRCS:%.c=$(BUILD)/%.o)
UNIT_BIN     := $(BUILD)/tests/unit/run-unit
$(TEST_OBJS): MOD_CPPFLAGS = $(ALL_INC) -I$(TS_DIR) $(CHECK_CFLAGS)

.PHONY: unit-bin fixtures
fixtures: $(FIXTURE_SOS)
unit-bin: $(UNIT_BIN) $(PLUGIN_SOS) $(FIXTURE_SOS)
$(UNIT_BIN): $(TEST_OBJS) $(VM_OBJS) $(DISP_OBJS) $(SRC_OBJS) $(TS_C_OBJS)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(CHECK_LIBS) $(LDLIBS)

# the lathe's plot suite draws text with cairo: fontconfig's configuration
# lives as long as the process (tests/plot/lsan.supp), not a leak of s42
unit: $(UNIT_BIN) $(PLUGIN_SOS) $(FIXTURE_SOS)
	LSAN_OPTIONS="suppressions=$(CURDIR)/tests/plot/lsan.supp:print_suppressions=0$${LSAN_OPTIONS:+:$$LSAN_OPTIONS}" \
	S42_SRCDIR=$(CURDIR) S42_FIXTURES=$(CURDIR)/$(BUILD)/test-plugins S42_PLUGINS=$(CURDIR)/$(BUILD)/plugins $(UNIT_BIN)

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
	@$(MB_REPLAY) tests/fuzz/corpus/modbus/*
	@$(STATE_REPLAY) tests/fuzz/corpus/state/*
	@$(MB_CONN_REPLAY) tests/fuzz/corpus/modbus_conn/*

# The Modbus request handler's fuzz harness, replayed without libFuzzer on
# its seeds and on inputs that once crashed it (tests/fuzz/corpus/modbus/).
MB_REPLAY := $(BUILD)/tests/fuzz/replay-modbus
$(MB_REPLAY): tests/fuzz/fuzz_modbus.c tests/fuzz/replay.c $(VM_OBJS) $(DISP_OBJS) $(SRC_OBJS)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(ALL_INC) $(WARN) $(CFLAGS) $(LDFLAGS) -o $@ $(filter %.c %.o,$^) $(LDLIBS)
regress: $(MB_REPLAY)
# built with the objects' flags (make asan builds, then tests with plain CFLAGS)
unit-bin: $(MB_REPLAY)
# the same for the restart state's loader (tests/fuzz/corpus/state/)
STATE_REPLAY := $(BUILD)/tests/fuzz/replay-state
$(STATE_REPLAY): tests/fuzz/fuzz_state.c tests/fuzz/replay.c $(VM_OBJS) $(DISP_OBJS) $(SRC_OBJS)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(ALL_INC) $(WARN) $(CFLAGS) $(LDFLAGS) -o $@ $(filter %.c %.o,$^) $(LDLIBS)
regress: $(STATE_REPLAY)
unit-bin: $(STATE_REPLAY)
# The server's connection code through loopback sockets (fuzz_modbus_conn.c),
# replayed the same way on tests/fuzz/corpus/modbus_conn/.
MB_CONN_REPLAY := $(BUILD)/tests/fuzz/replay-modbus-conn
$(MB_CONN_REPLAY): tests/fuzz/fuzz_modbus_conn.c tests/fuzz/replay.c $(VM_OBJS) $(DISP_OBJS) $(SRC_OBJS)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(ALL_INC) $(WARN) $(CFLAGS) $(LDFLAGS) -o $@ $(filter %.c %.o,$^) $(LDLIBS)
regress: $(MB_CONN_REPLAY)
unit-bin: $(MB_CONN_REPLAY)

# SIGKILL at many points of a cycle with M15, then restart; damaged states,
# and states edited by hand with a recomputed checksum (tests/restart/forge).
FORGE := $(BUILD)/tests/restart/forge
$(FORGE): tests/restart/forge.c src/dialect/2c42/state.h $(VM_OBJS) $(DISP_OBJS) $(SRC_OBJS)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(ALL_INC) $(WARN) $(CFLAGS) $(LDFLAGS) -o $@ $(filter %.c %.o,$^) $(LDLIBS)
unit-bin: $(FORGE)
# an LD_PRELOAD shim that kills a run inside its Nth save (tests/restart/killsave.c);
# built without the sanitizers of make asan: it only wraps libc calls
KILLSAVE := $(BUILD)/tests/restart/killsave.so
$(KILLSAVE): tests/restart/killsave.c
	@mkdir -p $(@D)
	$(CC) -D_GNU_SOURCE $(WARN) -O2 -g -fPIC -shared -o $@ $< -ldl
unit-bin: $(KILLSAVE)
restart: $(S42) $(FORGE) $(KILLSAVE)
	sh tests/restart/run.sh $(S42) $(FORGE) $(KILLSAVE)

# --realtime paces the run at machine speed (a lower bound on the wall time)
realtime: $(S42)
	sh tests/realtime/run.sh $(S42)

# s42 plot on every bundled program: image size, drawn pixels, valid SVG.
plot: $(S42)
	sh tests/plot/run.sh $(S42)
	sh tests/plot/lathe/run.sh $(S42)

# plugins from the outside: built against the installed header, searched,
# refused, missing; OpenCV only for programs that search teeth; then
# `make install` into a temporary root and the installed s42 (install.sh)
plugins: $(S42) $(PLUGIN_SOS) $(TS_CV_SO) $(FIXTURE_SOS)
	sh tests/plugins/run.sh $(S42) $(BUILD)
	sh tests/plugins/install.sh $(S42) $(BUILD) $(PREFIX)

# Limits and bad input: deep nesting, huge blocks, files and scripts, bytes
# that are not UTF-8, NUL, CRLF, an empty file, a directory.
limits: $(S42)
	sh tests/limits/run.sh $(S42)

# A valgrind leak check of a representative run (.ci/run).
VALGRIND_RUN := $(S42) run programs/endmill_flute.kp --operator programs/endmill_flute.operator --dump --screen
.PHONY: valgrind
valgrind: $(S42)
	valgrind -q --leak-check=full --show-leak-kinds=definite,indirect,possible --errors-for-leak-kinds=definite,indirect,possible \
	  --error-exitcode=99 $(VALGRIND_RUN) >/dev/null
	valgrind -q --leak-check=full --show-leak-kinds=definite,indirect,possible --errors-for-leak-kinds=definite,indirect,possible \
	  --error-exitcode=99 $(S42) check programs/*.kp
	@echo "valgrind: no leaks, no errors"

# The command line's promises: output errors are status 4, CR-only files
cli: $(S42)
	sh tests/cli/run.sh $(S42)

# s42 tui in a real terminal: tmux send-keys, capture-pane
tui: $(S42)
	sh tests/tui/run.sh $(S42)
	sh tests/tui/lathe.sh $(S42)

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

# Fuzzing with libFuzzer (clang): make fuzz FUZZ_SECONDS=60 runs each harness
# that long, from the committed seeds in tests/fuzz/corpus/<harness>/ (new
# inputs go to $(BUILD)/fuzz/corpus-<harness>/); crashes land in $(BUILD)/fuzz/.
FUZZ_SECONDS ?= 30
FUZZ_TARGETS := compile vm operator toolmodel modbus modbus_conn state u22
FUZZ_FLAGS   := -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined $(ALL_INC) -D_GNU_SOURCE
.PHONY: fuzz fuzz-bin
fuzz-bin: $(FUZZ_TARGETS:%=$(BUILD)/fuzz/fuzz_%)
FUZZ_SRCS    := $(VM_SRCS) $(DISP_SRCS) $(filter-out src/host/plot.c src/host/plot_planes.c src/host/plot_lathe.c src/host/plot_run.c src/host/picture.c src/host/cairo_dl.c,$(SRC_SRCS)) $(BUILD)/gen/dialects.c
$(BUILD)/fuzz/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_SRCS) $(wildcard src/*/*.h src/*/*/*.h vm/*.h display/*.h)
	@mkdir -p $(@D)
	clang $(FUZZ_FLAGS) -o $@ $< $(FUZZ_SRCS) $(MODBUS_LIBS) -pthread -lm -ldl
# the tool-model parser alone (plugins/toothsearch/toolmodel.c)
$(BUILD)/fuzz/fuzz_toolmodel: tests/fuzz/fuzz_toolmodel.c $(TS_DIR)/toolmodel.c $(TS_DIR)/toolmodel.h
	@mkdir -p $(@D)
	clang $(FUZZ_FLAGS) -I$(TS_DIR) -o $@ $< $(TS_DIR)/toolmodel.c -lm
fuzz: fuzz-bin
	@for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(BUILD)/fuzz/corpus-$$t; \
	  echo "fuzz $$t: $(FUZZ_SECONDS) s"; \
	  $(BUILD)/fuzz/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
	    -artifact_prefix=$(BUILD)/fuzz/$$t- -print_final_stats=1 \
	    $(BUILD)/fuzz/corpus-$$t tests/fuzz/corpus/$$t || exit 1; \
	done

# The fixture dialect (tests/dialect/fixture): a test s42 whose registry is
# generated with it added, as a dialect's folder adds itself; then the
# dialect seam's tests against it and against the real s42.
include tests/dialect/fixture/module.mk
FIXTURE_S42 := $(BUILD)/tests/dialect/s42
$(BUILD)/tests/dialect/gen/dialects.stamp: FORCE
	@mkdir -p $(@D)
	@echo '$(FIXTURE_DIALECTS)' | cmp -s - $@ || echo '$(FIXTURE_DIALECTS)' > $@
$(BUILD)/tests/dialect/gen/dialects.c: $(BUILD)/tests/dialect/gen/dialects.stamp scripts/gen-dialects.sh
	sh scripts/gen-dialects.sh $(FIXTURE_DIALECTS) > $@
$(BUILD)/tests/dialect/gen/dialects.o: $(BUILD)/tests/dialect/gen/dialects.c
	$(CC) $(CPPFLAGS) -Isrc/core -Ivm $(WARN) $(CFLAGS) -c -o $@ $<
$(FIXTURE_S42): $(VM_OBJS) $(DISP_OBJS) $(filter-out $(BUILD)/gen/dialects.o,$(SRC_OBJS)) $(SRC_MAIN_OBJ) \
                $(FIXTURE_DIALECT_OBJS) $(BUILD)/tests/dialect/gen/dialects.o
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(LDLIBS)
unit-bin: $(FIXTURE_S42)
dialect: $(S42) $(FIXTURE_S42)
	sh tests/dialect/run.sh $(S42) $(FIXTURE_S42)
