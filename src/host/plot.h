/* `s42 plot`: one plot engine for every dialect.  It watches a headless
 * run (src/host/run.h's watcher: the canonical records of the committed
 * blocks, the moves outside them -- jogs, corrections, teach-in, section
 * moves, oscillation -- the rows and the result), collects the tool path
 * once, and draws it with cairo (PNG, SVG or PDF by the file's extension)
 * in the view of the machine's kind (canon_info.kind):
 *   - "grinder": the planes XY, XZ and YZ side by side and A against time,
 *     block numbers at block starts, arcs as true arcs, hand moves and
 *     corrections apart from the programmed path, the oscillation teal;
 *   - "lathe": the tool tip's path in the part's XZ plane and, with a
 *     stock, the turned part's silhouette;
 *   - any other: the three planes alone (a mill's path is never a lathe's
 *     silhouette).
 * A run that failed is captioned with how and where it stopped. */
#ifndef S42_PLOT_H
#define S42_PLOT_H

#include "canon.h"
#include <stddef.h>
#include <stdint.h>

struct plot;
struct run_watch;

/* A lathe's stock: a bar of diameter d mm, its face at Z 0, reaching to
 * Z -len (the chuck holds it beyond). */
struct plot_stock {
  int has;
  double d, len;
};

/* Parse --stock "40x100" (mm; diameter x length): 0, or -1 with why. */
int plot_parse_stock(const char *text, struct plot_stock *s, char *why, size_t n);

/* stock: a lathe's bar, or NULL.  NULL: out of memory. */
struct plot *plot_new(const struct plot_stock *stock);
void plot_free(struct plot *pl);

/* The engine as the watcher of a run (src/host/run.c): w's members call
 * the feeding functions below (plot_run.c). */
void plot_watch(struct plot *pl, struct run_watch *w);

/* ---- the stream, as the watcher feeds it (the tests feed it directly) ---- */

/* The run starts: the machine (its kind chooses the view) and where the
 * tool is, in counts. */
void plot_begin(struct plot *pl, const struct canon_info *in, const int64_t pos[CANON_AXES]);
/* Each canonical record of a committed block, in order. */
void plot_call(struct plot *pl, const struct canon_call *c);
/* A move outside the program's calls (kind: enum mrun_move_kind of
 * src/core/mrun.h): axis by d counts, the axes at pos after it, at time t. */
void plot_move(struct plot *pl, int kind, int axis, int64_t d, const int64_t pos[CANON_AXES], double t);
/* A block ran: its number (-1 none) and the time after it. */
void plot_row(struct plot *pl, int n, double t);

/* How a run stopped (status 3). */
enum plot_stop { PLOT_STOP_OTHER, PLOT_STOP_KEY, PLOT_STOP_SCRIPT };

struct plot_result {
  int status;                 /* 0 end, 1 program error, 3 stopped */
  const char *code;           /* the error's code, or NULL */
  int n;                      /* the block: the error's (status 1), the one in progress (3); -1 none */
  unsigned line;              /* ... its source line, 0 unknown */
  int stop;                   /* status 3: enum plot_stop */
  const char *waited;         /* PLOT_STOP_SCRIPT: what the machine waited for ("Пуск (key PUSK)") */
  unsigned long long blocks;  /* the blocks the run executed (the dump's "blocks") */
  double t;                   /* the simulated time */
  int has_pos;
  int64_t pos[CANON_AXES];    /* where the axes are, counts (has_pos) */
};
/* How the run ended (status 0, 1 or 3). */
void plot_end(struct plot *pl, const struct plot_result *res);
/* The program did not compile: the view of its machine's kind, the first
 * error's code, block number (-1 none) and line. */
void plot_refused(struct plot *pl, const char *kind, const char *code, int n, unsigned line);

/* Is the output path's extension one we can write (.png .svg .pdf), and
 * is it not the program's file (program: its path, or NULL)?  0, or -1
 * with err. */
int plot_check_path(const char *path, const char *program, char *err, size_t n);
/* Draw and write the file (program: its path, for the title).  0, or -1
 * with err. */
int plot_write(struct plot *pl, const char *program, const char *path, char *err, size_t n);

/* ---- for the tests ---- */
/* The view chosen: "grinder", "lathe" or "planes" (the neutral one). */
const char *plot_view_name(const struct plot *pl);
/* The lathe's silhouette: the part's radius R(z) mm left at z (the cell
 * holding z, 0.01 mm long for a stock up to 200 mm), or -1 without a stock
 * or for z outside 0 .. -len. */
double plot_lathe_radius_at(struct plot *pl, double z);
/* Did the path cut past the stock's end (z < -len at a radius under
 * d/2)?  1 and the least such z in *z, else 0. */
int plot_lathe_chuck(struct plot *pl, double *z);
/* Where the point (radius r, z) lands in the lathe's picture as drawn now
 * (x right, y down, px of the PNG = pt of the SVG and PDF). */
int plot_lathe_page_xy(struct plot *pl, double r, double z, double *x, double *y);

#endif
