/* The lathe's view of the plot (src/host/plot_view.h): the tool tip's path
 * in the XZ plane and the turned part's silhouette, drawn with cairo from
 * the engine's pieces (a lathe's X counts its diameter: the pieces' mm per
 * count make it the radius).
 *
 * The picture is PW x PH (pixels for PNG, points for SVG and PDF):
 *   - a title line (the program's name), a line with the run's status, the
 *     stock and the path's extents, and a line of warnings in red (cuts
 *     into the chuck side, never touches the stock, material cut off);
 *   - the drawing, frame FX..FX+FW x FY..FY+FH: Z along (to the right; the
 *     part's face at Z 0, the chuck on the left at negative Z), the radius
 *     up, one scale on both axes; the axis of rotation a dash-dot centre
 *     line at radius 0, the tick labels along it in Z (mm) and up it as
 *     diameters (Ø, mm: a drawing's dimensions); the part mirrored below
 *     the axis, pale;
 *   - a legend.
 * The stock is a bar Ø d from Z 0 to Z -len held by the chuck beyond (its
 * jaws drawn hatched).  The silhouette: at each z the remaining radius
 * R(z) = min(d/2, the least |radius| the tool tip reached at that z), the
 * tool tip taken as a point (a turning tool at radius r removes all above r
 * at that z: the part rotates).  Moves at z > 0, at z < -len or at radius
 * >= d/2 cut nothing; every move cuts, traverses too (a traverse through
 * the material is the program's fault, and shows); thread moves (between
 * CANON_SYNCH_START and CANON_SYNCH_STOP) do not lower R (the crests stay)
 * but hatch the band they cut.  Material beyond (at greater Z than) a z
 * where the tool reached the axis is cut off from what the chuck holds: a
 * facing pass's sliver or a parted-off part, drawn pale and named.
 *
 * R is kept on NCOL cells of the stock's length (0.01 mm, at most
 * LP_MAXCOL cells), exactly for lines: a line's least radius over a cell is
 * at one end of its piece in the cell, so each line sets the cells its
 * ends fall in directly and, for the cell boundaries it spans, goes into a
 * Li Chao tree of linear functions over the boundaries (O(log^2) a line:
 * a million full-length passes take a second or two); a cell's R is the
 * least of its own value and the tree's at its two boundaries.  Arcs are
 * cut as chords within LP_TOL mm of the arc, only where the circle is
 * within the bar's radius.  Drawing strokes at most INK_BUDGET px of path
 * per style (moves under a pixel merged, the rest clipped to the frame);
 * past it the caption says the path is drawn in part. */
#include "plot_view.h"
#include "picture.h"
#include "geom.h"
#include "cairo_dl.h"
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define PW 1000.0
#define PH 600.0
/* the drawing's frame, and in it the bands for the tick labels */
#define FX 20.0
#define FY 76.0
#define FW 960.0
#define FH 462.0
#define LBAND 58.0
#define BBAND 26.0
#define PAD 14.0

#define LP_CELL 0.01      /* mm: the silhouette's cell */
#define LP_MAXCOL 20000   /* cells at most (a longer stock gets longer cells) */
#define LP_TOL 0.002      /* mm: an arc's chords stay this close to it */
#define LP_MAXCHORD 512

enum { MV_JUMP, MV_LINE, MV_ARC, MV_TRAV };
enum { MF_THREAD = 1, MF_CHUCK = 2 };   /* a thread; cuts past the stock's end */

struct mv {
  double r, z;          /* the end, mm (the start: the record before) */
  double cr, cz;        /* arc: the centre */
  float sweep;          /* arc: radians, + turning from X towards Z (G02) */
  uint8_t kind, flags;
};

struct lc {             /* a Li Chao tree node: r = a * j + b over boundaries j */
  double a, b;
  int has;
};

struct lathe {
  struct plot_stock st;
  struct mv *v;
  size_t n, cap;
  int oom;
  size_t done;          /* the engine's pieces taken */
  double last_r, last_z;/* where the last move ends */
  double pitch;
  unsigned long long moves, threads;
  /* the silhouette */
  int ncol;
  double dz, half;
  double *direct;       /* ncol: the least radius set in the cell directly */
  struct lc *lc;        /* 4 (ncol + 1) */
  double *R;            /* ncol, computed from the above when dirty */
  int dirty;
  double *thr;          /* thread bands: ncol, the least thread radius, +inf none */
  int any_thread_band;
  /* chuck */
  int chuck;
  double chuck_z;
  unsigned long long chuck_hits;
  /* extents of the path */
  int ext;
  double rmin, rmax, zmin, zmax, amax;
  /* the result */
  char status[240];
  /* the caption as drawn, for the SVG's <title> and <desc> */
  char cap_title[300], cap_line[600], cap_warn[600];
};

/* ---- the silhouette ---- */

static void lc_add(struct lc *t, int node, int lo, int hi, double a, double b)
{
  for (;;) {
    struct lc *c = &t[node];
    if (!c->has) {
      c->a = a;
      c->b = b;
      c->has = 1;
      return;
    }
    int mid = lo + (hi - lo) / 2;
    if (a * mid + b < c->a * mid + c->b) {
      double ta = c->a, tb = c->b;
      c->a = a;
      c->b = b;
      a = ta;
      b = tb;
    }
    if (lo == hi)
      return;
    if (a * lo + b < c->a * lo + c->b) {
      node = 2 * node;
      hi = mid;
    } else if (a * hi + b < c->a * hi + c->b) {
      node = 2 * node + 1;
      lo = mid + 1;
    } else
      return;
  }
}

static void lc_insert(struct lc *t, int node, int lo, int hi, int l, int r, double a, double b)
{
  if (r < lo || hi < l)
    return;
  if (l <= lo && hi <= r) {
    lc_add(t, node, lo, hi, a, b);
    return;
  }
  int mid = lo + (hi - lo) / 2;
  lc_insert(t, 2 * node, lo, mid, l, r, a, b);
  lc_insert(t, 2 * node + 1, mid + 1, hi, l, r, a, b);
}

static double lc_query(const struct lc *t, int hi, int j)
{
  int node = 1, lo = 0;
  double v = INFINITY;
  for (;;) {
    const struct lc *c = &t[node];
    if (c->has) {
      double f = c->a * j + c->b;
      if (f < v)
        v = f;
    }
    if (lo == hi)
      return v;
    int mid = lo + (hi - lo) / 2;
    if (j <= mid) {
      node = 2 * node;
      hi = mid;
    } else {
      node = 2 * node + 1;
      lo = mid + 1;
    }
  }
}

static int cell_of(const struct lathe *pl, double z)
{
  double t = (z + pl->st.len) / pl->dz;
  int i = t <= 0 ? 0 : t >= pl->ncol ? pl->ncol - 1 : (int)floor(t);
  return i;
}

static void set_min(double *v, double x)
{
  if (x < *v)
    *v = x;
}

/* The tool tip went from (ra, za) to (rb, zb), ra, rb >= 0, za <= zb, the
 * radius linear in z, all within the stock's length. */
static void cut_piece(struct lathe *pl, double ra, double za, double rb, double zb)
{
  if (ra >= pl->half && rb >= pl->half)
    return;
  pl->dirty = 1;
  set_min(&pl->direct[cell_of(pl, za)], ra);
  set_min(&pl->direct[cell_of(pl, zb)], rb);
  double zs = -pl->st.len, tl = (za - zs) / pl->dz, th = (zb - zs) / pl->dz;
  double jl = ceil(tl - 1e-7), jh = floor(th + 1e-7);
  if (jl < 0) jl = 0;
  if (jh > pl->ncol) jh = pl->ncol;
  if (jl > jh)
    return;
  double a, b;
  if (zb - za < 1e-9) {
    a = 0;
    b = fmin(ra, rb);
  } else {
    double k = (rb - ra) / (zb - za);
    a = k * pl->dz;
    b = ra + k * (zs - za);
  }
  if (jh - jl < 16) {
    /* a short piece: its boundaries' values straight into their cells */
    for (int j = (int)jl; j <= (int)jh; j++) {
      double v = a * j + b;
      if (j > 0)
        set_min(&pl->direct[j - 1], v);
      if (j < pl->ncol)
        set_min(&pl->direct[j], v);
    }
    return;
  }
  lc_insert(pl->lc, 1, 0, pl->ncol, (int)jl, (int)jh, a, b);
}

/* A thread's band: the least radius of the thread at the cells it spans. */
static void thread_piece(struct lathe *pl, double ra, double za, double rb, double zb)
{
  if (ra >= pl->half && rb >= pl->half)
    return;
  int i0 = cell_of(pl, za), i1 = cell_of(pl, zb);
  for (int i = i0; i <= i1; i++) {
    double zc = -pl->st.len + (i + 0.5) * pl->dz;
    double r = zb - za < 1e-9 ? fmin(ra, rb) : ra + (rb - ra) * (fmin(fmax(zc, za), zb) - za) / (zb - za);
    set_min(&pl->thr[i], r);
    pl->any_thread_band = 1;
  }
}

/* |r| linear: split at r = 0, clip to the stock's length, cut. */
static void cut_line(struct lathe *pl, double r0, double z0, double r1, double z1, int thread)
{
  if (!pl->st.has)
    return;
  /* the chuck side: z < -len with |r| < d/2 (Liang-Barsky on the slab) */
  double h = pl->half, zs = -pl->st.len, eps = 1e-6;
  {
    double t0 = 0, t1 = 1, dr = r1 - r0, dzz = z1 - z0;
    double p[3] = {dzz, dr, -dr}, q[3] = {zs - eps - z0, h - eps - r0, h - eps + r0};
    int ok = 1;
    for (int k = 0; k < 3 && ok; k++) {
      if (p[k] == 0) {
        if (q[k] < 0)
          ok = 0;
      } else {
        double t = q[k] / p[k];
        if (p[k] > 0) {
          if (t < t1) t1 = t;
        } else if (t > t0)
          t0 = t;
      }
    }
    if (ok && t0 <= t1) {
      double za = z0 + dzz * t0, zb = z0 + dzz * t1, m = fmin(za, zb);
      if (!pl->chuck || m < pl->chuck_z)
        pl->chuck_z = m;
      pl->chuck = 1;
      pl->chuck_hits++;
    }
  }
  if ((r0 < 0 && r1 > 0) || (r0 > 0 && r1 < 0)) {
    double t = r0 / (r0 - r1), zc = z0 + (z1 - z0) * t;
    cut_line(pl, r0, z0, 0, zc, thread);
    cut_line(pl, 0, zc, r1, z1, thread);
    return;
  }
  r0 = fabs(r0);
  r1 = fabs(r1);
  if (z0 > z1) {
    double t = z0; z0 = z1; z1 = t;
    t = r0; r0 = r1; r1 = t;
  }
  if (z1 < zs || z0 > 0)
    return;
  double ra = r0, za = z0, rb = r1, zb = z1;
  if (z1 - z0 > 0) {
    if (za < zs) {
      ra = r0 + (r1 - r0) * (zs - z0) / (z1 - z0);
      za = zs;
    }
    if (zb > 0) {
      rb = r0 + (r1 - r0) * (0 - z0) / (z1 - z0);
      zb = 0;
    }
  }
  if (thread)
    thread_piece(pl, ra, za, rb, zb);
  else
    cut_piece(pl, ra, za, rb, zb);
}

/* The arc's point at share u: radius and angle interpolated (a spiral when
 * the two radii differ). */
static void arc_point(double r0, double z0, double cr, double cz, double sweep, double rho1, double u,
                      double *r, double *z)
{
  double rho0 = hypot(r0 - cr, z0 - cz), th0 = atan2(z0 - cz, r0 - cr);
  double th = th0 + sweep * u, rho = rho0 + (rho1 - rho0) * u;
  *r = cr + rho * cos(th);
  *z = cz + rho * sin(th);
}

static int arc_chords(double rho, double sweep)
{
  if (!(rho > LP_TOL))
    return 1;
  double dth = 2 * acos(1 - LP_TOL / rho);
  double n = ceil(fabs(sweep) / (dth > 1e-9 ? dth : 1e-9));
  return n < 1 ? 1 : n > LP_MAXCHORD ? LP_MAXCHORD : (int)n;
}

/* Cut along the arc from share u0 to u1 in chords (its points by turning
 * a unit vector, the radius interpolated: a spiral when the two differ). */
static void cut_arc_part(struct lathe *pl, double r0, double z0, const struct mv *m, double rho1, double u0,
                         double u1, int thread)
{
  double rho0 = hypot(r0 - m->cr, z0 - m->cz);
  int n = arc_chords(fmax(rho0, rho1), m->sweep * (u1 - u0));
  double th = atan2(z0 - m->cz, r0 - m->cr) + m->sweep * u0;
  double er = cos(th), ez = sin(th), d = m->sweep * (u1 - u0) / n, cd = cos(d), sd = sin(d);
  double rho = rho0 + (rho1 - rho0) * u0;
  double pr = m->cr + rho * er, pz = m->cz + rho * ez;
  for (int i = 1; i <= n; i++) {
    double r, z, u = u0 + (u1 - u0) * i / n;
    double t = er * cd - ez * sd;
    ez = er * sd + ez * cd;
    er = t;
    if (u >= 1) {
      r = m->r;
      z = m->z;
    } else {
      rho = rho0 + (rho1 - rho0) * u;
      r = m->cr + rho * er;
      z = m->cz + rho * ez;
    }
    cut_line(pl, pr, pz, r, z, thread);
    pr = r;
    pz = z;
  }
}

static void cut_arc(struct lathe *pl, double r0, double z0, const struct mv *m, int thread)
{
  if (!pl->st.has)
    return;
  double rho0 = hypot(r0 - m->cr, z0 - m->cz), rho1 = hypot(m->r - m->cr, m->z - m->cz);
  double rho = fmax(rho0, rho1), h = pl->half;
  /* nowhere near the stock or the chuck side: nothing to cut */
  if (!(rho > 0) || m->cz - rho > 0 || fabs(m->cr) - rho >= h)
    return;
  if (fabs(rho0 - rho1) > 1e-6 * rho + 0.01) {
    cut_arc_part(pl, r0, z0, m, rho1, 0, 1, thread);   /* a spiral: all of it */
    return;
  }
  /* only where the circle is within the bar's radius, |r| < d/2: where
   * cos(th) is in [c1, c2], th in [a, b] or [-b, -a] */
  double c1 = fmax(-1, (-h - m->cr) / rho), c2 = fmin(1, (h - m->cr) / rho);
  if (!(c1 < c2))
    return;
  double a = acos(c2), b = acos(c1), th0 = atan2(z0 - m->cz, r0 - m->cr), s = m->sweep;
  double lo = fmin(th0, th0 + s), hi = fmax(th0, th0 + s);
  double iv[2][2] = {{a, b}, {-b, -a}};
  for (int q = 0; q < 2; q++)
    for (int k = -3; k <= 3; k++) {
      double ia = iv[q][0] + 2 * M_PI * k, ib = iv[q][1] + 2 * M_PI * k;
      double x0 = fmax(ia, lo), x1 = fmin(ib, hi);
      if (!(x0 <= x1) || s == 0)
        continue;
      double u0 = (x0 - th0) / s, u1 = (x1 - th0) / s;
      if (u0 > u1) {
        double t = u0; u0 = u1; u1 = t;
      }
      cut_arc_part(pl, r0, z0, m, rho1, fmax(0, u0), fmin(1, u1), thread);
    }
}

static void compute_R(struct lathe *pl)
{
  if (!pl->st.has || !pl->dirty)
    return;
  double gprev = lc_query(pl->lc, pl->ncol, 0);
  for (int i = 0; i < pl->ncol; i++) {
    double g = lc_query(pl->lc, pl->ncol, i + 1);
    double r = fmin(pl->half, fmin(pl->direct[i], fmin(gprev, g)));
    pl->R[i] = r < 0 ? 0 : r;
    gprev = g;
  }
  pl->dirty = 0;
}

/* The first cell (from the chuck) where the tool reached the axis: what is
 * beyond it is cut off; ncol: none. */
static int cutoff_cell(const struct lathe *pl)
{
  for (int i = 0; i < pl->ncol; i++)
    if (pl->R[i] <= 1e-6)
      return i;
  return pl->ncol;
}

static double radius_at(struct lathe *pl, double z)
{
  if (!pl || !pl->st.has || !(z >= -pl->st.len && z <= 0))
    return -1;
  compute_R(pl);
  return pl->R[cell_of(pl, z)];
}

static int chuck_at(const struct lathe *pl, double *z)
{
  if (!pl || !pl->chuck)
    return 0;
  if (z)
    *z = pl->chuck_z;
  return 1;
}

static int page_xy(struct lathe *pl, double r, double z, double *x, double *y);

/* ---- the engine's pieces ---- */

static void lathe_free(struct lathe *pl)
{
  if (!pl)
    return;
  free(pl->v);
  free(pl->direct);
  free(pl->R);
  free(pl->thr);
  free(pl->lc);
  free(pl);
}

static struct lathe *lathe_new(const struct plot_stock *stock)
{
  struct lathe *pl = calloc(1, sizeof *pl);
  if (!pl)
    return NULL;
  if (stock && stock->has && stock->d > 0 && stock->len > 0 && isfinite(stock->d) && isfinite(stock->len)) {
    pl->st = *stock;
    pl->half = stock->d / 2;
    double nc = ceil(stock->len / LP_CELL - 1e-9);
    pl->ncol = nc < 1 ? 1 : nc > LP_MAXCOL ? LP_MAXCOL : (int)nc;
    pl->dz = stock->len / pl->ncol;
    pl->direct = malloc(sizeof(double) * (size_t)pl->ncol);
    pl->R = malloc(sizeof(double) * (size_t)pl->ncol);
    pl->thr = malloc(sizeof(double) * (size_t)pl->ncol);
    pl->lc = calloc(4 * ((size_t)pl->ncol + 1), sizeof *pl->lc);
    if (!pl->direct || !pl->R || !pl->thr || !pl->lc) {
      lathe_free(pl);
      return NULL;
    }
    for (int i = 0; i < pl->ncol; i++) {
      pl->direct[i] = INFINITY;
      pl->thr[i] = INFINITY;
    }
    pl->dirty = 1;
    compute_R(pl);
  }
  return pl;
}

static int push(struct lathe *pl, struct mv m)
{
  if (pl->oom)
    return -1;
  if (pl->n == pl->cap) {
    size_t nc = pl->cap ? pl->cap * 2 : 1024;
    struct mv *nv = realloc(pl->v, nc * sizeof *nv);
    if (!nv) {
      pl->oom = 1;
      return -1;
    }
    pl->v = nv;
    pl->cap = nc;
  }
  pl->v[pl->n++] = m;
  pl->last_r = m.r;
  pl->last_z = m.z;
  return 0;
}

static void extent(struct lathe *pl, double r, double z)
{
  if (!pl->ext) {
    pl->rmin = pl->rmax = r;
    pl->zmin = pl->zmax = z;
    pl->amax = fabs(r);
    pl->ext = 1;
    return;
  }
  if (r < pl->rmin) pl->rmin = r;
  if (r > pl->rmax) pl->rmax = r;
  if (z < pl->zmin) pl->zmin = z;
  if (z > pl->zmax) pl->zmax = z;
  if (fabs(r) > pl->amax) pl->amax = fabs(r);
}

/* A piece of the path: the tool tip from its start to its end (radius and
 * Z, mm), cutting the silhouette; a start away from where the last move
 * ended is a jump (a tool change, a new part zero).  Hand moves are not
 * the lathe's picture: where the next move starts shows them. */
static void take(struct lathe *pl, const struct plot *e, const struct seg *g)
{
  if (g->kind == K_MARK)
    return;
  double r0 = g->start[0] / e->unit[0], z0 = g->start[2] / e->unit[2];
  double r = ((double)g->start[0] + g->d[0]) / e->unit[0], z = ((double)g->start[2] + g->d[2]) / e->unit[2];
  if (!isfinite(r) || !isfinite(z) || !isfinite(r0) || !isfinite(z0))
    return;
  struct mv m = {r, z, 0, 0, 0, 0, 0};
  m.kind = g->kind == K_TRAV ? MV_TRAV : MV_LINE;
  int thread = (g->flags & F_THREAD) && g->kind != K_TRAV;
  if (thread)
    m.flags |= MF_THREAD;
  if (g->kind == K_ARC && g->plane == GEOM_XZ) {
    int p, q;
    geom_plane_axes(GEOM_XZ, &p, &q);
    double c[PLOT_AXES] = {(double)g->start[0], 0, (double)g->start[2], 0};
    c[p] += g->cp;
    c[q] += g->cq;
    double cr = c[0] / e->unit[0], cz = c[2] / e->unit[2];
    if (isfinite(cr) && isfinite(cz) && (cr != r0 || cz != z0)) {
      int ccw = (g->flags & F_CCW) != 0;
      struct geom_arc a = {r - r0, z - z0, cr - r0, cz - z0, ccw};
      double sw = geom_arc_sweep(&a);
      m.kind = MV_ARC;
      m.cr = cr;
      m.cz = cz;
      m.sweep = (float)(ccw ? sw : -sw);
    }
  }
  if (m.kind != MV_ARC && r == r0 && z == z0)
    return;   /* nowhere */
  pl->moves++;
  if (thread)
    pl->threads++;
  if (pl->n == 0 || pl->last_r != r0 || pl->last_z != z0) {
    struct mv j = {r0, z0, 0, 0, 0, MV_JUMP, 0};
    push(pl, j);
  }
  int kept = push(pl, m) == 0;
  extent(pl, r0, z0);
  extent(pl, r, z);
  unsigned long long hits = pl->chuck_hits;
  if (m.kind == MV_ARC) {
    double rho = hypot(r0 - m.cr, z0 - m.cz);
    double t0 = atan2(z0 - m.cz, r0 - m.cr);
    for (int k = 0; k < 4; k++) {
      double th = k * M_PI / 2;
      if (geom_in_sweep(t0, m.sweep, th))
        extent(pl, m.cr + rho * cos(th), m.cz + rho * sin(th));
    }
    cut_arc(pl, r0, z0, &m, thread);
  } else
    cut_line(pl, r0, z0, r, z, thread);
  if (kept && pl->chuck_hits != hits)
    pl->v[pl->n - 1].flags |= MF_CHUCK;
}

/* The lathe's state, with every piece the engine has taken. */
static struct lathe *lathe_of(struct plot *e)
{
  if (!e)
    return NULL;
  if (!e->vs && !(e->vs = lathe_new(&e->stock)))
    return NULL;
  struct lathe *pl = e->vs;
  for (; pl->done < e->n; pl->done++)
    take(pl, e, &e->v[pl->done]);
  pl->pitch = e->pitch;
  pl->oom |= e->oom;
  return pl;
}

double plot_lathe_radius_at(struct plot *e, double z)
{
  struct lathe *pl = lathe_of(e);
  return pl ? radius_at(pl, z) : -1;
}

int plot_lathe_chuck(struct plot *e, double *z)
{
  struct lathe *pl = lathe_of(e);
  return pl ? chuck_at(pl, z) : 0;
}

int plot_lathe_page_xy(struct plot *e, double r, double z, double *x, double *y)
{
  struct lathe *pl = lathe_of(e);
  return pl ? page_xy(pl, r, z, x, y) : -1;
}

/* ---- the fit ---- */

struct fit {
  double s;             /* px per mm */
  double zc, rc;        /* mm at the centre of the inner area */
  double ix, iy, iw, ih;/* the inner area */
  double zlo, zhi, rlo, rhi;  /* the box fitted */
  double jaw_l, jaw_h;  /* the chuck's jaws, mm */
};

static void make_fit(const struct lathe *pl, struct fit *F)
{
  double zlo, zhi, rlo, rhi;
  int have = 0;
  F->jaw_l = F->jaw_h = 0;
  if (pl->st.has) {
    F->jaw_l = fmin(fmax(pl->st.len * 0.12, pl->st.d * 0.3), pl->st.len * 0.5 + pl->st.d);
    F->jaw_h = fmax(pl->half * 0.35, 2);
    zlo = -pl->st.len - F->jaw_l;
    zhi = 0;
    rhi = pl->half + F->jaw_h;
    rlo = -rhi;
    have = 1;
  } else {
    zlo = zhi = rlo = rhi = 0;
  }
  if (pl->ext) {
    if (!have) {
      zlo = pl->zmin;
      zhi = pl->zmax;
      rlo = pl->rmin;
      rhi = pl->rmax;
    }
    zlo = fmin(zlo, pl->zmin);
    zhi = fmax(zhi, pl->zmax);
    rlo = fmin(rlo, fmin(0, pl->rmin));
    rhi = fmax(rhi, pl->rmax);
    have = 1;
  }
  if (!have) {
    zlo = -10;
    zhi = 0;
    rlo = -5;
    rhi = 5;
  }
  /* never zoom in further than 1 mm across */
  if (zhi - zlo < 1) {
    double c = (zhi + zlo) / 2;
    zlo = c - 0.5;
    zhi = c + 0.5;
  }
  if (rhi - rlo < 1) {
    double c = (rhi + rlo) / 2;
    rlo = c - 0.5;
    rhi = c + 0.5;
  }
  F->zlo = zlo;
  F->zhi = zhi;
  F->rlo = rlo;
  F->rhi = rhi;
  F->ix = FX + LBAND + PAD;
  F->iy = FY + PAD + 6;
  F->iw = FW - LBAND - 2 * PAD;
  F->ih = FH - BBAND - 2 * PAD - 6;
  F->s = fmin(F->iw / (zhi - zlo), F->ih / (rhi - rlo));
  F->zc = (zlo + zhi) / 2;
  F->rc = (rlo + rhi) / 2;
}

static double PX(const struct fit *F, double z)
{
  return F->ix + F->iw / 2 + (z - F->zc) * F->s;
}

static double PY(const struct fit *F, double r)
{
  return F->iy + F->ih / 2 - (r - F->rc) * F->s;
}

static int page_xy(struct lathe *pl, double r, double z, double *x, double *y)
{
  if (!pl)
    return -1;
  struct fit F;
  make_fit(pl, &F);
  *x = PX(&F, z);
  *y = PY(&F, r);
  return 0;
}

/* ---- drawing ---- */

#define C_FEED 0x1f4db3u
#define C_TRAV 0x4d6680u
#define C_THREAD 0xbf1a99u
#define C_CHUCKCUT 0xd91a1au
#define C_REMOVED 0xf5a04bu    /* orange: the material the path removed */
#define C_PART 0x8fa8c2u       /* steel blue-grey: the part */
#define C_PARTPALE 0xd3dde8u
#define C_CUTOFF 0xe2e2e2u
#define C_STOCK 0x333333u
#define C_JAW 0x7a7a7au
#define C_CENTRE 0x444444u
#define C_GRID 0xececec
#define C_WARN 0xb3000fu
#define C_END 0x222222u
#define CHUNK 128

/* A tick's label: v with dec decimals, or %g when it is huge. */
static void tick_label(char *buf, size_t n, double v, int dec, const char *prefix)
{
  char t[48];
  if (fabs(v) >= 1e7)
    snprintf(t, sizeof t, "%.3g", v);
  else
    plot_fmt_num(t, sizeof t, v, dec, 0);
  picture_fix_point(t);
  snprintf(buf, n, "%s%s", prefix, t);
}

/* The next round step above s (1, 2, 5 x 10^k). */
static double step_up(double s, int *dec)
{
  return plot_nice_step(s * 2.01, dec);
}

static void grid_and_ticks(cairo_t *cr, const struct fit *F)
{
  int zdec, rdec;
  double x0 = FX + LBAND, x1 = FX + FW, y0 = FY, y1 = FY + FH - BBAND;
  double zl = F->zc - (PX(F, F->zc) - x0) / F->s, zh = F->zc + (x1 - PX(F, F->zc)) / F->s;
  double rl = F->rc - (y1 - PY(F, F->rc)) / F->s, rh = F->rc + (PY(F, F->rc) - y0) / F->s;
  char lab[48];
  /* along: a round step whose labels do not touch */
  double zstep = plot_nice_step(70 / F->s, &zdec);
  for (int tries = 0; tries < 40; tries++) {
    double w = 0;
    tick_label(lab, sizeof lab, zl, zdec, "");
    w = fmax(w, plot_text_w(cr, lab, 11, 0));
    tick_label(lab, sizeof lab, zh, zdec, "");
    w = fmax(w, plot_text_w(cr, lab, 11, 0));
    if (zstep * F->s >= w + 14)
      break;
    zstep = step_up(zstep, &zdec);
  }
  /* up: diameters at a round step; the lines at half of it in radius */
  double dstep = plot_nice_step(2 * 40 / F->s, &rdec);
  for (int tries = 0; tries < 40 && dstep / 2 * F->s < 18; tries++)
    dstep = step_up(dstep, &rdec);
  double rstep = dstep / 2;
  cairo_set_line_width(cr, 1);
  if (zh - zl > 0 && (zh - zl) / zstep < 400) {
    for (double k = ceil(zl / zstep); k <= floor(zh / zstep); k++) {
      double x = floor(PX(F, k * zstep)) + 0.5;
      plot_rgb(cr, C_GRID);
      cairo_move_to(cr, x, y0);
      cairo_line_to(cr, x, y1);
      cairo_stroke(cr);
      tick_label(lab, sizeof lab, k * zstep, zdec, "");
      double w = plot_text_w(cr, lab, 11, 0);
      if (x - w / 2 < FX + LBAND - 20 || x + w / 2 > FX + FW + 16)
        continue;   /* off the frame */
      plot_rgb(cr, C_TEXT);
      plot_text_at(cr, x, y1 + 15, lab, 11, 0, 0.5);
    }
  }
  if (rh - rl > 0 && (rh - rl) / rstep < 400) {
    for (double k = ceil(rl / rstep); k <= floor(rh / rstep); k++) {
      double y = floor(PY(F, k * rstep)) + 0.5;
      plot_rgb(cr, C_GRID);
      cairo_move_to(cr, x0, y);
      cairo_line_to(cr, x1, y);
      cairo_stroke(cr);
      if (y < FY + 22 || y > y1 - 2)
        continue;   /* under the axis's name, or off the frame */
      if (k == 0)
        snprintf(lab, sizeof lab, "0");
      else
        tick_label(lab, sizeof lab, fabs(k) * dstep, rdec, "Ø");
      double size = 11;
      while (size > 7 && plot_text_w(cr, lab, size, 0) > LBAND - 8)
        size -= 0.5;
      plot_rgb(cr, C_TEXT);
      plot_text_at(cr, x0 - 5, y + 4, lab, size, 0, 1);
    }
  }
}

/* The silhouette's columns: one a pixel (or a cell when cells are wider),
 * the least R over the cells in it. */
struct colv {
  double z, r, thr;
  int off;              /* cut off from what the chuck holds */
};

static struct colv *columns(struct lathe *pl, const struct fit *F, int *nc)
{
  compute_R(pl);
  double px = pl->st.len * F->s;
  int n = (int)ceil(px);
  if (n > pl->ncol) n = pl->ncol;
  if (n < 1) n = 1;
  if (n > 8000) n = 8000;
  struct colv *c = malloc(sizeof *c * (size_t)n);
  if (!c)
    return NULL;
  int cut = cutoff_cell(pl);
  for (int k = 0; k < n; k++) {
    int i0 = (int)((long long)k * pl->ncol / n), i1 = (int)((long long)(k + 1) * pl->ncol / n) - 1;
    if (i1 < i0) i1 = i0;
    double r = INFINITY, t = INFINITY;
    for (int i = i0; i <= i1; i++) {
      set_min(&r, pl->R[i]);
      set_min(&t, pl->thr[i]);
    }
    c[k].z = -pl->st.len + pl->st.len * (k + 0.5) / n;
    c[k].r = r;
    c[k].thr = t;
    c[k].off = i0 > cut;
  }
  *nc = n;
  return c;
}

/* The outline of the part (sign +1 above the axis, -1 below) over the
 * columns [a, b), from the axis and back. */
static void part_path(cairo_t *cr, const struct fit *F, const struct colv *c, int a, int b, double z0, double z1,
                      int sign)
{
  cairo_move_to(cr, PX(F, z0), PY(F, 0));
  cairo_line_to(cr, PX(F, z0), PY(F, sign * c[a].r));
  for (int k = a; k < b; k++)
    cairo_line_to(cr, PX(F, c[k].z), PY(F, sign * c[k].r));
  cairo_line_to(cr, PX(F, z1), PY(F, sign * c[b - 1].r));
  cairo_line_to(cr, PX(F, z1), PY(F, 0));
  cairo_close_path(cr);
}

static void hatch(cairo_t *cr, double x0, double y0, double x1, double y1, double step)
{
  for (double x = x0 - (y1 - y0); x < x1; x += step) {
    cairo_move_to(cr, x, y1);
    cairo_line_to(cr, x + (y1 - y0), y0);
  }
  cairo_stroke(cr);
}

static void draw_stock(cairo_t *cr, struct lathe *pl, const struct fit *F, int *cutoff, double *cut_z)
{
  double L = pl->st.len, h = pl->half;
  double zs = -L;
  *cutoff = 0;
  /* the chuck: the bar held in it, the jaws above and below */
  plot_rgb(cr, 0xeeeeee);
  cairo_rectangle(cr, PX(F, zs - F->jaw_l), PY(F, h), F->jaw_l * F->s, 2 * h * F->s);
  cairo_fill(cr);
  for (int sgn = -1; sgn <= 1; sgn += 2) {
    double ya = PY(F, sgn * h), yb = PY(F, sgn * (h + F->jaw_h));
    double xa = PX(F, zs - F->jaw_l), xb = PX(F, zs);
    double top = fmin(ya, yb), bot = fmax(ya, yb);
    cairo_save(cr);
    cairo_rectangle(cr, xa, top, xb - xa, bot - top);
    plot_rgb(cr, 0xdadada);
    cairo_fill_preserve(cr);
    cairo_clip(cr);
    plot_rgb(cr, C_JAW);
    cairo_set_line_width(cr, 0.8);
    hatch(cr, xa, top, xb, bot, 5);
    cairo_restore(cr);
    cairo_rectangle(cr, xa + 0.5, top + 0.5, xb - xa - 1, bot - top - 1);
    plot_rgb(cr, C_JAW);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);
  }
  plot_rgb(cr, C_LABEL);
  plot_text_at(cr, PX(F, zs - F->jaw_l / 2), PY(F, h + F->jaw_h) - 5, "chuck", 11, 0, 0.5);

  int n;
  struct colv *c = columns(pl, F, &n);
  if (c) {
    /* the removed material: between R and d/2, above the axis */
    plot_rgb(cr, C_REMOVED);
    cairo_move_to(cr, PX(F, zs), PY(F, h));
    cairo_line_to(cr, PX(F, zs), PY(F, c[0].r));
    for (int k = 0; k < n; k++)
      cairo_line_to(cr, PX(F, c[k].z), PY(F, c[k].r));
    cairo_line_to(cr, PX(F, 0), PY(F, c[n - 1].r));
    cairo_line_to(cr, PX(F, 0), PY(F, h));
    cairo_close_path(cr);
    cairo_fill(cr);
    /* the part: held by the chuck, and what is cut off */
    int a = 0;
    while (a < n && !c[a].off)
      a++;
    double zcut = a < n ? c[a].z - (pl->st.len / n) / 2 : 0;
    for (int sgn = 1; sgn >= -1; sgn -= 2) {
      if (a > 0) {
        part_path(cr, F, c, 0, a, zs, a < n ? zcut : 0, sgn);
        plot_rgb(cr, sgn > 0 ? C_PART : C_PARTPALE);
        cairo_fill(cr);
      }
      if (a < n) {
        part_path(cr, F, c, a, n, zcut, 0, sgn);
        plot_rgb(cr, C_CUTOFF);
        cairo_fill_preserve(cr);
        cairo_save(cr);
        cairo_clip(cr);
        plot_rgb(cr, 0xa0a0a0);
        cairo_set_line_width(cr, 0.7);
        hatch(cr, PX(F, zcut), PY(F, h), PX(F, 0), PY(F, -h), 4);
        cairo_restore(cr);
      }
    }
    if (a < n) {
      /* the cut-off column itself: where the tool reached the axis */
      int cc = cutoff_cell(pl);
      *cutoff = 1;
      *cut_z = -pl->st.len + (cc + 0.5) * pl->dz;
    }
    /* thread bands: hatched between the thread's least radius and R */
    if (pl->any_thread_band) {
      cairo_save(cr);
      cairo_new_path(cr);
      for (int k = 0; k < n; k++) {
        if (!isfinite(c[k].thr) || c[k].thr >= c[k].r)
          continue;
        double w = pl->st.len / n;
        double xa = PX(F, c[k].z - w / 2), xb = PX(F, c[k].z + w / 2);
        cairo_rectangle(cr, xa, PY(F, c[k].r), xb - xa, (c[k].r - c[k].thr) * F->s);
      }
      cairo_clip(cr);
      plot_rgba(cr, C_THREAD, 0.18);
      cairo_paint(cr);
      plot_rgb(cr, C_THREAD);
      cairo_set_line_width(cr, 0.8);
      hatch(cr, PX(F, zs), PY(F, h), PX(F, 0), PY(F, 0), 3.5);
      cairo_restore(cr);
    }
    /* the part's outline, above and below */
    cairo_set_line_width(cr, 1.2);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
    for (int sgn = 1; sgn >= -1; sgn -= 2) {
      plot_rgb(cr, sgn > 0 ? 0x33475c : 0x8a9aab);
      cairo_move_to(cr, PX(F, zs), PY(F, sgn * c[0].r));
      for (int k = 0; k < n; k++)
        cairo_line_to(cr, PX(F, c[k].z), PY(F, sgn * c[k].r));
      cairo_line_to(cr, PX(F, 0), PY(F, sgn * c[n - 1].r));
      cairo_line_to(cr, PX(F, 0), PY(F, 0));
      cairo_stroke(cr);
    }
    free(c);
  }
  /* the stock's outline */
  plot_rgb(cr, C_STOCK);
  cairo_set_line_width(cr, 1.2);
  double dash[] = {7, 3};
  cairo_set_dash(cr, dash, 2, 0);
  cairo_rectangle(cr, PX(F, zs), PY(F, h), L * F->s, 2 * h * F->s);
  cairo_stroke(cr);
  cairo_set_dash(cr, NULL, 0, 0);
}

static void centre_line(cairo_t *cr, const struct fit *F)
{
  double y = PY(F, 0);
  double dd[] = {14, 3, 2, 3};
  plot_rgb(cr, C_CENTRE);
  cairo_set_line_width(cr, 0.9);
  cairo_set_dash(cr, dd, 4, 0);
  cairo_move_to(cr, FX + LBAND, y);
  cairo_line_to(cr, FX + FW, y);
  cairo_stroke(cr);
  cairo_set_dash(cr, NULL, 0, 0);
}

/* The zig-zag of a thread from (x0,y0) to (x1,y1): a tooth at the pitch. */
static void zigzag(cairo_t *cr, double x0, double y0, double x1, double y1, double period)
{
  double L = hypot(x1 - x0, y1 - y0);
  cairo_move_to(cr, x0, y0);
  if (L < 1e-9) return;
  double ux = (x1 - x0) / L, uy = (y1 - y0) / L, amp = 3;
  if (period < 5) period = 5;
  double halves = floor(2 * L / period);
  if (halves > 4000) halves = 4000;
  for (int k = 1; k < halves; k++) {
    double t = k * L / halves, s = (k & 1) ? amp : -amp;
    cairo_line_to(cr, x0 + ux * t - uy * s, y0 + uy * t + ux * s);
  }
  cairo_line_to(cr, x1, y1);
}

/* The pen of a style's strokes: where the path is (page), and how many
 * pieces since the last stroke. */
struct pen {
  int have;
  double x, y;
  size_t k;
  double ink;           /* page length drawn */
};

/* The page length of strokes drawn at most (about 15 times over the
 * frame): past it the path is too dense to see and takes cairo long. */
#define INK_BUDGET 6e6

static void pen_to(cairo_t *cr, struct pen *p, double x0, double y0, double x1, double y1)
{
  if (!p->have || fabs(x0 - p->x) > 0.05 || fabs(y0 - p->y) > 0.05) {
    cairo_move_to(cr, x0, y0);
    p->have = 1;
    p->x = x0;
    p->y = y0;
  }
  if (fabs(x1 - p->x) < 0.4 && fabs(y1 - p->y) < 0.4)
    return;   /* under a pixel: the next piece goes on from here */
  cairo_line_to(cr, x1, y1);
  p->ink += hypot(x1 - p->x, y1 - p->y);
  p->x = x1;
  p->y = y1;
  p->k++;
}

/* Clip the page segment to the frame (a little outside it): 0 nothing left. */
static int clip_page(double *x0, double *y0, double *x1, double *y1)
{
  const double xa = FX - 20, xb = FX + FW + 20, ya = FY - 20, yb = FY + FH + 20;
  double t0 = 0, t1 = 1, dx = *x1 - *x0, dy = *y1 - *y0;
  double p[4] = {-dx, dx, -dy, dy}, q[4] = {*x0 - xa, xb - *x0, *y0 - ya, yb - *y0};
  for (int k = 0; k < 4; k++) {
    if (p[k] == 0) {
      if (q[k] < 0)
        return 0;
      continue;
    }
    double t = q[k] / p[k];
    if (p[k] < 0) {
      if (t > t1) return 0;
      if (t > t0) t0 = t;
    } else {
      if (t < t0) return 0;
      if (t < t1) t1 = t;
    }
  }
  double ax = *x0 + dx * t0, ay = *y0 + dy * t0;
  *x1 = *x0 + dx * t1;
  *y1 = *y0 + dy * t1;
  *x0 = ax;
  *y0 = ay;
  return 1;
}

static void line_piece(cairo_t *cr, struct pen *p, double x0, double y0, double x1, double y1, int thread,
                       double period)
{
  if (!isfinite(x0) || !isfinite(y0) || !isfinite(x1) || !isfinite(y1) || !clip_page(&x0, &y0, &x1, &y1))
    return;
  if (thread && hypot(x1 - x0, y1 - y0) > 3) {
    zigzag(cr, x0, y0, x1, y1, period);
    p->ink += 2 * hypot(x1 - x0, y1 - y0);
    p->have = 1;
    p->x = x1;
    p->y = y1;
    p->k += 8;
    return;
  }
  pen_to(cr, p, x0, y0, x1, y1);
}

/* Add the move from (r0, z0) to the path. */
static void move_path(cairo_t *cr, struct pen *p, const struct fit *F, const struct mv *m, double r0, double z0,
                      double pitch)
{
  double x0 = PX(F, z0), y0 = PY(F, r0), x1 = PX(F, m->z), y1 = PY(F, m->r);
  int thread = (m->flags & MF_THREAD) != 0;
  if (m->kind != MV_ARC) {
    line_piece(cr, p, x0, y0, x1, y1, thread, pitch * F->s);
    return;
  }
  double rho0 = hypot(r0 - m->cr, z0 - m->cz), rho1 = hypot(m->r - m->cr, m->z - m->cz);
  double R = fmax(rho0, rho1) * F->s, cx = PX(F, m->cz), cy = PY(F, m->cr);
  if (!isfinite(R) || cx + R < FX || cx - R > FX + FW || cy + R < FY || cy - R > FY + FH)
    return;   /* not in the picture */
  if (R * fabs(m->sweep) < 1) {
    line_piece(cr, p, x0, y0, x1, y1, 0, 0);
    return;
  }
  if (fabs(rho0 - rho1) <= 1e-3 * fmax(rho0, 1e-3) && R < 2e4) {
    /* the page's angle is the arc's (from X towards Z) less 90 degrees,
     * and grows the same way: G02 (+) clockwise on the page, cairo_arc */
    double th0 = atan2(z0 - m->cz, r0 - m->cr), phi0 = th0 - M_PI / 2;
    if (!p->have || fabs(x0 - p->x) > 0.05 || fabs(y0 - p->y) > 0.05)
      cairo_move_to(cr, x0, y0);
    if (m->sweep > 0)
      cairo_arc(cr, cx, cy, rho0 * F->s, phi0, phi0 + m->sweep);
    else
      cairo_arc_negative(cr, cx, cy, rho0 * F->s, phi0, phi0 + m->sweep);
    cairo_line_to(cr, x1, y1);
    p->ink += R * fabs(m->sweep);
    p->have = 1;
    p->x = x1;
    p->y = y1;
    p->k += 4;
    return;
  }
  /* a spiral, or a circle too big for the page: in pieces */
  int k = (int)ceil(fabs(m->sweep) * R / 3);
  if (k < 8) k = 8;
  if (k > 256) k = 256;
  double pr = r0, pz = z0;
  for (int i = 1; i <= k; i++) {
    double r, z;
    if (i == k) {
      r = m->r;
      z = m->z;
    } else
      arc_point(r0, z0, m->cr, m->cz, m->sweep, rho1, (double)i / k, &r, &z);
    line_piece(cr, p, PX(F, pz), PY(F, pr), PX(F, z), PY(F, r), 0, 0);
    pr = r;
    pz = z;
  }
}

/* Stroke the moves of one style: feed (0), traverse (1), thread (2); or
 * (style 3) those that cut past the stock's end. */
static int draw_moves(cairo_t *cr, const struct lathe *pl, const struct fit *F, int style, double budget)
{
  double r0 = 0, z0 = 0;
  struct pen p = {0, 0, 0, 0, 0};
  size_t i;
  for (i = 0; i < pl->n && p.ink < budget; i++) {
    const struct mv *m = &pl->v[i];
    if (m->kind != MV_JUMP) {
      int st = m->kind == MV_TRAV ? 1 : (m->flags & MF_THREAD) ? 2 : 0;
      if (style == 3 ? (m->flags & MF_CHUCK) != 0 : st == style) {
        move_path(cr, &p, F, m, r0, z0, pl->pitch);
        if (p.k >= CHUNK) {
          cairo_stroke(cr);
          p.k = 0;
          p.have = 0;
        }
      }
    }
    r0 = m->r;
    z0 = m->z;
  }
  cairo_stroke(cr);
  return i < pl->n;   /* the budget ran out */
}

/* 1: the path is too dense to draw whole (drawn in part). */
static int draw_path(cairo_t *cr, const struct lathe *pl, const struct fit *F)
{
  int part = 0;
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  double dash[] = {6, 4};
  plot_rgb(cr, C_TRAV);
  cairo_set_line_width(cr, 1.1);
  cairo_set_dash(cr, dash, 2, 0);
  part |= draw_moves(cr, pl, F, 1, INK_BUDGET / 4);
  cairo_set_dash(cr, NULL, 0, 0);
  plot_rgb(cr, C_FEED);
  cairo_set_line_width(cr, 1.5);
  part |= draw_moves(cr, pl, F, 0, INK_BUDGET);
  plot_rgb(cr, C_THREAD);
  cairo_set_line_width(cr, 1.2);
  part |= draw_moves(cr, pl, F, 2, INK_BUDGET / 4);
  if (pl->chuck) {
    /* over it all, in red where the path cuts past the stock's end */
    cairo_save(cr);
    double x0 = FX + LBAND, xe = PX(F, -pl->st.len);
    cairo_rectangle(cr, x0, PY(F, pl->half), xe - x0, 2 * pl->half * F->s);
    cairo_clip(cr);
    plot_rgb(cr, C_CHUCKCUT);
    cairo_set_line_width(cr, 3);
    part |= draw_moves(cr, pl, F, 3, INK_BUDGET / 4);
    cairo_restore(cr);
  }
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  /* the start: a ring; the end: a square */
  for (size_t i = 0; i < pl->n; i++)
    if (pl->v[i].kind == MV_JUMP) {
      plot_rgb(cr, C_START);
      cairo_set_line_width(cr, 2);
      cairo_new_path(cr);
      cairo_arc(cr, PX(F, pl->v[i].z), PY(F, pl->v[i].r), 5, 0, 2 * M_PI);
      cairo_stroke(cr);
      break;
    }
  if (pl->n) {
    plot_rgb(cr, C_END);
    cairo_rectangle(cr, PX(F, pl->last_z) - 3.5, PY(F, pl->last_r) - 3.5, 7, 7);
    cairo_fill(cr);
  }
  return part;
}

enum { LG_NOTE, LG_LINE, LG_DASH, LG_ZIG, LG_RED, LG_BOX, LG_DASHBOX, LG_HATCH, LG_CENTRE, LG_RING, LG_SQUARE, LG_THRBOX };

static double legend_item(cairo_t *cr, double x, double y, int style, unsigned c, const char *text, int measure)
{
  double w = (style == LG_NOTE ? 0 : 30) + plot_text_w(cr, text, 11, 0);
  if (measure)
    return w;
  if (style == LG_NOTE) {
    plot_rgb(cr, C_LABEL);
    plot_text_at(cr, x, y, text, 11, 0, 0);
    return w;
  }
  cairo_new_path(cr);
  double dash[] = {6, 4}, dd[] = {10, 2.5, 2, 2.5};
  switch (style) {
  case LG_LINE: case LG_DASH: case LG_RED: case LG_CENTRE:
    plot_rgb(cr, c);
    cairo_set_line_width(cr, style == LG_RED ? 3 : style == LG_CENTRE ? 0.9 : 1.5);
    if (style == LG_DASH) cairo_set_dash(cr, dash, 2, 0);
    if (style == LG_CENTRE) cairo_set_dash(cr, dd, 4, 0);
    cairo_move_to(cr, x, y - 4);
    cairo_line_to(cr, x + 24, y - 4);
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0);
    break;
  case LG_ZIG:
    plot_rgb(cr, c);
    cairo_set_line_width(cr, 1.2);
    zigzag(cr, x, y - 4, x + 24, y - 4, 6);
    cairo_stroke(cr);
    break;
  case LG_BOX: case LG_DASHBOX: case LG_HATCH: case LG_THRBOX:
    cairo_rectangle(cr, x + 2, y - 10, 20, 11);
    if (style == LG_DASHBOX) {
      plot_rgb(cr, c);
      cairo_set_line_width(cr, 1.2);
      cairo_set_dash(cr, dash, 2, 0);
      cairo_stroke(cr);
      cairo_set_dash(cr, NULL, 0, 0);
      break;
    }
    plot_rgb(cr, style == LG_THRBOX ? 0xf2d4ea : c);
    cairo_fill_preserve(cr);
    if (style == LG_HATCH || style == LG_THRBOX) {
      cairo_save(cr);
      cairo_clip(cr);
      plot_rgb(cr, style == LG_THRBOX ? C_THREAD : 0xa0a0a0);
      cairo_set_line_width(cr, 0.7);
      hatch(cr, x + 2, y - 10, x + 22, y + 1, 4);
      cairo_restore(cr);
    }
    cairo_new_path(cr);
    break;
  case LG_RING:
    plot_rgb(cr, c);
    cairo_set_line_width(cr, 2);
    cairo_arc(cr, x + 12, y - 4, 5, 0, 2 * M_PI);
    cairo_stroke(cr);
    break;
  case LG_SQUARE:
    plot_rgb(cr, c);
    cairo_rectangle(cr, x + 8.5, y - 7.5, 7, 7);
    cairo_fill(cr);
    break;
  }
  plot_rgb(cr, C_TEXT);
  plot_text_at(cr, x + 30, y, text, 11, 0, 0);
  return w;
}

static void legend(cairo_t *cr, const struct lathe *pl, int cutoff)
{
  struct { int style; unsigned c; const char *text; int show; } it[] = {
    {LG_LINE, C_FEED, "feed move (arcs as arcs)", 1},
    {LG_DASH, C_TRAV, "traverse", 1},
    {LG_ZIG, C_THREAD, "thread (G33)", 1},
    {LG_THRBOX, C_THREAD, "thread's cut", pl->any_thread_band},
    {LG_RED, C_CHUCKCUT, "cut past the stock's end", pl->st.has},
    {LG_RING, C_START, "start", 1},
    {LG_SQUARE, C_END, "end", 1},
    {LG_DASHBOX, C_STOCK, "stock", pl->st.has},
    {LG_BOX, C_REMOVED, "material removed", pl->st.has},
    {LG_BOX, C_PART, "the part (below the axis: mirrored)", pl->st.has},
    {LG_HATCH, C_CUTOFF, "cut off", cutoff},
    {LG_CENTRE, C_CENTRE, "axis of rotation", 1},
  };
  size_t k = sizeof it / sizeof it[0];
  double x = FX, y = FY + FH + 22, gap = 18;
  for (size_t i = 0; i < k; i++) {
    if (!it[i].show)
      continue;
    double w = legend_item(cr, x, y, it[i].style, it[i].c, it[i].text, 1);
    if (x + w > FX + FW && x > FX) {
      x = FX;
      y += 20;
    }
    legend_item(cr, x, y, it[i].style, it[i].c, it[i].text, 0);
    x += w + gap;
  }
}

static void draw(cairo_t *cr, struct lathe *pl, const char *program)
{
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  struct fit F;
  make_fit(pl, &F);
  /* the grid and the ticks in the frame, the drawing clipped to its area */
  cairo_save(cr);
  cairo_rectangle(cr, FX, FY, FW, FH);
  cairo_clip(cr);
  grid_and_ticks(cr, &F);
  cairo_restore(cr);
  cairo_save(cr);
  cairo_rectangle(cr, FX + LBAND, FY, FW - LBAND, FH - BBAND);
  cairo_clip(cr);
  int cutoff = 0;
  double cut_z = 0;
  if (pl->st.has)
    draw_stock(cr, pl, &F, &cutoff, &cut_z);
  centre_line(cr, &F);
  int part = draw_path(cr, pl, &F);
  plot_rgb(cr, C_TEXT);
  plot_text_at(cr, FX + FW - 6, PY(&F, 0) - 6, "Z, mm", 11, 1, 1);
  if (!pl->moves) {
    plot_rgb(cr, C_LABEL);
    plot_text_at(cr, FX + LBAND + (FW - LBAND) / 2, FY + 40, "no moves", 16, 1, 0.5);
  }
  cairo_restore(cr);
  plot_rgb(cr, C_FRAME);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, FX + LBAND + 0.5, FY + 0.5, FW - LBAND - 1, FH - BBAND - 1);
  cairo_stroke(cr);
  plot_rgb(cr, C_TEXT);
  plot_text_at(cr, FX + 2, FY + 12, "Ø, mm", 11, 1, 0);
  legend(cr, pl, cutoff);

  /* the title, the status, the stock and the extents */
  const char *base = strrchr(program ? program : "", '/');
  base = base ? base + 1 : program ? program : "";
  char title[300], line[600], a[40], b[40], c[40];
  snprintf(title, sizeof title, "%s", base);
  plot_rgb(cr, C_TEXT);
  plot_text_at(cr, FX, 28, title, 19, 1, 0);
  plot_text_at(cr, FX + plot_text_w(cr, title, 19, 1) + 12, 28, "the lathe's tool path and the turned part, s42 (2У22)", 12, 0,
          0);
  /* the orientation, at the right of the title */
  {
    const char *ori = "Z along: the chuck left, the face at Z 0;  the radius up (labelled Ø);  one scale";
    double used = FX + plot_text_w(cr, title, 19, 1) + 12 +
                  plot_text_w(cr, "the lathe's tool path and the turned part, s42 (2У22)", 12, 0) + 16;
    double size = 11;
    while (size > 7 && FX + FW - plot_text_w(cr, ori, size, 0) < used)
      size -= 0.5;
    plot_rgb(cr, C_LABEL);
    plot_text_at(cr, FX + FW, 28, ori, size, 0, 1);
  }
  size_t o = 0;
  o += snprintf(line + o, sizeof line - o, "%s", pl->status);
  if (pl->st.has) {
    plot_fmt_num(a, sizeof a, pl->st.d, 2, 1);
    plot_fmt_num(b, sizeof b, pl->st.len, 2, 1);
    o += snprintf(line + o, sizeof line - o, "  ·  stock Ø%s × %s mm, face at Z 0", a, b);
  } else
    o += snprintf(line + o, sizeof line - o, "  ·  no stock given (--stock DxL)");
  if (pl->ext && pl->moves) {
    plot_fmt_num(a, sizeof a, 2 * pl->amax, 2, 0);
    plot_fmt_num(b, sizeof b, pl->zmin, 2, 0);
    plot_fmt_num(c, sizeof c, pl->zmax, 2, 0);
    o += snprintf(line + o, sizeof line - o, "  ·  path: max Ø%s, Z %s .. %s  ·  %llu move%s", a, b, c,
                  pl->moves, pl->moves == 1 ? "" : "s");
  } else
    o += snprintf(line + o, sizeof line - o, "  ·  no moves");
  (void)o;
  snprintf(pl->cap_title, sizeof pl->cap_title, "%s", title);
  snprintf(pl->cap_line, sizeof pl->cap_line, "%s", line);
  double lsize = 12;
  while (lsize > 8 && plot_text_w(cr, line, lsize, 0) > FW)
    lsize -= 0.5;
  plot_rgb(cr, C_LABEL);
  plot_text_at(cr, FX, 48, line, lsize, 0, 0);
  /* warnings */
  char warn[600] = "";
  size_t w = 0;
#define WARN(...) do { \
    if (w < sizeof warn) \
      w += snprintf(warn + w, sizeof warn - w, "%s", w ? ";  " : ""); \
    if (w < sizeof warn) \
      w += snprintf(warn + w, sizeof warn - w, __VA_ARGS__); \
  } while (0)
  if (pl->chuck) {
    plot_fmt_num(a, sizeof a, pl->chuck_z, 2, 0);
    plot_fmt_num(b, sizeof b, -pl->st.len, 2, 0);
    WARN("cuts into the chuck side at Z %s (the stock ends at Z %s)", a, b);
  }
  if (pl->st.has && pl->moves) {
    compute_R(pl);
    int touched = 0;
    for (int i = 0; i < pl->ncol && !touched; i++)
      if (pl->R[i] < pl->half - 1e-9 || pl->thr[i] < pl->half - 1e-9)
        touched = 1;
    if (!touched)
      WARN("the path never touches the stock");
  }
  if (cutoff) {
    plot_fmt_num(a, sizeof a, cut_z, 2, 0);
    WARN("the tool reached the axis at Z %s: what is beyond it is cut off (hatched)", a);
  }
  if (pl->oom)
    WARN("out of memory: the path is cut short");
  if (part)
    WARN("the path is too dense to draw whole: drawn in part");
#undef WARN
  snprintf(pl->cap_warn, sizeof pl->cap_warn, "%s", warn);
  if (warn[0]) {
    double size = 12;
    while (size > 8 && plot_text_w(cr, warn, size, 1) > FW)
      size -= 0.5;
    plot_rgb(cr, C_WARN);
    plot_text_at(cr, FX, 66, warn, size, 1, 0);
  }
}

/* ---- the view ---- */

static void draw_lathe(cairo_t *cr, struct plot *e, int raster)
{
  (void)raster;
  struct lathe *pl = lathe_of(e);
  if (!pl) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    plot_rgb(cr, C_WARN);
    plot_text_at(cr, FX, 48, "out of memory: no picture of the path", 14, 1, 0);
    return;
  }
  /* the caption's status: the engine's result caption */
  snprintf(pl->status, sizeof pl->status, "%s",
           !e->ended ? "run not finished" : e->why[0] ? e->why : e->status == 0 ? "end" : "stopped");
  draw(cr, pl, e->program);
}

/* The SVG's <title> and <desc>: the caption, searchable (cairo writes the
 * picture's text as glyphs). */
static char *svg_head(struct plot *e)
{
  const struct lathe *pl = e->vs;
  if (!pl)
    return NULL;
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  if (!f)
    return NULL;
  fputs("\n<title>", f);
  plot_xml_text(f, pl->cap_title);
  fputs("</title>\n<desc>", f);
  plot_xml_text(f, pl->cap_line);
  if (pl->cap_warn[0]) {
    fputs("\n", f);
    plot_xml_text(f, pl->cap_warn);
  }
  fputs("</desc>", f);
  if (fclose(f) != 0) {
    free(buf);
    return NULL;
  }
  return buf;
}

static void free_lathe(struct plot *e)
{
  lathe_free(e->vs);
  e->vs = NULL;
}

const struct plot_view plot_view_lathe = {"lathe", PW, PH, draw_lathe, svg_head, free_lathe};
