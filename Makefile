# s42 -- one non-recursive make; each folder adds its module.mk.
#   make            build ./s42
#   make check      all tests (unit, conformance, programs)
#   make asan       the whole test suite under ASan + UBSan
#   make run        build and run the emulator on a bundled program
#   make install PREFIX=/usr/local
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
PYTHON   ?= python3
# The binary the tests run: ./s42 for a normal build, inside BUILD otherwise.
S42      ?= ./s42
SHARED   ?= ../shared
VERSION  := $(shell cat VERSION 2>/dev/null || echo 0.1.0)

CPPFLAGS += -DS42_VERSION='"$(VERSION)"'

include vm/module.mk
include display/module.mk
include src/module.mk
include tests/module.mk

OBJS := $(VM_OBJS) $(DISP_OBJS) $(SRC_OBJS)
DEPS := $(OBJS:.o=.d) $(SRC_MAIN_OBJ:.o=.d) $(TEST_OBJS:.o=.d)

.PHONY: all check test unit conformance programs regress restart realtime plot shared modbus asan run clean install deps docs

all: $(S42)

$(S42): $(OBJS) $(SRC_MAIN_OBJ)
	$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/%.o: %.c
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(MOD_CPPFLAGS) $(WARN) $(CFLAGS) -c -o $@ $<

deps:
	@sh scripts/deps.sh

run: deps $(S42)
	$(S42) run programs/reamer_rake.kp --trace --dump

check: deps
	@$(MAKE) --no-print-directory all unit-bin
	@$(MAKE) --no-print-directory test

# The tests themselves, once everything is built.
test: unit conformance programs regress restart realtime plot shared modbus

asan:
	@sh scripts/deps.sh
	$(MAKE) BUILD=build-asan S42=build-asan/s42 \
	  CFLAGS="-O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all" \
	  LDFLAGS="-fsanitize=address,undefined" all unit-bin
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  $(MAKE) BUILD=build-asan S42=build-asan/s42 test

docs: docs/opcodes.md
docs/opcodes.md: vm/opcodes.h $(S42)
	$(S42) --opcodes-md > $@

install: $(S42)
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(MANDIR)
	install -m 755 $(S42) $(DESTDIR)$(BINDIR)/s42
	if [ -f docs/s42.1 ]; then install -m 644 docs/s42.1 $(DESTDIR)$(MANDIR)/s42.1; fi

clean:
	rm -rf build build-asan s42

-include $(DEPS)
