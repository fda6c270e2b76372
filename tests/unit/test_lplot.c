/* The plot engine's lathe view (src/host/plot.h): the turned part's
 * silhouette from canonical calls, computed by hand; the arcs' sense; the
 * chuck mark; the --stock parser; robustness (a million calls, extremes);
 * the files. */
#include "suites.h"
#include "canon.h"
#include "geom.h"
#include "plot.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static const double lmm[CANON_AXES] = {0.0005, 0.001, 0.001, 0.001, 0.001, 0.001};

/* Where the tool is: a record starts where the one before it ended, as the
 * lathe reports them. */
static int64_t here[CANON_AXES];

/* A lathe's plot: the machine as the lathe describes itself (X counts
 * 0.5 um of radius), the tool at the origin. */
static struct plot *lathe_plot(const struct plot_stock *s)
{
  struct plot *pl = plot_new(s);
  ck_assert_ptr_nonnull(pl);
  struct canon_info in;
  memset(&in, 0, sizeof in);
  in.kind = "lathe";
  in.name = "16Б16Ф3";
  in.naxes = 2;
  for (int a = 0; a < CANON_AXES; a++)
    in.axis[a].mm = lmm[a];
  in.axis[0].name = 'X';
  in.axis[2].name = 'Z';
  memset(here, 0, sizeof here);
  plot_begin(pl, &in, here);
  return pl;
}

static void put(struct plot *pl, struct canon_call *c)
{
  memcpy(c->from, here, sizeof here);
  memcpy(here, c->pos, sizeof here);
  plot_call(pl, c);
}

/* A call at (radius r, z) mm, as the lathe reports it (X counts 0.5 µm of
 * radius: the diameter in µm). */
static struct canon_call call(int kind, double r, double z)
{
  struct canon_call c;
  memset(&c, 0, sizeof c);
  c.kind = kind;
  c.pos[0] = llround(r / lmm[0]);
  c.pos[2] = llround(z / lmm[2]);
  c.mm = lmm;
  return c;
}

static void feed(struct plot *pl, double r, double z)
{
  struct canon_call c = call(CANON_FEED_LINE, r, z);
  c.f = 100;
  put(pl, &c);
}

static void trav(struct plot *pl, double r, double z)
{
  struct canon_call c = call(CANON_TRAVERSE, r, z);
  put(pl, &c);
}

/* ARC_FEED to (r, z) round (cr, cz); g 2 or 3. */
static void arc(struct plot *pl, int g, double r, double z, double cr, double cz)
{
  struct canon_call c = call(CANON_FEED_ARC, r, z);
  c.plane = GEOM_XZ;
  c.centre[0] = llround(cr / lmm[0]);
  c.centre[1] = llround(cz / lmm[2]);
  c.ccw = g == 2;   /* the sink's sense: from X towards Z is a G02 */
  c.f = 100;
  put(pl, &c);
}

static void tool_at(struct plot *pl, double r, double z)
{
  struct canon_call c = call(CANON_TOOL, r, z);
  c.dir = 1;
  put(pl, &c);
}

static struct plot *with_stock(double d, double len)
{
  struct plot_stock s = {1, d, len};
  return lathe_plot(&s);
}

/* Stock Ø40 x 100; face at Z 0; turn to Ø30 over Z 0 .. -30, out at -30;
 * a groove to Ø25 at Z -20.  By hand: R = 15 on 0 .. -30 but 12.5 at -20,
 * 20 (untouched) beyond -30; 0 at the face (the facing pass reached the
 * axis there). */
START_TEST(silhouette_by_hand)
{
  struct plot *pl = with_stock(40, 100);
  tool_at(pl, 25, 5);
  trav(pl, 21, 0);
  feed(pl, 0, 0);           /* facing at Z 0 */
  trav(pl, 0, 1);
  trav(pl, 15, 1);
  feed(pl, 15, -30);        /* Ø30 */
  feed(pl, 21, -30);        /* out */
  trav(pl, 21, -20);
  feed(pl, 12.5, -20);      /* the groove Ø25 */
  feed(pl, 21, -20);
  trav(pl, 25, 5);
  ck_assert_int_eq(plot_lathe_chuck(pl, NULL), 0);
  ck_near(plot_lathe_radius_at(pl, -0.001), 0, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -0.5), 15, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -10), 15, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -19.5), 15, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -20), 12.5, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -20.004), 12.5, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -19.996), 12.5, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -20.5), 15, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -29.99), 15, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -30.03), 20, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -50), 20, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -100), 20, 1e-9);
  ck_assert(plot_lathe_radius_at(pl, 0.5) == -1 && plot_lathe_radius_at(pl, -100.5) == -1);
  plot_free(pl);
}
END_TEST

/* A chamfer and a taper: the radius along a slanted line, exactly; the
 * tool past the axis (negative X) cuts as |X|; above the stock or beyond
 * the face nothing. */
START_TEST(silhouette_slanted_and_outside)
{
  struct plot *pl = with_stock(40, 100);
  tool_at(pl, 30, 10);
  trav(pl, 14, 1);
  feed(pl, 18, -3);         /* through the face: r = 15 at z 0, 18 at -3 */
  feed(pl, 18, -40);
  feed(pl, -16, -60);       /* across the axis: |r| 18 -> 0 at z -50.5882 -> 16 */
  trav(pl, -25, -60);
  trav(pl, -25, 10);        /* above the stock, on the far side: nothing */
  trav(pl, 30, 10);         /* across the axis beyond the face: nothing */
  trav(pl, 25, -80);        /* above the stock: nothing */
  trav(pl, 25, 50);
  trav(pl, 0, 50);          /* beyond the face: nothing */
  ck_near(plot_lathe_radius_at(pl, -1), 16, 0.011);   /* 15 + 1; a cell is 0.01 long */
  ck_near(plot_lathe_radius_at(pl, -2.5), 17.5, 0.011);
  ck_near(plot_lathe_radius_at(pl, -20), 18, 1e-9);
  double zc = -40 - 20 * 18.0 / 34;
  ck_near(plot_lathe_radius_at(pl, zc), 0, 0.02);
  ck_near(plot_lathe_radius_at(pl, -45), 18 - 5 * 34.0 / 20, 0.02);
  ck_near(plot_lathe_radius_at(pl, -59), (59 - 40) * 34.0 / 20 - 18, 0.02);
  ck_near(plot_lathe_radius_at(pl, -70), 20, 1e-9);
  ck_near(plot_lathe_radius_at(pl, -90), 20, 1e-9);
  plot_free(pl);
}
END_TEST

/* The arcs' sense, by hand.  G03 from (r 10, z 0) to (r 20, z -10) round
 * (r 10, z -10): the quarter bulging out, R(z) = 10 + sqrt(100 - (z+10)^2)
 * (the other way round, the long way, would pass r 0 at z -10).  G02 from
 * (r 10, z -30) to (r 20, z -40) round (r 20, z -30): the quarter hollowed
 * in, R(z) = 20 - sqrt(100 - (z+30)^2) (the long way stays above r 20). */
START_TEST(arcs_turn_the_right_way)
{
  struct plot *pl = with_stock(60, 100);
  tool_at(pl, 10, 0);
  arc(pl, 3, 20, -10, 10, -10);
  trav(pl, 35, -10);
  trav(pl, 35, -30);
  trav(pl, 10, -30);
  arc(pl, 2, 20, -40, 20, -30);
  trav(pl, 35, -40);
  for (double z = -0.5; z > -10; z -= 1.5)
    ck_near(plot_lathe_radius_at(pl, z), 10 + sqrt(100 - (z + 10) * (z + 10)), 0.06);
  ck_near(plot_lathe_radius_at(pl, -2.928932), 17.071068, 0.02);
  ck_near(plot_lathe_radius_at(pl, -5), 18.660254, 0.02);
  ck_near(plot_lathe_radius_at(pl, -15), 30, 1e-9);
  for (double z = -30.5; z > -40; z -= 1.5)
    ck_near(plot_lathe_radius_at(pl, z), 20 - sqrt(100 - (z + 30) * (z + 30)), 0.06);
  ck_near(plot_lathe_radius_at(pl, -35), 11.339746, 0.02);
  ck_near(plot_lathe_radius_at(pl, -45), 30, 1e-9);
  /* the page: Z to the right, the radius up */
  double x0, y0, x1, y1;
  plot_lathe_page_xy(pl, 10, 0, &x0, &y0);
  plot_lathe_page_xy(pl, 20, -10, &x1, &y1);
  ck_assert(x1 < x0 && y1 < y0);
  ck_near(x0 - x1, y0 - y1, 1e-9);   /* one scale */
  plot_free(pl);
}
END_TEST

/* Past the stock's end while under its radius: marked, with the least z;
 * at the stock's radius or above, or only at the end's plane, not. */
START_TEST(chuck_side)
{
  double z;
  struct plot *pl = with_stock(40, 100);
  tool_at(pl, 25, 5);
  trav(pl, 19, 5);
  feed(pl, 19, -100);
  ck_assert_int_eq(plot_lathe_chuck(pl, &z), 0);
  feed(pl, 21, -100);
  trav(pl, 20, -110);       /* at d/2: cuts nothing */
  ck_assert_int_eq(plot_lathe_chuck(pl, &z), 0);
  trav(pl, 25, -90);
  feed(pl, 17, -102);
  ck_assert_int_eq(plot_lathe_chuck(pl, &z), 1);
  ck_near(z, -102, 1e-9);
  feed(pl, 25, -110);       /* leaves the bar's radius at z -105 */
  ck_assert_int_eq(plot_lathe_chuck(pl, &z), 1);
  ck_near(z, -105, 1e-5);
  plot_free(pl);
  /* without a stock, no chuck */
  pl = lathe_plot(NULL);
  tool_at(pl, 0, 0);
  feed(pl, 0, -500);
  ck_assert_int_eq(plot_lathe_chuck(pl, &z), 0);
  ck_assert(plot_lathe_radius_at(pl, -1) == -1);
  plot_free(pl);
}
END_TEST

START_TEST(stock_parses)
{
  struct plot_stock s;
  char why[200];
  ck_assert_int_eq(plot_parse_stock("40x100", &s, why, sizeof why), 0);
  ck_assert(s.has && s.d == 40 && s.len == 100);
  ck_assert_int_eq(plot_parse_stock("40X100", &s, why, sizeof why), 0);
  ck_assert(s.has && s.d == 40 && s.len == 100);
  ck_assert_int_eq(plot_parse_stock("12.5x0.75", &s, why, sizeof why), 0);
  ck_near(s.d, 12.5, 1e-12);
  ck_near(s.len, 0.75, 1e-12);
  ck_assert_int_eq(plot_parse_stock("10000x10000", &s, why, sizeof why), 0);
  static const char *const bad[] = {"", "40", "40x", "x100", "40*100", "-40x100", "40x-100", "0x100", "40x0",
                                    "40x100x3", "40 x 100", "1e3x100", "nanxinf", "40x100mm", "10001x100",
                                    "40x10000.5", "4..0x100", ".x1"};
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    why[0] = 0;
    int r = plot_parse_stock(bad[i], &s, why, sizeof why);
    ck_assert_msg(r == -1, "'%s' accepted", bad[i]);
    ck_assert_msg(strstr(why, "--stock") && strlen(why) > 20, "'%s': %s", bad[i], why);
    ck_assert(!s.has);
  }
  plot_parse_stock("40", &s, why, sizeof why);
  ck_assert_msg(strstr(why, "DIAMETERxLENGTH"), "%s", why);
  plot_parse_stock("0x100", &s, why, sizeof why);
  ck_assert_msg(strstr(why, "more than 0"), "%s", why);
  plot_parse_stock("20000x100", &s, why, sizeof why);
  ck_assert_msg(strstr(why, "10000"), "%s", why);
}
END_TEST

/* A million calls, many across the whole stock, extreme values, zero-length
 * moves and arcs: no crash, and a picture of them.  How long they take is
 * the bench's to say (make bench), not a unit test's on a loaded machine;
 * a hang runs into the suite's timeout. */
START_TEST(a_million_calls)
{
  struct plot *pl = with_stock(40, 100);
  unsigned x = 12345;
  for (int i = 0; i < 1000000; i++) {
    x = x * 1103515245u + 12345u;
    struct canon_call c = call(CANON_FEED_LINE, 0, 0);
    c.kind = (x >> 8) % 3 == 0 ? CANON_FEED_ARC : (x >> 8) % 3 == 1 ? CANON_FEED_LINE : CANON_TRAVERSE;
    switch ((x >> 12) % 8) {
    case 0: c.pos[0] = INT64_MAX; c.pos[2] = INT64_MIN; break;
    case 1: c.pos[0] = -INT64_MAX; c.pos[2] = INT64_MAX; break;
    case 2: break;   /* zero length, or back to the origin */
    default:
      c.pos[0] = (int64_t)((x >> 4) % 60000) - 10000;
      c.pos[2] = (i & 1) ? 10000 : -130000;
    }
    c.plane = GEOM_XZ;
    c.centre[0] = (x >> 3) % 2 ? c.pos[0] / 2 : INT64_MIN / 3;
    c.centre[1] = (int64_t)(x % 200000) - 100000;
    c.ccw = x & 1;
    put(pl, &c);
  }
  ck_assert(plot_lathe_radius_at(pl, -50) >= 0);
  char path[] = "/tmp/s42-lplot-XXXXXX.png", err[200];
  int fd = mkstemps(path, 4);
  ck_assert_int_ge(fd, 0);
  close(fd);
  ck_assert_msg(plot_write(pl, "million", path, err, sizeof err) == 0, "%s", err);
  unlink(path);
  plot_free(pl);
}
END_TEST

START_TEST(files)
{
  char err[300], dir[] = "/tmp/s42-lplot-XXXXXX", path[400];
  ck_assert_ptr_nonnull(mkdtemp(dir));
  struct plot *pl = lathe_plot(NULL);
  /* no calls: still a picture */
  snprintf(path, sizeof path, "%s/empty.svg", dir);
  ck_assert_msg(plot_write(pl, "empty.u22", path, err, sizeof err) == 0, "%s", err);
  FILE *f = fopen(path, "r");
  ck_assert_ptr_nonnull(f);
  fclose(f);
  snprintf(path, sizeof path, "%s/x.jpg", dir);
  ck_assert_int_eq(plot_write(pl, "p", path, err, sizeof err), -1);
  ck_assert_msg(strstr(err, ".png") && strstr(err, "x.jpg"), "%s", err);
  ck_assert(access(path, F_OK) != 0);
  ck_assert_int_eq(plot_check_path("a.PDF", NULL, err, sizeof err), 0);
  ck_assert_int_eq(plot_check_path("dir.png/", NULL, err, sizeof err), -1);
  ck_assert_int_eq(plot_check_path("png", NULL, err, sizeof err), -1);
  snprintf(path, sizeof path, "%s/nodir/x.png", dir);
  ck_assert_int_eq(plot_write(pl, "p", path, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "nodir"), "%s", err);
  plot_free(pl);
  snprintf(path, sizeof path, "%s/empty.svg", dir);
  unlink(path);
  rmdir(dir);
}
END_TEST

Suite *suite_lplot(void)
{
  Suite *s = suite_create("lplot");
  TCase *tc = tcase_create("lplot");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, silhouette_by_hand);
  tcase_add_test(tc, silhouette_slanted_and_outside);
  tcase_add_test(tc, arcs_turn_the_right_way);
  tcase_add_test(tc, chuck_side);
  tcase_add_test(tc, stock_parses);
  tcase_add_test(tc, a_million_calls);
  tcase_add_test(tc, files);
  suite_add_tcase(s, tc);
  return s;
}
