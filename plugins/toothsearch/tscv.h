/* The boundary between the tooth-search plugin and its heavy part.
 *
 * toothsearch.so (plugin.c, toolmodel.c; plain C, no OpenCV) is what s42
 * loads: the descriptor of G10 G11 M10 M12, the operator's flow of
 * language.md section 15 and the tool model.  Its init() dlopens
 * toothsearch/toothsearch-cv.so beside it (RTLD_NOW | RTLD_LOCAL): the
 * probe camera and the measurement (libtoothsearch.a, C++17 and OpenCV),
 * behind the one C entry below.  So a program that never uses G10/G11
 * never maps OpenCV, and one that does finds out at its start whether the
 * heavy part loads.
 *
 * The heavy part needs only OpenCV's core and imgproc (some twenty
 * libraries).  Writing PNGs needs imgcodecs, which brings some 120 more
 * (codecs, GDAL, ...) and took most of a searching run's time to load, so
 * it is a third library, toothsearch/toothsearch-png.so (png.cpp): init()
 * dlopens it only for --dump-images and hands its one function to the
 * search as ts_request.write_png. */
#ifndef S42_TSCV_H
#define S42_TSCV_H

#include "toothsearch.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TS_CV_ENTRY "ts_cv_entry"
#define TS_CV_VERSION 2   /* 2: ts_request.write_png */
#define TS_CV_FILE "toothsearch/toothsearch-cv.so"   /* under the plugin's directory */
#define TS_PNG_ENTRY "ts_png_write"                  /* a ts_png_fn (toothsearch.h) */
#define TS_PNG_FILE "toothsearch/toothsearch-png.so" /* likewise */

/* toothsearch.h's functions; every one catches every C++ exception. */
struct ts_cv {
  uint32_t size;            /* sizeof(struct ts_cv) */
  int version;              /* TS_CV_VERSION */
  int (*pass)(const struct tm_model *m, const struct ts_request *rq, int which, struct ts_pass *out, char *err,
              size_t errlen);
  int (*combine)(const struct tm_model *m, const struct ts_request *rq, const struct ts_pass *p1,
                 const struct ts_pass *p2, struct ts_result *out, char *err, size_t errlen);
  int (*first_tooth)(const struct tm_model *m, double x1_um, double a1_deg, double x_um, double a_deg);
  double (*follow_flute)(const struct tm_model *m, double x1_um, double a1_deg, double x2_um);
  double (*revolution_time)(double speed_deg_min);
};

typedef const struct ts_cv *(*ts_cv_entry_fn)(void);

#ifdef __cplusplus
}
#endif

#endif
