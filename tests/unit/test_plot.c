/* The plot engine (src/host/plot.h): one engine, a view by the machine's
 * kind -- a grinder's planes and A(t), a lathe's profile, and the neutral
 * planes for any other kind (a mill's path never a lathe's silhouette);
 * fed directly and as the watcher of a runner with a made-up machine. */
#include "suites.h"
#include "canon.h"
#include "mrun.h"
#include "plot.h"
#include "run.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static struct canon_info machine(const char *kind, const char *name)
{
  struct canon_info in;
  memset(&in, 0, sizeof in);
  in.kind = kind;
  in.name = name;
  in.naxes = 3;
  for (int a = 0; a < CANON_AXES; a++)
    in.axis[a].mm = 0.001;
  in.axis[0].name = 'X';
  in.axis[1].name = 'Y';
  in.axis[2].name = 'Z';
  return in;
}

static struct canon_call rec(int kind, const int64_t from[3], const int64_t to[3], double t0, double t1)
{
  struct canon_call c = canon_of(kind);
  for (int a = 0; a < 3; a++) {
    c.from[a] = from[a];
    c.pos[a] = to[a];
  }
  c.t0 = t0;
  c.t1 = t1;
  c.f = 500;
  return c;
}

/* A mill's path: a traverse down, a square pocket's side, an arc in XY. */
static void mill_path(struct plot *pl)
{
  const int64_t o[3] = {0, 0, 5000}, a[3] = {0, 0, -2000}, b[3] = {40000, 0, -2000}, e[3] = {40000, 20000, -2000};
  struct canon_call c = rec(CANON_TRAVERSE, o, a, 0, 1);
  plot_call(pl, &c);
  plot_row(pl, 1, 1);
  c = rec(CANON_FEED_LINE, a, b, 1, 6);
  plot_call(pl, &c);
  plot_row(pl, 2, 6);
  c = rec(CANON_FEED_ARC, b, e, 6, 9);
  c.plane = 0;   /* XY */
  c.centre[0] = 40000;
  c.centre[1] = 10000;
  c.ccw = 1;
  plot_call(pl, &c);
  plot_row(pl, 3, 9);
}

/* The file's text (an SVG), or NULL. */
static char *slurp(const char *path)
{
  FILE *f = fopen(path, "r");
  if (!f)
    return NULL;
  static char buf[1 << 20];
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[n] = 0;
  return buf;
}

START_TEST(view_by_kind)
{
  static const struct { const char *kind, *view; } cases[] = {
    {"grinder", "grinder"}, {"lathe", "lathe"}, {"mill", "planes"}, {"robot", "planes"}, {NULL, "planes"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    struct plot *pl = plot_new(NULL);
    ck_assert_ptr_nonnull(pl);
    ck_assert_str_eq(plot_view_name(pl), "none");
    struct canon_info in = machine(cases[i].kind, "M");
    plot_begin(pl, &in, NULL);
    ck_assert_msg(!strcmp(plot_view_name(pl), cases[i].view), "%s: %s", cases[i].kind ? cases[i].kind : "NULL",
                  plot_view_name(pl));
    plot_free(pl);
  }
  /* a program that did not compile: its machine's kind still chooses */
  struct plot *pl = plot_new(NULL);
  plot_refused(pl, "mill", "E-SYNTAX", 2, 2);
  ck_assert_str_eq(plot_view_name(pl), "planes");
  plot_refused(pl, "lathe", "E-SYNTAX", 2, 2);
  ck_assert_str_eq(plot_view_name(pl), "lathe");
  plot_free(pl);
}
END_TEST

/* A mill's path: the neutral planes (no A panel, no silhouette), its
 * machine named, the end position in X Y Z. */
START_TEST(mill_gets_the_planes)
{
  char dir[] = "/tmp/s42-plot-XXXXXX", path[300], err[300];
  ck_assert_ptr_nonnull(mkdtemp(dir));
  struct plot *pl = plot_new(NULL);
  struct canon_info in = machine("mill", "a test mill");
  const int64_t start[CANON_AXES] = {0, 0, 5000};
  plot_begin(pl, &in, start);
  mill_path(pl);
  struct plot_result res = {0};
  res.n = -1;
  res.blocks = 3;
  res.t = 9;
  plot_end(pl, &res);
  ck_assert_str_eq(plot_view_name(pl), "planes");
  snprintf(path, sizeof path, "%s/mill.svg", dir);
  ck_assert_msg(plot_write(pl, "mill.nc", path, err, sizeof err) == 0, "%s", err);
  const char *svg = slurp(path);
  ck_assert_ptr_nonnull(svg);
  ck_assert_msg(strstr(svg, "<title>mill.nc</title>"), "%.400s", svg);
  ck_assert_msg(strstr(svg, "a test mill, mill): the planes XY, XZ and YZ"), "%.600s", svg);
  ck_assert_msg(strstr(svg, "3 blocks, 9 s simulated; end position X +40  Y +20  Z -2 mm<"), "%.600s", svg);
  ck_assert(!strstr(svg, "turned part") && !strstr(svg, "stock"));
  unlink(path);
  snprintf(path, sizeof path, "%s/mill.png", dir);
  ck_assert_msg(plot_write(pl, "mill.nc", path, err, sizeof err) == 0, "%s", err);
  unlink(path);
  plot_free(pl);
  rmdir(dir);
}
END_TEST

/* The engine as a runner's watcher (run.h): a runner whose made-up machine
 * is a mill gets the neutral view; the stop is captioned. */
static void fake_info(const struct mrun *r, struct canon_info *in)
{
  (void)r;
  *in = machine("mill", "the fixture's mill");
}

static void fake_position(const struct mrun *r, int64_t pos[CANON_AXES])
{
  (void)r;
  memset(pos, 0, CANON_AXES * sizeof *pos);
  pos[0] = 40000;
  pos[1] = 20000;
  pos[2] = -2000;
}

static double fake_time(const struct mrun *r)
{
  (void)r;
  return 9;
}

START_TEST(watcher_of_a_mill)
{
  static struct mrun_rt rt;
  static struct mrun r;
  memset(&rt, 0, sizeof rt);
  memset(&r, 0, sizeof r);
  rt.info = fake_info;
  rt.position = fake_position;
  rt.time = fake_time;
  r.rt = &rt;
  r.vm.blocks = 3;
  struct plot *pl = plot_new(NULL);
  struct run_watch w;
  plot_watch(pl, &w);
  ck_assert_ptr_eq(w.ctx, pl);
  w.start(w.ctx, &r);
  ck_assert_str_eq(plot_view_name(pl), "planes");
  mill_path(pl);
  w.result(w.ctx, &r, 3, NULL, -1, 0, RUN_STOP_KEY);
  char dir[] = "/tmp/s42-plot-XXXXXX", path[300], err[300];
  ck_assert_ptr_nonnull(mkdtemp(dir));
  snprintf(path, sizeof path, "%s/w.svg", dir);
  ck_assert_msg(plot_write(pl, "w.nc", path, err, sizeof err) == 0, "%s", err);
  const char *svg = slurp(path);
  ck_assert_msg(svg && strstr(svg, "stopped (key STOP)</desc>"), "%.600s", svg ? svg : "");
  ck_assert_msg(strstr(svg, "position at the stop X +40  Y +20  Z -2 mm"), "%.600s", svg);
  unlink(path);
  rmdir(dir);
  plot_free(pl);
}
END_TEST

Suite *suite_plot(void)
{
  Suite *s = suite_create("plot");
  TCase *tc = tcase_create("plot");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, view_by_kind);
  tcase_add_test(tc, mill_gets_the_planes);
  tcase_add_test(tc, watcher_of_a_mill);
  suite_add_tcase(s, tc);
  return s;
}
