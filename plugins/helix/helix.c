/* The helix plugin: G12 / G13, helical interpolation clockwise / counter-
 * clockwise -- an arc as G02 / G03 in the block's plane (G17 XY, G18 YZ,
 * G19 XZ) plus a linear move of one axis outside that plane (X, Y, Z or A),
 * both in proportion along the path (language.md sections 8 and 16). */
#include <s42_plugin.h>
#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const struct s42_host *host;
static const char axis_names[] = "XYZAIJK";

/* The block's helix, from its words. */
struct helix {
  int p, q;            /* the plane's axes */
  int h;               /* the helix axis, -1 none */
  double cp, cq;       /* centre relative to the start, discretes */
  double ep, eq;       /* arc end relative to the start */
  double rise;         /* the helix axis's increment */
  double r0, r1;       /* start and end radius */
  double th0, sweep;   /* start angle, signed sweep (radians) */
  double arc_mm, len;  /* arc length H (mm), path length (mm) */
  double limit;        /* the speed limit, mm/min */
};

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)dir;
  S42_PLUGIN_INIT(h, host);
  *self = NULL;
  return S42_OK;
}

static void plane_axes(int plane, int *p, int *q)
{
  switch (plane) {
  case 17: *p = S42_X; *q = S42_Y; break;
  case 18: *p = S42_Y; *q = S42_Z; break;
  default: *p = S42_X; *q = S42_Z; break;
  }
}

/* Is angle t inside the sweep from t0 of signed length dt? */
static int in_sweep(double t0, double dt, double t)
{
  double rel = fmod(dt >= 0 ? t - t0 : t0 - t, 2 * M_PI);
  if (rel < 0)
    rel += 2 * M_PI;
  return rel <= fabs(dt) + 1e-12;
}

/* Work out the helix; 0, or S42_FAIL after host->error. */
static int geometry(struct s42_block *b, struct helix *x)
{
  memset(x, 0, sizeof *x);
  int plane = host->plane(b);
  if (!plane) {
    host->error(b, "E-PLANE", "G%d needs a plane: G17 (XY), G18 (YZ) or G19 (XZ)", host->has_g(b, 12) ? 12 : 13);
    return S42_FAIL;
  }
  plane_axes(plane, &x->p, &x->q);
  x->h = -1;
  for (int a = S42_X; a <= S42_A; a++)
    if (a != x->p && a != x->q && host->has_word(b, axis_names[a]))
      x->h = a;
  x->ep = host->word(b, axis_names[x->p]);
  x->eq = host->word(b, axis_names[x->q]);
  x->cp = host->word(b, axis_names[4 + x->p]);
  x->cq = host->word(b, axis_names[4 + x->q]);
  x->rise = x->h >= 0 ? host->word(b, axis_names[x->h]) : 0;
  x->r0 = hypot(x->cp, x->cq);
  x->r1 = hypot(x->ep - x->cp, x->eq - x->cq);
  if (x->r0 == 0) {
    host->error(b, "E-ARC", "helix centre at its start point: radius 0");
    return S42_FAIL;
  }
  if (x->r0 > 4000000.0 || x->r1 > 4000000.0) {
    host->error(b, "E-ARC", "helix radius %.3f mm is over 4000 mm", fmax(x->r0, x->r1) / 1000);
    return S42_FAIL;
  }
  if (fabs(x->r0 - x->r1) > 2.0) {
    host->error(b, "E-ARC", "helix start radius %.0f µm and end radius %.0f µm differ by more than 2 µm", x->r0,
                x->r1);
    return S42_FAIL;
  }
  int ccw = host->has_g(b, 13);
  x->th0 = atan2(-x->cq, -x->cp);
  double sw;
  if (x->ep == 0 && x->eq == 0) {
    sw = 2 * M_PI;   /* end = start: a full turn */
  } else {
    double t1 = atan2(x->eq - x->cq, x->ep - x->cp);
    sw = fmod(ccw ? t1 - x->th0 : x->th0 - t1, 2 * M_PI);
    if (sw <= 0)
      sw += 2 * M_PI;
  }
  x->sweep = ccw ? sw : -sw;
  x->arc_mm = (x->r0 + x->r1) / 2 * sw / 1000.0;
  double h_mm = x->rise / 1000.0;
  x->len = sqrt(x->arc_mm * x->arc_mm + h_mm * h_mm);

  /* Speed (sec. 16 rule 4): rule 1 with the arc length H in place of the
   * in-plane increments.  When Y is in the plane, the arc's own factor
   * (rules 2 and 3) weighs H: k^2 = cos^2 w + 36^2 sin^2 w. */
  double k2 = 1;
  if (x->p == S42_Y || x->q == S42_Y) {
    double c0 = x->p == S42_Y ? fabs(sin(x->th0)) : fabs(cos(x->th0));
    double te = x->th0 + x->sweep;
    double c1 = x->p == S42_Y ? fabs(sin(te)) : fabs(cos(te));
    double ys = fmax(c0, c1);
    double crit[2] = {x->p == S42_Y ? M_PI / 2 : 0, x->p == S42_Y ? -M_PI / 2 : M_PI};
    for (int i = 0; i < 2; i++)
      if (in_sweep(x->th0, x->sweep, crit[i]))
        ys = 1;   /* the path's tangent is parallel to Y somewhere */
    k2 = (1 - ys * ys) + 36.0 * 36.0 * ys * ys;
  }
  double H2 = x->arc_mm * x->arc_mm, h2 = h_mm * h_mm;
  double w2 = x->h == S42_Y ? 36.0 * 36.0 : 1.0;
  x->limit = 6000.0 * sqrt((H2 + h2) / (H2 * k2 + w2 * h2));
  return S42_OK;
}

static int check(void *self, struct s42_block *b)
{
  (void)self;
  struct helix x;
  if (geometry(b, &x))
    return S42_FAIL;
  if (!host->has_m(b, 19) && x.len > 0 && !(host->param(b, S42_F) > 0)) {
    host->error(b, "E-FEED", "a contour move with F = 0: give the speed with F");
    return S42_FAIL;
  }
  return S42_OK;
}

static int run(void *self, struct s42_block *b)
{
  (void)self;
  struct helix x;
  if (geometry(b, &x))
    return S42_FAIL;
  struct s42_move m;
  memset(&m, 0, sizeof m);
  m.size = sizeof m;
  m.d[x.p] = x.ep;
  m.d[x.q] = x.eq;
  if (x.h >= 0)
    m.d[x.h] = x.rise;
  m.length = x.len;
  m.limit = x.limit;
  if (host->move(b, &m)) {
    host->error(b, "E-PLUGIN", "helix: the move was refused");
    return S42_FAIL;
  }
  return S42_OK;
}

/* The point at fraction t of the path: both parts in proportion. */
static int path(void *self, struct s42_block *b, double t, double d[4])
{
  (void)self;
  struct helix x;
  if (geometry(b, &x))
    return S42_FAIL;
  memset(d, 0, 4 * sizeof *d);
  if (t == 1) {
    d[x.p] = x.ep;
    d[x.q] = x.eq;
  } else {
    double th = x.th0 + x.sweep * t, r = x.r0 + (x.r1 - x.r0) * t;
    d[x.p] = x.cp + r * cos(th);
    d[x.q] = x.cq + r * sin(th);
  }
  if (x.h >= 0)
    d[x.h] = x.rise * t;
  return S42_OK;
}

static const struct s42_function functions[] = {
  S42_G_FUNCTION(12, 1, "XYZAIJKF", S42_FN_PLANE | S42_FN_MOTION,
                 "helical interpolation clockwise: an arc as G02 plus one axis outside its plane"),
  S42_G_FUNCTION(13, 1, "XYZAIJKF", S42_FN_PLANE | S42_FN_MOTION,
                 "helical interpolation counter-clockwise: an arc as G03 plus one axis outside its plane"),
};

S42_PLUGIN_DECLARE("helix", "1.0", "helical interpolation (G12 G13)", functions,
                   .init = init, .check = check, .run = run, .path = path);
