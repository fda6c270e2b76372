/* Sessions (src/core/session.h): a program on a VM against the machine, with
 * operator waits, keys, jogs and the rows that reach the sink. */
#include "suites.h"
#include "errors.h"
#include "session.h"
#include <stdlib.h>
#include <string.h>

#define MAXROWS 64

static struct tprog t;
static struct session *s;
static struct sess_row rows[MAXROWS];
static char motions[MAXROWS][8];
static int nrows, nwarn;
static char lastwarn[240];

static void on_row(void *ctx, const struct session *ss, const struct sess_row *r)
{
  (void)ctx;
  (void)ss;
  ck_assert_int_lt(nrows, MAXROWS);
  rows[nrows] = *r;
  snprintf(motions[nrows], sizeof motions[nrows], "%s", r->motion);
  nrows++;
}

static void on_warn(void *ctx, const struct session *ss, const char *msg)
{
  (void)ctx;
  (void)ss;
  nwarn++;
  snprintf(lastwarn, sizeof lastwarn, "%s", msg);
}

static void setup(void)
{
  memset(&t, 0, sizeof t);
  prog_init(&t.p);
  diag_init(&t.d, "t.kp");
  s = calloc(1, sizeof *s);
  nrows = nwarn = 0;
  lastwarn[0] = 0;
}

static void teardown(void)
{
  tp_free(&t);
  free(s);
}

static void load(const char *src)
{
  tp_free(&t);
  tp_compile(&t, src);
  ck_assert_msg(t.rc == 0, "does not compile:\n%s", tp_diags(&t.d));
  sess_init(s, &t.p);
  s->sink.row = on_row;
  s->sink.warn = on_warn;
}

/* Run until something other than a block start. */
static enum sess_ev go(void)
{
  enum sess_ev ev;
  while ((ev = sess_run(s)) == SE_START)
    ;
  return ev;
}

START_TEST(plain_run_rows)
{
  load("N1 G01 X+10000 F1000\nN2 G04 X+20\nN3 R1+1\nN4 M3 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(nrows, 3);          /* N3 has nothing for the machine: no row unless watched */
  ck_assert_uint_eq(rows[0].seq, 1);
  ck_assert_int_eq(rows[0].n, 1);
  ck_assert_uint_eq(rows[0].line, 1);
  ck_assert_str_eq(motions[0], "G01");
  ck_assert_int_eq(rows[0].d[0], 10000);
  ck_near(rows[0].f, 1000, 0);
  ck_near(rows[0].feed, 1000, 0);
  ck_near(rows[0].t, 0.6, 1e-12);
  ck_assert_str_eq(motions[1], "G04");
  ck_assert_int_eq(rows[1].d[0], 0);   /* a dwell moves nothing */
  ck_near(rows[1].t, 2.6, 1e-12);
  ck_assert_int_eq(rows[2].n, 4);
  ck_assert_str_eq(motions[2], "none");
  ck_assert_int_eq(s->m.wheel, WHEEL_CW);
  ck_assert_int_eq(s->m.pos[0], 10000);
}
END_TEST

START_TEST(rows_for_every_block_when_watched)
{
  load("N1 R1+1\nN2 R2+1\nN3 M2\n");
  s->vm.yield_all = 1;
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(nrows, 3);
  for (int i = 0; i < 3; i++)
    ck_assert_uint_eq(rows[i].seq, (uint64_t)i + 1);
}
END_TEST

START_TEST(rows_carry_depth)
{
  load("N5 G01 X+1 F100 M17\nN1 L5 H2 F50\nN2 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(nrows, 4);
  ck_assert_int_eq(rows[0].depth, 0);
  ck_assert_int_eq(rows[1].depth, 1);
  ck_assert_int_eq(rows[1].n, 5);
  ck_assert_int_eq(rows[2].depth, 1);
  ck_near(rows[3].f, 50, 0);
}
END_TEST

START_TEST(g20_waits_for_pusk)
{
  load("N1 G20\nN2 R1+1 M2\n");
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(s->wait, W_PUSK);
  ck_assert_int_eq(sess_block_number(s), 1);
  ck_assert_int_eq(nrows, 0);          /* the row comes when the block ends */
  ck_assert_int_eq(sess_run(s), SE_WAIT);   /* still waiting */
  ck_assert_int_eq(sess_key_ps(s), -1);     /* ПС does not fit */
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(nrows, 1);
  ck_assert_str_eq(motions[0], "G20");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_double_eq(s->vm.reg[1], 1);
  ck_assert_int_eq(sess_key_pusk(s), -1);   /* nothing waits */
}
END_TEST

START_TEST(g20_m18_needs_ps_first)
{
  load("N1 G20 M18 /ПС, ПОТІМ ПУСК/\nN2 M2\n");
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(s->wait, W_PS);
  ck_assert_uint_ne(s->directive, 0);
  ck_assert_str_eq(kp_str(&t.p, s->directive), "ПС, ПОТІМ ПУСК");
  ck_assert_int_eq(sess_key_pusk(s), -1);   /* Пуск before ПС does not fit */
  ck_assert_int_eq(s->wait, W_PS);
  ck_assert_int_eq(sess_key_ps(s), 0);
  ck_assert_int_eq(s->wait, W_PUSK);
  ck_assert_int_eq(sess_key_ps(s), -1);
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
}
END_TEST

START_TEST(jogs_counted_in_position)
{
  load("N1 G01 X+1000 F1000\nN2 G20\nN3 G01 X+1000 M2\n");
  ck_assert_int_eq(sess_jog(s, 0, 5), -1);  /* not waiting */
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_jog(s, 0, -300), 0);
  ck_assert_int_eq(sess_jog(s, 2, 70), 0);
  ck_assert_int_eq(sess_jog(s, 0, 50), 0);
  ck_assert_int_eq(sess_jog(s, 4, 1), -1);  /* no such axis */
  ck_assert_int_eq(s->m.pos[0], 750);
  ck_assert_int_eq(s->m.pos[2], 70);
  double t0 = s->m.t;
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_near(s->m.t, t0, 0);              /* jogs take no simulated time */
  ck_assert_int_eq(nrows, 2);
  ck_assert_int_eq(rows[1].has_jogs, 1);
  ck_assert_int_eq(rows[1].jogs[0], -250);
  ck_assert_int_eq(rows[1].jogs[2], 70);
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(s->m.pos[0], 1750);
  ck_assert_int_eq(rows[2].has_jogs, 0);
  ck_assert_int_eq(s->m.corr[0], 0);   /* M23 (default): jogs are no corrections */
}
END_TEST

START_TEST(m16_stores_corrections)
{
  load("N1 M22\nN2 G20\nN3 M16 /R1+X R2-X R3+Z// M2\n");
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_jog(s, 0, 300), 0);
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
  ck_assert_double_eq(s->vm.reg[1], 300);
  ck_assert_double_eq(s->vm.reg[2], -300);
  ck_assert_double_eq(s->vm.reg[3], 0);
}
END_TEST

START_TEST(corrections_refused_under_m23)
{
  load("N1 G20\nN2 M22 G20\nN3 M2\n");
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_correct(s, 3, 150), -1);
  ck_assert_int_eq(nwarn, 1);
  ck_assert_int_eq(s->m.pos[3], 0);
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_correct(s, 3, 150), 0);
  ck_assert_int_eq(s->m.pos[3], 150);
  ck_assert_int_eq(s->m.corr[3], 150);
}
END_TEST

START_TEST(override_and_m25)
{
  load("N1 G01 X+10000 F1000\nN2 M25\nN3 G01 X+10000 M2\n");
  ck_assert_int_eq(sess_override(s, 50), 0);
  ck_assert_int_eq(go(), SE_END);
  ck_near(rows[0].feed, 500, 1e-12);
  ck_assert_int_eq(rows[0].override_pct, 50);
  ck_near(rows[2].feed, 1000, 1e-12);  /* M25: the switch is ignored */
  ck_assert_int_eq(rows[2].override_pct, 100);
  ck_assert_int_eq(sess_override(s, 80), -1);
  ck_assert_int_eq(nwarn, 1);
}
END_TEST

START_TEST(machine_error_stops_before_block)
{
  load("N1 M3 R1+1\nN2 M4 R1+2\nN3 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_WHEEL);
  ck_assert_int_eq(sess_block_number(s), 2);
  ck_assert_double_eq(s->vm.reg[1], 1);     /* rolled back */
  ck_assert_int_eq(nrows, 1);               /* the failed block is not traced */
  ck_assert_int_eq(sess_run(s), SE_ERROR);
}
END_TEST

START_TEST(feed_zero_is_error)
{
  load("N1 G01 X+1000\nN2 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_FEED);
  ck_assert_int_eq(s->m.pos[0], 0);
}
END_TEST

START_TEST(run_time_arc_error)
{
  load("N1 R1+10005\nN2 G02 G19 X-20000 Z+0 I-R1 F100\nN3 M2\n");
  ck_assert_int_eq(go(), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_ARC);
  ck_assert_int_eq(sess_block_number(s), 2);
}
END_TEST

START_TEST(feed_clamp_warns)
{
  load("N1 R1+7000\nN2 F+R1 X+6000\nN3 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(nwarn, 1);
  ck_near(rows[0].f, 6000, 0);
  ck_near(rows[0].t, 0.06, 1e-12);
}
END_TEST

START_TEST(key_stop)
{
  load("N1 G20\nN2 M2\n");
  ck_assert_int_eq(go(), SE_WAIT);
  sess_key_stop(s);
  ck_assert_int_eq(sess_run(s), SE_STOPPED);
  ck_assert_int_eq(sess_key_pusk(s), -1);
}
END_TEST

START_TEST(key_exit_latches_for_pp)
{
  load("N1 G20\nN2 R1+1 PP4\nN3 M2\nN4 R2+1 M2\n");
  ck_assert_int_eq(go(), SE_WAIT);
  sess_key_exit(s);
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
  ck_assert_double_eq(s->vm.reg[2], 1);
}
END_TEST

START_TEST(watched_block_starts)
{
  load("N1 R1+1\nN2 G01 X+5 F10\nN3 M2\n");
  uint8_t watch[3] = {0, 1, 0};
  s->vm.watch = watch;
  ck_assert_int_eq(sess_run(s), SE_START);
  ck_assert_int_eq(sess_block_number(s), 2);
  ck_assert_int_eq(s->m.pos[0], 0);
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(s->m.pos[0], 5);
}
END_TEST

START_TEST(g37_returns_y)
{
  load("N1 G01 Y-5000 F1000\nN2 G37 /Y/\nN3 M2\n");
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(s->m.pos[1], 0);
  ck_assert_str_eq(motions[1], "G37");
  ck_assert_int_eq(rows[1].d[1], 5000);
  ck_near(rows[1].t, 3.6, 1e-9);
}
END_TEST

START_TEST(m16_counts_from_g20)
{
  load("N1 M22\nN2 R5+1\nN3 G20\nN4 M16 /R1+X// M2\n");
  uint8_t watch[4] = {0, 1, 0, 0};
  s->vm.watch = watch;
  ck_assert_int_eq(sess_run(s), SE_START);      /* N2 starts: M22 is in force */
  ck_assert_int_eq(sess_correct(s, 0, 100), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_jog(s, 0, 300), 0);
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
  ck_assert_double_eq(s->vm.reg[1], 300);       /* the correction before G20 is not counted */
  ck_assert_int_eq(s->m.pos[0], 400);
}
END_TEST

START_TEST(m16_counts_from_start)
{
  load("N1 M22\nN2 R5+1\nN3 M16 /R1-X// M2\n");
  uint8_t watch[3] = {0, 1, 0};
  s->vm.watch = watch;
  ck_assert_int_eq(sess_run(s), SE_START);
  ck_assert_int_eq(sess_correct(s, 0, 100), 0);
  ck_assert_int_eq(go(), SE_END);
  ck_assert_double_eq(s->vm.reg[1], -100);
}
END_TEST

Suite *suite_session(void)
{
  Suite *su = suite_create("session");
  TCase *tc = tcase_create("run");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, plain_run_rows);
  tcase_add_test(tc, rows_for_every_block_when_watched);
  tcase_add_test(tc, rows_carry_depth);
  tcase_add_test(tc, g20_waits_for_pusk);
  tcase_add_test(tc, g20_m18_needs_ps_first);
  tcase_add_test(tc, jogs_counted_in_position);
  tcase_add_test(tc, m16_stores_corrections);
  tcase_add_test(tc, corrections_refused_under_m23);
  tcase_add_test(tc, override_and_m25);
  tcase_add_test(tc, machine_error_stops_before_block);
  tcase_add_test(tc, feed_zero_is_error);
  tcase_add_test(tc, run_time_arc_error);
  tcase_add_test(tc, feed_clamp_warns);
  tcase_add_test(tc, key_stop);
  tcase_add_test(tc, key_exit_latches_for_pp);
  tcase_add_test(tc, watched_block_starts);
  tcase_add_test(tc, g37_returns_y);
  tcase_add_test(tc, m16_counts_from_g20);
  tcase_add_test(tc, m16_counts_from_start);
  suite_add_tcase(su, tc);
  return su;
}
