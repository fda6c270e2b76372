/* The simulated probe camera: renders the tool's cross-section at a section
 * X and rotation A as an 8-bit grey image (tool bright, background and flutes
 * dark), with blur, noise, an illumination gradient and a per-section offset
 * of the rotation axis.  Deterministic for a model, view and seed. */
#ifndef S42_TS_RENDER_H
#define S42_TS_RENDER_H

#include "toolmodel.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Pixel coordinates follow OpenCV: the centre of pixel (column i, row j) is
 * the point (i, j); angles are atan2(y - cy, x - cx) in degrees, so they
 * grow clockwise on the screen (y points down).  The probe touches the
 * tool at camera angle 0 (to the right of the axis); turning A forward adds
 * to every camera angle, so a tooth's face leads and meets the probe. */
struct ts_view {
  double x_um;        /* section: position along the tool (table X), µm */
  double a_deg;       /* tool rotation A, degrees (any value, unwrapped) */
  double mount_deg;   /* where the tool sits on the spindle: tool angle 0 is
                         at camera angle mount + A in section X = 0 */
  int section;        /* 0 or 1: each section has its own axis offset */
  uint32_t shot;      /* image number: the noise differs per shot */
};

/* What the renderer knows and a measurer must find: for tests. */
struct ts_truth {
  double cx, cy;                  /* rotation axis, pixels */
  double tip_px;                  /* tip radius, pixels */
  double depth_px;                /* flute depth, pixels */
  double edge_deg[TM_MAX_TEETH];  /* camera angle of each cutting edge */
  double flute_deg[TM_MAX_TEETH]; /* angular width of the flute ahead of it */
};

/* Geometry shared with the measurer and tests, no image: the tooth edges'
 * tool-frame angles at section X (degrees, tooth order of the model) and
 * each tooth's flute width (degrees). */
void ts_geometry(const struct tm_model *m, double x_um, double *edge_deg, double *flute_deg);
/* Flute depth, pixels, for an image of the model's size. */
double ts_flute_depth(const struct tm_model *m);

/* Render into pix (m->image rows of m->image bytes).  Returns 0, or -1 with
 * a message (an exception from OpenCV, no memory). */
int ts_render(const struct tm_model *m, const struct ts_view *v, unsigned char *pix,
              struct ts_truth *truth, char *err, size_t errlen);

/* The same image made as the renderer was first written: every pixel of
 * the outline from its definition (atan2 and all), the noise a pixel at a
 * time.  Slow; ts_render must equal it byte for byte (the tests check). */
int ts_render_reference(const struct tm_model *m, const struct ts_view *v, unsigned char *pix,
                        struct ts_truth *truth, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
