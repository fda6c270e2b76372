/* The parser (src/dialect/2c42/parse.h): blocks, words, expressions, conditions, slash
 * arguments and syntax diagnostics with their positions. */
#include "suites.h"
#include "ast.h"
#include "errors.h"
#include "opcodes.h"
#include "parse.h"
#include "vmmath.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

static struct diag_list d;
static struct parser ps;
static struct block *b;
static int started;

static void setup(void)
{
  diag_init(&d, "t.kp");
  b = malloc(sizeof *b);
  started = 0;
}

static void teardown(void)
{
  if (started)
    parse_free(&ps);
  free(b);
  diag_free(&d);
}

/* Parse the first block of src; returns parse_block's result. */
static int first(const char *src)
{
  if (started)
    parse_free(&ps);
  parse_init(&ps, src, strlen(src), &d);
  started = 1;
  return parse_block(&ps, b);
}

static int again(void) { return parse_block(&ps, b); }

/* A program with the 2С42's limits and texts, for vm_math. */
static const struct program *kp(void)
{
  static struct program p;
  if (!p.msgs)
    comp_setup(&p);
  return &p;
}

/* The value of a constant expression tree (slots read as 0). */
static double eval(const struct expr *e)
{
  double a, r = 0;
  char msg[200];
  switch (e->kind) {
  case EX_NUM: return e->v;
  case EX_SLOT: return 0;
  case EX_NEG: return -eval(e->a);
  case EX_BIN:
    a = eval(e->a);
    ck_assert_int_eq(vm_math(kp(), e->op, a, eval(e->b), &r, msg, sizeof msg), 0);
    return r;
  case EX_FN:
    ck_assert_int_eq(vm_math(kp(), e->op, eval(e->a), 0, &r, msg, sizeof msg), 0);
    return r;
  default:
    ck_abort_msg("not a constant expression (kind %d)", e->kind);
    return 0;
  }
}

static const struct word *wordk(int kind, char letter)
{
  for (int i = 0; i < b->nw; i++)
    if (b->w[i].kind == kind && b->w[i].letter == letter)
      return &b->w[i];
  ck_abort_msg("no word %c of kind %d", letter, kind);
  return NULL;
}

/* The one diagnostic of the text, which must be an error. */
static const struct diag *only_error(void)
{
  ck_assert_msg(d.n == 1, "expected one diagnostic, got %zu:\n%s", d.n, tp_diags(&d));
  ck_assert_int_eq(d.v[0].sev, DIAG_ERROR);
  return &d.v[0];
}

#define ASSERT_DIAG(g, code_, line_, col_) do { \
    ck_assert_msg((g)->code == (code_), "code %s, expected %s: %s", err_code((g)->code), err_code(code_), (g)->msg); \
    ck_assert_uint_eq((g)->line, line_); \
    ck_assert_uint_eq((g)->col, col_); \
  } while (0)

/* ---- blocks ---- */

START_TEST(block_number_n)
{
  ck_assert_int_eq(first("N12 G01 X+1"), 1);
  ck_assert_int_eq(b->number, 12);
  ck_assert_uint_eq(b->line, 1);
  ck_assert_uint_eq(b->col, 1);
  ck_assert_int_eq(b->bad, 0);
  ck_assert_int_eq(b->nw, 2);
}
END_TEST

START_TEST(block_number_numero_and_space)
{
  first("№01 G04 X+20");
  ck_assert_int_eq(b->number, 1);
  first("№ 12 M2");
  ck_assert_int_eq(b->number, 12);
  first("N 0 07 M2");                 /* whitespace inside the number */
  ck_assert_int_eq(b->number, 7);
  ck_assert_uint_eq(d.n, 0);
}
END_TEST

START_TEST(block_without_number)
{
  first("  G01 X+1");
  ck_assert_int_eq(b->number, -1);
  ck_assert_uint_eq(b->col, 3);
}
END_TEST

START_TEST(block_number_range)
{
  first("N0 M2");
  ASSERT_DIAG(only_error(), S42_E_RANGE, 1, 1);
  ck_assert_int_eq(b->bad, 1);
}
END_TEST

START_TEST(block_number_four_digits)
{
  first("\nN1000 M2");
  ASSERT_DIAG(only_error(), S42_E_RANGE, 2, 2);   /* at the digits */
}
END_TEST

START_TEST(empty_blocks_skipped)
{
  ck_assert_int_eq(first("\n^ ; c\nПС\n  N3 M2 ^\n\n"), 1);
  ck_assert_int_eq(b->number, 3);
  ck_assert_uint_eq(b->line, 4);
  ck_assert_uint_eq(b->col, 3);
  ck_assert_int_eq(again(), 0);
}
END_TEST

START_TEST(blocks_in_sequence)
{
  first("N1 X+1 ^ N2 Y+2 ПС N3 Z+3\nN4 M2");
  ck_assert_int_eq(b->number, 1);
  ck_assert_int_eq(again(), 1);
  ck_assert_int_eq(b->number, 2);
  ck_assert_uint_eq(b->col, 10);
  ck_assert_int_eq(again(), 1);
  ck_assert_int_eq(b->number, 3);
  ck_assert_int_eq(again(), 1);
  ck_assert_int_eq(b->number, 4);
  ck_assert_uint_eq(b->line, 2);
  ck_assert_int_eq(again(), 0);
}
END_TEST

START_TEST(block_len_counts_significant)
{
  first("N1 G01 X + 10 000 ; comment");
  ck_assert_uint_eq(b->len, 12);     /* N1G01X+10000 */
  first("N1 M18 /A B/");
  ck_assert_uint_eq(b->len, 10);     /* N1M18/A B/: text keeps its space */
}
END_TEST

/* ---- G and M ---- */

START_TEST(g_m_numbers_leading_zeros)
{
  /* leading zeros are insignificant however many (language.md sec. 9) */
  first("N0001 G001 G0009 M0003 M005 G00019");
  ck_assert_int_eq(d.nerr, 0);
  ck_assert_int_eq(b->number, 1);
  ck_assert(b->g == ((1ull << 1) | (1ull << 9) | (1ull << 19)));
  ck_assert(b->m == ((1u << 3) | (1u << 5)));
  first("N1 G100");
  ck_assert_int_eq(d.nerr, 1);        /* three significant digits */
  first("№0000002 L0000002 P0003 R00001+1");
  ck_assert_int_eq(d.nerr, 1);        /* (counted since the start) none new */
  ck_assert_int_eq(b->number, 2);
  ck_assert_int_eq(b->bad, 0);
  first("N000");
  ck_assert_int_eq(d.nerr, 2);        /* 0 however written is no block number */
  first("N1 G01 G9 M03 M5");
  ck_assert_int_eq(b->bad, 0);
  ck_assert(b->g == ((1ull << 1) | (1ull << 9)));
  ck_assert(b->m == ((1u << 3) | (1u << 5)));
  ck_assert_uint_eq(b->gcol[1], 4);
  ck_assert_uint_eq(b->gcol[9], 8);
  ck_assert_uint_eq(b->mcol[3], 11);
  ck_assert_uint_eq(b->mcol[5], 15);
}
END_TEST

START_TEST(unknown_g_is_efunc)
{
  first("N5 G01 G05 X+1");
  const struct diag *g = only_error();
  ASSERT_DIAG(g, S42_E_FUNC, 1, 8);
  ck_assert_int_eq(g->number, 5);
  ck_assert_int_eq(b->bad, 1);
}
END_TEST

START_TEST(unknown_m_is_efunc)
{
  first("N1 M1\nN2 M30 M24");
  ASSERT_DIAG(only_error(), S42_E_FUNC, 1, 4);
  again();
  ck_assert_uint_eq(d.nerr, 3);
  ASSERT_DIAG(&d.v[1], S42_E_FUNC, 2, 4);
  ASSERT_DIAG(&d.v[2], S42_E_FUNC, 2, 8);
}
END_TEST

START_TEST(valid_function_tables)
{
  static const int gs[] = {1, 2, 3, 4, 7, 9, 10, 11, 12, 13, 17, 18, 19, 20, 27, 28, 29, 33, 34, 37};
  int n = 0;
  for (int g = 0; g < 100; g++)
    n += kp_valid_g(g);
  ck_assert_int_eq(n, 20);
  for (size_t i = 0; i < sizeof gs / sizeof gs[0]; i++)
    ck_assert_msg(kp_valid_g(gs[i]), "G%d", gs[i]);
  static const int ms[] = {2, 3, 4, 5, 10, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 25, 26, 27, 28, 29};
  n = 0;
  for (int m = 0; m < 100; m++)
    n += kp_valid_m(m);
  ck_assert_int_eq(n, 22);
  for (size_t i = 0; i < sizeof ms / sizeof ms[0]; i++)
    ck_assert_msg(kp_valid_m(ms[i]), "M%d", ms[i]);
  ck_assert_int_eq(kp_g_group(1), 1);
  ck_assert_int_eq(kp_g_group(37), 1);
  ck_assert_int_eq(kp_g_group(18), 2);
  ck_assert_int_eq(kp_g_group(9), 3);
  ck_assert_int_eq(kp_g_group(29), 4);
}
END_TEST

START_TEST(g_twice_is_egroup)
{
  first("N1 G01 G01");
  ASSERT_DIAG(only_error(), S42_E_GROUP, 1, 8);
}
END_TEST

START_TEST(m_twice_is_syntax)
{
  first("N1 M3 M03");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 7);
}
END_TEST

/* ---- words and expressions ---- */

START_TEST(axis_words_and_slots)
{
  first("G02 G17 X+1 Y-2 I+3 J-4 F100");
  ck_assert_int_eq(b->nw, 7);
  ck_assert_int_eq(wordk(WK_SLOT, 'X')->idx, SL_X);
  ck_assert_int_eq(wordk(WK_SLOT, 'J')->idx, SL_J);
  ck_assert_double_eq(eval(wordk(WK_SLOT, 'Y')->e), -2);
  ck_assert_double_eq(eval(wordk(WK_SLOT, 'J')->e), -4);
  const struct word *f = wordk(WK_REG, 'F');
  ck_assert_uint_eq(f->idx, REG_F);
  ck_assert_double_eq(eval(f->e), 100);
  ck_assert_uint_eq(wordk(WK_SLOT, 'I')->col, 17);
}
END_TEST

START_TEST(axis_needs_sign)
{
  first("N1 X100");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 5);
}
END_TEST

START_TEST(word_twice_is_syntax)
{
  first("N1 X+1 Y+2 X+3");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 12);
  first("N1 F1 F2");
  ck_assert_uint_eq(d.v[1].col, 7);
  first("N1 L5 L6");
  ck_assert_uint_eq(d.v[2].col, 7);
  first("N1 P5 P(R1:R:0)6");
  ck_assert_uint_eq(d.v[3].col, 7);
  ck_assert_uint_eq(d.nerr, 4);
}
END_TEST

START_TEST(assignments_may_repeat)
{
  first("R1+1 R1+2 T11+1 T11+2");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_int_eq(b->nw, 4);
}
END_TEST

START_TEST(whitespace_inside_numbers)
{
  first("X + 10 000");
  ck_assert_double_eq(eval(b->w[0].e), 10000);
}
END_TEST

START_TEST(sign_starts_first_term)
{
  /* X-R3+100 is (-R3)+100 */
  first("X-R3+100");
  const struct expr *e = b->w[0].e;
  ck_assert_int_eq(e->kind, EX_BIN);
  ck_assert_int_eq(e->op, OP_ADD);
  ck_assert_int_eq(e->a->kind, EX_NEG);
  ck_assert_int_eq(e->a->a->kind, EX_REG);
  ck_assert_uint_eq(e->a->a->idx, 3);
  ck_assert_double_eq(e->b->v, 100);
}
END_TEST

START_TEST(precedence_mul_over_add)
{
  first("R1+2+3%4-10/5");       /* 2 + 12 - 2 */
  ck_assert_double_eq(eval(b->w[0].e), 12);
  const struct expr *e = b->w[0].e;
  ck_assert_int_eq(e->op, OP_SUB);
  ck_assert_int_eq(e->b->op, OP_DIV);
  ck_assert_int_eq(e->a->op, OP_ADD);
  ck_assert_int_eq(e->a->b->op, OP_MUL);
}
END_TEST

START_TEST(left_assoc_div)
{
  first("R1+100/10/5");
  ck_assert_double_eq(eval(b->w[0].e), 2);
  first("R1+10-4-3");
  ck_assert_double_eq(eval(b->w[0].e), 3);
}
END_TEST

START_TEST(power_right_assoc)
{
  first("R1+2%%3%%2");
  ck_assert_double_eq(eval(b->w[0].e), 512);
  const struct expr *e = b->w[0].e;
  ck_assert_int_eq(e->op, OP_POW);
  ck_assert_int_eq(e->b->op, OP_POW);
}
END_TEST

START_TEST(power_binds_tighter_than_mul)
{
  first("R1+3%2%%2");
  ck_assert_double_eq(eval(b->w[0].e), 12);
  first("R1+(1+2)%%2");
  ck_assert_double_eq(eval(b->w[0].e), 9);
}
END_TEST

START_TEST(sign_rules_with_power)
{
  first("R8-2%%2");
  ck_assert_double_eq(eval(b->w[0].e), -4);
  first("R8+5%-2%%2");
  ck_assert_double_eq(eval(b->w[0].e), -20);
  first("R8+(-8)");
  ck_assert_double_eq(eval(b->w[0].e), -8);
  first("R8-3-2");
  ck_assert_double_eq(eval(b->w[0].e), -5);
  ck_assert_uint_eq(d.n, 0);
}
END_TEST

START_TEST(expression_ends_at_next_word)
{
  first("R1+100R2+200");
  ck_assert_int_eq(b->nw, 2);
  ck_assert_double_eq(eval(b->w[0].e), 100);
  ck_assert_int_eq(b->w[1].num, 2);
  ck_assert_double_eq(eval(b->w[1].e), 200);
  ck_assert_uint_eq(b->w[1].col, 7);
}
END_TEST

START_TEST(axis_operand_in_expression)
{
  first("X+5 Y+X+200");
  ck_assert_int_eq(b->nw, 2);
  const struct expr *e = b->w[1].e;
  ck_assert_int_eq(e->op, OP_ADD);
  ck_assert_int_eq(e->a->kind, EX_SLOT);
  ck_assert_uint_eq(e->a->idx, SL_X);
}
END_TEST

START_TEST(functions_parse)
{
  first("R1+SI(30000)+CO(0)+TG(45000)+ASI(1)+ACO(1)+ATG(1)+LO(1)");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_double_eq_tol(eval(b->w[0].e), 0.5 + 1 + 1 + 90000 + 0 + 45000 + 0, 1e-6);
}
END_TEST

START_TEST(operands_p1_tk_ug_d1_arrays)
{
  first("R1+P1");
  ck_assert_double_eq(b->w[0].e->v, 3.141592);
  first("R1+TK");
  ck_assert_uint_eq(b->w[0].e->idx, REG_TK);
  first("R1+UG");
  ck_assert_uint_eq(b->w[0].e->idx, REG_UG);
  first("R1+D1");
  ck_assert_uint_eq(b->w[0].e->idx, REG_D1);
  first("R1+T32");
  ck_assert_int_eq(b->w[0].e->kind, EX_ARR);
  ck_assert_uint_eq(b->w[0].e->idx, 1u | 3u << 2);
  ck_assert_uint_eq(d.n, 0);
}
END_TEST

START_TEST(p1_operand_and_jump)
{
  /* P1 is pi where an operand is expected, a jump where a word is */
  first("R1+P1 P1");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_int_eq(b->nw, 2);
  ck_assert_double_eq(b->w[0].e->v, 3.141592);
  ck_assert_int_eq(b->w[1].kind, WK_P);
  ck_assert_int_eq(b->w[1].num, 1);
}
END_TEST

START_TEST(unknown_function_is_syntax)
{
  first("N1 R1+SX(1)");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 7);
}
END_TEST

START_TEST(register_out_of_range)
{
  first("N1 R114+1");
  ASSERT_DIAG(only_error(), S42_E_RANGE, 1, 4);
  first("N1 X+R200");
  ASSERT_DIAG(&d.v[1], S42_E_RANGE, 1, 6);
}
END_TEST

START_TEST(literal_of_eight_digits)
{
  first("N1 R1+12345678");
  ASSERT_DIAG(only_error(), S42_E_RANGE, 1, 7);
}
END_TEST

START_TEST(unclosed_parenthesis)
{
  first("N1 R1+(2+3");
  const struct diag *g = only_error();
  ASSERT_DIAG(g, S42_E_SYNTAX, 1, 11);
}
END_TEST

START_TEST(lowercase_address)
{
  first("N1 x+1");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 4);
}
END_TEST

START_TEST(error_skips_rest_of_block)
{
  first("N1 X+ \nN2 G99 ^ N3 M2");
  ck_assert_int_eq(b->bad, 1);
  ASSERT_DIAG(&d.v[0], S42_E_SYNTAX, 1, 7);
  ck_assert_int_eq(d.v[0].number, 1);
  again();
  ck_assert_int_eq(b->number, 2);
  ASSERT_DIAG(&d.v[1], S42_E_FUNC, 2, 4);
  ck_assert_int_eq(d.v[1].number, 2);
  again();
  ck_assert_int_eq(b->number, 3);
  ck_assert_int_eq(b->bad, 0);
  ck_assert_uint_eq(d.nerr, 2);
}
END_TEST

START_TEST(array_words)
{
  first("TT1 TT T0 T02 T03 T04 T11+5 T22-1 T31+R1");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_int_eq(b->nw, 9);
  ck_assert_int_eq(b->w[0].op, OP_AZERO);
  ck_assert_uint_eq(b->w[0].idx, 1);
  ck_assert_uint_eq(b->w[1].idx, 3);
  ck_assert_int_eq(b->w[2].op, OP_APTR0);
  ck_assert_uint_eq(b->w[2].idx, 3);
  ck_assert_uint_eq(b->w[3].idx, 2);
  ck_assert_int_eq(b->w[4].op, OP_APTREND);
  ck_assert_uint_eq(b->w[4].idx, 1);
  ck_assert_uint_eq(b->w[5].idx, 2);
  ck_assert_int_eq(b->w[6].kind, WK_AWR);
  ck_assert_uint_eq(b->w[6].idx, 0u | 1u << 2);
  ck_assert_uint_eq(b->w[7].idx, 1u | 2u << 2);
  ck_assert_double_eq(eval(b->w[7].e), -1);
}
END_TEST

START_TEST(bad_array_word)
{
  first("N1 T41+1");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 4);
}
END_TEST

START_TEST(jumps_and_calls)
{
  first("L12 H+3 PP40 P7");
  ck_assert_int_eq(wordk(WK_L, 'L')->num, 12);
  ck_assert_double_eq(eval(wordk(WK_SLOT, 'H')->e), 3);
  ck_assert_int_eq(wordk(WK_PP, 'P')->num, 40);
  ck_assert_int_eq(wordk(WK_P, 'P')->num, 7);
}
END_TEST

/* ---- conditions ---- */

START_TEST(condition_relation_masks)
{
  static const struct { const char *rel; unsigned mask; } t[] = {
    {"R", 2}, {"B", 4}, {"M", 1}, {"BR", 6}, {"RB", 6}, {"MR", 3}, {"RM", 3}, {"BM", 5}, {"BMR", 7}, {"", 0},
  };
  for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
    char src[64];
    snprintf(src, sizeof src, "P(R1:%s:0)5", t[i].rel);
    first(src);
    ck_assert_msg(b->cond && b->cond->kind == EX_CMP && b->cond->op == t[i].mask, "%s", src);
    ck_assert_int_eq(wordk(WK_PCOND, 'P')->num, 5);
  }
  ck_assert_uint_eq(d.n, 0);
}
END_TEST

START_TEST(condition_with_expressions)
{
  first("P(Z-R0 : BR : R3+R4) 5");
  ck_assert_int_eq(b->cond->kind, EX_CMP);
  ck_assert_uint_eq(b->cond->op, 6);
  ck_assert_int_eq(b->cond->a->op, OP_SUB);
  ck_assert_int_eq(b->cond->b->op, OP_ADD);
  ck_assert_int_eq(wordk(WK_PCOND, 'P')->num, 5);
}
END_TEST

START_TEST(condition_or)
{
  first("P(Z+R0:R:100) S (R3:M:0) 20");
  ck_assert_int_eq(b->cond->kind, EX_OR);
  ck_assert_uint_eq(b->cond->a->op, 2);
  ck_assert_uint_eq(b->cond->b->op, 1);
  ck_assert_int_eq(wordk(WK_PCOND, 'P')->num, 20);
}
END_TEST

START_TEST(condition_and_binds_tighter)
{
  first("P(R1:R:0) S (R2:R:0) U (R3:R:0) 9");
  ck_assert_int_eq(b->cond->kind, EX_OR);
  ck_assert_int_eq(b->cond->b->kind, EX_AND);
}
END_TEST

START_TEST(condition_grouped)
{
  first("P(((X:R:0) S (Y:R:0)) U (Z:M:1000)) 20");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_int_eq(b->cond->kind, EX_AND);
  ck_assert_int_eq(b->cond->a->kind, EX_OR);
  ck_assert_int_eq(b->cond->b->kind, EX_CMP);
  ck_assert_double_eq(b->cond->b->b->v, 1000);
}
END_TEST

START_TEST(condition_parenthesised_expression)
{
  first("P((R1+1)%2:B:(4)) 3");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_int_eq(b->cond->kind, EX_CMP);
  ck_assert_int_eq(b->cond->a->op, OP_MUL);
}
END_TEST

START_TEST(relation_repeated_letter)
{
  first("N1 P(R1:RR:0)5");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 9);
}
END_TEST

START_TEST(relation_bad_letter)
{
  first("N1 P(R1:X:0)5");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 9);
}
END_TEST

START_TEST(condition_needs_target)
{
  first("N1 P(R1:R:0)");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 13);
}
END_TEST

/* ---- slash arguments ---- */

START_TEST(g27_text_and_forms)
{
  first("N1 G27 /ДІАМЕТР,  МКМ/");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_str_eq(b->g27.s, "ДІАМЕТР,  МКМ");
  ck_assert_uint_eq(b->g27.nchars, 13);
  ck_assert_uint_eq(b->g27.col, 9);
  ck_assert_int_eq(b->g27form, ':');
  first("N1 G27 /A/:");
  ck_assert_int_eq(b->g27form, ':');
  first("N1 G27 /A/-");
  ck_assert_int_eq(b->g27form, '-');
  ck_assert_uint_eq(d.n, 0);
}
END_TEST

START_TEST(g27_text_not_closed)
{
  first("N1 G27 /ABC\nN2 M2");
  ASSERT_DIAG(only_error(), S42_E_TEXT, 1, 9);
  again();
  ck_assert_int_eq(b->number, 2);
}
END_TEST

START_TEST(g27_needs_slash)
{
  first("N1 G27 ABC");
  ASSERT_DIAG(only_error(), S42_E_TEXT, 1, 8);
}
END_TEST

START_TEST(g28_bounds_and_register)
{
  first("G28 /30000:40000/ R0");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_double_eq(eval(b->g28min), 30000);
  ck_assert_double_eq(eval(b->g28max), 40000);
  ck_assert_int_eq(b->g28reg, 0);
  ck_assert_uint_eq(b->g28col, 6);
  ck_assert_int_eq(b->nw, 1);        /* the R names the destination: no assignment */
}
END_TEST

START_TEST(g28_division_in_parentheses)
{
  first("G28 / (R1/2) : R2+1 / R3");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_int_eq(b->g28min->op, OP_DIV);
  ck_assert_int_eq(b->g28max->op, OP_ADD);
  ck_assert_int_eq(b->g28reg, 3);
}
END_TEST

START_TEST(g28_without_register)
{
  first("N1 G28 /1:2/");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 9);
}
END_TEST

START_TEST(g29_lines)
{
  first("G29 /ДІАМЕТР ((R100/ КРОК/ //");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_int_eq(b->ng29, 3);
  ck_assert_str_eq(b->g29[0].s, "ДІАМЕТР ((R100");
  ck_assert_str_eq(b->g29[1].s, " КРОК");
  ck_assert_str_eq(b->g29[2].s, " ");
  ck_assert_uint_eq(b->g29[1].col, 21);
}
END_TEST

START_TEST(g29_two_lines)
{
  first("G29 /A/B//");
  ck_assert_int_eq(b->ng29, 2);
  ck_assert_str_eq(b->g29[1].s, "B");
}
END_TEST

START_TEST(g33_and_m18_text)
{
  first("M18 /ВІДВЕСТИ УПОРКУ/ G33 / КІНЕЦЬ /");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_str_eq(b->m18.s, "ВІДВЕСТИ УПОРКУ");
  ck_assert_uint_eq(b->m18.nchars, 15);
  ck_assert_str_eq(b->g33.s, " КІНЕЦЬ ");
  ck_assert_uint_eq(b->g33.nchars, 8);
}
END_TEST

START_TEST(m20_list)
{
  first("M20 / R12 R1 5 /");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_int_eq(b->nm20, 2);
  ck_assert_uint_eq(b->m20[0], 12);
  ck_assert_uint_eq(b->m20[1], 15);
  ck_assert_uint_eq(b->m20col[1], 11);
}
END_TEST

START_TEST(m20_empty_list)
{
  first("N1 M20 //");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 9);
}
END_TEST

START_TEST(m16_list)
{
  first("M16 /R1+X R2-Z R113+A//");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_int_eq(b->nm16, 3);
  ck_assert_uint_eq(b->m16[0].reg, 1);
  ck_assert_int_eq(b->m16[0].axis, 'X');
  ck_assert_int_eq(b->m16[0].sign, 1);
  ck_assert_uint_eq(b->m16[1].reg, 2);
  ck_assert_int_eq(b->m16[1].axis, 'Z');
  ck_assert_int_eq(b->m16[1].sign, -1);
  ck_assert_uint_eq(b->m16[2].reg, 113);
  ck_assert_uint_eq(b->m16[1].col, 11);
}
END_TEST

START_TEST(m16_bad_axis)
{
  first("N1 M16 /R1+Q//");
  ASSERT_DIAG(only_error(), S42_E_AXIS, 1, 12);
}
END_TEST

START_TEST(g37_axis)
{
  first("G37 /Y/");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_int_eq(b->g37axis, 'Y');
  ck_assert_uint_eq(b->g37col, 6);
  first("G37 /X/");                  /* parsed; the compiler refuses it */
  ck_assert_int_eq(b->g37axis, 'X');
  first("N1 G37 /Q/");
  ASSERT_DIAG(only_error(), S42_E_AXIS, 1, 9);
}
END_TEST

START_TEST(g33_with_m_before)
{
  first("M21 G33 /A/");
  ck_assert_uint_eq(d.n, 0);
  ck_assert_str_eq(b->g33.s, "A");
}
END_TEST

START_TEST(stray_slash)
{
  first("N1 M2 /A/");
  ASSERT_DIAG(only_error(), S42_E_SYNTAX, 1, 7);
  first("N1 X+1 /A/");               /* X = 1/A, then a '/' with nothing after it */
  ASSERT_DIAG(&d.v[1], S42_E_SYNTAX, 1, 11);
}
END_TEST

START_TEST(slash_text_counts_cyrillic_chars)
{
  first("G33 /ЖЖЖЖ/ X+1");
  ck_assert_uint_eq(b->g33.nchars, 4);
  ck_assert_uint_eq(wordk(WK_SLOT, 'X')->col, 12);
}
END_TEST

START_TEST(error_line_and_number_in_later_block)
{
  first("N1 M2\n\n   N17 G01 X+1 Y+ )Z+1");
  again();
  const struct diag *g = only_error();
  ASSERT_DIAG(g, S42_E_SYNTAX, 3, 19);
  ck_assert_int_eq(g->number, 17);
}
END_TEST

Suite *suite_parse(void)
{
  Suite *s = suite_create("parse");
  TCase *tc = tcase_create("blocks");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, block_number_n);
  tcase_add_test(tc, block_number_numero_and_space);
  tcase_add_test(tc, block_without_number);
  tcase_add_test(tc, block_number_range);
  tcase_add_test(tc, block_number_four_digits);
  tcase_add_test(tc, empty_blocks_skipped);
  tcase_add_test(tc, blocks_in_sequence);
  tcase_add_test(tc, block_len_counts_significant);
  tcase_add_test(tc, g_m_numbers_leading_zeros);
  tcase_add_test(tc, unknown_g_is_efunc);
  tcase_add_test(tc, unknown_m_is_efunc);
  tcase_add_test(tc, valid_function_tables);
  tcase_add_test(tc, g_twice_is_egroup);
  tcase_add_test(tc, m_twice_is_syntax);
  suite_add_tcase(s, tc);

  tc = tcase_create("words");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, axis_words_and_slots);
  tcase_add_test(tc, axis_needs_sign);
  tcase_add_test(tc, word_twice_is_syntax);
  tcase_add_test(tc, assignments_may_repeat);
  tcase_add_test(tc, whitespace_inside_numbers);
  tcase_add_test(tc, sign_starts_first_term);
  tcase_add_test(tc, precedence_mul_over_add);
  tcase_add_test(tc, left_assoc_div);
  tcase_add_test(tc, power_right_assoc);
  tcase_add_test(tc, power_binds_tighter_than_mul);
  tcase_add_test(tc, sign_rules_with_power);
  tcase_add_test(tc, expression_ends_at_next_word);
  tcase_add_test(tc, axis_operand_in_expression);
  tcase_add_test(tc, functions_parse);
  tcase_add_test(tc, operands_p1_tk_ug_d1_arrays);
  tcase_add_test(tc, p1_operand_and_jump);
  tcase_add_test(tc, unknown_function_is_syntax);
  tcase_add_test(tc, register_out_of_range);
  tcase_add_test(tc, literal_of_eight_digits);
  tcase_add_test(tc, unclosed_parenthesis);
  tcase_add_test(tc, lowercase_address);
  tcase_add_test(tc, error_skips_rest_of_block);
  tcase_add_test(tc, array_words);
  tcase_add_test(tc, bad_array_word);
  tcase_add_test(tc, jumps_and_calls);
  tcase_add_test(tc, error_line_and_number_in_later_block);
  suite_add_tcase(s, tc);

  tc = tcase_create("conditions");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, condition_relation_masks);
  tcase_add_test(tc, condition_with_expressions);
  tcase_add_test(tc, condition_or);
  tcase_add_test(tc, condition_and_binds_tighter);
  tcase_add_test(tc, condition_grouped);
  tcase_add_test(tc, condition_parenthesised_expression);
  tcase_add_test(tc, relation_repeated_letter);
  tcase_add_test(tc, relation_bad_letter);
  tcase_add_test(tc, condition_needs_target);
  suite_add_tcase(s, tc);

  tc = tcase_create("slash");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, g27_text_and_forms);
  tcase_add_test(tc, g27_text_not_closed);
  tcase_add_test(tc, g27_needs_slash);
  tcase_add_test(tc, g28_bounds_and_register);
  tcase_add_test(tc, g28_division_in_parentheses);
  tcase_add_test(tc, g28_without_register);
  tcase_add_test(tc, g29_lines);
  tcase_add_test(tc, g29_two_lines);
  tcase_add_test(tc, g33_and_m18_text);
  tcase_add_test(tc, m20_list);
  tcase_add_test(tc, m20_empty_list);
  tcase_add_test(tc, m16_list);
  tcase_add_test(tc, m16_bad_axis);
  tcase_add_test(tc, g37_axis);
  tcase_add_test(tc, g33_with_m_before);
  tcase_add_test(tc, stray_slash);
  tcase_add_test(tc, slash_text_counts_cyrillic_chars);
  suite_add_tcase(s, tc);
  return s;
}
