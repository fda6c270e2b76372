# plugins/toothsearch/: the tooth-step search of G10/G11 (C++17, OpenCV 4).
# Three shared objects (tscv.h):
#   $(BUILD)/plugins/toothsearch.so     the plugin s42 loads: descriptor,
#       operator flow, tool model (plugin.c, toolmodel.c); plain C, no OpenCV
#   $(BUILD)/plugins/toothsearch/toothsearch-cv.so   what its init() dlopens:
#       libtoothsearch.a (render, measure; C++17 and OpenCV's core and
#       imgproc) behind one C entry (cventry.c).  In a subfolder, so the
#       plugin scan never sees it.
#   $(BUILD)/plugins/toothsearch/toothsearch-png.so  what init() dlopens for
#       --dump-images alone: the PNG writer (png.cpp), the one user of
#       OpenCV's imgcodecs, whose dependencies (some 120 libraries) took
#       most of a searching run's time to load.
# ./s42 itself never links either (nor OpenCV).  The tool-model parser is
# plain C and also goes into the unit tests and the fuzzer.
#   make toothsearch        the OpenCV stand-ins against OpenCV, the renderer
#                           against its reference, the accuracy test set,
#                           the plugin (part of make check)
#   make toothsearch-bench  time per image and per search
TS_DIR        := plugins/toothsearch
OPENCV_CFLAGS = $(call pkg,OPENCV_CFLAGS,--cflags opencv4)
OPENCV_LIBS_L = $(call pkg,OPENCV_LIBS_L,--libs-only-L opencv4)
# the measurement needs core and imgproc alone; imgcodecs only the writer
OPENCV_LIBS   = $(OPENCV_LIBS_L) -lopencv_imgproc -lopencv_core
OPENCV_PNG_LIBS = $(OPENCV_LIBS_L) -lopencv_imgcodecs -lopencv_core
TS_CXXWARN    := -std=c++17 -Wall -Wextra -Wshadow -Wformat=2
TS_C_OBJS     := $(BUILD)/$(TS_DIR)/toolmodel.o
TS_CXX_OBJS   := $(BUILD)/$(TS_DIR)/render.o $(BUILD)/$(TS_DIR)/measure.o
TS_LIB        := $(BUILD)/$(TS_DIR)/libtoothsearch.a
TS_TEST       := $(BUILD)/tests/toothsearch/accuracy
TS_REF        := $(BUILD)/tests/toothsearch/render_ref
TS_CVEXACT    := $(BUILD)/tests/toothsearch/cvexact
TS_BENCH      := $(BUILD)/$(TS_DIR)/bench

$(TS_C_OBJS): MOD_CPPFLAGS := -I$(TS_DIR) -fPIC
$(BUILD)/$(TS_DIR)/%.o: $(TS_DIR)/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(CPPFLAGS) -I$(TS_DIR) $(OPENCV_CFLAGS) $(TS_CXXWARN) $(CFLAGS) $(TS_CXXVIS) $(TS_CXXVEC) -fPIC -c -o $@ $<
# the renderer's per-pixel loop (illumination, noise, clamp, 8 bits) and
# the measurement's silhouette sums are vectorized by GCC only if a float
# compare may be if-converted (no floating-point traps: s42 never enables
# them) and the vector loop's cost is weighed (the dynamic model; -O2's
# very cheap one refuses a loop with a remainder); and lrint, the sampler's
# rounding, is one instruction only when it need not set errno (nothing
# here reads errno after a math function).  None of these changes a value:
# no reassociation, no contraction.
TS_VEC := -ftree-vectorize -fno-trapping-math -fno-math-errno -fvect-cost-model=dynamic
$(BUILD)/$(TS_DIR)/render.o $(BUILD)/$(TS_DIR)/measure.o: TS_CXXVEC := $(TS_VEC)

$(TS_LIB): $(TS_C_OBJS) $(TS_CXX_OBJS)
	@mkdir -p $(@D)
	rm -f $@
	$(AR) rcs $@ $^

# the plugin and its heavy part; `all` and every plugin target build both
TS_PLUGIN := $(BUILD)/plugins/toothsearch.so
TS_CV_SO  := $(BUILD)/plugins/toothsearch/toothsearch-cv.so
TS_CV_OBJ := $(BUILD)/$(TS_DIR)/cventry.o
TS_PNG_SO  := $(BUILD)/plugins/toothsearch/toothsearch-png.so
TS_PNG_OBJ := $(BUILD)/$(TS_DIR)/png.o
PLUGIN_SOS += $(TS_PLUGIN)
$(TS_PLUGIN): $(TS_DIR)/plugin.c $(TS_DIR)/toolmodel.c $(TS_DIR)/toolmodel.h $(TS_DIR)/tscv.h \
              $(TS_DIR)/toothsearch.h include/s42_plugin.h | $(TS_CV_SO) $(TS_PNG_SO)
	@mkdir -p $(@D)
	$(CC) -D_GNU_SOURCE $(WARN) $(CFLAGS) $(PLUGIN_FLAGS) -I$(TS_DIR) $(LDFLAGS) -o $@ $(filter %.c,$^) -ldl -lm
$(TS_CV_OBJ): $(TS_DIR)/cventry.c
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) -I$(TS_DIR) $(WARN) $(CFLAGS) -fPIC -fvisibility=hidden -c -o $@ $<
# the static library's own symbols stay inside (--exclude-libs): only
# ts_cv_entry is exported
$(TS_CV_SO): $(TS_CV_OBJ) $(TS_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CFLAGS) $(LDFLAGS) -shared -Wl,--exclude-libs,ALL -o $@ $^ $(OPENCV_LIBS) -lm
# png.o (from png.cpp by the rule above) exports ts_png_write alone
$(TS_PNG_SO): $(TS_PNG_OBJ)
	@mkdir -p $(@D)
	$(CXX) $(CFLAGS) $(LDFLAGS) -shared -o $@ $^ $(OPENCV_PNG_LIBS)
$(TS_PNG_OBJ): TS_CXXVIS := -fvisibility=hidden

.PHONY: install-toothsearch
install: install-toothsearch
install-toothsearch: $(TS_CV_SO) $(TS_PNG_SO)
	install -d $(DESTDIR)$(PLUGINDIR)/toothsearch
	install -m 644 $(TS_CV_SO) $(DESTDIR)$(PLUGINDIR)/toothsearch/toothsearch-cv.so
	install -m 644 $(TS_PNG_SO) $(DESTDIR)$(PLUGINDIR)/toothsearch/toothsearch-png.so

$(BUILD)/tests/toothsearch/%.o $(BUILD)/$(TS_DIR)/bench.o: MOD_CPPFLAGS := -I$(TS_DIR)
# the accuracy test writes a dump too: png.o, with imgcodecs
$(TS_TEST): $(BUILD)/tests/toothsearch/accuracy.o $(TS_LIB) $(TS_PNG_OBJ)
	$(CXX) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(OPENCV_PNG_LIBS) $(OPENCV_LIBS) -lm
$(TS_BENCH): $(BUILD)/$(TS_DIR)/bench.o $(TS_LIB)
	$(CXX) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(OPENCV_LIBS) -lm
$(TS_REF): $(BUILD)/tests/toothsearch/render_ref.o $(TS_LIB)
	$(CXX) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(OPENCV_LIBS) -lm
# cvexact.h is compiled as in measure.o
$(BUILD)/tests/toothsearch/cvexact.o: tests/toothsearch/cvexact.cpp
	@mkdir -p $(@D)
	$(CXX) $(CPPFLAGS) -I$(TS_DIR) $(OPENCV_CFLAGS) $(TS_CXXWARN) $(CFLAGS) $(TS_VEC) -c -o $@ $<
$(TS_CVEXACT): $(BUILD)/tests/toothsearch/cvexact.o
	$(CXX) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(OPENCV_LIBS) -lm

.PHONY: toothsearch toothsearch-bin toothsearch-bench
toothsearch-bin: $(TS_TEST) $(TS_BENCH) $(TS_REF) $(TS_CVEXACT)
# the measurement's stand-ins for OpenCV calls against OpenCV (cvexact),
# every model in tests/toothsearch rendered as the renderer's definition
# renders it (render_ref), measured against its truth, then the plugin
# through s42 run against the truth of eight of them (plugin.sh); under
# ASan OpenCV's process-long allocations are not ours (lsan.supp)
TS_LSAN = LSAN_OPTIONS="suppressions=$(CURDIR)/tests/toothsearch/lsan.supp$${LSAN_OPTIONS:+:$$LSAN_OPTIONS}"
toothsearch: $(TS_TEST) $(TS_REF) $(TS_CVEXACT) $(S42) $(PLUGIN_SOS)
	$(TS_LSAN) $(TS_CVEXACT)
	$(TS_LSAN) $(TS_REF) tests/toothsearch/*.tool programs/endmill_search.tool
	$(TS_LSAN) $(TS_TEST) tests/toothsearch/*.tool
	$(TS_LSAN) sh tests/toothsearch/plugin.sh $(S42)
toothsearch-bench: $(TS_BENCH)
	$(TS_BENCH) tests/toothsearch/t004_reamer_seed.tool tests/toothsearch/t150_saw_fine.tool

-include $(TS_C_OBJS:.o=.d) $(TS_CXX_OBJS:.o=.d) $(TS_CV_OBJ:.o=.d) $(TS_PNG_OBJ:.o=.d) $(BUILD)/tests/toothsearch/accuracy.d $(BUILD)/tests/toothsearch/render_ref.d $(BUILD)/tests/toothsearch/cvexact.d $(BUILD)/$(TS_DIR)/bench.d
