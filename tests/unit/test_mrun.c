/* The one runner (src/core/mrun.h) with a runtime of the test's own: the
 * journal holds every record and warning of a block, however many, until
 * the block commits, and drops them all when it fails; the host gets them
 * in the order the machine made them. */
#include "suites.h"
#include "canon.h"
#include "errors.h"
#include "mrun.h"
#include "../../src/dialect/2u22/u22c.h"
#include <stdio.h>
#include <string.h>

/* A machine of one axis that reports every call it is asked for. */
struct toy {
  int64_t x;
  double t;
  struct canon_sink out;
};

static int toy_feed(void *mv, struct canon_call *c, char *msg, size_t n)
{
  struct toy *m = mv;
  if (c->pos[0] < 0) {
    snprintf(msg, n, "X %lld is below 0", (long long)c->pos[0]);
    return S42_E_TRAVEL;
  }
  c->from[0] = m->x;
  c->t0 = m->t;
  m->x = c->pos[0];
  m->t += 1;
  c->t1 = m->t;
  canon_report(&m->out, c);
  return 0;
}

static void toy_info(const void *m, struct canon_info *in)
{
  (void)m;
  memset(in, 0, sizeof *in);
  in->kind = "toy";
  in->name = "toy";
  in->naxes = 1;
  in->axis[0].name = 'X';
}

static const struct canon_ops toy_ops = {.fn = {[CANON_FEED_LINE] = toy_feed}, .info = toy_info};

static int calls_per_block = 100;

/* Block 1 makes calls_per_block calls and a warning every tenth; block 2
 * makes as many, then fails. */
static int toy_block(struct mrun *r)
{
  struct toy *m = r->st;
  struct canon_dev d = {&toy_ops, m};
  char msg[120];
  m->out = mrun_sink(r);
  int second = mrun_block_number(r) == 2;
  for (int i = 0; i < calls_per_block; i++) {
    struct canon_call c = canon_of(CANON_FEED_LINE);
    c.pos[0] = m->x + 1;
    c.f = 100;
    int e = canon_do(&d, &c, msg, sizeof msg);
    ck_assert_int_eq(e, 0);
    if (i % 10 == 9)
      mrun_warn(r, "call %d", i + 1);
  }
  if (second) {
    struct canon_call c = canon_of(CANON_FEED_LINE);
    c.pos[0] = -1;
    int e = canon_do(&d, &c, msg, sizeof msg);
    mrun_fail(r, e, "%s", msg);
    return -1;
  }
  return 0;
}

static const struct mrun_rt toy_rt = {.size = sizeof(struct toy), .block = toy_block};

struct seen {
  int calls, warns, order_ok;
  int64_t last;
  char first_warn[40];
};

static void got_call(void *ctx, const struct canon_call *c)
{
  struct seen *s = ctx;
  if (c->pos[0] != s->last + 1 || c->from[0] != s->last)
    s->order_ok = 0;
  s->last = c->pos[0];
  s->calls++;
}

static void got_warn(void *ctx, const struct mrun *r, const char *msg)
{
  (void)r;
  struct seen *s = ctx;
  if (!s->warns++)
    snprintf(s->first_warn, sizeof s->first_warn, "%s", msg);
}

static void run_toy(int per_block, struct seen *s, struct mrun *r, struct program *p)
{
  calls_per_block = per_block;
  struct diag_list d;
  diag_init(&d, "t.u22");
  prog_init(p);
  const char *src = "%\nN1 G04 E1\nN2 G04 E1\nN3 M02\n";
  ck_assert_int_eq(u22_compile(src, strlen(src), &d, p), 0);
  diag_free(&d);
  p->runtime = &toy_rt;    /* the test's runtime in the program's place */
  memset(s, 0, sizeof *s);
  s->order_ok = 1;
  struct mrun_config c;
  memset(&c, 0, sizeof c);
  c.ctx = s;
  c.canon = got_call;
  c.warn = got_warn;
  c.rows = 1;
  ck_assert_int_eq(mrun_init(r, p, &c), 0);
}

/* A block of 100 calls: all of them out, in order, at its commit. */
START_TEST(hundred_calls_in_one_block)
{
  struct seen s;
  struct mrun r;
  struct program p;
  run_toy(100, &s, &r, &p);
  ck_assert_int_eq(mrun_run(&r), MR_ROW);
  ck_assert_int_eq(s.calls, 100);
  ck_assert_int_eq(s.warns, 10);
  ck_assert_str_eq(s.first_warn, "call 10");
  ck_assert(s.order_ok);
  /* block 2 makes 100 more and fails: none of them reaches the host */
  ck_assert_int_eq(mrun_run(&r), MR_ERROR);
  ck_assert_int_eq(s.calls, 100);
  ck_assert_int_eq(s.warns, 10);
  ck_assert_int_eq(r.vm.err.code, S42_E_TRAVEL);
  ck_assert_str_eq(r.vm.err.msg, "X -1 is below 0");
  mrun_free(&r);
  prog_free(&p);
}
END_TEST

/* The journal grows with the block: no bound but memory. */
START_TEST(many_calls_in_one_block)
{
  struct seen s;
  struct mrun r;
  struct program p;
  run_toy(100000, &s, &r, &p);
  ck_assert_int_eq(mrun_run(&r), MR_ROW);
  ck_assert_int_eq(s.calls, 100000);
  ck_assert_int_eq(s.warns, 10000);
  ck_assert(s.order_ok);
  mrun_free(&r);
  prog_free(&p);
}
END_TEST

/* A call the machine does not have is E-FUNC, naming it. */
START_TEST(a_call_the_machine_lacks)
{
  struct toy m;
  memset(&m, 0, sizeof m);
  struct canon_dev d = {&toy_ops, &m};
  struct canon_call c = canon_of(CANON_DWELL);
  char msg[80];
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), S42_E_FUNC);
  ck_assert_str_eq(msg, "the toy has no call DWELL");
  c = canon_of(CANON_NKIND + 3);
  ck_assert_int_eq(canon_do(&d, &c, msg, sizeof msg), S42_E_FUNC);
  ck_assert_str_eq(msg, "the toy has no call UNKNOWN");
}
END_TEST

Suite *suite_mrun(void)
{
  Suite *s = suite_create("mrun");
  TCase *tc = tcase_create("journal");
  tcase_set_timeout(tc, 30);
  tcase_add_test(tc, hundred_calls_in_one_block);
  tcase_add_test(tc, many_calls_in_one_block);
  tcase_add_test(tc, a_call_the_machine_lacks);
  suite_add_tcase(s, tc);
  return s;
}
