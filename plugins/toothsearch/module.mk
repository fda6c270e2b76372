# plugins/toothsearch/: the tooth-step search of G10/G11 (C++17, OpenCV 4).
# Built position-independent, as the static library the plugin .so will
# wrap; ./s42 itself never links it (nor OpenCV).  The tool-model parser is
# plain C and also goes into the unit tests and the fuzzer.
#   make toothsearch        the accuracy test set (part of make check)
#   make toothsearch-bench  time per image and per search
TS_DIR        := plugins/toothsearch
OPENCV_CFLAGS := $(shell pkg-config --cflags opencv4 2>/dev/null)
OPENCV_LIBS   := $(shell pkg-config --libs-only-L opencv4 2>/dev/null) -lopencv_imgcodecs -lopencv_imgproc -lopencv_core
TS_CXXWARN    := -std=c++17 -Wall -Wextra -Wshadow -Wformat=2
TS_C_OBJS     := $(BUILD)/$(TS_DIR)/toolmodel.o
TS_CXX_OBJS   := $(BUILD)/$(TS_DIR)/render.o $(BUILD)/$(TS_DIR)/measure.o
TS_LIB        := $(BUILD)/$(TS_DIR)/libtoothsearch.a
TS_TEST       := $(BUILD)/tests/toothsearch/accuracy
TS_BENCH      := $(BUILD)/$(TS_DIR)/bench

$(TS_C_OBJS): MOD_CPPFLAGS := -I$(TS_DIR) -fPIC
$(BUILD)/$(TS_DIR)/%.o: $(TS_DIR)/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(CPPFLAGS) -I$(TS_DIR) $(OPENCV_CFLAGS) $(TS_CXXWARN) $(CFLAGS) -fPIC -c -o $@ $<

$(TS_LIB): $(TS_C_OBJS) $(TS_CXX_OBJS)
	@mkdir -p $(@D)
	rm -f $@
	$(AR) rcs $@ $^

$(BUILD)/tests/toothsearch/%.o $(BUILD)/$(TS_DIR)/bench.o: MOD_CPPFLAGS := -I$(TS_DIR)
$(TS_TEST): $(BUILD)/tests/toothsearch/accuracy.o $(TS_LIB)
	$(CXX) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(OPENCV_LIBS) -lm
$(TS_BENCH): $(BUILD)/$(TS_DIR)/bench.o $(TS_LIB)
	$(CXX) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(OPENCV_LIBS) -lm

.PHONY: toothsearch toothsearch-bin toothsearch-bench
toothsearch-bin: $(TS_TEST) $(TS_BENCH)
# every model in tests/toothsearch measured against its truth; under ASan
# OpenCV's process-long allocations are not ours (lsan.supp)
toothsearch: $(TS_TEST)
	LSAN_OPTIONS="suppressions=$(CURDIR)/tests/toothsearch/lsan.supp$${LSAN_OPTIONS:+:$$LSAN_OPTIONS}" \
	  $(TS_TEST) tests/toothsearch/*.tool
toothsearch-bench: $(TS_BENCH)
	$(TS_BENCH) tests/toothsearch/t004_reamer_seed.tool tests/toothsearch/t150_saw_fine.tool

-include $(TS_C_OBJS:.o=.d) $(TS_CXX_OBJS:.o=.d) $(BUILD)/tests/toothsearch/accuracy.d $(BUILD)/$(TS_DIR)/bench.d
