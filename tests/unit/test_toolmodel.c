/* Tool-model parser (plugins/toothsearch/toolmodel.c): the contracts.md
 * example, defaults, and every refusal with its FILE:LINE message. */
#include "suites.h"
#include "toolmodel.h"

#include <string.h>

static int parse(struct tm_model *m, const char *text, char *err, size_t n)
{
  return tm_parse(m, text, strlen(text), "t.tool", err, n);
}

/* The text must be refused with a message containing want. */
#define REFUSED(text, want) do { \
    struct tm_model m_; char e_[256]; \
    ck_assert_int_eq(parse(&m_, text, e_, sizeof e_), -1); \
    ck_assert_msg(strstr(e_, want) != NULL, "message '%s' lacks '%s'", e_, want); \
  } while (0)

#define BASE "teeth = 4\ndiameter = 60000\n"

START_TEST(contract_example)
{
  const char *t =
    "teeth    = 4\n"
    "steps    = 90, 80, 110, 80   ; degrees between successive teeth, sum 360; or \"even\"\n"
    "diameter = 60000             ; µm\n"
    "lead     = 250000            ; µm; 0 = straight flutes\n"
    "hand     = right             ; right | left\n"
    "noise    = 0.02              ; image noise, 0–1\n"
    "blur     = 1.5               ; pixels\n"
    "image    = 1024              ; image side, pixels\n"
    "seed     = 1                 ; random seed: the same file gives the same images\n";
  struct tm_model m;
  char err[256];
  ck_assert_msg(parse(&m, t, err, sizeof err) == 0, "%s", err);
  ck_assert_int_eq(m.teeth, 4);
  ck_assert_int_eq(m.even, 0);
  ck_near(m.steps[0], 90, 0);
  ck_near(m.steps[2], 110, 0);
  ck_near(m.diameter, 60000, 0);
  ck_near(m.lead, 250000, 0);
  ck_assert_int_eq(m.hand, TM_RIGHT);
  ck_near(m.noise, 0.02, 1e-15);
  ck_near(m.blur, 1.5, 0);
  ck_assert_int_eq(m.image, 1024);
  ck_assert_uint_eq(m.seed, 1);
  double a[TM_MAX_TEETH];
  tm_tooth_angles(&m, a);
  ck_near(a[0], 0, 0);
  ck_near(a[1], -90, 0);
  ck_near(a[3], -280, 0);
}
END_TEST

START_TEST(defaults_and_forms)
{
  struct tm_model m;
  char err[256];
  ck_assert_msg(parse(&m, "\xEF\xBB\xBF; a comment only\r\n\r\n" BASE, err, sizeof err) == 0, "%s", err);
  ck_assert_int_eq(m.even, 1);
  ck_near(m.steps[3], 90, 0);
  ck_near(m.lead, 0, 0);
  ck_assert_int_eq(m.hand, TM_RIGHT);
  ck_assert_int_eq(m.image, 512);
  ck_assert_uint_eq(m.seed, 1);
  ck_assert_msg(parse(&m, BASE "steps = EVEN\nhand = Left\nseed = 4294967295", err, sizeof err) == 0, "%s", err);
  ck_assert_int_eq(m.hand, TM_LEFT);
  ck_assert_uint_eq(m.seed, 4294967295u);
  ck_assert_msg(parse(&m, BASE "steps = 89.5 90.5,90 , 90\n", err, sizeof err) == 0, "%s", err);
  ck_near(m.steps[1], 90.5, 0);
  ck_assert_msg(parse(&m, "teeth=1\ndiameter=5e3\n", err, sizeof err) == 0, "%s", err);
  ck_near(m.steps[0], 360, 0);
}
END_TEST

START_TEST(impossible_models)
{
  REFUSED(BASE "steps = 90, 80, 110, 70\n", "t.tool:3: steps: they sum to 350");
  REFUSED(BASE "steps = 90, 90, 180\n", "t.tool:3: steps: 3 steps for 4 teeth");
  REFUSED(BASE "steps = 90, 0, 180, 90\n", "t.tool:3: steps: step 2 is 0 degrees");
  REFUSED(BASE "steps = 90, , 180, 90\n", "t.tool:3: steps: an empty item");
  REFUSED("teeth = 0\ndiameter = 1\n", "t.tool:1: teeth: 0; a tool has 1 to 150 teeth");
  REFUSED("teeth = 151\ndiameter = 1\n", "t.tool:1: teeth: 151");
  REFUSED("teeth = 2.5\n", "t.tool:1: teeth: 2.5 is not a whole number");
  REFUSED("teeth = 4\ndiameter = -60000\n", "t.tool:2: diameter: -60000 µm is negative");
  REFUSED("teeth = 4\ndiameter = 0\n", "t.tool:2: diameter: 0");
  REFUSED(BASE "lead = -250000\n", "t.tool:3: lead: -250000 µm is negative");
  REFUSED(BASE "lead = 10\n", "t.tool:3: lead: 10 µm is shorter");
  REFUSED(BASE "noise = 1.5\n", "t.tool:3: noise: 1.5 is outside 0..1");
  REFUSED(BASE "noise = -0.1\n", "t.tool:3: noise: -0.1 is outside 0..1");
  REFUSED(BASE "blur = -1\n", "t.tool:3: blur: -1 pixels is negative");
  REFUSED(BASE "image = 32\n", "t.tool:3: image: 32 pixels is too small");
  REFUSED(BASE "image = 5000\n", "t.tool:3: image: 5000 pixels is too large");
  REFUSED("teeth = 150\ndiameter = 1000\nimage = 256\n", "t.tool:3: image: 256 pixels is too small for a step of 2.4");
  REFUSED(BASE "hand = up\n", "t.tool:3: hand: 'up'; right or left");
  REFUSED(BASE "seed = -1\n", "t.tool:3: seed: -1 is outside");
}
END_TEST

START_TEST(malformed_lines)
{
  REFUSED(BASE "colour = red\n", "t.tool:3: unknown key 'colour'");
  REFUSED(BASE "\nteeth = 5\n", "t.tool:4: teeth: given twice (first on line 1)");
  REFUSED(BASE "lead 250000\n", "t.tool:3: expected 'key = value'");
  REFUSED(BASE " = 5\n", "t.tool:3: a value without a key");
  REFUSED(BASE "lead =   ; nothing\n", "t.tool:3: lead: no value");
  REFUSED(BASE "lead = 12abc\n", "t.tool:3: lead: '12abc' is not a number");
  REFUSED(BASE "lead = nan\n", "t.tool:3: lead: 'nan' is not a number");
  REFUSED(BASE "lead = 0x10\n", "t.tool:3: lead: '0x10' is not a number");
  REFUSED(BASE "lead = 1e999\n", "t.tool:3: lead: '1e999' is not a number");
  REFUSED(BASE "lead = 2,5\n", "t.tool:3: lead: '2,5' is not a number");
  REFUSED("diameter = 1\n", "t.tool: no 'teeth'");
  REFUSED("teeth = 3\n", "t.tool: no 'diameter'");
  struct tm_model m;
  char err[256];
  ck_assert_int_eq(tm_parse(&m, "teeth = 4\0\n", 11, "nul.tool", err, sizeof err), -1);
  ck_assert_msg(strstr(err, "nul.tool:1: a NUL byte") != NULL, "%s", err);
}
END_TEST

START_TEST(load_and_check)
{
  struct tm_model m;
  char err[256];
  ck_assert_int_eq(tm_load(&m, "/nonexistent/x.tool", err, sizeof err), -1);
  ck_assert_msg(strstr(err, "/nonexistent/x.tool: cannot open") != NULL, "%s", err);
  tm_defaults(&m);
  m.teeth = 3;
  m.diameter = 1000;
  ck_assert_msg(tm_check(&m, err, sizeof err) == 0, "%s", err);
  m.even = 0;
  m.steps[0] = m.steps[1] = m.steps[2] = 100;
  ck_assert_int_eq(tm_check(&m, err, sizeof err), -1);
  ck_assert_msg(strstr(err, "sum to 300") != NULL, "%s", err);
  /* a tiny error buffer is never overrun */
  char small[8];
  ck_assert_int_eq(parse(&m, "teeth = 0\n", small, sizeof small), -1);
  ck_assert_int_eq((int)strlen(small), 7);
}
END_TEST

Suite *suite_toolmodel(void)
{
  Suite *s = suite_create("toolmodel");
  TCase *tc = tcase_create("toolmodel");
  tcase_add_test(tc, contract_example);
  tcase_add_test(tc, defaults_and_forms);
  tcase_add_test(tc, impossible_models);
  tcase_add_test(tc, malformed_lines);
  tcase_add_test(tc, load_and_check);
  suite_add_tcase(s, tc);
  return s;
}
