# bench/: make bench prints s42's figures beside its Lua 5.4 and LinuxCNC
# twins (bench/README.md).  Not a test: nothing here is timed by make check.
BENCH_FLAGS ?=
.PHONY: bench
bench: $(S42)
	$(PYTHON) bench/run.py --s42 $(S42) --out $(BUILD)/bench $(BENCH_FLAGS)
