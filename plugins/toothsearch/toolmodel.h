/* The tool model of the tooth-step search (contracts.md section 5): a
 * `key = value` file with `;` comments, parsed into struct tm_model.  Every
 * error names FILE:LINE; impossible tools are refused.  Plain C, no OpenCV:
 * the unit tests and the fuzzer link it alone. */
#ifndef S42_TOOLMODEL_H
#define S42_TOOLMODEL_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TM_MAX_TEETH 150
/* The probe camera is framed so the tip circle's radius is this fraction of
 * the image side (the renderer and the image-size check share it). */
#define TM_TIP_FRACTION 0.42
/* The smallest step must span this many pixels along the tip circle. */
#define TM_MIN_STEP_PX 8.0
#define TM_MIN_IMAGE 64
#define TM_MAX_IMAGE 4096
#define TM_MAX_DIAMETER 1000000.0   /* µm: 1 m */
#define TM_MIN_LEAD 1000.0          /* µm, when not 0 (straight flutes) */
#define TM_MAX_LEAD 9999999.0       /* µm: the largest value TK can hold */
#define TM_MAX_BLUR 10.0            /* px */

enum tm_hand { TM_LEFT = -1, TM_RIGHT = 1 };

struct tm_model {
  int teeth;                      /* 1 .. TM_MAX_TEETH */
  double steps[TM_MAX_TEETH];     /* degrees from each tooth to the next */
  int even;                       /* the file said "steps = even" */
  double diameter;                /* µm, > 0 */
  double lead;                    /* µm; 0 = straight flutes */
  int hand;                       /* TM_RIGHT or TM_LEFT */
  double noise;                   /* image noise (sigma, grey 0..1), 0..1 */
  double blur;                    /* optical blur (Gaussian sigma), px */
  int image;                      /* image side, px */
  uint32_t seed;                  /* the same model gives the same images */
};

/* Defaults for every key but the required ones (teeth, diameter): steps
 * even, lead 0, hand right, noise 0, blur 0, image 512, seed 1. */
void tm_defaults(struct tm_model *m);

/* Parse a model from text (not NUL-terminated; len bytes).  name is used
 * in messages.  Returns 0, or -1 with "name:line: message" in err. */
int tm_parse(struct tm_model *m, const char *text, size_t len, const char *name,
             char *err, size_t errlen);

/* Read and parse a file (at most 1 MiB).  Returns 0 or -1 with a message. */
int tm_load(struct tm_model *m, const char *path, char *err, size_t errlen);

/* Check a model's consistency (what tm_parse checks after reading the
 * keys); for models built in code.  Returns 0 or -1 with a message. */
int tm_check(const struct tm_model *m, char *err, size_t errlen);

/* The angle (degrees, tool frame, section X = 0) of each tooth's cutting
 * edge: tooth 0 at 0, tooth j+1 at tooth j minus steps[j], so that a search
 * turning A forward meets the teeth in the model's order. */
void tm_tooth_angles(const struct tm_model *m, double *angles);

#ifdef __cplusplus
}
#endif

#endif
