/* The 2С42 block on the grinder (src/dialect/2c42/kpmach.h). */
#include "kpmach.h"
#include "ast.h"
#include "errors.h"
#include "geom.h"
#include "kp.h"
#include "canon.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#define BIT(x, n) (((x) >> (n)) & 1)

int kp_plane(int g)
{
  return g == 17 ? GEOM_XY : g == 18 ? GEOM_YZ : GEOM_XZ;
}

static int is_arc(int motion)
{
  return motion == MO_G02 || motion == MO_G03 || motion == MO_G12 || motion == MO_G13;
}

static __attribute__((noinline)) int path_of(const int64_t pos[4], const struct kp_block *b, struct mach_path *pa)
{
  memset(pa, 0, sizeof *pa);
  for (int a = 0; a < 4; a++)
    pa->to[a] = pos[a] + (BIT(b->given, a) ? (int64_t)llround(b->w[a]) : 0);
  if (is_arc(b->motion)) {
    int p, q;
    pa->arc = 1;
    pa->plane = kp_plane(b->plane);
    geom_plane_axes(pa->plane, &p, &q);
    pa->cp = b->w[SL_I + p];
    pa->cq = b->w[SL_I + q];
    pa->ccw = b->motion == MO_G03 || b->motion == MO_G13;
  }
  return 1;
}

int kp_path(const int64_t pos[4], const struct kp_block *b, struct mach_path *pa)
{
  if (b->motion != MO_G01 && !is_arc(b->motion))
    return 0;   /* most blocks that yield: no frame for them */
  return path_of(pos, b, pa);
}

int kp_mach_arc(const struct kp_block *b, double *len_mm, double *yshare, char *msg, size_t n)
{
  static const int64_t origin[4];
  struct mach_path pa;
  kp_path(origin, b, &pa);
  int p, q;
  geom_plane_axes(pa.plane, &p, &q);
  struct geom_arc a = {(double)pa.to[p], (double)pa.to[q], pa.cp, pa.cq, pa.ccw};
  if (geom_arc_check(&a, MACH_ARC_RMAX, MACH_ARC_TOL, msg, n))
    return S42_E_ARC;
  mach_arc_shape(pa.plane, &a, len_mm, yshare);
  return 0;
}

static __attribute__((noinline)) int check_block(const struct machine *m, const struct kp_block *b, char *msg,
                                                 size_t n)
{
  if (BIT(b->m, 3) && mach_check_spindle(m, 1, msg, n)) {
    snprintf(msg, n, "M3 while the wheel turns counter-clockwise: stop it with M5 first");
    return S42_E_WHEEL;
  }
  if (BIT(b->m, 4) && mach_check_spindle(m, -1, msg, n)) {
    snprintf(msg, n, "M4 while the wheel turns clockwise: stop it with M5 first");
    return S42_E_WHEEL;
  }
  struct mach_path pa;
  if (b->motion != MO_G01 && !is_arc(b->motion))
    return 0;   /* no path: what kp_path says, without the call */
  kp_path(m->pos, b, &pa);
  if (b->motion == MO_G12 || b->motion == MO_G13)
    return mach_check_travel(m, &pa, msg, n);   /* the helix plugin checks its own curve */
  return mach_check_path(m, &pa, b->f, msg, n);
}

int kp_mach_check(const struct machine *m, const struct kp_block *b, char *msg, size_t n)
{
  /* most blocks that come here have no path and no M3/M4: no frame for them */
  if (!(b->m & (1u << 3 | 1u << 4)) && b->motion != MO_G01 && !is_arc(b->motion))
    return 0;
  return check_block(m, b, msg, n);
}

/* A call on the grinder that cannot fail once the block passed its check
 * (kp_mach_check): the wheel, the switches, a dwell, the end. */
static void call(struct machine *m, struct canon_call *c)
{
  struct canon_dev d = grinder_dev(m);
  char msg[200];
  canon_do(&d, c, msg, sizeof msg);
}

static void wheel(struct machine *m, int dir)
{
  struct canon_call c = canon_of(CANON_SPINDLE);
  c.dir = dir;
  call(m, &c);
}

static void panel(struct machine *m, int kind, int which, int on)
{
  struct canon_call c = canon_of(kind);
  c.n = which;
  c.on = on;
  call(m, &c);
}

void kp_mach_modal(struct machine *m, const struct kp_block *b)
{
  if (!(b->m & (1u << 3 | 1u << 4 | 1u << 5 | 1u << 22 | 1u << 23 | 1u << 25 | 1u << 26)))
    return;
  if (BIT(b->m, 5))
    wheel(m, 0);
  if (BIT(b->m, 3))
    wheel(m, 1);
  if (BIT(b->m, 4))
    wheel(m, -1);
  if (BIT(b->m, 22)) panel(m, CANON_SWITCH, MACH_SW_CORR, 1);
  if (BIT(b->m, 23)) panel(m, CANON_SWITCH, MACH_SW_CORR, 0);
  if (BIT(b->m, 25)) panel(m, CANON_OVERRIDE, 0, 0);
  if (BIT(b->m, 26)) panel(m, CANON_OVERRIDE, 0, 1);
}

/* The contour move of a path as the grinder's record. */
static struct canon_call feed_of(const struct machine *m, const struct mach_path *pa, double f)
{
  struct canon_call c = canon_of(pa->arc ? CANON_FEED_ARC : CANON_FEED_LINE);
  memcpy(c.pos, pa->to, sizeof pa->to);
  for (int a = 4; a < CANON_AXES; a++)
    c.pos[a] = 0;
  c.f = f;
  if (pa->arc) {
    int p, q;
    geom_plane_axes(pa->plane, &p, &q);
    c.plane = pa->plane;
    c.cp = pa->cp;
    c.cq = pa->cq;
    c.centre[0] = m->pos[p] + (int64_t)llround(pa->cp);
    c.centre[1] = m->pos[q] + (int64_t)llround(pa->cq);
    c.ccw = pa->ccw;
  }
  return c;
}

int kp_mach_motion(struct machine *m, const struct kp_block *b, struct mach_out *o, char *msg, size_t n)
{
  memset(o, 0, sizeof *o);
  struct canon_dev d = grinder_dev(m);
  int e = 0;
  if (b->motion == MO_G01 || b->motion == MO_G02 || b->motion == MO_G03) {
    struct mach_path pa;
    kp_path(m->pos, b, &pa);
    int64_t from[4];
    memcpy(from, m->pos, sizeof from);
    struct canon_call c = feed_of(m, &pa, b->f);
    if ((e = canon_do(&d, &c, msg, n)) != 0)
      return e;
    *o = m->last;
    /* the surface speed with A (language.md sec. 16): a line that turns A
     * while it moves a linear axis, on a work of diameter D1 */
    double dd[4];
    for (int a = 0; a < 4; a++)
      dd[a] = (double)(pa.to[a] - from[a]);
    double lin2 = dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2];
    double len = sqrt(lin2 + dd[3] * dd[3]);
    if (!pa.arc && len > 0 && dd[3] != 0 && lin2 > 0) {
      double ad = dd[3] * M_PI * (b->d1 / 1000.0) / 360.0;
      o->v = o->feed * sqrt((lin2 + ad * ad) / (lin2 + dd[3] * dd[3]));
      o->has_v = 1;
    }
  } else if (b->motion == MO_G04) {
    struct canon_call c = canon_of(CANON_DWELL);
    c.v = b->w[SL_X] / 10.0;
    e = canon_do(&d, &c, msg, n);
  } else if (b->motion == MO_G37) {
    struct canon_call c = canon_of(CANON_TRAVERSE);
    c.axes = 1u << AX_Y;
    c.pos[AX_Y] = 0;
    if ((e = canon_do(&d, &c, msg, n)) == 0)
      *o = m->last;
  }
  return e;
}

int kp_mach_path_move(struct machine *m, const struct mach_path *along, const double d[4], double len,
                      double limit, double f, struct mach_out *o, char *msg, size_t n)
{
  struct canon_dev dv = grinder_dev(m);
  struct canon_call c;
  if (along && along->arc) {
    c = feed_of(m, along, f);
  } else {
    c = canon_of(CANON_FEED_LINE);
    c.f = f;
  }
  for (int a = 0; a < 4; a++)
    c.pos[a] = m->pos[a] + (int64_t)llround(d[a]);
  c.len = len;
  c.limit = limit;
  int e = canon_do(&dv, &c, msg, n);
  if (!e)
    *o = m->last;
  return e;
}

int kp_mach_moves(const struct kp_block *b)
{
  for (int a = 0; a < 4; a++)
    if (BIT(b->given, a) && b->w[a] != 0)
      return 1;
  return 0;
}
