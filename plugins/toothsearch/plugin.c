/* The toothsearch plugin: G10 / G11 tooth-step search for a right- / left-
 * hand tool, M10 (lead TK and helix angle UG from two sections), M12 (F is
 * the search speed) -- language.md section 15, contracts.md section 5.
 *
 * This library is light: the descriptor, the operator's flow and the tool
 * model (toolmodel.c), no OpenCV.  init() reads --tool, then dlopens the
 * heavy part, toothsearch/toothsearch-cv.so beside this file (tscv.h), which
 * renders the probe camera's images and measures them, and with
 * --dump-images toothsearch/toothsearch-png.so, which writes them.
 *
 * The flow of one G10 block, each step a call of run() (host->resumed()
 * counts the calls after waits):
 *   directive "упор в перетин 1", service line РУЧНИЙ    wait for Пуск
 *   "пошук в перетині 1", АВТОМАТ: one revolution in section 1
 *   with M10: "упорку в переріз 2", РУЧНИЙ               wait for Пуск while
 *             the operator moves the table and A (S42_WAIT_SECTION)
 *             "пошук в перетині 2": one revolution there
 *   without M10: a second revolution in section 1
 *   results: R99, array 2, TK and UG (M10), P5 and РЕЗУЛЬТАТИ,
 *   "відвести упорку"                                     wait for ПС
 *                                                         wait for Пуск
 * Each revolution takes 360 / speed minutes of simulated time (the default
 * speed TS_DEFAULT_SPEED, or F with M12); the revolutions leave A where
 * it was, the operator's moves count in the position. */
#include <s42_plugin.h>

#include "toolmodel.h"
#include "tscv.h"

#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define ARRAY_CELLS 15

/* where the block's search is */
enum stage { ST_START, ST_SECTION1, ST_SECTION2, ST_RETRACT, ST_DONE };

struct ts {
  const struct s42_host *host;
  struct tm_model model;
  const char *tool;          /* --tool */
  const char *dump;          /* --dump-images, or NULL */
  void *cv_handle;
  const struct ts_cv *cv;
  void *png_handle;          /* --dump-images: the PNG writer (tscv.h) */
  ts_png_fn png;
  /* the block in progress */
  int stage;
  int m10;
  struct ts_request rq;
  struct ts_pass p1, p2;
  struct ts_result res;
  char prefix[24];
  /* the last results, for the trace and the dump */
  int have, fresh, searches;
  double tk, ug;             /* as stored: whole µm and 0.001° */
  int teeth, hand, mismatch, lead;
};

static const struct s42_host *host;

static int init(const struct s42_host *h, const char *dir, void **self)
{
  S42_PLUGIN_INIT(h, host);   /* older than 1.1: the loader never lets it come to this */
  const char *tool = h->option("tool");
  if (!tool || !*tool) {
    h->error(NULL, NULL, "a tooth-step search (G10/G11) needs a tool model: give --tool FILE");
    return S42_FAIL_USAGE;
  }
  struct ts *t = calloc(1, sizeof *t);
  if (!t) {
    h->error(NULL, NULL, "out of memory");
    return S42_FAIL;
  }
  t->host = h;
  t->tool = tool;
  char err[512];
  if (tm_load(&t->model, tool, err, sizeof err)) {
    h->error(NULL, NULL, "%s", err);
    free(t);
    return S42_FAIL_USAGE;
  }
  t->dump = h->option("dump-images");
  if (t->dump) {
    struct stat st;
    if (mkdir(t->dump, 0777) != 0 && errno != EEXIST) {
      h->error(NULL, NULL, "--dump-images %s: %s", t->dump, strerror(errno));
      free(t);
      return S42_FAIL_USAGE;
    }
    if (stat(t->dump, &st) != 0 || !S_ISDIR(st.st_mode) || access(t->dump, W_OK | X_OK) != 0) {
      h->error(NULL, NULL, "--dump-images %s: not a directory s42 can write in", t->dump);
      free(t);
      return S42_FAIL_USAGE;
    }
  }
  /* the heavy part: OpenCV comes with it */
  char path[PATH_MAX];
  if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, TS_CV_FILE) >= sizeof path) {
    h->error(NULL, "E-PLUGIN", "its directory's name is too long");
    free(t);
    return S42_FAIL;
  }
  dlerror();
  t->cv_handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!t->cv_handle) {
    const char *e = dlerror();
    h->error(NULL, "E-PLUGIN", "its OpenCV part cannot be loaded: %s", e ? e : path);
    free(t);
    return S42_FAIL;
  }
  void *sym = dlsym(t->cv_handle, TS_CV_ENTRY);
  ts_cv_entry_fn entry;
  memcpy(&entry, &sym, sizeof entry);
  t->cv = sym ? entry() : NULL;
  if (!t->cv || t->cv->size < sizeof *t->cv || t->cv->version != TS_CV_VERSION) {
    h->error(NULL, "E-PLUGIN", "%s is not its OpenCV part of version %d (no %s() or another version)", path,
             TS_CV_VERSION, TS_CV_ENTRY);
    dlclose(t->cv_handle);
    free(t);
    return S42_FAIL;
  }
  /* --dump-images: OpenCV's imgcodecs comes with the writer, and only then */
  if (t->dump) {
    if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, TS_PNG_FILE) >= sizeof path) {
      h->error(NULL, "E-PLUGIN", "its directory's name is too long");
      dlclose(t->cv_handle);
      free(t);
      return S42_FAIL;
    }
    dlerror();
    t->png_handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    sym = t->png_handle ? dlsym(t->png_handle, TS_PNG_ENTRY) : NULL;
    if (!sym) {
      const char *e = dlerror();
      h->error(NULL, "E-PLUGIN", "no PNG writer for --dump-images: %s", e ? e : path);
      if (t->png_handle)
        dlclose(t->png_handle);
      dlclose(t->cv_handle);
      free(t);
      return S42_FAIL;
    }
    memcpy(&t->png, &sym, sizeof t->png);
  }
  *self = t;
  return S42_OK;
}

static void fini(void *self)
{
  struct ts *t = self;
  if (!t)
    return;
  if (t->png_handle)
    dlclose(t->png_handle);
  if (t->cv_handle)
    dlclose(t->cv_handle);
  free(t);
}

static void reset(void *self)
{
  struct ts *t = self;
  t->stage = ST_START;
  t->have = t->fresh = t->searches = 0;
}

static int gnum(struct s42_block *b)
{
  return host->has_g(b, 10) ? 10 : 11;
}

static int check(void *self, struct s42_block *b)
{
  (void)self;
  if (!host->has_g(b, 10) && !host->has_g(b, 11))
    return S42_OK;   /* M10 and M12 stand only beside them (s42 check) */
  if (!(host->param(b, S42_D1) > 0)) {
    host->error(b, "E-RANGE", "G%d needs the tool's diameter: D1 > 0 in this block or before it", gnum(b));
    return S42_FAIL;
  }
  if (host->has_m(b, 12)) {
    if (!host->has_word(b, 'F')) {
      host->error(b, "E-BLOCK", "M12 takes the search speed from F in the same block, and there is none");
      return S42_FAIL;
    }
    if (!(host->word(b, 'F') > 0)) {
      host->error(b, "E-FEED", "M12 F0: the search cannot turn the tool at speed 0");
      return S42_FAIL;
    }
  }
  return S42_OK;
}

/* A pass's or the combination's failure: E-TEETH for what the search
 * found (or could not), E-PLUGIN for the plugin's own trouble. */
static int failed(struct s42_block *b, int st, const char *err)
{
  host->error(b, st == TS_E_TEETH || st == TS_E_ARG ? "E-TEETH" : "E-PLUGIN", "%s", err);
  return S42_FAIL;
}

/* One revolution: the directive, the time, the measurement. */
static int revolution(struct ts *t, struct s42_block *b, int which, int msg, struct ts_pass *out)
{
  char err[512];
  host->mode(b, S42_MODE_AUTO);
  host->directive(b, host->text(b, msg));
  host->dwell(b, t->cv->revolution_time(t->rq.speed_deg_min));
  int st = t->cv->pass(&t->model, &t->rq, which, out, err, sizeof err);
  if (st != TS_OK)
    return failed(b, st, err);
  t->searches++;
  if (out->images_failed)
    host->warn(b, "--dump-images %s: some images of this search could not be written", t->dump);
  return S42_OK;
}

/* Steps in 0.001°, rounded to whole discretes so that they still sum to
 * 360000: the largest remainders take the difference. */
static void whole_steps(const double *deg, int n, double *out)
{
  int order[TM_MAX_TEETH];
  long long left = 360000;
  for (int i = 0; i < n; i++) {
    out[i] = floor(deg[i] * 1000.0);
    left -= (long long)out[i];
    order[i] = i;
  }
  /* by remainder, largest first (n <= 150: insertion sort) */
  for (int i = 1; i < n; i++)
    for (int j = i; j > 0; j--) {
      double rj = deg[order[j]] * 1000.0 - out[order[j]], rp = deg[order[j - 1]] * 1000.0 - out[order[j - 1]];
      if (rj <= rp)
        break;
      int x = order[j];
      order[j] = order[j - 1];
      order[j - 1] = x;
    }
  for (int i = 0; i < n && left > 0; i++, left--)
    out[order[i]] += 1;
}

/* The results into the machine and onto the screen. */
static int publish(struct ts *t, struct s42_block *b)
{
  const struct ts_result *r = &t->res;
  double steps[TM_MAX_TEETH];
  whole_steps(r->steps, r->teeth, steps);
  if (host->set_param(b, 99, r->teeth) ||
      host->load_array(b, 2, steps, r->teeth < ARRAY_CELLS ? r->teeth : ARRAY_CELLS)) {
    host->error(b, "E-PLUGIN", "the results could not be stored");
    return S42_FAIL;
  }
  t->teeth = r->teeth;
  t->lead = t->m10;
  t->hand = r->measured_hand;
  t->mismatch = r->hand_mismatch;
  if (t->m10) {
    /* straight flutes (or a lead beyond the largest TK) read 0 and 0 */
    t->tk = round(r->tk_um);
    t->ug = round(r->ug_mdeg);
    if (host->set_param(b, S42_TK, t->tk) || host->set_param(b, S42_UG, t->ug)) {
      host->error(b, "E-PLUGIN", "TK and UG could not be stored");
      return S42_FAIL;
    }
  }
  struct s42_results res = {sizeof res, r->teeth, steps, t->m10, t->tk, t->ug, r->measured_hand};
  host->results(b, &res);
  char line[200];
  int k = snprintf(line, sizeof line, "N%d: %d teeth, steps", host->number(b), r->teeth);
  for (int i = 0; i < r->teeth && i < 8 && k < (int)sizeof line; i++)
    k += snprintf(line + k, sizeof line - (size_t)k, " %.3f", r->steps[i]);
  if (k < (int)sizeof line && r->teeth > 8)
    k += snprintf(line + k, sizeof line - (size_t)k, " ...");
  if (k < (int)sizeof line && t->m10)
    snprintf(line + k, sizeof line - (size_t)k, "; TK %.0f µm, UG %.0f (0.001°), %s hand", t->tk, t->ug,
             r->measured_hand > 0 ? "right" : r->measured_hand < 0 ? "left" : "no (straight flutes)");
  host->log(b, "%s", line);
  host->mode(b, S42_MODE_RESULTS);
  host->directive(b, host->text(b, S42_MSG_RETRACT_PROBE));
  if (r->hand_mismatch) {
    int g = gnum(b);
    host->warn(b, "the flutes measured %s-hand, but G%d says %s-hand", r->measured_hand > 0 ? "right" : "left",
               g, g == 10 ? "right" : "left");
    host->message(b, host->text(b, r->measured_hand > 0 ? S42_MSG_HAND_RIGHT : S42_MSG_HAND_LEFT));
  }
  t->have = 1;
  return S42_OK;
}

/* Section 2 (M10): is the probe in the flute before tooth 1, where the
 * operator who follows the flute from section 1 puts it?  If not, the
 * tooth order starts at another tooth and the lead comes out wrong. */
static void placement(struct ts *t, struct s42_block *b)
{
  const struct ts_request *q = &t->rq;
  if (t->cv->first_tooth(&t->model, q->x1_um, q->a1_deg, q->x2_um, q->a2_deg) == 0)
    return;
  double want = t->cv->follow_flute(&t->model, q->x1_um, q->a1_deg, q->x2_um);
  double turn = fmod(want - q->a1_deg, 360.0);
  if (turn > 180)
    turn -= 360;
  else if (turn < -180)
    turn += 360;
  host->warn(b, "section 2: the probe is not in the flute before tooth 1; following the flute from section 1 "
                "turns A by %+.0f (0.001°) with the table's %+.0f µm: TK and UG will be wrong",
             turn * 1000.0, q->x2_um - q->x1_um);
}

static int run(void *self, struct s42_block *b)
{
  struct ts *t = self;
  if (!host->has_g(b, 10) && !host->has_g(b, 11))
    return S42_OK;
  if (host->resumed(b) == 0)
    t->stage = ST_START;
  switch (t->stage) {
  case ST_START:
    memset(&t->rq, 0, sizeof t->rq);
    memset(&t->res, 0, sizeof t->res);
    t->m10 = host->has_m(b, 10);
    t->rq.hand = host->has_g(b, 10) ? TM_RIGHT : TM_LEFT;
    t->rq.diameter_um = host->param(b, S42_D1);
    t->rq.speed_deg_min = host->has_m(b, 12) ? host->word(b, 'F') : 0;
    t->rq.x2_um = NAN;
    t->rq.dump_dir = t->dump;
    t->rq.write_png = t->png;
    if (host->number(b) > 0)
      snprintf(t->prefix, sizeof t->prefix, "N%d_", host->number(b));
    else
      snprintf(t->prefix, sizeof t->prefix, "N-_");
    t->rq.dump_prefix = t->prefix;
    t->fresh = 0;
    host->mode(b, S42_MODE_MANUAL);
    host->directive(b, host->text(b, S42_MSG_PROBE_SECTION1));
    t->stage = ST_SECTION1;
    return S42_WAIT_PUSK;
  case ST_SECTION1: {
    /* Пуск: the probe is in the flute before the first tooth */
    t->rq.x1_um = (double)host->position(b, S42_X);
    t->rq.a1_deg = (double)host->position(b, S42_A) / 1000.0;
    if (revolution(t, b, 0, S42_MSG_SEARCH_SECTION1, &t->p1))
      return S42_FAIL;
    if (t->m10) {
      host->mode(b, S42_MODE_MANUAL);
      host->directive(b, host->text(b, S42_MSG_PROBE_SECTION2));
      t->stage = ST_SECTION2;
      return S42_WAIT_SECTION;
    }
    /* without M10: the second revolution at once, in section 1 */
    if (revolution(t, b, 1, S42_MSG_SEARCH_SECTION1, &t->p2))
      return S42_FAIL;
    break;
  }
  case ST_SECTION2:
    /* Пуск in section 2: where the table and A are now */
    t->rq.x2_um = (double)host->position(b, S42_X);
    t->rq.a2_deg = (double)host->position(b, S42_A) / 1000.0;
    if (fabs(t->rq.x2_um - t->rq.x1_um) < 1.0) {
      host->error(b, "E-TEETH", "section 2 is where section 1 was (X %+.0f): M10 needs the table moved along "
                                "the tool to measure the lead", t->rq.x2_um);
      return S42_FAIL;
    }
    placement(t, b);
    if (revolution(t, b, 1, S42_MSG_SEARCH_SECTION2, &t->p2))
      return S42_FAIL;
    break;
  case ST_RETRACT:
    /* ПС: the probe is out; Пуск goes on */
    host->directive(b, NULL);
    t->stage = ST_DONE;
    return S42_WAIT_PUSK;
  default:
    t->stage = ST_START;
    t->fresh = 1;
    return S42_OK;
  }
  /* both revolutions done: the results */
  char err[512];
  int st = t->cv->combine(&t->model, &t->rq, &t->p1, &t->p2, &t->res, err, sizeof err);
  if (st != TS_OK)
    return failed(b, st, err);
  if (publish(t, b))
    return S42_FAIL;
  t->stage = ST_RETRACT;
  return S42_WAIT_PS;
}

/* The trace row of the search block, and the dump: the last results. */
static size_t describe(void *self, int what, char *buf, size_t cap)
{
  struct ts *t = self;
  if (!t->have || (what == S42_DESCRIBE_TRACE && !t->fresh))
    return 0;
  if (what == S42_DESCRIBE_TRACE)
    t->fresh = 0;
  int k = snprintf(buf, cap, "{\"teeth\":%d", t->teeth);
  if (k >= 0 && (size_t)k < cap && t->lead)
    k += snprintf(buf + k, cap - (size_t)k, ",\"tk\":%.0f,\"ug\":%.0f,\"hand\":\"%s\",\"mismatch\":%s", t->tk,
                  t->ug, t->hand > 0 ? "right" : t->hand < 0 ? "left" : "straight",
                  t->mismatch ? "true" : "false");
  if (k >= 0 && (size_t)k < cap && what == S42_DESCRIBE_DUMP)
    k += snprintf(buf + k, cap - (size_t)k, ",\"revolutions\":%d", t->searches);
  if (k >= 0 && (size_t)k < cap)
    k += snprintf(buf + k, cap - (size_t)k, "}");
  return k < 0 ? 0 : (size_t)k;
}

static const struct s42_function functions[] = {
  S42_G_FUNCTION(10, 1, "F", S42_FN_SEPARATE, "tooth-step search, right-hand tool (needs --tool)"),
  S42_G_FUNCTION(11, 1, "F", S42_FN_SEPARATE, "tooth-step search, left-hand tool (needs --tool)"),
  S42_M_FUNCTION(10, "F", 0, "with G10/G11: also lead TK and helix angle UG (two sections)"),
  S42_M_FUNCTION(12, "F", 0, "with G10/G11: F is the search speed, deg/min"),
};

S42_PLUGIN_DECLARE("toothsearch", "1.0",
                   "tooth-step search on simulated probe images (G10 G11 M10 M12; OpenCV, loaded on first use)",
                   functions, .init = init, .fini = fini, .check = check, .run = run, .describe = describe,
                   .trace_key = "search", .reset = reset);
