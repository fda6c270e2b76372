# s42 -- one non-recursive make; each folder adds its module.mk.
#   make            build ./s42
#   make check      all tests (unit, conformance, programs)
#   make asan       the whole test suite under ASan + UBSan
#   make check-switch  the unit suite and the conformance cases with the VM's switch dispatch
#   make run        build and run the emulator on a bundled program (the TUI on a terminal)
#   make install PREFIX=/usr/local
#   make PGO=0      build without the front end's profile feedback
.SUFFIXES:
.DEFAULT_GOAL := all

CC       ?= cc
CFLAGS   ?= -O2 -g
WARN     := -std=c11 -Wall -Wextra -Wshadow -Wmissing-prototypes -Wstrict-prototypes -Wformat=2 -Wvla
CPPFLAGS += -D_GNU_SOURCE -MMD -MP
LDLIBS   += -lm
BUILD    ?= build
PREFIX   ?= /usr/local
BINDIR   ?= $(PREFIX)/bin
MANDIR   ?= $(PREFIX)/share/man/man1
BASHCOMPDIR ?= $(PREFIX)/share/bash-completion/completions
PYTHON   ?= python3
# The binary the tests run: ./s42 for a normal build, inside BUILD otherwise.
S42      ?= ./s42
SHARED   ?= ../shared
VERSION  := $(shell cat VERSION 2>/dev/null || echo 0.1.0)

PLUGINDIR ?= $(PREFIX)/lib/s42/plugins
INCLUDEDIR ?= $(PREFIX)/include

CPPFLAGS += -DS42_VERSION='"$(VERSION)"'

# $(call pkg,VAR,ARGS[,FALLBACK]): pkg-config ARGS, asked once and only when a
# recipe first needs VAR -- never while make reads the Makefile, so that
# `make run` and `make check` ask it after scripts/deps.sh has installed
# what was missing (their sub-make builds).
pkg = $(eval $1 := $$(shell pkg-config $2 2>/dev/null$(if $3, || echo $3)))$($1)

include vm/module.mk
include display/module.mk
include src/module.mk
include plugins/module.mk
include plugins/toothsearch/module.mk
include tests/module.mk
include bench/module.mk

OBJS := $(VM_OBJS) $(DISP_OBJS) $(SRC_OBJS)
DEPS := $(OBJS:.o=.d) $(SRC_MAIN_OBJ:.o=.d) $(TEST_OBJS:.o=.d)

.PHONY: pgo canon dialect all check check-switch test unit conformance programs regress restart realtime plot plugins tui shared limits toothsearch modbus asan run clean install deps docs errors guide tutorial cli load

all: $(S42) $(PLUGIN_SOS)

$(S42): $(OBJS) $(SRC_MAIN_OBJ)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(MOD_CPPFLAGS) $(WARN) $(CFLAGS)$(if $(filter $@,$(PGO_OBJS)), $(PGO_USE)) -c -o $@ $<

# Profile feedback for the front end (the 2С42 lexer, parser and compiler:
# bench/README.md, "sixth round").  Its files are built a second time with
# counters into BUILD/pgo/gen and linked with the other objects into an
# instrumented s42, which compiles every program of the repository but the
# benchmarks' (scripts/pgo-train.sh); GCC then builds them with the counts,
# and a program compiles 15-25 % faster.  Only there: the VM's and the
# session's paths depend on the program run, and a path no training program
# took would be laid out as cold.  On by default with GCC (11 or later) and
# the Makefile's own CFLAGS; PGO=0 turns it off, and a build with CFLAGS of
# its own (make asan, check-switch, the fuzzers) has none.  The counters
# count branches only (no value profiles, whose pointer bits change from
# run to run), so the counts are the same until the front end changes.
PGO ?= auto
ifeq ($(PGO),auto)
  ifeq ($(origin CFLAGS),file)
    PGO := $(shell $(CC) -fprofile-use -fprofile-prefix-path=/ -fprofile-partial-training -Wno-missing-profile \
             -S -o /dev/null -x c /dev/null 2>/dev/null && echo 1 || echo 0)
  else
    PGO := 0
  endif
endif
PGO_SRCS := src/dialect/2c42/lex.c src/dialect/2c42/parse.c src/dialect/2c42/compile.c \
            src/dialect/2c42/peep.c src/dialect/2c42/words.c vm/program.c
ifeq ($(PGO),1)
PGO_OBJS := $(PGO_SRCS:%.c=$(BUILD)/%.o)
PGO_GEN  := $(BUILD)/pgo/gen
PGO_GEN_OBJS := $(PGO_SRCS:%.c=$(PGO_GEN)/%.o)
# (the same for the counters and the counts: a static function's counts
# are found by its number in its file, not by a hash of the object's path)
PGO_BOTH := -fno-profile-values --param=profile-func-internal-id=1
# $(call pgo_use,DIR): the counts, for an object under DIR
pgo_use = -fprofile-use=$(abspath $(BUILD)/pgo/use) -fprofile-prefix-path=$(abspath $1) \
          -fprofile-partial-training $(PGO_BOTH)
PGO_USE   = $(call pgo_use,$(BUILD)) -Wno-error=coverage-mismatch
PGO_TRAIN := $(shell find programs docs tests -type f -name '*.kp')
# the counters' build and make pgo's (below) compile the files as the build does
PGO_CHECK := $(BUILD)/pgo/check
PGO_CHECK_OBJS := $(PGO_SRCS:%.c=$(PGO_CHECK)/%.o)
$(PGO_GEN)/src/dialect/2c42/%.o $(PGO_CHECK)/src/dialect/2c42/%.o: MOD_CPPFLAGS = $(C42_INC)
$(PGO_GEN)/vm/%.o $(PGO_CHECK)/vm/%.o: MOD_CPPFLAGS = -Ivm
$(PGO_GEN)/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(MOD_CPPFLAGS) $(WARN) $(CFLAGS) -fprofile-generate=$(abspath $(BUILD)/pgo/counts) \
	  -fprofile-prefix-path=$(abspath $(PGO_GEN)) -fprofile-update=single $(PGO_BOTH) -c -o $@ $<
$(PGO_GEN)/s42: $(PGO_GEN_OBJS) $(filter-out $(PGO_OBJS),$(OBJS)) $(SRC_MAIN_OBJ)
	$(CC) $(CFLAGS) $(LDFLAGS) -fprofile-generate -o $@ $^ $(LDLIBS)
$(BUILD)/pgo/trained: $(PGO_GEN)/s42 $(PLUGIN_SOS) scripts/pgo-train.sh $(PGO_TRAIN)
	sh scripts/pgo-train.sh $(PGO_GEN)/s42 $(BUILD)/pgo/counts $(BUILD)/pgo/use $(BUILD)/plugins $(PGO_SRCS)
	@touch $@
# touched by the training only when the counts changed
$(BUILD)/pgo/use/stamp: $(BUILD)/pgo/trained ;
$(PGO_OBJS): $(BUILD)/pgo/use/stamp
-include $(PGO_GEN_OBJS:.o=.d) $(PGO_CHECK_OBJS:.o=.d)
endif

# make check: the counts fit the front end's sources as they are.  A
# function whose counts GCC cannot find is built as if never trained, with
# no more than a warning in the build's output; here it is an error.
ifeq ($(PGO),1)
$(PGO_CHECK)/%.o: %.c $(BUILD)/pgo/use/stamp
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(MOD_CPPFLAGS) $(WARN) $(CFLAGS) $(call pgo_use,$(PGO_CHECK)) \
	  -Werror=missing-profile -Werror=coverage-mismatch -c -o $@ $<
pgo: $(PGO_CHECK_OBJS)
	@echo "pgo: the counts of the $(words $(PGO_SRCS)) front-end files fit their sources"
else
pgo:
	@echo "pgo: this build has no profile feedback (PGO=0): nothing to check"
endif

deps:
	@sh scripts/deps.sh

# On a terminal: the TUI on the drill dialog; otherwise the headless run.
# The packages first, then a sub-make builds s42 and its plugins (the
# bundled cycles need them) with the flags pkg-config gives now.
run: deps
	@$(MAKE) --no-print-directory all
	@if [ -t 0 ] && [ -t 1 ]; then $(S42) tui programs/drill_dialog.kp; \
	else $(S42) run programs/reamer_rake.kp --trace --dump; fi

# make check builds with CHECK_JOBS jobs, then runs the tests CHECK_JOBS at
# a time, the longest first (each has its own temporary directory, tmux
# server and ports), each one's output kept together (-Otarget).
# CHECK_JOBS=1 runs them one after another.
CHECK_JOBS ?= 2
check: deps
	@$(MAKE) --no-print-directory -j$(CHECK_JOBS) all unit-bin toothsearch-bin
	@$(MAKE) --no-print-directory -j$(CHECK_JOBS) -Otarget test

# The tests themselves, once everything is built (the longest first).
test: modbus tutorial toothsearch tui plot restart plugins conformance errors realtime limits regress unit programs guide cli shared dialect canon u22 oracle load pgo

# What s42 maps: s42 run none of the libraries of tui, --modbus, plot and
# the tooth search, which load theirs with dlopen (tests/load/run.sh)
load: $(S42)
	sh tests/load/run.sh $(S42)

# The 2У22: its golden cases (tests/conformance/2u22*) and programs/2u22
u22: $(S42)
	$(PYTHON) tests/conformance/run.py --s42 $(S42) $(wildcard tests/conformance/2u22 tests/conformance/2u22-check)
	sh programs/2u22/run.sh $(S42) tests/conformance/run.py

# LinuxCNC's rs274 on the NGC twins of programs/2u22 against --trace=canon
# (skipped with a notice without linuxcnc-uspace; CI requires it)
oracle: $(S42)
	sh tests/oracle/run.sh $(S42)

# --trace=canon: the calls on the machine, exactly (tests/canon/)
canon: $(S42)
	sh tests/canon/run.sh $(S42)

# programs/errors/: one program per error class, its diagnostics exactly
errors: $(S42)
	sh programs/errors/run.sh $(S42)

# docs/guide.md: its examples are docs/guide/*, they run, its transcripts hold
guide: $(S42)
	sh tests/guide/run.sh $(S42)

# README.md's five-minute tutorial, done as written on a copy of the
# repository (its own make, tmux for s42 tui); the man page renders
tutorial:
	sh tests/tutorial/run.sh

ASAN_MAKE = $(MAKE) BUILD=build-asan S42=build-asan/s42 \
	  CFLAGS="-O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all" \
	  LDFLAGS="-fsanitize=address,undefined"
asan:
	@sh scripts/deps.sh
	$(ASAN_MAKE) -j$(CHECK_JOBS) all unit-bin toothsearch-bin
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  $(ASAN_MAKE) test

# The VM's other dispatch: vm/vm.c dispatches by computed goto under GCC and
# by a switch otherwise; S42_SWITCH_DISPATCH forces the switch.  check-switch
# builds everything so into build-switch/ (a build of its own), makes sure the
# VM there has no computed-goto table, and runs the unit suite, the
# conformance cases and the bundled programs on it (.ci/run calls it).
SWITCH_BUILD := build-switch
SWITCH_MAKE = $(MAKE) --no-print-directory BUILD=$(SWITCH_BUILD) S42=$(SWITCH_BUILD)/s42 \
	  CFLAGS="$(CFLAGS) -DS42_SWITCH_DISPATCH"
check-switch: deps
	@$(SWITCH_MAKE) all unit-bin
	@if nm $(SWITCH_BUILD)/vm/vm.o | grep -q ' disp\.'; then \
	  echo "check-switch: $(SWITCH_BUILD)/vm/vm.o still has the computed-goto table (disp)"; exit 1; fi
	@echo "check-switch: $(SWITCH_BUILD)/vm/vm.o dispatches by switch (no computed-goto table)"
	@$(SWITCH_MAKE) unit conformance programs

docs: docs/opcodes.md
docs/opcodes.md: vm/opcodes.h $(S42)
	$(S42) --opcodes-md > $@

install: $(S42) $(PLUGIN_SOS)
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(MANDIR)
	install -m 755 $(S42) $(DESTDIR)$(BINDIR)/s42
	install -d $(DESTDIR)$(PLUGINDIR) $(DESTDIR)$(INCLUDEDIR)
	install -m 644 $(PLUGIN_SOS) $(DESTDIR)$(PLUGINDIR)/
	install -m 644 include/s42_plugin.h $(DESTDIR)$(INCLUDEDIR)/s42_plugin.h
	if [ -f docs/s42.1 ]; then install -m 644 docs/s42.1 $(DESTDIR)$(MANDIR)/s42.1; fi
	install -d $(DESTDIR)$(BASHCOMPDIR)
	install -m 644 scripts/s42.bash $(DESTDIR)$(BASHCOMPDIR)/s42

clean:
	rm -rf build build-asan $(SWITCH_BUILD) s42

-include $(DEPS)
