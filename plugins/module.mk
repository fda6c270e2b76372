# plugins/: shared objects built against include/s42_plugin.h alone, into
# $(BUILD)/plugins where ./s42 finds them with no option.  Each folder
# plugins/NAME/ holds the C sources of NAME.so.
PLUGIN_NAMES := $(notdir $(patsubst %/,%,$(dir $(wildcard plugins/*/*.c))))
PLUGIN_NAMES := $(sort $(filter-out toothsearch,$(PLUGIN_NAMES)))
PLUGIN_SOS   := $(PLUGIN_NAMES:%=$(BUILD)/plugins/%.so)
PLUGIN_FLAGS := -fPIC -shared -fvisibility=hidden -Iinclude

.SECONDEXPANSION:
$(BUILD)/plugins/%.so: $$(wildcard plugins/$$*/*.c) include/s42_plugin.h
	@mkdir -p $(@D)
	$(CC) $(WARN) $(CFLAGS) $(PLUGIN_FLAGS) $(LDFLAGS) -o $@ $(filter %.c,$^) -lm

# Fixture plugins for the loader's tests, one folder each (a folder is a
# plugin directory: each is scanned on its own).
FIXTURE_NAMES := $(basename $(notdir $(wildcard tests/plugins/*.c)))
FIXTURE_SOS   := $(foreach f,$(FIXTURE_NAMES),$(BUILD)/test-plugins/$(f)/$(f).so)
$(BUILD)/test-plugins/%.so: tests/plugins/$$(notdir $$*).c include/s42_plugin.h
	@mkdir -p $(@D)
	$(CC) $(WARN) $(CFLAGS) $(PLUGIN_FLAGS) $(LDFLAGS) -o $@ $< -lm
# cbcrash crashes for real, so it is built without the sanitizers of make
# asan: UBSan would report its division by zero (and abort) before the CPU
# raised SIGFPE, and the guard's test is of the signals a plugin raises
$(BUILD)/test-plugins/cbcrash/cbcrash.so: tests/plugins/cbcrash.c include/s42_plugin.h
	@mkdir -p $(@D)
	$(CC) $(WARN) -O2 -g $(PLUGIN_FLAGS) -o $@ $< -lm
