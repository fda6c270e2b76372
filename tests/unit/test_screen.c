/* Golden screens of the 2С42-65 display (display/screen.h, language.md
 * sec. 13): a screen is built with the screen API, or by running a program
 * through a session, rendered into the 16x32 grid, printed as text and
 * compared with the exact 16 lines expected.  Lines are written as
 * screen_print gives them: trailing blanks dropped. */
#include "suites.h"
#include "messages.h"
#include "screen.h"
#include "session.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- golden comparison ---------------------------------------------- */

static char *grid_text(uint32_t g[SCR_ROWS][SCR_COLS])
{
  char *buf = NULL;
  size_t n = 0;
  FILE *f = open_memstream(&buf, &n);
  ck_assert_ptr_nonnull(f);
  screen_print(f, g);
  fclose(f);
  return buf;
}

/* The lines numbered "NN|", so that failure messages show empty lines. */
static char *numbered(const char *text)
{
  char *buf = NULL;
  size_t n = 0;
  FILE *f = open_memstream(&buf, &n);
  ck_assert_ptr_nonnull(f);
  int r = 1;
  fprintf(f, "%02d|", r);
  for (const char *p = text; *p; p++) {
    fputc(*p, f);
    if (*p == '\n' && p[1])
      fprintf(f, "%02d|", ++r);
  }
  fclose(f);
  return buf;
}

/* want: up to 16 lines, missing (NULL) lines are empty. */
static void check_grid(uint32_t g[SCR_ROWS][SCR_COLS], const char *const want[SCR_ROWS], int line)
{
  char exp[SCR_ROWS * (SCR_COLS * 4 + 1) + 1];
  size_t k = 0;
  for (int r = 0; r < SCR_ROWS; r++) {
    const char *w = want[r] ? want[r] : "";
    size_t n = strlen(w);
    ck_assert_msg(k + n + 1 < sizeof exp, "golden line %d too long", r + 1);
    memcpy(exp + k, w, n);
    k += n;
    exp[k++] = '\n';
  }
  exp[k] = 0;
  char *got = grid_text(g);
  int same = strcmp(got, exp) == 0;
  if (!same) {
    char *ng = numbered(got), *ne = numbered(exp);
    free(got);
    got = ng;
    snprintf(exp, sizeof exp, "%s", ne);
    free(ne);
  }
  if (!same) {
    /* name the first line that differs, then show both screens */
    int r = 0;
    const char *a = got, *b = exp;
    while (*a && *a == *b) {
      if (*a == '\n')
        r++;
      a++;
      b++;
    }
    ck_assert_msg(0, "screen (test line %d) differs at screen line %d:\n--- got\n%s--- want\n%s", line, r + 1, got,
                  exp);
  }
  free(got);
}

#define CK_SCREEN(g, ...) check_grid((g), (const char *const[SCR_ROWS]){__VA_ARGS__}, __LINE__)

/* ---- the screen model on its own ------------------------------------ */

static struct screen S;
static double R[114];
static uint32_t G[SCR_ROWS][SCR_COLS];

static void screen_setup(void)
{
  screen_init(&S);
  memset(R, 0, sizeof R);
  memset(G, 0, sizeof G);
}

static void render(void)
{
  screen_render(&S, R, S.en, G);
}

START_TEST(empty_screen)
{
  render();
  CK_SCREEN(G, "АВТОМАТ");
}
END_TEST

START_TEST(service_line_modes_and_block)
{
  S.block = 12;
  render();
  CK_SCREEN(G, "АВТОМАТ                      N12");
  S.mode = SCR_MANUAL;
  S.block = 3;
  render();
  CK_SCREEN(G, "РУЧНИЙ                        N3");
  S.mode = SCR_RESULTS;
  S.block = 1234;
  render();
  CK_SCREEN(G, "РЕЗУЛЬТАТИ                 N1234");
  S.mode = SCR_AUTO;
  S.cyr = 1;                 /* Cyrillic keyboard: the letter R */
  S.block = -1;              /* no number shown */
  render();
  CK_SCREEN(G, "АВТОМАТ R");
}
END_TEST

START_TEST(service_line_english)
{
  S.en = 1;
  S.block = 7;
  render();
  CK_SCREEN(G, "AUTO                          N7");
  S.mode = SCR_MANUAL;
  render();
  CK_SCREEN(G, "MANUAL                        N7");
  S.mode = SCR_RESULTS;
  render();
  CK_SCREEN(G, "RESULTS                       N7");
}
END_TEST

START_TEST(g33_centred_even_odd_full)
{
  screen_center(&S, "ABCD");                          /* (32-4)/2 = 14 */
  screen_center(&S, "ABC");                           /* floor(29/2) = 14 */
  screen_center(&S, "СВЕРДЛО");                       /* 7 letters: 12 */
  screen_center(&S, "КІНЕЦЬ ВВОДУ");                  /* 12: 10 */
  screen_center(&S, "ABCDEFGHIJKLMNOPQRSTUVWXYZ01234");  /* 31: 0 */
  screen_center(&S, "ЗАТОЧУВАННЯ СВЕРДЛА ДІАМЕТРОМ 35");  /* 32: 0 */
  screen_center(&S, "X");                             /* 1: 15 */
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "              ABCD",
            "              ABC",
            "            СВЕРДЛО",
            "          КІНЕЦЬ ВВОДУ",
            "ABCDEFGHIJKLMNOPQRSTUVWXYZ01234",
            "ЗАТОЧУВАННЯ СВЕРДЛА ДІАМЕТРОМ 35",
            "               X");
}
END_TEST

START_TEST(g27_colon_format)
{
  screen_prompt(&S, "ДІАМЕТР, МКМ", 0);
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "ДІАМЕТР, МКМ............._");
  screen_field_type(&S, 35000);
  screen_field_close(&S);
  screen_prompt(&S, "КРОК ГВИНТ. КАНАВКИ, МКМ", 0);   /* 24 characters: one dot */
  screen_prompt(&S, "", 0);                           /* no text: dots only */
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "ДІАМЕТР, МКМ.............  35000",
            "КРОК ГВИНТ. КАНАВКИ, МКМ.",                /* its field left empty */
            "........................._");
}
END_TEST

START_TEST(g27_wrapped_format)
{
  /* the line breaks at the last space that leaves <= 24 characters */
  screen_prompt(&S, "КРОК ГВИНТОВОЇ КАНАВКИ СВЕРДЛА, МКМ", 1);
  screen_field_type(&S, 3335);
  screen_field_close(&S);
  screen_prompt(&S, "ДІАМЕТР ЗАГОТОВКИ ПІД ЗАТОЧУВАННЯ, МКМ", 1);
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "КРОК ГВИНТОВОЇ КАНАВКИ СВЕРДЛА,",
            "МКМ......................   3335",
            "ДІАМЕТР ЗАГОТОВКИ ПІД",
            "ЗАТОЧУВАННЯ, МКМ........._");
}
END_TEST

START_TEST(g27_wrapped_56_characters)
{
  /* 32 + 24 = 56 characters, the most the '-' format takes */
  screen_prompt(&S, "AAAAAAAAAA BBBBBBBBBB CCCCCCCCC DDDDDDDDDD EEEEEEEEEEEEE", 1);
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "AAAAAAAAAA BBBBBBBBBB CCCCCCCCC",
            "DDDDDDDDDD EEEEEEEEEEEEE._");
  /* a short text in the '-' format stays on one line */
  screen_field_type(&S, 1);
  screen_field_close(&S);
  screen_prompt(&S, "ЗУБЦІВ", 1);
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "AAAAAAAAAA BBBBBBBBBB CCCCCCCCC",
            "DDDDDDDDDD EEEEEEEEEEEEE.      1",
            "ЗУБЦІВ..................._");
}
END_TEST

START_TEST(field_digits_move_the_cursor)
{
  screen_prompt(&S, "ДОВЖИНА, МКМ", 0);
  screen_field_digit(&S, 9);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ДОВЖИНА, МКМ.............9_");
  screen_field_digit(&S, 5);
  screen_field_digit(&S, 0);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ДОВЖИНА, МКМ.............950_");
  screen_field_digit(&S, 0);
  screen_field_digit(&S, 0);
  screen_field_digit(&S, 0);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ДОВЖИНА, МКМ.............950000_");
  ck_assert_double_eq(screen_field_value(&S), 950000);
  screen_field_close(&S);                           /* ПС: right-aligned, no cursor */
  render();
  CK_SCREEN(G, "АВТОМАТ", "ДОВЖИНА, МКМ............. 950000");
}
END_TEST

START_TEST(field_backspace)
{
  screen_prompt(&S, "КУТ, ГРАД", 0);
  screen_field_digit(&S, 1);
  screen_field_digit(&S, 2);
  screen_field_digit(&S, 7);
  screen_field_backspace(&S);                       /* ЗБ erases the 7 */
  render();
  CK_SCREEN(G, "АВТОМАТ", "КУТ, ГРАД................12_");
  screen_field_digit(&S, 0);
  render();
  CK_SCREEN(G, "АВТОМАТ", "КУТ, ГРАД................120_");
  screen_field_backspace(&S);
  screen_field_backspace(&S);
  screen_field_backspace(&S);
  screen_field_backspace(&S);                       /* one more at the first digit: nothing left */
  render();
  CK_SCREEN(G, "АВТОМАТ", "КУТ, ГРАД................_");
  ck_assert_double_eq(screen_field_value(&S), 0);
  screen_field_digit(&S, 9);
  screen_field_digit(&S, 0);
  screen_field_close(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ", "КУТ, ГРАД................     90");
}
END_TEST

START_TEST(field_arrows)
{
  screen_prompt(&S, "ПОДАЧА", 0);
  screen_field_digit(&S, 1);
  screen_field_digit(&S, 2);
  screen_field_digit(&S, 3);
  screen_field_move(&S, -2);                        /* <- <-: back onto the 2 */
  screen_field_digit(&S, 9);                        /* overwrite it */
  ck_assert_double_eq(screen_field_value(&S), 193);
  screen_field_move(&S, +1);                        /* ->: past the 3, an empty cell */
  render();
  CK_SCREEN(G, "АВТОМАТ", "ПОДАЧА...................193_");
  screen_field_move(&S, -3);                        /* to the first digit */
  screen_field_digit(&S, 5);
  ck_assert_int_eq(S.cursor, 1);
  render();                                      /* the cursor on a digit: no '_' over it */
  CK_SCREEN(G, "АВТОМАТ", "ПОДАЧА...................593");
  screen_field_move(&S, -2);                        /* <- from the first cell: to the seventh */
  ck_assert_int_eq(S.cursor, 6);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ПОДАЧА...................593   _");
  screen_field_move(&S, +1);                        /* -> from the seventh: to the first */
  ck_assert_int_eq(S.cursor, 0);
  screen_field_close(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ПОДАЧА...................    593");
}
END_TEST

START_TEST(field_wraps_after_seventh_digit)
{
  screen_prompt(&S, "ЧИСЛО", 0);
  for (int d = 1; d <= 7; d++)
    screen_field_digit(&S, d);
  render();                                      /* the cursor is back on the first digit */
  CK_SCREEN(G, "АВТОМАТ", "ЧИСЛО....................1234567");
  ck_assert_int_eq(S.cursor, 0);
  screen_field_digit(&S, 9);                        /* an eighth digit overwrites the first */
  screen_field_digit(&S, 8);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ЧИСЛО....................9834567");
  ck_assert_double_eq(screen_field_value(&S), 9834567);
  screen_field_close(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ЧИСЛО....................9834567");
}
END_TEST

START_TEST(field_leading_zeros_dropped)
{
  screen_prompt(&S, "ЗАЗОР", 0);
  screen_field_digit(&S, 0);
  screen_field_digit(&S, 0);
  screen_field_digit(&S, 4);
  screen_field_digit(&S, 0);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ЗАЗОР....................0040_");
  screen_field_close(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ЗАЗОР....................     40");
  ck_assert_double_eq(screen_field_value(&S), 40);
  screen_prompt(&S, "НУЛЬ", 0);
  screen_field_digit(&S, 0);
  screen_field_digit(&S, 0);
  screen_field_close(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ЗАЗОР....................     40", "НУЛЬ.....................      0");
}
END_TEST

START_TEST(field_negative)
{
  screen_prompt(&S, "КОРЕКЦІЯ, МКМ", 0);
  screen_field_minus(&S);
  screen_field_digit(&S, 1);
  screen_field_digit(&S, 2);
  screen_field_digit(&S, 0);
  render();                                      /* the sign left of the field */
  CK_SCREEN(G, "АВТОМАТ", "КОРЕКЦІЯ, МКМ...........-120_");
  ck_assert_double_eq(screen_field_value(&S), -120);
  screen_field_close(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ", "КОРЕКЦІЯ, МКМ............   -120");
  screen_prompt(&S, "ЗНОВУ", 0);
  screen_field_minus(&S);
  screen_field_minus(&S);                           /* the key again: positive */
  screen_field_digit(&S, 5);
  ck_assert_double_eq(screen_field_value(&S), 5);
  screen_field_type(&S, -999999);                   /* the script's answer: six digits and the sign */
  screen_field_close(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ", "КОРЕКЦІЯ, МКМ............   -120", "ЗНОВУ....................-999999");
}
END_TEST

/* SCREEN_BUGS.txt #1: a negative number of seven digits loses its first
 * digit when ПС closes the field ("-234567" for -1234567). */
START_TEST(field_negative_seven_digits)
{
  screen_prompt(&S, "ЧИСЛО", 0);
  screen_field_type(&S, -1234567);
  ck_assert_double_eq(screen_field_value(&S), -1234567);
  screen_field_close(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ЧИСЛО...................-1234567");
}
END_TEST

START_TEST(field_type_answer)
{
  screen_prompt(&S, "ДІАМЕТР, МКМ", 0);
  screen_field_digit(&S, 7);                        /* typed digits are replaced */
  screen_field_type(&S, 35000);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ДІАМЕТР, МКМ.............35000_");
  screen_field_close(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ", "ДІАМЕТР, МКМ.............  35000");
}
END_TEST

START_TEST(g28_refusal_and_reentry)
{
  S.block = 3;
  screen_prompt(&S, "ДІАМЕТР, МКМ", 0);
  screen_field_type(&S, 100);
  screen_field_close(&S);
  /* G28 /30000:40000/: too small -- the message and the field again */
  screen_message(&S, screen_msg_text(MSG_BELOW, S.en));
  screen_field_reopen(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ                       N3",
            "ДІАМЕТР, МКМ............._",
            [15] = "знач. менше допустимого");
  screen_field_digit(&S, 5);                        /* the next key takes the message away */
  render();
  CK_SCREEN(G, "АВТОМАТ                       N3", "ДІАМЕТР, МКМ.............5_");
  screen_field_type(&S, 50000);
  screen_field_close(&S);
  screen_message(&S, screen_msg_text(MSG_ABOVE, S.en));
  screen_field_reopen(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ                       N3",
            "ДІАМЕТР, МКМ............._",
            [15] = "знач. більше допустимого");
  S.has_message = 0;
  screen_field_type(&S, 35000);
  screen_field_close(&S);
  render();
  CK_SCREEN(G, "АВТОМАТ                       N3", "ДІАМЕТР, МКМ.............  35000");
}
END_TEST

START_TEST(messages_both_languages)
{
  static const char *const uk[] = {"знач. менше допустимого", "знач. більше допустимого", "Введення завершено",
                                    "Обмеження введення"};
  static const char *const en[] = {"value below the minimum", "value above the maximum", "Input complete",
                                   "Input buffer full"};
  static const int ids[] = {MSG_BELOW, MSG_ABOVE, MSG_DONE, MSG_LIMIT};
  for (int i = 0; i < 4; i++) {
    ck_assert_str_eq(screen_msg_text(ids[i], 0), uk[i]);
    ck_assert_str_eq(screen_msg_text(ids[i], 1), en[i]);
    screen_init(&S);
    screen_message(&S, screen_msg_text(ids[i], 0));
    render();
    CK_SCREEN(G, "АВТОМАТ", NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL,
              uk[i]);
    S.en = 1;
    screen_message(&S, screen_msg_text(ids[i], S.en));
    render();
    CK_SCREEN(G, "AUTO", NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, en[i]);
  }
}
END_TEST

START_TEST(message_pushes_directive_aside)
{
  screen_set_directive(&S, "ВСТАНОВИТИ КРУГ, ПУСК");
  render();
  CK_SCREEN(G, "АВТОМАТ", [15] = "ВСТАНОВИТИ КРУГ, ПУСК");
  screen_message(&S, screen_msg_text(MSG_DONE, 0));
  render();
  CK_SCREEN(G, "АВТОМАТ", [15] = "Введення завершено");
  S.has_message = 0;                             /* the next key */
  render();
  CK_SCREEN(G, "АВТОМАТ", [15] = "ВСТАНОВИТИ КРУГ, ПУСК");
  screen_clear_directive(&S);                       /* M21 */
  render();
  CK_SCREEN(G, "АВТОМАТ");
}
END_TEST

/* SCREEN_BUGS.txt #3: a message stays on line 16 after ЗБ, an arrow or the
 * minus key; only a digit takes it away. */
START_TEST(message_goes_on_next_key)
{
  screen_set_directive(&S, "ВВЕДІТЬ ЗАНОВО");
  screen_prompt(&S, "ДІАМЕТР, МКМ", 0);
  screen_message(&S, screen_msg_text(MSG_BELOW, 0));
  screen_field_backspace(&S);                       /* ЗБ is a key */
  render();
  CK_SCREEN(G, "АВТОМАТ", "ДІАМЕТР, МКМ............._", [15] = "ВВЕДІТЬ ЗАНОВО");
  screen_message(&S, screen_msg_text(MSG_BELOW, 0));
  screen_field_move(&S, 1);                         /* so is an arrow (the cursor moves on) */
  render();
  CK_SCREEN(G, "АВТОМАТ", "ДІАМЕТР, МКМ............. _", [15] = "ВВЕДІТЬ ЗАНОВО");
  screen_message(&S, screen_msg_text(MSG_BELOW, 0));
  screen_field_minus(&S);                           /* and the minus */
  render();
  CK_SCREEN(G, "АВТОМАТ", "ДІАМЕТР, МКМ............- _", [15] = "ВВЕДІТЬ ЗАНОВО");
}
END_TEST

START_TEST(directive_with_live_value)
{
  R[5] = 3;
  screen_set_directive(&S, "ЗАЛИШИЛОСЬ ЗУБІВ ((R5");
  render();
  CK_SCREEN(G, "АВТОМАТ", [15] = "ЗАЛИШИЛОСЬ ЗУБІВ        3");
  R[5] = -12.6;                                  /* live: rounded, with the sign */
  render();
  CK_SCREEN(G, "АВТОМАТ", [15] = "ЗАЛИШИЛОСЬ ЗУБІВ      -13");
  R[5] = 123456789;                              /* does not fit 8 */
  render();
  CK_SCREEN(G, "АВТОМАТ", [15] = "ЗАЛИШИЛОСЬ ЗУБІВ ********");
  screen_set_directive(&S, "((R5");              /* the value alone */
  R[5] = 42;
  render();
  CK_SCREEN(G, "АВТОМАТ", [15] = "      42");
}
END_TEST

/* SCREEN_BUGS.txt #2: the text after ((Rn in a directive loses the blank
 * that follows the number ("ЗУБ        3ПС, ПУСК"). */
START_TEST(directive_value_mid_text)
{
  R[5] = 3;
  screen_set_directive(&S, "ЗУБ ((R5 ПС, ПУСК");
  render();
  CK_SCREEN(G, "АВТОМАТ", [15] = "ЗУБ        3 ПС, ПУСК");
}
END_TEST

/* SCREEN_BUGS.txt #5: ((Р5 with the Cyrillic Р (which the compiler and G29
 * accept) shows R0 in a directive, followed by the text "Р5". */
START_TEST(directive_cyrillic_r)
{
  R[0] = 9;
  R[5] = 3;
  screen_set_directive(&S, "ЗУБ ((Р5");
  render();
  CK_SCREEN(G, "АВТОМАТ", [15] = "ЗУБ        3");
}
END_TEST

START_TEST(p3_cyrillic_r)
{
  R[0] = 9;
  R[105] = 4;
  screen_p3_clear(&S);
  screen_p3_add(&S, "ЗУБ ((Р105");                  /* the Cyrillic Р names the parameter too */
  render();
  CK_SCREEN(G, "АВТОМАТ", "ЗУБ                            4");
}
END_TEST

START_TEST(value8_formats)
{
  static const struct { double v; const char *s; } t[] = {
    {0, "       0"},        {35000, "   35000"},  {-120, "    -120"},   {2.5, "       3"},
    {-2.5, "      -3"},     {2.4999, "       2"}, {-0.4, "       0"},   {99999999, "99999999"},
    {99999999.4, "99999999"}, {99999999.5, "********"}, {100000000, "********"}, {-9999999, "-9999999"},
    {-9999999.5, "********"}, {-10000000, "********"}, {1e300, "********"},
  };
  for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
    char out[9];
    screen_value8(t[i].v, out);
    ck_assert_msg(strcmp(out, t[i].s) == 0, "%.10g shows \"%s\", want \"%s\"", t[i].v, out, t[i].s);
  }
}
END_TEST

START_TEST(p3_live_values)
{
  screen_p3_clear(&S);
  screen_p3_add(&S, "ЗАТОЧУВАННЯ МІТЧИКА");
  screen_p3_add(&S, "ПРИПУСК ((R100");
  screen_p3_add(&S, "КІЛЬКІСТЬ ЗУБЦІВ ((R101");
  screen_p3_add(&S, "ПОДАЧА ((R 102");
  R[100] = 1000;
  R[101] = 6;
  R[102] = 10;
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "ЗАТОЧУВАННЯ МІТЧИКА",
            "ПРИПУСК                     1000",
            "КІЛЬКІСТЬ ЗУБЦІВ               6",
            "ПОДАЧА                        10");
  R[100] = 700;                                  /* the display follows the parameters */
  R[101] = 5;
  R[102] = -2.7;
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "ЗАТОЧУВАННЯ МІТЧИКА",
            "ПРИПУСК                      700",
            "КІЛЬКІСТЬ ЗУБЦІВ               5",
            "ПОДАЧА                        -3");
  R[100] = 1e9;
  R[101] = -10000000;
  R[102] = 99999999;
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "ЗАТОЧУВАННЯ МІТЧИКА",
            "ПРИПУСК                 ********",
            "КІЛЬКІСТЬ ЗУБЦІВ        ********",
            "ПОДАЧА                  99999999");
}
END_TEST

START_TEST(p3_full_lines)
{
  screen_p3_clear(&S);
  screen_p3_add(&S, "ЗАТОЧУВАННЯ СВЕРДЛА ДІАМЕТРОМ 35");   /* 32 without a value */
  screen_p3_add(&S, "ЗАЛИШОК ПРИПУСКУ НА ЗУБІ((R113");     /* 24 beside a value */
  screen_p3_add(&S, "");
  screen_p3_add(&S, "((R100");
  R[113] = 15;
  R[100] = -7;
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "ЗАТОЧУВАННЯ СВЕРДЛА ДІАМЕТРОМ 35",
            "ЗАЛИШОК ПРИПУСКУ НА ЗУБІ      15",
            "",
            "                              -7");
}
END_TEST

START_TEST(p3_and_dialog_switch)
{
  screen_center(&S, "СВЕРДЛО");
  screen_prompt(&S, "ДІАМЕТР, МКМ", 0);
  screen_field_type(&S, 35000);
  screen_field_close(&S);
  screen_p3_clear(&S);
  screen_p3_add(&S, "ДІАМЕТР((R100");
  R[100] = 35000;
  render();                                      /* G29: the P3 display */
  CK_SCREEN(G, "АВТОМАТ", "ДІАМЕТР                    35000");
  screen_center(&S, "ЩЕ");                          /* the next G33: back to the dialog lines */
  render();
  CK_SCREEN(G, "АВТОМАТ", "            СВЕРДЛО", "ДІАМЕТР, МКМ.............  35000", "               ЩЕ");
}
END_TEST

START_TEST(buffer_of_four_screens)
{
  char t[32];
  for (int i = 1; i <= SCR_BUF; i++) {
    snprintf(t, sizeof t, "L%02d", i);
    screen_center(&S, t);
  }
  ck_assert_int_eq(S.nbuf, 56);
  ck_assert_int_eq(S.has_message, 0);            /* four screens exactly: no message yet */
  render();                                      /* the last screen */
  CK_SCREEN(G, "АВТОМАТ",
            "              L43", "              L44", "              L45", "              L46",
            "              L47", "              L48", "              L49", "              L50",
            "              L51", "              L52", "              L53", "              L54",
            "              L55", "              L56");
  screen_center(&S, "L57");                         /* past four screens */
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "              L44", "              L45", "              L46", "              L47",
            "              L48", "              L49", "              L50", "              L51",
            "              L52", "              L53", "              L54", "              L55",
            "              L56", "              L57",
            "Обмеження введення");
  S.has_message = 0;
  screen_scroll(&S, -100);                          /* ↑ to the top: L1 has gone */
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "              L02", "              L03", "              L04", "              L05",
            "              L06", "              L07", "              L08", "              L09",
            "              L10", "              L11", "              L12", "              L13",
            "              L14", "              L15");
  screen_scroll(&S, 14);                            /* ↓ one screen */
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "              L16", "              L17", "              L18", "              L19",
            "              L20", "              L21", "              L22", "              L23",
            "              L24", "              L25", "              L26", "              L27",
            "              L28", "              L29");
  screen_scroll(&S, 1);                             /* ↓ one line */
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "              L17", "              L18", "              L19", "              L20",
            "              L21", "              L22", "              L23", "              L24",
            "              L25", "              L26", "              L27", "              L28",
            "              L29", "              L30");
  screen_scroll(&S, 1000);                          /* no further than the last line */
  ck_assert_int_eq(S.top, SCR_BUF - SCR_WORK);
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "              L44", "              L45", "              L46", "              L47",
            "              L48", "              L49", "              L50", "              L51",
            "              L52", "              L53", "              L54", "              L55",
            "              L56", "              L57");
}
END_TEST

START_TEST(buffer_full_english)
{
  S.en = 1;
  for (int i = 0; i <= SCR_BUF; i++)
    screen_center(&S, "X");
  render();
  CK_SCREEN(G, "AUTO",
            "               X", "               X", "               X", "               X", "               X",
            "               X", "               X", "               X", "               X", "               X",
            "               X", "               X", "               X", "               X",
            "Input buffer full");
}
END_TEST

START_TEST(scroll_short_buffer)
{
  screen_center(&S, "A");
  screen_center(&S, "B");
  screen_scroll(&S, 5);                             /* less than a screen: nothing to scroll */
  ck_assert_int_eq(S.top, 0);
  screen_scroll(&S, -5);
  ck_assert_int_eq(S.top, 0);
  for (int i = 0; i < 14; i++)                   /* 16 lines: the first screen scrolled by 2 */
    screen_center(&S, "C");
  ck_assert_int_eq(S.top, 2);
  screen_scroll(&S, -1);
  render();
  CK_SCREEN(G, "АВТОМАТ",
            "               B", "               C", "               C", "               C", "               C",
            "               C", "               C", "               C", "               C", "               C",
            "               C", "               C", "               C", "               C");
}
END_TEST

START_TEST(fixed_line_m27_m28)
{
  screen_center(&S, "ЗУБЦІ");
  screen_prompt(&S, "ЗУБ", 0);
  S.fixed = S.last;                              /* M27 */
  screen_field_type(&S, 1);
  screen_field_close(&S);
  S.at_fixed = 1;                                /* M28 */
  screen_prompt(&S, "ЗУБ", 0);                      /* on the same line again */
  render();
  CK_SCREEN(G, "АВТОМАТ", "             ЗУБЦІ", "ЗУБ......................_");
  screen_field_type(&S, 2);
  screen_field_close(&S);
  ck_assert_int_eq(S.at_fixed, 0);
  S.fixed = -1;                                  /* M29 */
  screen_prompt(&S, "КІНЕЦЬ", 0);                   /* a new line */
  render();
  CK_SCREEN(G, "АВТОМАТ", "             ЗУБЦІ", "ЗУБ......................      2", "КІНЕЦЬ..................._");
}
END_TEST

/* ---- whole programs through a session ------------------------------- */

static struct tprog t;
static struct session *s;

static void sess_setup(void)
{
  memset(&t, 0, sizeof t);
  prog_init(&t.p);
  diag_init(&t.d, "t.kp");
  s = calloc(1, sizeof *s);
  memset(G, 0, sizeof G);
}

static void sess_teardown(void)
{
  tp_free(&t);
  free(s);
}

static void load(const char *src, int en)
{
  tp_free(&t);
  tp_compile(&t, src);
  ck_assert_msg(t.rc == 0, "does not compile:\n%s", tp_diags(&t.d));
  sess_init(s, &t.p);
  s->en = en;          /* as s42's --lang does: the session and its screen */
  s->scr.en = en;
}

static enum sess_ev go(void)
{
  enum sess_ev ev;
  while ((ev = sess_run(s)) == SE_START)
    ;
  return ev;
}

static void shot(void)
{
  sess_screen(s, G);
}

static const char drill[] =
  "№01 G33 /СВЕРДЛО/ ^\n"
  "№02 G27 /ДІАМЕТР, МКМ/ ^\n"
  "№03 G28 /30000:40000/ R0 ^\n"
  "№04 G27 /ДОВЖИНА, МКМ/ ^\n"
  "№05 G28 /10000:120000/ R1 ^\n"
  "№06 G27 /КУТ ЗАГОСТРЕННЯ, ГРАД/ ^\n"
  "№07 G28 /90:130/ R40 ^\n"
  "№08 G27 /КРОК ГВИНТ. КАНАВКИ, МКМ/ ^\n"
  "№09 G28 /100:999999/ R3 ^\n"
  "№10 G33 /КІНЕЦЬ ВВОДУ/ ^\n"
  "№11 G34 ^\n"
  "№12 M02 ^\n";

START_TEST(sess_drill_dialog)
{
  load(drill, 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(s->wait, W_ANSWER);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N2", "            СВЕРДЛО", "ДІАМЕТР, МКМ............._");
  ck_assert_int_eq(sess_answer(s, 100), 0);    /* below 30000 */
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(s->wait, W_ANSWER);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N3", "            СВЕРДЛО", "ДІАМЕТР, МКМ............._",
            [15] = "знач. менше допустимого");
  ck_assert_double_eq(s->vm.reg[0], 0);
  ck_assert_int_eq(sess_answer(s, 35000), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N4", "            СВЕРДЛО", "ДІАМЕТР, МКМ.............  35000",
            "ДОВЖИНА, МКМ............._");
  ck_assert_int_eq(sess_answer(s, 95000), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 140), 0);    /* above 130 */
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N7", "            СВЕРДЛО", "ДІАМЕТР, МКМ.............  35000",
            "ДОВЖИНА, МКМ.............  95000", "КУТ ЗАГОСТРЕННЯ, ГРАД...._",
            [15] = "знач. більше допустимого");
  ck_assert_int_eq(sess_answer(s, 118), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 33350), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(s->wait, W_PUSK);            /* G34 */
  shot();
  CK_SCREEN(G, "АВТОМАТ                      N11", "            СВЕРДЛО", "ДІАМЕТР, МКМ.............  35000",
            "ДОВЖИНА, МКМ.............  95000", "КУТ ЗАГОСТРЕННЯ, ГРАД....    118",
            "КРОК ГВИНТ. КАНАВКИ, МКМ.  33350", "          КІНЕЦЬ ВВОДУ",
            [15] = "Введення завершено");
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "АВТОМАТ                      N12", "            СВЕРДЛО", "ДІАМЕТР, МКМ.............  35000",
            "ДОВЖИНА, МКМ.............  95000", "КУТ ЗАГОСТРЕННЯ, ГРАД....    118",
            "КРОК ГВИНТ. КАНАВКИ, МКМ.  33350", "          КІНЕЦЬ ВВОДУ");
  ck_assert_double_eq(s->vm.reg[0], 35000);
  ck_assert_double_eq(s->vm.reg[1], 95000);
  ck_assert_double_eq(s->vm.reg[40], 118);
  ck_assert_double_eq(s->vm.reg[3], 33350);
}
END_TEST

START_TEST(sess_drill_dialog_english)
{
  load(drill, 1);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 100), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "AUTO                          N3", "            СВЕРДЛО", "ДІАМЕТР, МКМ............._",
            [15] = "value below the minimum");
  ck_assert_int_eq(sess_answer(s, 35000), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 200000), 0);  /* above 120000 */
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "AUTO                          N5", "            СВЕРДЛО", "ДІАМЕТР, МКМ.............  35000",
            "ДОВЖИНА, МКМ............._",
            [15] = "value above the maximum");
  ck_assert_int_eq(sess_answer(s, 95000), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 120), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 3335), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "AUTO                         N11", "            СВЕРДЛО", "ДІАМЕТР, МКМ.............  35000",
            "ДОВЖИНА, МКМ.............  95000", "КУТ ЗАГОСТРЕННЯ, ГРАД....    120",
            "КРОК ГВИНТ. КАНАВКИ, МКМ.   3335", "          КІНЕЦЬ ВВОДУ",
            [15] = "Input complete");
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
}
END_TEST

START_TEST(sess_refusal_negative_and_bounds)
{
  /* G28 checks |value|: -35000 is inside 30000:40000, -50 is below it;
   * the bounds may be expressions */
  load("№1 R10+30000 ^\n"
       "№2 G27 /КОРЕКЦІЯ, МКМ/: ^\n"
       "№3 G28 /R10:R10+10000/ R0 ^\n"
       "№4 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, -50), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N3", "КОРЕКЦІЯ, МКМ............_",
            [15] = "знач. менше допустимого");
  ck_assert_int_eq(sess_answer(s, -40001), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N3", "КОРЕКЦІЯ, МКМ............_",
            [15] = "знач. більше допустимого");
  ck_assert_int_eq(sess_answer(s, -35000), 0);
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N4", "КОРЕКЦІЯ, МКМ............ -35000");
  ck_assert_double_eq(s->vm.reg[0], -35000);
}
END_TEST

START_TEST(sess_without_g34_goes_on)
{
  /* no G34: the ПС that ends the last entry starts the cycle */
  load("№1 G33 /ФРЕЗА/ ^\n"
       "№2 G27 /ЗУБЦІВ/: ^\n"
       "№3 G28 /2:12/ R1 ^\n"
       "№4 G01 X+1000 F1000 ^\n"
       "№5 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 4), 0);
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(s->m.pos[0], 1000);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N5", "             ФРЕЗА", "ЗУБЦІВ...................      4");
}
END_TEST

START_TEST(sess_g27_wrapped_program)
{
  load("№1 G27 /КРОК ГВИНТОВОЇ КАНАВКИ СВЕРДЛА, МКМ/- ^\n"
       "№2 G28 /100:999999/ R3 ^\n"
       "№3 G27 /AAAAAAAAAA BBBBBBBBBB CCCCCCCCC DDDDDDDDDD EEEEEEEEEEEEE/- ^\n"
       "№4 G28 /0:9999999/ R4 ^\n"
       "№5 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N1", "КРОК ГВИНТОВОЇ КАНАВКИ СВЕРДЛА,",
            "МКМ......................_");
  ck_assert_int_eq(sess_answer(s, 333500), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 9999999), 0);
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N5", "КРОК ГВИНТОВОЇ КАНАВКИ СВЕРДЛА,",
            "МКМ...................... 333500", "AAAAAAAAAA BBBBBBBBBB CCCCCCCCC",
            "DDDDDDDDDD EEEEEEEEEEEEE.9999999");
  ck_assert_double_eq(s->vm.reg[4], 9999999);
}
END_TEST

START_TEST(sess_g20_service_line)
{
  load("№1 G33 /ЗАТОЧУВАННЯ/ ^\n"
       "№17 G20 ^\n"
       "№18 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();                                        /* the wait changes only the service line */
  CK_SCREEN(G, "РУЧНИЙ                       N17", "          ЗАТОЧУВАННЯ");
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "АВТОМАТ                      N18", "          ЗАТОЧУВАННЯ");
}
END_TEST

START_TEST(sess_g20_service_line_english)
{
  load("№1 G20 M18 /WHEEL TO THE FLUTE, PS/ ^\n"
       "№2 M21 M02 ^\n", 1);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "MANUAL                        N1", [15] = "WHEEL TO THE FLUTE, PS");
  ck_assert_int_eq(sess_key_ps(s), 0);
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "AUTO                          N2");
}
END_TEST

START_TEST(sess_g29_live)
{
  load("№1 R100+1000 R101+6 R102+10 ^\n"
       "№2 G29 /ЗАТОЧУВАННЯ МІТЧИКА/ПРИПУСК ((R100/КІЛЬКІСТЬ ЗУБЦІВ ((R101/ПОДАЧА ((R102// ^\n"
       "№3 G20 ^\n"
       "№4 R100+R100-300 R101+R101-1 ^\n"
       "№5 G20 ^\n"
       "№6 R102-9999999 ^\n"    /* the widest value a parameter can hold */
       "№7 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "РУЧНИЙ                        N3",
            "ЗАТОЧУВАННЯ МІТЧИКА",
            "ПРИПУСК                     1000",
            "КІЛЬКІСТЬ ЗУБЦІВ               6",
            "ПОДАЧА                        10");
  s->vm.reg[102] = 25;                           /* change the register, render again */
  shot();
  CK_SCREEN(G, "РУЧНИЙ                        N3",
            "ЗАТОЧУВАННЯ МІТЧИКА",
            "ПРИПУСК                     1000",
            "КІЛЬКІСТЬ ЗУБЦІВ               6",
            "ПОДАЧА                        25");
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "РУЧНИЙ                        N5",
            "ЗАТОЧУВАННЯ МІТЧИКА",
            "ПРИПУСК                      700",
            "КІЛЬКІСТЬ ЗУБЦІВ               5",
            "ПОДАЧА                        25");
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N7",
            "ЗАТОЧУВАННЯ МІТЧИКА",
            "ПРИПУСК                      700",
            "КІЛЬКІСТЬ ЗУБЦІВ               5",
            "ПОДАЧА                  -9999999");
  s->vm.reg[102] = -10000000;                    /* one that does not fit 8 characters */
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N7",
            "ЗАТОЧУВАННЯ МІТЧИКА",
            "ПРИПУСК                      700",
            "КІЛЬКІСТЬ ЗУБЦІВ               5",
            "ПОДАЧА                  ********");
}
END_TEST

START_TEST(sess_g29_after_m15_extends)
{
  load("№1 R100+1 R101+2 R102+3 ^\n"
       "№2 G29 /ПЕРШИЙ ((R100// ^\n"
       "№3 G29 /ДРУГИЙ ((R101// ^\n"        /* no M15 yet: replaces */
       "№4 M15 ^\n"
       "№5 G29 /ТРЕТІЙ ((R102/ЛИШЕ ТЕКСТ// ^\n"   /* after M15: adds */
       "№6 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N6",
            "ДРУГИЙ                         2",
            "ТРЕТІЙ                         3",
            "ЛИШЕ ТЕКСТ");
}
END_TEST

START_TEST(sess_g29_then_dialog)
{
  /* G29 shows P3 from its block on; the next G27/G33 brings the dialog back */
  load("№1 G33 /СВЕРДЛО/ ^\n"
       "№2 G27 /ДІАМЕТР, МКМ/: ^\n"
       "№3 G28 /1:40000/ R100 ^\n"
       "№4 G29 /ДІАМЕТР ((R100// ^\n"
       "№5 G20 ^\n"
       "№6 G33 /ДАЛІ/ ^\n"
       "№7 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 35000), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "РУЧНИЙ                        N5", "ДІАМЕТР                    35000");
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N7", "            СВЕРДЛО", "ДІАМЕТР, МКМ.............  35000",
            "              ДАЛІ");
}
END_TEST

START_TEST(sess_m18_value_and_m21)
{
  load("№1 R5+4 ^\n"
       "№2 G20 M18 /ЗАЛИШИЛОСЬ ЗУБІВ ((R5/ ^\n"
       "№3 R5+R5-1 ^\n"
       "№4 G20 ^\n"
       "№5 M21 ^\n"
       "№6 G20 ^\n"
       "№7 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(s->wait, W_PS);
  shot();
  CK_SCREEN(G, "РУЧНИЙ                        N2", [15] = "ЗАЛИШИЛОСЬ ЗУБІВ        4");
  ck_assert_int_eq(sess_key_ps(s), 0);
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_WAIT);              /* the directive stays, its value follows R5 */
  shot();
  CK_SCREEN(G, "РУЧНИЙ                        N4", [15] = "ЗАЛИШИЛОСЬ ЗУБІВ        3");
  s->vm.reg[5] = -100000000;
  shot();
  CK_SCREEN(G, "РУЧНИЙ                        N4", [15] = "ЗАЛИШИЛОСЬ ЗУБІВ ********");
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_WAIT);              /* M21 erased it */
  shot();
  CK_SCREEN(G, "РУЧНИЙ                        N6");
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
}
END_TEST

START_TEST(sess_m27_m28_m29_loop)
{
  load("№1 R1+0 ^\n"
       "№2 G33 /ВИСОТА ЗУБІВ/ ^\n"
       "№3 G27 /ЗУБ/: M27 ^\n"
       "№4 G28 /0:100/ R2 ^\n"
       "№5 R1+R1+1 M28 P(R1:M:3)3 ^\n"
       "№6 M29 ^\n"
       "№7 G27 /ПІСЛЯ M29/: ^\n"
       "№8 G28 /0:100/ R3 ^\n"
       "№9 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 7), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();                                        /* the second time: the same line, empty again */
  CK_SCREEN(G, "АВТОМАТ                       N3", "          ВИСОТА ЗУБІВ", "ЗУБ......................_");
  ck_assert_int_eq(sess_answer(s, 8), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 101), 0);      /* refused on the fixed line */
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N4", "          ВИСОТА ЗУБІВ", "ЗУБ......................_",
            [15] = "знач. більше допустимого");
  ck_assert_int_eq(sess_answer(s, 9), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 50), 0);
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N9", "          ВИСОТА ЗУБІВ", "ЗУБ......................      9",
            "ПІСЛЯ M29................     50");
  ck_assert_double_eq(s->vm.reg[2], 9);
  ck_assert_double_eq(s->vm.reg[3], 50);
}
END_TEST

START_TEST(sess_buffer_full_message)
{
  /* 60 G33 lines in a loop: past four screens, "Обмеження введення" */
  load("№1 R1+0 ^\n"
       "№2 G33 /РЯДОК/ R1+R1+1 ^\n"
       "№3 P(R1:M:60)2 ^\n"
       "№4 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_END);
  ck_assert_int_eq(s->scr.nbuf, SCR_BUF);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N4",
            "             РЯДОК", "             РЯДОК", "             РЯДОК", "             РЯДОК",
            "             РЯДОК", "             РЯДОК", "             РЯДОК", "             РЯДОК",
            "             РЯДОК", "             РЯДОК", "             РЯДОК", "             РЯДОК",
            "             РЯДОК", "             РЯДОК",
            "Обмеження введення");
}
END_TEST

START_TEST(sess_buffer_full_english)
{
  load("№1 R1+0 ^\n"
       "№2 G33 /LINE/ R1+R1+1 ^\n"
       "№3 P(R1:M:57)2 ^\n"
       "№4 M02 ^\n", 1);
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "AUTO                          N4",
            "              LINE", "              LINE", "              LINE", "              LINE",
            "              LINE", "              LINE", "              LINE", "              LINE",
            "              LINE", "              LINE", "              LINE", "              LINE",
            "              LINE", "              LINE",
            "Input buffer full");
}
END_TEST

START_TEST(sess_buffer_scroll_in_dialog)
{
  /* 14 G33 lines and a G27: the screen scrolls to keep the field in view;
   * ↑ shows the first line again */
  load("№1 R1+0 ^\n"
       "№2 G33 /ЗАГОЛОВОК/ R1+R1+1 ^\n"
       "№3 P(R1:M:14)2 ^\n"
       "№4 G27 /ОСТАННІЙ/: ^\n"
       "№5 G28 /0:10/ R2 ^\n"
       "№6 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_WAIT);
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N4",
            "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК",
            "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК",
            "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК",
            "           ЗАГОЛОВОК", "ОСТАННІЙ................._");
  screen_scroll(&s->scr, -1);                       /* ↑ */
  shot();
  CK_SCREEN(G, "АВТОМАТ                       N4",
            "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК",
            "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК",
            "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК", "           ЗАГОЛОВОК",
            "           ЗАГОЛОВОК", "           ЗАГОЛОВОК");
  ck_assert_int_eq(sess_answer(s, 5), 0);
  ck_assert_int_eq(go(), SE_END);
}
END_TEST

/* SCREEN_BUGS.txt #4: a message hides an M18 directive past the next key:
 * ПС at a G20 M18 wait leaves "Обмеження введення" on line 16. */
START_TEST(sess_message_goes_on_ps)
{
  load("№1 R1+0 ^\n"
       "№2 G33 /РЯДОК/ R1+R1+1 ^\n"
       "№3 P(R1:M:57)2 ^\n"
       "№4 G20 M18 /КРУГ ДО ЗАГОТОВКИ, ПС/ ^\n"
       "№5 M02 ^\n", 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(s->wait, W_PS);
  shot();                                        /* the message pushes the directive aside ... */
  CK_SCREEN(G, "РУЧНИЙ                        N4",
            "             РЯДОК", "             РЯДОК", "             РЯДОК", "             РЯДОК",
            "             РЯДОК", "             РЯДОК", "             РЯДОК", "             РЯДОК",
            "             РЯДОК", "             РЯДОК", "             РЯДОК", "             РЯДОК",
            "             РЯДОК", "             РЯДОК",
            "Обмеження введення");
  ck_assert_int_eq(sess_key_ps(s), 0);
  shot();                                        /* ... until the next key */
  CK_SCREEN(G, "РУЧНИЙ                        N4",
            "             РЯДОК", "             РЯДОК", "             РЯДОК", "             РЯДОК",
            "             РЯДОК", "             РЯДОК", "             РЯДОК", "             РЯДОК",
            "             РЯДОК", "             РЯДОК", "             РЯДОК", "             РЯДОК",
            "             РЯДОК", "             РЯДОК",
            "КРУГ ДО ЗАГОТОВКИ, ПС");
  ck_assert_int_eq(sess_key_pusk(s), 0);
  ck_assert_int_eq(go(), SE_END);
}
END_TEST

START_TEST(sess_g34_english_pusk_clears)
{
  load("№1 G27 /D/: ^\n"
       "№2 G28 /0:9/ R1 ^\n"
       "№3 G34 ^\n"
       "№4 M02 ^\n", 1);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(sess_answer(s, 3), 0);
  ck_assert_int_eq(go(), SE_WAIT);
  ck_assert_int_eq(s->wait, W_PUSK);
  ck_assert_int_eq(sess_answer(s, 1), -1);      /* no field after G34 */
  shot();
  CK_SCREEN(G, "AUTO                          N3", "D........................      3",
            [15] = "Input complete");
  ck_assert_int_eq(sess_key_pusk(s), 0);        /* Пуск takes the message away */
  ck_assert_int_eq(go(), SE_END);
  shot();
  CK_SCREEN(G, "AUTO                          N4", "D........................      3");
}
END_TEST

/* ---- P5: the results of a tooth-step search ------------------------ */

static const double steps12[12] = {30000, 29995, 30010, 29990, 30005, 30000,
                                   29998, 30002, 30001, 29999, 30004, 29996};

START_TEST(p5_with_lead_and_paging)
{
  S.block = 10;
  ck_assert_int_eq(screen_p5_set(&S, 12, steps12, 1, 249998.6, 37012.4, 1), 0);
  screen_set_directive(&S, "відвести упорку");
  render();
  CK_SCREEN(G, "РЕЗУЛЬТАТИ                   N10",
            "ЗУБІВ                         12",
            "КРОК ГВИНТА TK, мкм       249999",
            "КУТ ГВИНТА UG, 0.001°      37012",
            "ГВИНТ                     ПРАВИЙ",
            "",
            "КРОКИ, 0.001°             1-8/12",
            "  1                        30000",
            "  2                        29995",
            "  3                        30010",
            "  4                        29990",
            "  5                        30005",
            "  6                        30000",
            "  7                        29998",
            "  8                        30002",
            "відвести упорку");
  ck_assert_int_eq(screen_p5_page(&S, -1), -1);   /* no page before the first */
  ck_assert_int_eq(screen_p5_page(&S, 1), 0);
  render();
  CK_SCREEN(G, "РЕЗУЛЬТАТИ                   N10",
            "ЗУБІВ                         12",
            "КРОК ГВИНТА TK, мкм       249999",
            "КУТ ГВИНТА UG, 0.001°      37012",
            "ГВИНТ                     ПРАВИЙ",
            "",
            "КРОКИ, 0.001°            9-12/12",
            "  9                        30001",
            " 10                        29999",
            " 11                        30004",
            " 12                        29996",
            NULL, NULL, NULL, NULL,
            "відвести упорку");
  ck_assert_int_eq(screen_p5_page(&S, 1), -1);    /* none after the last */
  ck_assert_int_eq(screen_p5_page(&S, -1), 0);
  ck_assert_int_eq(S.res.page, 0);
}
END_TEST

START_TEST(p5_without_lead_english)
{
  S.en = 1;
  const double st[4] = {90002, 79997, 110003, 79998};
  ck_assert_int_eq(screen_p5_set(&S, 4, st, 0, 0, 0, 0), 0);
  render();
  CK_SCREEN(G, "RESULTS",
            "TEETH                          4",
            "LEAD TK, µm             not meas",
            "HELIX ANGLE UG, 0.001°  not meas",
            "",
            "",
            "STEPS, 0.001°              1-4/4",
            "  1                        90002",
            "  2                        79997",
            "  3                       110003",
            "  4                        79998");
  ck_assert_int_eq(screen_p5_page(&S, 1), -1);
}
END_TEST

START_TEST(p5_left_hand_and_refusals)
{
  const double st[2] = {180000, 180000};
  ck_assert_int_eq(screen_p5_set(&S, 0, st, 1, 0, 0, 0), -1);
  ck_assert_int_eq(screen_p5_set(&S, 151, st, 1, 0, 0, 0), -1);
  ck_assert_int_eq(screen_p5_set(&S, 2, NULL, 1, 0, 0, 0), -1);
  ck_assert_int_eq(screen_p5_set(&S, 2, st, 1, NAN, 0, 0), -1);
  ck_assert_int_eq(S.p5, 0);
  ck_assert_int_eq(screen_p5_page(&S, 1), -1);
  ck_assert_int_eq(screen_p5_set(&S, 2, st, 1, 120000, 27000, -1), 0);
  render();
  ck_assert_int_eq(G[4][27], 0x041B);   /* ЛІВИЙ in columns 28..32 */
  /* a dialog line or a G29 display takes the work area back */
  screen_center(&S, "КІНЕЦЬ");
  ck_assert_int_eq(S.p5, 0);
  ck_assert_int_eq(screen_p5_set(&S, 2, st, 1, 120000, 27000, -1), 0);
  screen_p3_add(&S, "ДАНІ");
  ck_assert_int_eq(S.p5, 0);
  ck_assert_int_eq(S.p3, 1);
}
END_TEST

Suite *suite_screen(void)
{
  Suite *su = suite_create("screen");
  TCase *tc = tcase_create("model");
  tcase_add_checked_fixture(tc, screen_setup, NULL);
  tcase_add_test(tc, empty_screen);
  tcase_add_test(tc, service_line_modes_and_block);
  tcase_add_test(tc, service_line_english);
  tcase_add_test(tc, g33_centred_even_odd_full);
  tcase_add_test(tc, g27_colon_format);
  tcase_add_test(tc, g27_wrapped_format);
  tcase_add_test(tc, g27_wrapped_56_characters);
  tcase_add_test(tc, field_digits_move_the_cursor);
  tcase_add_test(tc, field_backspace);
  tcase_add_test(tc, field_arrows);
  tcase_add_test(tc, field_wraps_after_seventh_digit);
  tcase_add_test(tc, field_leading_zeros_dropped);
  tcase_add_test(tc, field_negative);
  tcase_add_test(tc, field_negative_seven_digits);
  tcase_add_test(tc, field_type_answer);
  tcase_add_test(tc, g28_refusal_and_reentry);
  tcase_add_test(tc, messages_both_languages);
  tcase_add_test(tc, message_pushes_directive_aside);
  tcase_add_test(tc, directive_with_live_value);
  tcase_add_test(tc, directive_value_mid_text);
  tcase_add_test(tc, message_goes_on_next_key);
  tcase_add_test(tc, directive_cyrillic_r);
  tcase_add_test(tc, p3_cyrillic_r);
  tcase_add_test(tc, value8_formats);
  tcase_add_test(tc, p3_live_values);
  tcase_add_test(tc, p3_full_lines);
  tcase_add_test(tc, p3_and_dialog_switch);
  tcase_add_test(tc, buffer_of_four_screens);
  tcase_add_test(tc, buffer_full_english);
  tcase_add_test(tc, scroll_short_buffer);
  tcase_add_test(tc, fixed_line_m27_m28);
  tcase_add_test(tc, p5_with_lead_and_paging);
  tcase_add_test(tc, p5_without_lead_english);
  tcase_add_test(tc, p5_left_hand_and_refusals);
  suite_add_tcase(su, tc);

  TCase *ts = tcase_create("session");
  tcase_add_checked_fixture(ts, sess_setup, sess_teardown);
  tcase_add_test(ts, sess_drill_dialog);
  tcase_add_test(ts, sess_drill_dialog_english);
  tcase_add_test(ts, sess_refusal_negative_and_bounds);
  tcase_add_test(ts, sess_without_g34_goes_on);
  tcase_add_test(ts, sess_g27_wrapped_program);
  tcase_add_test(ts, sess_g20_service_line);
  tcase_add_test(ts, sess_g20_service_line_english);
  tcase_add_test(ts, sess_g29_live);
  tcase_add_test(ts, sess_g29_after_m15_extends);
  tcase_add_test(ts, sess_g29_then_dialog);
  tcase_add_test(ts, sess_m18_value_and_m21);
  tcase_add_test(ts, sess_m27_m28_m29_loop);
  tcase_add_test(ts, sess_buffer_full_message);
  tcase_add_test(ts, sess_buffer_full_english);
  tcase_add_test(ts, sess_buffer_scroll_in_dialog);
  tcase_add_test(ts, sess_g34_english_pusk_clears);
  tcase_add_test(ts, sess_message_goes_on_ps);
  suite_add_tcase(su, ts);
  return su;
}
