# bench/: make bench prints the figures of issue 18 beside their targets,
# s42 beside its Lua 5.4, LuaJIT and LinuxCNC twins (bench/README.md), then
# the tooth search's (toothsearch-bench).  Not a test: nothing here is timed
# by make check, and a missed target does not fail it.
# BENCH_FLAGS=--quick: about a minute instead of about three.
BENCH_FLAGS ?=
.PHONY: bench
bench: $(S42) $(PLUGIN_SOS) $(TS_BENCH)
	$(PYTHON) bench/run.py --s42 $(S42) --out $(BUILD)/bench $(BENCH_FLAGS)
	$(TS_BENCH) tests/toothsearch/t004_reamer_seed.tool tests/toothsearch/t150_saw_fine.tool
