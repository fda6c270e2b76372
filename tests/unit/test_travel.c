/* Travel limits (--machine FILE): the machine file's parser
 * (src/machine/grinder/machfile.h) and the machine's checks of moves against the travel
 * (src/machine/grinder/machine.h). */
#include "suites.h"
#include "ast.h"
#include "errors.h"
#include "kp.h"
#include "machfile.h"
#include "machine.h"
#include "kpmach.h"
#include <stdio.h>
#include <string.h>

static struct mach_travel tr;
static char msg[200];

/* Parse text; the errors it printed, in a static buffer. */
static int parse(const char *text, const char **errs)
{
  static char buf[2048];
  FILE *f = fmemopen(buf, sizeof buf, "w");
  ck_assert_ptr_nonnull(f);
  int r = machfile_parse(text, strlen(text), "m.txt", &tr, f);
  fclose(f);
  buf[sizeof buf - 1] = 0;
  if (errs)
    *errs = buf;
  return r;
}

START_TEST(file_parses)
{
  const char *e;
  ck_assert_int_eq(parse("; a machine\n travel x = -200 .. 200  ; mm\ntravel Z=-10.5..+10\r\ntravel a = none\n", &e), 0);
  ck_assert(tr.has[0] && !tr.has[1] && tr.has[2] && !tr.has[3]);
  ck_assert(tr.lo[0] == -200000 && tr.hi[0] == 200000);
  ck_assert(tr.lo[2] == -10500 && tr.hi[2] == 10000);
  ck_assert_int_eq(parse("", &e), 0);
  ck_assert(!tr.has[0] && !tr.has[1] && !tr.has[2] && !tr.has[3]);
}
END_TEST

START_TEST(file_errors_name_line_and_column)
{
  const char *e;
  ck_assert_int_eq(parse("travel x = 5 .. 50\n", &e), -1);
  ck_assert_msg(strstr(e, "m.txt:1:12: error:") && strstr(e, "must hold 0"), "%s", e);
  ck_assert_int_eq(parse("\ntravel q = 1 .. 2\n", &e), -1);
  ck_assert_msg(strstr(e, "m.txt:2:8: error: travel of which axis"), "%s", e);
  ck_assert_int_eq(parse("travel y = -1 ..\n", &e), -1);
  ck_assert_msg(strstr(e, "m.txt:1:12: error: expected MIN .. MAX"), "%s", e);
  ck_assert_int_eq(parse("speed x = 5\n", &e), -1);
  ck_assert_msg(strstr(e, "m.txt:1:1: error: expected `travel"), "%s", e);
  ck_assert_int_eq(parse("travel x = -1 .. 1\ntravel x = -2 .. 2\n", &e), -1);
  ck_assert_msg(strstr(e, "m.txt:2:1: error: the travel of X is given twice"), "%s", e);
  ck_assert_int_eq(parse("travel x = -1e9 .. 1\n", &e), -1);
  ck_assert_int_eq(parse("travel x = none 5\n", &e), -1);
  ck_assert_int_eq(parse("travel x = nan .. 1\n", &e), -1);
}
END_TEST

static struct machine m;
static struct kp_block b;

static void block(int motion, int plane, double f, int n, const int *slots, const double *v)
{
  memset(&b, 0, sizeof b);
  b.motion = motion;
  b.plane = plane;
  b.f = f;
  for (int i = 0; i < n; i++) {
    b.given |= (uint16_t)(1u << slots[i]);
    b.w[slots[i]] = v[i];
  }
}

START_TEST(moves_checked_by_their_path)
{
  mach_init(&m);
  ck_assert_int_eq(parse("travel x = -50 .. 50\ntravel z = -10 .. 10\n", NULL), 0);
  m.travel = tr;
  /* a line: its end point */
  block(MO_G01, 0, 1000, 1, (int[]){SL_X}, (double[]){50000});
  ck_assert_int_eq(kp_mach_check(&m, &b, msg, sizeof msg), 0);
  block(MO_G01, 0, 1000, 1, (int[]){SL_X}, (double[]){50001});
  ck_assert_int_eq(kp_mach_check(&m, &b, msg, sizeof msg), S42_E_TRAVEL);
  ck_assert_msg(strstr(msg, "X would reach 50.001 mm, outside its travel -50.000 .. 50.000"), "%s", msg);
  /* a full circle in XZ ending where it starts, swinging to Z+16 */
  block(MO_G02, 19, 1000, 3, (int[]){SL_X, SL_Z, SL_K}, (double[]){0, 0, 8000});
  ck_assert_int_eq(kp_mach_check(&m, &b, msg, sizeof msg), S42_E_TRAVEL);
  ck_assert_msg(strstr(msg, "Z would reach 16.000"), "%s", msg);
  /* a quarter of it: G03 from the circle's bottom (centre Z+8) to (+8, +8)
   * never rises above Z+8 */
  block(MO_G03, 19, 1000, 3, (int[]){SL_X, SL_Z, SL_K}, (double[]){8000, 8000, 8000});
  ck_assert_int_eq(kp_mach_check(&m, &b, msg, sizeof msg), 0);
  /* the same radius the long way round: reaches Z+16 */
  block(MO_G02, 19, 1000, 3, (int[]){SL_X, SL_Z, SL_K}, (double[]){8000, 8000, 8000});
  ck_assert_int_eq(kp_mach_check(&m, &b, msg, sizeof msg), S42_E_TRAVEL);
  /* Y and A have no travel: anything goes */
  block(MO_G01, 0, 100, 2, (int[]){SL_Y, SL_A}, (double[]){999999, 9999999});
  ck_assert_int_eq(kp_mach_check(&m, &b, msg, sizeof msg), 0);
  /* no machine file: no limit */
  mach_init(&m);
  block(MO_G01, 0, 1000, 1, (int[]){SL_X}, (double[]){999999});
  ck_assert_int_eq(kp_mach_check(&m, &b, msg, sizeof msg), 0);
}
END_TEST

START_TEST(jogs_stop_at_the_limit)
{
  mach_init(&m);
  ck_assert_int_eq(parse("travel z = -10 .. 10\n", NULL), 0);
  m.travel = tr;
  ck_assert(mach_jog(&m, AX_Z, 8000, 1) == 8000);
  ck_assert(mach_jog(&m, AX_Z, 5000, 1) == 2000);   /* stopped at +10 */
  ck_assert(m.pos[AX_Z] == 10000 && m.corr[AX_Z] == 10000);
  ck_assert(mach_jog(&m, AX_Z, 1, 0) == 0);
  ck_assert(mach_jog(&m, AX_Z, -30000, 0) == -20000);
  ck_assert(m.pos[AX_Z] == -10000);
  ck_assert(mach_jog(&m, AX_X, 123456789, 0) == 123456789);   /* no travel for X */
  int64_t d[4] = {0, 0, 1, 0};
  ck_assert_int_eq(mach_in_travel(&m, d), 1);
  d[2] = -1;
  ck_assert_int_eq(mach_in_travel(&m, d), 0);
}
END_TEST

Suite *suite_travel(void)
{
  Suite *s = suite_create("travel");
  TCase *tc = tcase_create("travel");
  tcase_add_test(tc, file_parses);
  tcase_add_test(tc, file_errors_name_line_and_column);
  tcase_add_test(tc, moves_checked_by_their_path);
  tcase_add_test(tc, jogs_stop_at_the_limit);
  suite_add_tcase(s, tc);
  return s;
}
