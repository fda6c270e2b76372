/* Operator scripts (src/host/operator.h, contracts.md section 3): every action,
 * the refusals with their lines and columns, words never cut short, `at`
 * for a block the program lacks, and the warnings for what a run left. */
#include "suites.h"
#include "operator.h"
#include "machine.h"
#include <stdlib.h>
#include <string.h>

static struct opscript sc;
static char *errbuf;
static size_t errlen;

static void setup(void)
{
  memset(&sc, 0, sizeof sc);
  errbuf = NULL;
  errlen = 0;
}

static void teardown(void)
{
  ops_free(&sc);
  free(errbuf);
}

static int parse(const char *text)
{
  free(errbuf);
  errbuf = NULL;
  FILE *f = open_memstream(&errbuf, &errlen);
  ck_assert_ptr_nonnull(f);
  ops_free(&sc);
  int r = ops_parse(text, strlen(text), "op.txt", &sc, f);
  fclose(f);
  return r;
}

/* One action, parsed alone. */
static const struct op_action *one(const char *text)
{
  ck_assert_msg(parse(text) == 0, "'%s' refused: %s", text, errbuf);
  ck_assert_uint_eq(sc.n, 1);
  return &sc.v[0];
}

/* Refused with FILE:LINE:COL: error: (col 0: any column). */
static void refused_at(const char *text, size_t len, unsigned line, unsigned col, const char *msg)
{
  free(errbuf);
  errbuf = NULL;
  FILE *f = open_memstream(&errbuf, &errlen);
  ck_assert_ptr_nonnull(f);
  ops_free(&sc);
  ck_assert_int_eq(ops_parse(text, len, "op.txt", &sc, f), -1);
  fclose(f);
  unsigned l = 0, c = 0;
  ck_assert_msg(sscanf(errbuf, "op.txt:%u:%u: error: ", &l, &c) == 2, "'%s': no op.txt:LINE:COL in '%s'", text, errbuf);
  ck_assert_msg(l == line && (!col || c == col), "'%s': expected line %u col %u in '%s'", text, line, col, errbuf);
  if (msg)
    ck_assert_msg(strstr(errbuf, msg) != NULL, "'%s': expected '%s' in '%s'", text, msg, errbuf);
  ck_assert_uint_eq(sc.n, 0);
  ck_assert_ptr_null(sc.v);
}

static void refused(const char *text, unsigned line)
{
  refused_at(text, strlen(text), line, 0, NULL);
}

START_TEST(answer_positive_and_negative)
{
  const struct op_action *a = one("answer 35000");
  ck_assert_int_eq(a->kind, OA_ANSWER);
  ck_assert_int_eq(a->n, 35000);
  ck_assert_int_eq(a->at_number, -1);
  ck_assert_int_eq(ops_is_waiting(a), 1);
  a = one("answer -120   ; a negative number");
  ck_assert_int_eq(a->n, -120);
  a = one("answer 9999999");
  ck_assert_int_eq(a->n, 9999999);
}
END_TEST

START_TEST(keys)
{
  static const struct { const char *t; int key, waiting; } k[] = {
    {"key PUSK", OPKEY_PUSK, 1}, {"key PS", OPKEY_PS, 1}, {"key EXIT", OPKEY_EXIT, 0}, {"key STOP", OPKEY_STOP, 0},
  };
  for (size_t i = 0; i < 4; i++) {
    const struct op_action *a = one(k[i].t);
    ck_assert_int_eq(a->kind, OA_KEY);
    ck_assert_int_eq(a->key, k[i].key);
    ck_assert_int_eq(ops_is_waiting(a), k[i].waiting);
  }
}
END_TEST

START_TEST(at_block)
{
  ck_assert_int_eq(parse("at N54 key EXIT\n"), 0);
  ck_assert_uint_eq(sc.n, 0);
  ck_assert_uint_eq(sc.nat, 1);
  ck_assert_int_eq(sc.at[0].at_number, 54);
  ck_assert_uint_eq(sc.at[0].at_run, 1);
  ck_assert_int_eq(sc.at[0].kind, OA_KEY);
  ck_assert_int_eq(sc.at[0].key, OPKEY_EXIT);
  ck_assert_uint_eq(sc.at[0].line, 1);
}
END_TEST

START_TEST(at_block_run)
{
  ck_assert_int_eq(parse("key PUSK\nat N54#3 key EXIT\nat N7 override 50\nat N8 correct A +150\nkey PS\n"), 0);
  ck_assert_uint_eq(sc.n, 2);
  ck_assert_uint_eq(sc.nat, 3);
  ck_assert_int_eq(sc.at[0].at_number, 54);
  ck_assert_uint_eq(sc.at[0].at_run, 3);
  ck_assert_uint_eq(sc.at[0].line, 2);
  ck_assert_int_eq(sc.at[1].kind, OA_OVERRIDE);
  ck_assert_int_eq(sc.at[2].kind, OA_CORRECT);
  ck_assert_int_eq(sc.v[1].key, OPKEY_PS);
  ck_assert_uint_eq(sc.v[1].line, 5);
}
END_TEST

START_TEST(jog)
{
  const struct op_action *a = one("jog X -20000");
  ck_assert_int_eq(a->kind, OA_JOG);
  ck_assert_int_eq(a->axis, AX_X);
  ck_assert_int_eq(a->n, -20000);
  ck_assert_int_eq(ops_is_waiting(a), 1);
  a = one("jog A +5");
  ck_assert_int_eq(a->axis, AX_A);
  ck_assert_int_eq(a->n, 5);
}
END_TEST

START_TEST(correct)
{
  const struct op_action *a = one("correct A +150");
  ck_assert_int_eq(a->kind, OA_CORRECT);
  ck_assert_int_eq(a->axis, AX_A);
  ck_assert_int_eq(a->n, 150);
  ck_assert_int_eq(ops_is_waiting(a), 0);
}
END_TEST

START_TEST(override)
{
  const struct op_action *a = one("override 50");
  ck_assert_int_eq(a->kind, OA_OVERRIDE);
  ck_assert_int_eq(a->n, 50);
  ck_assert_int_eq(ops_is_waiting(a), 0);
  ck_assert_int_eq(one("override 0")->n, 0);
  ck_assert_int_eq(one("override 150")->n, 150);
}
END_TEST

START_TEST(section_one_axis)
{
  const struct op_action *a = one("section X +30000");
  ck_assert_int_eq(a->kind, OA_SECTION);
  ck_assert_int_eq(a->axis, AX_X);
  ck_assert_int_eq(a->n, 30000);
  ck_assert_int_eq(a->axis2, -1);
  ck_assert_int_eq(ops_is_waiting(a), 1);
}
END_TEST

START_TEST(section_two_axes)
{
  const struct op_action *a = one("section X +30000 A +36000  ; and turn A");
  ck_assert_int_eq(a->axis, AX_X);
  ck_assert_int_eq(a->n, 30000);
  ck_assert_int_eq(a->axis2, AX_A);
  ck_assert_int_eq(a->n2, 36000);
}
END_TEST

START_TEST(comments_and_blank_lines)
{
  ck_assert_int_eq(parse("; a script\n\n   \n\tkey PUSK ; go\n;key PS\nanswer 1"), 0);
  ck_assert_uint_eq(sc.n, 2);
  ck_assert_uint_eq(sc.v[0].line, 4);
  ck_assert_uint_eq(sc.v[1].line, 6);
  ck_assert_int_eq(parse(""), 0);
  ck_assert_uint_eq(sc.n, 0);
}
END_TEST

START_TEST(order_kept)
{
  ck_assert_int_eq(parse("answer 1\nkey PS\njog Z -5\noverride 10\nkey PUSK\n"), 0);
  ck_assert_uint_eq(sc.n, 5);
  static const int kinds[] = {OA_ANSWER, OA_KEY, OA_JOG, OA_OVERRIDE, OA_KEY};
  for (int i = 0; i < 5; i++)
    ck_assert_int_eq(sc.v[i].kind, kinds[i]);
}
END_TEST

START_TEST(describe)
{
  char buf[64];
  ck_assert_str_eq(ops_describe(one("jog X -20000"), buf, sizeof buf), "jog X -20000");
  ck_assert_str_eq(ops_describe(one("key PUSK"), buf, sizeof buf), "key PUSK");
  ck_assert_str_eq(ops_describe(one("section X +30000 A +36000"), buf, sizeof buf), "section X +30000 A +36000");
  ck_assert_str_eq(ops_describe(one("answer -5"), buf, sizeof buf), "answer -5");
}
END_TEST

START_TEST(reject_unknown_action)
{
  refused("key PUSK\npress PUSK\n", 2);
  refused("Key PUSK", 1);
}
END_TEST

START_TEST(reject_answer_8_digits)
{
  refused("answer 1\nanswer 12345678\n", 2);
  refused("answer -12345678", 1);
  refused("answer 12a", 1);
  refused("answer", 1);
}
END_TEST

START_TEST(reject_bad_axis)
{
  refused("jog Q +5", 1);
  refused("\n\njog x +5", 3);
  refused("correct XY +5", 1);
  refused("section X +1 X +2", 1);
  refused("section X +1 B +2", 1);
  refused("jog X", 1);
}
END_TEST

START_TEST(reject_override_151)
{
  refused("override 151", 1);
  refused("override -1", 1);
  refused("override", 1);
}
END_TEST

START_TEST(reject_unknown_key)
{
  refused("key ENTER", 1);
  refused("key", 1);
}
END_TEST

START_TEST(reject_at_with_waiting_action)
{
  refused("at N54 key PUSK", 1);
  refused("at N54 answer 5", 1);
  refused("at N54 jog X +1", 1);
  refused("at N54 key PS", 1);
  refused("at N54 section X +1", 1);
}
END_TEST

START_TEST(reject_bad_at)
{
  refused("at 54 key EXIT", 1);
  refused("at N0 key EXIT", 1);
  refused("at N100000 key EXIT", 1);
  refused("at N5#0 key EXIT", 1);
  refused("at N5# key EXIT", 1);
  refused("at N-5 key EXIT", 1);
}
END_TEST

START_TEST(reject_trailing_text)
{
  refused("key PUSK now", 1);
  refused("override 50 %", 1);
}
END_TEST

START_TEST(reject_reports_every_bad_line)
{
  ck_assert_int_eq(parse("bogus\nkey PUSK\noverride 200\n"), -1);
  ck_assert_ptr_nonnull(strstr(errbuf, "op.txt:1:"));
  ck_assert_ptr_nonnull(strstr(errbuf, "op.txt:3:"));
  ck_assert_ptr_null(strstr(errbuf, "op.txt:2:"));
}
END_TEST

START_TEST(reject_columns)
{
  refused_at("jog Q +5", 8, 1, 5, "expected an axis");
  refused_at("override 151", 12, 1, 10, "override takes a percentage 0..150");
  refused_at("key PUSK now", 12, 1, 10, "unexpected text after the action");
  refused_at("at N54 key PUSK", 15, 1, 8, "at fires at a block's start");
  refused_at("  at 54 key EXIT", 16, 1, 6, "at needs a block");
  refused_at("answer", 6, 1, 7, "answer needs a number");
  refused_at("\tpress PUSK", 11, 1, 2, "unknown action 'press'");
}
END_TEST

/* A word is never read cut short: 63 characters are read whole, 64 are
 * an error (before, `override 000...0150` read as `override 0` and
 * `at N000...022` fired at N2). */
START_TEST(long_words_not_cut)
{
  char t[200];
  snprintf(t, sizeof t, "override %0*d", 63, 150);          /* 60 zeros, then 150 */
  ck_assert_int_eq(one(t)->n, 150);
  snprintf(t, sizeof t, "override %0*d", 64, 150);
  refused_at(t, strlen(t), 1, 10, "a word of 64 characters: at most 63");
  snprintf(t, sizeof t, "at N%0*d key EXIT", 62, 22);       /* N and 62 digits: 63 */
  ck_assert_int_eq(parse(t), 0);
  ck_assert_uint_eq(sc.nat, 1);
  ck_assert_int_eq(sc.at[0].at_number, 22);
  snprintf(t, sizeof t, "at N%0*d key EXIT", 63, 22);
  refused_at(t, strlen(t), 1, 4, "a word of 64 characters");
  snprintf(t, sizeof t, "at N5#%0*d key EXIT", 60, 3);
  ck_assert_int_eq(parse(t), 0);
  ck_assert_uint_eq(sc.at[0].at_run, 3);
  snprintf(t, sizeof t, "jog X -%0*d", 62, 20000);
  ck_assert_int_eq(one(t)->n, -20000);
  ck_assert_int_eq(one("answer 0000035")->n, 35);
  refused_at("answer 00000035", 15, 1, 8, "at most 7 digits");   /* the field has 7 */
  /* a long word in a comment is free text */
  memset(t, 'x', 150);
  t[150] = 0;
  char line[200];
  snprintf(line, sizeof line, "key PS ; %s", t);
  ck_assert_int_eq(one(line)->key, OPKEY_PS);
  /* a word of any length is refused, not read in pieces */
  static char huge[100000];
  memcpy(huge, "override ", 9);
  memset(huge + 9, '0', sizeof huge - 13);
  memcpy(huge + sizeof huge - 4, "150", 4);
  refused_at(huge, strlen(huge), 1, 10, "a word of 99990 characters");
}
END_TEST

START_TEST(nul_in_a_word)
{
  refused_at("key PU\0SK\n", 10, 1, 5, "a NUL byte inside a word");
  refused_at("key PUSK\nanswer 3\0005\n", 19, 2, 8, "a NUL byte inside a word");
  refused_at("\0", 1, 1, 1, "a NUL byte inside a word");
  /* in a comment it changes nothing */
  static const char c[] = "key PUSK ; a \0 in a comment\n";
  ck_assert_int_eq(ops_parse(c, sizeof c - 1, "op.txt", &sc, stderr), 0);
  ck_assert_uint_eq(sc.n, 1);
}
END_TEST

START_TEST(at_block_must_exist)
{
  ck_assert_int_eq(parse("at N3 key EXIT\nkey PUSK\n  at N22#2 override 50\nat N999 key STOP\n"), 0);
  unsigned char have[1000] = {0};
  have[1] = have[3] = have[999] = 1;
  free(errbuf);
  errbuf = NULL;
  FILE *f = open_memstream(&errbuf, &errlen);
  ck_assert_int_eq(ops_check_at(&sc, have, "op.txt", f), -1);
  fclose(f);
  ck_assert_str_eq(errbuf, "op.txt:3:3: error: at N22: the program has no block N22, so this never fires\n");
  have[22] = 1;
  ck_assert_int_eq(ops_check_at(&sc, have, "op.txt", stderr), 0);
}
END_TEST

/* The lathe's switches and its part zero (2u22.md D-34). */
START_TEST(lathe_modes_and_zero)
{
  char d[64];
  const struct op_action *a = one("mode skip on");
  ck_assert_int_eq(a->kind, OA_MODE);
  ck_assert_int_eq(a->n2, OPMODE_SKIP);
  ck_assert_int_eq(a->n, 1);
  ck_assert_str_eq(ops_describe(a, d, sizeof d), "mode skip on");
  a = one("mode optstop off ; ST off");
  ck_assert_int_eq(a->n2, OPMODE_OPTSTOP);
  ck_assert_int_eq(a->n, 0);
  a = one("mode single off");
  ck_assert_int_eq(a->n2, OPMODE_SINGLE);
  ck_assert_int_eq(a->n, 0);
  ck_assert_str_eq(ops_describe(a, d, sizeof d), "mode auto");
  a = one("mode single on");
  ck_assert_int_eq(a->n, 1);
  a = one("zero X 0 Z 300.5");
  ck_assert_int_eq(a->kind, OA_ZERO);
  ck_assert_int_eq(a->axis, 1 | 4);
  ck_assert_int_eq(a->zero[0], 0);
  ck_assert_int_eq(a->zero[2], 300500);
  ck_assert(!ops_is_waiting(a));
  a = one("zero Z -12.25");
  ck_assert_int_eq(a->axis, 4);
  ck_assert_int_eq(a->zero[2], -12250);
  a = one("zero Y 3 A -90 B 1");   /* any axes: the machine says which it has */
  ck_assert_int_eq(a->axis, 2 | 8 | 16);
  ck_assert_int_eq(a->zero[3], -90000);
  refused_at("mode skip", 9, 1, 6, "take on or off");
  refused_at("mode skip maybe", 15, 1, 11, "on or off");
  refused_at("zero", 4, 1, 1, "zero takes axes");
  refused_at("zero X 1.2345", 13, 1, 8, "millimetres");
  refused_at("zero X 1 X 2", 12, 1, 10, "twice");
  refused_at("zero Q 3", 8, 1, 6, "zero takes axes");
  /* 5-digit blocks (the 2У22's) in at and break */
  ck_assert_int_eq(parse("at N2001 key STOP\n"), 0);
  ck_assert_int_eq(sc.at[0].at_number, 2001);
}
END_TEST

START_TEST(mode_and_break)
{
  const struct op_action *a = one("mode single");
  ck_assert_int_eq(a->kind, OA_MODE);
  ck_assert_int_eq(a->n, 1);
  ck_assert(!ops_is_waiting(a));
  a = one("mode auto ; back to automatic");
  ck_assert_int_eq(a->n, 0);
  a = one("break N54");
  ck_assert_int_eq(a->kind, OA_BREAK);
  ck_assert_int_eq(a->n, 54);
  ck_assert(!ops_is_waiting(a));
  char d[64];
  ck_assert_str_eq(ops_describe(a, d, sizeof d), "break N54");
  a = one("break off");
  ck_assert_int_eq(a->n, 0);
  ck_assert_str_eq(ops_describe(a, d, sizeof d), "break off");
  ck_assert_int_eq(parse("at N3#2 mode single\n"), 0);
  ck_assert_int_eq(sc.nat, 1);
  refused_at("mode singel", 11, 1, 6, "mode is single");
  refused_at("break 54", 8, 1, 7, "break needs a block");
  refused_at("break N100000", 13, 1, 7, "block 1..99999");
  refused_at("break N-3", 9, 1, 7, "block 1..99999");
  refused_at("mode", 4, 1, 5, "mode is single");
  /* a break for a block the program lacks is refused before the run */
  ck_assert_int_eq(parse("break N22\nkey PUSK\nbreak off\n"), 0);
  unsigned char have[1000] = {0};
  have[1] = 1;
  free(errbuf);
  errbuf = NULL;
  FILE *f = open_memstream(&errbuf, &errlen);
  ck_assert_int_eq(ops_check_at(&sc, have, "op.txt", f), -1);
  fclose(f);
  ck_assert_str_eq(errbuf, "op.txt:1:1: error: break N22: the program has no block N22, so it never waits there\n");
  have[22] = 1;
  ck_assert_int_eq(ops_check_at(&sc, have, "op.txt", stderr), 0);
}
END_TEST

/* A word typed wrong says which it was meant to be, and lists the rest. */
START_TEST(did_you_mean)
{
  refused_at("anser 118", 9, 1, 1,
             "unknown action 'anser': did you mean answer? (answer, key, jog, correct, override, section, mode, "
             "break, at, zero)");
  refused_at("key PUS", 7, 1, 5, "unknown key 'PUS': did you mean PUSK? (PUSK, PS, EXIT, STOP)");
  refused_at("key STPO", 8, 1, 5, "did you mean STOP?");
  refused_at("frobnicate 3", 12, 1, 1, "unknown action 'frobnicate' (answer, key,");
  refused_at("key BANG", 8, 1, 5, "unknown key 'BANG' (PUSK, PS, EXIT, STOP)");
}
END_TEST

START_TEST(unused_actions_warned)
{
  ck_assert_int_eq(parse("key PUSK\nanswer 5\njog X +3\nat N3#2 key EXIT\n at N4 key STOP\nat N7 override 9\n"), 0);
  sc.at[1].fired = 1;
  unsigned runs[1000] = {0};
  runs[3] = 1;
  free(errbuf);
  errbuf = NULL;
  FILE *f = open_memstream(&errbuf, &errlen);
  ops_warn_unused(&sc, 1, 0, runs, "op.txt", f);
  fclose(f);
  ck_assert_str_eq(errbuf,
                   "op.txt:2:1: warning: answer 5 was not used: the run ended before it\n"
                   "op.txt:3:1: warning: jog X +3 was not used: the run ended before it\n"
                   "op.txt:4:1: warning: at N3#2 key EXIT never fired: block N3 started only once\n"
                   "op.txt:6:1: warning: at N7#1 override 9 never fired: block N7 never started\n");
  /* the action already reported as not fitting a wait is not repeated */
  free(errbuf);
  errbuf = NULL;
  f = open_memstream(&errbuf, &errlen);
  sc.at[0].fired = sc.at[2].fired = 1;
  runs[3] = 5;
  ops_warn_unused(&sc, 1, 2, runs, "op.txt", f);
  fclose(f);
  ck_assert_str_eq(errbuf, "op.txt:3:1: warning: jog X +3 was not used: the run ended before it\n");
  /* all used: nothing */
  free(errbuf);
  errbuf = NULL;
  f = open_memstream(&errbuf, &errlen);
  ops_warn_unused(&sc, 3, 0, NULL, "op.txt", f);
  fclose(f);
  ck_assert_str_eq(errbuf, "");
}
END_TEST

Suite *suite_operator(void)
{
  Suite *s = suite_create("operator");
  TCase *tc = tcase_create("actions");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, answer_positive_and_negative);
  tcase_add_test(tc, keys);
  tcase_add_test(tc, at_block);
  tcase_add_test(tc, at_block_run);
  tcase_add_test(tc, jog);
  tcase_add_test(tc, correct);
  tcase_add_test(tc, override);
  tcase_add_test(tc, section_one_axis);
  tcase_add_test(tc, section_two_axes);
  tcase_add_test(tc, comments_and_blank_lines);
  tcase_add_test(tc, order_kept);
  tcase_add_test(tc, describe);
  suite_add_tcase(s, tc);

  tc = tcase_create("refusals");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, reject_unknown_action);
  tcase_add_test(tc, reject_answer_8_digits);
  tcase_add_test(tc, reject_bad_axis);
  tcase_add_test(tc, reject_override_151);
  tcase_add_test(tc, reject_unknown_key);
  tcase_add_test(tc, reject_at_with_waiting_action);
  tcase_add_test(tc, reject_bad_at);
  tcase_add_test(tc, lathe_modes_and_zero);
  tcase_add_test(tc, reject_trailing_text);
  tcase_add_test(tc, reject_reports_every_bad_line);
  tcase_add_test(tc, reject_columns);
  tcase_add_test(tc, long_words_not_cut);
  tcase_add_test(tc, nul_in_a_word);
  tcase_add_test(tc, at_block_must_exist);
  tcase_add_test(tc, unused_actions_warned);
  tcase_add_test(tc, mode_and_break);
  tcase_add_test(tc, did_you_mean);
  suite_add_tcase(s, tc);
  return s;
}
