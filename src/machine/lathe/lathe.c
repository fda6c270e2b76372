/* The simulated 16Б16Ф3 lathe (src/machine/lathe/lathe.h): positions,
 * travel, feeds and their limits, arcs, threads, the spindle and its
 * ranges, constant cutting speed, tools, coolant and simulated time. */
#include "lathe.h"
#include "canon.h"
#include "errors.h"
#include "geom.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const double lathe_range_lo[3] = {45, 45, 224}, lathe_range_hi[3] = {1800, 280, 1800};

/* mm per count of X Y Z A in a canonical call: X counts the diameter and
 * prints the radius (LinuxCNC's G7). */
static const double canon_mm[4] = {0.0005, 0.001, 0.001, 0.001};

/* Pieces of a move whose spindle speed varies along it (G96). */
#define PIECES 64

static const char *const axis_name[2] = {"X", "Z"};

/* ---- small helpers ---- */

static void say(char *msg, size_t n, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void say(char *msg, size_t n, const char *fmt, ...)
{
  if (!msg || n == 0)
    return;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, n, fmt, ap);
  va_end(ap);
}

/* A number for a message: at most `dec` decimals, trailing zeros dropped. */
static const char *num(char *buf, size_t n, double v, int dec)
{
  if (isnan(v)) {
    snprintf(buf, n, "nan");
    return buf;
  }
  if (isinf(v)) {
    snprintf(buf, n, v > 0 ? "inf" : "-inf");
    return buf;
  }
  snprintf(buf, n, "%.*f", dec, v);
  if (strchr(buf, '.')) {
    char *e = buf + strlen(buf) - 1;
    while (*e == '0')
      *e-- = 0;
    if (*e == '.')
      *e = 0;
  }
  if (strcmp(buf, "-0") == 0)
    snprintf(buf, n, "0");
  return buf;
}

static void warn(const struct lathe *l, const char *text)
{
  if (l->warn && text[0])
    l->warn(l->warn_ctx, text);
}

static const struct lathe_tool *cur_tool(const struct lathe *l)
{
  static const struct lathe_tool none = {0, {0, 0}};
  if (l->tool <= 0 || l->tool >= LATHE_TOOLS || !l->tools[l->tool].has)
    return &none;
  return &l->tools[l->tool];
}

int64_t lathe_pos(const struct lathe *l, int axis)
{
  if (axis != LX && axis != LZ)
    return 0;
  return l->slide[axis] + cur_tool(l)->d[axis] - l->zero[axis];
}

static void emit_at(const struct lathe *l, struct canon_call *c, int kind)
{
  if (!l->canon)
    return;
  c->kind = kind;
  c->pos[0] = lathe_pos(l, LX);
  c->pos[1] = 0;
  c->pos[2] = lathe_pos(l, LZ);
  c->pos[3] = 0;
  c->mm = canon_mm;
  l->canon(l->canon_ctx, c);
}

static void emit(const struct lathe *l, int kind)
{
  struct canon_call c;
  memset(&c, 0, sizeof c);
  emit_at(l, &c, kind);
}

static int spindle_turns(const struct lathe *l)
{
  return l->dir != 0 && l->s > 0;
}

double lathe_rpm(const struct lathe *l, int64_t d)
{
  if (!spindle_turns(l))
    return 0;
  int r = l->range >= 0 && l->range <= 2 ? l->range : 0;
  if (!l->css)
    return l->s;
  double dmm = fabs((double)d) / 1000, rpm = dmm > 0 ? 1000 * l->s / (M_PI * dmm) : lathe_range_hi[r];
  return fmin(fmax(rpm, lathe_range_lo[r]), lathe_range_hi[r]);
}

/* After every call: the spindle's speed where the tip is now. */
static void settle(struct lathe *l)
{
  l->rpm_now = lathe_rpm(l, lathe_pos(l, LX));
}

/* ---- power-on, zeros ---- */

void lathe_init(struct lathe *l)
{
  memset(l, 0, sizeof *l);   /* slides and part zero at 0, no tools, T0, G94 G97, time 0 */
  l->lo[LX] = -2 * (int64_t)LATHE_TRAVEL_X;
  l->hi[LX] = 2 * (int64_t)LATHE_TRAVEL_X;
  l->lo[LZ] = -(int64_t)LATHE_TRAVEL_Z;
  l->hi[LZ] = LATHE_TRAVEL_Z;
}

void lathe_set_zero(struct lathe *l, int64_t ox, int64_t oz)
{
  l->zero[LX] = ox;
  l->zero[LZ] = oz;
  settle(l);
}

/* ---- travel ---- */

static int travel_msg(const struct lathe *l, int a, double v, char *msg, size_t n)
{
  char b0[40], b1[40], b2[40];
  /* mm of the slide in machine coordinates; X as a diameter, as everywhere */
  snprintf(b0, sizeof b0, "%.2f", v / 1000);
  snprintf(b1, sizeof b1, "%.2f", (double)l->lo[a] / 1000);
  snprintf(b2, sizeof b2, "%.2f", (double)l->hi[a] / 1000);
  say(msg, n, "%s %s mm%s is outside the travel %s..%s mm", axis_name[a], b0, a == LX ? " (diameter)" : "", b1, b2);
  return S42_E_TRAVEL;
}

/* The slides' targets for tip positions `to` (part coordinates) of the axes
 * in mask; the others stay.  0, or E-TRAVEL (an overflow is outside too). */
static int targets(const struct lathe *l, unsigned mask, const int64_t to[2], int64_t s[2], char *msg, size_t n)
{
  const struct lathe_tool *t = cur_tool(l);
  for (int a = 0; a < 2; a++) {
    s[a] = l->slide[a];
    if (!(mask & (1u << a)))
      continue;
    int64_t v;
    if (__builtin_add_overflow(to[a], l->zero[a], &v) || __builtin_sub_overflow(v, t->d[a], &v))
      return travel_msg(l, a, (double)to[a] + (double)l->zero[a] - (double)t->d[a], msg, n);
    if (v < l->lo[a] || v > l->hi[a])
      return travel_msg(l, a, (double)v, msg, n);
    s[a] = v;
  }
  return 0;
}

/* ---- feed: the speed a move may have, and its time ---- */

/* A feed move's geometry on the slides: its length (mm), the largest share
 * of the path speed each slide takes anywhere on it (X of the slide, so of
 * the radius), and the tip's diameter (µm, part coordinates) at the middle
 * of each of PIECES equal pieces (used under G96 only). */
struct path {
  double len, xs, zs;
  double dia[PIECES];
};

static void line_path(const struct lathe *l, const int64_t s[2], struct path *p)
{
  double dx = (double)(s[LX] - l->slide[LX]) / 2000, dz = (double)(s[LZ] - l->slide[LZ]) / 1000;
  p->len = hypot(dx, dz);
  p->xs = p->len > 0 ? fabs(dx) / p->len : 0;
  p->zs = p->len > 0 ? fabs(dz) / p->len : 0;
  double x0 = (double)lathe_pos(l, LX), dd = (double)(s[LX] - l->slide[LX]);
  for (int i = 0; i < PIECES; i++)
    p->dia[i] = x0 + dd * (i + 0.5) / PIECES;
}

static int feed_ok(const struct lathe *l, double f, char *msg, size_t n)
{
  char b[40];
  if (isnan(f)) {
    say(msg, n, "feed is not a number");
    return S42_E_FEED;
  }
  if (isinf(f)) {
    say(msg, n, "feed is infinite");
    return S42_E_FEED;
  }
  if (f == 0) {
    say(msg, n, "a feed move with F 0: give the feed with F");
    return S42_E_FEED;
  }
  if (f < 0) {
    say(msg, n, "feed F%s is negative", num(b, sizeof b, f, 4));
    return S42_E_FEED;
  }
  if (l->per_rev && !spindle_turns(l)) {
    say(msg, n, "feed per revolution with the spindle stopped");
    return S42_E_FEED;
  }
  return 0;
}

/* The time (s) and the mean path speed (mm/min) of a path at F, the speed
 * cut so that neither slide passes its working-feed limit; the warning
 * for a cut goes to wmsg ("" when none).  0, or E-FEED when the time
 * would not be finite. */
static int feed_time(const struct lathe *l, double f, const struct path *p, double *sec, double *vmean, char *wmsg,
                     size_t wn, char *msg, size_t n)
{
  double cx = p->xs > 0 ? LATHE_FEED_X / p->xs : INFINITY, cz = p->zs > 0 ? LATHE_FEED_Z / p->zs : INFINITY;
  double cap = fmin(cx, cz);
  int by_x = cx <= cz;
  double vreq_max, v_at_max, rpm_at_max, t = 0;
  wmsg[0] = 0;
  if (l->per_rev && l->css) {
    vreq_max = -1;
    v_at_max = 0;
    rpm_at_max = 0;
    for (int i = 0; i < PIECES; i++) {
      double rpm = lathe_rpm(l, (int64_t)llround(p->dia[i])), vreq = f * rpm, v = fmin(vreq, cap);
      t += p->len / PIECES / v;
      if (vreq > vreq_max) {
        vreq_max = vreq;
        v_at_max = v;
        rpm_at_max = rpm;
      }
    }
  } else {
    rpm_at_max = l->per_rev ? lathe_rpm(l, lathe_pos(l, LX)) : 0;
    vreq_max = l->per_rev ? f * rpm_at_max : f;
    v_at_max = fmin(vreq_max, cap);
    t = p->len / v_at_max;
  }
  if (p->len == 0)
    t = 0;
  if (!isfinite(t) || !(v_at_max > 0)) {
    char b[40];
    say(msg, n, "feed F%s is too small for a move of %.3f mm", num(b, sizeof b, f, 6), p->len);
    return S42_E_FEED;
  }
  *sec = t * 60;
  *vmean = t > 0 ? p->len / t : v_at_max;
  if (vreq_max > cap) {
    char bf[40], bv[40], bc[40], br[40];
    const char *lim = by_x ? "X slide at most 1200 mm/min" : "Z at most 2400 mm/min";
    if (l->per_rev)
      say(wmsg, wn, "F%s mm/rev = %s mm/min at %s rpm, cut to %s mm/min: %s", num(bf, sizeof bf, f, 4),
          num(bv, sizeof bv, vreq_max, 1), num(br, sizeof br, rpm_at_max, 1), num(bc, sizeof bc, v_at_max, 1), lim);
    else
      say(wmsg, wn, "F%s cut to %s mm/min: %s", num(bf, sizeof bf, f, 4), num(bc, sizeof bc, v_at_max, 1), lim);
  }
  return 0;
}

/* ---- motion ---- */

int lathe_traverse(struct lathe *l, unsigned mask, const int64_t to[2], char *msg, size_t n)
{
  int64_t s[2];
  mask &= 3u;
  if (!mask)
    return 0;
  int e = targets(l, mask, to, s, msg, n);
  if (e)
    return e;
  double tx = fabs((double)(s[LX] - l->slide[LX])) / 2000 / LATHE_RAPID_X;
  double tz = fabs((double)(s[LZ] - l->slide[LZ])) / 1000 / LATHE_RAPID_Z;
  l->slide[LX] = s[LX];
  l->slide[LZ] = s[LZ];
  l->t += fmax(tx, tz) * 60;
  settle(l);
  emit(l, CANON_TRAVERSE);
  return 0;
}

int lathe_home(struct lathe *l, unsigned mask, char *msg, size_t n)
{
  mask &= 3u;
  if (!mask)
    return 0;
  /* the tip positions that put the named slides at machine zero */
  const struct lathe_tool *t = cur_tool(l);
  int64_t to[2];
  for (int a = 0; a < 2; a++) {
    if (!(mask & (1u << a))) {
      to[a] = 0;
      continue;
    }
    if (0 < l->lo[a] || 0 > l->hi[a])
      return travel_msg(l, a, 0, msg, n);
    to[a] = t->d[a] - l->zero[a];   /* slide 0: tip = 0 + d - zero */
  }
  /* no overflow possible in targets(): to + zero - d = 0 */
  return lathe_traverse(l, mask, to, msg, n);
}

/* A feed move along path p to the slides s, timed at f: the slides, the
 * time, the feed and the warning of a cut feed, then the canonical call c
 * (its kind and its own members set by the caller). */
static int feed_move(struct lathe *l, double f, const struct path *p, const int64_t s[2], struct canon_call *c,
                     int kind, char *msg, size_t n)
{
  double sec, v;
  char w[200];
  int e = feed_time(l, f, p, &sec, &v, w, sizeof w, msg, n);
  if (e)
    return e;
  l->slide[LX] = s[LX];
  l->slide[LZ] = s[LZ];
  l->t += sec;
  l->feed = v;
  l->f_canon = f;
  settle(l);
  warn(l, w);
  c->f = f;
  emit_at(l, c, kind);
  return 0;
}

int lathe_feed_line(struct lathe *l, const int64_t to[2], double f, char *msg, size_t n)
{
  int64_t s[2];
  int e = feed_ok(l, f, msg, n);
  if (!e)
    e = targets(l, 3u, to, s, msg, n);
  if (e)
    return e;
  struct path p;
  line_path(l, s, &p);
  struct canon_call c;
  memset(&c, 0, sizeof c);
  return feed_move(l, f, &p, s, &c, CANON_FEED_LINE, msg, n);
}

/* The arc in the geometry's terms: radius space (X halved), relative to the
 * start, p = X and q = Z; geom's ccw turns from X to Z, LinuxCNC's G2 in
 * G18 (whose first axis is Z): so ccw = G02. */
static void arc_geom(const struct lathe *l, const int64_t to[2], const int64_t c[2], int cw, struct geom_arc *g)
{
  double x0 = (double)lathe_pos(l, LX), z0 = (double)lathe_pos(l, LZ);
  g->ep = ((double)to[LX] - x0) / 2;
  g->eq = (double)to[LZ] - z0;
  g->cp = ((double)c[LX] - x0) / 2;
  g->cq = (double)c[LZ] - z0;
  g->ccw = cw != 0;
}

static int arc_check(const struct lathe *l, const int64_t to[2], const int64_t c[2], const struct geom_arc *g,
                     char *msg, size_t n)
{
  char b0[40], b1[40];
  if (to[LX] == lathe_pos(l, LX) && to[LZ] == lathe_pos(l, LZ)) {
    say(msg, n, "arc ends where it starts: a full circle is more than one quadrant");
    return S42_E_ARC;
  }
  double r0, r1;
  geom_arc_radii(g, &r0, &r1);
  if (r0 == 0 || r1 == 0) {
    say(msg, n, "arc centre at its %s point: radius 0", r0 == 0 ? "start" : "end");
    return S42_E_ARC;
  }
  if (!(fabs(r0 - r1) <= LATHE_ARC_TOL)) {
    say(msg, n, "arc start radius %.3f mm and end radius %.3f mm differ by more than %s mm", r0 / 1000, r1 / 1000,
        num(b0, sizeof b0, LATHE_ARC_TOL / 1000.0, 3));
    return S42_E_ARC;
  }
  /* One quadrant at most: no line through the centre parallel to an axis
   * (angle 0, pi: the line Z = Zc; pi/2, 3pi/2: X = Xc) strictly inside the
   * sweep.  A point within LATHE_ARC_TOL µm of such a line (at most 0.01
   * rad) counts as on it, for the ends' rounding. */
  double t0, dt, eps = fmin(LATHE_ARC_TOL / fmax(r0, r1), 0.01);
  geom_arc_angles(g, &t0, &dt);
  for (int k = 0; k < 4; k++) {
    double a = k * M_PI / 2, rel = fmod(dt >= 0 ? a - t0 : t0 - a, 2 * M_PI);
    if (rel < 0)
      rel += 2 * M_PI;
    if (rel > eps && rel < fabs(dt) - eps) {
      if (k % 2 == 0)
        say(msg, n, "arc goes past Z %s mm of its centre: one quadrant at most (%s degrees)",
            num(b0, sizeof b0, (double)c[LZ] / 1000, 3), num(b1, sizeof b1, fabs(dt) * 180 / M_PI, 1));
      else
        say(msg, n, "arc goes past X %s mm (diameter) of its centre: one quadrant at most (%s degrees)",
            num(b0, sizeof b0, (double)c[LX] / 1000, 3), num(b1, sizeof b1, fabs(dt) * 180 / M_PI, 1));
      return S42_E_ARC;
    }
  }
  return 0;
}

/* The arc as a path: its length on the slides (radius space) and the
 * largest share of the path speed each slide takes on it.  Within one
 * quadrant a slide's share (X |sin|, Z |cos| of the angle from the X line
 * through the centre) changes monotonically, so the larger of the two
 * ends' is the largest anywhere: the speed is held constant at what that
 * worst point allows (conservative: no slide ever passes its limit). */
static void arc_path(const struct lathe *l, const struct geom_arc *g, struct path *p)
{
  double t0, dt, r0, r1;
  geom_arc_angles(g, &t0, &dt);
  geom_arc_radii(g, &r0, &r1);
  p->len = geom_arc_length(g) / 1000;
  double t1 = t0 + dt;
  p->xs = fmax(fabs(sin(t0)), fabs(sin(t1)));
  p->zs = fmax(fabs(cos(t0)), fabs(cos(t1)));
  double x0 = (double)lathe_pos(l, LX);
  for (int i = 0; i < PIECES; i++) {
    double pp, qq;
    geom_arc_point(g, (i + 0.5) / PIECES, &pp, &qq);
    p->dia[i] = x0 + 2 * pp;
  }
}

int lathe_feed_arc(struct lathe *l, const int64_t to[2], const int64_t c[2], int cw, double f, char *msg, size_t n)
{
  struct geom_arc g;
  arc_geom(l, to, c, cw, &g);
  int e = arc_check(l, to, c, &g, msg, n);
  if (!e)
    e = feed_ok(l, f, msg, n);
  int64_t s[2];
  if (!e)
    e = targets(l, 3u, to, s, msg, n);
  if (e)
    return e;
  /* the box the arc stays in (its ends and any quadrant point on it) */
  double lo[2], hi[2];
  geom_arc_box(&g, lo, hi);
  double sx0 = (double)l->slide[LX], sz0 = (double)l->slide[LZ];
  double bx[2] = {sx0 + 2 * lo[0], sx0 + 2 * hi[0]}, bz[2] = {sz0 + lo[1], sz0 + hi[1]};
  for (int i = 0; i < 2; i++) {
    if (bx[i] < (double)l->lo[LX] - 0.5 || bx[i] > (double)l->hi[LX] + 0.5)
      return travel_msg(l, LX, bx[i], msg, n);
    if (bz[i] < (double)l->lo[LZ] - 0.5 || bz[i] > (double)l->hi[LZ] + 0.5)
      return travel_msg(l, LZ, bz[i], msg, n);
  }
  struct path p;
  arc_path(l, &g, &p);
  struct canon_call cc;
  memset(&cc, 0, sizeof cc);
  cc.plane = GEOM_XZ;
  cc.centre[0] = c[LX];
  cc.centre[1] = c[LZ];
  cc.ccw = cw != 0;   /* canon's ccw turns from X to Z: LinuxCNC's G2 in G18 (the sink prints -1) */
  return feed_move(l, f, &p, s, &cc, CANON_FEED_ARC, msg, n);
}

int lathe_thread(struct lathe *l, const int64_t to[2], double k, char *msg, size_t n)
{
  char b0[40], b1[40];
  if (isnan(k) || !(k > 0)) {
    say(msg, n, "G33 without a pitch: K must be more than 0");
    return S42_E_THREAD;
  }
  if (k > LATHE_PITCH_MAX) {
    say(msg, n, "G33 pitch %s mm is over the %s mm the machine cuts", num(b0, sizeof b0, k / 1000, 3),
        num(b1, sizeof b1, LATHE_PITCH_MAX / 1000.0, 3));
    return S42_E_THREAD;
  }
  if (!spindle_turns(l)) {
    say(msg, n, "G33 with the spindle stopped");
    return S42_E_THREAD;
  }
  int64_t s[2];
  int e = targets(l, 3u, to, s, msg, n);
  if (e)
    return e;
  if (s[LZ] == l->slide[LZ]) {
    say(msg, n, "G33 without a Z move: the pitch runs along Z");
    return S42_E_THREAD;
  }
  struct path p;
  line_path(l, s, &p);
  double dz = fabs((double)(s[LZ] - l->slide[LZ])) / 1000, xr = p.xs / p.zs;   /* X slide mm per mm of Z */
  /* Z speed = pitch * rpm, piece by piece when G96 varies the rpm */
  double zmax = 0, rpm_max = 0, t = 0;
  for (int i = 0; i < (l->css ? PIECES : 1); i++) {
    double rpm = l->css ? lathe_rpm(l, (int64_t)llround(p.dia[i])) : lathe_rpm(l, lathe_pos(l, LX));
    double vz = k / 1000 * rpm;
    if (vz > zmax) {
      zmax = vz;
      rpm_max = rpm;
    }
    t += (l->css ? dz / PIECES : dz) / vz;
  }
  if (zmax > LATHE_FEED_Z) {
    say(msg, n, "G33 needs Z %s mm/min at %s rpm: more than the 2400 mm/min it can keep synchronised",
        num(b0, sizeof b0, zmax, 1), num(b1, sizeof b1, rpm_max, 1));
    return S42_E_THREAD;
  }
  if (zmax * xr > LATHE_FEED_X) {
    say(msg, n, "G33 taper needs the X slide at %s mm/min: more than its 1200 mm/min", num(b0, sizeof b0, zmax * xr, 1));
    return S42_E_THREAD;
  }
  if (!isfinite(t)) {
    say(msg, n, "G33 too slow to finish");
    return S42_E_THREAD;
  }
  struct canon_call c;
  memset(&c, 0, sizeof c);
  c.v = k / 1000;
  emit_at(l, &c, CANON_SYNCH_START);
  l->slide[LX] = s[LX];
  l->slide[LZ] = s[LZ];
  l->t += t * 60;
  l->feed = t > 0 ? p.len / t : 0;
  settle(l);
  memset(&c, 0, sizeof c);
  c.f = l->f_canon;   /* the feed rate stays as it was (LinuxCNC prints none for G33) */
  emit_at(l, &c, CANON_FEED_LINE);
  emit(l, CANON_SYNCH_STOP);
  return 0;
}

void lathe_dwell(struct lathe *l, double sec)
{
  if (!(sec > 0) || !isfinite(sec))
    sec = 0;
  l->t += sec;
  settle(l);
  struct canon_call c;
  memset(&c, 0, sizeof c);
  c.v = sec;
  emit_at(l, &c, CANON_DWELL);
}

/* ---- the spindle ---- */

/* S in rpm clamped into the range in force; the warning when it moved. */
static double clamp_rpm(const struct lathe *l, double s, int say_it)
{
  if (s == 0)
    return 0;
  int r = l->range >= 0 && l->range <= 2 ? l->range : 0;
  double c = fmin(fmax(s, lathe_range_lo[r]), lathe_range_hi[r]);
  if (c != s && say_it) {
    char b0[40], b1[40], b2[40], b3[40], w[200];
    num(b0, sizeof b0, s, 3);
    num(b1, sizeof b1, c, 3);
    num(b2, sizeof b2, lathe_range_lo[r], 0);
    num(b3, sizeof b3, lathe_range_hi[r], 0);
    if (r == 0)
      snprintf(w, sizeof w, "S%s clamped to %s rpm: no range is selected, %s..%s", b0, b1, b2, b3);
    else
      snprintf(w, sizeof w, "S%s clamped to %s rpm: range %d is %s..%s", b0, b1, r, b2, b3);
    warn(l, w);
  }
  return c;
}

static void set_s(struct lathe *l, double s)
{
  if (s != l->s) {
    l->s = s;
    struct canon_call c;
    memset(&c, 0, sizeof c);
    c.v = s;
    emit_at(l, &c, CANON_SPINDLE_SPEED);
  }
  settle(l);
}

void lathe_speed(struct lathe *l, double s)
{
  if (isnan(s) || isinf(s) || s < 0) {
    char b[40], w[100];
    snprintf(w, sizeof w, "S%s refused: S is 0 or more", num(b, sizeof b, s, 3));
    warn(l, w);
    settle(l);
    return;
  }
  set_s(l, l->css ? s : clamp_rpm(l, s, 1));
}

void lathe_range(struct lathe *l, int range)
{
  if (range < 0 || range > 2) {
    char w[80];
    snprintf(w, sizeof w, "spindle range %d refused: 0, 1 or 2", range);
    warn(l, w);
    settle(l);
    return;
  }
  l->range = range;
  set_s(l, l->css ? l->s : clamp_rpm(l, l->s, 1));
}

void lathe_css(struct lathe *l, int on)
{
  on = on != 0;
  if (on == l->css) {
    settle(l);
    return;
  }
  l->css = on;
  /* G97 after G96: the S in force is rpm again, and must fit the range */
  set_s(l, on ? l->s : clamp_rpm(l, l->s, 1));
}

void lathe_spindle(struct lathe *l, int dir)
{
  dir = dir > 0 ? 1 : dir < 0 ? -1 : 0;
  if (dir != l->dir) {
    l->dir = dir;
    settle(l);   /* rpm_now, before the event */
    struct canon_call c;
    memset(&c, 0, sizeof c);
    c.dir = dir;
    emit_at(l, &c, CANON_SPINDLE);
  }
  settle(l);
}

/* ---- modes, tool, coolant, end ---- */

void lathe_feed_mode(struct lathe *l, int per_rev)
{
  per_rev = per_rev != 0;
  if (per_rev != l->per_rev) {
    l->per_rev = per_rev;
    l->f_canon = 0;   /* a switch cancels F (L672); the sink prints SET_FEED_RATE(0) */
    struct canon_call c;
    memset(&c, 0, sizeof c);
    c.on = per_rev;
    emit_at(l, &c, CANON_FEED_MODE);
  }
  settle(l);
}

void lathe_tool(struct lathe *l, int t)
{
  if (t < 0 || t >= LATHE_TOOLS) {
    char w[80];
    snprintf(w, sizeof w, "T%d refused: tools are T0..T%d", t, LATHE_TOOLS - 1);
    warn(l, w);
    settle(l);
    return;
  }
  l->tool = t;
  settle(l);
  struct canon_call c;
  memset(&c, 0, sizeof c);
  c.dir = t;
  emit_at(l, &c, CANON_TOOL);
}

void lathe_coolant(struct lathe *l, int on)
{
  on = on != 0;
  if (on != l->coolant) {
    l->coolant = on;
    struct canon_call c;
    memset(&c, 0, sizeof c);
    c.on = on;
    emit_at(l, &c, CANON_COOLANT);
  }
  settle(l);
}

void lathe_end(struct lathe *l)
{
  lathe_spindle(l, 0);
  lathe_coolant(l, 0);
  settle(l);
  emit(l, CANON_END);
}
