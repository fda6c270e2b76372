/* The lexer (src/dialect/2c42/lex.h): what lex_peek sees, where it is, and what
 * it notes. */
#include "suites.h"
#include "lex.h"
#include "utf8.h"
#include <string.h>

static struct diag_list d;
static struct lex l;

static void setup(void) { diag_init(&d, "t.kp"); }
static void teardown(void) { diag_free(&d); }

static void start(const char *s) { lex_init(&l, s, strlen(s), &d); }

/* Peek and consume. */
static int32_t next(void)
{
  int32_t c = lex_peek(&l);
  lex_adv(&l);
  return c;
}

START_TEST(spaces_and_tabs_skipped)
{
  start("  X \t+ 1\v 0");
  ck_assert_int_eq(next(), 'X');
  ck_assert_int_eq(next(), '+');
  ck_assert_int_eq(next(), '1');
  ck_assert_int_eq(next(), '0');
  ck_assert_int_eq(lex_peek(&l), LX_EOF);
}
END_TEST

START_TEST(comment_runs_to_end_of_line)
{
  start("X ; Y Z ^ ПС\nA");
  ck_assert_int_eq(next(), 'X');
  ck_assert_int_eq(next(), LX_EOB);     /* the newline, not the ^ in the comment */
  ck_assert_uint_eq(l.line, 2);
  ck_assert_int_eq(next(), 'A');
  ck_assert_int_eq(lex_peek(&l), LX_EOF);
}
END_TEST

/* CR alone is a line end (old Mac OS files), noted once; CR LF is one */
START_TEST(cr_only_line_ends)
{
  start("X ; a comment\rY\r\rZ\r\nA");
  ck_assert_int_eq(next(), 'X');
  ck_assert_int_eq(next(), LX_EOB);     /* the comment ends at the CR */
  ck_assert_uint_eq(l.line, 2);
  ck_assert_int_eq(next(), 'Y');
  ck_assert_int_eq(next(), LX_EOB);
  ck_assert_int_eq(next(), LX_EOB);
  ck_assert_uint_eq(l.line, 4);
  ck_assert_int_eq(next(), 'Z');
  ck_assert_int_eq(next(), LX_EOB);     /* CR LF: one line end */
  ck_assert_uint_eq(l.line, 5);
  ck_assert_int_eq(lex_peek(&l), 'A');
  ck_assert_uint_eq(lex_col(&l), 1);
  ck_assert_int_eq(next(), 'A');
  ck_assert_int_eq(lex_peek(&l), LX_EOF);
  ck_assert_uint_eq(tp_count(&d, DIAG_NOTE), 1);
  ck_assert_ptr_nonnull(strstr(d.v[0].msg, "CR alone"));
}
END_TEST

START_TEST(cr_lf_file_has_no_cr_note)
{
  start("X\r\nY\r\n");
  while (next() != LX_EOF)
    ;
  ck_assert_uint_eq(d.n, 0);
}
END_TEST

START_TEST(caret_comment_manual_style)
{
  start("N1 G01 ^;\nN2");
  ck_assert_int_eq(next(), 'N');
  ck_assert_int_eq(next(), '1');
  ck_assert_int_eq(next(), 'G');
  ck_assert_int_eq(next(), '0');
  ck_assert_int_eq(next(), '1');
  ck_assert_int_eq(next(), LX_EOB);     /* ^ */
  ck_assert_int_eq(next(), LX_EOB);     /* the newline after the comment */
  ck_assert_int_eq(next(), 'N');
}
END_TEST

START_TEST(newline_and_caret_are_eob)
{
  start("X\nY^Z");
  ck_assert_int_eq(next(), 'X');
  ck_assert_int_eq(next(), LX_EOB);
  ck_assert_int_eq(next(), 'Y');
  ck_assert_int_eq(next(), LX_EOB);
  ck_assert_int_eq(next(), 'Z');
  ck_assert_int_eq(next(), LX_EOF);
}
END_TEST

START_TEST(ps_is_one_eob)
{
  start("X+1ПСY");
  ck_assert_int_eq(next(), 'X');
  ck_assert_int_eq(next(), '+');
  ck_assert_int_eq(next(), '1');
  ck_assert_int_eq(lex_peek(&l), LX_EOB);
  ck_assert_uint_eq(lex_col(&l), 4);
  lex_adv(&l);
  /* both letters consumed: Y is the 6th character */
  ck_assert_int_eq(lex_peek(&l), 'Y');
  ck_assert_uint_eq(lex_col(&l), 6);
  ck_assert_uint_eq(lex_line(&l), 1);
  /* ПС is not a look-alike letter: no note */
  ck_assert_uint_eq(d.n, 0);
}
END_TEST

START_TEST(ps_with_latin_c)
{
  start("\xD0\x9F" "CX");          /* П then Latin C */
  ck_assert_int_eq(next(), LX_EOB);
  ck_assert_int_eq(next(), 'X');
}
END_TEST

START_TEST(lone_pe_is_not_eob)
{
  start("\xD0\x9FX");              /* П alone is no 2С42 letter */
  ck_assert_int_eq(next(), 0x041F);
  ck_assert_int_eq(next(), 'X');
}
END_TEST

START_TEST(lookalikes_mapped)
{
  /* А В С Е Н К М О Р Т Х */
  static const char *const cyr[] = {"А", "В", "С", "Е", "Н", "К", "М", "О", "Р", "Т", "Х"};
  static const char lat[] = "ABCEHKMOPTX";
  for (int i = 0; i < 11; i++) {
    start(cyr[i]);
    ck_assert_msg(lex_peek(&l) == lat[i], "%s read as %d, expected %c", cyr[i], (int)lex_peek(&l), lat[i]);
  }
}
END_TEST

START_TEST(lookalike_note_once)
{
  start("Х+1 Р2\nМ2 Т11");
  int n = 0;
  while (lex_peek(&l) != LX_EOF) {
    lex_adv(&l);
    n++;
  }
  ck_assert_int_eq(n, 11);
  ck_assert_uint_eq(d.n, 1);
  ck_assert_int_eq(d.v[0].sev, DIAG_NOTE);
  ck_assert_int_eq(d.v[0].code, 0);
  ck_assert_uint_eq(d.v[0].line, 1);
  ck_assert_uint_eq(d.v[0].col, 1);
  ck_assert_uint_eq(d.nerr, 0);
}
END_TEST

START_TEST(lookalike_note_at_first_place)
{
  start("X+1\n  Y+Х");
  while (lex_peek(&l) != LX_EOF)
    lex_adv(&l);
  ck_assert_uint_eq(d.n, 1);
  ck_assert_uint_eq(d.v[0].line, 2);
  ck_assert_uint_eq(d.v[0].col, 5);
}
END_TEST

START_TEST(other_cyrillic_not_mapped)
{
  start("Д");
  ck_assert_int_eq(lex_peek(&l), 0x0414);
  ck_assert_uint_eq(d.n, 0);
}
END_TEST

START_TEST(columns_count_characters)
{
  start("ХХХ Y");                  /* three 2-byte letters */
  next(); next(); next();
  ck_assert_int_eq(lex_peek(&l), 'Y');
  ck_assert_uint_eq(lex_col(&l), 5);
  ck_assert_uint_eq(lex_pos(&l), 7);  /* but byte 7 */
}
END_TEST

START_TEST(lines_and_columns)
{
  start("AB\n  C");
  ck_assert_int_eq(lex_peek(&l), 'A');
  ck_assert_uint_eq(lex_line(&l), 1);
  ck_assert_uint_eq(lex_col(&l), 1);
  next(); next();
  ck_assert_int_eq(lex_peek(&l), LX_EOB);
  ck_assert_uint_eq(lex_line(&l), 1);
  ck_assert_uint_eq(lex_col(&l), 3);
  lex_adv(&l);
  ck_assert_int_eq(lex_peek(&l), 'C');
  ck_assert_uint_eq(lex_line(&l), 2);
  ck_assert_uint_eq(lex_col(&l), 3);
}
END_TEST

START_TEST(invalid_utf8_is_fffd)
{
  start("\xFFX");
  ck_assert_int_eq(next(), 0xFFFD);
  ck_assert_int_eq(lex_peek(&l), 'X');
  ck_assert_uint_eq(lex_col(&l), 2);
}
END_TEST

START_TEST(truncated_utf8_is_fffd)
{
  start("X\xD0");
  ck_assert_int_eq(next(), 'X');
  ck_assert_int_eq(next(), 0xFFFD);
  ck_assert_int_eq(lex_peek(&l), LX_EOF);
}
END_TEST

START_TEST(overlong_and_surrogate_are_fffd)
{
  start("\xC0\x80");
  ck_assert_int_eq(lex_peek(&l), 0xFFFD);
  start("\xED\xA0\x80");
  ck_assert_int_eq(lex_peek(&l), 0xFFFD);
  start("\xF4\x90\x80\x80");        /* above U+10FFFF */
  ck_assert_int_eq(lex_peek(&l), 0xFFFD);
  start("\xE2\x28\xA1");            /* bad continuation */
  ck_assert_int_eq(lex_peek(&l), 0xFFFD);
}
END_TEST

START_TEST(four_byte_character)
{
  start("\xF0\x9F\x98\x80X");       /* U+1F600 */
  ck_assert_int_eq(next(), 0x1F600);
  ck_assert_int_eq(lex_peek(&l), 'X');
  ck_assert_uint_eq(lex_col(&l), 2);
}
END_TEST

START_TEST(bom_skipped)
{
  start("\xEF\xBB\xBFN1");
  ck_assert_int_eq(lex_peek(&l), 'N');
  ck_assert_uint_eq(lex_col(&l), 1);
  ck_assert_uint_eq(lex_line(&l), 1);
}
END_TEST

START_TEST(bom_only_at_start)
{
  start("X\xEF\xBB\xBF");
  next();
  ck_assert_int_eq(lex_peek(&l), 0xFEFF);
}
END_TEST

START_TEST(empty_text_is_eof)
{
  start("");
  ck_assert_int_eq(lex_peek(&l), LX_EOF);
  start("   ; nothing");
  ck_assert_int_eq(lex_peek(&l), LX_EOF);
}
END_TEST

START_TEST(raw_keeps_spaces)
{
  start("/А Б/");
  ck_assert_int_eq(next(), '/');
  ck_assert_int_eq(lex_raw_peek(&l), 0x0410);   /* raw: not mapped */
  lex_raw_adv(&l);
  ck_assert_int_eq(lex_raw_peek(&l), ' ');
  lex_raw_adv(&l);
  ck_assert_int_eq(lex_raw_peek(&l), 0x0411);
  lex_raw_adv(&l);
  ck_assert_int_eq(lex_raw_peek(&l), '/');
  ck_assert_uint_eq(lex_raw_col(&l), 5);
  ck_assert_uint_eq(d.n, 0);          /* raw text gives no look-alike note */
}
END_TEST

START_TEST(raw_stops_at_newline_and_caret)
{
  start("a\nb");
  lex_raw_adv(&l);
  ck_assert_int_eq(lex_raw_peek(&l), LX_EOB);
  start("a^b");
  lex_raw_adv(&l);
  ck_assert_int_eq(lex_raw_peek(&l), LX_EOB);
  start("a\r\nb");
  lex_raw_adv(&l);
  ck_assert_int_eq(lex_raw_peek(&l), LX_EOB);
  start("a;b");                      /* a comment mark is text inside text */
  lex_raw_adv(&l);
  ck_assert_int_eq(lex_raw_peek(&l), ';');
  start("");
  ck_assert_int_eq(lex_raw_peek(&l), LX_EOF);
}
END_TEST

START_TEST(blen_counts_significant_characters)
{
  start("N 1 X+1 ; comment\nY ^\nZ");
  ck_assert_int_eq(lex_peek(&l), 'N');
  unsigned c0 = lex_col(&l);
  lex_block_begin(&l);
  while (lex_peek(&l) != LX_EOB)
    lex_adv(&l);
  ck_assert_uint_eq(lex_block_len(&l, c0), 5);   /* N1X+1: the end mark does not count */
  lex_adv(&l);
  ck_assert_int_eq(lex_peek(&l), 'Y');
  c0 = lex_col(&l);
  lex_block_begin(&l);
  ck_assert_int_eq(next(), 'Y');
  ck_assert_int_eq(lex_peek(&l), LX_EOB);   /* ^ */
  ck_assert_uint_eq(lex_block_len(&l, c0), 1);
  lex_adv(&l);
  ck_assert_int_eq(next(), LX_EOB);   /* and the newline */
  ck_assert_int_eq(lex_peek(&l), 'Z');
  ck_assert_uint_eq(lex_line(&l), 3);
}
END_TEST

/* Text counts as characters, its spaces too */
START_TEST(blen_counts_text)
{
  start("G27 /А Б/ X+1^");
  ck_assert_int_eq(lex_peek(&l), 'G');
  unsigned c0 = lex_col(&l);
  lex_block_begin(&l);
  for (int i = 0; i < 4; i++)
    next();                            /* G 2 7 / */
  while (lex_raw_peek(&l) != '/')
    lex_raw_adv(&l);
  lex_raw_adv(&l);
  while (lex_peek(&l) != LX_EOB)
    lex_adv(&l);
  ck_assert_uint_eq(lex_block_len(&l, c0), 11);   /* G27/А Б/X+1 */
  ck_assert_uint_eq(lex_col(&l), 14);
}
END_TEST

/* The window: a look two ahead and a walk ahead read what lex_peek will */
START_TEST(peek2_and_ahead)
{
  start("AB C;x\nD");
  ck_assert_int_eq(lex_peek(&l), 'A');
  ck_assert_int_eq(lex_peek2(&l), 'B');
  next();
  ck_assert_int_eq(lex_peek2(&l), 'C');
  struct lex_ahead a;
  lex_ahead_start(&l, &a);
  ck_assert_int_eq(lex_ahead_next(&l, &a), 'B');
  ck_assert_int_eq(lex_ahead_next(&l, &a), 'C');
  ck_assert_int_eq(lex_ahead_next(&l, &a), LX_EOB);   /* the comment skipped */
  ck_assert_int_eq(next(), 'B');
  ck_assert_int_eq(lex_peek(&l), 'C');
  ck_assert_int_eq(lex_col(&l), 4);
  ck_assert_int_eq(next(), 'C');
  ck_assert_int_eq(next(), LX_EOB);
  ck_assert_int_eq(next(), 'D');
}
END_TEST

/* A long run of characters, on the last line (read a chunk at a time,
 * LX_CHUNK bytes) and on one before it */
static void long_run_in(const char *end)
{
  enum { RUN = 12 * LX_CHUNK + 5 };
  static char buf[RUN + 16];
  size_t n = 0;
  for (int i = 0; i < RUN; i++)
    buf[n++] = (char)('0' + i % 10);
  buf[n++] = '/';
  buf[n++] = ';';
  strcpy(buf + n, end);
  start(buf);
  for (int i = 0; i < RUN; i++) {
    ck_assert_int_eq(lex_peek(&l), '0' + i % 10);
    ck_assert_uint_eq(lex_col(&l), (unsigned)i + 1);
    if (i % 7 == 0)
      ck_assert_int_eq(lex_peek2(&l), i + 1 < RUN ? '0' + (i + 1) % 10 : '/');
    lex_adv(&l);
  }
  ck_assert_int_eq(next(), '/');
  ck_assert_int_eq(lex_raw_peek(&l), ';');   /* text after the slash: not lexed */
}

START_TEST(long_run)
{
  long_run_in("");
  long_run_in("\n");
}
END_TEST

/* The last line's chunks end anywhere: in a space, a letter of two bytes,
 * ПС, a number; what is read is the same as on a line before it */
START_TEST(last_line_chunks)
{
  static const char *const piece[] = {"Х", " ", "1", "ПС", "+", " ; c", "\t", "№"};
  char text[4 * LX_CHUNK + 64], text2[sizeof text + 1];
  for (int pad = 0; pad < 8; pad++) {
    for (int k = 0; k < 8; k++) {
      size_t n = 0;
      for (int i = 0; i < LX_CHUNK - 4 + pad; i++)
        text[n++] = 'A';
      for (int j = 0; j < 6; j++) {
        const char *q = piece[(k + j) % 8];
        memcpy(text + n, q, strlen(q));
        n += strlen(q);
      }
      text[n] = 0;
      memcpy(text2, text, n);
      text2[n] = '\n';
      text2[n + 1] = 0;
      /* each of the two: the characters, their columns and lines */
      int32_t got[2][64 + LX_CHUNK];
      unsigned col[2][64 + LX_CHUNK], line[2][64 + LX_CHUNK];
      int m[2];
      for (int t = 0; t < 2; t++) {
        diag_free(&d);
        diag_init(&d, "t.kp");
        start(t ? text2 : text);
        int i = 0;
        for (;;) {
          int32_t c = lex_peek(&l);
          got[t][i] = c;
          col[t][i] = lex_col(&l);
          line[t][i] = lex_line(&l);
          i++;
          if (c == LX_EOF || (t && c == LX_EOB && line[t][i - 1] == 1 && lex_pos(&l) == n))
            break;
          lex_adv(&l);
        }
        m[t] = i;
      }
      ck_assert_int_eq(m[0], m[1]);
      for (int i = 0; i + 1 < m[0]; i++) {
        ck_assert_int_eq(got[0][i], got[1][i]);
        ck_assert_uint_eq(col[0][i], col[1][i]);
        ck_assert_uint_eq(line[0][i], line[1][i]);
      }
      ck_assert_uint_eq(col[0][m[0] - 1], col[1][m[1] - 1]);   /* the end of the file; the newline */
    }
  }
}
END_TEST

START_TEST(skip_block)
{
  start("X+1 Y+2\nZ");
  lex_skip_block(&l);
  ck_assert_int_eq(lex_peek(&l), LX_EOB);
  lex_adv(&l);
  ck_assert_int_eq(lex_peek(&l), 'Z');
}
END_TEST

START_TEST(utf8_encoding)
{
  char b[4];
  ck_assert_int_eq(utf8_encode('A', b), 1);
  ck_assert_int_eq(b[0], 'A');
  ck_assert_int_eq(utf8_encode(0x0416, b), 2);
  ck_assert_mem_eq(b, "Ж", 2);
  ck_assert_int_eq(utf8_encode(0x2116, b), 3);
  ck_assert_mem_eq(b, "№", 3);
  ck_assert_int_eq(utf8_encode(0x1F600, b), 4);
  ck_assert_mem_eq(b, "\xF0\x9F\x98\x80", 4);
}
END_TEST

START_TEST(numero_sign_passes_through)
{
  start("№12");
  ck_assert_int_eq(next(), 0x2116);
  ck_assert_int_eq(next(), '1');
  ck_assert_int_eq(lex_peek(&l), '2');
  ck_assert_uint_eq(lex_col(&l), 3);
}
END_TEST

Suite *suite_lex(void)
{
  Suite *s = suite_create("lex");
  TCase *tc = tcase_create("cursor");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, spaces_and_tabs_skipped);
  tcase_add_test(tc, comment_runs_to_end_of_line);
  tcase_add_test(tc, caret_comment_manual_style);
  tcase_add_test(tc, newline_and_caret_are_eob);
  tcase_add_test(tc, ps_is_one_eob);
  tcase_add_test(tc, ps_with_latin_c);
  tcase_add_test(tc, lone_pe_is_not_eob);
  tcase_add_test(tc, lookalikes_mapped);
  tcase_add_test(tc, lookalike_note_once);
  tcase_add_test(tc, lookalike_note_at_first_place);
  tcase_add_test(tc, other_cyrillic_not_mapped);
  tcase_add_test(tc, columns_count_characters);
  tcase_add_test(tc, lines_and_columns);
  tcase_add_test(tc, invalid_utf8_is_fffd);
  tcase_add_test(tc, truncated_utf8_is_fffd);
  tcase_add_test(tc, overlong_and_surrogate_are_fffd);
  tcase_add_test(tc, four_byte_character);
  tcase_add_test(tc, bom_skipped);
  tcase_add_test(tc, bom_only_at_start);
  tcase_add_test(tc, empty_text_is_eof);
  tcase_add_test(tc, raw_keeps_spaces);
  tcase_add_test(tc, raw_stops_at_newline_and_caret);
  tcase_add_test(tc, blen_counts_significant_characters);
  tcase_add_test(tc, peek2_and_ahead);
  tcase_add_test(tc, long_run);
  tcase_add_test(tc, last_line_chunks);
  tcase_add_test(tc, blen_counts_text);
  tcase_add_test(tc, skip_block);
  tcase_add_test(tc, cr_only_line_ends);
  tcase_add_test(tc, cr_lf_file_has_no_cr_note);
  tcase_add_test(tc, utf8_encoding);
  tcase_add_test(tc, numero_sign_passes_through);
  suite_add_tcase(s, tc);
  return s;
}
