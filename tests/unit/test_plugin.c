/* Plugins: the loader against the fixture plugins (tests/plugins: good,
 * wrong ABI, no entry symbol, init fails, callbacks fail or crash), E-PLUGIN when a
 * plugin is missing, and the oscillation and helix plugins run through
 * sessions.  The make target passes the directories: S42_FIXTURES (one
 * folder per fixture) and S42_PLUGINS (the built plugins). */
#include "suites.h"
#include "errors.h"
#include "plugin.h"
#include "session.h"
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#define MAXROWS 64

static struct plug_set ps;
static struct plug_set ps2, many[PLUG_THUNKS + 1];   /* more sets in the process */
static struct tprog t;
static struct session *s;
static struct sess_row rows[MAXROWS];
static char extras[MAXROWS][64];
static int nrows, nwarn, nmoved;
static char lastwarn[240];

static const char *dir_of(const char *env, const char *sub)
{
  static char buf[4096];
  const char *d = getenv(env);
  ck_assert_msg(d != NULL, "%s is not set (run through make unit)", env);
  snprintf(buf, sizeof buf, "%s%s%s", d, sub ? "/" : "", sub ? sub : "");
  return buf;
}

static void on_row(void *ctx, const struct session *ss, const struct sess_row *r)
{
  (void)ctx;
  (void)ss;
  ck_assert_int_lt(nrows, MAXROWS);
  rows[nrows] = *r;
  snprintf(extras[nrows], sizeof extras[nrows], "%s", r->extra ? r->extra : "");
  nrows++;
}

static void on_warn(void *ctx, const struct session *ss, const char *msg)
{
  (void)ctx;
  (void)ss;
  nwarn++;
  snprintf(lastwarn, sizeof lastwarn, "%s", msg);
}

static void on_moved(void *ctx, const struct session *ss, int axis, int64_t d)
{
  (void)ctx;
  (void)ss;
  (void)axis;
  (void)d;
  nmoved++;
}

static void setup(void)
{
  memset(&t, 0, sizeof t);
  memset(&ps, 0, sizeof ps);
  prog_init(&t.p);
  diag_init(&t.d, "t.kp");
  s = calloc(1, sizeof *s);
  nrows = nwarn = nmoved = 0;
  lastwarn[0] = 0;
}

static void teardown(void)
{
  tp_free(&t);
  free(s);
  plug_free(&ps);
  plug_free(&ps2);
  for (size_t k = 0; k < sizeof many / sizeof many[0]; k++)
    plug_free(&many[k]);
}

static void compile_with(const char *src)
{
  tp_free(&t);
  t.src = src;
  prog_init(&t.p);
  diag_init(&t.d, "t.kp");
  t.rc = comp_program_with(src, strlen(src), &t.d, &t.p, &ps);
}

static void load(const char *src)
{
  compile_with(src);
  ck_assert_msg(t.rc == 0, "does not compile:\n%s", tp_diags(&t.d));
  sess_init(s, &t.p);
  s->plugins = &ps;
  s->crashes = ps.crashes;   /* as sess_configure does */
  s->sink.row = on_row;
  s->sink.warn = on_warn;
  s->sink.moved = on_moved;
}

static enum sess_ev go(void)
{
  enum sess_ev ev;
  while ((ev = sess_run(s)) == SE_START)
    ;
  return ev;
}

/* ---- the loader and the fixtures ---- */

START_TEST(good_plugin_loads_and_runs)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "good"));
  const struct s42_function *fn;
  int i = plug_find(&ps, 'G', 50, &fn);
  ck_assert_int_ge(i, 0);
  ck_assert_str_eq(ps.v[i].d->name, "good");
  ck_assert_int_eq(fn->group, 1);
  ck_assert_int_eq(ps.v[i].state, PLUG_FOUND);     /* init waits for a program that needs it */
  load("N1 G50 X+5000 F1000 M30\nN2 M30\nN3 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(ps.v[i].state, PLUG_READY);
  ck_assert_double_eq(s->vm.reg[1], 2);
  ck_assert_int_eq(s->m.pos[0], 5000);
  ck_near(s->m.t, 0.3, 1e-9);
  ck_assert_int_eq(nrows, 3);          /* each block has machine work */
  ck_assert_str_eq(rows[0].motion, "G50");
}
END_TEST

START_TEST(good_plugin_check_error)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "good"));
  load("N1 R1+7\nN2 G50 X+13 F1000\nN3 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_RANGE);
  ck_assert_str_eq(s->vm.err.msg, "G50: X+13 is unlucky");
  ck_assert_int_eq(s->m.pos[0], 0);
}
END_TEST

START_TEST(plugin_functions_take_their_words)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "good"));
  compile_with("N1 G50 Z+10 F100\nN2 M2\n");
  ck_assert_int_ge(tp_find(&t.d, DIAG_ERROR, S42_E_BLOCK, 1, 8), 0);
  compile_with("N1 G50 G01 X+10 F100\nN2 M2\n");
  ck_assert_int_ge(tp_find(&t.d, DIAG_ERROR, S42_E_GROUP, 1, 0), 0);
}
END_TEST

START_TEST(unknown_function_without_plugin)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "initfail"));
  compile_with("N1 G50 X+10 F100\nN2 M2\n");
  ck_assert_int_ge(tp_find(&t.d, DIAG_ERROR, S42_E_FUNC, 1, 4), 0);
}
END_TEST

START_TEST(wrong_abi_refused)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "wrongabi"));
  ck_assert_int_eq(plug_find(&ps, 'G', 51, NULL), -1);
  ck_assert_uint_eq(ps.nbad, 1);
  ck_assert_ptr_nonnull(strstr(ps.bad[0].msg, "built for plugin ABI 2.0"));
  ck_assert_ptr_nonnull(strstr(ps.bad[0].msg, "this s42 has ABI 1.1"));
}
END_TEST

START_TEST(no_entry_refused)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "noentry"));
  ck_assert_uint_eq(ps.nbad, 0);          /* nothing is opened by scanning */
  plug_open_all(&ps);
  ck_assert_uint_eq(ps.nbad, 1);
  ck_assert_ptr_nonnull(strstr(ps.bad[0].msg, "no entry symbol s42_plugin_entry"));
}
END_TEST

/* A program that uses no plugin function opens no plugin file; one that
 * uses a function the language does not have opens files until one
 * provides it; G12 opens the helix plugin's file and no other. */
START_TEST(files_open_only_when_needed)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "good"));
  ck_assert_uint_eq(ps.nfiles, 1);
  load("N1 G01 X+10 F100 M03\nN2 G04 X+1\nN3 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_uint_eq(ps.n, 0);
  ck_assert_int_eq(ps.files[0].state, PF_NEW);
  load("N1 M30\nN2 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_uint_eq(ps.n, 1);
  ck_assert_int_eq(ps.files[0].state, PF_OPEN);
  ck_assert_double_eq(s->vm.reg[1], 1);
  plug_free(&ps);
  plug_scan(&ps, dir_of("S42_PLUGINS", NULL));
  ck_assert_uint_ge(ps.nfiles, 3);
  compile_with("N1 G12 G17 X+0 Y+0 I-1000 J+0 Z+10 F100\nN2 M2\n");
  ck_assert_int_eq(t.rc, 0);
  ck_assert_uint_eq(ps.n, 1);
  ck_assert_str_eq(ps.v[0].d->name, "helix");
  for (size_t f = 0; f < ps.nfiles; f++)
    ck_assert_int_eq(ps.files[f].state, strcmp(ps.files[f].stem, "helix") == 0 ? PF_OPEN : PF_NEW);
}
END_TEST

/* The probe loads a file in a child: what its constructor does there is
 * reported, never suffered (the badctor fixture chooses by S42_BADCTOR). */
START_TEST(probe_survives_constructors)
{
  char why[300], so[4096];
  snprintf(so, sizeof so, "%s", dir_of("S42_FIXTURES", "badctor/badctor.so"));
  unsetenv("S42_BADCTOR");
  ck_assert_int_eq(plug_probe(so, why, sizeof why), 0);
  setenv("S42_BADCTOR", "crash", 1);
  ck_assert_int_eq(plug_probe(so, why, sizeof why), -1);
  ck_assert_str_eq(why, "cannot be used: its constructor crashed: signal 11 (SIGSEGV)");
  setenv("S42_BADCTOR", "exit", 1);
  ck_assert_int_eq(plug_probe(so, why, sizeof why), -1);
  ck_assert_str_eq(why, "cannot be used: loading it ended the process: exit 0");
  /* a program that needs it: E-FUNC, the file refused with the reason */
  plug_scan(&ps, dir_of("S42_FIXTURES", "badctor"));
  compile_with("N1 G53\nN2 M2\n");
  unsetenv("S42_BADCTOR");
  ck_assert_int_ge(tp_find(&t.d, DIAG_ERROR, S42_E_FUNC, 1, 4), 0);
  ck_assert_uint_eq(ps.nbad, 1);
  ck_assert_ptr_nonnull(strstr(ps.bad[0].msg, "loading it ended the process: exit 0"));
  ck_assert_int_eq(ps.files[0].state, PF_REFUSED);
  /* the probe's verdict stands for the process: the file is not tried again */
  compile_with("N1 G53\nN2 M2\n");
  ck_assert_int_ge(tp_find(&t.d, DIAG_ERROR, S42_E_FUNC, 1, 4), 0);
}
END_TEST

START_TEST(init_failure_is_e_plugin)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "initfail"));
  load("N1 G01 X+10 F100\nN2 M2\n");       /* does not use it: never started */
  ck_assert_int_eq(go(), SE_END);
  int i = plug_find(&ps, 'M', 31, NULL);
  ck_assert_int_eq(ps.v[i].state, PLUG_FOUND);
  load("N1 G01 X+10 F100\nN2 M31\nN3 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_PLUGIN);
  ck_assert_ptr_nonnull(strstr(s->vm.err.msg, "initfail plugin"));
  ck_assert_ptr_nonnull(strstr(s->vm.err.msg, "failed to start: the fixture's licence is missing"));
  ck_assert_int_eq(ps.v[i].usage, 0);
  ck_assert_int_eq(s->m.pos[0], 10);
}
END_TEST

START_TEST(abi_10_plugin_still_loads)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "old10"));
  ck_assert_uint_eq(ps.nbad, 0);
  int i = plug_find(&ps, 'M', 8, NULL);
  ck_assert_int_ge(i, 0);
  ck_assert_int_eq(ps.v[i].d->abi_minor, 0);
  load("N1 R5+1\nN4 M8\nN5 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_double_eq(s->vm.reg[5], 14);
}
END_TEST

START_TEST(failing_callbacks)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "cbfail"));
  load("N1 M24\nN2 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_TEETH);
  ck_assert_str_eq(s->vm.err.msg, "no teeth found (fixture)");
  load("N1 G52\nN2 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_PLUGIN);
  ck_assert_ptr_nonnull(strstr(s->vm.err.msg, "cbfail plugin failed in check()"));
}
END_TEST

/* A block that fails after its plugin wrote registers and arrays leaves
 * them as after the block before it (language.md sec. 7): the host's
 * set_param and load_array are part of the block's transaction. */
START_TEST(failed_block_rolls_back_plugin_writes)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "txfail"));
  load("N1 R1+7 R0+5\nN2 M06\nN3 M07\nN4 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_TEETH);
  ck_assert_int_eq(sess_block_number(s), 3);
  /* as N2 left them */
  ck_assert_double_eq(s->vm.reg[0], 599);
  ck_assert_double_eq(s->vm.reg[1], 8);       /* written after 600 writes of R0 */
  ck_assert_double_eq(s->vm.reg[REG_TK], 1002);
  ck_assert_double_eq(s->vm.reg[REG_UG], 2002);
  ck_assert_int_eq(s->vm.arr[0].len, 3);
  ck_assert_double_eq(s->vm.arr[0].cell[0], 2);
  ck_assert_int_eq(s->vm.arr[1].len, 5);
  ck_assert_double_eq(s->vm.arr[1].cell[4], 2);
  /* the first block a plugin writes in fails: nothing of it stays */
  load("N1 R1+7\nN3 M07\nN4 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_double_eq(s->vm.reg[0], 0);
  ck_assert_double_eq(s->vm.reg[1], 7);
  ck_assert_double_eq(s->vm.reg[REG_TK], 0);
  ck_assert_int_eq(s->vm.arr[0].len, 0);
  ck_assert_double_eq(s->vm.arr[0].cell[0], 0);
  ck_assert_int_eq(s->vm.arr[1].len, 0);
}
END_TEST

START_TEST(missing_plugin_is_e_plugin_at_check)
{
  plug_scan(&ps, "/nonexistent/plugins");
  compile_with("N1 G12 G17 X+0 Y+0 I-1000 J+0 Z+10 F100\nN2 G07 Z+10 F10\nN3 M2\n");
  int k = tp_find(&t.d, DIAG_ERROR, S42_E_PLUGIN, 1, 4);
  ck_assert_int_ge(k, 0);
  ck_assert_ptr_nonnull(strstr(t.d.v[k].msg, "G12 (helical interpolation) needs the helix plugin"));
  ck_assert_ptr_nonnull(strstr(t.d.v[k].msg, "/nonexistent/plugins"));
  k = tp_find(&t.d, DIAG_ERROR, S42_E_PLUGIN, 2, 4);
  ck_assert_int_ge(k, 0);
  ck_assert_ptr_nonnull(strstr(t.d.v[k].msg, "oscillation plugin"));
  /* with no plugin set at all */
  t.rc = 0;
  tp_free(&t);
  tp_compile(&t, "N1 G13 G18 Y+0 Z+0 J-1000 K+0 F100\nN2 M2\n");
  ck_assert_int_ge(tp_find(&t.d, DIAG_ERROR, S42_E_PLUGIN, 1, 4), 0);
}
END_TEST

/* ---- two plugin sets in one process ---- */

/* Two sessions, each with its own set and options (s42 run --tool A and
 * --tool B in one process), run a block at a time in turn: each plugin
 * gets its own set's options in init() and in every later callback. */
struct rows { struct sess_row r[8]; char extra[8][96]; int n; };

static void on_row_ctx(void *ctx, const struct session *ss, const struct sess_row *r)
{
  struct rows *rs = ctx;
  (void)ss;
  ck_assert_int_lt(rs->n, 8);
  rs->r[rs->n] = *r;
  snprintf(rs->extra[rs->n], sizeof rs->extra[rs->n], "%s", r->extra ? r->extra : "");
  rs->n++;
}

START_TEST(two_sets_two_tools)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "opts"));
  plug_scan(&ps2, dir_of("S42_FIXTURES", "opts"));
  plug_set_option(&ps, "tool", "a.tool");
  plug_set_option(&ps2, "tool", "bb.tool");
  plug_set_option(&ps2, "lang", "en");
  plug_set_option(&ps2, "no-such-option", "x");   /* ignored */
  ck_assert_str_eq(plug_get_option(&ps, "tool"), "a.tool");
  ck_assert_str_eq(plug_get_option(&ps2, "tool"), "bb.tool");
  ck_assert_str_eq(plug_get_option(&ps, "lang"), "uk");
  ck_assert_str_eq(plug_get_option(&ps2, "lang"), "en");
  ck_assert_ptr_null(plug_get_option(&ps, "dump-images"));
  ck_assert_ptr_null(plug_get_option(&ps2, "no-such-option"));
  ck_assert_str_eq(plug_get_option(NULL, "lang"), "uk");

  static const char src[] = "N1 M01\nN2 M01\nN3 M2\n";
  struct tprog ta, tb;
  struct session *sa = calloc(1, sizeof *sa), *sb = calloc(1, sizeof *sb);
  struct rows ra = {0}, rb = {0};
  ck_assert(sa && sb);
  prog_init(&ta.p);
  diag_init(&ta.d, "a.kp");
  prog_init(&tb.p);
  diag_init(&tb.d, "b.kp");
  ck_assert_int_eq(comp_program_with(src, strlen(src), &ta.d, &ta.p, &ps), 0);
  ck_assert_int_eq(comp_program_with(src, strlen(src), &tb.d, &tb.p, &ps2), 0);
  sess_init(sa, &ta.p);
  sess_init(sb, &tb.p);
  sa->plugins = &ps;
  sb->plugins = &ps2;
  sa->sink.row = sb->sink.row = on_row_ctx;
  sa->sink.ctx = &ra;
  sb->sink.ctx = &rb;
  uint8_t watch[3] = {1, 1, 1};
  sa->vm.watch = sb->vm.watch = watch;
  /* block by block, in turn: A N1 starts, B N1 starts, A's N1 runs
   * (its plugin starts) and N2 starts, then B's */
  for (int k = 0; k < 3; k++) {
    ck_assert_int_eq(sess_run(sa), SE_START);
    ck_assert_int_eq(sess_run(sb), SE_START);
    if (k == 1) {
      ck_assert_double_eq(sa->vm.reg[1], 6);    /* strlen("a.tool") */
      ck_assert_double_eq(sb->vm.reg[1], 7);    /* strlen("bb.tool") */
    }
  }
  enum sess_ev ev;
  while ((ev = sess_run(sa)) == SE_START)
    ;
  ck_assert_int_eq(ev, SE_END);
  while ((ev = sess_run(sb)) == SE_START)
    ;
  ck_assert_int_eq(ev, SE_END);
  ck_assert_int_eq(ra.n, 3);
  ck_assert_int_eq(rb.n, 3);
  for (int i = 0; i < 2; i++) {
    ck_assert_str_eq(ra.extra[i], ",\"opts\":{\"init\":\"a.tool\",\"now\":\"a.tool\",\"lang\":\"uk\"}");
    ck_assert_str_eq(rb.extra[i], ",\"opts\":{\"init\":\"bb.tool\",\"now\":\"bb.tool\",\"lang\":\"en\"}");
  }
  /* the same shared object, started once in each set, with its own table */
  int ia = plug_find(&ps, 'M', 1, NULL), ib = plug_find(&ps2, 'M', 1, NULL);
  ck_assert_int_ge(ia, 0);
  ck_assert_int_ge(ib, 0);
  ck_assert_ptr_eq(ps.v[ia].d, ps2.v[ib].d);
  ck_assert_ptr_ne(ps.v[ia].self, ps2.v[ib].self);
  ck_assert(ps.host.option != ps2.host.option);
  tp_free(&ta);
  tp_free(&tb);
  free(sa);
  free(sb);
}
END_TEST

/* init()'s reason (error(NULL, ...)) belongs to the plugin that starts: a
 * set whose tool is refused says so; the other set's plugin is not hurt */
START_TEST(init_reason_is_the_set_s)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "opts"));
  plug_scan(&ps2, dir_of("S42_FIXTURES", "opts"));
  plug_set_option(&ps, "tool", "fail");
  plug_set_option(&ps2, "tool", "fine");
  static const char src[] = "N1 M01\nN2 M2\n";
  load(src);
  char msg[300] = "";
  size_t block = 99;
  ck_assert_int_eq(sess_start_plugins(s, msg, sizeof msg, &block), -1);
  ck_assert_str_eq(msg, "the tool is fail");
  ck_assert_uint_eq(block, 0);
  int i = plug_find(&ps, 'M', 1, NULL);
  ck_assert_int_eq(ps.v[i].usage, 1);
  ck_assert_ptr_nonnull(strstr(ps.v[i].err, "failed to start: the tool is fail"));
  struct tprog tb;
  prog_init(&tb.p);
  diag_init(&tb.d, "b.kp");
  ck_assert_int_eq(comp_program_with(src, strlen(src), &tb.d, &tb.p, &ps2), 0);
  struct session *sb = calloc(1, sizeof *sb);
  ck_assert_ptr_nonnull(sb);
  sess_init(sb, &tb.p);
  sb->plugins = &ps2;
  ck_assert_int_eq(sess_start_plugins(sb, msg, sizeof msg, &block), 0);
  int k = plug_find(&ps2, 'M', 1, NULL);
  ck_assert_int_eq(ps2.v[k].state, PLUG_READY);
  ck_assert_str_eq(ps2.v[k].reason, "");
  /* said outside any init(): nobody's reason */
  plug_init_reason("stray");
  ck_assert_str_eq(ps2.v[k].reason, "");
  ck_assert_str_eq(ps.v[i].reason, "the tool is fail");
  tp_free(&tb);
  free(sb);
}
END_TEST

/* More sets at once than there are option() functions: the one beyond
 * still gets its own options in init(), and NULL outside it; freeing a set
 * gives its function to the next. */
START_TEST(sets_beyond_the_thunks)
{
  static const char src[] = "N1 M01\nN2 M2\n";
  static char tools[PLUG_THUNKS + 1][16];
  char buf[160];
  for (int k = 0; k <= PLUG_THUNKS; k++) {
    plug_scan(&many[k], dir_of("S42_FIXTURES", "opts"));
    snprintf(tools[k], sizeof tools[k], "t%d", k);
    plug_set_option(&many[k], "tool", tools[k]);
    struct tprog tk;
    prog_init(&tk.p);
    diag_init(&tk.d, "k.kp");
    ck_assert_int_eq(comp_program_with(src, strlen(src), &tk.d, &tk.p, &many[k]), 0);
    struct session *sk = calloc(1, sizeof *sk);
    ck_assert_ptr_nonnull(sk);
    sess_init(sk, &tk.p);
    sk->plugins = &many[k];
    ck_assert_int_eq(sess_start_plugins(sk, buf, sizeof buf, &(size_t){0}), 0);
    tp_free(&tk);
    free(sk);
  }
  for (int k = 0; k <= PLUG_THUNKS; k++) {
    int i = plug_find(&many[k], 'M', 1, NULL);
    struct plug *p = &many[k].v[i];
    ck_assert_int_eq(p->state, PLUG_READY);
    p->d->describe(p->self, S42_DESCRIBE_TRACE, buf, sizeof buf);
    char want[160];
    if (k < PLUG_THUNKS)
      snprintf(want, sizeof want, "{\"init\":\"t%d\",\"now\":\"t%d\",\"lang\":\"uk\"}", k, k);
    else
      snprintf(want, sizeof want, "{\"init\":\"t%d\",\"now\":\"\",\"lang\":\"uk\"}", k);
    ck_assert_str_eq(buf, want);
    ck_assert_int_eq(many[k].thunk != 0, k < PLUG_THUNKS);
  }
  plug_free(&many[3]);
  plug_scan(&many[3], dir_of("S42_FIXTURES", "opts"));
  plug_set_option(&many[3], "tool", "again");
  struct tprog tk;
  prog_init(&tk.p);
  diag_init(&tk.d, "k.kp");
  ck_assert_int_eq(comp_program_with(src, strlen(src), &tk.d, &tk.p, &many[3]), 0);
  struct session *sk = calloc(1, sizeof *sk);
  ck_assert_ptr_nonnull(sk);
  sess_init(sk, &tk.p);
  sk->plugins = &many[3];
  ck_assert_int_eq(sess_start_plugins(sk, buf, sizeof buf, &(size_t){0}), 0);
  ck_assert_int_eq(many[3].thunk, 4);
  struct plug *p = &many[3].v[plug_find(&many[3], 'M', 1, NULL)];
  p->d->describe(p->self, S42_DESCRIBE_TRACE, buf, sizeof buf);
  ck_assert_str_eq(buf, "{\"init\":\"again\",\"now\":\"again\",\"lang\":\"uk\"}");
  tp_free(&tk);
  free(sk);
}
END_TEST

/* ---- oscillation ---- */

static void with_plugins(void)
{
  plug_scan(&ps, dir_of("S42_PLUGINS", NULL));
  ck_assert_int_ge(plug_find(&ps, 'G', 7, NULL), 0);
  ck_assert_int_ge(plug_find(&ps, 'G', 12, NULL), 0);
}

START_TEST(osc_seed_subs)
{
  with_plugins();
  load("№10 G02 G19 G09 X-20000 Z+0 I-10000 K+0 F200 L11 H2 M17 ^\n"
       "№11 G09 Z+20000 M17 ^\n"
       "№01 G07 A-20000 F5500 ^\n"
       "№02 G09 X+40000 Y-10000 F1000 L10 H2 M13 ^\n"
       "№03 G09 Z-80000 M02 ^\n");
  ck_assert_int_eq(go(), SE_END);
  static const int want[] = {1, 2, 10, 11, 11, 10, 11, 11, 3};
  ck_assert_int_eq(nrows, 9);
  for (int i = 0; i < 9; i++)
    ck_assert_int_eq(rows[i].n, want[i]);
  ck_near(rows[2].f, 200, 0);
  ck_near(rows[8].f, 1000, 0);
  ck_assert_str_eq(extras[0], "");
  ck_assert_str_eq(extras[1], ",\"osc\":\"on\"");
  ck_assert_str_eq(extras[7], ",\"osc\":\"on\"");
  ck_assert_str_eq(extras[8], "");     /* M2 ends it */
  ck_assert_int_eq(s->m.pos[3], 0);    /* A back where it started */
  ck_assert_int_gt(nmoved, 100);       /* the turning points reached the sink */
}
END_TEST

START_TEST(osc_offset_and_return)
{
  with_plugins();
  /* 5500 deg/min = 91666.7 discretes/s: after 0.3 s 27500 travelled, the
   * offset is -20000 + 7500 = -12500; the return takes 12.5/5500 min */
  load("N1 G07 A-20000 F5500\nN2 M13\nN3 G04 X+3\nN4 M14\nN5 M2\n");
  uint8_t watch[5] = {0, 0, 0, 1, 0};
  s->vm.watch = watch;
  ck_assert_int_eq(sess_run(s), SE_START);   /* N4 starts */
  ck_assert_int_eq(s->m.pos[3], -12500);
  ck_near(s->m.t, 0.3, 1e-12);
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(s->m.pos[3], 0);
  ck_near(s->m.t, 0.3 + 12.5 / 5500 * 60, 1e-9);
}
END_TEST

START_TEST(osc_runs_during_moves)
{
  with_plugins();
  load("N1 G07 A+20000 F6000\nN2 G01 X+1000 F1000 M13\nN3 G01 X+1000 M2\n");
  uint8_t watch[3] = {0, 0, 1};
  s->vm.watch = watch;
  ck_assert_int_eq(sess_run(s), SE_START);
  ck_assert_int_eq(s->m.pos[3], 6000);       /* 0.06 s at 6000 deg/min */
  ck_assert_int_eq(s->m.pos[0], 1000);
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(s->m.pos[3], 0);          /* M2 includes M14 */
  ck_near(s->m.t, 0.12 + 12.0 / 6000 * 60, 1e-9);
}
END_TEST

START_TEST(osc_errors)
{
  with_plugins();
  load("N1 M13\nN2 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_OSC);      /* M13 before any G07 */
  load("N1 G07 A+0 F100\nN2 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_OSC);      /* stroke 0 */
  load("N1 G07 A-20000 F5500\nN2 G01 X+100 F100 M13\nN3 G01 A+5\nN4 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_OSC);      /* the oscillating axis in the contour */
  ck_assert_int_eq(sess_block_number(s), 3);
  load("N1 G07 A-20000 F5500\nN2 M13\nN3 G07 X+100 F50\nN4 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_OSC);      /* another axis while it oscillates */
  load("N1 G07 A-20000 F5500\nN2 M13\nN3 G12 G17 X+0 Y+0 I-1000 J+0 A+10 F100\nN4 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_OSC);      /* ... also along a helix */
}
END_TEST

START_TEST(osc_speed_clamped_warns)
{
  with_plugins();
  load("N1 G07 Y+1000 F500\nN2 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(nwarn, 1);
  ck_assert_ptr_nonnull(strstr(lastwarn, "clamped"));
  load("N1 G07 Z+1000 F5500\nN2 M2\n");
  nwarn = 0;
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(nwarn, 0);
}
END_TEST

START_TEST(osc_keeps_contour_f)
{
  with_plugins();
  load("N1 G01 X+1000 F100\nN2 G07 A-20000 F5500\nN3 G01 X+1000 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_near(rows[2].f, 100, 0);
  ck_near(rows[2].feed, 100, 0);
}
END_TEST

/* ---- helix ---- */

START_TEST(helix_half_turn_seed)
{
  with_plugins();
  /* language.md 19 item 2: half circle R10 in YZ, X rising 20 mm */
  load("№1 G12 G18 G09 Y+0 Z-20000 J+0 K-10000 X+20000 F1000 ^\n№2 M02 ^\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(s->m.pos[0], 20000);
  ck_assert_int_eq(s->m.pos[2], -20000);
  double H = 10 * M_PI, L = hypot(H, 20);
  /* Y is in the plane and the tangent is parallel to Y at the start:
   * Y's share of the speed is H/L: F = (6000/36) L / H */
  ck_near(rows[0].feed, 6000.0 * sqrt(L * L / (H * H * 1296 + 400)), 1e-9);
  ck_near(s->m.t, L / rows[0].feed * 60, 1e-9);
}
END_TEST

START_TEST(helix_geometry_errors)
{
  with_plugins();
  load("N1 R1+1000\nN2 G13 G17 X+0 Y+R1 I-1000 J+0 Z+5 F100\nN3 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_ARC);
  load("N1 G13 G17 X+0 Y+0 I-1000 J+0 Z+5 F0\nN2 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_FEED);
  compile_with("N1 G13 X+0 Y+0 I-1000 J+0 Z+5 F100\nN2 M2\n");
  ck_assert_int_ge(tp_find(&t.d, DIAG_ERROR, S42_E_PLANE, 1, 0), 0);
  compile_with("N1 G12 G17 X+0 Y+0 I-1000 J+0 Z+5 A+5 F100\nN2 M2\n");
  ck_assert_int_ge(tp_find(&t.d, DIAG_ERROR, S42_E_PLANE, 1, 0), 0);
}
END_TEST

START_TEST(helix_teach_in)
{
  with_plugins();
  /* M19 along a helix: a quarter turn R10 in XY rising Z 10 mm.  X is the
   * junior axis; the jog is the path length, the other axes follow. */
  compile_with("N1 G13 G17 X-10000 Y+10000 I-10000 J+0 Z+10000 M19\nN2 M2\n");
  ck_assert_msg(t.rc == 0, "%s", tp_diags(&t.d));
  sess_init(s, &t.p);
  s->plugins = &ps;
  s->crashes = ps.crashes;   /* as sess_configure does */
  s->sink.row = on_row;
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(s->wait, W_TEACH);
  double L = hypot(10 * M_PI / 2, 10) * 1000;
  ck_assert_int_eq(sess_jog(s, 0, -(int64_t)llround(L / 2)), 0);   /* half the path, forwards */
  ck_assert_int_eq(s->m.pos[2], 5000);
  ck_near((double)s->m.pos[0], -10000 + 10000 * cos(M_PI / 4), 1.0);
  ck_near((double)s->m.pos[1], 10000 * sin(M_PI / 4), 1.0);
  ck_assert_int_eq(sess_jog(s, 0, (int64_t)llround(L / 2)), 0);    /* and back */
  ck_assert_int_eq(s->m.pos[2], 0);
  ck_assert_int_eq(s->m.pos[0], 0);
  ck_assert_int_eq(sess_jog(s, 1, 500), 0);    /* another axis of the block: nothing */
  ck_assert_int_eq(s->m.pos[1], 0);
  ck_assert_int_eq(sess_jog(s, 3, 700), 0);    /* an axis not in the block: alone */
  ck_assert_int_eq(s->m.pos[3], 700);
  ck_assert_int_eq(sess_key_ps(s), 0);
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
}
END_TEST

/* ---- the crash guard: callbacks that die of a signal (cbcrash) ---- */

static const struct {
  const char *src;
  int block;                 /* the block that fails */
  const char *msg;
} crashes[] = {
  {"N1 G01 X+10 F100\nN2 G54\nN3 M2\n", 2, "the cbcrash plugin crashed (SIGSEGV) in run(): it is not called again"},
  {"N1 G55\nN2 M2\n", 1, "the cbcrash plugin crashed (SIGFPE) in run(): it is not called again"},
  {"N1 G56\nN2 M2\n", 1, "the cbcrash plugin crashed (SIGABRT) in run(): it is not called again"},
  {"N1 G57\nN2 M2\n", 1, "the cbcrash plugin crashed (SIGSEGV) in run(): it is not called again"},   /* the stack */
  {"N1 G58\nN2 M2\n", 1, "the cbcrash plugin crashed (SIGSEGV) in check(): it is not called again"},
  /* advance() in the next block's move, describe() as the row is made */
  {"N1 G59\nN2 G01 X+100 F100\nN3 M2\n", 2, "the cbcrash plugin crashed (SIGSEGV) in advance(): it is not called again"},
  {"N1 G60\nN2 M2\n", 1, "the cbcrash plugin crashed (SIGSEGV) in describe(): it is not called again"},
};

/* Each crash fails its block with E-PLUGIN, registers as after the block
 * before; the plugin is never called again: the next run that needs it is
 * refused with the same words, and nothing of the plugin runs. */
START_TEST(crashing_callbacks_are_e_plugin)
{
  plug_scan(&ps, dir_of("S42_FIXTURES", "cbcrash"));
  load(crashes[_i].src);
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_PLUGIN);
  ck_assert_str_eq(s->vm.err.msg, crashes[_i].msg);
  ck_assert_int_eq(sess_block_number(s), crashes[_i].block);
  int i = plug_find(&ps, 'G', 54, NULL);
  ck_assert_int_ge(i, 0);
  ck_assert_int_eq(ps.v[i].state, PLUG_CRASHED);
  ck_assert_uint_eq(ps.crashes, 1);
  load("N1 R1+5\nN2 G59\nN3 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_PLUGIN);
  ck_assert_str_eq(s->vm.err.msg, crashes[_i].msg);
  ck_assert_int_eq(sess_block_number(s), 2);
  ck_assert_double_eq(s->vm.reg[1], 5);
  ck_assert_uint_eq(ps.crashes, 1);
  /* a program that does not need it runs */
  load("N1 G01 X+10 F100\nN2 M2\n");
  ck_assert_int_eq(go(), SE_END);
}
END_TEST

/* A write to a page that allows none: a real SIGSEGV, which neither the
 * compiler nor UBSan's null check (make asan) can see coming. */
static void write_nowhere(void *ctx)
{
  (void)ctx;
  static int *volatile page;
  if (!page) {
    void *p = mmap(NULL, 4096, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ck_assert(p != MAP_FAILED);
    page = p;
  }
  *page = 1;
}

static void do_abort(void *ctx)
{
  (void)ctx;
  abort();
}

static void on_segv(int sig)
{
  (void)sig;
}

static void (*handler_of(int sig))(int)
{
  struct sigaction cur;
  ck_assert_int_eq(sigaction(sig, NULL, &cur), 0);
  return cur.sa_handler;
}

/* The guard's handlers: in for one call when no set holds them (a file's
 * entry function), held from a set's first plugin start to its plug_free;
 * what was there before is there again after. */
START_TEST(guard_puts_the_handlers_back)
{
  struct sigaction mine;
  memset(&mine, 0, sizeof mine);
  mine.sa_handler = on_segv;
  sigemptyset(&mine.sa_mask);
  ck_assert_int_eq(sigaction(SIGSEGV, &mine, NULL), 0);
  ck_assert_int_eq(plug_guarded(NULL, -1, "test", write_nowhere, NULL), SIGSEGV);
  ck_assert_int_eq(plug_guarded(NULL, -1, "test", do_abort, NULL), SIGABRT);
  ck_assert_ptr_eq(handler_of(SIGSEGV), on_segv);
  plug_scan(&ps, dir_of("S42_FIXTURES", "good"));
  load("N1 M30\nN2 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_ptr_ne(handler_of(SIGSEGV), on_segv);   /* the guard's, while the set lives */
  plug_free(&ps);
  ck_assert_ptr_eq(handler_of(SIGSEGV), on_segv);
}
END_TEST

/* A signal outside a plugin's callback goes where it went before the
 * guard: here the default action, after a plugin crashed and was caught
 * (SIG_DFL first: under ASan its own handler would abort instead). */
START_TEST(signal_outside_a_callback_still_kills)
{
  signal(SIGSEGV, SIG_DFL);
  plug_scan(&ps, dir_of("S42_FIXTURES", "cbcrash"));
  load("N1 G54\nN2 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  raise(SIGSEGV);
}
END_TEST

START_TEST(fault_outside_a_callback_still_kills)
{
  signal(SIGSEGV, SIG_DFL);
  plug_scan(&ps, dir_of("S42_FIXTURES", "cbcrash"));
  load("N1 G54\nN2 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  write_nowhere(NULL);
}
END_TEST

Suite *suite_plugin(void)
{
  Suite *su = suite_create("plugin");
  TCase *tc = tcase_create("loader");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, good_plugin_loads_and_runs);
  tcase_add_test(tc, good_plugin_check_error);
  tcase_add_test(tc, plugin_functions_take_their_words);
  tcase_add_test(tc, unknown_function_without_plugin);
  tcase_add_test(tc, wrong_abi_refused);
  tcase_add_test(tc, no_entry_refused);
  tcase_add_test(tc, files_open_only_when_needed);
  tcase_add_test(tc, probe_survives_constructors);
  tcase_add_test(tc, init_failure_is_e_plugin);
  tcase_add_test(tc, abi_10_plugin_still_loads);
  tcase_add_test(tc, failing_callbacks);
  tcase_add_test(tc, failed_block_rolls_back_plugin_writes);
  tcase_add_test(tc, missing_plugin_is_e_plugin_at_check);
  tcase_add_test(tc, two_sets_two_tools);
  tcase_add_test(tc, init_reason_is_the_set_s);
  tcase_add_test(tc, sets_beyond_the_thunks);
  suite_add_tcase(su, tc);
  tc = tcase_create("crash guard");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_loop_test(tc, crashing_callbacks_are_e_plugin, 0, (int)(sizeof crashes / sizeof crashes[0]));
  tcase_add_test(tc, guard_puts_the_handlers_back);
  tcase_add_test_raise_signal(tc, signal_outside_a_callback_still_kills, SIGSEGV);
  tcase_add_test_raise_signal(tc, fault_outside_a_callback_still_kills, SIGSEGV);
  suite_add_tcase(su, tc);
  tc = tcase_create("oscillation");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, osc_seed_subs);
  tcase_add_test(tc, osc_offset_and_return);
  tcase_add_test(tc, osc_runs_during_moves);
  tcase_add_test(tc, osc_errors);
  tcase_add_test(tc, osc_speed_clamped_warns);
  tcase_add_test(tc, osc_keeps_contour_f);
  suite_add_tcase(su, tc);
  tc = tcase_create("helix");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, helix_half_turn_seed);
  tcase_add_test(tc, helix_geometry_errors);
  tcase_add_test(tc, helix_teach_in);
  suite_add_tcase(su, tc);
  return su;
}
