/* The 2С42 block on the grinder (src/dialect/2c42/kpmach.h). */
#include "kpmach.h"
#include "ast.h"
#include "errors.h"
#include "geom.h"
#include "kp.h"
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
  pa->d1 = b->d1;
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

void kp_mach_modal(struct machine *m, const struct kp_block *b)
{
  if (!(b->m & (1u << 3 | 1u << 4 | 1u << 5 | 1u << 22 | 1u << 23 | 1u << 25 | 1u << 26)))
    return;
  if (BIT(b->m, 5))
    mach_spindle(m, 0);
  if (BIT(b->m, 3))
    mach_spindle(m, 1);
  if (BIT(b->m, 4))
    mach_spindle(m, -1);
  if (BIT(b->m, 22)) mach_switch(m, MACH_SW_CORR, 1);
  if (BIT(b->m, 23)) mach_switch(m, MACH_SW_CORR, 0);
  if (BIT(b->m, 25)) mach_switch(m, MACH_SW_OVERRIDE, 0);
  if (BIT(b->m, 26)) mach_switch(m, MACH_SW_OVERRIDE, 1);
}

void kp_mach_motion(struct machine *m, const struct kp_block *b, struct mach_out *o)
{
  memset(o, 0, sizeof *o);
  struct mach_path pa;
  if (b->motion == MO_G01 || b->motion == MO_G02 || b->motion == MO_G03) {
    kp_path(m->pos, b, &pa);
    mach_feed(m, &pa, b->f, o);
  } else if (b->motion == MO_G04) {
    mach_dwell(m, b->w[SL_X] / 10.0);
  } else if (b->motion == MO_G37) {
    mach_traverse_axis(m, AX_Y, 0, o);
  }
}

int kp_mach_moves(const struct kp_block *b)
{
  for (int a = 0; a < 4; a++)
    if (BIT(b->given, a) && b->w[a] != 0)
      return 1;
  return 0;
}
