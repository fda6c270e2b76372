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

/* ---- the records it reports (src/core/canon.h) ---- */

/* A record of kind k begins: where the axes are and the time now. */
static struct canon_call begin(const struct machine *m, int k)
{
  struct canon_call c = canon_of(k);
  memcpy(c.from, m->pos, sizeof m->pos);
  c.t0 = m->t;
  return c;
}

static void report(const struct machine *m, struct canon_call *c)
{
  memcpy(c->pos, m->pos, sizeof m->pos);
  c->t1 = m->t;
  canon_report(&m->out, c);
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

static void spindle(struct machine *m, int dir)
{
  struct canon_call c = begin(m, CANON_SPINDLE);
  c.dir = dir > 0 ? 1 : dir < 0 ? -1 : 0;
  if (dir == 0) {
    if (m->wheel != WHEEL_OFF)
      mach_advance(m, MACH_WHEEL_RUNDOWN);
    m->wheel = WHEEL_OFF;
  } else {
    m->wheel = dir > 0 ? WHEEL_CW : WHEEL_CCW;
  }
  c.t1 = c.t0;   /* the run-down is the wheel's, not the call's (the record comes first, as LinuxCNC's) */
  memcpy(c.pos, m->pos, sizeof m->pos);
  canon_report(&m->out, &c);
}

static void override_switch(struct machine *m, int on)
{
  if ((on != 0) != (m->override_allowed != 0)) {
    struct canon_call c = begin(m, CANON_OVERRIDE);
    c.on = on != 0;
    report(m, &c);
  }
  m->override_allowed = on != 0;
}

static void dwell(struct machine *m, double sec)
{
  struct canon_call c = begin(m, CANON_DWELL);
  c.v = sec;
  mach_advance(m, sec);
  report(m, &c);
}

/* STRAIGHT_TRAVERSE of the axes in mask to `to` at their maximum speed,
 * together: the time is the slowest axis's (G37: Y home). */
static void traverse(struct machine *m, unsigned mask, const int64_t *to)
{
  struct canon_call c = begin(m, CANON_TRAVERSE);
  double dt = 0;
  for (int a = 0; a < 4; a++)
    if (mask & (1u << a)) {
      double ta = fabs((double)(to[a] - m->pos[a])) / 1000.0 / mach_axis_max(a) * 60.0;
      dt = ta > dt ? ta : dt;
    }
  mach_advance(m, dt);
  memset(&m->last, 0, sizeof m->last);
  for (int a = 0; a < 4; a++)
    if (mask & (1u << a)) {
      m->last.d[a] = to[a] - m->pos[a];
      m->pos[a] = to[a];
    }
  c.axes = mask;
  report(m, &c);
}

/* The move proper, its speed and time (no record). */
static void move(struct machine *m, const double d[4], double len, double limit, double f, struct mach_out *o);

static void move_along(struct machine *m, const struct mach_path *along, const double d[4], double len,
                       double limit, double f, struct mach_out *o);

static void feed(struct machine *m, const struct mach_path *pa, double f, struct mach_out *o)
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
  move_along(m, pa, d, len, lim, f, o);
}

/* The move, then its record: an ARC_FEED when it follows an arc (a helix:
 * the arc in its plane, the rest of d the other axes), else STRAIGHT_FEED. */
static void move_along(struct machine *m, const struct mach_path *along, const double d[4], double len,
                       double limit, double f, struct mach_out *o)
{
  struct canon_call c = begin(m, along && along->arc ? CANON_FEED_ARC : CANON_FEED_LINE);
  c.f = f;
  if (along && along->arc) {
    int p, q;
    geom_plane_axes(along->plane, &p, &q);
    c.plane = along->plane;
    c.centre[0] = m->pos[p] + (int64_t)llround(along->cp);
    c.centre[1] = m->pos[q] + (int64_t)llround(along->cq);
    c.ccw = along->ccw;
  }
  move(m, d, len, limit, f, o);
  c.feed = o->feed;
  report(m, &c);
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

void mach_displace(struct machine *m, int axis, int64_t d)
{
  if (axis >= 0 && axis < 4)
    m->pos[axis] += d;
}

/* ---- the canonical table (src/core/canon.h) ---- */

/* The contour path of a feed record: to its pos; an arc round the centre
 * (cp, cq) relative to the start, or the rounded centre when not given. */
static void path_of(const struct machine *m, const struct canon_call *c, struct mach_path *pa)
{
  memset(pa, 0, sizeof *pa);
  memcpy(pa->to, c->pos, sizeof pa->to);
  if (c->kind != CANON_FEED_ARC)
    return;
  int p, q;
  pa->arc = 1;
  pa->plane = c->plane >= 0 && c->plane <= 2 ? c->plane : GEOM_XY;
  geom_plane_axes(pa->plane, &p, &q);
  pa->cp = c->cp != 0 || c->cq != 0 ? c->cp : (double)(c->centre[0] - m->pos[p]);
  pa->cq = c->cp != 0 || c->cq != 0 ? c->cq : (double)(c->centre[1] - m->pos[q]);
  pa->ccw = c->ccw;
}

static int g_feed(void *mv, struct canon_call *c, char *msg, size_t n)
{
  struct machine *m = mv;
  struct mach_path pa;
  path_of(m, c, &pa);
  memset(&m->last, 0, sizeof m->last);
  if (c->len > 0 || c->limit > 0) {
    /* a plugin's own curve (the helix): its length and speed limit, the
     * travel checked by the caller along that curve */
    if (!isfinite(c->len) || c->len < 0 || !(c->limit > 0)) {
      snprintf(msg, n, "a contour move of length %g mm at a limit of %g mm/min", c->len, c->limit);
      return S42_E_FEED;
    }
    double d[4];
    for (int a = 0; a < 4; a++)
      d[a] = (double)(c->pos[a] - m->pos[a]);
    move_along(m, pa.arc ? &pa : NULL, d, c->len, c->limit < MACH_AXIS_MAX ? c->limit : MACH_AXIS_MAX, c->f,
               &m->last);
    return 0;
  }
  int e = mach_check_path(m, &pa, c->f, msg, n);
  if (e)
    return e;
  feed(m, &pa, c->f, &m->last);
  return 0;
}

static int g_traverse(void *mv, struct canon_call *c, char *msg, size_t n)
{
  struct machine *m = mv;
  unsigned mask = c->axes ? c->axes & 15u : 15u;
  struct mach_path pa;
  memset(&pa, 0, sizeof pa);
  for (int a = 0; a < 4; a++)
    pa.to[a] = mask & (1u << a) ? c->pos[a] : m->pos[a];
  int e = mach_check_travel(m, &pa, msg, n);
  if (e)
    return e;
  traverse(m, mask, pa.to);
  return 0;
}

static int g_dwell(void *mv, struct canon_call *c, char *msg, size_t n)
{
  if (!isfinite(c->v) || c->v < 0) {
    snprintf(msg, n, "a dwell of %g s", c->v);
    return S42_E_RANGE;
  }
  dwell(mv, c->v);
  return 0;
}

static int g_spindle(void *mv, struct canon_call *c, char *msg, size_t n)
{
  struct machine *m = mv;
  int e = c->dir ? mach_check_spindle(m, c->dir, msg, n) : 0;
  if (e)
    return e;
  spindle(m, c->dir);
  return 0;
}

static int g_override(void *mv, struct canon_call *c, char *msg, size_t n)
{
  (void)msg;
  (void)n;
  override_switch(mv, c->on);
  return 0;
}

static int g_switch(void *mv, struct canon_call *c, char *msg, size_t n)
{
  struct machine *m = mv;
  if (c->n != MACH_SW_CORR) {
    snprintf(msg, n, "the ВЗ-208Ф3 has no panel switch %d", c->n);
    return S42_E_FUNC;
  }
  m->corr_allowed = c->on != 0;
  return 0;
}

static int g_end(void *mv, struct canon_call *c, char *msg, size_t n)
{
  (void)msg;
  (void)n;
  struct machine *m = mv;
  *c = begin(m, CANON_END);
  report(m, c);
  return 0;
}

static void g_info(const void *mv, struct canon_info *in)
{
  const struct machine *m = mv;
  memset(in, 0, sizeof *in);
  in->kind = "grinder";
  in->name = "ВЗ-208Ф3";
  in->naxes = 4;
  for (int a = 0; a < 4; a++) {
    struct canon_axis *x = &in->axis[a];
    x->name = mach_axes[a].name;
    x->unit = mach_axes[a].unit;
    x->rotary = mach_axes[a].rotary;
    x->mm = 0.001;
    x->max_speed = mach_axes[a].max_speed;
    x->has_travel = m ? m->travel.has[a] : 0;
    x->lo = m ? m->travel.lo[a] : 0;
    x->hi = m ? m->travel.hi[a] : 0;
  }
}

const struct canon_ops grinder_ops = {
  .fn = {
    [CANON_FEED_LINE] = g_feed,
    [CANON_FEED_ARC] = g_feed,
    [CANON_TRAVERSE] = g_traverse,
    [CANON_DWELL] = g_dwell,
    [CANON_SPINDLE] = g_spindle,
    [CANON_OVERRIDE] = g_override,
    [CANON_SWITCH] = g_switch,
    [CANON_END] = g_end,
  },
  .info = g_info,
};
