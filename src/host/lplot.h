/* The plot of a lathe's run (s42 plot PROGRAM.u22 -o FILE [--stock DxL]):
 * the tool tip's path in the XZ plane of the part -- Z along, the radius
 * up -- drawn from the machine's canonical calls (src/core/canon.h), and,
 * given a stock, the turned part's silhouette: the material the path
 * removed, shaded.  Traverses are dashed; a path that cuts past the
 * stock's end (into the chuck) is marked.  PNG, SVG or PDF by the
 * extension, with cairo loaded at the first plot (src/host/cairo_dl.h). */
#ifndef S42_LPLOT_H
#define S42_LPLOT_H

#include <stddef.h>

struct canon_call;
struct lplot;

/* A stock: a bar of diameter d mm, its face at Z 0, reaching to Z -len
 * (the chuck holds it beyond). */
struct lplot_stock {
  int has;
  double d, len;
};

struct lplot *lplot_new(const struct lplot_stock *stock);
/* Each canonical call of the run, in order (positions in mm by c->mm: a
 * lathe's X comes as the radius). */
void lplot_call(struct lplot *pl, const struct canon_call *c);
/* How the run ended, for the caption: "end", or the error code and block
 * number (-1 none). */
void lplot_result(struct lplot *pl, const char *status, const char *code, int n);
/* Parse --stock "40x100" (mm; diameter x length): 0, or -1 with why. */
int lplot_parse_stock(const char *text, struct lplot_stock *s, char *why, size_t n);
/* Draw to path (.png, .svg, .pdf): 0, or -1 with err. */
int lplot_write(struct lplot *pl, const char *program, const char *path, char *err, size_t n);
void lplot_free(struct lplot *pl);

/* Additions (the host and the tests): */
/* Where the tool is before the first call (radius and Z, mm); without it
 * the first call's position: a first call that moves is not drawn. */
void lplot_at(struct lplot *pl, double r, double z);
/* Is the output path's extension one we can write (.png .svg .pdf), and is
 * it not the program's file (program: its path, or NULL)?  0, or -1 with
 * err (lplot_write checks the extension too: this is for refusing before
 * the run). */
int lplot_check_path(const char *path, const char *program, char *err, size_t n);
/* The silhouette: the part's radius R(z) mm left at z (the silhouette's
 * cell holding z, 0.01 mm long for a stock up to 200 mm), or -1 without a
 * stock or for z outside 0 .. -len. */
double lplot_radius_at(struct lplot *pl, double z);
/* Did the path cut past the stock's end (z < -len at a radius under d/2)?
 * 1 and the least such z in *z, else 0. */
int lplot_chuck(const struct lplot *pl, double *z);
/* Where the point (radius r, z) lands in the picture lplot_write would
 * draw now (x right, y down, px of the PNG = pt of the SVG and PDF). */
int lplot_page_xy(struct lplot *pl, double r, double z, double *x, double *y);

#endif
