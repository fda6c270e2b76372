# bench/: make bench prints s42's figures beside its Lua 5.4 and LinuxCNC
# twins (bench/README.md), then the tooth search's (toothsearch-bench).
# Not a test: nothing here is timed by make check.
BENCH_FLAGS ?=
.PHONY: bench
bench: $(S42) $(TS_BENCH)
	$(PYTHON) bench/run.py --s42 $(S42) --out $(BUILD)/bench $(BENCH_FLAGS)
	$(TS_BENCH) tests/toothsearch/t004_reamer_seed.tool tests/toothsearch/t150_saw_fine.tool
