/* The simulated machine (src/machine/grinder/machine.h): contour-speed limits, arcs,
 * checks, simulated time and the wheel (oscillation: test_plugin.c). */
#include "suites.h"
#include "ast.h"
#include "errors.h"
#include "kp.h"
#include "machine.h"
#include "kpmach.h"
#include "geom.h"
#include "canon.h"
#include <math.h>
#include <stdarg.h>
#include <string.h>

static struct machine m;
static struct kp_block b;
static struct mach_out o;
static char msg[200];

static void setup(void)
{
  mach_init(&m);
  memset(&b, 0, sizeof b);
  memset(&o, 0, sizeof o);
  msg[0] = 0;
}

/* A block: motion, then slot/value pairs ending with -1. */
static void block(int motion, int plane, double f, ...)
{
  memset(&b, 0, sizeof b);
  b.motion = motion;
  b.plane = plane;
  b.f = f;
  va_list ap;
  va_start(ap, f);
  for (int s; (s = va_arg(ap, int)) >= 0;) {
    b.given |= (uint16_t)(1u << s);
    b.w[s] = va_arg(ap, double);
  }
  va_end(ap);
}

static void with_m(int n) { b.m |= 1u << n; }

static int check(void) { return kp_mach_check(&m, &b, msg, sizeof msg); }

static void exec(void)
{
  ck_assert_msg(check() == 0, "mach_check: %s", msg);
  kp_mach_modal(&m, &b);
  kp_mach_motion(&m, &b, &o, msg, sizeof msg);
}

/* ---- linear limit ---- */

START_TEST(linear_limit_seed_example)
{
  double d[4] = {10000, 10000, 0, 0};
  double lim = mach_linear_limit(d);
  ck_near(lim, 6000 * sqrt(2.0 / 1297.0), 1e-9);
  ck_near(lim, 235.6, 0.05);
}
END_TEST

START_TEST(linear_limit_single_axes)
{
  double x[4] = {5000, 0, 0, 0}, y[4] = {0, -5000, 0, 0}, a[4] = {0, 0, 0, 90000}, z[4] = {0, 0, 0, 0};
  ck_near(mach_linear_limit(x), 6000, 1e-9);
  ck_near(mach_linear_limit(y), 6000.0 / 36, 1e-9);
  ck_near(mach_linear_limit(a), 6000, 1e-9);
  ck_near(mach_linear_limit(z), 6000, 1e-9);
}
END_TEST

START_TEST(linear_limit_mixed)
{
  double d[4] = {30000, 1000, 40000, 0};   /* mm: 30, 1, 40 */
  double want = 6000 * sqrt((900.0 + 1 + 1600) / (900 + 1296 + 1600));
  ck_near(mach_linear_limit(d), want, 1e-9);
}
END_TEST

START_TEST(exec_seed_linear)
{
  /* №01 G01 G09 X+10000 Y+10000 F1000: limited to ~235.6 mm/min */
  block(MO_G01, 0, 1000, SL_X, 10000.0, SL_Y, 10000.0, -1);
  exec();
  double feed = 6000 * sqrt(2.0 / 1297.0);
  ck_near(o.feed, feed, 1e-9);
  ck_near(m.t, sqrt(200.0) / feed * 60, 1e-9);
  ck_assert_int_eq(m.pos[AX_X], 10000);
  ck_assert_int_eq(m.pos[AX_Y], 10000);
  ck_assert_int_eq(o.d[AX_Y], 10000);
}
END_TEST

START_TEST(exec_linear_time)
{
  block(MO_G01, 0, 1000, SL_X, 10000.0, -1);
  exec();
  ck_near(o.feed, 1000, 0);
  ck_near(m.t, 0.6, 1e-12);
  block(MO_G01, 0, 9000, SL_Z, -6000.0, -1);   /* over the axis limit */
  exec();
  ck_near(o.feed, 6000, 1e-9);
  ck_near(m.t, 0.66, 1e-12);
  ck_assert_int_eq(m.pos[AX_Z], -6000);
}
END_TEST

START_TEST(exec_override)
{
  m.override_pct = 50;
  block(MO_G01, 0, 1000, SL_X, 10000.0, -1);
  exec();
  ck_near(o.feed, 500, 1e-12);
  ck_near(m.t, 1.2, 1e-12);
  /* M25 forbids the override: 100 % */
  block(MO_G01, 0, 1000, SL_X, 10000.0, -1);
  with_m(25);
  exec();
  ck_near(o.feed, 1000, 1e-12);
}
END_TEST

START_TEST(exec_surface_speed)
{
  /* X 3 mm and A 4 deg with D = 100 mm */
  block(MO_G01, 0, 100, SL_X, 3000.0, SL_A, 4000.0, -1);
  b.d1 = 100000;
  exec();
  ck_assert_int_eq(o.has_v, 1);
  double ad = 4 * M_PI * 100 / 360;
  ck_near(o.v, 100 * sqrt((9 + ad * ad) / (9 + 16)), 1e-9);
}
END_TEST

/* ---- arcs ---- */

START_TEST(arc_half_circle)
{
  /* №01 G02 G19 G09 X-20000 Z+0 I-10000 K+0 F1000: R 10 mm in XZ */
  block(MO_G02, 19, 1000, SL_X, -20000.0, SL_Z, 0.0, SL_I, -10000.0, SL_K, 0.0, -1);
  double len, ys;
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(len, M_PI * 10, 1e-9);
  ck_near(ys, 0, 0);
  exec();
  ck_near(o.feed, 1000, 1e-9);         /* XZ: only the 6000 clamp */
  ck_near(m.t, M_PI * 10 / 1000 * 60, 1e-9);
  ck_assert_int_eq(m.pos[AX_X], -20000);
  ck_assert_int_eq(m.pos[AX_Z], 0);
}
END_TEST

START_TEST(arc_full_circle)
{
  /* №07 G02 G19 G09 X+0 Z+0 I-10000 K+0 F1000 */
  block(MO_G02, 19, 1000, SL_X, 0.0, SL_Z, 0.0, SL_I, -10000.0, SL_K, 0.0, -1);
  double len, ys;
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(len, 2 * M_PI * 10, 1e-9);
  b.motion = MO_G03;
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(len, 2 * M_PI * 10, 1e-9);
}
END_TEST

START_TEST(arc_direction_lengths)
{
  /* XY, centre 10 mm along +X, end at the centre's top: G02 turns a
   * quarter (through the bottom? no: clockwise from 180 deg to 90 deg),
   * G03 three quarters */
  double len, ys;
  block(MO_G02, 17, 1000, SL_X, 10000.0, SL_Y, 10000.0, SL_I, 10000.0, SL_J, 0.0, -1);
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(len, M_PI / 2 * 10, 1e-9);
  block(MO_G03, 17, 1000, SL_X, 10000.0, SL_Y, 10000.0, SL_I, 10000.0, SL_J, 0.0, -1);
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(len, 3 * M_PI / 2 * 10, 1e-9);
}
END_TEST

START_TEST(arc_direction_xz)
{
  /* XZ: G03 turns from X towards Z.  Start at angle 180 (centre +X),
   * end at angle 270 (Z = -R): counter-clockwise is a quarter */
  double len, ys;
  block(MO_G03, 19, 1000, SL_X, 10000.0, SL_Z, -10000.0, SL_I, 10000.0, SL_K, 0.0, -1);
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(len, M_PI / 2 * 10, 1e-9);
  b.motion = MO_G02;
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(len, 3 * M_PI / 2 * 10, 1e-9);
}
END_TEST

START_TEST(arc_y_share_rule_2)
{
  /* XY arc from 60 deg to 120 deg (G03): the radius makes at most 30 deg
   * with Y at its ends and never lies along X: Y share sin 30 = 0.5 */
  block(MO_G03, 17, 1000, SL_X, -10000.0, SL_Y, 0.0, SL_I, -5000.0, SL_J, -8660.0, -1);
  double len, ys;
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(ys, 0.5, 1e-4);
  ck_near(len, M_PI / 3 * 10, 1e-2);
  exec();
  ck_near(o.feed, 6000 / sqrt((1 - ys * ys) + 36.0 * 36.0 * ys * ys), 1e-9);
  ck_near(o.feed, 332.95, 0.05);
}
END_TEST

START_TEST(arc_y_share_rule_3)
{
  /* the same ends clockwise: the arc passes 0 deg, where the tangent is
   * parallel to Y: F <= 6000/36 */
  block(MO_G02, 17, 1000, SL_X, -10000.0, SL_Y, 0.0, SL_I, -5000.0, SL_J, -8660.0, -1);
  double len, ys;
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(ys, 1, 0);
  ck_near(len, 5 * M_PI / 3 * 10, 1e-2);
  exec();
  ck_near(o.feed, 6000.0 / 36, 1e-9);
}
END_TEST

START_TEST(arc_y_share_yz_plane)
{
  /* YZ: Y is the first axis, the Y share is |sin t|.  A quarter from
   * 180 deg to 270 deg passes no point with the tangent along Y... its
   * end at 270 deg has the radius along -Z: tangent along Y, share 1 */
  block(MO_G03, 18, 1000, SL_Y, 10000.0, SL_Z, -10000.0, SL_J, 10000.0, SL_K, 0.0, -1);
  double len, ys;
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(len, M_PI / 2 * 10, 1e-9);
  ck_near(ys, 1, 1e-12);
  /* from 180 deg to 210 deg: the tangent turns from Z by 30 deg */
  block(MO_G03, 18, 1000, SL_Y, 1340.0, SL_Z, -5000.0, SL_J, 10000.0, SL_K, 0.0, -1);
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);
  ck_near(ys, 0.5, 1e-4);
  ck_near(len, M_PI / 6 * 10, 1e-2);
}
END_TEST

START_TEST(arc_errors)
{
  double len, ys;
  block(MO_G02, 19, 1000, SL_X, -20000.0, SL_Z, 0.0, SL_I, -10005.0, -1);
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), S42_E_ARC);
  block(MO_G02, 19, 1000, SL_X, -20000.0, SL_Z, 0.0, SL_I, -10002.0, -1);
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), S42_E_ARC);   /* radii 10002, 9998 */
  block(MO_G02, 19, 1000, SL_X, -20000.0, SL_Z, 0.0, SL_I, -10001.0, -1);
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), 0);   /* 2 µm apart: fine */
  block(MO_G02, 17, 1000, SL_X, 100.0, -1);
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), S42_E_ARC);
  block(MO_G02, 17, 1000, SL_X, 0.0, SL_I, 3000000.0, SL_J, 3000000.0, -1);
  ck_assert_int_eq(kp_mach_arc(&b, &len, &ys, msg, sizeof msg), S42_E_ARC);
  ck_assert_int_eq(check(), S42_E_ARC);
}
END_TEST

/* ---- checks ---- */

START_TEST(check_wheel)
{
  block(MO_NONE, 0, 0, -1);
  with_m(3);
  exec();
  ck_assert_int_eq(m.wheel, WHEEL_CW);
  block(MO_NONE, 0, 0, -1);
  with_m(4);
  ck_assert_int_eq(check(), S42_E_WHEEL);
  block(MO_NONE, 0, 0, -1);
  with_m(3);
  ck_assert_int_eq(check(), 0);        /* M3 again: no reversal */
  block(MO_NONE, 0, 0, -1);
  with_m(5);
  exec();
  block(MO_NONE, 0, 0, -1);
  with_m(4);
  exec();
  ck_assert_int_eq(m.wheel, WHEEL_CCW);
  block(MO_NONE, 0, 0, -1);
  with_m(3);
  ck_assert_int_eq(check(), S42_E_WHEEL);
}
END_TEST

START_TEST(check_feed_zero)
{
  block(MO_G01, 0, 0, SL_X, 1.0, -1);
  ck_assert_int_eq(check(), S42_E_FEED);
  block(MO_G02, 19, 0, SL_X, -20000.0, SL_I, -10000.0, -1);
  ck_assert_int_eq(check(), S42_E_FEED);
  block(MO_G01, 0, 0, SL_X, 0.0, -1);  /* no path: no speed needed */
  ck_assert_int_eq(check(), 0);
  block(MO_G04, 0, 0, SL_X, 20.0, -1);
  ck_assert_int_eq(check(), 0);
}
END_TEST

/* ---- time ---- */

START_TEST(time_dwell)
{
  block(MO_G04, 0, 0, SL_X, 20.0, -1);
  exec();
  ck_near(m.t, 2.0, 1e-12);
  ck_assert_int_eq(m.pos[AX_X], 0);    /* G04's X is no move */
}
END_TEST

START_TEST(time_wheel_rundown)
{
  block(MO_NONE, 0, 0, -1);
  with_m(5);
  exec();
  ck_near(m.t, 0, 0);                  /* the wheel was off */
  block(MO_NONE, 0, 0, -1);
  with_m(3);
  exec();
  block(MO_G01, 0, 1000, SL_X, 10000.0, -1);
  with_m(5);
  exec();
  ck_near(m.t, 3.0 + 0.6, 1e-12);
  ck_assert_int_eq(m.wheel, WHEEL_OFF);
}
END_TEST

START_TEST(time_g37_return)
{
  block(MO_G01, 0, 1000, SL_Y, -5000.0, -1);
  exec();
  double t0 = m.t;
  ck_near(t0, 5.0 / (6000.0 / 36) * 60, 1e-9);
  block(MO_G37, 0, 0, -1);
  exec();
  ck_assert_int_eq(m.pos[AX_Y], 0);
  ck_assert_int_eq(o.d[AX_Y], 5000);
  ck_near(m.t - t0, 5.0 / (6000.0 / 36) * 60, 1e-9);
}
END_TEST

START_TEST(jog_counts_in_position)
{
  mach_jog(&m, AX_Z, -250, 0);
  ck_assert_int_eq(m.pos[AX_Z], -250);
  ck_assert_int_eq(m.corr[AX_Z], 0);
  mach_jog(&m, AX_Z, 100, 1);
  ck_assert_int_eq(m.pos[AX_Z], -150);
  ck_assert_int_eq(m.corr[AX_Z], 100);
  ck_near(m.t, 0, 0);
}
END_TEST

/* The override turned within a move: the rest of it goes at the new speed,
 * and the simulated time is what that speed makes of the rest. */
START_TEST(override_within_a_move)
{
  block(MO_G01, 0, 60, SL_X, 60000.0, -1);   /* 60 mm at 60 mm/min: 60 s */
  kp_mach_motion(&m, &b, &o, msg, sizeof msg);
  ck_assert(fabs(m.t - 60) < 1e-9);
  m.override_pct = 50;                       /* at 30 s: 30 mm left at 30 mm/min = 60 s */
  ck_assert(fabs(mach_override_at(&m, 30) - 30) < 1e-9);
  ck_assert(fabs(m.t - 90) < 1e-9);
  ck_assert(fabs(m.mv.feed - 30) < 1e-9);
  m.override_pct = 150;                      /* at 60 s: 15 mm left at 90 mm/min = 10 s */
  ck_assert(fabs(mach_override_at(&m, 60) + 20) < 1e-9);
  ck_assert(fabs(m.t - 70) < 1e-9);
  m.override_pct = 0;                        /* 0 %: the host holds the move, nothing changes here */
  ck_assert(mach_override_at(&m, 65) == 0);
  ck_assert(fabs(m.t - 70) < 1e-9);
  m.override_pct = 100;                      /* outside the move: nothing */
  ck_assert(mach_override_at(&m, 70) == 0);
  ck_assert(mach_override_at(&m, -1) == 0);
  ck_assert_int_eq((int)m.pos[AX_X], 60000);
  /* the speed limit holds: 150 % of 6000 mm/min is 6000 */
  setup();
  block(MO_G01, 0, 6000, SL_X, 100000.0, -1);   /* 100 mm at 6000 mm/min: 1 s */
  kp_mach_motion(&m, &b, &o, msg, sizeof msg);
  m.override_pct = 150;
  ck_assert(mach_override_at(&m, 0.5) == 0);
  ck_assert(fabs(m.t - 1) < 1e-9);
  /* under M25 the override does not act */
  setup();
  m.override_allowed = 0;
  block(MO_G01, 0, 60, SL_X, 60000.0, -1);
  kp_mach_motion(&m, &b, &o, msg, sizeof msg);
  m.override_pct = 50;
  ck_assert(mach_override_at(&m, 30) == 0);
  ck_assert(fabs(m.t - 60) < 1e-9);
  /* a dwell is no move: the last move is over */
  setup();
  block(MO_G01, 0, 60, SL_X, 1000.0, -1);
  kp_mach_motion(&m, &b, &o, msg, sizeof msg);
  block(MO_G04, 0, 60, SL_X, 100.0, -1);
  kp_mach_motion(&m, &b, &o, msg, sizeof msg);
  m.override_pct = 50;
  ck_assert(mach_override_at(&m, 5) == 0);
}
END_TEST

/* The one geometry (src/core/geom.h): sweeps, the box an arc stays in,
 * points along it, and the E-ARC checks with their messages. */
START_TEST(geometry_of_arcs)
{
  struct geom_arc q = {-10000, 10000, -10000, 0, 1};   /* a quarter, ccw, from (0,0) round (-10,0) */
  ck_near(geom_arc_sweep(&q), M_PI / 2, 1e-12);
  ck_near(geom_arc_length(&q), 10000 * M_PI / 2, 1e-6);
  double t0, dt, lo[2], hi[2], p, qq;
  geom_arc_angles(&q, &t0, &dt);
  ck_near(t0, 0, 1e-12);
  ck_near(dt, M_PI / 2, 1e-12);
  geom_arc_box(&q, lo, hi);
  ck_near(lo[0], -10000, 1e-9);
  ck_near(hi[1], 10000, 1e-9);
  geom_arc_point(&q, 0.5, &p, &qq);
  ck_near(p, -10000 + 10000 * cos(M_PI / 4), 1e-6);
  ck_near(qq, 10000 * sin(M_PI / 4), 1e-6);
  struct geom_arc cw = q;
  cw.ccw = 0;                                          /* the other way round: three quarters */
  ck_near(geom_arc_sweep(&cw), 3 * M_PI / 2, 1e-12);
  geom_arc_box(&cw, lo, hi);
  ck_near(lo[1], -10000, 1e-9);                        /* it passes below the centre */
  struct geom_arc full = {0, 0, 5000, 0, 0};
  ck_near(geom_arc_sweep(&full), 2 * M_PI, 1e-12);
  ck_assert(geom_in_sweep(0, M_PI / 2, M_PI / 4));
  ck_assert(!geom_in_sweep(0, M_PI / 2, M_PI));
  ck_assert(geom_in_sweep(0, -M_PI / 2, -M_PI / 4));
  char m[120];
  struct geom_arc r0 = {1000, 0, 0, 0, 1}, big = {0, 0, 4000001, 0, 1}, off = {10000, 0, 5003, 0, 1};
  ck_assert_int_eq(geom_arc_check(&r0, MACH_ARC_RMAX, MACH_ARC_TOL, m, sizeof m), -1);
  ck_assert_str_eq(m, "arc centre at its start point: radius 0");
  ck_assert_int_eq(geom_arc_check(&big, MACH_ARC_RMAX, MACH_ARC_TOL, m, sizeof m), -1);
  ck_assert_str_eq(m, "arc radius 4000.001 mm is over 4000 mm");
  ck_assert_int_eq(geom_arc_check(&off, MACH_ARC_RMAX, MACH_ARC_TOL, m, sizeof m), -1);
  ck_assert_str_eq(m, "arc start radius 5003 µm and end radius 4997 µm differ by more than 2 µm");
  ck_assert_int_eq(geom_arc_check(&q, MACH_ARC_RMAX, MACH_ARC_TOL, m, sizeof m), 0);
  int a, b;
  geom_plane_axes(GEOM_XY, &a, &b);
  ck_assert(a == AX_X && b == AX_Y);
  geom_plane_axes(GEOM_YZ, &a, &b);
  ck_assert(a == AX_Y && b == AX_Z);
  geom_plane_axes(GEOM_XZ, &a, &b);
  ck_assert(a == AX_X && b == AX_Z);
  ck_assert_int_eq(kp_plane(17), GEOM_XY);
  ck_assert_int_eq(kp_plane(18), GEOM_YZ);
  ck_assert_int_eq(kp_plane(19), GEOM_XZ);
}
END_TEST

static char canon_buf[4096];
static void canon_to_buf(void *ctx, const char *call)
{
  (void)ctx;
  strncat(canon_buf, call, sizeof canon_buf - strlen(canon_buf) - 2);
  strcat(canon_buf, "\n");
}
static struct canon_trace canon_sink;

/* The canonical calls, with the trace observer watching: each call once,
 * as LinuxCNC prints it; SET_FEED_RATE and SELECT_PLANE only on a change. */
START_TEST(canonical_calls_traced)
{
  canon_buf[0] = 0;
  canon_trace_init(&canon_sink, canon_to_buf, NULL);
  m.out.call = canon_trace_call;
  m.out.ctx = &canon_sink;
  /* through the table, as a runtime calls it */
  struct canon_dev d = grinder_dev(&m);
  struct canon_call c = canon_of(CANON_FEED_LINE);
  c.pos[0] = 10000;
  c.f = 600;
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), 0);
  c = canon_of(CANON_FEED_LINE);
  c.pos[0] = 20000;
  c.f = 600;
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), 0);
  ck_assert(m.last.feed == 600 && m.last.d[0] == 10000);
  c = canon_of(CANON_FEED_ARC);
  c.pos[0] = 15000;
  c.pos[2] = 5000;
  c.plane = GEOM_XZ;
  c.cp = -5000;
  c.ccw = 1;
  c.f = 300;
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), 0);
  c = canon_of(CANON_SPINDLE);
  c.dir = 1;
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), 0);
  c = canon_of(CANON_SPINDLE);
  c.dir = -1;   /* a reversal without a stop: refused, nothing reported */
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), S42_E_WHEEL);
  c = canon_of(CANON_DWELL);
  c.v = 1.5;
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), 0);
  c = canon_of(CANON_SPINDLE);
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), 0);
  c = canon_of(CANON_TRAVERSE);
  c.axes = 1u << AX_Z;
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), 0);
  c = canon_of(CANON_END);
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), 0);
  c = canon_of(CANON_THREAD);   /* a call the grinder does not have: E-FUNC naming it */
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), S42_E_FUNC);
  ck_assert_str_eq(msg, "the ВЗ-208Ф3 has no call THREAD");
  ck_assert_str_eq(canon_buf, "SET_FEED_RATE(600.0000)\n"
                              "STRAIGHT_FEED(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
                              "STRAIGHT_FEED(20.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
                              "SET_FEED_RATE(300.0000)\n"
                              "SELECT_PLANE(CANON_PLANE_XZ)\n"
                              "ARC_FEED(5.0000, 15.0000, 0.0000, 15.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)\n"
                              "START_SPINDLE_CLOCKWISE(0)\n"
                              "DWELL(1.5000)\n"
                              "STOP_SPINDLE_TURNING(0)\n"
                              "STRAIGHT_TRAVERSE(15.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
                              "PROGRAM_END()\n");
  ck_assert_int_eq((int)m.pos[AX_X], 15000);   /* the arc took X back by 5 mm round (15, 0) */
  /* the wheel ran down for 3 s after the stop; the traverse took 5 mm at 6 m/min */
  ck_assert(m.t > 3 + 1.5);
}
END_TEST

Suite *suite_machine(void)
{
  Suite *s = suite_create("machine");
  TCase *tc = tcase_create("speed");
  tcase_add_checked_fixture(tc, setup, NULL);
  tcase_add_test(tc, linear_limit_seed_example);
  tcase_add_test(tc, linear_limit_single_axes);
  tcase_add_test(tc, linear_limit_mixed);
  tcase_add_test(tc, exec_seed_linear);
  tcase_add_test(tc, exec_linear_time);
  tcase_add_test(tc, exec_override);
  tcase_add_test(tc, exec_surface_speed);
  suite_add_tcase(s, tc);

  tc = tcase_create("arcs");
  tcase_add_checked_fixture(tc, setup, NULL);
  tcase_add_test(tc, arc_half_circle);
  tcase_add_test(tc, arc_full_circle);
  tcase_add_test(tc, arc_direction_lengths);
  tcase_add_test(tc, arc_direction_xz);
  tcase_add_test(tc, arc_y_share_rule_2);
  tcase_add_test(tc, arc_y_share_rule_3);
  tcase_add_test(tc, arc_y_share_yz_plane);
  tcase_add_test(tc, arc_errors);
  suite_add_tcase(s, tc);

  tc = tcase_create("checks");
  tcase_add_checked_fixture(tc, setup, NULL);
  tcase_add_test(tc, check_wheel);
  tcase_add_test(tc, check_feed_zero);
  suite_add_tcase(s, tc);

  tc = tcase_create("time");
  tcase_add_checked_fixture(tc, setup, NULL);
  tcase_add_test(tc, time_dwell);
  tcase_add_test(tc, time_wheel_rundown);
  tcase_add_test(tc, time_g37_return);
  tcase_add_test(tc, jog_counts_in_position);
  tcase_add_test(tc, override_within_a_move);
  tcase_add_test(tc, geometry_of_arcs);
  tcase_add_test(tc, canonical_calls_traced);
  suite_add_tcase(s, tc);
  return s;
}
