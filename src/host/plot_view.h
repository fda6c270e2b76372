/* The plot engine's inside (src/host/plot.h), shared by the engine
 * (plot.c: what the run did, collected once from its stream) and the views
 * that draw it (plot_planes.c: the grinder's planes and A(t), and the
 * neutral planes of any other machine; plot_lathe.c: a lathe's profile
 * and silhouette).  Not for the hosts: they see plot.h. */
#ifndef S42_PLOT_VIEW_H
#define S42_PLOT_VIEW_H

#include "plot.h"
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef struct _cairo cairo_t;

#define PLOT_AXES 4            /* X Y Z A: what a picture shows */

/* A piece of the path (about 110 bytes): one programmed move (a record of
 * FEED_LINE, FEED_ARC or TRAVERSE), or a mark where a block started that
 * moved no programmed axis (only by hand, or after a position change);
 * with the hand moves made after it.  Positions are the machine's counts
 * with the oscillation's displacement taken out (drawn apart). */
enum { K_LINE, K_ARC, K_TRAV, K_MARK };
enum { F_THREAD = 1, F_CCW = 2 };

struct seg {
  int64_t start[PLOT_AXES];   /* where the piece starts */
  int32_t d[PLOT_AXES];       /* the programmed move */
  int32_t jog[PLOT_AXES];     /* the hand moves after it, all of them */
  float cp, cq;               /* arc: the centre relative to the start, the plane's axes */
  float sweep;                /* arc: signed sweep, radians (+ counter-clockwise), the turns in it */
  double t0, t1;              /* simulated time it began and ended */
  int32_t n;                  /* block number at a block's first piece, else -1 */
  uint32_t step;              /* its hand moves: steps[step .. the next piece's step) */
  uint8_t kind, plane, flags;
};

/* A hand move (a jog, a teach-in step, a section move): the axes that moved
 * together at one time, from where the piece's path was. */
struct step {
  int32_t d[PLOT_AXES];
  double t;
};

/* A point of an oscillation: the axis's displacement from the contour. */
struct osc_pt {
  double t;
  int64_t off;
  int axis, start;            /* start: where an oscillation begins */
};

struct plot_view;

struct plot {
  const struct plot_view *view;
  const char *program;        /* its path, for the title (plot_write) */
  void *vs;                   /* the view's own state (the lathe's silhouette), or NULL */
  struct plot_stock stock;
  /* the machine */
  int begun;
  char kind[24], name[64];
  char axis_name[PLOT_AXES];  /* 0: the machine has no such axis */
  double unit[PLOT_AXES];     /* counts a mm (a degree) */
  int64_t start_pos[PLOT_AXES];
  /* the path */
  struct seg *v;
  size_t n, cap;
  struct step *steps;
  size_t nsteps, capsteps;
  struct osc_pt *osc;
  size_t nosc, caposc;
  size_t block_seg;           /* the open block's first piece (== n: none yet) */
  int step_open;              /* the last step may take more axes (a move at its time) */
  int step_kind;
  double pitch;               /* the last thread's pitch, mm a revolution */
  int thread;                 /* between SYNCH_START and SYNCH_STOP */
  int64_t cur[PLOT_AXES];     /* where the programmed path is */
  int64_t disp[PLOT_AXES];    /* the oscillation's displacement so far */
  int64_t dapp[PLOT_AXES];    /* ... as taken out of the records up to osc[ocur] */
  size_t ocur;
  unsigned long long rows;
  double t;                   /* time at the end of the last row */
  int oom, retimed;
  /* how the run ended (plot_end): what the dump says */
  int ended, status;
  unsigned long long blocks;
  double t_end;
  int64_t end_pos[PLOT_AXES];
  char why[240];              /* the result caption: "stopped: E-DIV0 at N3"; "" at the end */
};

/* A view: how the run is drawn for a kind of machine. */
struct plot_view {
  const char *name;           /* "grinder", "lathe", "planes" */
  double w, h;                /* the picture, px of the PNG = pt of the SVG and PDF */
  void (*draw)(cairo_t *cr, struct plot *pl, int raster);
  /* the SVG's <title> and <desc> (malloc'd), or NULL: none */
  char *(*svg_head)(struct plot *pl);
  void (*free)(struct plot *pl);
};
extern const struct plot_view plot_view_grinder, plot_view_planes, plot_view_lathe;

/* ---- shared helpers (plot.c) ---- */
void plot_rgb(cairo_t *cr, unsigned c);
void plot_rgba(cairo_t *cr, unsigned c, double a);
void plot_font(cairo_t *cr, double size, int bold);
double plot_text_w(cairo_t *cr, const char *s, double size, int bold);
/* s at (x, y), its advance times align to the left of x (0 left, 0.5 centred, 1 right) */
void plot_text_at(cairo_t *cr, double x, double y, const char *s, double size, int bold, double align);
/* v with dec decimals and the C locale's point; trim: trailing zeros dropped */
void plot_fmt_num(char *buf, size_t n, double v, int dec, int trim);
/* the round step (1, 2, 5 x 10^k) nearest below x, and the decimals it needs */
double plot_nice_step(double x, int *dec);
/* the stop marker: a yellow octagon outlined dark, as a stop sign */
void plot_stop_sign(cairo_t *cr, double x, double y);
/* text for an SVG's <title>/<desc> */
void plot_xml_text(FILE *f, const char *s);
/* the program's file name without its folders */
const char *plot_base(const char *program);

#define C_TEXT 0x222222u
#define C_LABEL 0x595959u
#define C_FRAME 0x8c8c8cu
#define C_START 0x1a9933u
#define C_STOP 0xffd400u       /* the stop marker: a yellow octagon, outlined dark */
#define C_STOPTEXT 0xb3000fu

#endif
