/* The operator's parameter setting from the panel (sess_set_param in
 * src/core/session.h): between blocks and in waits, journaled as a dialog
 * answer, refused for what is not the operator's and after the cycle. */
#include "suites.h"
#include "session.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static struct tprog t;
static struct session *s;

static void setup(void)
{
  memset(&t, 0, sizeof t);
  prog_init(&t.p);
  diag_init(&t.d, "t.kp");
  s = calloc(1, sizeof *s);
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
}

static enum sess_ev go(void)
{
  enum sess_ev ev;
  while ((ev = sess_run(s)) == SE_START)
    ;
  return ev;
}

START_TEST(set_in_a_dialog_wait)
{
  load("№1 G27 /ЧИСЛО/ ^\n№2 G28 /0:100/ R1 ^\n№3 R2+R5+R1 ^\n№4 M02 ^\n");
  char why[200];
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(s->wait, W_ANSWER);
  ck_assert_int_eq(sess_set_param(s, 5, 42.5, why, sizeof why), 0);
  ck_near(s->vm.reg[5], 42.5, 0);
  /* journaled in the waiting block, as the answer will be: its old value is
   * there for a rollback */
  int found = 0;
  for (unsigned i = 0; i < s->vm.nundo; i++)
    if (s->vm.undo[i].reg == 5 && s->vm.undo[i].old == 0)
      found = 1;
  ck_assert(found);
  ck_assert_int_eq(sess_answer(s, 10), 0);
  ck_assert_int_eq(go(), SE_END);
  ck_near(s->vm.reg[2], 52.5, 0);   /* the program read the operator's R5 */
}
END_TEST

START_TEST(set_between_blocks)
{
  load("№1 R7+1 ^\n№2 R8+R7%2 ^\n№3 M02 ^\n");
  s->vm.start_all = 1;
  char why[200];
  ck_assert_int_eq(sess_run(s), SE_START);   /* before block 1 */
  ck_assert_int_eq(sess_run(s), SE_START);   /* block 1 ran: before block 2 */
  ck_near(s->vm.reg[7], 1, 0);
  ck_assert_int_eq(sess_set_param(s, 7, 30, why, sizeof why), 0);
  ck_assert_int_eq(go(), SE_END);
  ck_near(s->vm.reg[8], 60, 0);   /* block 2 saw the operator's value */
  /* the cycle is over: nothing is set any more */
  ck_assert_int_eq(sess_set_param(s, 7, 1, why, sizeof why), -1);
  ck_assert_ptr_nonnull(strstr(why, "over"));
  ck_near(s->vm.reg[7], 30, 0);
}
END_TEST

START_TEST(refused_values_and_registers)
{
  load("№1 G34 ^\n№2 M02 ^\n");
  char why[200];
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_set_param(s, 113, -9999999, why, sizeof why), 0);
  ck_assert_int_eq(sess_set_param(s, 3, 10000000, why, sizeof why), -1);
  ck_assert_ptr_nonnull(strstr(why, "9999999"));
  ck_assert_int_eq(sess_set_param(s, 3, NAN, why, sizeof why), -1);
  ck_assert_int_eq(sess_set_param(s, 3, INFINITY, why, sizeof why), -1);
  ck_near(s->vm.reg[3], 0, 0);
  ck_assert_int_eq(sess_set_param(s, REG_D1, 50000, why, sizeof why), 0);
  ck_near(s->vm.reg[REG_D1], 50000, 0);
  ck_assert_int_eq(sess_set_param(s, REG_D1, -1, why, sizeof why), -1);
  ck_assert_ptr_nonnull(strstr(why, "D1"));
  ck_assert_int_eq(sess_set_param(s, REG_D1, 400001, why, sizeof why), -1);
  ck_assert_int_eq(sess_set_param(s, REG_TK, 5, why, sizeof why), -1);
  ck_assert_ptr_nonnull(strstr(why, "TK"));
  ck_assert_int_eq(sess_set_param(s, REG_UG, 5, why, sizeof why), -1);
  ck_assert_int_eq(sess_set_param(s, REG_F, 500, why, sizeof why), -1);
  ck_assert_int_eq(sess_set_param(s, -1, 5, why, sizeof why), -1);
  ck_near(s->vm.reg[REG_TK], 0, 0);
  ck_near(s->vm.reg[REG_F], 0, 0);
}
END_TEST

Suite *suite_param(void)
{
  Suite *su = suite_create("param");
  TCase *c = tcase_create("param");
  tcase_add_checked_fixture(c, setup, teardown);
  tcase_add_test(c, set_in_a_dialog_wait);
  tcase_add_test(c, set_between_blocks);
  tcase_add_test(c, refused_values_and_registers);
  suite_add_tcase(su, c);
  return su;
}
