/* The tooth-search accuracy set: every tool model given is searched with
 * M10 (two sections) and, for every third model, without (two searches in
 * section 1); what was measured is compared with the model: each step within
 * ±0.03°, TK within ±0.5 %, UG within ±0.03°, the tooth count and hand exact.
 *   accuracy tests/toothsearch/NAME.tool ...   exit 1 on any failure */
#include "render.h"
#include "toothsearch.h"

#include <math.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#define STEP_TOL 0.03
#define TK_TOL 0.005
#define UG_TOL 0.03

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + t.tv_nsec * 1e-9;
}

struct worst {
  double step, tk, ug;
  const char *step_at, *tk_at, *ug_at;
};

static void print_model(const char *path, const struct tm_model *m)
{
  printf("  model %s: teeth %d, steps %s, diameter %.0f, lead %.0f, hand %s, noise %g, blur %g, image %d, seed %u\n",
         path, m->teeth, m->even ? "even" : "uneven", m->diameter, m->lead,
         m->hand == TM_RIGHT ? "right" : "left", m->noise, m->blur, m->image, m->seed);
}

/* One search; returns the number of failed checks. */
static int check(const char *path, const struct tm_model *m, int m10, struct worst *w)
{
  double edge[TM_MAX_TEETH], flute[TM_MAX_TEETH];
  ts_geometry(m, 0, edge, flute);
  /* the operator: sections and A from the seed, the probe in the flute
   * before tooth 1 in each (in section 2 a little off where it was) */
  struct ts_request rq;
  memset(&rq, 0, sizeof rq);
  rq.x1_um = 5000.0 + 1000.0 * (m->seed % 7);
  rq.x2_um = m10 ? rq.x1_um + (m->seed % 2 ? 40000.0 : -30000.0) : NAN;
  rq.a1_deg = -20.0 + 3.25 * (m->seed % 13);
  rq.a2_deg = m10 ? ts_follow_flute(m, rq.x1_um, rq.a1_deg, rq.x2_um) + 0.3 * flute[0] * sin(m->seed) : 0;
  rq.hand = m->hand;
  struct ts_result r;
  char err[512];
  double t0 = now();
  int st = ts_search(m, &rq, &r, err, sizeof err);
  double dt = now() - t0;
  const char *mode = m10 ? "M10" : "no M10";
  if (st != TS_OK) {
    printf("FAIL %s (%s): status %d: %s\n", path, mode, st, err);
    print_model(path, m);
    return 1;
  }
  int bad = 0;
  char msg[4096];
  size_t ml = 0;
  msg[0] = 0;
#define NOTE(...) (ml += (size_t)snprintf(msg + ml, ml < sizeof msg ? sizeof msg - ml : 0, __VA_ARGS__))
  if (r.teeth != m->teeth) {
    NOTE("  tooth count %d, the model has %d\n", r.teeth, m->teeth);
    bad++;
  }
  double ws = 0;
  int wk = -1;
  for (int k = 0; k < r.teeth && k < m->teeth; k++) {
    double e = r.steps[k] - m->steps[k];
    if (fabs(e) > fabs(ws)) {
      ws = e;
      wk = k;
    }
  }
  if (fabs(ws) > STEP_TOL) {
    NOTE("  step %d: measured %.4f, model %.4f, error %+.4f deg (limit %.2f)\n", wk + 1, r.steps[wk],
         m->steps[wk], ws, STEP_TOL);
    bad++;
  }
  if (fabs(ws) > fabs(w->step)) {
    w->step = ws;
    w->step_at = path;
  }
  double etk = 0, eug = 0;
  if (m10) {
    if (m->lead > 0) {
      double ug = atan(M_PI * m->diameter / m->lead) * 180 / M_PI;
      etk = (r.tk_um - m->lead) / m->lead;
      eug = r.ug_mdeg / 1000 - ug;
      if (fabs(etk) > TK_TOL) {
        NOTE("  TK %.1f µm, model %.1f µm, error %+.3f %% (limit %.1f %%)\n", r.tk_um, m->lead, 100 * etk,
             100 * TK_TOL);
        bad++;
      }
      if (fabs(eug) > UG_TOL) {
        NOTE("  UG %.4f deg, model %.4f deg, error %+.4f deg (limit %.2f)\n", r.ug_mdeg / 1000, ug, eug, UG_TOL);
        bad++;
      }
      if (r.measured_hand != m->hand || r.hand_mismatch) {
        NOTE("  hand measured %d, model %d\n", r.measured_hand, m->hand);
        bad++;
      }
    } else if (r.tk_um != 0 || r.ug_mdeg != 0 || r.measured_hand != 0) {
      NOTE("  straight flutes, but TK %.1f µm, UG %.4f deg (shift %.5f deg)\n", r.tk_um, r.ug_mdeg / 1000,
           r.shift_deg);
      bad++;
    }
    if (fabs(etk) > fabs(w->tk)) {
      w->tk = etk;
      w->tk_at = path;
    }
    if (fabs(eug) > fabs(w->ug)) {
      w->ug = eug;
      w->ug_at = path;
    }
  }
  if (bad) {
    printf("FAIL %s (%s)\n%s", path, mode, msg);
    print_model(path, m);
  } else {
    printf("ok   %-40s %-6s teeth %3d  step %+.4f", path, mode, r.teeth, ws);
    if (m10 && m->lead > 0)
      printf("  TK %+.3f%%  UG %+.4f", 100 * etk, eug);
    printf("  %.0f ms\n", dt * 1000);
  }
  return bad ? 1 : 0;
}

/* Refusals and the image dump, on one model. */
static int api_checks(const char *path, const struct tm_model *m)
{
  int bad = 0;
  struct ts_request rq;
  struct ts_result r;
  char err[512];
  memset(&rq, 0, sizeof rq);
  rq.x2_um = NAN;
  rq.hand = m->hand;
#define EXPECT(cond, ...) do { if (!(cond)) { printf("FAIL api (%s): ", path); printf(__VA_ARGS__); printf("\n"); bad++; } } while (0)
  rq.speed_deg_min = TS_MAX_SPEED * 2;
  int st = ts_search(m, &rq, &r, err, sizeof err);
  EXPECT(st == TS_E_ARG && strstr(err, "speed"), "speed above the limit: status %d '%s'", st, err);
  rq.speed_deg_min = 0;
  rq.x2_um = rq.x1_um;
  st = ts_search(m, &rq, &r, err, sizeof err);
  EXPECT(st == TS_E_ARG && strstr(err, "section 2"), "equal sections: status %d '%s'", st, err);
  rq.x2_um = NAN;
  rq.hand = 0;
  st = ts_search(m, &rq, &r, err, sizeof err);
  EXPECT(st == TS_E_ARG, "no hand: status %d", st);
  rq.hand = m->hand;
  struct tm_model bad_model = *m;
  bad_model.teeth = 0;
  st = ts_search(&bad_model, &rq, &r, err, sizeof err);
  EXPECT(st == TS_E_ARG && strstr(err, "teeth"), "0 teeth in the model: status %d '%s'", st, err);
  rq.dump_dir = "/nonexistent/dir";
  st = ts_search(m, &rq, &r, err, sizeof err);
  EXPECT(st == TS_E_IO, "dump to a missing parent: status %d '%s'", st, err);
  /* the dump: the images and their annotated twins */
  char dir[] = "/tmp/s42tsXXXXXX";
  if (mkdtemp(dir)) {
    rq.dump_dir = dir;
    rq.write_png = NULL;     /* no writer: the images are not written */
    st = ts_search(m, &rq, &r, err, sizeof err);
    EXPECT(st == TS_E_IO, "dump without write_png: status %d '%s'", st, err);
    rq.write_png = ts_png_write;
    rq.speed_deg_min = 720;
    st = ts_search(m, &rq, &r, err, sizeof err);
    EXPECT(st == TS_OK, "dump: status %d '%s'", st, err);
    EXPECT(fabs(r.time_s - 60.0) < 1e-9, "two revolutions at 720 deg/min: %g s, want 60", r.time_s);
    const char *names[] = {"section1_shot1.png", "section1_shot1_annotated.png",
                           "section1_search2_shot4.png", "section1_search2_shot4_annotated.png"};
    for (int i = 0; i < 4; i++) {
      char f[256];
      struct stat sb;
      snprintf(f, sizeof f, "%s/%s", dir, names[i]);
      EXPECT(stat(f, &sb) == 0 && sb.st_size > 1000, "dump: %s missing", f);
    }
    for (int i = 0; i < TS_SHOTS; i++) {
      const char *tags[] = {"section1", "section1_search2"};
      for (int k = 0; k < 4; k++) {
        char f[256];
        snprintf(f, sizeof f, "%s/%s_shot%d%s.png", dir, tags[k / 2], i + 1, k % 2 ? "_annotated" : "");
        unlink(f);
      }
    }
    rmdir(dir);
  }
  /* the default speed */
  rq.dump_dir = NULL;
  rq.speed_deg_min = 0;
  st = ts_search(m, &rq, &r, err, sizeof err);
  EXPECT(st == TS_OK && fabs(r.time_s - 2 * 360.0 / TS_DEFAULT_SPEED * 60) < 1e-9, "default speed: %g s", r.time_s);
  return bad;
}

int main(int argc, char **argv)
{
  int pass = 0, fail = 0;
  struct worst w = {0, 0, 0, "-", "-", "-"};
  double t0 = now();
  for (int i = 1; i < argc; i++) {
    struct tm_model m;
    char err[512];
    if (tm_load(&m, argv[i], err, sizeof err) != 0) {
      printf("FAIL %s\n  %s\n", argv[i], err);
      fail++;
      continue;
    }
    if (i == 1) {
      if (api_checks(argv[i], &m)) fail++; else pass++;
    }
    if (check(argv[i], &m, 1, &w)) fail++; else pass++;
    if (i % 3 == 1) {
      if (check(argv[i], &m, 0, &w)) fail++; else pass++;
    }
  }
  printf("toothsearch: worst step %+.4f deg (%s), TK %+.3f %% (%s), UG %+.4f deg (%s)\n", w.step, w.step_at,
         100 * w.tk, w.tk_at, w.ug, w.ug_at);
  printf("toothsearch: %d passed, %d failed (%.1f s)\n", pass, fail, now() - t0);
  return fail ? 1 : 0;
}
