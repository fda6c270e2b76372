/* The simulated machine (src/machine/grinder/machine.h). */
#include "machine.h"
#include "errors.h"
#include "canon.h"
#include "geom.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

void mach_init(struct machine *m)
{
  memset(m, 0, sizeof *m);
  m->override_pct = 100;
  m->override_allowed = 1;
}

const struct mach_axis mach_axes[MACH_NAXES] = {
  {'X', "mm", 0, MACH_AXIS_MAX},
  {'Y', "mm", 0, MACH_Y_MAX},
  {'Z', "mm", 0, MACH_AXIS_MAX},
  {'A', "deg", 1, MACH_AXIS_MAX},
};

double mach_axis_max(int axis)
{
  return axis >= 0 && axis < MACH_NAXES ? mach_axes[axis].max_speed : 0;
}

void mach_advance(struct machine *m, double dt)
{
  if (!(dt > 0))
    return;
  m->t += dt;
  if (m->tick)
    m->tick(m->tick_ctx, dt);
}

int64_t mach_jog(struct machine *m, int axis, int64_t d, int correction)
{
  const struct mach_travel *t = &m->travel;
  if (t->has[axis]) {   /* the limit switch stops the axis */
    if (m->pos[axis] + d > t->hi[axis])
      d = t->hi[axis] > m->pos[axis] ? t->hi[axis] - m->pos[axis] : 0;
    if (m->pos[axis] + d < t->lo[axis])
      d = t->lo[axis] < m->pos[axis] ? t->lo[axis] - m->pos[axis] : 0;
  }
  m->pos[axis] += d;
  if (correction)
    m->corr[axis] += d;
  return d;
}

int mach_in_travel(const struct machine *m, const int64_t d[4])
{
  for (int a = 0; a < 4; a++)
    if (m->travel.has[a] && (m->pos[a] + d[a] > m->travel.hi[a] || m->pos[a] + d[a] < m->travel.lo[a]))
      return 0;
  return 1;
}

double mach_linear_limit(const double d[4])
{
  double x = d[0] / 1000, y = d[1] / 1000, z = d[2] / 1000, a = d[3] / 1000;
  double l2 = x * x + y * y + z * z + a * a;
  if (l2 == 0)
    return MACH_AXIS_MAX;
  return MACH_AXIS_MAX * sqrt(l2 / (x * x + 36.0 * 36.0 * y * y + z * z + a * a));
}

/* ---- the trace observer: each call as a canonical event ---- */

static void report(const struct machine *m, struct canon_call *c)
{
  memcpy(c->pos, m->pos, sizeof c->pos);
  m->canon(m->canon_ctx, c);
}

static void report_move(const struct machine *m, const struct mach_path *along, const int64_t centre[2], double f)
{
  struct canon_call c = {.kind = along && along->arc ? CANON_FEED_ARC : CANON_FEED_LINE, .f = f};
  if (along && along->arc) {
    c.plane = along->plane;
    c.centre[0] = centre[0];
    c.centre[1] = centre[1];
    c.ccw = along->ccw;
  }
  report(m, &c);
}

/* ---- contour moves ---- */

static struct geom_arc arc_of(const struct machine *m, const struct mach_path *pa)
{
  int p, q;
  geom_plane_axes(pa->plane, &p, &q);
  struct geom_arc a = {(double)(pa->to[p] - m->pos[p]), (double)(pa->to[q] - m->pos[q]), pa->cp, pa->cq, pa->ccw};
  return a;
}

void mach_arc_shape(int plane, const struct geom_arc *a, double *len_mm, double *yshare)
{
  int p, q;
  geom_plane_axes(plane, &p, &q);
  *len_mm = geom_arc_length(a) / 1000.0;
  /* The tangent at angle t is (-sin t, cos t): its Y share is |sin t| when Y
   * is the plane's first axis and |cos t| when it is the second. */
  double s = 0, t0, dt;
  geom_arc_angles(a, &t0, &dt);
  if (p == AX_Y || q == AX_Y) {
    double c0 = p == AX_Y ? fabs(sin(t0)) : fabs(cos(t0));
    double c1 = p == AX_Y ? fabs(sin(t0 + dt)) : fabs(cos(t0 + dt));
    s = fmax(c0, c1);
    double crit[2] = {p == AX_Y ? M_PI / 2 : 0, p == AX_Y ? -M_PI / 2 : M_PI};
    for (int i = 0; i < 2; i++)
      if (geom_in_sweep(t0, dt, crit[i]))
        s = 1;   /* rule 16.3: the arc passes where its tangent is parallel to Y */
  }
  *yshare = s;
}

static double effective(const struct machine *m, double f)
{
  if (m->override_allowed)
    f = f * m->override_pct / 100.0;
  return f;
}

int mach_held(const struct machine *m, int moves)
{
  return moves && m->override_allowed && m->override_pct <= 0;
}

/* The path stays in the travel: the ends of a line; an arc's ends and the
 * points where it turns back on an axis.  0, or E-TRAVEL. */
int mach_check_travel(const struct machine *m, const struct mach_path *pa, char *msg, size_t n)
{
  const struct mach_travel *t = &m->travel;
  if (!(t->has[0] | t->has[1] | t->has[2] | t->has[3]))
    return 0;
  double lo[4], hi[4];
  for (int a = 0; a < 4; a++) {
    lo[a] = fmin((double)m->pos[a], (double)pa->to[a]);
    hi[a] = fmax((double)m->pos[a], (double)pa->to[a]);
  }
  if (pa->arc) {
    int p, q;
    geom_plane_axes(pa->plane, &p, &q);
    struct geom_arc a = arc_of(m, pa);
    double blo[2], bhi[2];
    geom_arc_box(&a, blo, bhi);
    lo[p] = fmin(lo[p], (double)m->pos[p] + blo[0]);
    hi[p] = fmax(hi[p], (double)m->pos[p] + bhi[0]);
    lo[q] = fmin(lo[q], (double)m->pos[q] + blo[1]);
    hi[q] = fmax(hi[q], (double)m->pos[q] + bhi[1]);
  }
  for (int a = 0; a < 4; a++) {
    if (!t->has[a])
      continue;
    double over = hi[a] > (double)t->hi[a] + 0.5 ? hi[a] : lo[a] < (double)t->lo[a] - 0.5 ? lo[a] : NAN;
    if (isnan(over))
      continue;
    snprintf(msg, n, "%c would reach %.3f %s, outside its travel %.3f .. %.3f (--machine)", mach_axes[a].name,
             over / 1000, mach_axes[a].unit, (double)t->lo[a] / 1000, (double)t->hi[a] / 1000);
    return S42_E_TRAVEL;
  }
  return 0;
}

int mach_check_path(const struct machine *m, const struct mach_path *pa, double f, char *msg, size_t n)
{
  double len = 0;
  if (!pa->arc) {
    for (int a = 0; a < 4; a++)
      len += (double)(pa->to[a] - m->pos[a]) * (double)(pa->to[a] - m->pos[a]);
  } else {
    struct geom_arc a = arc_of(m, pa);
    if (geom_arc_check(&a, MACH_ARC_RMAX, MACH_ARC_TOL, msg, n))
      return S42_E_ARC;
    len = geom_arc_length(&a);
  }
  if (len > 0 && f <= 0) {
    snprintf(msg, n, "a contour move with F = 0: give the speed with F");
    return S42_E_FEED;
  }
  return mach_check_travel(m, pa, msg, n);
}

int mach_check_spindle(const struct machine *m, int dir, char *msg, size_t n)
{
  if ((dir > 0 && m->wheel == WHEEL_CCW) || (dir < 0 && m->wheel == WHEEL_CW)) {
    snprintf(msg, n, "the wheel turns the other way: stop it first");
    return S42_E_WHEEL;
  }
  return 0;
}

void mach_spindle(struct machine *m, int dir)
{
  if (m->canon)
    report(m, &(struct canon_call){.kind = CANON_SPINDLE, .dir = dir > 0 ? 1 : dir < 0 ? -1 : 0});
  if (dir == 0) {
    if (m->wheel != WHEEL_OFF)
      mach_advance(m, MACH_WHEEL_RUNDOWN);
    m->wheel = WHEEL_OFF;
    return;
  }
  m->wheel = dir > 0 ? WHEEL_CW : WHEEL_CCW;
}

void mach_switch(struct machine *m, int sw, int on)
{
  if (sw == MACH_SW_CORR) {
    m->corr_allowed = on != 0;
    return;
  }
  if (m->canon && (on != 0) != (m->override_allowed != 0))
    report(m, &(struct canon_call){.kind = CANON_OVERRIDE, .on = on != 0});
  m->override_allowed = on != 0;
}

void mach_program_end(struct machine *m)
{
  if (m->canon)
    report(m, &(struct canon_call){.kind = CANON_END});
}

void mach_dwell(struct machine *m, double sec)
{
  if (m->canon)
    report(m, &(struct canon_call){.kind = CANON_DWELL, .v = sec});
  mach_advance(m, sec);
}

void mach_traverse_axis(struct machine *m, int axis, int64_t to, struct mach_out *o)
{
  int64_t d = to - m->pos[axis];
  mach_advance(m, fabs((double)d) / 1000.0 / mach_axis_max(axis) * 60.0);
  m->pos[axis] += d;
  o->d[axis] += d;
  if (m->canon)
    report(m, &(struct canon_call){.kind = CANON_TRAVERSE});
}

/* The move proper, its speed and time (no trace line). */
static void move(struct machine *m, const double d[4], double len, double limit, double f, struct mach_out *o);

void mach_feed(struct machine *m, const struct mach_path *pa, double f, struct mach_out *o)
{
  double d[4], len, lim;
  for (int a = 0; a < 4; a++)
    d[a] = (double)(pa->to[a] - m->pos[a]);
  if (!pa->arc) {
    len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + d[3] * d[3]) / 1000.0;
    lim = mach_linear_limit(d);
  } else {
    double ys;
    struct geom_arc ga = arc_of(m, pa);
    mach_arc_shape(pa->plane, &ga, &len, &ys);
    lim = MACH_AXIS_MAX / sqrt((1 - ys * ys) + 36.0 * 36.0 * ys * ys);
    /* only the plane's axes move along an arc */
    int p, q;
    geom_plane_axes(pa->plane, &p, &q);
    for (int a = 0; a < 4; a++)
      if (a != p && a != q)
        d[a] = 0;
  }
  mach_move_along(m, pa, d, len, lim, f, o);
  double lin2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  if (len > 0 && d[3] != 0 && lin2 > 0 && !pa->arc) {
    double ad = d[3] * M_PI * (pa->d1 / 1000.0) / 360.0;
    o->v = o->feed * sqrt((lin2 + ad * ad) / (lin2 + d[3] * d[3]));
    o->has_v = 1;
  }
}

void mach_move(struct machine *m, const double d[4], double len, double limit, double f, struct mach_out *o)
{
  mach_move_along(m, NULL, d, len, limit, f, o);
}

void mach_move_along(struct machine *m, const struct mach_path *along, const double d[4], double len, double limit,
                     double f, struct mach_out *o)
{
  int64_t centre[2] = {0, 0};
  if (along && along->arc) {
    int p, q;
    geom_plane_axes(along->plane, &p, &q);
    centre[0] = m->pos[p] + (int64_t)llround(along->cp);
    centre[1] = m->pos[q] + (int64_t)llround(along->cq);
  }
  move(m, d, len, limit, f, o);
  if (m->canon)
    report_move(m, along, centre, f);
}

static void move(struct machine *m, const double d[4], double len, double limit, double f, struct mach_out *o)
{
  double dt = 0, f0 = f;
  if (len > 0) {
    f = effective(m, f);
    o->feed = f < limit ? f : limit;
    if (o->feed > 0)
      dt = len / o->feed * 60.0;
  }
  m->mv.on = dt > 0 && m->override_allowed;
  m->mv.len = len;
  m->mv.limit = limit;
  m->mv.f = f0;
  m->mv.feed = o->feed;
  m->mv.t0 = m->t;
  mach_advance(m, dt);
  m->mv.t1 = m->t;
  for (int a = 0; a < 4; a++) {
    o->d[a] = (int64_t)llround(d[a]);
    m->pos[a] += o->d[a];
  }
}

int mach_in_move(const struct machine *m, double now)
{
  return m->mv.on && m->override_allowed && m->mv.feed > 0 && now >= m->mv.t0 && now < m->mv.t1;
}

double mach_override_at(struct machine *m, double now)
{
  if (m->override_pct <= 0 || !mach_in_move(m, now))
    return 0;
  double f = effective(m, m->mv.f);
  if (f > m->mv.limit)
    f = m->mv.limit;
  double rest = (m->mv.t1 - now) * m->mv.feed / 60.0;   /* mm still to go */
  double d = rest / f * 60.0 - (m->mv.t1 - now);
  m->mv.feed = f;
  m->mv.t1 += d;
  if (d > 0)
    mach_advance(m, d);    /* the time the slower rest adds passes as any other (oscillation goes on) */
  else
    m->t += d;
  return d;
}
