/* The simulated 16Б16Ф3 lathe (src/machine/lathe/lathe.h): travel, feeds
 * and their limits (D-24), G95, G96, threads, arcs and their canon text
 * (matched against LinuxCNC's rs274 -g), traverse and homing, the
 * spindle's ranges, tools and the part zero, the tool table's parser.
 * Positions are µm, X a diameter; times are seconds. */
#include "suites.h"
#include "canon.h"
#include "errors.h"
/* the unit tests' include path is the hosts' (src/host/module.mk), which
 * does not have the lathe's folder yet */
#include "lathe.h"
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static struct lathe l;
static char msg[256];

/* the canon lines and the warnings, kept as text */
static char canon_buf[8192], warn_buf[4096];
static int n_canon, n_warn;
static struct canon_trace sink;

static void canon_line(void *ctx, const char *text)
{
  (void)ctx;
  size_t k = strlen(canon_buf);
  snprintf(canon_buf + k, sizeof canon_buf - k, "%s\n", text);
}

static void count_canon(void *ctx, const struct canon_call *c)
{
  n_canon++;
  canon_trace_call(ctx, c);
}

static void on_warn(void *ctx, const char *text)
{
  (void)ctx;   /* the trace sink's: the canon calls' */
  n_warn++;
  size_t k = strlen(warn_buf);
  snprintf(warn_buf + k, sizeof warn_buf - k, "%s\n", text);
}

static void setup(void)
{
  lathe_init(&l, &lathe_16b16f3);
  canon_trace_init(&sink, canon_line, NULL);
  l.out.call = count_canon;
  l.out.warn = on_warn;
  l.out.ctx = &sink;
  canon_buf[0] = warn_buf[0] = msg[0] = 0;
  n_canon = n_warn = 0;
}

static void clear_out(void)
{
  canon_buf[0] = warn_buf[0] = 0;
  n_canon = n_warn = 0;
}

static void line_ok(int64_t x, int64_t z, double f)
{
  int64_t to[2] = {x, z};
  int rc = lathe_feed_line(&l, to, f, msg, sizeof msg);
  ck_assert_msg(rc == 0, "feed_line: %s", msg);
}

static void traverse_ok(int64_t x, int64_t z)
{
  int64_t to[2] = {x, z};
  int rc = lathe_traverse(&l, 3, to, msg, sizeof msg);
  ck_assert_msg(rc == 0, "traverse: %s", msg);
}

/* A state snapshot: an error must change nothing in it. */
static struct lathe before;
static void snap(void) { before = l; }
static void unchanged(void)
{
  ck_assert_int_eq(l.slide[LX], before.slide[LX]);
  ck_assert_int_eq(l.slide[LZ], before.slide[LZ]);
  ck_assert(l.t == before.t);
  ck_assert(l.feed == before.feed);
  ck_assert(l.rpm_now == before.rpm_now);
  ck_assert(l.f_canon == before.f_canon);
  ck_assert_int_eq(n_canon, 0);
  ck_assert_int_eq(n_warn, 0);
}

/* ---- power-on ---- */

START_TEST(power_on)
{
  ck_assert_int_eq(l.slide[LX], 0);
  ck_assert_int_eq(l.slide[LZ], 0);
  ck_assert_int_eq(l.lo[LX], -450000);   /* 225 mm of radius = 450 mm of diameter */
  ck_assert_int_eq(l.hi[LX], 450000);
  ck_assert_int_eq(l.lo[LZ], -650000);
  ck_assert_int_eq(l.hi[LZ], 650000);
  ck_assert_int_eq(l.tool, 0);
  ck_assert_int_eq(l.dir, 0);
  ck_assert_int_eq(l.range, 0);
  ck_assert_int_eq(l.per_rev, 0);
  ck_assert_int_eq(l.css, 0);
  ck_assert(l.t == 0);
  ck_assert(lathe_rpm(&l, 0) == 0);
  ck_assert(l.model.range_lo[0] == 45 && l.model.range_hi[0] == 1800);
  ck_assert(l.model.range_lo[1] == 45 && l.model.range_hi[1] == 280);
  ck_assert(l.model.range_lo[2] == 224 && l.model.range_hi[2] == 1800);
  ck_assert_int_eq(l.model.nranges, 2);
}
END_TEST

/* ---- travel (D-23) ---- */

START_TEST(travel_refused)
{
  line_ok(40000, -10000, 100);
  clear_out();
  snap();
  /* the seed's G33 Z-75000 under D-1: Z -750 mm */
  int64_t z750[2] = {40000, -750000};
  ck_assert_int_eq(lathe_feed_line(&l, z750, 100, msg, sizeof msg), S42_E_TRAVEL);
  ck_assert_str_eq(msg, "Z -750.00 mm is outside the travel -650.00..650.00 mm");
  unchanged();
  /* Ø460 is 230 mm of radius: over 225 */
  int64_t x460[2] = {460000, 0};
  ck_assert_int_eq(lathe_traverse(&l, 3, x460, msg, sizeof msg), S42_E_TRAVEL);
  ck_assert_str_eq(msg, "X 460.00 mm (diameter) is outside the travel -450.00..450.00 mm");
  unchanged();
  /* Ø450 and Z±650 exactly are inside */
  int64_t edge[2] = {-450000, 650000};
  ck_assert_int_eq(lathe_traverse(&l, 3, edge, msg, sizeof msg), 0);
  ck_assert_int_eq(l.slide[LX], -450000);
  ck_assert_int_eq(l.slide[LZ], 650000);
}
END_TEST

START_TEST(travel_on_the_slide)
{
  /* part zero Z at machine -100 mm: the tip's Z -560 puts the slide at -660 */
  lathe_set_zero(&l, 0, -100000);
  clear_out();
  snap();
  int64_t to[2] = {0, -560000};
  ck_assert_int_eq(lathe_feed_line(&l, to, 100, msg, sizeof msg), S42_E_TRAVEL);
  ck_assert_str_eq(msg, "Z -660.00 mm is outside the travel -650.00..650.00 mm");
  unchanged();
  /* a tool with Z -20: slide = tip + zero - d = -560 - 100 + 20 = -640, inside */
  static const char tab[] = "T1 Z -20\n";
  ck_assert_int_eq(lathe_tools_parse(&l, tab, strlen(tab), "t.tools", msg, sizeof msg), 0);
  lathe_tool(&l, 1);
  ck_assert_int_eq(lathe_feed_line(&l, to, 100, msg, sizeof msg), 0);
  ck_assert_int_eq(l.slide[LZ], -640000);
  ck_assert_int_eq(lathe_pos(&l, LZ), -560000);
  /* an overflowing target is outside too, and no crash */
  int64_t huge[2] = {INT64_MAX, INT64_MIN};
  ck_assert_int_eq(lathe_feed_line(&l, huge, 100, msg, sizeof msg), S42_E_TRAVEL);
  ck_assert_int_eq(lathe_traverse(&l, 3, huge, msg, sizeof msg), S42_E_TRAVEL);
}
END_TEST

/* ---- feed (D-24) ---- */

START_TEST(feed_plain)
{
  /* Ø0 -> Ø20 at F100: the X slide moves 10 mm: 10/100 min = 6 s */
  line_ok(20000, 0, 100);
  ck_near(l.t, 6, 1e-9);
  ck_near(l.feed, 100, 1e-9);
  ck_assert_int_eq(l.slide[LX], 20000);
  ck_assert_int_eq(n_warn, 0);
}
END_TEST

START_TEST(feed_cut_x)
{
  /* X only, F2000: the X slide at most 1200; 50 mm of slide (Ø100) / 1200 = 2.5 s */
  line_ok(100000, 0, 2000);
  ck_near(l.feed, 1200, 1e-9);
  ck_near(l.t, 2.5, 1e-9);
  ck_assert_str_eq(warn_buf, "F2000 cut to 1200 mm/min: X slide at most 1200 mm/min\n");
  /* X slide 30 mm (Ø60 more), Z 40 mm: length 50, X share 0.6, Z share
   * 0.8; F3000 -> X needs 1800: v = 1200/0.6 = 2000 (Z then 1600 < 2400);
   * 50/2000 min = 1.5 s */
  clear_out();
  line_ok(160000, 40000, 3000);
  ck_near(l.feed, 2000, 1e-9);
  ck_near(l.t, 2.5 + 1.5, 1e-9);
  ck_assert_str_eq(warn_buf, "F3000 cut to 2000 mm/min: X slide at most 1200 mm/min\n");
}
END_TEST

START_TEST(feed_cut_z)
{
  /* X slide 5 mm (Ø10), Z 12 mm: length 13; X share 5/13 allows 3120,
   * Z share 12/13 allows 2600: F3000 cut to 2600; 13/2600 min = 0.3 s */
  line_ok(10000, 12000, 3000);
  ck_near(l.feed, 2600, 1e-9);
  ck_near(l.t, 0.3, 1e-9);
  ck_assert_str_eq(warn_buf, "F3000 cut to 2600 mm/min: Z at most 2400 mm/min\n");
  /* F2000 under 2600: no cut, no warning */
  clear_out();
  line_ok(0, 0, 2000);
  ck_near(l.feed, 2000, 1e-9);
  ck_assert_int_eq(n_warn, 0);
}
END_TEST

START_TEST(feed_per_rev)
{
  lathe_speed(&l, 500);
  lathe_spindle(&l, 1);
  lathe_feed_mode(&l, 1);
  clear_out();
  /* F0.2 mm/rev at 500 rpm = 100 mm/min; X slide 5 mm (Ø10): 3 s */
  line_ok(10000, 0, 0.2);
  ck_near(l.feed, 100, 1e-9);
  ck_near(l.t, 3, 1e-9);
  ck_near(l.rpm_now, 500, 0);
  ck_assert_int_eq(n_warn, 0);
  ck_assert_str_eq(canon_buf, "SET_FEED_RATE(0.2000)\n"
                              "STRAIGHT_FEED(5.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n");
  /* Fig. 1.9 N14: F10 mm/rev at 500 rpm = 5000 mm/min, cut to 1200 on X;
   * X slide 5 mm back: 5/1200 min = 0.25 s */
  clear_out();
  line_ok(0, 0, 10);
  ck_near(l.feed, 1200, 1e-9);
  ck_near(l.t, 3.25, 1e-9);
  ck_assert_str_eq(warn_buf, "F10 mm/rev = 5000 mm/min at 500 rpm, cut to 1200 mm/min: X slide at most 1200 mm/min\n");
}
END_TEST

START_TEST(feed_errors)
{
  int64_t to[2] = {10000, -10000};
  snap();
  ck_assert_int_eq(lathe_feed_line(&l, to, 0, msg, sizeof msg), S42_E_FEED);
  ck_assert_str_eq(msg, "a feed move with F 0: give the feed with F");
  ck_assert_int_eq(lathe_feed_line(&l, to, NAN, msg, sizeof msg), S42_E_FEED);
  ck_assert_int_eq(lathe_feed_line(&l, to, INFINITY, msg, sizeof msg), S42_E_FEED);
  ck_assert_int_eq(lathe_feed_line(&l, to, -5, msg, sizeof msg), S42_E_FEED);
  ck_assert_int_eq(lathe_feed_line(&l, to, 1e-320, msg, sizeof msg), S42_E_FEED);   /* the time would be infinite */
  int64_t ae[2] = {20000, -10000}, c[2] = {0, -10000};   /* a good quarter, radius 10 */
  ck_assert_int_eq(lathe_feed_arc(&l, ae, c, 0, 0, msg, sizeof msg), S42_E_FEED);
  /* G95 with the spindle stopped, or turning at S0 */
  lathe_feed_mode(&l, 1);
  clear_out();
  snap();
  ck_assert_int_eq(lathe_feed_line(&l, to, 0.2, msg, sizeof msg), S42_E_FEED);
  ck_assert_str_eq(msg, "feed per revolution with the spindle stopped");
  lathe_speed(&l, 300);
  ck_assert_int_eq(lathe_feed_line(&l, to, 0.2, msg, sizeof msg), S42_E_FEED);   /* S but no M03 */
  lathe_speed(&l, 0);
  lathe_spindle(&l, 1);
  clear_out();
  snap();
  ck_assert_int_eq(lathe_feed_line(&l, to, 0.2, msg, sizeof msg), S42_E_FEED);
  ck_assert_str_eq(msg, "feed per revolution with the spindle stopped");
  unchanged();
}
END_TEST

START_TEST(feed_mode_switch)
{
  /* D-30: G94 under G94 is no switch; a switch prints SET_FEED_MODE and a
   * feed rate 0 (rs274 -g prints both) */
  line_ok(10000, 0, 100);
  clear_out();
  lathe_feed_mode(&l, 0);
  ck_assert_int_eq(n_canon, 0);
  lathe_feed_mode(&l, 1);
  lathe_feed_mode(&l, 1);
  lathe_feed_mode(&l, 0);
  ck_assert_int_eq(n_canon, 2);
  ck_assert_str_eq(canon_buf, "SET_FEED_MODE(0, 1)\nSET_FEED_RATE(0.0000)\nSET_FEED_MODE(0, 0)\nSET_FEED_RATE(0.0000)\n");
  ck_assert(l.f_canon == 0);
}
END_TEST

/* ---- G96 ---- */

START_TEST(css_rpm)
{
  lathe_spindle(&l, 1);
  lathe_css(&l, 1);
  lathe_speed(&l, 100);   /* 100 m/min */
  ck_assert(l.s == 100);
  /* rpm = 1000 S / (pi D): Ø50 -> 636.62; Ø10 -> 3183 clamped to 1800;
   * Ø0 -> the range's top */
  ck_near(lathe_rpm(&l, 50000), 100000 / (M_PI * 50), 1e-9);
  ck_near(lathe_rpm(&l, 10000), 1800, 0);
  ck_near(lathe_rpm(&l, -10000), 1800, 0);
  ck_near(lathe_rpm(&l, 0), 1800, 0);
  /* Ø800: 39.8 -> the bottom, 45 */
  ck_near(lathe_rpm(&l, 800000), 45, 0);
  lathe_range(&l, 1);
  ck_near(lathe_rpm(&l, 50000), 280, 0);
  ck_assert(l.s == 100);   /* m/min: nothing to re-clamp */
  /* G97: the S in force is rpm again, and range 1 keeps it */
  lathe_css(&l, 0);
  ck_assert(l.s == 100);
  ck_near(lathe_rpm(&l, 50000), 100, 0);
  /* stopped: 0 */
  lathe_spindle(&l, 0);
  ck_assert(lathe_rpm(&l, 50000) == 0);
}
END_TEST

START_TEST(css_per_rev_time)
{
  /* Facing from Ø100 to Ø20 at F0.1 mm/rev, G96 S100: rpm = 100000/(pi D)
   * stays inside 45..1800 (1800 is reached at D = 17.7 mm), so the speed
   * is v = 0.1 rpm = 10000/(pi D) mm/min (at most 159 at Ø20, under the X
   * slide's 1200), and the time is the integral of the slide's path
   * ds = dD/2 over v:  int_20^100 pi D / 20000 dD / 1 = pi/20000 * (100^2
   * - 20^2)/2 = 0.24 pi min = 45.2389 s; 1/v is linear in D, so the
   * midpoints of 64 pieces give it exactly. */
  line_ok(100000, 0, 1000);
  double t0 = l.t;
  lathe_spindle(&l, 1);
  lathe_css(&l, 1);
  lathe_speed(&l, 100);
  lathe_feed_mode(&l, 1);
  clear_out();
  line_ok(20000, 0, 0.1);
  ck_near(l.t - t0, 0.24 * M_PI * 60, 1e-9);
  ck_near(l.feed, 40 / (0.24 * M_PI), 1e-9);   /* the mean: 40 mm of slide in 0.754 min = 53.05 */
  ck_near(l.rpm_now, 100000 / (M_PI * 20), 1e-9);   /* at the end, Ø20: 1591.5 */
  ck_assert_int_eq(n_warn, 0);
  /* under G94 the rpm does not change the speed */
  lathe_feed_mode(&l, 0);
  t0 = l.t;
  line_ok(100000, 0, 80);
  ck_near(l.t - t0, 40.0 / 80 * 60, 1e-9);
  ck_near(l.rpm_now, 100000 / (M_PI * 100), 1e-9);
}
END_TEST

/* ---- G33 (D-24) ---- */

START_TEST(thread_ok)
{
  /* Ex. 7's variant: from (Ø24, Z5) G33 Z-75 K2500 at 500 rpm: Z speed
   * 2.5 * 500 = 1250 mm/min; 80 mm / 1250 = 0.064 min = 3.84 s */
  lathe_speed(&l, 500);
  lathe_spindle(&l, 1);
  line_ok(24000, 5000, 200);
  clear_out();
  double t0 = l.t;
  int64_t to[2] = {24000, -75000};
  ck_assert_int_eq(lathe_thread(&l, to, 2500, msg, sizeof msg), 0);
  ck_near(l.t - t0, 3.84, 1e-9);
  ck_near(l.feed, 1250, 1e-9);
  ck_assert_int_eq(lathe_pos(&l, LZ), -75000);
  /* rs274 -g on `G1 F200 X24 Z5` / `G33 Z-75 K2.5` (G18 G7): no feed rate
   * printed for the thread */
  ck_assert_str_eq(canon_buf, "START_SPEED_FEED_SYNC(2.500000,0)\n"
                              "STRAIGHT_FEED(12.0000, 0.0000, -75.0000, 0.0000, 0.0000, 0.0000)\n"
                              "STOP_SPEED_FEED_SYNCH()\n");
  /* 2400 mm/min exactly is allowed: K4800 at 500 rpm; 10 mm in 0.25 s */
  int64_t back[2] = {24000, -65000};
  t0 = l.t;
  ck_assert_int_eq(lathe_thread(&l, back, 4800, msg, sizeof msg), 0);
  ck_near(l.t - t0, 0.25, 1e-9);
}
END_TEST

START_TEST(thread_errors)
{
  int64_t to[2] = {24000, -50000};
  snap();
  ck_assert_int_eq(lathe_thread(&l, to, 2500, msg, sizeof msg), S42_E_THREAD);
  ck_assert_str_eq(msg, "G33 with the spindle stopped");
  lathe_speed(&l, 500);
  lathe_spindle(&l, 1);
  clear_out();
  snap();
  /* K5000 at 500 rpm: 2500 mm/min of Z > 2400 */
  ck_assert_int_eq(lathe_thread(&l, to, 5000, msg, sizeof msg), S42_E_THREAD);
  ck_assert_str_eq(msg, "G33 needs Z 2500 mm/min at 500 rpm: more than the 2400 mm/min it can keep synchronised");
  ck_assert_int_eq(lathe_thread(&l, to, 0, msg, sizeof msg), S42_E_THREAD);
  ck_assert_int_eq(lathe_thread(&l, to, NAN, msg, sizeof msg), S42_E_THREAD);
  ck_assert_int_eq(lathe_thread(&l, to, -1, msg, sizeof msg), S42_E_THREAD);
  ck_assert_int_eq(lathe_thread(&l, to, 40001, msg, sizeof msg), S42_E_THREAD);   /* over 40 mm */
  int64_t nz[2] = {30000, 0};
  ck_assert_int_eq(lathe_thread(&l, nz, 1000, msg, sizeof msg), S42_E_THREAD);     /* no Z move */
  /* a taper whose X slide would pass 1200: K4000 at 500 = 2000 of Z, the
   * slide 1 mm of X per mm of Z -> 2000 */
  int64_t taper[2] = {2 * 10000, -10000};
  ck_assert_int_eq(lathe_thread(&l, taper, 4000, msg, sizeof msg), S42_E_THREAD);
  int64_t far[2] = {0, -750000};
  ck_assert_int_eq(lathe_thread(&l, far, 2500, msg, sizeof msg), S42_E_TRAVEL);
  unchanged();
}
END_TEST

/* ---- arcs ---- */

START_TEST(arc_quarter)
{
  /* Ex. 6's variant: from (Ø20, Z0) G03 to (Ø40, Z-10) round (Ø20, Z-10):
   * radius 10, a quarter: 10 pi/2 = 15.708 mm; both slides take the whole
   * speed at one end or the other (X at the start, Z at the end), so the
   * speed may be min(1200, 2400): F100 stays, 0.15708 min = 9.4248 s */
  line_ok(20000, 0, 100);
  double t0 = l.t;
  int64_t to[2] = {40000, -10000}, c[2] = {20000, -10000};
  ck_assert_int_eq(lathe_feed_arc(&l, to, c, 0, 100, msg, sizeof msg), 0);
  ck_near(l.t - t0, 10 * M_PI / 2 / 100 * 60, 1e-9);
  ck_near(l.feed, 100, 1e-9);
  ck_assert_int_eq(lathe_pos(&l, LX), 40000);
  ck_assert_int_eq(lathe_pos(&l, LZ), -10000);
  /* at F2000 the X slide's 1200 binds: 15.708 mm / 1200 = 0.7854 s */
  int64_t to2[2] = {20000, -20000}, c2[2] = {40000, -20000};   /* G02 on round (Ø40, Z-20) */
  clear_out();
  t0 = l.t;
  ck_assert_int_eq(lathe_feed_arc(&l, to2, c2, 1, 2000, msg, sizeof msg), 0);
  ck_near(l.t - t0, 10 * M_PI / 2 / 1200 * 60, 1e-9);
  ck_assert_str_eq(warn_buf, "F2000 cut to 1200 mm/min: X slide at most 1200 mm/min\n");
}
END_TEST

START_TEST(arc_eighth)
{
  /* An eighth: from (Ø20, Z0) G03 round (Ø20, Z-10), radius 10; the start
   * is at 90 degrees from the X line through the centre (angles from X
   * towards Z), the end at 45: radius-space X 10 + 7.071 (Ø34.142), Z
   * -10 + 7.071.  X share |sin|: 1 at the start, 0.707 at the end -> 1;
   * Z share |cos|: 0 and 0.707 -> 0.707: v = min(1200/1, 2400/0.707) = 1200 */
  line_ok(20000, 0, 100);
  double t0 = l.t;
  int64_t to[2] = {2 * (10000 + 7071), -10000 + 7071}, c[2] = {20000, -10000};
  ck_assert_int_eq(lathe_feed_arc(&l, to, c, 0, 5000, msg, sizeof msg), 0);
  ck_near(l.feed, 1200, 1e-9);
  /* length: the mean radius times pi/4 (both radii 10 mm within 0.1 µm) */
  ck_near(l.t - t0, 10 * M_PI / 4 / 1200 * 60, 1e-4);
}
END_TEST

START_TEST(arc_errors)
{
  line_ok(20000, 0, 100);
  clear_out();
  snap();
  int64_t to[2] = {40000, -10000}, c[2] = {20000, -10000};
  /* the same ends as G02: 270 degrees */
  ck_assert_int_eq(lathe_feed_arc(&l, to, c, 1, 100, msg, sizeof msg), S42_E_ARC);
  ck_assert_str_eq(msg, "arc goes past Z -10 mm of its centre: one quadrant at most (270 degrees)");
  /* a half circle: from (Ø20, Z0) G03 round (Ø20, Z-10) to (Ø20, Z-20) */
  int64_t half[2] = {20000, -20000};
  ck_assert_int_eq(lathe_feed_arc(&l, half, c, 0, 100, msg, sizeof msg), S42_E_ARC);
  ck_assert_str_eq(msg, "arc goes past Z -10 mm of its centre: one quadrant at most (180 degrees)");
  /* the seed's L608-613 arc (its 0.01 mm read as mm): start (Ø31, Z57),
   * end (Ø52, Z33), centre (Ø19, Z32); in radius space the start is
   * (6, 25) from the centre, radius 25.710, the end (16.5, 1), 16.530 */
  lathe_traverse(&l, 3, (int64_t[2]){31000, 57000}, msg, sizeof msg);
  clear_out();
  snap();
  int64_t e2[2] = {52000, 33000}, c2[2] = {19000, 32000};
  ck_assert_int_eq(lathe_feed_arc(&l, e2, c2, 1, 100, msg, sizeof msg), S42_E_ARC);
  ck_assert_str_eq(msg, "arc start radius 25.710 mm and end radius 16.530 mm differ by more than 0.01 mm");
  /* a start equal to the end: a full circle */
  int64_t here[2] = {31000, 57000};
  ck_assert_int_eq(lathe_feed_arc(&l, here, c2, 0, 100, msg, sizeof msg), S42_E_ARC);
  ck_assert_str_eq(msg, "arc ends where it starts: a full circle is more than one quadrant");
  /* the centre at the start */
  ck_assert_int_eq(lathe_feed_arc(&l, e2, here, 0, 100, msg, sizeof msg), S42_E_ARC);
  unchanged();
  /* radii 10 µm apart pass, 11 do not (D-32: LATHE_ARC_TOL) */
  lathe_traverse(&l, 3, (int64_t[2]){20000, 0}, msg, sizeof msg);
  int64_t ok[2] = {40020, -10000}, bad[2] = {40022, -10000};   /* end radius 10.010, 10.011 mm */
  ck_assert_int_eq(lathe_feed_arc(&l, bad, c, 0, 100, msg, sizeof msg), S42_E_ARC);
  ck_assert_int_eq(lathe_feed_arc(&l, ok, c, 0, 100, msg, sizeof msg), 0);
}
END_TEST

/* ---- the canon text against LinuxCNC ---- */

/* The twin, run with `rs274 -g` (LinuxCNC 2.9):
 *   G21 G18 G7 G90 G94
 *   G1 F100 X20 Z0
 *   G3 X40 Z-10 I0 K-10
 *   G2 X20 Z-20 I0 K-10
 *   G0 X50 Z5
 *   S500 M3
 *   G1 F200 X24 Z5
 *   G33 Z-75 K2.5
 *   G95
 *   G1 F0.2 X30
 *   M8
 *   M9
 *   G4 P1.5
 *   M5
 * printed these lines (without their N..... prefix; its start-up lines
 * before the first feed are left out, and its SELECT_PLANE(CANON_PLANE_XZ),
 * which G18 printed at the start, comes before the first arc here). */
static const char rs274_twin[] =
    "SET_FEED_RATE(100.0000)\n"
    "STRAIGHT_FEED(10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
    "SELECT_PLANE(CANON_PLANE_XZ)\n"
    "ARC_FEED(-10.0000, 20.0000, -10.0000, 10.0000, 1, 0.0000, 0.0000, 0.0000, 0.0000)\n"
    "ARC_FEED(-20.0000, 10.0000, -20.0000, 20.0000, -1, 0.0000, 0.0000, 0.0000, 0.0000)\n"
    "STRAIGHT_TRAVERSE(25.0000, 0.0000, 5.0000, 0.0000, 0.0000, 0.0000)\n"
    "SET_SPINDLE_SPEED(0, 500.0000)\n"
    "START_SPINDLE_CLOCKWISE(0)\n"
    "SET_FEED_RATE(200.0000)\n"
    "STRAIGHT_FEED(12.0000, 0.0000, 5.0000, 0.0000, 0.0000, 0.0000)\n"
    "START_SPEED_FEED_SYNC(2.500000,0)\n"
    "STRAIGHT_FEED(12.0000, 0.0000, -75.0000, 0.0000, 0.0000, 0.0000)\n"
    "STOP_SPEED_FEED_SYNCH()\n"
    "SET_FEED_MODE(0, 1)\n"
    "SET_FEED_RATE(0.0000)\n"
    "SET_FEED_RATE(0.2000)\n"
    "STRAIGHT_FEED(15.0000, 0.0000, -75.0000, 0.0000, 0.0000, 0.0000)\n"
    "FLOOD_ON()\n"
    "MIST_OFF()\n"
    "FLOOD_OFF()\n"
    "DWELL(1.5000)\n"
    "STOP_SPINDLE_TURNING(0)\n";

START_TEST(canon_twin)
{
  line_ok(20000, 0, 100);
  int64_t a1[2] = {40000, -10000}, c1[2] = {20000, -10000};
  ck_assert_int_eq(lathe_feed_arc(&l, a1, c1, 0, 100, msg, sizeof msg), 0);   /* G03 */
  int64_t a2[2] = {20000, -20000}, c2[2] = {40000, -20000};
  ck_assert_int_eq(lathe_feed_arc(&l, a2, c2, 1, 100, msg, sizeof msg), 0);   /* G02 */
  traverse_ok(50000, 5000);
  lathe_speed(&l, 500);
  lathe_spindle(&l, 1);
  line_ok(24000, 5000, 200);
  int64_t th[2] = {24000, -75000};
  ck_assert_int_eq(lathe_thread(&l, th, 2500, msg, sizeof msg), 0);
  lathe_feed_mode(&l, 1);
  line_ok(30000, -75000, 0.2);
  lathe_coolant(&l, 1);
  lathe_coolant(&l, 0);
  lathe_dwell(&l, 1.5);
  lathe_spindle(&l, 0);
  ck_assert_str_eq(canon_buf, rs274_twin);
}
END_TEST

START_TEST(canon_part_zero_and_events)
{
  /* canon positions are the tip's in part coordinates */
  lathe_set_zero(&l, 10000, -100000);
  traverse_ok(30000, 2000);   /* slide X 40000, Z -98000 */
  ck_assert_int_eq(l.slide[LX], 40000);
  ck_assert_int_eq(l.slide[LZ], -98000);
  ck_assert_str_eq(canon_buf, "STRAIGHT_TRAVERSE(15.0000, 0.0000, 2.0000, 0.0000, 0.0000, 0.0000)\n");
  /* the speed only on a change; the spindle only on a change (rs274 -g
   * prints neither `S500` nor `M3` again) */
  clear_out();
  lathe_speed(&l, 500);
  lathe_speed(&l, 500);
  lathe_spindle(&l, 1);
  lathe_spindle(&l, 1);
  lathe_coolant(&l, 1);
  lathe_coolant(&l, 1);
  lathe_tool(&l, 3);
  ck_assert_str_eq(canon_buf, "SET_SPINDLE_SPEED(0, 500.0000)\nSTART_SPINDLE_CLOCKWISE(0)\nFLOOD_ON()\nSELECT_TOOL(3)\n");
  /* M02: the spindle and the coolant stop, then PROGRAM_END */
  clear_out();
  lathe_end(&l);
  ck_assert_str_eq(canon_buf, "STOP_SPINDLE_TURNING(0)\nMIST_OFF()\nFLOOD_OFF()\nPROGRAM_END()\n");
  ck_assert_int_eq(l.dir, 0);
  ck_assert_int_eq(l.coolant, 0);
  ck_assert(l.rpm_now == 0);
  clear_out();
  lathe_end(&l);
  ck_assert_str_eq(canon_buf, "PROGRAM_END()\n");
  /* under G96 SET_SPINDLE_SPEED prints the S in force, m/min, as rs274
   * does for `G96 S100` */
  clear_out();
  lathe_css(&l, 1);
  lathe_speed(&l, 120);
  ck_assert_str_eq(canon_buf, "SET_SPINDLE_SPEED(0, 120.0000)\n");
}
END_TEST

/* ---- traverse, G25 (D-31), dwell ---- */

START_TEST(traverse_time)
{
  /* to (Ø100, Z200): the X slide 50 mm at 5000 = 0.6 s, Z 200 at 10000 =
   * 1.2 s, together: 1.2 s */
  traverse_ok(100000, 200000);
  ck_near(l.t, 1.2, 1e-12);
  /* X only, back to Ø0: 0.6 s */
  int64_t to[2] = {0, 999999999};
  ck_assert_int_eq(lathe_traverse(&l, 1u << LX, to, msg, sizeof msg), 0);   /* Z not named: ignored */
  ck_near(l.t, 1.8, 1e-12);
  ck_assert_int_eq(l.slide[LZ], 200000);
  ck_assert(l.feed == 0);   /* a traverse is not a feed move */
}
END_TEST

START_TEST(home_time)
{
  lathe_set_zero(&l, 20000, -300000);
  traverse_ok(80000, 100000);   /* slide X 100000 (50 mm of radius), Z -200000 */
  double t0 = l.t;
  clear_out();
  /* G25 X Z: X 50 mm at 5000 = 0.6 s, Z 200 mm at 10000 = 1.2 s: 1.2 s;
   * one STRAIGHT_TRAVERSE to the end: the tip at slide 0 - zero (Ø-20, Z300) */
  ck_assert_int_eq(lathe_home(&l, 3, msg, sizeof msg), 0);
  ck_near(l.t - t0, 1.2, 1e-12);
  ck_assert_int_eq(l.slide[LX], 0);
  ck_assert_int_eq(l.slide[LZ], 0);
  ck_assert_int_eq(lathe_pos(&l, LX), -20000);
  ck_assert_int_eq(lathe_pos(&l, LZ), 300000);
  ck_assert_str_eq(canon_buf, "STRAIGHT_TRAVERSE(-10.0000, 0.0000, 300.0000, 0.0000, 0.0000, 0.0000)\n");
  ck_assert_int_eq(n_canon, 1);
  /* G25 X alone, from Z elsewhere: only X moves */
  traverse_ok(80000, 100000);
  t0 = l.t;
  ck_assert_int_eq(lathe_home(&l, 1u << LX, msg, sizeof msg), 0);
  ck_near(l.t - t0, 0.6, 1e-12);
  ck_assert_int_eq(l.slide[LX], 0);
  ck_assert_int_eq(l.slide[LZ], -200000);
}
END_TEST

START_TEST(dwell)
{
  lathe_dwell(&l, 2.0);   /* G04 E20 */
  ck_near(l.t, 2.0, 0);
  ck_assert_str_eq(canon_buf, "DWELL(2.0000)\n");
  lathe_dwell(&l, NAN);
  lathe_dwell(&l, -3);
  ck_near(l.t, 2.0, 0);
}
END_TEST

/* ---- the spindle (D-10, D-30) ---- */

START_TEST(speed_clamp)
{
  /* no range: 45..1800 */
  lathe_speed(&l, 2000);
  ck_assert(l.s == 1800);
  ck_assert_str_eq(warn_buf, "S2000 clamped to 1800 rpm: no range is selected, 45..1800\n");
  clear_out();
  lathe_speed(&l, 10);
  ck_assert(l.s == 45);
  ck_assert_int_eq(n_warn, 1);
  clear_out();
  lathe_speed(&l, 0);   /* S0: 0 rpm, no warning */
  ck_assert(l.s == 0);
  ck_assert_int_eq(n_warn, 0);
  /* the seed's N1 S500 M03 M38: range 1 */
  lathe_range(&l, 1);
  clear_out();
  lathe_speed(&l, 500);
  ck_assert(l.s == 280);
  ck_assert_str_eq(warn_buf, "S500 clamped to 280 rpm: range 1 is 45..280\n");
  ck_assert_str_eq(canon_buf, "SET_SPINDLE_SPEED(0, 280.0000)\n");
  lathe_range(&l, 2);
  clear_out();
  lathe_speed(&l, 100);
  ck_assert(l.s == 224);
  ck_assert_str_eq(warn_buf, "S100 clamped to 224 rpm: range 2 is 224..1800\n");
  clear_out();
  lathe_speed(&l, 1500);
  ck_assert(l.s == 1500);
  ck_assert_int_eq(n_warn, 0);
  lathe_speed(&l, NAN);   /* refused, kept */
  lathe_speed(&l, -5);
  ck_assert(l.s == 1500);
  lathe_range(&l, 7);     /* refused */
  ck_assert_int_eq(l.range, 2);
}
END_TEST

START_TEST(range_reclamp)
{
  lathe_speed(&l, 1000);
  lathe_spindle(&l, 1);
  ck_near(l.rpm_now, 1000, 0);
  clear_out();
  lathe_range(&l, 1);   /* M38 re-clamps the S in force */
  ck_assert(l.s == 280);
  ck_near(l.rpm_now, 280, 0);
  ck_assert_str_eq(warn_buf, "S1000 clamped to 280 rpm: range 1 is 45..280\n");
  ck_assert_str_eq(canon_buf, "SET_SPINDLE_SPEED(0, 280.0000)\n");
  clear_out();
  lathe_range(&l, 2);   /* 280 is inside 224..1800: unchanged, silent */
  ck_assert(l.s == 280);
  ck_assert_int_eq(n_warn, 0);
  ck_assert_int_eq(n_canon, 0);
  lathe_speed(&l, 1800);
  clear_out();
  lathe_range(&l, 1);
  ck_assert(l.s == 280);
  ck_assert_int_eq(n_warn, 1);
  lathe_range(&l, 0);
  ck_assert(l.s == 280);
}
END_TEST

/* ---- tools and the part zero ---- */

START_TEST(tool_offsets)
{
  static const char tab[] = "; the turret\nT1 X -12.50 Z 40.00\nT2 X 5\n";
  ck_assert_int_eq(lathe_tools_parse(&l, tab, strlen(tab), "t.tools", msg, sizeof msg), 0);
  traverse_ok(100000, 50000);
  clear_out();
  /* T1: the slide stays, the tip moves by the correction: tip = slide + d */
  lathe_tool(&l, 1);
  ck_assert_int_eq(l.slide[LX], 100000);
  ck_assert_int_eq(l.slide[LZ], 50000);
  ck_assert_int_eq(lathe_pos(&l, LX), 100000 - 12500);
  ck_assert_int_eq(lathe_pos(&l, LZ), 50000 + 40000);
  ck_assert_str_eq(canon_buf, "SELECT_TOOL(1)\n");
  /* the tip to (Ø0, Z0): slide = tip + zero - d = (12500, -40000) */
  line_ok(0, 0, 100);
  ck_assert_int_eq(l.slide[LX], 12500);
  ck_assert_int_eq(l.slide[LZ], -40000);
  ck_assert_int_eq(lathe_pos(&l, LX), 0);
  /* T2 (X +5, Z 0), T3 not in the table (no correction), T0 none */
  lathe_tool(&l, 2);
  ck_assert_int_eq(lathe_pos(&l, LX), 17500);
  ck_assert_int_eq(lathe_pos(&l, LZ), -40000);
  lathe_tool(&l, 3);
  ck_assert_int_eq(lathe_pos(&l, LX), 12500);
  lathe_tool(&l, 0);
  ck_assert_int_eq(lathe_pos(&l, LX), 12500);
  lathe_tool(&l, 100);   /* refused */
  lathe_tool(&l, -1);
  ck_assert_int_eq(l.tool, 0);
}
END_TEST

START_TEST(part_zero)
{
  traverse_ok(60000, -20000);
  /* OX 10 mm, OZ -100 mm: the tip stays, its part coordinates change */
  lathe_set_zero(&l, 10000, -100000);
  ck_assert_int_eq(l.slide[LX], 60000);
  ck_assert_int_eq(l.slide[LZ], -20000);
  ck_assert_int_eq(lathe_pos(&l, LX), 50000);
  ck_assert_int_eq(lathe_pos(&l, LZ), 80000);
  /* a move in part coordinates: Ø0 Z0 of the part = slide (10000, -100000) */
  line_ok(0, 0, 500);
  ck_assert_int_eq(l.slide[LX], 10000);
  ck_assert_int_eq(l.slide[LZ], -100000);
  ck_assert_int_eq(lathe_pos(&l, LZ), 0);
}
END_TEST

/* ---- the tool table's text ---- */

static int parse(const char *text, size_t len)
{
  msg[0] = 0;
  return lathe_tools_parse(&l, text, len, "t.tools", msg, sizeof msg);
}

START_TEST(tools_good)
{
  static const char tab[] = "; corrections in mm, X a diameter\n"
                            "\n"
                            "   \t\n"
                            "T1  X -12.50  Z 40.00\n"
                            "T02 Z3 ; a comment after\n"
                            "t3 x+.5 z-0.001\r\n"
                            "T99X1Z2\n"
                            "T4";
  ck_assert_msg(parse(tab, strlen(tab)) == 0, "%s", msg);
  ck_assert_int_eq(l.tools[1].has, 1);
  ck_assert_int_eq(l.tools[1].d[LX], -12500);
  ck_assert_int_eq(l.tools[1].d[LZ], 40000);
  ck_assert_int_eq(l.tools[2].d[LX], 0);
  ck_assert_int_eq(l.tools[2].d[LZ], 3000);
  ck_assert_int_eq(l.tools[3].d[LX], 500);
  ck_assert_int_eq(l.tools[3].d[LZ], -1);
  ck_assert_int_eq(l.tools[99].d[LX], 1000);
  ck_assert_int_eq(l.tools[99].d[LZ], 2000);
  ck_assert_int_eq(l.tools[4].has, 1);
  ck_assert_int_eq(l.tools[4].d[LX], 0);
  ck_assert_int_eq(l.tools[5].has, 0);
  ck_assert_int_eq(l.tools[0].has, 0);
  /* an empty text: an empty table */
  ck_assert_int_eq(parse("", 0), 0);
  ck_assert_int_eq(l.tools[1].has, 0);
}
END_TEST

START_TEST(tools_bad)
{
  static const struct {
    const char *text, *err;
  } bad[] = {
      {"T1 X 1\nT1 Z 2\n", "t.tools:2:1: T1 given twice (first on line 1)"},
      {"T0 X 1\n", "t.tools:1:2: tool number 0: tools are T1..T99"},
      {"T100 X 1\n", "t.tools:1:2: tool number 100: tools are T1..T99"},
      {"T123456789012345678901234567890\n", "t.tools:1:2: tool number over 999: tools are T1..T99"},
      {"T X 1\n", "t.tools:1:3: expected the tool's number after T, found 'X'"},
      {"X 1\n", "t.tools:1:1: expected T<n> X <mm> Z <mm>, found 'X'"},
      {"T1 X 1 X 2\n", "t.tools:1:8: X given twice for T1"},
      {"T1 Y 1\n", "t.tools:1:4: expected X or Z, found 'Y'"},
      {"T1 X\n", "t.tools:1:5: expected a number in mm after X, found the end of the line"},
      {"T1 X -\n", "t.tools:1:6: expected digits in the X correction"},
      {"T1 X 1.2345\n", "t.tools:1:6: X correction with more than 3 decimals: the table is in whole µm"},
      {"T1 Z 12345\n", "t.tools:1:6: Z correction over 4 digits before the point: at most 9999.999 mm"},
      {"T1 X 1.2.3\n", "t.tools:1:9: unexpected '.' after the number"},
      {"T1 X 1,5\n", "t.tools:1:7: unexpected ',' after the number"},
      {"T1 X .\n", "t.tools:1:6: expected digits in the X correction"},
      {"T1 X - 5\n", "t.tools:1:6: expected digits in the X correction"},
      {"; ok\nT1 Ж 1\n", "t.tools:2:4: expected X or Z, found byte 0xD0"},
      {"T1 Z 1 Ж\n", "t.tools:1:8: expected X or Z, found byte 0xD0"},
      {"T1 Z 1\rT2\n", "t.tools:1:7: expected X or Z, found a carriage return"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    lathe_init(&l, &lathe_16b16f3);
    l.tools[7].has = 1;   /* a table before: kept on an error */
    ck_assert_msg(parse(bad[i].text, strlen(bad[i].text)) == -1, "case %zu parsed", i);
    ck_assert_msg(strcmp(msg, bad[i].err) == 0, "case %zu: \"%s\", expected \"%s\"", i, msg, bad[i].err);
    ck_assert_int_eq(l.tools[7].has, 1);
    ck_assert_int_eq(l.tools[1].has, 0);
  }
  /* NUL bytes are refused where they are */
  static const char nul[] = "T1 X 1\nT2 \0Z 1\n";
  ck_assert_int_eq(parse(nul, sizeof nul - 1), -1);
  ck_assert_str_eq(msg, "t.tools:2:4: a NUL byte: not a tool table");
  /* no file name, no room for the message, no text: no crash */
  ck_assert_int_eq(lathe_tools_parse(&l, "T0", 2, NULL, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "-:1:2: tool number 0: tools are T1..T99");
  ck_assert_int_eq(lathe_tools_parse(&l, "T0", 2, "f", NULL, 0), -1);
  ck_assert_int_eq(lathe_tools_parse(&l, NULL, 5, "f", msg, sizeof msg), 0);
}
END_TEST

/* Random calls and random tables: no crash, the slides always inside the
 * travel, the time never decreasing nor NaN.  A fixed LCG: deterministic. */
static uint64_t rnd_state;
static uint64_t rnd(void)
{
  rnd_state = rnd_state * 6364136223846793005ULL + 1442695040888963407ULL;
  return rnd_state >> 17;
}
static int64_t rpos(void)
{
  switch (rnd() % 4) {
  case 0: return (int64_t)(rnd() % 2000001) - 1000000;
  case 1: return (int64_t)(rnd() % 2001) - 1000;
  case 2: return (int64_t)rnd() * (rnd() % 2 ? 1 : -1);
  default: return (int64_t)(rnd() % 200001) - 100000;
  }
}
static double rval(void)
{
  static const double odd[] = {0, -1, NAN, INFINITY, -INFINITY, 1e-300, 1e300, 0.01, 99999};
  return rnd() % 4 == 0 ? odd[rnd() % 9] : (double)(rnd() % 100000) / 10;
}

START_TEST(robust)
{
  rnd_state = 42;
  memset(&l.out, 0, sizeof l.out);   /* no sink at all: also allowed */
  static const char tab[] = "T1 X -12.5 Z 40\nT2 X 3 Z -7\n";
  ck_assert_int_eq(parse(tab, strlen(tab)), 0);
  double t = 0;
  for (int i = 0; i < 20000; i++) {
    int64_t to[2] = {rpos(), rpos()}, c[2] = {rpos(), rpos()};
    switch (rnd() % 14) {
    case 0: lathe_traverse(&l, (unsigned)(rnd() % 4), to, msg, sizeof msg); break;
    case 1: lathe_feed_line(&l, to, rval(), msg, sizeof msg); break;
    case 2: lathe_feed_arc(&l, to, c, (int)(rnd() % 2), rval(), msg, sizeof msg); break;
    case 3: lathe_thread(&l, to, rval() * 10, msg, sizeof msg); break;
    case 4: lathe_home(&l, (unsigned)(rnd() % 4), msg, sizeof msg); break;
    case 5: lathe_speed(&l, rval()); break;
    case 6: lathe_range(&l, (int)(rnd() % 5) - 1); break;
    case 7: lathe_css(&l, (int)(rnd() % 2)); break;
    case 8: lathe_spindle(&l, (int)(rnd() % 3) - 1); break;
    case 9: lathe_feed_mode(&l, (int)(rnd() % 2)); break;
    case 10: lathe_tool(&l, (int)(rnd() % 5)); break;
    case 11: lathe_dwell(&l, rval()); break;
    case 12: lathe_set_zero(&l, (int64_t)(rnd() % 20001) - 10000, (int64_t)(rnd() % 20001) - 10000); break;
    default: lathe_coolant(&l, (int)(rnd() % 2)); break;
    }
    ck_assert(l.slide[LX] >= l.lo[LX] && l.slide[LX] <= l.hi[LX]);
    ck_assert(l.slide[LZ] >= l.lo[LZ] && l.slide[LZ] <= l.hi[LZ]);
    ck_assert_msg(isfinite(l.t) && l.t >= t, "step %d: t %g after %g", i, l.t, t);
    ck_assert(isfinite(l.feed) && isfinite(l.rpm_now));
    t = l.t;
  }
  char buf[64];
  for (int i = 0; i < 20000; i++) {
    size_t n = rnd() % sizeof buf;
    for (size_t k = 0; k < n; k++) {
      static const char alpha[] = "TtXxZz0123456789 .+-;\n\r\t\0\xd0\x96";
      buf[k] = rnd() % 8 ? alpha[rnd() % (sizeof alpha - 1)] : (char)rnd();
    }
    lathe_tools_parse(&l, buf, n, "r", msg, sizeof msg);
    lathe_tools_parse(&l, buf, n, "r", msg, 1 + rnd() % 8);
  }
}
END_TEST

Suite *suite_lathe(void)
{
  Suite *s = suite_create("lathe");
  TCase *tc = tcase_create("motion");
  tcase_add_checked_fixture(tc, setup, NULL);
  tcase_add_test(tc, power_on);
  tcase_add_test(tc, travel_refused);
  tcase_add_test(tc, travel_on_the_slide);
  tcase_add_test(tc, feed_plain);
  tcase_add_test(tc, feed_cut_x);
  tcase_add_test(tc, feed_cut_z);
  tcase_add_test(tc, feed_per_rev);
  tcase_add_test(tc, feed_errors);
  tcase_add_test(tc, feed_mode_switch);
  tcase_add_test(tc, css_rpm);
  tcase_add_test(tc, css_per_rev_time);
  tcase_add_test(tc, thread_ok);
  tcase_add_test(tc, thread_errors);
  tcase_add_test(tc, traverse_time);
  tcase_add_test(tc, home_time);
  tcase_add_test(tc, dwell);
  suite_add_tcase(s, tc);

  tc = tcase_create("arcs");
  tcase_add_checked_fixture(tc, setup, NULL);
  tcase_add_test(tc, arc_quarter);
  tcase_add_test(tc, arc_eighth);
  tcase_add_test(tc, arc_errors);
  tcase_add_test(tc, canon_twin);
  tcase_add_test(tc, canon_part_zero_and_events);
  suite_add_tcase(s, tc);

  tc = tcase_create("spindle_tools");
  tcase_add_checked_fixture(tc, setup, NULL);
  tcase_add_test(tc, speed_clamp);
  tcase_add_test(tc, range_reclamp);
  tcase_add_test(tc, tool_offsets);
  tcase_add_test(tc, part_zero);
  tcase_add_test(tc, tools_good);
  tcase_add_test(tc, tools_bad);
  tcase_add_test(tc, robust);
  suite_add_tcase(s, tc);
  return s;
}
