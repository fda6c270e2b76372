/* The tooth-step search of G10/G11 (language.md section 15) as a small C
 * library: render the probe camera's images of a tool model in one or two
 * sections, measure the tooth angles in them with OpenCV, and return the
 * circular steps, TK, UG and the simulated search time.  Every entry point
 * catches every C++ exception and returns a status; nothing here exits. */
#ifndef S42_TOOTHSEARCH_H
#define S42_TOOTHSEARCH_H

#include "toolmodel.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The search turns the tool at this speed unless M12 gives F (deg/min):
 * 2000 deg/min, one revolution in 10.8 s -- language.md section 7's
 * default search speed. */
#define TS_DEFAULT_SPEED 2000.0
#define TS_MAX_SPEED 36000.0        /* deg/min: 100 rev/min */
/* Images the camera takes during one revolution, at evenly spaced A. */
#define TS_SHOTS 4

/* Write one 8-bit image as a PNG: rows x cols pixels of channels (1 grey,
 * 3 BGR) bytes, rows step bytes apart; compression 0-9, -1 the default.
 * 0, or -1 when it was not written. */
typedef int (*ts_png_fn)(const char *path, int rows, int cols, int channels, const unsigned char *data,
                         size_t step, int compression);
/* The one ts_png_fn, with OpenCV's imgcodecs (png.cpp): the whole of
 * toothsearch/toothsearch-png.so, which the plugin dlopens for
 * --dump-images; a program may link png.cpp itself (the accuracy test). */
int ts_png_write(const char *path, int rows, int cols, int channels, const unsigned char *data, size_t step,
                 int compression);

enum ts_status {
  TS_OK = 0,
  TS_E_TEETH = 1,      /* no tooth found, more than 150, or no consistent count */
  TS_E_ARG = 2,        /* a bad request: model, speed, equal sections */
  TS_E_INTERNAL = 3,   /* an exception or no memory inside */
  TS_E_IO = 4          /* the images could not be written (results are valid) */
};

struct ts_request {
  double x1_um;          /* table X of section 1, µm */
  double x2_um;          /* table X of section 2 (M10); NaN: no M10 */
  double a1_deg;         /* A when the search in section 1 starts: the probe is
                            in the flute before the first tooth */
  double a2_deg;         /* A when the search in section 2 starts (M10) */
  int hand;              /* programmed: TM_RIGHT (G10) or TM_LEFT (G11) */
  double diameter_um;    /* D1, for UG; <= 0: the model's diameter */
  double speed_deg_min;  /* M12 with F; <= 0: TS_DEFAULT_SPEED */
  const char *dump_dir;  /* NULL, or a directory for the images (PNG) */
  const char *dump_prefix; /* NULL, or the start of their names ("N10_") */
  /* What writes the images of dump_dir (OpenCV's imgcodecs, which loads
   * some 120 libraries, lives apart: tscv.h); NULL with dump_dir: the
   * images are not written (TS_E_IO). */
  ts_png_fn write_png;
};

struct ts_result {
  int teeth;                       /* R99 */
  double steps[TM_MAX_TEETH];      /* degrees, from the first tooth; sum 360 */
  double tk_um;                    /* TK, µm; 0 without M10 or straight flutes */
  double ug_mdeg;                  /* UG, 0.001 degree; 0 likewise */
  double shift_deg;                /* mean angular shift between the sections */
  int measured_hand;               /* TM_RIGHT / TM_LEFT; 0 straight or no M10 */
  int hand_mismatch;               /* measured hand disagrees with G10/G11 */
  double time_s;                   /* simulated time of the search rotations */
  int images;                      /* images taken */
  double centre_px[2][2];          /* calibrated axis (x, y) per section */
  double positions[2][TM_MAX_TEETH]; /* A (deg) where each tooth met the probe,
                                        per search (section 2 or second search) */
};

/* The mounting of the tool on the spindle that puts the probe 40 % into the
 * flute before tooth 1 when section x1 starts at A = a1 (the operator's
 * placement); ts_search uses it for the renderer. */
double ts_mount(const struct tm_model *m, double x1_um, double a1_deg);
/* The A at which an operator who follows the flute from (x1, a1) to section
 * x2 starts the second search (probe at the same place before tooth 1). */
double ts_follow_flute(const struct tm_model *m, double x1_um, double a1_deg, double x2_um);

/* Run a search: with M10 (x2 a number) one revolution in each section, else
 * two revolutions in section 1, averaged.  Returns a ts_status; on an error
 * err holds a message (E-TEETH: "no teeth found", "more than 150 teeth"). */
int ts_search(const struct tm_model *m, const struct ts_request *rq, struct ts_result *out,
              char *err, size_t errlen);

/* Simulated seconds of one revolution at this speed (deg/min, <= 0 default). */
double ts_revolution_time(double speed_deg_min);

/* One search (one revolution, TS_SHOTS images) at a time, for a host that
 * runs them between the operator's actions: ts_search is pass 0, pass 1,
 * then ts_search_combine (and TS_E_IO when images were not written). */
struct ts_pass {
  int teeth;
  double a0_deg;                    /* A when the revolution started */
  double psi_deg[TM_MAX_TEETH];     /* each face's tool-frame angle, degrees */
  double centre_px[2];              /* the calibrated axis */
  int images_failed;                /* some --dump-images file was not written */
};
/* which 0: the search in section 1 (rq->x2_um and a2_deg are not looked
 * at); which 1: section 2 when rq->x2_um is a number (M10), otherwise the
 * second revolution in section 1, from a1 + 360.  E-TEETH here when the
 * images show no teeth, more than 150, or no consistent count. */
int ts_search_pass(const struct tm_model *m, const struct ts_request *rq, int which, struct ts_pass *out,
                   char *err, size_t errlen);
/* Steps, TK, UG and hand from the two passes (as ts_search). */
int ts_search_combine(const struct tm_model *m, const struct ts_request *rq, const struct ts_pass *p1,
                      const struct ts_pass *p2, struct ts_result *out, char *err, size_t errlen);
/* The tooth (0-based, model order) the probe meets first when A turns
 * forward from a_deg in section x_um, the tool mounted as the operator's
 * probe placement (x1_um, a1_deg) in section 1 put it: 0 when the probe is
 * in the flute before tooth 1 -- where a search's tooth order starts. */
int ts_first_tooth(const struct tm_model *m, double x1_um, double a1_deg, double x_um, double a_deg);

#ifdef __cplusplus
}
#endif

#endif
