/* The plane views of the plot (src/host/plot_view.h): the grinder's and the
 * neutral one of any machine that has no view of its own (a mill's).
 *
 * The picture is always 1600 x 1000 (pixels for PNG, points for SVG and
 * PDF).  Layout, top to bottom (the test tests/plot/run.sh relies on the
 * frames):
 *   - a title line with the program's name and a summary line (the blocks,
 *     time and end position the run counted); when the run failed, a line
 *     under it says how ("stopped: E-DIV0 at N3");
 *   - three panels, the projections XY, XZ and YZ (the 2С42's planes G17,
 *     G19 and G18), each with the plane's first axis to the right and its
 *     second axis up, so that a counter-clockwise arc turns
 *     counter-clockwise on the page.  Frames: x 40..530, 555..1045,
 *     1070..1560; y 96..676 (the neutral view, which has no A panel:
 *     96..924).  A band of LB px at the left and BB px at the bottom of each
 *     frame holds the tick labels (coordinates in mm), the scale bar and the
 *     axis arrows; everything drawn is fitted into the inner area (left 62,
 *     top 22, right 18, bottom 62 px in from the frame), with one scale on
 *     both axes; a grid at the bar's step; the program start marked by a
 *     green ring, the end by a red square or, for a run that failed, where
 *     it stopped by a yellow octagon;
 *   - the grinder's A panel: A (degrees) against simulated time (s), frame
 *     x 90..1560, y 724..924, labelled along both;
 *   - a legend.
 * Programmed moves are solid blue lines (arcs as true arcs in their plane,
 * projected point by point in the other panels; the neutral view draws
 * traverses apart, dashed); hand moves -- the grinder's G20 jogs and M19
 * teach-in -- dashed orange, step by step as they were made; a position
 * change between blocks (a correction while the cycle runs) dotted
 * magenta; oscillation teal.  Block numbers label block starts where there
 * is room. */
#include "plot_view.h"
#include "geom.h"
#include "cairo_dl.h"
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define PW 1600.0
#define PH 1000.0

/* What differs between the grinder's view and the neutral one. */
struct layout {
  int grinder;              /* the A panel, the 2С42's plane names, the oscillation */
  double ph;                /* the plane panels' height */
};

static void fmt_num(char *buf, size_t n, double v, int dec)
{
  plot_fmt_num(buf, n, v, dec, 1);
}

static double nice_step(double x, int *dec)
{
  return plot_nice_step(x, dec);
}

/* Where the machine was at the end (mm), the contour's end without
 * oscillation in con. */
static void final_pos(const struct plot *pl, double at[4], double con[4])
{
  for (int a = 0; a < 4; a++) {
    int64_t e = pl->ended ? pl->end_pos[a] : pl->cur[a] + pl->disp[a];
    at[a] = e / pl->unit[a];
    con[a] = (e - pl->disp[a]) / pl->unit[a];
  }
}

/* Where the run started (mm). */
static void start_of(const struct plot *pl, double z[4])
{
  for (int a = 0; a < 4; a++)
    z[a] = pl->start_pos[a] / pl->unit[a];
}

/* ---- geometry of the path ---- */

/* Point of segment g at fraction u along its programmed part, mm/deg. */
static void seg_point(const struct plot *pl, const struct seg *g, double u, double out[4])
{
  const int32_t *d = g->d;
  double base[4];
  for (int a = 0; a < 4; a++) {
    base[a] = (double)g->start[a];
    out[a] = base[a] + d[a] * u;
  }
  if (g->kind == K_ARC && u > 0 && u < 1) {
    /* (at its ends an arc is where the linear part is, exactly) */
    int p, q;
    geom_plane_axes(g->plane, &p, &q);
    double cp = g->cp, cq = g->cq;
    double r0 = hypot(cp, cq), r1 = hypot(d[p] - cp, d[q] - cq);
    double th = atan2(-cq, -cp) + g->sweep * u, rr = r0 + (r1 - r0) * u;
    out[p] = base[p] + cp + rr * cos(th);
    out[q] = base[q] + cq + rr * sin(th);
  }
  for (int a = 0; a < 4; a++)
    out[a] /= pl->unit[a];
}

/* The hand moves after g: steps[k] of them, k from g->step up to *end. */
static size_t steps_end(const struct plot *pl, size_t i)
{
  return i + 1 < pl->n ? pl->v[i + 1].step : pl->nsteps;
}

struct bbox { double lo[4], hi[4]; };

static void bb_add(struct bbox *b, const double p[4])
{
  for (int a = 0; a < 4; a++) {
    if (p[a] < b->lo[a]) b->lo[a] = p[a];
    if (p[a] > b->hi[a]) b->hi[a] = p[a];
  }
}

/* Where along an arc (fractions u in (0, 1), in the order the arc reaches
 * them) a coordinate of its plane turns: the start angle th0 plus the
 * sweep passes a multiple of pi/2 -- the first axis (which 0) at 0 and pi,
 * the second (1) at pi/2 and 3 pi/2, either (2) at all four.  At most 5
 * for a sweep of up to 2 pi; returns how many. */
static int arc_turns(double th0, double sweep, int which, double u[8])
{
  int n = 0;
  if (sweep == 0)
    return 0;
  const double h = M_PI / 2;
  double dir = sweep > 0 ? 1 : -1;
  /* the first multiple of pi/2 strictly past th0 in the arc's sense */
  double k = dir > 0 ? floor(th0 / h) + 1 : ceil(th0 / h) - 1;
  for (int i = 0; i < 6 && n < 8; i++, k += dir) {
    double f = (k * h - th0) / sweep;
    if (!(f > 0 && f < 1))
      break;
    long kk = (long)k;
    int odd = (kk % 2 + 2) % 2;   /* 0: a turn of the first axis, 1: of the second */
    if (which == 2 || which == odd)
      u[n++] = f;
  }
  return n;
}

/* An arc's start angle in its plane (the start relative to the centre). */
static double arc_th0(const struct seg *g)
{
  return atan2(-(double)g->cq, -(double)g->cp);
}

/* The box of a segment's programmed part: its ends and, for an arc, the
 * points where a coordinate turns (the extent exactly, without sampling the
 * curve: on a helix the linear axis turns only at the ends). */
static void bb_curve(const struct plot *pl, struct bbox *b, const struct seg *g)
{
  double pt[4], u[8];
  seg_point(pl, g, 0, pt);
  bb_add(b, pt);
  seg_point(pl, g, 1, pt);
  bb_add(b, pt);
  int k = g->kind == K_ARC ? arc_turns(arc_th0(g), g->sweep, 2, u) : 0;
  for (int i = 0; i < k; i++) {
    seg_point(pl, g, u[i], pt);
    bb_add(b, pt);
  }
}

/* The box of the hand moves after segment i: every point they reached. */
static void bb_hand(const struct plot *pl, struct bbox *b, size_t i)
{
  const struct seg *g = &pl->v[i];
  double at[4], pt[4];
  for (int a = 0; a < 4; a++)
    at[a] = (double)g->start[a] + g->d[a];
  for (size_t k = g->step, e = steps_end(pl, i); k < e; k++) {
    for (int a = 0; a < 4; a++) {
      at[a] += pl->steps[k].d[a];
      pt[a] = at[a] / pl->unit[a];
    }
    bb_add(b, pt);
  }
}

/* ---- drawing ---- */

/* A plane panel's frame holds, at its left and bottom, bands for the tick
 * labels (LB and BB px); the grid and the path are in the rest, the
 * region. */
#define LB 50.0
#define BB 50.0

struct panel {
  int u, v;                 /* axes right and up */
  const char *name, *plane;
  double x, y, w, h;        /* the frame */
  double rx, ry, rw, rh;    /* the region inside the tick bands */
  double ix, iy, iw, ih;    /* the area the path is fitted into */
  double s;                 /* px per mm */
  double u0, v0;            /* mm at the centre of the inner area */
  unsigned char *occ;       /* label occupancy, 4x4 px cells */
  int ocw, och, nlabels;
  struct { int n; float x, y; } lab[400];   /* the labels placed */
};

static void pmap(const struct panel *P, double u, double v, double *x, double *y)
{
  *x = P->ix + P->iw / 2 + (u - P->u0) * P->s;
  *y = P->iy + P->ih / 2 - (v - P->v0) * P->s;
}

#define C_PATH 0x1f4db3u
#define C_JOG 0xe67300u
#define C_CORR 0xbf1a99u
#define C_OSC 0x0f9aa6u        /* teal: apart from the start's green */
#define C_TRAV 0x4d6680u       /* the neutral view's traverses */
#define C_END 0xd91a1au
#define C_GRID 0xe6e6e6u
#define C_AXIS 0xbfbfbfu

/* ---- the pen: only what the pixels can show goes to cairo ----
 *
 * A long program draws the same few strokes over and over (repeated passes,
 * small infeeds), and short moves far below a pixel; cairo's cost grows with
 * every segment it strokes, seen or not.  So in each panel and style:
 *   - a segment (or arc) is drawn once for each chunk of the caller's
 *     drawing (CHUNK blocks) it is in, up to PEN_LAYERS times, and never
 *     twice in one chunk: "the same" is ends (and centre) on the same
 *     1/PEN_Q px grid points.  The old plot stroked each chunk apart, so a
 *     line drawn again in another chunk inked its antialiased edges again;
 *     the second and third times are kept aside and stroked over the rest
 *     (the fourth would add less than 1/30 of the ink: left out);
 *   - a new chunk starts a new stroke (lines that cross in two chunks
 *     darken where they cross, as before);
 *   - a polyline's vertices are dropped while the line drawn stays within
 *     PEN_TOL px of every one of them (collinear moves, short moves in a
 *     row: one line), so the cone of directions from the last vertex drawn
 *     that passes within PEN_TOL of each dropped point is kept;
 *   - with colw (the A panel: x is time), the points of a run falling into
 *     one column colw px wide are cut to the first, the lowest, the highest
 *     and the last, in their order: a stroke back and forth within the
 *     column covers the same pixels;
 *   - a stroke holds at most PEN_BATCH segments.
 * The picture differs from drawing every segment by less than PEN_TOL px in
 * its lines and a few levels in the ink of their edges.  SVG and PDF get
 * the same: each visible line once, arcs as arcs. */
#define PEN_Q 8.0          /* the duplicate test's grid: 1/8 px */
#define PEN_TOL 0.0625     /* px: how far a dropped vertex may be off the line */
#define PEN_BATCH 2048     /* segments a stroke: cairo strokes a huge path slowly */
#define PEN_SETS 16384     /* the duplicate test's cache: 64 K keys, 1 MiB */
#define PEN_WAYS 4
#define PEN_LAYERS 3       /* a line seen in more chunks is drawn up to 3 times */

struct pen_col { double x, y; int i; };
struct pen_pt { double x, y; int move; };
/* a line or an arc, as pen_line and pen_arc take it */
struct pen_prim { double x0, y0, x1, y1, cx, cy, r, a0, a1; int arc; };
struct pen_layer { struct pen_prim *v; size_t n, cap; };

struct pen {
  cairo_t *cr;
  int dedupe;                  /* 0 draw all; else the layer: draw what is seen in
                                  that many chunks, when it is */
  long chunk;                  /* the caller's chunk of what it draws */
  struct pen_layer layer[PEN_LAYERS - 1];   /* seen in 2, 3 chunks: drawn over */
  int maxcount;                /* the most chunks a key was seen in */
  uint64_t *set;               /* the cache: 2 words a key, {0, 0} empty */
  size_t used, evicted;        /* keys put in, pushed out */
  int have;                    /* cairo's current point is (sx, sy) */
  double sx, sy;
  int pend;                    /* (ex, ey) is added but not yet drawn */
  double ex, ey, ed;           /* ... and its distance from (sx, sy) */
  int cone;                    /* directions from s: ref + [lo, hi] */
  double ref, lo, hi;
  long nseg;                   /* in cairo's path since the last stroke */
  /* the column (colw > 0) */
  double colw;
  int ncol;                    /* points in the column: 0 none */
  long colk;                   /* its index */
  struct pen_col c_first, c_min, c_max, c_last;
  long ndrawn, nskipped;       /* for the curious (S42_PLOT_STATS) */
  long nprim;                  /* lines and arcs offered (pen_fresh) */
  int lhave;                   /* pen_moveto, pen_lineto: the producer is at (lx, ly) */
  double lx, ly;
  /* the band (pen_band): a stroke's path kept here, not in cairo's */
  double band_r;               /* half the line width; 0: straight to cairo */
  struct pen_pt *bp;
  size_t bn, bcap;
  long nband, nstrip;          /* dense strokes cut, strips stroked */
};

static void pen_init(struct pen *pn, cairo_t *cr, int dedupe, double colw)
{
  memset(pn, 0, sizeof *pn);
  pn->cr = cr;
  pn->dedupe = dedupe;
  pn->colw = colw;
}

static uint64_t mix64(uint64_t x)
{
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdULL;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ULL;
  x ^= x >> 33;
  return x;
}

static int64_t pen_q(double v)
{
  double q = floor(v * PEN_Q + 0.5);
  if (q != q)
    return 0;
  return q > 1e15 ? (int64_t)1e15 : q < -1e15 ? -(int64_t)1e15 : (int64_t)q;
}

/* The key k[0..n) is seen in chunk pn->chunk: how many chunks it has been
 * seen in, this one included, when this is the first time in this one;
 * else 0.  Keys are held as 96 bits of two independent hashes (two keys
 * that differ collide with odds of 2^-96), with the count and the last
 * chunk in the rest of the second word, in a cache of PEN_SETS sets of
 * PEN_WAYS that fits the L2 of a processor: a key forgotten counts from 1
 * again (drawn again, no worse than without the test), and a huge program
 * that repeats nothing costs no cache misses. */
static int pen_count_key(struct pen *pn, const int64_t *k, int n)
{
  uint64_t h1 = 0x9e3779b97f4a7c15ULL, h2 = 0x243f6a8885a308d3ULL;
  for (int i = 0; i < n; i++) {
    h1 = mix64(h1 ^ (uint64_t)k[i]);
    h2 = mix64(h2 + (uint64_t)k[i] * 0x9e3779b97f4a7c15ULL);
  }
  const uint64_t ID = ~(uint64_t)0 << 32, CH = (1u << 28) - 1;
  uint64_t chunk = (uint64_t)pn->chunk & CH;
  h2 &= ID;
  if (!pn->set) {
    pn->set = calloc((size_t)PEN_SETS * PEN_WAYS, 2 * sizeof *pn->set);
    if (!pn->set)
      return 1;   /* no memory for the test: draw it */
  }
  /* two sets it may be in: a key goes where there is room, so that a few
   * too many in one set (drawn again at every pass) take two full sets */
  uint64_t *w = pn->set + (h1 >> 40 & (PEN_SETS - 1)) * PEN_WAYS * 2;
  uint64_t *w2 = pn->set + (h2 >> 40 & (PEN_SETS - 1)) * PEN_WAYS * 2;
  for (int j = 0; j < 2; j++, w = w2)
    for (int i = 0; i < PEN_WAYS; i++) {
      uint64_t *e = w + 2 * i;
      if (e[0] != h1 || (e[1] & ID) != h2 || !e[1])
        continue;
      int cnt = (int)(e[1] >> 28 & 15);
      if ((e[1] & CH) == chunk)
        return 0;
      if (cnt < 15)
        cnt++;
      e[1] = h2 | (uint64_t)cnt << 28 | chunk;
      if (cnt > pn->maxcount)
        pn->maxcount = cnt;
      return cnt;
    }
  w = pn->set + (h1 >> 40 & (PEN_SETS - 1)) * PEN_WAYS * 2;
  if (w[2 * (PEN_WAYS - 1) + 1]) {
    if (!w2[2 * (PEN_WAYS - 1) + 1])
      w = w2;
    else
      pn->evicted++;
  }
  /* new: first in its set, the oldest out */
  memmove(w + 2, w, (PEN_WAYS - 1) * 2 * sizeof *w);
  w[0] = h1;
  w[1] = h2 | (uint64_t)1 << 28 | chunk;
  pn->used++;
  if (pn->maxcount < 1)
    pn->maxcount = 1;
  return 1;
}

/* ---- the band: a dense trace on a raster, drawn by the pixels it covers ----
 *
 * The A panel's traces are functions of time, and a long program puts many
 * blocks into each pixel column: the pen cuts each 1/8 px column to four
 * points, but a run that goes up and down is then still a zigzag of long,
 * nearly vertical lines 1/8 px apart, and cairo's scan converter steps each
 * of their edges through every row it spans -- nearly all of them inside a
 * solid band, where one more line changes nothing.  So on a raster the pen
 * of such a trace (pen_band) keeps each stroke's path, and when the stroke
 * is dense (BAND_DENSE):
 *   - its cores, rectangles of whole pixels it surely covers, are found: in
 *     each pixel column the rows inside the union of the lines' rectangles
 *     (the joins left out), on BAND_SUB sub-columns a pixel; a run of
 *     columns of about the same rows makes one rectangle;
 *   - the rows are cut into strips where a core starts or ends; each strip
 *     is stroked under a clip of its rows with only the lines that come
 *     near its pixels outside the cores spanning it, each run of them with
 *     one line more at either end so that the joins are as in the whole
 *     path: those pixels come out of the same edges as in the whole stroke;
 *   - the cores are filled over it, as solid as the stroke makes them.
 * The picture is the whole stroke's, but for cairo choosing how it samples
 * a row by the edges in that row (a level in an edge pixel, here and
 * there).  The clips are whole rows, wider than the stroke: cairo clips an
 * edge exactly in y, but replaces its part beyond a clip's side by a
 * vertical edge, which a side among the lines can get wrong by a whole
 * pixel; and several boxes in one clip it takes by intersecting polygons,
 * slower than the stroke.  SVG and PDF keep the plain strokes. */
#define BAND_DENSE 32.0    /* px of lines' height per px of width: cut the stroke */
#define BAND_SUB 8         /* sub-columns a pixel column, for the core */
#define BAND_LOST 4        /* rows a column a run may leave out of the core */
#define BAND_RECTS 8       /* cores a stroke, the largest */

/* The pen's path goes to cairo (its current point and stroke) through these
 * three, or into the band's path. */
static void band_replay(struct pen *pn)
{
  for (size_t i = 0; i < pn->bn; i++)
    if (pn->bp[i].move)
      cairo_move_to(pn->cr, pn->bp[i].x, pn->bp[i].y);
    else
      cairo_line_to(pn->cr, pn->bp[i].x, pn->bp[i].y);
  pn->bn = 0;
}

/* No band from here on: what is kept goes into cairo's path. */
static void band_off(struct pen *pn)
{
  if (!(pn->band_r > 0))
    return;
  band_replay(pn);
  free(pn->bp);
  pn->bp = NULL;
  pn->bn = pn->bcap = 0;
  pn->band_r = 0;
}

/* Keep a point of the path: 1, or 0 when there is no band (any more). */
static int band_put(struct pen *pn, double x, double y, int move)
{
  if (!(pn->band_r > 0))
    return 0;
  if (pn->bn == pn->bcap) {
    size_t nc = pn->bcap ? pn->bcap * 2 : 4096;
    struct pen_pt *nv = realloc(pn->bp, nc * sizeof *nv);
    if (!nv) {
      band_off(pn);   /* no memory: the plain stroke */
      return 0;
    }
    pn->bp = nv;
    pn->bcap = nc;
  }
  /* a line with no point before it starts there, as in cairo */
  pn->bp[pn->bn++] = (struct pen_pt){x, y, move || !pn->bn};
  return 1;
}

static void pen_cmove(struct pen *pn, double x, double y)
{
  if (!band_put(pn, x, y, 1))
    cairo_move_to(pn->cr, x, y);
}

static void pen_cline(struct pen *pn, double x, double y)
{
  if (!band_put(pn, x, y, 0))
    cairo_line_to(pn->cr, x, y);
}

/* The rectangle of the line from (px, py) along the unit (ux, uy), len long,
 * r either side -- the points where t = e.u is in [0, len] and s = e.n in
 * [-r, r], e from (px, py), n = (-uy, ux) -- crossed by the vertical line at
 * x: [*lo, *hi], or 0 when it misses it. */
static int rect_at(double px, double py, double ux, double uy, double len, double r, double x, double *lo,
                   double *hi)
{
  double ex = x - px, a = -INFINITY, b = INFINITY;
  double tx = ex * ux, sx = -ex * uy;   /* t = tx + ey uy, s = sx + ey ux */
  if (uy != 0) {
    double y0 = -tx / uy, y1 = (len - tx) / uy;
    a = y0 < y1 ? y0 : y1;
    b = y0 < y1 ? y1 : y0;
  } else if (tx < 0 || tx > len) {
    return 0;
  }
  if (ux != 0) {
    double y0 = (-r - sx) / ux, y1 = (r - sx) / ux;
    if (y0 > y1) {
      double t = y0;
      y0 = y1;
      y1 = t;
    }
    if (y0 > a) a = y0;
    if (y1 < b) b = y1;
  } else if (sx < -r || sx > r) {
    return 0;
  }
  *lo = py + a;
  *hi = py + b;
  return a <= b;
}

/* The line from p to q, r either side, into the sub-columns' intervals
 * (sub-column s spans x from s / BAND_SUB to (s + 1) / BAND_SUB, iv[2 (s -
 * s0)] its lowest and highest y covered whole, lo > hi none): the y at
 * which a sub-column, a little wider, is inside the line's rectangle.  An
 * interval that meets the one kept joins it; else the longer is kept (less
 * core, never a wrong one). */
static void band_rect(const struct pen_pt *p, const struct pen_pt *q, double r, long s0, long ns, double *iv)
{
  const double mx = 1.0 / 64;   /* px: the sub-column's margin */
  double dx = q->x - p->x, dy = q->y - p->y, len = hypot(dx, dy);
  if (!(len > 0) || fabs(dy) < 2)
    return;   /* no more than a row or two of core: left to the stroke */
  double ux = dx / len, uy = dy / len;
  /* the rectangle's corners are p and q, r either way along (-uy, ux) */
  double xa = (p->x < q->x ? p->x : q->x) - r * fabs(uy), xb = (p->x < q->x ? q->x : p->x) + r * fabs(uy);
  long sa = (long)ceil((xa + mx) * BAND_SUB), sb = (long)floor((xb - mx) * BAND_SUB);
  if (sa < s0)
    sa = s0;
  if (sb > s0 + ns)
    sb = s0 + ns;
  for (long s = sa; s < sb; s++) {
    double l0, h0, l1, h1;
    if (!rect_at(p->x, p->y, ux, uy, len, r, (double)s / BAND_SUB - mx, &l0, &h0) ||
        !rect_at(p->x, p->y, ux, uy, len, r, (double)(s + 1) / BAND_SUB + mx, &l1, &h1))
      continue;
    double a = l0 > l1 ? l0 : l1, b = h0 < h1 ? h0 : h1;
    if (!(a < b))
      continue;
    double *v = iv + 2 * (s - s0);
    if (v[0] <= v[1] && a <= v[1] && b >= v[0]) {
      if (a < v[0]) v[0] = a;
      if (b > v[1]) v[1] = b;
    } else if (v[0] > v[1] || b - a > v[1] - v[0]) {
      v[0] = a;
      v[1] = b;
    }
  }
}

/* Is the line ending at point k of the path (k >= 1, not a move) too short
 * for cairo to keep (its ends on the same 1/256 px)? */
static int band_tiny(const struct pen *pn, size_t k)
{
  return fabs(pn->bp[k].x - pn->bp[k - 1].x) < 1.0 / 64 && fabs(pn->bp[k].y - pn->bp[k - 1].y) < 1.0 / 64;
}

/* Add the lines ending at points ka..kb (one subpath) to cairo's path, with
 * the line before and the line after them in the subpath, so that their
 * joins are as in the whole path (a line cairo drops as too short does not
 * count). */
static void band_lines(struct pen *pn, size_t ka, size_t kb)
{
  const struct pen_pt *v = pn->bp;
  for (int more = 1; more && ka > 1 && !v[ka - 1].move; ka--)
    more = band_tiny(pn, ka - 1);
  for (int more = 1; more && kb + 1 < pn->bn && !v[kb + 1].move; kb++)
    more = band_tiny(pn, kb + 1);
  cairo_move_to(pn->cr, v[ka - 1].x, v[ka - 1].y);
  for (size_t k = ka; k <= kb; k++)
    cairo_line_to(pn->cr, v[k].x, v[k].y);
}

/* A core: whole pixels [x0, x1) x [y0, y1) the stroke covers. */
struct band_rect { long x0, x1, y0, y1; };

/* Stroke, under a clip of the rows [y0, y1) across the whole stroke, the
 * lines that come within R of a pixel there outside the cores cov[0..ncov)
 * (those that span these rows). */
static void band_strip(struct pen *pn, long y0, long y1, double xl, double xr, const struct band_rect *cov,
                       int ncov, double R)
{
  const struct pen_pt *v = pn->bp;
  cairo_t *cr = pn->cr;
  size_t ga = 0, gb = 0;   /* the lines ending at points ga..gb, to add */
  int any = 0;
  for (size_t k = 1; k < pn->bn; k++) {
    if (v[k].move)
      continue;
    double ya = fmin(v[k - 1].y, v[k].y), yb = fmax(v[k - 1].y, v[k].y);
    if (yb + R < y0 || ya - R > y1)
      continue;
    int inside = 0;
    for (int i = 0; i < ncov && !inside; i++)
      inside = (v[k - 1].x < v[k].x ? v[k - 1].x : v[k].x) - R >= cov[i].x0 &&
               (v[k - 1].x < v[k].x ? v[k].x : v[k - 1].x) + R <= cov[i].x1;
    if (inside)
      continue;
    if (!any) {
      cairo_save(cr);
      cairo_new_path(cr);
      cairo_rectangle(cr, xl, (double)y0, xr - xl, (double)(y1 - y0));
      cairo_clip(cr);
      any = 1;
    }
    /* a gap of a line or two in one subpath is taken along */
    int join = ga && k <= gb + 3;
    for (size_t i = gb + 1; join && i <= k; i++)
      join = !v[i].move;
    if (ga && !join)
      band_lines(pn, ga, gb);
    if (!join)
      ga = k;
    gb = k;
  }
  if (!any)
    return;
  band_lines(pn, ga, gb);
  cairo_stroke(cr);
  cairo_restore(cr);
  pn->nstrip++;
}

static int rect_larger(const void *a, const void *b)
{
  const struct band_rect *p = a, *q = b;
  long sa = (p->x1 - p->x0) * (p->y1 - p->y0), sb = (q->x1 - q->x0) * (q->y1 - q->y0);
  return sa > sb ? -1 : sa < sb;
}

static int long_cmp(const void *a, const void *b)
{
  long p = *(const long *)a, q = *(const long *)b;
  return p < q ? -1 : p > q;
}

/* Draw the kept path, dense, by its cores and strips: 0, or -1 when it is
 * not worth it (or no memory for it), nothing drawn. */
static int band_cut(struct pen *pn)
{
  const struct pen_pt *v = pn->bp;
  size_t n = pn->bn;
  double r = pn->band_r, R = r + 1;
  double xa = v[0].x, xb = v[0].x, ya = v[0].y, yb = v[0].y, sdy = 0;
  size_t nseg = 0;
  for (size_t k = 0; k < n; k++) {
    if (!isfinite(v[k].x) || !isfinite(v[k].y) || fabs(v[k].x) > 1e6 || fabs(v[k].y) > 1e6)
      return -1;
    xa = fmin(xa, v[k].x);
    xb = fmax(xb, v[k].x);
    ya = fmin(ya, v[k].y);
    yb = fmax(yb, v[k].y);
    if (k && !v[k].move) {
      sdy += fabs(v[k].y - v[k - 1].y);
      nseg++;
    }
  }
  if (nseg < 64 || sdy < BAND_DENSE * (xb - xa + 1))
    return -1;
  long c0 = (long)floor(xa - R), c1 = (long)ceil(xb + R);
  long j0 = (long)floor(ya - R), j1 = (long)ceil(yb + R);
  size_t nc = (size_t)(c1 - c0);
  if (nc > 65536)
    return -1;
  double *iv = malloc(nc * BAND_SUB * 2 * sizeof *iv);
  long *core = malloc(nc * 2 * sizeof *core);
  if (!iv || !core) {
    free(iv);
    free(core);
    return -1;
  }
  for (size_t i = 0; i < nc * BAND_SUB; i++) {
    iv[2 * i] = 1;
    iv[2 * i + 1] = 0;
  }
  for (size_t k = 1; k < n; k++)
    if (!v[k].move)
      band_rect(&v[k - 1], &v[k], r, c0 * BAND_SUB, (long)nc * BAND_SUB, iv);
  /* a column's core: the rows inside every one of its sub-columns' */
  const double my = 1.0 / 16;   /* px: the rows' margin */
  long ncore = 0;
  for (size_t c = 0; c < nc; c++) {
    double lo = -INFINITY, hi = INFINITY;
    for (int s = 0; s < BAND_SUB; s++) {
      const double *w = iv + 2 * (c * BAND_SUB + s);
      lo = fmax(lo, w[0]);
      hi = fmin(hi, w[1]);
    }
    core[2 * c] = core[2 * c + 1] = 0;
    if (lo < hi) {
      long ra = (long)ceil(lo + my), rb = (long)floor(hi - my);
      if (ra < rb) {
        core[2 * c] = ra;
        core[2 * c + 1] = rb;
        ncore += rb - ra;
      }
    }
  }
  free(iv);
  if (!ncore) {
    free(core);
    return -1;
  }
  /* runs of columns, each with a core of one rectangle that leaves out at
   * most BAND_LOST rows a column; the BAND_RECTS largest are kept */
  struct band_rect *rc = malloc(nc * sizeof *rc);
  long *cut = malloc((2 * BAND_RECTS + 2) * sizeof *cut);
  if (!rc || !cut) {
    free(core);
    free(rc);
    free(cut);
    return -1;
  }
  size_t nr = 0;
  for (size_t c = 0, e; c < nc; c = e) {
    long ka = core[2 * c], kb = core[2 * c + 1], sum = kb - ka;
    for (e = c + 1; ka < kb && e < nc && core[2 * e] < core[2 * e + 1]; e++) {
      long na = ka > core[2 * e] ? ka : core[2 * e], nb = kb < core[2 * e + 1] ? kb : core[2 * e + 1];
      long cols = (long)(e - c + 1), s2 = sum + core[2 * e + 1] - core[2 * e];
      if (nb <= na || s2 - (nb - na) * cols > BAND_LOST * cols)
        break;
      ka = na;
      kb = nb;
      sum = s2;
    }
    if (ka < kb)
      rc[nr++] = (struct band_rect){c0 + (long)c, c0 + (long)e, ka, kb};
  }
  free(core);
  qsort(rc, nr, sizeof *rc, rect_larger);
  if (nr > BAND_RECTS)
    nr = BAND_RECTS;
  /* rows cut where a core starts or ends: each strip is stroked with the
   * lines near its pixels outside the cores that span it, then the cores
   * are filled over what the strips drew into them */
  size_t ncut = 0;
  cut[ncut++] = j0;
  cut[ncut++] = j1;
  for (size_t i = 0; i < nr; i++) {
    cut[ncut++] = rc[i].y0;
    cut[ncut++] = rc[i].y1;
  }
  qsort(cut, ncut, sizeof *cut, long_cmp);
  double xl = (double)c0 - 16, xr = (double)c1 + 16;   /* wider than the stroke: only rows clipped */
  for (size_t i = 0; i + 1 < ncut; i++) {
    if (cut[i] == cut[i + 1])
      continue;
    struct band_rect cov[BAND_RECTS];
    int ncov = 0;
    for (size_t k = 0; k < nr; k++)
      if (rc[k].y0 <= cut[i] && rc[k].y1 >= cut[i + 1])
        cov[ncov++] = rc[k];
    band_strip(pn, cut[i], cut[i + 1], xl, xr, cov, ncov, R);
  }
  for (size_t i = 0; i < nr; i++) {
    cairo_new_path(pn->cr);
    cairo_rectangle(pn->cr, (double)rc[i].x0, (double)rc[i].y0, (double)(rc[i].x1 - rc[i].x0),
                    (double)(rc[i].y1 - rc[i].y0));
    cairo_fill(pn->cr);
  }
  free(rc);
  free(cut);
  pn->nband++;
  return 0;
}

static void pen_cstroke(struct pen *pn)
{
  if (!(pn->band_r > 0)) {
    cairo_stroke(pn->cr);
    return;
  }
  if (pn->bn && band_cut(pn) != 0) {
    band_replay(pn);
    cairo_stroke(pn->cr);
  }
  pn->bn = 0;
}

/* The pen draws on a raster with solid lines (no dash) of width w: dense
 * strokes by the band (the cores are inside the lines' rectangles, which
 * every join and cap keeps; a dash would not). */
static void pen_band(struct pen *pn, double w)
{
  pn->band_r = w / 2;
}

static void pen_stroke(struct pen *pn)
{
  pen_cstroke(pn);
  pn->nseg = 0;
  if (pn->have)
    pen_cmove(pn, pn->sx, pn->sy);
}

static void pen_emit(struct pen *pn, double x, double y)
{
  pen_cline(pn, x, y);
  pn->sx = x;
  pn->sy = y;
  pn->pend = pn->cone = 0;
  pn->ed = 0;
  pn->ndrawn++;
  if (++pn->nseg >= PEN_BATCH)
    pen_stroke(pn);
}

static double wrap_pi(double a)
{
  while (a > M_PI) a -= 2 * M_PI;
  while (a <= -M_PI) a += 2 * M_PI;
  return a;
}

/* The polyline goes on to (x, y): drop the pending vertex when the line
 * from the last vertex drawn to (x, y) passes within PEN_TOL of it and of
 * all dropped before it. */
static void pen_vertex(struct pen *pn, double x, double y)
{
  for (int again = 0; again < 2; again++) {
    double dx = x - pn->sx, dy = y - pn->sy, d = hypot(dx, dy);
    if (d >= pn->ed) {
      if (d <= PEN_TOL) {
        pn->pend = 1, pn->ex = x, pn->ey = y, pn->ed = d;
        return;
      }
      double th = atan2(dy, dx), al = asin(PEN_TOL / d);
      if (!pn->cone) {
        pn->cone = 1;
        pn->ref = th;
        pn->lo = -al;
        pn->hi = al;
        pn->pend = 1, pn->ex = x, pn->ey = y, pn->ed = d;
        return;
      }
      double o = wrap_pi(th - pn->ref);
      if (o >= pn->lo && o <= pn->hi) {
        if (o - al > pn->lo) pn->lo = o - al;
        if (o + al < pn->hi) pn->hi = o + al;
        pn->pend = 1, pn->ex = x, pn->ey = y, pn->ed = d;
        return;
      }
    }
    if (!pn->pend)
      break;
    pen_emit(pn, pn->ex, pn->ey);   /* and start over from there */
  }
  pen_emit(pn, x, y);
}

static void pen_col_flush(struct pen *pn)
{
  if (!pn->ncol)
    return;
  struct pen_col c[4] = {pn->c_first, pn->c_min, pn->c_max, pn->c_last};
  /* in the order they came, each once */
  if (c[2].i < c[1].i) {
    struct pen_col t = c[1];
    c[1] = c[2];
    c[2] = t;
  }
  int last = -1;
  for (int k = 0; k < 4; k++)
    if (c[k].i > last) {
      pen_vertex(pn, c[k].x, c[k].y);
      last = c[k].i;
    }
  pn->ncol = 0;
}

static void pen_point(struct pen *pn, double x, double y)
{
  if (!(pn->colw > 0)) {
    pen_vertex(pn, x, y);
    return;
  }
  long k = (long)floor(x / pn->colw);
  if (pn->ncol && k != pn->colk)
    pen_col_flush(pn);
  struct pen_col p = {x, y, pn->ncol};
  if (!pn->ncol) {
    pn->colk = k;
    pn->c_first = pn->c_min = pn->c_max = p;
  }
  if (y < pn->c_min.y) pn->c_min = p;
  if (y > pn->c_max.y) pn->c_max = p;
  pn->c_last = p;
  pn->ncol++;
}

/* The end of a polyline: draw what is pending. */
static void pen_break(struct pen *pn)
{
  pen_col_flush(pn);
  if (pn->pend)
    pen_emit(pn, pn->ex, pn->ey);
  pn->have = 0;
  pn->cone = 0;
  pn->ed = 0;
}

/* What follows is in chunk c: a new chunk is a new stroke, as before the
 * pen (lines that cross in two strokes darken where they cross). */
static void pen_chunk(struct pen *pn, long c)
{
  if (c != pn->chunk && pn->nseg) {
    pen_col_flush(pn);
    if (pn->pend)
      pen_emit(pn, pn->ex, pn->ey);
    if (pn->nseg)
      pen_stroke(pn);
  }
  pn->chunk = c;
}

/* The point the polyline is at. */
static int pen_at(const struct pen *pn, double x, double y)
{
  double cx = pn->sx, cy = pn->sy;
  if (pn->ncol) {
    cx = pn->c_last.x;
    cy = pn->c_last.y;
  } else if (pn->pend) {
    cx = pn->ex;
    cy = pn->ey;
  }
  return pn->have && fabs(cx - x) < 1e-7 && fabs(cy - y) < 1e-7;
}

static void pen_start(struct pen *pn, double x, double y)
{
  if (pen_at(pn, x, y))
    return;
  pen_break(pn);
  pen_cmove(pn, x, y);
  pn->have = 1;
  pn->sx = x;
  pn->sy = y;
}

/* Is this line (arc 0) or arc (1 cairo_arc, 2 cairo_arc_negative; round
 * (cx, cy), radius r, angles a0 to a1) one to draw now?  Seen again in
 * another chunk, it goes to the next layer (drawn later, over). */
static int pen_fresh(struct pen *pn, const struct pen_prim *pr)
{
  pn->nprim++;
  if (!pn->dedupe)
    return 1;
  int64_t k[7] = {pen_q(pr->x0), pen_q(pr->y0), pen_q(pr->x1), pen_q(pr->y1), pr->arc, 0, 0};
  if (!pr->arc && (k[0] > k[2] || (k[0] == k[2] && k[1] > k[3]))) {
    /* a line is the same both ways */
    int64_t t = k[0]; k[0] = k[2]; k[2] = t;
    t = k[1]; k[1] = k[3]; k[3] = t;
  }
  if (pr->arc) {
    k[5] = pen_q(pr->cx);
    k[6] = pen_q(pr->cy);
  }
  int c = pen_count_key(pn, k, pr->arc ? 7 : 5);
  if (c == 1)
    return 1;
  if (c >= 2 && c <= PEN_LAYERS) {
    struct pen_layer *L = &pn->layer[c - 2];
    if (L->n == L->cap) {
      size_t nc = L->cap ? L->cap * 2 : 256;
      struct pen_prim *nv = realloc(L->v, nc * sizeof *nv);
      if (nv) {
        L->v = nv;
        L->cap = nc;
      }
    }
    if (L->n < L->cap)
      L->v[L->n++] = *pr;
  }
  pn->nskipped++;
  pen_break(pn);
  return 0;
}

static void pen_draw(struct pen *pn, const struct pen_prim *pr)
{
  pen_start(pn, pr->x0, pr->y0);
  if (!pr->arc) {
    pen_point(pn, pr->x1, pr->y1);
    return;
  }
  pen_col_flush(pn);
  if (pn->pend)
    pen_emit(pn, pn->ex, pn->ey);
  band_off(pn);   /* (the band takes lines only) */
  if (pr->arc == 2)
    cairo_arc_negative(pn->cr, pr->cx, pr->cy, pr->r, pr->a0, pr->a1);
  else
    cairo_arc(pn->cr, pr->cx, pr->cy, pr->r, pr->a0, pr->a1);
  pn->pend = 0;
  pn->nseg += 8;
  pen_emit(pn, pr->x1, pr->y1);
}

/* A line from (x0, y0) to (x1, y1): on from the point the polyline is at
 * when it starts there. */
static void pen_line(struct pen *pn, double x0, double y0, double x1, double y1)
{
  struct pen_prim pr = {x0, y0, x1, y1, 0, 0, 0, 0, 0, 0};
  if (pen_fresh(pn, &pr))
    pen_draw(pn, &pr);
}

/* An arc round (cx, cy) of radius r from angle a0 to a1 (cairo's sense:
 * neg, decreasing), from (x0, y0) to (x1, y1). */
static void pen_arc(struct pen *pn, double cx, double cy, double r, double a0, double a1, int neg, double x0,
                    double y0, double x1, double y1)
{
  struct pen_prim pr = {x0, y0, x1, y1, cx, cy, r, a0, a1, neg ? 2 : 1};
  if (pen_fresh(pn, &pr))
    pen_draw(pn, &pr);
}

/* Stroke what is left, then the layers over it (each its own strokes, as
 * the same line stroked again darkens its edges), forget what was drawn. */
static void pen_done(struct pen *pn)
{
  pen_break(pn);
  pen_cstroke(pn);
  if (getenv("S42_PLOT_STATS"))
    fprintf(stderr, "pen: %ld drawn, %ld duplicates left out (%zu, %zu again), %zu keys, %zu forgotten; "
            "%ld dense strokes in %ld strips\n", pn->ndrawn, pn->nskipped, pn->layer[0].n, pn->layer[1].n,
            pn->used, pn->evicted, pn->nband, pn->nstrip);
  free(pn->bp);
  pn->bp = NULL;
  pn->bn = pn->bcap = 0;
  pn->band_r = 0;
  free(pn->set);
  pn->set = NULL;
  pn->used = pn->evicted = 0;
  pn->nseg = 0;
  pn->have = 0;
  for (int l = 0; l < PEN_LAYERS - 1; l++) {
    struct pen_layer *L = &pn->layer[l];
    if (L->n) {
      struct pen sub;
      pen_init(&sub, pn->cr, 0, 0);
      for (size_t i = 0; i < L->n; i++)
        pen_draw(&sub, &L->v[i]);
      pen_break(&sub);
      cairo_stroke(pn->cr);
    }
    free(L->v);
    L->v = NULL;
    L->n = L->cap = 0;
  }
}

/* A producer's polyline: to (x, y) with no line, then lines on from there. */
static void pen_moveto(struct pen *pn, double x, double y)
{
  pn->lx = x;
  pn->ly = y;
  pn->lhave = 1;
}

static void pen_lineto(struct pen *pn, double x, double y)
{
  if (pn->lhave && (pn->lx != x || pn->ly != y))
    pen_line(pn, pn->lx, pn->ly, x, y);
  pen_moveto(pn, x, y);
}

/* Add the programmed part (teach 0) or the hand moves (teach 1: jogs,
 * teach-in, section moves, step by step) of segment i to the pen's path in
 * panel P. */
static void path_seg(struct pen *pn, const struct plot *pl, const struct panel *P, size_t i, int teach)
{
  const struct seg *g = &pl->v[i];
  double a[4], b[4], x0, y0, x1, y1;
  if (teach) {
    /* the hand moves, step by step as they were made */
    for (int k = 0; k < 4; k++)
      a[k] = (double)g->start[k] + g->d[k];
    for (size_t k = g->step, e = steps_end(pl, i); k < e; k++) {
      const int32_t *d = pl->steps[k].d;
      if (!d[P->u] && !d[P->v]) {
        for (int c = 0; c < 4; c++)
          a[c] += d[c];
        continue;   /* does not move in this panel */
      }
      pmap(P, a[P->u] / pl->unit[P->u], a[P->v] / pl->unit[P->v], &x0, &y0);
      for (int c = 0; c < 4; c++)
        a[c] += d[c];
      pmap(P, a[P->u] / pl->unit[P->u], a[P->v] / pl->unit[P->v], &x1, &y1);
      pen_line(pn, x0, y0, x1, y1);
    }
    return;
  }
  seg_point(pl, g, 0, a);
  seg_point(pl, g, 1, b);
  int curve = g->kind == K_ARC;
  if (a[P->u] == b[P->u] && a[P->v] == b[P->v] && !curve)
    return;   /* does not move in this panel */
  pmap(P, a[P->u], a[P->v], &x0, &y0);
  pmap(P, b[P->u], b[P->v], &x1, &y1);
  int p = 0, q = 0;
  if (curve)
    geom_plane_axes(g->plane, &p, &q);
  if (curve && P->u == p && P->v == q) {
    double r = hypot(g->cp, g->cq) / pl->unit[p] * P->s;
    double cx = x0 + g->cp / pl->unit[p] * P->s, cy = y0 - g->cq / pl->unit[q] * P->s;
    double th0 = atan2(-(double)g->cq, -(double)g->cp);
    /* page y runs down: a counter-clockwise turn decreases the page angle */
    pen_arc(pn, cx, cy, r, -th0, -th0 - g->sweep, g->sweep > 0, x0, y0, x1, y1);
  } else if (curve && g->d[P->u != p && P->u != q ? P->u : P->v] == 0) {
    /* the panel's other axis does not move: the arc projects to a line
     * along the plane's axis in the panel, drawn to where that coordinate
     * turns and on to the end (not point by point) */
    double u[8], pt[4], x, y;
    int k = arc_turns(arc_th0(g), g->sweep, P->u == p || P->v == p ? 0 : 1, u);
    pen_moveto(pn, x0, y0);
    for (int j = 0; j < k; j++) {
      seg_point(pl, g, u[j], pt);
      pmap(P, pt[P->u], pt[P->v], &x, &y);
      pen_lineto(pn, x, y);
    }
    pen_lineto(pn, x1, y1);
  } else if (curve) {
    double r = hypot(g->cp, g->cq) / pl->unit[p] * P->s;
    int k = (int)ceil(fabs(g->sweep) * r / 2.0);
    if (k < 2) k = 2;
    if (k > 360) k = 360;
    pen_moveto(pn, x0, y0);
    for (int j = 1; j <= k; j++) {
      double pt[4], x, y;
      seg_point(pl, g, (double)j / k, pt);
      pmap(P, pt[P->u], pt[P->v], &x, &y);
      pen_lineto(pn, x, y);
    }
  } else {
    pen_line(pn, x0, y0, x1, y1);
  }
}

static void end_of(const struct plot *pl, const struct seg *g, double out[4])
{
  for (int a = 0; a < 4; a++)
    out[a] = ((double)g->start[a] + g->d[a] + g->jog[a]) / pl->unit[a];
}

static int seg_has_jog(const struct seg *g)
{
  return g->jog[0] || g->jog[1] || g->jog[2] || g->jog[3];
}

#define CHUNK 128   /* blocks a chunk (the old plot's strokes): see the pen */

/* ---- segments seen before ----
 *
 * Repeated passes repeat segments exactly, most of them within one chunk,
 * where the pen leaves out each of their lines and arcs again: a segment's
 * shape (its start, moves, arc: all that path_seg and bb_curve read) gets
 * two independent 64-bit hashes (seg_hash; two different shapes collide
 * with odds of 2^-128), and a small table of the shapes drawn whole in the
 * chunk (SEEN_SLOTS; one that drops out is drawn whole again, as without
 * it) lets the next copy in the same chunk go without working out its
 * geometry: what the pen would do with it, given its lines and arcs all
 * seen in this chunk, is to break the polyline.  (Where the pen's own cache
 * would have forgotten one of them in between and drawn it again -- a
 * chunk of tens of thousands of lines -- it stays left out, as the pen
 * means.) */
#define SEEN_SLOTS 1024

struct seen { uint64_t h1, h2; long chunk, nprim; };

static void seg_hash(const struct plot *pl, size_t i, uint64_t h[2])
{
  const struct seg *g = &pl->v[i];
  uint64_t w[10];
  float f[3] = {g->cp, g->cq, g->sweep};
  uint32_t fb[3];
  memcpy(fb, f, sizeof fb);
  for (int a = 0; a < 4; a++)
    w[a] = (uint64_t)g->start[a];
  w[4] = (uint32_t)g->d[0] | (uint64_t)(uint32_t)g->d[1] << 32;
  w[5] = (uint32_t)g->d[2] | (uint64_t)(uint32_t)g->d[3] << 32;
  w[6] = (uint32_t)g->jog[0] | (uint64_t)(uint32_t)g->jog[1] << 32;
  w[7] = (uint32_t)g->jog[2] | (uint64_t)(uint32_t)g->jog[3] << 32;
  w[8] = fb[0] | (uint64_t)fb[1] << 32;
  w[9] = fb[2] | (uint64_t)g->kind << 32 | (uint64_t)g->plane << 40 | (uint64_t)g->flags << 48;
  uint64_t h1 = 0x9e3779b97f4a7c15ULL, h2 = 0x243f6a8885a308d3ULL;
  for (int k = 0; k < 10; k++) {
    h1 = mix64(h1 ^ w[k]);
    h2 = mix64(h2 + w[k] * 0x9e3779b97f4a7c15ULL);
  }
  /* hand moves in more than one step: their shape too */
  size_t k0 = g->step, k1 = steps_end(pl, i);
  for (size_t k = k0; k1 > k0 + 1 && k < k1; k++)
    for (int a = 0; a < 4; a += 2) {
      uint64_t x = (uint32_t)pl->steps[k].d[a] | (uint64_t)(uint32_t)pl->steps[k].d[a + 1] << 32;
      h1 = mix64(h1 ^ x);
      h2 = mix64(h2 + x * 0x9e3779b97f4a7c15ULL);
    }
  h[0] = h1;
  h[1] = h2;
}

/* Every segment's hashes (2 words a segment), or NULL (no memory: none). */
static uint64_t *seg_hashes(const struct plot *pl)
{
  uint64_t *gh = pl->n ? malloc(pl->n * 2 * sizeof *gh) : NULL;
  for (size_t i = 0; gh && i < pl->n; i++)
    seg_hash(pl, i, gh + 2 * i);
  return gh;
}

static struct seen *seen_new(const uint64_t *gh)
{
  struct seen *t = gh ? malloc(SEEN_SLOTS * sizeof *t) : NULL;
  for (size_t i = 0; t && i < SEEN_SLOTS; i++)
    t[i] = (struct seen){0, 0, -1, 0};
  return t;
}

/* path_seg, or what it would come to for a segment drawn whole before in
 * this chunk (h its hashes). */
static void path_seg_seen(struct pen *pn, struct seen *tab, const uint64_t *h, const struct plot *pl,
                          const struct panel *P, size_t i, int teach)
{
  if (!tab || !pn->set || !pn->dedupe) {   /* (no cache in the pen: it draws all) */
    path_seg(pn, pl, P, i, teach);
    return;
  }
  struct seen *e = &tab[h[0] & (SEEN_SLOTS - 1)];
  if (e->chunk == pn->chunk && e->h1 == h[0] && e->h2 == h[1]) {
    if (e->nprim) {
      pn->nskipped += e->nprim;
      pen_break(pn);
    }
    return;
  }
  long before = pn->nprim;
  path_seg(pn, pl, P, i, teach);
  *e = (struct seen){h[0], h[1], pn->chunk, pn->nprim - before};
}

static void draw_panel_path(cairo_t *cr, struct panel *P, const struct plot *pl, const uint64_t *gh,
                            const struct layout *ly)
{
  struct pen pn;
  struct seen *tab = seen_new(gh);
  /* traverses apart (the neutral view): dashed, under the rest */
  int apart = !ly->grinder;
  if (apart) {
    double dash[] = {6.0, 4.0};
    plot_rgb(cr, C_TRAV);
    cairo_set_line_width(cr, 1.1);
    cairo_set_dash(cr, dash, 2, 0);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    pen_init(&pn, cr, 1, 0);
    for (size_t i = 0, k = 0; i < pl->n; i++)
      if (pl->v[i].kind == K_TRAV) {
        pen_chunk(&pn, (long)(k++ / CHUNK));
        path_seg_seen(&pn, tab, gh + 2 * i, pl, P, i, 0);
      }
    pen_done(&pn);
    cairo_set_dash(cr, NULL, 0, 0);
    for (size_t i = 0; tab && i < SEEN_SLOTS; i++)
      tab[i].chunk = -1;
  }
  /* programmed moves: solid */
  plot_rgb(cr, C_PATH);
  cairo_set_line_width(cr, 1.4);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  pen_init(&pn, cr, 1, 0);
  for (size_t i = 0; i < pl->n; i++) {
    if (apart && pl->v[i].kind == K_TRAV) {
      pen_break(&pn);
      continue;
    }
    pen_chunk(&pn, (long)(i / CHUNK));
    path_seg_seen(&pn, tab, gh + 2 * i, pl, P, i, 0);
  }
  pen_done(&pn);
  for (size_t i = 0; tab && i < SEEN_SLOTS; i++)
    tab[i].chunk = -1;

  /* manual moves: dashed */
  plot_rgb(cr, C_JOG);
  cairo_set_line_width(cr, 2.0);
  double dash[] = {6.0, 3.5};
  cairo_set_dash(cr, dash, 2, 0);
  pen_init(&pn, cr, 1, 0);
  for (size_t i = 0, k = 0; i < pl->n; i++)
    if (seg_has_jog(&pl->v[i])) {
      pen_chunk(&pn, (long)(k++ / CHUNK));
      path_seg_seen(&pn, tab, gh + 2 * i, pl, P, i, 1);
    }
  pen_done(&pn);
  free(tab);
  cairo_set_dash(cr, NULL, 0, 0);
  /* corrections between blocks: dotted */
  plot_rgb(cr, C_CORR);
  cairo_set_line_width(cr, 1.6);
  double dots[] = {1.0, 3.0};
  cairo_set_dash(cr, dots, 2, 0);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  pen_init(&pn, cr, 1, 0);
  double prev[4];
  start_of(pl, prev);
  size_t k = 0;
  for (size_t i = 0; i < pl->n; i++) {
    const struct seg *g = &pl->v[i];
    double st[4], x0, y0, x1, y1;
    for (int a = 0; a < 4; a++)
      st[a] = g->start[a] / pl->unit[a];
    if (st[P->u] != prev[P->u] || st[P->v] != prev[P->v]) {
      pmap(P, prev[P->u], prev[P->v], &x0, &y0);
      pmap(P, st[P->u], st[P->v], &x1, &y1);
      pen_break(&pn);   /* each a stroke of its own: the dots start at its start */
      pen_chunk(&pn, (long)(k++ / CHUNK));
      pen_line(&pn, x0, y0, x1, y1);
    }
    end_of(pl, g, prev);
  }
  /* a correction after the last block */
  double at[4], con[4], x0, y0, x1, y1;
  final_pos(pl, at, con);
  if (con[P->u] != prev[P->u] || con[P->v] != prev[P->v]) {
    pmap(P, prev[P->u], prev[P->v], &x0, &y0);
    pmap(P, con[P->u], con[P->v], &x1, &y1);
    pen_break(&pn);
    pen_line(&pn, x0, y0, x1, y1);
  }
  pen_done(&pn);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  cairo_set_dash(cr, NULL, 0, 0);
}

/* The programmed point at time t (the segment walk starts at *j). */
static void point_at(const struct plot *pl, double t, size_t *j, double out[4])
{
  while (*j + 1 < pl->n && pl->v[*j].t1 < t)
    (*j)++;
  const struct seg *g = &pl->v[*j];
  double u = g->t1 > g->t0 ? (t - g->t0) / (g->t1 - g->t0) : 1;
  if (t < g->t0)
    u = 0;   /* between blocks: where this one starts */
  seg_point(pl, g, u < 0 ? 0 : u > 1 ? 1 : u, out);
}

/* Oscillation: the programmed path plus the axis's displacement.  Between
 * two points the axis moves evenly while the contour may curve: `steps`
 * points from point i-1 to point i follow it; this is the k-th (mm). */
static int osc_steps(const struct plot *pl, size_t i)
{
  return i == 0 || pl->osc[i].start ? 1 : 16;
}

static void osc_point(const struct plot *pl, size_t i, int k, size_t *j, double pt[4])
{
  const struct osc_pt *o = &pl->osc[i];
  int steps = osc_steps(pl, i);
  double f = (double)k / steps;
  double t = steps == 1 ? o->t : pl->osc[i - 1].t + (o->t - pl->osc[i - 1].t) * f;
  double off = steps == 1 ? (double)o->off : pl->osc[i - 1].off + (o->off - pl->osc[i - 1].off) * f;
  point_at(pl, t, j, pt);
  pt[o->axis] += off / pl->unit[o->axis];
}

/* The plugin reports an advance's turning points all at its end time (the
 * machine's clock moves first): spread them over the advance, in
 * proportion to the way the axis travelled, as it runs at one speed.  An
 * advance starts where the point before it was reported. */
static void osc_retime(struct plot *pl)
{
  for (size_t i = 1; i < pl->nosc;) {
    const struct osc_pt *o = &pl->osc[i];
    size_t e = i;
    while (e + 1 < pl->nosc && !pl->osc[e + 1].start && pl->osc[e + 1].t == o->t &&
           pl->osc[e + 1].axis == o->axis)
      e++;
    double t0 = pl->osc[i - 1].t, t1 = o->t, way = 0, done = 0;
    if (o->start || e == i || !(t1 > t0) || pl->osc[i - 1].axis != o->axis) {
      i = e + 1;
      continue;
    }
    for (size_t k = i; k <= e; k++)
      way += fabs((double)(pl->osc[k].off - pl->osc[k - 1].off));
    for (size_t k = i; k <= e && way > 0; k++) {
      done += fabs((double)(pl->osc[k].off - pl->osc[k - 1].off));
      pl->osc[k].t = k == e ? t1 : t0 + (t1 - t0) * done / way;
    }
    i = e + 1;
  }
}

static void draw_panel_osc(cairo_t *cr, const struct panel *P, const struct plot *pl)
{
  if (!pl->nosc || !pl->n)
    return;
  plot_rgb(cr, C_OSC);
  cairo_set_line_width(cr, 1.0);
  struct pen pn;
  pen_init(&pn, cr, 1, 0);
  size_t j = 0;
  for (size_t i = 0; i < pl->nosc; i++) {
    const struct osc_pt *o = &pl->osc[i];
    double pt[4], x = 0, y = 0;
    int steps = osc_steps(pl, i);
    if (o->axis != P->u && o->axis != P->v)
      continue;   /* it would only cover the contour */
    pen_chunk(&pn, (long)(i / CHUNK));
    for (int k = 1; k <= steps; k++) {
      osc_point(pl, i, k, &j, pt);
      pmap(P, pt[P->u], pt[P->v], &x, &y);
      if (i == 0 || o->start)
        pen_moveto(&pn, x, y);
      else
        pen_lineto(&pn, x, y);
    }
  }
  pen_done(&pn);
}

/* Block numbers at block starts, where there is room. */
static void draw_labels(cairo_t *cr, struct panel *P, const struct plot *pl)
{
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 9.5);
  /* the numbers' widths, measured once each (block numbers have at most 3
   * digits): a long program labels few of its blocks but asks about all */
  double wid[1000];
  for (int k = 0; k < 1000; k++)
    wid[k] = -1;
  for (size_t i = 0; i < pl->n && P->nlabels < 400; i++) {
    const struct seg *g = &pl->v[i];
    if (g->n < 0)
      continue;
    double a[4], b[4], x0, y0, x1, y1;
    seg_point(pl, g, 0, a);
    end_of(pl, g, b);
    pmap(P, a[P->u], a[P->v], &x0, &y0);
    pmap(P, b[P->u], b[P->v], &x1, &y1);
    if (fabs(x1 - x0) < 1 && fabs(y1 - y0) < 1 && g->kind != K_ARC)
      continue;   /* the block does not move in this panel */
    char s[16];
    snprintf(s, sizeof s, "%d", (int)g->n);   /* (cheap beside what follows) */
    double adv = g->n < 1000 ? wid[g->n] : -1;
    if (adv < 0) {
      cairo_text_extents_t e;
      cairo_text_extents(cr, s, &e);
      adv = e.x_advance;
      if (g->n < 1000)
        wid[g->n] = adv;
    }
    double lx = x0 + 3, ly = y0 - 3;   /* baseline left */
    double rx0 = lx - 1, ry0 = ly - 10, rx1 = lx + adv + 1, ry1 = ly + 2;
    if (rx0 < P->rx + 2 || rx1 > P->rx + P->rw - 2 || ry0 < P->ry + 2 || ry1 > P->ry + P->rh - 2)
      continue;
    int c0 = (int)((rx0 - P->x) / 4), c1 = (int)((rx1 - P->x) / 4);
    int r0 = (int)((ry0 - P->y) / 4), r1 = (int)((ry1 - P->y) / 4);
    int free_ = 1;
    for (int r = r0; r <= r1 && free_; r++)
      for (int c = c0; c <= c1; c++)
        if (r < 0 || c < 0 || r >= P->och || c >= P->ocw || P->occ[r * P->ocw + c]) {
          free_ = 0;
          break;
        }
    for (int k = 0; k < P->nlabels && free_; k++)
      if (P->lab[k].n == g->n && fabs(P->lab[k].x - x0) < 70 && fabs(P->lab[k].y - y0) < 70)
        free_ = 0;   /* the same block again close by: once is enough */
    if (!free_)
      continue;
    P->lab[P->nlabels].n = g->n;
    P->lab[P->nlabels].x = (float)x0;
    P->lab[P->nlabels].y = (float)y0;
    for (int r = r0 - 1; r <= r1 + 1; r++)
      for (int c = c0 - 1; c <= c1 + 1; c++)
        if (r >= 0 && c >= 0 && r < P->och && c < P->ocw)
          P->occ[r * P->ocw + c] = 1;
    P->nlabels++;
    plot_rgb(cr, C_LABEL);
    cairo_new_path(cr);
    cairo_arc(cr, x0, y0, 1.6, 0, 2 * M_PI);
    cairo_fill(cr);
    /* a white halo keeps the number readable over the path */
    cairo_move_to(cr, lx, ly);
    cairo_text_path(cr, s);
    cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
    cairo_set_line_width(cr, 2.5);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_stroke_preserve(cr);
    plot_rgb(cr, C_LABEL);
    cairo_fill(cr);
  }
}

/* Tick labels: the grid has a line at every k*step; a label goes on every
 * m-th, m the least for which m*step is itself a round step (1, 2, 5 x
 * 10^n) and labels `ext` px long along the axis keep 6 px apart at px_step
 * px a step. */
static long label_every(double step, double px_step, double ext)
{
  double lab = step;
  for (int i = 0; i < 60; i++) {
    long m = lround(lab / step);
    if (m >= 1 && fabs(m * step - lab) <= 1e-9 * lab && m * px_step >= ext + 6)
      return m;
    double e = pow(10, floor(log10(lab) + 1e-9)), f = lab / e;
    lab = (f < 1.5 ? 2 : f < 3.5 ? 5 : 10) * e;
  }
  return LONG_MAX;
}

/* The label of tick k: k*step with the step's decimals. */
static void tick_text(char *buf, size_t n, long k, double step, int dec, const char *unit)
{
  char num[40];
  fmt_num(num, sizeof num, (double)k * step, dec);
  snprintf(buf, n, "%s%s", num, unit);
}

static void draw_scale(cairo_t *cr, const struct panel *P, double step)
{
  /* grid at multiples of the step, axes through the program start */
  double xa, ya;
  cairo_save(cr);
  cairo_rectangle(cr, P->rx, P->ry, P->rw, P->rh);
  cairo_clip(cr);
  double umin = P->u0 + (P->rx - (P->ix + P->iw / 2)) / P->s, umax = umin + P->rw / P->s;
  double vmax = P->v0 + ((P->iy + P->ih / 2) - P->ry) / P->s, vmin = vmax - P->rh / P->s;
  if ((umax - umin) / step < 200 && (vmax - vmin) / step < 200) {
    for (long k = (long)ceil(umin / step); k * step <= umax; k++) {
      pmap(P, k * step, 0, &xa, &ya);
      cairo_move_to(cr, floor(xa) + 0.5, P->ry);
      cairo_line_to(cr, floor(xa) + 0.5, P->ry + P->rh);
    }
    for (long k = (long)ceil(vmin / step); k * step <= vmax; k++) {
      pmap(P, 0, k * step, &xa, &ya);
      cairo_move_to(cr, P->rx, floor(ya) + 0.5);
      cairo_line_to(cr, P->rx + P->rw, floor(ya) + 0.5);
    }
    plot_rgb(cr, C_GRID);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);
  }
  pmap(P, 0, 0, &xa, &ya);
  cairo_move_to(cr, floor(xa) + 0.5, P->ry);
  cairo_line_to(cr, floor(xa) + 0.5, P->ry + P->rh);
  cairo_move_to(cr, P->rx, floor(ya) + 0.5);
  cairo_line_to(cr, P->rx + P->rw, floor(ya) + 0.5);
  plot_rgb(cr, C_AXIS);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
  cairo_restore(cr);
}

/* Ticks on the region's left and bottom edges at the grid's lines, with
 * the coordinates in mm: the same labelled step on both axes, labels that
 * do not fit the frame left out. */
static void draw_ticks(cairo_t *cr, const struct panel *P, double step, int dec)
{
  double umin = P->u0 + (P->rx - (P->ix + P->iw / 2)) / P->s, umax = umin + P->rw / P->s;
  double vmax = P->v0 + ((P->iy + P->ih / 2) - P->ry) / P->s, vmin = vmax - P->rh / P->s;
  long u0 = (long)ceil(umin / step), u1 = (long)floor(umax / step);
  long v0 = (long)ceil(vmin / step), v1 = (long)floor(vmax / step);
  if (u1 - u0 > 400 || v1 - v0 > 400)
    return;
  char t[48];
  const double fu = 10;
  double wu = 0, wv = 0, fv = 10;
  for (long k = u0; k <= u1; k++) {
    tick_text(t, sizeof t, k, step, dec, "");
    wu = fmax(wu, plot_text_w(cr, t, fu, 0));
  }
  for (long k = v0; k <= v1; k++) {
    tick_text(t, sizeof t, k, step, dec, "");
    wv = fmax(wv, plot_text_w(cr, t, fv, 0));
  }
  if (wv > LB - 12) {
    fv = fmax(6.5, fv * (LB - 12) / wv);   /* long numbers: a smaller font */
    wv = 0;
    for (long k = v0; k <= v1; k++) {
      tick_text(t, sizeof t, k, step, dec, "");
      wv = fmax(wv, plot_text_w(cr, t, fv, 0));
    }
  }
  long mu = label_every(step, step * P->s, wu), mv = label_every(step, step * P->s, fv + 2);
  long m = mu > mv ? mu : mv;
  double xa, ya, by = P->ry + P->rh, lx = P->rx;
  /* the region's edges, and a tick at every grid line */
  plot_rgb(cr, C_FRAME);
  cairo_set_line_width(cr, 1);
  cairo_move_to(cr, lx + 0.5, P->ry);
  cairo_line_to(cr, lx + 0.5, by + 0.5);
  cairo_line_to(cr, P->rx + P->rw, by + 0.5);
  for (long k = u0; k <= u1; k++) {
    pmap(P, k * step, 0, &xa, &ya);
    cairo_move_to(cr, floor(xa) + 0.5, by);
    cairo_line_to(cr, floor(xa) + 0.5, by + (k % m ? 3 : 6));
  }
  for (long k = v0; k <= v1; k++) {
    pmap(P, 0, k * step, &xa, &ya);
    cairo_move_to(cr, lx, floor(ya) + 0.5);
    cairo_line_to(cr, lx - (k % m ? 3 : 6), floor(ya) + 0.5);
  }
  cairo_stroke(cr);
  plot_rgb(cr, C_TEXT);
  for (long k = u0; k <= u1; k++) {
    if (k % m)
      continue;
    tick_text(t, sizeof t, k, step, dec, "");
    double w = plot_text_w(cr, t, fu, 0);
    pmap(P, k * step, 0, &xa, &ya);
    xa = floor(xa) + 0.5;
    /* clear of the axis arrows in the corner and of the frame */
    if (xa - w / 2 < P->x + 30 || xa + w / 2 > P->x + P->w - 4)
      continue;
    plot_text_at(cr, xa, by + 16, t, fu, 0, 0.5);
  }
  for (long k = v0; k <= v1; k++) {
    if (k % m)
      continue;
    tick_text(t, sizeof t, k, step, dec, "");
    pmap(P, 0, k * step, &xa, &ya);
    double base = floor(ya) + 0.5 + 0.35 * fv;
    if (base - 0.75 * fv < P->y + 3 || base + 0.25 * fv > by + 4)
      continue;
    plot_text_at(cr, lx - 8, base, t, fv, 0, 1);
  }
}

static void draw_panel_furniture(cairo_t *cr, const struct panel *P, double step, int dec)
{
  draw_ticks(cr, P, step, dec);
  /* the scale bar, bottom right, under the tick labels */
  double len = step * P->s, bx1 = P->x + P->w - 16, bx0 = bx1 - len, by = P->y + P->h - 9;
  plot_rgb(cr, C_TEXT);
  cairo_set_line_width(cr, 2);
  cairo_move_to(cr, bx0, by);
  cairo_line_to(cr, bx1, by);
  cairo_stroke(cr);
  cairo_set_line_width(cr, 1.2);
  cairo_move_to(cr, bx0, by - 5);
  cairo_line_to(cr, bx0, by + 3);
  cairo_move_to(cr, bx1, by - 5);
  cairo_line_to(cr, bx1, by + 3);
  cairo_stroke(cr);
  char num[32], lab[48];
  fmt_num(num, sizeof num, step, dec);
  snprintf(lab, sizeof lab, "%s mm", num);
  plot_text_at(cr, bx0 - 6, by + 3, lab, 10, 0, 1);
  /* axis arrows, in the corner between the tick bands */
  static const char *const names = "XYZA";
  double ox = P->x + 12, oy = P->y + P->h - 10;
  cairo_set_line_width(cr, 1.3);
  cairo_move_to(cr, ox, oy);
  cairo_line_to(cr, ox + 22, oy);
  cairo_move_to(cr, ox, oy);
  cairo_line_to(cr, ox, oy - 18);
  cairo_stroke(cr);
  cairo_move_to(cr, ox + 26, oy);
  cairo_line_to(cr, ox + 20, oy - 3);
  cairo_line_to(cr, ox + 20, oy + 3);
  cairo_close_path(cr);
  cairo_move_to(cr, ox, oy - 22);
  cairo_line_to(cr, ox - 3, oy - 16);
  cairo_line_to(cr, ox + 3, oy - 16);
  cairo_close_path(cr);
  cairo_fill(cr);
  char a[2] = {names[P->u], 0}, b[2] = {names[P->v], 0};
  plot_text_at(cr, ox + 29, oy + 4, a, 11, 1, 0);
  plot_text_at(cr, ox + 5, oy - 14, b, 11, 1, 0);
  /* the frame and the title */
  plot_rgb(cr, C_FRAME);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, P->x + 0.5, P->y + 0.5, P->w - 1, P->h - 1);
  cairo_stroke(cr);
  plot_rgb(cr, C_TEXT);
  plot_text_at(cr, P->x, P->y - 8, P->name, 15, 1, 0);
  plot_text_at(cr, P->x + plot_text_w(cr, P->name, 15, 1) + 8, P->y - 8, P->plane, 12, 0, 0);
}

/* end: 0 the program start, 1 the end, 2 where a failed run stopped */
static void marker(cairo_t *cr, const struct panel *P, const double pt[4], int end)
{
  double x, y;
  pmap(P, pt[P->u], pt[P->v], &x, &y);
  if (end == 2) {
    plot_stop_sign(cr, x, y);
  } else if (end) {
    cairo_new_path(cr);
    cairo_rectangle(cr, x - 4, y - 4, 8, 8);
    plot_rgb(cr, C_END);
    cairo_fill(cr);
  } else {
    /* a ring: an end at the start still shows inside it */
    cairo_new_path(cr);
    cairo_arc(cr, x, y, 6, 0, 2 * M_PI);
    plot_rgb(cr, C_START);
    cairo_set_line_width(cr, 2.4);
    cairo_stroke(cr);
  }
}

static void draw_xyz(cairo_t *cr, const struct plot *pl, const struct bbox *bb, const uint64_t *gh,
                     const struct layout *ly)
{
  /* the 2С42's planes: G17 XY, G18 YZ, G19 XZ; the neutral view names none */
  static const struct { int u, v; const char *name, *plane, *neutral; } def[3] = {
    {0, 1, "XY", "plane G17, mm", "plane, mm"},
    {0, 2, "XZ", "plane G19, mm", "plane, mm"},
    {1, 2, "YZ", "plane G18, mm", "plane, mm"},
  };
  static const double fx[3] = {40, 555, 1070};
  for (int k = 0; k < 3; k++) {
    struct panel P;
    memset(&P, 0, sizeof P);
    P.u = def[k].u;
    P.v = def[k].v;
    P.name = def[k].name;
    P.plane = ly->grinder ? def[k].plane : def[k].neutral;
    P.x = fx[k];
    P.y = 96;
    P.w = 490;
    P.h = ly->ph;
    P.rx = P.x + LB;
    P.ry = P.y;
    P.rw = P.w - LB;
    P.rh = P.h - BB;
    P.ix = P.rx + 12;
    P.iy = P.ry + 22;
    P.iw = P.rw - 12 - 18;
    P.ih = P.rh - 22 - 12;
    double du = bb->hi[P.u] - bb->lo[P.u], dv = bb->hi[P.v] - bb->lo[P.v];
    const double minext = 0.02;   /* mm: never zoom in further than this */
    double su = du > minext ? du : minext, sv = dv > minext ? dv : minext;
    P.s = fmin(P.iw / su, P.ih / sv);
    if (du < minext && dv < minext)
      P.s = fmin(P.iw, P.ih) / 1.0;   /* nothing moves here: 1 mm across */
    P.u0 = (bb->lo[P.u] + bb->hi[P.u]) / 2;
    P.v0 = (bb->lo[P.v] + bb->hi[P.v]) / 2;
    P.ocw = (int)(P.w / 4) + 1;
    P.och = (int)(P.h / 4) + 1;
    P.occ = calloc((size_t)P.ocw * (size_t)P.och, 1);
    int dec;
    double step = nice_step(P.iw / 4 / P.s, &dec);

    cairo_save(cr);
    cairo_rectangle(cr, P.rx, P.ry, P.rw, P.rh);
    cairo_clip(cr);
    draw_scale(cr, &P, step);
    draw_panel_path(cr, &P, pl, gh, ly);
    draw_panel_osc(cr, &P, pl);
    double z[4], e[4], con[4];
    start_of(pl, z);
    final_pos(pl, e, con);
    int stopped = pl->why[0] != 0;
    if (pl->n && !stopped)
      marker(cr, &P, e, 1);
    if (stopped)
      marker(cr, &P, e, 2);
    marker(cr, &P, z, 0);   /* over the stop sign: a run that stopped before it moved */
    if (P.occ)
      draw_labels(cr, &P, pl);
    if (du < minext && dv < minext) {
      plot_rgb(cr, C_LABEL);
      plot_text_at(cr, P.rx + P.rw / 2, P.ry + P.rh / 2 + 28, "no move in this plane", 13, 0, 0.5);
    }
    cairo_restore(cr);
    draw_panel_furniture(cr, &P, step, dec);
    free(P.occ);
  }
}

/* A against simulated time; raster: into an image (the pen's band). */
static void draw_a(cairo_t *cr, const struct plot *pl, int raster)
{
  const double X = 90, Y = 724, W = 1470, H = 200, U3 = pl->unit[3], sa = pl->start_pos[3] / U3;
  double t_end = pl->ended && pl->t_end > pl->t ? pl->t_end : pl->t;
  double tend = t_end > 0 ? t_end : 1;
  double fin[4], con[4];
  final_pos(pl, fin, con);
  double amin = fmin(sa, fmin(fin[3], con[3])), amax = fmax(sa, fmax(fin[3], con[3])), a = sa;
  for (size_t i = 0; i < pl->n; i++) {
    const struct seg *g = &pl->v[i];
    double v[3] = {g->start[3] / U3, (g->start[3] + g->d[3]) / U3,
                   (g->start[3] + g->d[3] + g->jog[3]) / U3};
    for (int k = 0; k < 3; k++) {
      if (v[k] < amin) amin = v[k];
      if (v[k] > amax) amax = v[k];
    }
  }
  /* A oscillating: as drawn, the programmed A plus its displacement */
  for (size_t i = 0, j = 0; i < pl->nosc && pl->n; i++)
    if (pl->osc[i].axis == 3) {
      double pt[4];
      point_at(pl, pl->osc[i].t, &j, pt);
      double v = pt[3] + pl->osc[i].off / U3;
      if (v < amin) amin = v;
      if (v > amax) amax = v;
    }
  int moves = amax - amin > 0;
  if (amax - amin < 1) {
    double c = (amax + amin) / 2;
    amin = c - 0.5;
    amax = c + 0.5;
  }
  double pad = (amax - amin) * 0.06;
  amin -= pad;
  amax += pad;
  double sx = (W - 20) / tend, sy = (H - 16) / (amax - amin);
#define TX(t) (X + 10 + (t) * sx)
#define AY(v) (Y + H - 8 - ((v) - amin) * sy)
  /* grid and ticks: a line at every step, a label where there is room
   * (label_every), as on the plane panels */
  int dt_dec, da_dec;
  double dt = nice_step(tend / 8, &dt_dec), da = nice_step((amax - amin) / 4, &da_dec);
  char lab[48];
  long t1 = (long)floor(tend * 1.0001 / dt), a0 = (long)ceil(amin / da), a1 = (long)floor(amax / da);
  double wt = 0;
  for (long k = 0; k <= t1; k++) {
    tick_text(lab, sizeof lab, k, dt, dt_dec, "");
    wt = fmax(wt, plot_text_w(cr, lab, 11, 0));
  }
  long mt = label_every(dt, dt * sx, wt), ma = label_every(da, da * sy, 13);
  cairo_set_line_width(cr, 1);
  for (long k = 0; k <= t1; k++) {
    double x = floor(TX(k * dt)) + 0.5;
    plot_rgb(cr, C_GRID);
    cairo_move_to(cr, x, Y);
    cairo_line_to(cr, x, Y + H);
    cairo_stroke(cr);
    if (k % mt)
      continue;
    plot_rgb(cr, C_TEXT);
    tick_text(lab, sizeof lab, k, dt, dt_dec, "");
    plot_text_at(cr, x, Y + H + 15, lab, 11, 0, 0.5);
  }
  for (long k = a0; k <= a1; k++) {
    double y = floor(AY(k * da)) + 0.5;
    plot_rgb(cr, k == 0 ? C_AXIS : C_GRID);
    cairo_move_to(cr, X, y);
    cairo_line_to(cr, X + W, y);
    cairo_stroke(cr);
    if (k % ma)
      continue;
    plot_rgb(cr, C_TEXT);
    tick_text(lab, sizeof lab, k, da, da_dec, "°");
    plot_text_at(cr, X - 6, y + 4, lab, 11, 0, 1);
  }
  plot_rgb(cr, C_TEXT);
  plot_text_at(cr, X + W, Y + H + 32, "time, s", 12, 0, 1);
  plot_text_at(cr, 40, Y - 8, "A", 15, 1, 0);
  plot_text_at(cr, 40 + plot_text_w(cr, "A", 15, 1) + 8, Y - 8, "workpiece spindle, degrees, against simulated time", 12, 0, 0);

  cairo_save(cr);
  cairo_rectangle(cr, X, Y, W, H);
  cairo_clip(cr);
  /* corrections of A between blocks: dotted; jogs: dashed; the trace: solid */
  plot_rgb(cr, C_CORR);
  cairo_set_line_width(cr, 1.6);
  double dots[] = {1.0, 3.0};
  cairo_set_dash(cr, dots, 2, 0);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  struct pen pn;
  pen_init(&pn, cr, 1, 0);
  a = sa;
  for (size_t i = 0; i < pl->n; i++) {
    const struct seg *g = &pl->v[i];
    double s0 = g->start[3] / U3;
    if (s0 != a) {
      pen_break(&pn);
      pen_line(&pn, TX(g->t0), AY(a), TX(g->t0), AY(s0));
    }
    a = (g->start[3] + g->d[3] + g->jog[3]) / U3;
  }
  if (con[3] != a) {   /* a correction after the last block */
    pen_break(&pn);
    pen_line(&pn, TX(t_end), AY(a), TX(t_end), AY(con[3]));
  }
  pen_done(&pn);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  plot_rgb(cr, C_JOG);
  cairo_set_line_width(cr, 2);
  double dash[] = {6.0, 3.5};
  cairo_set_dash(cr, dash, 2, 0);
  pen_init(&pn, cr, 1, 0);
  for (size_t i = 0; i < pl->n; i++) {
    const struct seg *g = &pl->v[i];
    if (g->jog[3]) {
      double m = (g->start[3] + g->d[3]) / U3;
      pen_break(&pn);
      pen_line(&pn, TX(g->t1), AY(m), TX(g->t1), AY(m + g->jog[3] / U3));
    }
  }
  pen_done(&pn);
  cairo_set_dash(cr, NULL, 0, 0);
  plot_rgb(cr, C_PATH);
  cairo_set_line_width(cr, 1.4);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  /* a function of time: many blocks a pixel column, cut to what it shows */
  pen_init(&pn, cr, 0, 1 / PEN_Q);
  if (raster)
    pen_band(&pn, 1.4);
  a = sa;
  pen_moveto(&pn, TX(0), AY(sa));
  for (size_t i = 0; i < pl->n; i++) {
    const struct seg *g = &pl->v[i];
    double s0 = g->start[3] / U3, e0 = (g->start[3] + g->d[3]) / U3;
    if (s0 != a)
      pen_moveto(&pn, TX(g->t0), AY(s0));
    else
      pen_lineto(&pn, TX(g->t0), AY(s0));
    pen_lineto(&pn, TX(g->t1), AY(e0));
    a = e0 + g->jog[3] / U3;
    if (g->jog[3])
      pen_moveto(&pn, TX(g->t1), AY(a));
  }
  pen_lineto(&pn, TX(tend), AY(a));
  if (con[3] != a) {
    pen_moveto(&pn, TX(t_end), AY(con[3]));
    pen_lineto(&pn, TX(tend), AY(con[3]));
  }
  pen_done(&pn);
  /* A oscillating: the programmed A plus its displacement */
  plot_rgb(cr, C_OSC);
  cairo_set_line_width(cr, 1.0);
  size_t j = 0;
  pen_init(&pn, cr, 0, 1 / PEN_Q);
  if (raster)
    pen_band(&pn, 1.0);
  for (size_t i = 0; i < pl->nosc && pl->n; i++) {
    if (pl->osc[i].axis != 3)
      continue;
    double pt[4];
    point_at(pl, pl->osc[i].t, &j, pt);
    double y = AY(pt[3] + pl->osc[i].off / U3), x = TX(pl->osc[i].t);
    if (pl->osc[i].start)
      pen_moveto(&pn, x, y);
    else
      pen_lineto(&pn, x, y);
  }
  pen_done(&pn);
  if (!moves) {
    plot_rgb(cr, C_LABEL);
    plot_text_at(cr, X + W / 2, Y + H / 2 - 14, "A does not move", 13, 0, 0.5);
  }
  if (pl->why[0])
    plot_stop_sign(cr, TX(t_end), AY(fin[3]));
  cairo_restore(cr);
  plot_rgb(cr, C_FRAME);
  cairo_rectangle(cr, X + 0.5, Y + 0.5, W - 1, H - 1);
  cairo_stroke(cr);
#undef TX
#undef AY
}

struct legend_item { unsigned c; int style; const char *text; };

static void legend(cairo_t *cr, double x, double y, int stopped, const struct layout *ly)
{
  static const struct legend_item grinder[] = {
    {C_PATH, 0, "programmed move (arcs as arcs)"},
    {C_JOG, 1, "manual move: G20 jog, M19 teach-in"},
    {C_CORR, 2, "position change between blocks (correction)"},
    {C_OSC, 0, "oscillation (G07 M13)"},
    {C_START, 3, "program start"},
    {C_END, 4, "end"},
    {C_STOP, 6, "stopped here"},
    {C_LABEL, 5, "block number at the block's start"},
  };
  static const struct legend_item neutral[] = {
    {C_PATH, 0, "feed move (arcs as arcs)"},
    {C_TRAV, 7, "traverse"},
    {C_JOG, 1, "manual move"},
    {C_CORR, 2, "position change between blocks"},
    {C_START, 3, "start"},
    {C_END, 4, "end"},
    {C_STOP, 6, "stopped here"},
    {C_LABEL, 5, "block number at the block's start"},
  };
  const struct legend_item *items = ly->grinder ? grinder : neutral;
  const size_t k = ly->grinder ? sizeof grinder / sizeof grinder[0] : sizeof neutral / sizeof neutral[0];
  /* a run ends or stops: the one that happened; the gaps share what is left
   * of the line */
  double used = 0, gap;
  for (size_t i = 0; i < k; i++)
    if (items[i].style != (stopped ? 4 : 6))
      used += 34 + plot_text_w(cr, items[i].text, 12, 0);
  gap = (PW - 2 * x - used) / (double)(k - 2);
  gap = gap > 26 ? 26 : gap < 8 ? 8 : gap;
  for (size_t i = 0; i < k; i++) {
    if (items[i].style == (stopped ? 4 : 6))
      continue;
    plot_rgb(cr, items[i].c);
    cairo_new_path(cr);
    switch (items[i].style) {
    case 0: case 1: case 2: case 7: {
      double dash[] = {6.0, 3.5}, dots[] = {1.0, 3.0}, trav[] = {6.0, 4.0};
      cairo_set_line_width(cr, items[i].style == 0 ? 1.4 : items[i].style == 1 ? 2 : items[i].style == 7 ? 1.1 : 1.6);
      if (items[i].style == 1) cairo_set_dash(cr, dash, 2, 0);
      if (items[i].style == 7) cairo_set_dash(cr, trav, 2, 0);
      if (items[i].style == 2) {
        cairo_set_dash(cr, dots, 2, 0);
        cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
      }
      cairo_move_to(cr, x, y - 4);
      cairo_line_to(cr, x + 28, y - 4);
      cairo_stroke(cr);
      cairo_set_dash(cr, NULL, 0, 0);
      cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
      break;
    }
    case 3:
      cairo_arc(cr, x + 14, y - 4, 6, 0, 2 * M_PI);
      cairo_set_line_width(cr, 2.4);
      cairo_stroke(cr);
      break;
    case 4:
      cairo_rectangle(cr, x + 10, y - 8, 8, 8);
      cairo_fill(cr);
      break;
    case 6:
      plot_stop_sign(cr, x + 14, y - 4);
      break;
    default:
      cairo_arc(cr, x + 4, y - 4, 1.6, 0, 2 * M_PI);
      cairo_fill(cr);
      plot_text_at(cr, x + 8, y - 1, "12", 9.5, 0, 0);
      break;
    }
    plot_rgb(cr, C_TEXT);
    plot_text_at(cr, x + 34, y, items[i].text, 12, 0, 0);
    x += 34 + plot_text_w(cr, items[i].text, 12, 0) + gap;
  }
}

/* The summary line: the blocks, the time and where the machine ended. */
static void summary(const struct plot *pl, const struct layout *ly, char *line, size_t size)
{
  char n[4][40], tt[32];
  for (int a = 0; a < 4; a++) {
    char v[32];
    int64_t e = pl->ended ? pl->end_pos[a] : pl->cur[a];
    fmt_num(v, sizeof v, e / pl->unit[a], 3);
    snprintf(n[a], sizeof n[a], "%s%s", e > 0 ? "+" : "", v);
  }
  double tsim = pl->ended ? pl->t_end : pl->t;
  fmt_num(tt, sizeof tt, tsim, tsim < 1 ? 3 : 1);   /* a short run is not "0 s" */
  unsigned long long nb = pl->ended ? pl->blocks : pl->rows;
  const char *at = pl->why[0] ? "position at the stop" : "end position";
  if (ly->grinder || pl->axis_name[3])
    snprintf(line, size, "%llu block%s, %s s simulated; %s X %s  Y %s  Z %s mm  A %s°", nb, nb == 1 ? "" : "s",
             tt, at, n[0], n[1], n[2], n[3]);
  else
    snprintf(line, size, "%llu block%s, %s s simulated; %s X %s  Y %s  Z %s mm", nb, nb == 1 ? "" : "s", tt, at,
             n[0], n[1], n[2]);
}

/* The line under the title. */
static void subtitle(const struct plot *pl, const struct layout *ly, char *sub, size_t size)
{
  int kind = pl->kind[0] && strcmp(pl->kind, "none");
  if (ly->grinder)
    snprintf(sub, size, "tool path of a headless run of s42 (2С42-65)");
  else
    snprintf(sub, size, "tool path of a headless run of s42 (%s%s%s): the planes XY, XZ and YZ",
             pl->name[0] ? pl->name : "a machine", kind ? ", " : "", kind ? pl->kind : "");
}

static void draw(cairo_t *cr, const struct plot *pl, int raster, const struct layout *ly)
{
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  /* the extent of the path on X, Y, Z (mm), the start in it */
  struct bbox bb;
  start_of(pl, bb.lo);
  start_of(pl, bb.hi);
  uint64_t *gh = seg_hashes(pl);
  struct seen *tab = seen_new(gh);
  for (size_t i = 0; i < pl->n; i++) {
    const struct seg *g = &pl->v[i];
    double p[4];
    if (tab) {   /* a segment seen before adds nothing */
      struct seen *e = &tab[gh[2 * i] & (SEEN_SLOTS - 1)];
      if (e->chunk == 0 && e->h1 == gh[2 * i] && e->h2 == gh[2 * i + 1])
        continue;
      *e = (struct seen){gh[2 * i], gh[2 * i + 1], 0, 0};
    }
    for (int a = 0; a < 4; a++)
      p[a] = g->start[a] / pl->unit[a];
    bb_add(&bb, p);
    bb_curve(pl, &bb, g);
    if (seg_has_jog(g))
      bb_hand(pl, &bb, i);
  }
  double fin[4], con[4];
  final_pos(pl, fin, con);
  bb_add(&bb, fin);
  bb_add(&bb, con);
  /* the oscillation's strokes, point by point as they are drawn */
  for (size_t i = 0, j = 0; i < pl->nosc && pl->n; i++)
    for (int k = 1, steps = osc_steps(pl, i); k <= steps; k++) {
      double pt[4];
      osc_point(pl, i, k, &j, pt);
      bb_add(&bb, pt);
    }
  free(tab);
  draw_xyz(cr, pl, &bb, gh, ly);
  free(gh);
  if (ly->grinder)
    draw_a(cr, pl, raster);
  legend(cr, 40, 984, pl->why[0] != 0, ly);

  /* title and summary */
  const char *base = plot_base(pl->program);
  char title[300], line[400], sub[120];
  snprintf(title, sizeof title, "%s", base);
  subtitle(pl, ly, sub, sizeof sub);
  plot_rgb(cr, C_TEXT);
  plot_text_at(cr, 40, 34, title, 22, 1, 0);
  plot_text_at(cr, 40 + plot_text_w(cr, title, 22, 1) + 14, 34, sub, 13, 0, 0);
  summary(pl, ly, line, sizeof line);
  plot_rgb(cr, C_LABEL);
  plot_text_at(cr, 1560, 34, line, 13, 0, 1);
  if (pl->why[0]) {
    /* how the run failed, under the title, with the marker of the panels */
    plot_stop_sign(cr, 48, 57);
    double size = 15, room = 1520 - 22 - (pl->oom ? 300 : 0);
    while (size > 8 && plot_text_w(cr, pl->why, size, 1) > room)
      size -= 0.5;
    plot_rgb(cr, C_STOPTEXT);
    plot_text_at(cr, 62, 62, pl->why, size, 1, 0);
  }
  if (pl->oom) {
    plot_rgb(cr, C_END);
    plot_text_at(cr, 1560, 62, "out of memory: the path is cut short", 13, 1, 1);
  }
}

/* ---- the views ---- */

static const struct layout grinder = {1, 580}, neutral = {0, 828};

static void draw_grinder(cairo_t *cr, struct plot *pl, int raster)
{
  if (!pl->retimed) {
    osc_retime(pl);
    pl->retimed = 1;
  }
  draw(cr, pl, raster, &grinder);
}

static void draw_neutral(cairo_t *cr, struct plot *pl, int raster)
{
  if (!pl->retimed) {
    osc_retime(pl);
    pl->retimed = 1;
  }
  draw(cr, pl, raster, &neutral);
}

/* The SVG's <title> and <desc>: the captions (cairo writes the picture's
 * text as glyphs). */
static char *svg_head(struct plot *pl, const struct layout *ly)
{
  char *buf = NULL, line[400], sub[160];
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  if (!f)
    return NULL;
  subtitle(pl, ly, sub, sizeof sub);
  summary(pl, ly, line, sizeof line);
  fputs("\n<title>", f);
  plot_xml_text(f, plot_base(pl->program));
  fputs("</title>\n<desc>", f);
  plot_xml_text(f, sub);
  fputs("\n", f);
  plot_xml_text(f, line);
  if (pl->why[0]) {
    fputs("\n", f);
    plot_xml_text(f, pl->why);
  }
  fputs("</desc>", f);
  if (fclose(f) != 0) {
    free(buf);
    return NULL;
  }
  return buf;
}

static char *svg_head_neutral(struct plot *pl)
{
  return svg_head(pl, &neutral);
}

const struct plot_view plot_view_grinder = {"grinder", PW, PH, draw_grinder, NULL, NULL};
const struct plot_view plot_view_planes = {"planes", PW, PH, draw_neutral, svg_head_neutral, NULL};
