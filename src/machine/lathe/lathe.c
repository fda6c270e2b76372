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

const struct lathe_model lathe_16b16f3 = {
  .name = "16Б16Ф3",
  .feed_x = 1200, .feed_z = 2400,
  .rapid_x = 5000, .rapid_z = 10000,
  .travel_x = 225000, .travel_z = 650000,
  .arc_tol = 10,
  .pitch_max = 40000,             /* sec. 1, L110-111 */
  .nranges = 2,                   /* M38 45..280, M39 224..1800; none selected 45..1800 (D-30) */
  .range_lo = {45, 45, 224},
  .range_hi = {1800, 280, 1800},
};

/* mm per count of each axis in a canonical call: X counts the diameter and
 * prints the radius (LinuxCNC's G7). */
static const double canon_mm[CANON_AXES] = {0.0005, 0.001, 0.001, 0.001, 0.001, 0.001};

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
  canon_warn(&l->out, text);
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

/* The tip in canonical counts: X (a diameter) and Z. */
static void tip(const struct lathe *l, int64_t p[CANON_AXES])
{
  memset(p, 0, CANON_AXES * sizeof *p);
  p[0] = lathe_pos(l, LX);
  p[2] = lathe_pos(l, LZ);
}

/* A record of kind k is reported: where the tip was (from, at t0: the
 * caller's c->from and c->t0, set by start()) and is now. */
static void emit_at(const struct lathe *l, struct canon_call *c, int kind)
{
  if (!l->out.call)
    return;
  c->kind = kind;
  tip(l, c->pos);
  c->t1 = l->t;
  c->mm = canon_mm;
  canon_report(&l->out, c);
}

/* Where a record starts: the tip and the time before the call. */
static void start(const struct lathe *l, struct canon_call *c)
{
  memset(c, 0, sizeof *c);
  tip(l, c->from);
  c->t0 = l->t;
}

static void emit(const struct lathe *l, int kind)
{
  struct canon_call c;
  start(l, &c);
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
  int r = l->range >= 0 && l->range <= l->model.nranges ? l->range : 0;
  if (!l->css)
    return l->s;
  double dmm = fabs((double)d) / 1000, rpm = dmm > 0 ? 1000 * l->s / (M_PI * dmm) : l->model.range_hi[r];
  return fmin(fmax(rpm, l->model.range_lo[r]), l->model.range_hi[r]);
}

/* After every call: the spindle's speed where the tip is now. */
static void settle(struct lathe *l)
{
  l->rpm_now = lathe_rpm(l, lathe_pos(l, LX));
}

/* ---- power-on, zeros ---- */

void lathe_init(struct lathe *l, const struct lathe_model *model)
{
  memset(l, 0, sizeof *l);   /* slides and part zero at 0, no tools, T0, G94 G97, time 0 */
  l->model = model ? *model : lathe_16b16f3;
  l->ovr_pct = 100;
  l->lo[LX] = -2 * l->model.travel_x;
  l->hi[LX] = 2 * l->model.travel_x;
  l->lo[LZ] = -l->model.travel_z;
  l->hi[LZ] = l->model.travel_z;
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
static int feed_time(const struct lathe *l, double f0, const struct path *p, double *sec, double *vmean, double *cap_out,
                     double *vreq100, char *wmsg, size_t wn, char *msg, size_t n)
{
  /* the override scales the feed before the axes' limits (D-46) */
  double k = l->ovr_on ? l->ovr_pct / 100.0 : 1, f = f0 * k;
  double cx = p->xs > 0 ? l->model.feed_x / p->xs : INFINITY, cz = p->zs > 0 ? l->model.feed_z / p->zs : INFINITY;
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
    say(msg, n, "feed F%s is too small for a move of %.3f mm", num(b, sizeof b, f0, 6), p->len);
    return S42_E_FEED;
  }
  *sec = t * 60;
  *vmean = t > 0 ? p->len / t : v_at_max;
  *cap_out = cap;
  /* the mean path speed asked at 100 %: what an override turned within the move scales */
  *vreq100 = k > 0 && t > 0 ? p->len / t / k : v_at_max;
  if (l->per_rev && k > 0 && t > 0) {
    double tr = 0;   /* asked speeds, uncapped */
    for (int i = 0; i < (l->css ? PIECES : 1); i++) {
      double rpm = l->css ? lathe_rpm(l, (int64_t)llround(p->dia[i])) : rpm_at_max;
      tr += (l->css ? p->len / PIECES : p->len) / (f0 * rpm);
    }
    *vreq100 = tr > 0 ? p->len / tr : v_at_max;
  } else if (!l->per_rev) {
    *vreq100 = f0;
  }
  if (vreq_max > cap) {
    char bf[40], bv[40], bc[40], br[40], bl[40], lim[80];
    if (by_x)
      snprintf(lim, sizeof lim, "X slide at most %s mm/min", num(bl, sizeof bl, l->model.feed_x, 1));
    else
      snprintf(lim, sizeof lim, "Z at most %s mm/min", num(bl, sizeof bl, l->model.feed_z, 1));
    if (l->per_rev)
      say(wmsg, wn, "F%s mm/rev = %s mm/min at %s rpm, cut to %s mm/min: %s", num(bf, sizeof bf, f0, 4),
          num(bv, sizeof bv, vreq_max, 1), num(br, sizeof br, rpm_at_max, 1), num(bc, sizeof bc, v_at_max, 1), lim);
    else
      say(wmsg, wn, "F%s cut to %s mm/min: %s", num(bf, sizeof bf, f0, 4), num(bc, sizeof bc, v_at_max, 1), lim);
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
  l->mv.on = 0;   /* a traverse: no override (D-46) */
  double tx = fabs((double)(s[LX] - l->slide[LX])) / 2000 / l->model.rapid_x;
  double tz = fabs((double)(s[LZ] - l->slide[LZ])) / 1000 / l->model.rapid_z;
  struct canon_call c;
  start(l, &c);
  c.axes = (mask & 1u ? 1u : 0) | (mask & 2u ? 4u : 0);
  l->slide[LX] = s[LX];
  l->slide[LZ] = s[LZ];
  l->t += fmax(tx, tz) * 60;
  settle(l);
  emit_at(l, &c, CANON_TRAVERSE);
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
  double sec, v, cap, vreq;
  char w[200];
  int e = feed_time(l, f, p, &sec, &v, &cap, &vreq, w, sizeof w, msg, n);
  if (e)
    return e;
  tip(l, c->from);
  c->t0 = l->t;
  l->mv.on = l->ovr_on && sec > 0;
  l->mv.t0 = l->t;
  l->mv.t1 = l->t + sec;
  l->mv.vreq = vreq;
  l->mv.cap = cap;
  l->mv.v = v;
  l->slide[LX] = s[LX];
  l->slide[LZ] = s[LZ];
  l->t += sec;
  l->feed = v;
  l->f_canon = f;
  settle(l);
  warn(l, w);
  c->f = f;
  c->feed = v;
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
  if (!(fabs(r0 - r1) <= (double)l->model.arc_tol)) {
    say(msg, n, "arc start radius %.3f mm and end radius %.3f mm differ by more than %s mm", r0 / 1000, r1 / 1000,
        num(b0, sizeof b0, (double)l->model.arc_tol / 1000.0, 3));
    return S42_E_ARC;
  }
  /* One quadrant at most: no line through the centre parallel to an axis
   * (angle 0, pi: the line Z = Zc; pi/2, 3pi/2: X = Xc) strictly inside the
   * sweep.  A point within LATHE_ARC_TOL µm of such a line (at most 0.01
   * rad) counts as on it, for the ends' rounding. */
  double t0, dt, eps = fmin((double)l->model.arc_tol / fmax(r0, r1), 0.01);
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
  if (k > (double)l->model.pitch_max) {
    say(msg, n, "G33 pitch %s mm is over the %s mm the machine cuts", num(b0, sizeof b0, k / 1000, 3),
        num(b1, sizeof b1, (double)l->model.pitch_max / 1000.0, 3));
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
  char b2[40];
  if (zmax > l->model.feed_z) {
    say(msg, n, "G33 needs Z %s mm/min at %s rpm: more than the %s mm/min it can keep synchronised",
        num(b0, sizeof b0, zmax, 1), num(b1, sizeof b1, rpm_max, 1), num(b2, sizeof b2, l->model.feed_z, 1));
    return S42_E_THREAD;
  }
  if (zmax * xr > l->model.feed_x) {
    say(msg, n, "G33 taper needs the X slide at %s mm/min: more than its %s mm/min", num(b0, sizeof b0, zmax * xr, 1),
        num(b2, sizeof b2, l->model.feed_x, 1));
    return S42_E_THREAD;
  }
  if (!isfinite(t)) {
    say(msg, n, "G33 too slow to finish");
    return S42_E_THREAD;
  }
  struct canon_call c;
  start(l, &c);
  c.v = k / 1000;
  l->mv.on = 0;   /* a thread stays synchronised to the spindle: no override */
  emit_at(l, &c, CANON_SYNCH_START);
  start(l, &c);
  l->slide[LX] = s[LX];
  l->slide[LZ] = s[LZ];
  l->t += t * 60;
  l->feed = t > 0 ? p.len / t : 0;
  settle(l);
  c.f = l->f_canon;   /* the feed rate stays as it was (LinuxCNC prints none for G33) */
  c.feed = l->feed;
  emit_at(l, &c, CANON_FEED_LINE);
  emit(l, CANON_SYNCH_STOP);
  return 0;
}

void lathe_dwell(struct lathe *l, double sec)
{
  if (!(sec > 0) || !isfinite(sec))
    sec = 0;
  struct canon_call c;
  start(l, &c);
  l->t += sec;
  settle(l);
  c.v = sec;
  emit_at(l, &c, CANON_DWELL);
}

/* ---- the spindle ---- */

/* S in rpm clamped into the range in force; the warning when it moved. */
static double clamp_rpm(const struct lathe *l, double s, int say_it)
{
  if (s == 0)
    return 0;
  int r = l->range >= 0 && l->range <= l->model.nranges ? l->range : 0;
  double c = fmin(fmax(s, l->model.range_lo[r]), l->model.range_hi[r]);
  if (c != s && say_it) {
    char b0[40], b1[40], b2[40], b3[40], w[200];
    num(b0, sizeof b0, s, 3);
    num(b1, sizeof b1, c, 3);
    num(b2, sizeof b2, l->model.range_lo[r], 0);
    num(b3, sizeof b3, l->model.range_hi[r], 0);
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
    start(l, &c);
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
  if (range < 0 || range > l->model.nranges) {
    char w[80];
    if (l->model.nranges == 2)
      snprintf(w, sizeof w, "spindle range %d refused: 0, 1 or 2", range);
    else
      snprintf(w, sizeof w, "spindle range %d refused: 0 to %d", range, l->model.nranges);
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
    start(l, &c);
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
    start(l, &c);
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
  struct canon_call c;
  start(l, &c);
  l->tool = t;
  settle(l);
  c.n = t;
  emit_at(l, &c, CANON_TOOL);
}

void lathe_coolant(struct lathe *l, int on)
{
  on = on != 0;
  if (on != l->coolant) {
    l->coolant = on;
    struct canon_call c;
    start(l, &c);
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

/* ---- the override within a move ---- */

int lathe_in_move(const struct lathe *l, double now)
{
  return l->mv.on && l->ovr_on && now >= l->mv.t0 && now < l->mv.t1;
}

double lathe_override_at(struct lathe *l, double now)
{
  if (l->ovr_pct <= 0 || !lathe_in_move(l, now) || !(l->mv.v > 0))
    return 0;
  double v = fmin(l->mv.vreq * l->ovr_pct / 100.0, l->mv.cap);
  if (!(v > 0))
    return 0;
  double rest = (l->mv.t1 - now) * l->mv.v / 60.0;   /* mm still to go */
  double d = rest / v * 60.0 - (l->mv.t1 - now);
  l->mv.v = v;
  l->mv.t1 += d;
  l->t += d;
  l->feed = v;
  return d;
}

static void override_switch(struct lathe *l, int on)
{
  on = on != 0;
  if (on != l->ovr_on) {
    l->ovr_on = on;
    struct canon_call c;
    start(l, &c);
    c.on = on;
    emit_at(l, &c, CANON_OVERRIDE);
  }
}

/* ---- the canonical table (src/core/canon.h) ---- */

/* The lathe's axes of a record's mask (bit 0 X, bit 2 Z; 0: both). */
static unsigned axes_of(const struct canon_call *c)
{
  if (!c->axes)
    return 3u;
  return (c->axes & 1u ? 1u << LX : 0) | (c->axes & 4u ? 1u << LZ : 0);
}

static void target(const struct canon_call *c, int64_t to[2])
{
  to[LX] = c->pos[0];
  to[LZ] = c->pos[2];
}

static int l_traverse(void *m, struct canon_call *c, char *msg, size_t n)
{
  int64_t to[2];
  target(c, to);
  return lathe_traverse(m, axes_of(c), to, msg, n);
}

static int l_home(void *m, struct canon_call *c, char *msg, size_t n)
{
  return lathe_home(m, axes_of(c), msg, n);
}

static int l_line(void *m, struct canon_call *c, char *msg, size_t n)
{
  int64_t to[2];
  target(c, to);
  return lathe_feed_line(m, to, c->f, msg, n);
}

static int l_arc(void *m, struct canon_call *c, char *msg, size_t n)
{
  int64_t to[2], ctr[2] = {c->centre[0], c->centre[1]};
  target(c, to);
  if (c->plane != GEOM_XZ) {
    say(msg, n, "the lathe turns arcs in the XZ plane only");
    return S42_E_ARC;
  }
  return lathe_feed_arc(m, to, ctr, c->ccw, c->f, msg, n);
}

static int l_thread(void *m, struct canon_call *c, char *msg, size_t n)
{
  int64_t to[2];
  target(c, to);
  return lathe_thread(m, to, c->v, msg, n);
}

static int l_dwell(void *m, struct canon_call *c, char *msg, size_t n)
{
  (void)msg;
  (void)n;
  lathe_dwell(m, c->v);
  return 0;
}

#define SIMPLE(name, call)                                              \
  static int name(void *m, struct canon_call *c, char *msg, size_t n)   \
  {                                                                     \
    (void)msg;                                                          \
    (void)n;                                                            \
    (void)c;                                                            \
    call;                                                               \
    return 0;                                                           \
  }
SIMPLE(l_spindle, lathe_spindle(m, c->dir))
SIMPLE(l_speed, lathe_speed(m, c->v))
SIMPLE(l_css, lathe_css(m, c->on))
SIMPLE(l_range, lathe_range(m, c->n))
SIMPLE(l_feed_mode, lathe_feed_mode(m, c->on))
SIMPLE(l_tool, lathe_tool(m, c->n))
SIMPLE(l_coolant, lathe_coolant(m, c->on))
SIMPLE(l_end, lathe_end(m))
SIMPLE(l_override, override_switch(m, c->on))
#undef SIMPLE

static void l_info(const void *mv, struct canon_info *in)
{
  const struct lathe *l = mv;
  const struct lathe_model *md = l ? &l->model : &lathe_16b16f3;
  memset(in, 0, sizeof *in);
  in->kind = "lathe";
  in->name = md->name;
  in->naxes = 2;
  static const int ax[2] = {0, 2};
  for (int a = 0; a < 2; a++) {
    struct canon_axis *x = &in->axis[ax[a]];
    x->name = a == LX ? 'X' : 'Z';
    x->unit = "mm";
    x->mm = canon_mm[ax[a]];
    x->max_speed = a == LX ? md->rapid_x : md->rapid_z;
    x->has_travel = 1;
    x->lo = l ? l->lo[a] : a == LX ? -2 * md->travel_x : -md->travel_z;
    x->hi = l ? l->hi[a] : a == LX ? 2 * md->travel_x : md->travel_z;
  }
}

const struct canon_ops lathe_ops = {
  .fn = {
    [CANON_TRAVERSE] = l_traverse,
    [CANON_HOME] = l_home,
    [CANON_FEED_LINE] = l_line,
    [CANON_FEED_ARC] = l_arc,
    [CANON_THREAD] = l_thread,
    [CANON_DWELL] = l_dwell,
    [CANON_SPINDLE] = l_spindle,
    [CANON_SPINDLE_SPEED] = l_speed,
    [CANON_SPINDLE_MODE] = l_css,
    [CANON_SPINDLE_RANGE] = l_range,
    [CANON_FEED_MODE] = l_feed_mode,
    [CANON_TOOL] = l_tool,
    [CANON_COOLANT] = l_coolant,
    [CANON_END] = l_end,
    [CANON_OVERRIDE] = l_override,
  },
  .info = l_info,
};
