/* The G and M table (src/dialect/2c42/words.h) against the language: the
 * spec's lists (language.md sec. 3, 8 and 9, transcribed here, and read
 * from the spec itself when ../shared/spec is there), and the functions
 * generated from the table against the rows, and the compiler against
 * both (motions, planes, the lists its messages print). */
#include "suites.h"
#include "errors.h"
#include "kp.h"
#include "words.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the spec's lists, transcribed ---- */

/* language.md sec. 8: group of each G */
static const struct { int g, group; } spec_g[] = {
  {1, 1}, {2, 1}, {3, 1}, {4, 1}, {7, 1}, {10, 1}, {11, 1}, {12, 1}, {13, 1}, {20, 1}, {37, 1},
  {17, 2}, {18, 2}, {19, 2}, {9, 3}, {27, 4}, {28, 4}, {29, 4}, {33, 4}, {34, 4},
};
/* sec. 8: "separate block" in the meaning */
static const int spec_sep[] = {4, 7, 10, 11, 20, 37};
/* sec. 9 */
static const int spec_m[] = {2, 3, 4, 5, 10, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 25, 26, 27, 28, 29};
/* sec. 3: "/text/ | argument of G27 G28 G29 G33 G37 M16 M18 M20" */
static const char *const spec_slash = "G27 G28 G29 G33 G37 M16 M18 M20";
/* sec. 9 M18, M21 and sec. 11 PP: "not in a block with G10 G11 G27 G28 G33 G34" */
static const char *const spec_nodir = "G10 G11 G27 G28 G33 G34";
/* sec. 8: circular and helical interpolation */
static const char *const spec_arcs = "G02 G03 G12 G13";

static int in(const int *v, size_t n, int x)
{
  for (size_t i = 0; i < n; i++)
    if (v[i] == x)
      return 1;
  return 0;
}

static int spec_group(int g)
{
  for (size_t i = 0; i < sizeof spec_g / sizeof spec_g[0]; i++)
    if (spec_g[i].g == g)
      return spec_g[i].group;
  return 0;
}

static int has_sep(const struct kp_word *w) { return (w->flags & KP_SEP) != 0; }
static int has_slash(const struct kp_word *w) { return w->slash != KP_SA_NONE; }
static int has_nodir(const struct kp_word *w) { return (w->flags & KP_NODIR) != 0; }
static int has_arc(const struct kp_word *w) { return (w->flags & KP_ARC) != 0; }
static int has_owner(const struct kp_word *w) { return w->owner != NULL; }

START_TEST(g_functions_are_the_spec_s)
{
  int n = 0;
  for (int g = -1; g < 100; g++) {
    int group = spec_group(g);
    ck_assert_msg(kp_valid_g(g) == (group != 0), "G%02d valid %d, the spec's group %d", g, kp_valid_g(g), group);
    if (!group)
      continue;
    n++;
    ck_assert_msg(kp_g_group(g) == group, "G%02d: group %d, the spec says %d", g, kp_g_group(g), group);
    int sep = in(spec_sep, sizeof spec_sep / sizeof spec_sep[0], g);
    ck_assert_msg(((kp_g(g)->flags & KP_SEP) != 0) == sep, "G%02d: separate block %d, the spec %d", g,
                  (kp_g(g)->flags & KP_SEP) != 0, sep);
  }
  ck_assert_int_eq(n, 20);
  /* a number the table has not: group 1 (a plugin's G declares its own) */
  ck_assert_int_eq(kp_g_group(50), 1);
  char buf[200];
  ck_assert_str_eq(kp_codes(buf, sizeof buf, has_sep), "G04 G07 G10 G11 G20 G37");
  ck_assert_str_eq(kp_codes(buf, sizeof buf, has_arc), spec_arcs);
  ck_assert_str_eq(kp_codes(buf, sizeof buf, has_nodir), spec_nodir);
}
END_TEST

START_TEST(m_functions_are_the_spec_s)
{
  int n = 0;
  for (int m = -1; m < 100; m++) {
    int want = in(spec_m, sizeof spec_m / sizeof spec_m[0], m);
    ck_assert_msg(kp_valid_m(m) == want, "M%02d valid %d, the spec %d", m, kp_valid_m(m), want);
    n += want;
    if (want) {
      ck_assert_int_eq(kp_m(m)->group, 0);
      ck_assert_int_eq(kp_m(m)->plane, 0);
    }
  }
  ck_assert_int_eq(n, 22);
}
END_TEST

START_TEST(slash_planes_arcs_owners)
{
  char buf[200];
  ck_assert_str_eq(kp_codes(buf, sizeof buf, has_slash), spec_slash);
  ck_assert_int_eq(kp_g(27)->slash, KP_SA_PROMPT);
  ck_assert_int_eq(kp_g(28)->slash, KP_SA_BOUNDS);
  ck_assert_int_eq(kp_g(29)->slash, KP_SA_LINES);
  ck_assert_int_eq(kp_g(33)->slash, KP_SA_TEXT);
  ck_assert_int_eq(kp_g(37)->slash, KP_SA_AXIS);
  ck_assert_int_eq(kp_m(16)->slash, KP_SA_CORR);
  ck_assert_int_eq(kp_m(18)->slash, KP_SA_TEXT);
  ck_assert_int_eq(kp_m(20)->slash, KP_SA_PARAMS);
  for (int g = 0; g < 64; g++)
    if (kp_g(g))
      ck_assert_int_eq(kp_g(g)->plane, g >= 17 && g <= 19 ? g : 0);
  /* helices are the arcs that let one more axis move */
  ck_assert_int_eq(kp_g(12)->flags & KP_HELIX, KP_HELIX);
  ck_assert_int_eq(kp_g(13)->flags & KP_HELIX, KP_HELIX);
  ck_assert_int_eq(kp_g(2)->flags & KP_HELIX, 0);
  ck_assert_int_eq(kp_g(3)->flags & KP_HELIX, 0);
  /* README "Oscillation and helices", "Tooth-step search" */
  ck_assert_str_eq(kp_codes(buf, sizeof buf, has_owner), "G07 G10 G11 G12 G13 M10 M12 M13 M14");
  ck_assert_str_eq(kp_g(7)->owner, "oscillation");
  ck_assert_str_eq(kp_m(13)->owner, "oscillation");
  ck_assert_str_eq(kp_m(14)->owner, "oscillation");
  ck_assert_str_eq(kp_g(10)->owner, "toothsearch");
  ck_assert_str_eq(kp_g(11)->owner, "toothsearch");
  ck_assert_str_eq(kp_m(10)->owner, "toothsearch");
  ck_assert_str_eq(kp_m(12)->owner, "toothsearch");
  ck_assert_str_eq(kp_g(12)->owner, "helix");
  ck_assert_str_eq(kp_g(13)->owner, "helix");
  /* the E-PLUGIN messages name them so */
  ck_assert_str_eq(kp_g(12)->name, "helical interpolation");
  ck_assert_str_eq(kp_g(7)->name, "oscillation parameters");
  ck_assert_str_eq(kp_m(12)->name, "search speed from F");
}
END_TEST

/* ---- the generated functions agree with the rows ---- */

START_TEST(lookups_agree_with_rows)
{
  for (int kind = 0; kind < 2; kind++) {
    char k = kind ? 'M' : 'G';
    int max = kind ? 32 : 64;
    for (int n = -5; n < 120; n++) {
      const struct kp_word *w = kp_word(k, n);
      ck_assert_ptr_eq(w, kind ? kp_m(n) : kp_g(n));
      ck_assert_int_eq(kind ? kp_valid_m(n) : kp_valid_g(n), w != NULL);
      if (n < 0 || n >= max) {
        ck_assert_ptr_null(w);
        continue;
      }
      if (!w)
        continue;
      char code[8];
      snprintf(code, sizeof code, "%c%02d", k, n);
      ck_assert_int_eq(w->kind, k);
      ck_assert_int_eq(w->number, n);
      ck_assert_str_eq(w->code, code);
      ck_assert_ptr_nonnull(w->name);
      ck_assert_int_gt((int)strlen(w->name), 3);
      if (k == 'G') {
        ck_assert_int_eq(kp_g_group(n), w->group);
        ck_assert_int_ge(w->group, 1);
        ck_assert_int_le(w->group, 4);
        /* the dialog group is the dialog motion */
        ck_assert_int_eq(w->group == 4, w->motion == MO_DIALOG);
        /* a motion of its own is a group-1 function */
        if (w->motion != MO_NONE && w->motion != MO_DIALOG)
          ck_assert_int_eq(w->group, 1);
      }
      if (w->flags & KP_HELIX)
        ck_assert(w->flags & KP_ARC);
      if (w->motion != MO_NONE && w->motion != MO_DIALOG) {
        /* its own motion, named after it */
        ck_assert_str_eq(kp_motion_name[w->motion], code);
        ck_assert_int_eq(kp_motion_arc(w->motion), (w->flags & KP_ARC) != 0);
      }
    }
  }
  ck_assert_ptr_null(kp_word('X', 1));
  ck_assert_ptr_null(kp_g(64));
  ck_assert_ptr_null(kp_m(32));
}
END_TEST

START_TEST(motions_and_their_names)
{
  /* every motion has one name, none twice */
  for (int i = 0; i < MO__COUNT; i++) {
    ck_assert_ptr_nonnull(kp_motion_name[i]);
    for (int j = 0; j < i; j++)
      ck_assert_str_ne(kp_motion_name[i], kp_motion_name[j]);
  }
  ck_assert_str_eq(kp_motion_name[MO_NONE], "none");
  ck_assert_str_eq(kp_motion_name[MO_G01], "G01");
  ck_assert_str_eq(kp_motion_name[MO_G37], "G37");
  ck_assert_str_eq(kp_motion_name[MO_M19], "M19");
  ck_assert_str_eq(kp_motion_name[MO_DIALOG], "dialog");
  ck_assert_str_eq(kp_motion_name[MO_PLUGIN], "plugin");
  /* the order enum motion had before it came from the table (traces and
   * the machine switch on the names; keep the values too) */
  static const int order[] = {MO_NONE, MO_G01, MO_G02, MO_G03, MO_G04, MO_G07, MO_G10, MO_G11, MO_G12, MO_G13,
                              MO_G20, MO_G37, MO_M19, MO_DIALOG, MO_PLUGIN};
  ck_assert_int_eq(MO__COUNT, (int)(sizeof order / sizeof order[0]));
  for (int i = 0; i < MO__COUNT; i++)
    ck_assert_int_eq(order[i], i);
  ck_assert(kp_motion_arc(MO_G02) && kp_motion_arc(MO_G03) && kp_motion_arc(MO_G12) && kp_motion_arc(MO_G13));
  ck_assert(!kp_motion_arc(MO_G01) && !kp_motion_arc(MO_NONE) && !kp_motion_arc(MO_PLUGIN) &&
            !kp_motion_arc(MO_DIALOG) && !kp_motion_arc(MO__COUNT) && !kp_motion_arc(-1));
  /* kp_codes cuts a list that does not fit between codes */
  char small[9];
  ck_assert_str_eq(kp_codes(small, sizeof small, has_arc), "G02 G03");
  ck_assert_str_eq(kp_codes(small, 3, has_arc), "");
}
END_TEST

/* ---- the compiler takes its rules from the table ---- */

static int motion_of(const char *src)
{
  struct tprog t;
  tp_compile(&t, src);
  ck_assert_msg(t.rc == 0, "%s does not compile:\n%s", src, tp_diags(&t.d));
  int mo = kp_attr(&t.p, 0)->motion, plane = kp_attr(&t.p, 0)->plane;
  tp_free(&t);
  return mo | plane << 8;
}

START_TEST(compiler_motions_and_planes)
{
  ck_assert_int_eq(motion_of("N1 G01 X+1\nN2 M2\n"), MO_G01);
  ck_assert_int_eq(motion_of("N1 G09 X+1\nN2 M2\n"), MO_G01);          /* axis words alone: G01 */
  ck_assert_int_eq(motion_of("N1 G09\nN2 M2\n"), MO_NONE);
  ck_assert_int_eq(motion_of("N1 G04 X+5\nN2 M2\n"), MO_G04);
  ck_assert_int_eq(motion_of("N1 G02 G18 Y+0 Z+0 J-10 K+0\nN2 M2\n"), MO_G02 | 18 << 8);
  ck_assert_int_eq(motion_of("N1 G03 G19 X+0 Z+0 I-10 K+0\nN2 M2\n"), MO_G03 | 19 << 8);
  ck_assert_int_eq(motion_of("N1 G20\nN2 M2\n"), MO_G20);
  ck_assert_int_eq(motion_of("N1 G37 /Y/\nN2 M2\n"), MO_G37);
  ck_assert_int_eq(motion_of("N1 M19 X+10\nN2 M2\n"), MO_M19);
  ck_assert_int_eq(motion_of("N1 G01 G17 M19 X+10\nN2 M2\n"), MO_M19 | 17 << 8);   /* M19 overrides */
  ck_assert_int_eq(motion_of("N1 G33 /A/\nN2 M2\n"), MO_DIALOG);
  ck_assert_int_eq(motion_of("N1 M03 G34\nN2 M2\n"), MO_DIALOG);
  ck_assert_int_eq(motion_of("N1 G29 /A/B//\nN2 M2\n"), MO_DIALOG);
}
END_TEST

/* src has an error with this code and message. */
static void first_error(const char *src, int code, const char *msg)
{
  struct tprog t;
  tp_compile(&t, src);
  int found = 0;
  for (size_t i = 0; i < t.d.n && !found; i++)
    found = t.d.v[i].sev == DIAG_ERROR && t.d.v[i].code == code && strcmp(t.d.v[i].msg, msg) == 0;
  ck_assert_msg(found, "%s: no error %d \"%s\":\n%s", src, code, msg, tp_diags(&t.d));
  tp_free(&t);
}

START_TEST(compiler_lists_from_the_table)
{
  /* each separate function refuses axis words; G04 and G07 say their own */
  static const char *const sep[] = {"G10", "G11", "G20"};
  for (size_t i = 0; i < sizeof sep / sizeof sep[0]; i++) {
    char src[80], msg[120];
    snprintf(src, sizeof src, "N1 %s D1+1000 Y+5\nN2 M2\n", sep[i]);
    snprintf(msg, sizeof msg, "%s stands in a separate block: no axis or centre words beside it", sep[i]);
    first_error(src, S42_E_BLOCK, msg);
  }
  first_error("N1 G37 /Y/ X+5\nN2 M2\n", S42_E_BLOCK,
              "G37 stands in a separate block: no axis or centre words beside it");
  first_error("N1 G04 X+5 Y+1\nN2 M2\n", S42_E_BLOCK, "G04 stands in a separate block: only X (the dwell) beside it");
  first_error("N1 G20 M19 X+5\nN2 M2\n", S42_E_BLOCK,
              "M19 gives the direction of a move: not with G04 G07 G10 G11 G20 G37");
  first_error("N1 G01 X+1 I+5\nN2 M2\n", S42_E_BLOCK, "centre words I J K belong to an arc (G02 G03 G12 G13)");
  first_error("N1 M03 /A/\nN2 M2\n", S42_E_SYNTAX,
              "a slash argument must follow its function (G27 G28 G29 G33 G37 M16 M18 M20)");
  first_error("N1 G33 /A/ M21\nN2 M2\n", S42_E_BLOCK, "M21 is not allowed in a block with G33");
  first_error("N1 G13 X+0 Y+0 I+1 J+0\nN2 M2\n", S42_E_PLANE,
              "G13 needs a plane in the same block: G17 (XY), G18 (YZ) or G19 (XZ)");
  /* an arc refuses an axis outside its plane; a helix takes one */
  first_error("N1 G02 G17 X+0 Y+0 I-10 J+0 Z+5\nN2 M2\n", S42_E_PLANE, "Z is not in the G17 plane of this arc (XY)");
  first_error("N1 G12 G17 X+0 Y+0 I-10 J+0 Z+5 A+1\nN2 M2\n", S42_E_PLANE,
              "G12: only one axis outside the G17 plane may move along the helix");
  struct tprog t;
  tp_compile(&t, "N1 G17 X+5\nN2 M2\n");
  int k = tp_find(&t.d, DIAG_WARNING, 0, 1, 0);
  ck_assert_int_ge(k, 0);
  ck_assert_str_eq(t.d.v[k].msg, "G17 has no effect without an arc (G02 G03 G12 G13)");
  tp_free(&t);
}
END_TEST

/* ---- the spec itself, when it is there ---- */

/* Append to out the codes (G01, M3 -> M03) found in s up to the end or a
 * '|'. */
static void codes_in(const char *s, const char *end, char kind, char *out, size_t n)
{
  for (const char *p = s; p < end && *p && *p != '|'; p++) {
    if (*p != kind || (p > s && ((p[-1] >= 'A' && p[-1] <= 'Z') || (p[-1] >= '0' && p[-1] <= '9'))))
      continue;
    if (p[1] < '0' || p[1] > '9')
      continue;
    int v = atoi(p + 1);
    size_t k = strlen(out);
    snprintf(out + k, n - k, "%s%c%02d", k ? " " : "", kind, v);
  }
}

START_TEST(the_spec_file_agrees)
{
  char path[4096];
  const char *spec = getenv("S42_SPEC");
  const char *src = getenv("S42_SRCDIR");
  if (spec)
    snprintf(path, sizeof path, "%s", spec);
  else
    snprintf(path, sizeof path, "%s/../shared/spec/language.md", src ? src : ".");
  FILE *f = fopen(path, "r");
  if (!f) {
    fprintf(stderr, "words: %s is not here: the table is checked against the transcription only\n", path);
    return;
  }
  char line[8192];
  int sec = 0, ng = 0, nm = 0;
  char slash[200] = "", nodir[200] = "";
  while (fgets(line, sizeof line, f)) {
    if (strncmp(line, "## ", 3) == 0)
      sec = atoi(line + 3);
    if (sec == 3 && strstr(line, "| `/text/` |")) {
      const char *a = strstr(line, "argument of ");
      ck_assert_ptr_nonnull(a);
      codes_in(a, a + strlen(a), 'G', slash, sizeof slash);
      codes_in(a, a + strlen(a), 'M', slash, sizeof slash);
    }
    /* sec. 8: | group | G01 / G02 | meaning | */
    if (sec == 8 && line[0] == '|' && line[2] >= '1' && line[2] <= '4' && line[3] == ' ') {
      int group = line[2] - '0';
      const char *cell = strchr(line + 1, '|') + 1;
      const char *meaning = strchr(cell, '|') + 1;
      char gs[100] = "";
      codes_in(cell, meaning, 'G', gs, sizeof gs);
      int sep = strstr(meaning, "separate block") != NULL;
      for (char *p = gs; *p; p += 3 + (p[3] == ' ')) {
        int g = atoi(p + 1);
        ck_assert_msg(kp_valid_g(g), "the spec's G%02d is not in the table", g);
        ck_assert_msg(kp_g_group(g) == group, "G%02d: group %d, the spec says %d", g, kp_g_group(g), group);
        ck_assert_msg(((kp_g(g)->flags & KP_SEP) != 0) == sep, "G%02d: separate block, the spec says %d", g, sep);
        ck_assert_msg(spec_group(g) == group, "G%02d: the transcription's group is not the spec's", g);
        ng++;
      }
    }
    /* sec. 9: | M3 / M4 | meaning | */
    if (sec == 9 && strncmp(line, "| M", 3) == 0) {
      const char *meaning = strchr(line + 1, '|');
      char ms[100] = "";
      codes_in(line + 1, meaning, 'M', ms, sizeof ms);
      for (char *p = ms; *p; p += 3 + (p[3] == ' ')) {
        int m = atoi(p + 1);
        ck_assert_msg(kp_valid_m(m), "the spec's M%02d is not in the table", m);
        ck_assert_msg(in(spec_m, sizeof spec_m / sizeof spec_m[0], m), "M%02d: not in the transcription", m);
        nm++;
      }
      const char *nd = strstr(meaning, "not in a block with ");
      if (nd && !*nodir)
        codes_in(nd, nd + strlen(nd), 'G', nodir, sizeof nodir);
    }
  }
  fclose(f);
  ck_assert_int_eq(ng, 20);
  ck_assert_int_eq(nm, 22);
  ck_assert_str_eq(slash, spec_slash);
  ck_assert_str_eq(nodir, spec_nodir);
}
END_TEST

Suite *suite_words(void)
{
  Suite *s = suite_create("words");
  TCase *tc = tcase_create("table");
  tcase_add_test(tc, g_functions_are_the_spec_s);
  tcase_add_test(tc, m_functions_are_the_spec_s);
  tcase_add_test(tc, slash_planes_arcs_owners);
  tcase_add_test(tc, lookups_agree_with_rows);
  tcase_add_test(tc, motions_and_their_names);
  tcase_add_test(tc, compiler_motions_and_planes);
  tcase_add_test(tc, compiler_lists_from_the_table);
  tcase_add_test(tc, the_spec_file_agrees);
  suite_add_tcase(s, tc);
  return s;
}
