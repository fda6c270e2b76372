/* The simulated machine (src/machine/grinder/machine.h). */
#include "machine.h"
#include "ast.h"
#include "errors.h"
#include "kp.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#define BIT(x, n) (((x) >> (n)) & 1)

void mach_init(struct machine *m)
{
  memset(m, 0, sizeof *m);
  m->override_pct = 100;
  m->override_allowed = 1;
}

double mach_axis_max(int axis)
{
  return axis == AX_Y ? MACH_Y_MAX : MACH_AXIS_MAX;
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

static void plane_axes(int plane, int *p, int *q)
{
  switch (plane) {
  case 17: *p = AX_X; *q = AX_Y; break;
  case 18: *p = AX_Y; *q = AX_Z; break;
  default: *p = AX_X; *q = AX_Z; break;
  }
}

/* Is angle t inside the sweep from t0 of signed length dt? */
static int in_sweep(double t0, double dt, double t)
{
  double rel = dt >= 0 ? t - t0 : t0 - t;
  rel = fmod(rel, 2 * M_PI);
  if (rel < 0)
    rel += 2 * M_PI;
  return rel <= fabs(dt) + 1e-12;
}

/* The start angle t0 and the signed sweep of an arc block (its geometry
 * checked by mach_arc). */
static void arc_angles(const struct mach_block *b, double *t0, double *dt)
{
  int p, q;
  plane_axes(b->plane, &p, &q);
  double ep = b->w[p], eq = b->w[q];
  double cp = b->w[SL_I + p], cq = b->w[SL_I + q];
  double a0 = atan2(-cq, -cp), a1 = atan2(eq - cq, ep - cp);
  int ccw = b->motion == MO_G03 || b->motion == MO_G13;
  double sweep;
  if (ep == 0 && eq == 0) {
    sweep = 2 * M_PI;
  } else {
    sweep = ccw ? a1 - a0 : a0 - a1;
    sweep = fmod(sweep, 2 * M_PI);
    if (sweep <= 0)
      sweep += 2 * M_PI;
  }
  *t0 = a0;
  *dt = ccw ? sweep : -sweep;
}

int mach_arc(const struct mach_block *b, double *len_mm, double *yshare, char *msg, size_t n)
{
  int p, q;
  plane_axes(b->plane, &p, &q);
  double ep = b->w[p], eq = b->w[q];
  double cp = b->w[SL_I + p], cq = b->w[SL_I + q];
  double r0 = hypot(cp, cq), r1 = hypot(ep - cp, eq - cq);
  if (r0 == 0) {
    snprintf(msg, n, "arc centre at its start point: radius 0");
    return S42_E_ARC;
  }
  if (r0 > 4000000.0 || r1 > 4000000.0) {
    snprintf(msg, n, "arc radius %.3f mm is over 4000 mm", fmax(r0, r1) / 1000);
    return S42_E_ARC;
  }
  if (fabs(r0 - r1) > 2.0) {
    snprintf(msg, n, "arc start radius %.0f µm and end radius %.0f µm differ by more than 2 µm", r0, r1);
    return S42_E_ARC;
  }
  double t0, dt;
  arc_angles(b, &t0, &dt);
  double sweep = fabs(dt);
  *len_mm = (r0 + r1) / 2 * sweep / 1000.0;
  /* The tangent at angle t is (-sin t, cos t): its Y share is |sin t| when Y
   * is the plane's first axis and |cos t| when it is the second. */
  double s = 0;
  if (p == AX_Y || q == AX_Y) {
    double c0 = p == AX_Y ? fabs(sin(t0)) : fabs(cos(t0));
    double c1 = p == AX_Y ? fabs(sin(t0 + dt)) : fabs(cos(t0 + dt));
    s = fmax(c0, c1);
    double crit[2] = {p == AX_Y ? M_PI / 2 : 0, p == AX_Y ? -M_PI / 2 : M_PI};
    for (int i = 0; i < 2; i++)
      if (in_sweep(t0, dt, crit[i]))
        s = 1;   /* rule 16.3: the arc passes where its tangent is parallel to Y */
  }
  *yshare = s;
  return 0;
}

static double effective(const struct machine *m, double f)
{
  if (m->override_allowed)
    f = f * m->override_pct / 100.0;
  return f;
}

static int contour(const struct mach_block *b)
{
  return b->motion == MO_G01 || b->motion == MO_G02 || b->motion == MO_G03;
}

int mach_held(const struct machine *m, const struct mach_block *b)
{
  if (!m->override_allowed || m->override_pct > 0)
    return 0;
  for (int a = 0; a < 4; a++)
    if (BIT(b->given, a) && b->w[a] != 0)
      return 1;
  return 0;
}

/* The block's path stays in the travel (language-independent: the ends of
 * a line; an arc's ends and the points where it turns back on an axis;
 * a helix's arc and the end of its rise).  0, or E-TRAVEL. */
static int travel_check(const struct machine *m, const struct mach_block *b, char *msg, size_t n)
{
  const struct mach_travel *t = &m->travel;
  if (!(t->has[0] | t->has[1] | t->has[2] | t->has[3]))
    return 0;
  int arc = b->motion == MO_G02 || b->motion == MO_G03 || b->motion == MO_G12 || b->motion == MO_G13;
  if (b->motion != MO_G01 && !arc)
    return 0;
  double lo[4], hi[4];
  for (int a = 0; a < 4; a++) {
    double e = (double)m->pos[a] + (BIT(b->given, a) ? b->w[a] : 0);
    lo[a] = fmin((double)m->pos[a], e);
    hi[a] = fmax((double)m->pos[a], e);
  }
  if (arc && b->plane) {
    int p, q;
    plane_axes(b->plane, &p, &q);
    double cp = (double)m->pos[p] + b->w[SL_I + p], cq = (double)m->pos[q] + b->w[SL_I + q];
    double r = hypot(b->w[SL_I + p], b->w[SL_I + q]), t0, dt;
    arc_angles(b, &t0, &dt);
    for (int k = 0; k < 4; k++) {
      double th = k * M_PI / 2;
      if (!in_sweep(t0, dt, th))
        continue;
      double x = cp + r * cos(th), y = cq + r * sin(th);
      lo[p] = fmin(lo[p], x); hi[p] = fmax(hi[p], x);
      lo[q] = fmin(lo[q], y); hi[q] = fmax(hi[q], y);
    }
  }
  for (int a = 0; a < 4; a++) {
    if (!t->has[a])
      continue;
    double over = hi[a] > (double)t->hi[a] + 0.5 ? hi[a] : lo[a] < (double)t->lo[a] - 0.5 ? lo[a] : NAN;
    if (isnan(over))
      continue;
    snprintf(msg, n, "%c would reach %.3f %s, outside its travel %.3f .. %.3f (--machine)", "XYZA"[a], over / 1000,
             a == 3 ? "deg" : "mm", (double)t->lo[a] / 1000, (double)t->hi[a] / 1000);
    return S42_E_TRAVEL;
  }
  return 0;
}

int mach_check(const struct machine *m, const struct mach_block *b, char *msg, size_t n)
{
  if (BIT(b->m, 3) && m->wheel == WHEEL_CCW) {
    snprintf(msg, n, "M3 while the wheel turns counter-clockwise: stop it with M5 first");
    return S42_E_WHEEL;
  }
  if (BIT(b->m, 4) && m->wheel == WHEEL_CW) {
    snprintf(msg, n, "M4 while the wheel turns clockwise: stop it with M5 first");
    return S42_E_WHEEL;
  }
  if (contour(b)) {
    double len = 0, ys;
    if (b->motion == MO_G01) {
      for (int a = 0; a < 4; a++)
        len += b->w[a] * b->w[a];
    } else {
      int e = mach_arc(b, &len, &ys, msg, n);
      if (e)
        return e;
    }
    if (len > 0 && b->f <= 0) {
      snprintf(msg, n, "a contour move with F = 0: give the speed with F");
      return S42_E_FEED;
    }
  }
  return travel_check(m, b, msg, n);
}

void mach_modal(struct machine *m, const struct mach_block *b)
{
  if (BIT(b->m, 5)) {
    if (m->wheel != WHEEL_OFF)
      mach_advance(m, MACH_WHEEL_RUNDOWN);
    m->wheel = WHEEL_OFF;
  }
  if (BIT(b->m, 3))
    m->wheel = WHEEL_CW;
  if (BIT(b->m, 4))
    m->wheel = WHEEL_CCW;
  if (BIT(b->m, 22)) m->corr_allowed = 1;
  if (BIT(b->m, 23)) m->corr_allowed = 0;
  if (BIT(b->m, 25)) m->override_allowed = 0;
  if (BIT(b->m, 26)) m->override_allowed = 1;
}

void mach_move(struct machine *m, const double d[4], double len, double limit, double f, struct mach_out *o)
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

double mach_override_at(struct machine *m, double now)
{
  if (!m->mv.on || !m->override_allowed || m->override_pct <= 0 || now < m->mv.t0 || now >= m->mv.t1 ||
      m->mv.feed <= 0)
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

void mach_motion(struct machine *m, const struct mach_block *b, struct mach_out *o)
{
  memset(o, 0, sizeof *o);
  if (contour(b)) {
    double d[4] = {0, 0, 0, 0};
    for (int a = 0; a < 4; a++)
      if (BIT(b->given, a))
        d[a] = b->w[a];
    double len, lim;
    if (b->motion == MO_G01) {
      len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + d[3] * d[3]) / 1000.0;
      lim = mach_linear_limit(d);
    } else {
      double ys;
      char msg[8];
      mach_arc(b, &len, &ys, msg, sizeof msg);
      lim = MACH_AXIS_MAX / sqrt((1 - ys * ys) + 36.0 * 36.0 * ys * ys);
      /* only the plane's axes move along an arc */
      int p, q;
      plane_axes(b->plane, &p, &q);
      for (int a = 0; a < 4; a++)
        if (a != p && a != q)
          d[a] = 0;
    }
    mach_move(m, d, len, lim, b->f, o);
    double lin2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (len > 0 && d[3] != 0 && lin2 > 0 && b->motion == MO_G01) {
      double ad = d[3] * M_PI * (b->d1 / 1000.0) / 360.0;
      o->v = o->feed * sqrt((lin2 + ad * ad) / (lin2 + d[3] * d[3]));
      o->has_v = 1;
    }
  } else if (b->motion == MO_G04) {
    mach_advance(m, b->w[SL_X] / 10.0);
  } else if (b->motion == MO_G37) {
    int64_t dy = -m->pos[AX_Y];
    mach_advance(m, fabs((double)dy) / 1000.0 / MACH_Y_MAX * 60.0);
    m->pos[AX_Y] += dy;
    o->d[AX_Y] = dy;
  }
}
