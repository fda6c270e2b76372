/* The 2У22 front end (src/dialect/2u22, spec/dialects/2u22.md): the text,
 * the words and their limits, the G and M tables and groups, parameters,
 * H repeats and subprograms, each rule good and bad with its error code,
 * line, column and block; the spec's examples; programs run on the VM
 * alone (the words' values at VM_EV_BLOCK, the block sequence, the depth). */
#include "suites.h"
#include "dialect.h"
#include "errors.h"
#include "msgs.h"
#include "opcodes.h"
#include "verify.h"
#include "../../src/dialect/2u22/u22.h"
#include "../../src/dialect/2u22/u22c.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct uprog {
  struct program p;
  struct diag_list d;
  int rc;
};

static void uc(struct uprog *u, const char *src)
{
  prog_init(&u->p);
  diag_init(&u->d, "t.u22");
  u->rc = u22_compile(src, strlen(src), &u->d, &u->p);
}

static void ufree(struct uprog *u)
{
  prog_free(&u->p);
  diag_free(&u->d);
}

/* src compiles, and its bytecode verifies with the stack it records. */
static void ok(struct uprog *u, const char *src)
{
  uc(u, src);
  ck_assert_msg(u->rc == 0, "does not compile:\n%s\n%s", src, tp_diags(&u->d));
  uint32_t need;
  char msg[200];
  ck_assert_msg(prog_verify_need(&u->p, &need, msg, sizeof msg) == 0, "%s", msg);
  ck_assert_uint_eq(need, u->p.max_stack);
}

/* src fails, its first error (in text order) code at line:col of block number. */
#define bad(src, code, line, col, number) bad_at(__LINE__, src, code, line, col, number)
static void bad_at(int at, const char *src, int code, unsigned line, unsigned col, int number)
{
  struct uprog u;
  uc(&u, src);
  ck_assert_msg(u.rc == -1, "line %d: compiles but should not:\n%s", at, src);
  diag_sort(&u.d);
  const struct diag *g = diag_first_error(&u.d);
  ck_assert_msg(g && g->code == code && g->line == line && g->col == col && g->number == number,
                "line %d: want %s at %u:%u of N%d, got:\n%s", at, err_code(code), line, col, number,
                tp_diags(&u.d));
  ufree(&u);
}

/* ---- the VM alone ---- */

#define MAXROWS 256
struct row {
  uint32_t n;
  int depth;
  double w[U22_NSLOT];
  uint16_t words;
};
struct trace {
  struct row r[MAXROWS];
  int n;
  enum vm_event last;
  int err;
  double reg[VM_NREG];
};

static void run(const struct program *p, struct trace *t)
{
  struct vm *vm = malloc(sizeof *vm);
  ck_assert_ptr_nonnull(vm);
  ck_assert_int_eq(vm_init(vm, p), 0);
  vm->max_blocks = 10000;
  t->n = 0;
  for (;;) {
    enum vm_event ev = vm_run(vm);
    if (ev == VM_EV_BLOCK) {
      if (t->n < MAXROWS) {
        struct row *r = &t->r[t->n++];
        r->n = p->blocks[vm->cur].number;
        r->depth = vm->depth;
        r->words = u22_attr(p, vm->cur)->words;
        memcpy(r->w, vm->w, sizeof r->w);
      }
      continue;
    }
    if (ev == VM_EV_START)
      continue;
    t->last = ev;
    t->err = vm->err.code;
    memcpy(t->reg, vm->reg, sizeof t->reg);
    break;
  }
  free(vm);
}

static void ok_run(const char *src, struct trace *t)
{
  struct uprog u;
  ok(&u, src);
  run(&u.p, t);
  ufree(&u);
}

/* The block numbers as "11 12 13". */
static const char *seq(const struct trace *t)
{
  static char buf[2048];
  size_t k = 0;
  buf[0] = 0;
  for (int i = 0; i < t->n && k + 12 < sizeof buf; i++)
    k += (size_t)snprintf(buf + k, sizeof buf - k, "%s%u", i ? " " : "", t->r[i].n);
  return buf;
}

/* ---- the spec's examples (spec/dialects/examples/2u22) ---- */

static const char *const fig1_9 =
  "% ПС\n"
  "N1 T1 G01 G90 G94 G97 S500 M03 M39 ПС\n"
  "N2 F1000 X4100 Z0 G09 ПС\n"
  "N3 F100 X0 G09 ПС\n"
  "N4 F1000 X3800 G09 ПС\n"
  "N5 F100 Z-5000 G09 G91 ПС\n"
  "N6 X300 G09 ПС\n"
  "N7 F1000 Z5000 G09 ПС\n"
  "N8 F100 X3000 G09 G90 ПС\n"
  "N9 X3400 Z-200 G09 ПС\n"
  "N10 Z-3000 G09 ПС\n"
  "N11 X3900 G09 ПС\n"
  "N12 F1000 X10000 Z10000 G09 ПС\n"
  "N13 T2 G95 ПС\n"
  "N14 F1000 X4000 Z-3000 G09 ПС\n"
  "N15 F20 X3000 G09 ПС\n"
  "N16 G04 E20 ПС\n"
  "N17 F1000 X4000 G09 ПС\n"
  "N18 X10000 Z20000 G09 ПС\n"
  "N19 M02 ПС\n";

static const char *const lin_abs_inc =
  "(L580-586: X0=27 Z0=75 -> XK=89 ZK=34, as two programs in one: absolute, then back and incremental)\n"
  "%\n"
  "N1 G90 G94 F100 X27 Z75\n"
  "N10 G90 X89 Z34\n"
  "N11 X27 Z75\n"
  "N12 G91 X62 Z-41\n"
  "N13 M02\n";

static const char *const params_r =
  "(L782-790: formal parameters; the values the source states are in the comments)\n"
  "%\n"
  "N001 G90 G94 F100 L04 R2+50 R1-1000\n"
  "N002 L02\n"
  "N003 M02\n"
  "N04001 S+R2 X+R1 Z-R1 M17\n"
  "(S = 50, X = -1000, Z = +1000)\n"
  "N02005 X-R2 Z-1200+R2 M17\n"
  "(X = -50, Z = -1150)\n";

static const char *const repeat_h =
  "%\n"
  "N11 F5000 X0 G09\n"
  "N12 X-300 H10 G09\n"
  "N13 X-2000 G09 M20\n"
  "N14 X-800 G09 M02\n";

static const char *const sub_l02 =
  "(L754-774 skeleton made runnable: the \"...\" of the source are filled with moves;)\n"
  "(N02001 written twice in the source, the second is N02002)\n"
  "%\n"
  "N101 G90 G94 F100 X4000 Z0\n"
  "N102 X4000 Z-1000\n"
  "N103 X4200 L02\n"
  "N104 G90 X5000 M02\n"
  "N02001 G91 Z-200\n"
  "N02002 X-400\n"
  "N02003 Z-300\n"
  "N02004 X400 Z500 M17\n";

START_TEST(registry_entry)
{
  const struct dialect *d = dialect_by_name("2u22");
  ck_assert_ptr_nonnull(d);
  ck_assert_str_eq(d->ext, ".u22");
  ck_assert_str_eq(d->machine, "lathe");
  ck_assert_int_eq(d->run, DIALECT_RUN_MACHINE);
  ck_assert_ptr_eq(dialect_by_file("part.u22"), d);
  struct program p;
  struct diag_list dl;
  prog_init(&p);
  diag_init(&dl, "x.u22");
  ck_assert_int_eq(d->compile(repeat_h, strlen(repeat_h), &dl, &p, NULL), 0);
  ck_assert_ptr_eq(p.runtime, &u22_runtime);
  ck_assert_ptr_eq(p.msgs, &u22_msgs);
  ck_assert_int_eq(p.saved_reg, -1);
  ck_assert_uint_eq(p.lim.depth, 2);
  ck_assert(p.lim.param_lo == -9999999 && p.lim.param_hi == 9999999);
  ck_assert(((const struct u22_ext *)p.ext)->unit == 0.01);
  ck_assert_uint_eq(((const struct u22_ext *)p.ext)->n, p.nblocks);
  ck_assert_ptr_nonnull(p.ext_free);
  prog_free(&p);
  diag_free(&dl);
  char msg[200];
  ck_assert_msg(vm_msgs_check(&u22_msgs, msg, sizeof msg) == 0, "%s", msg);
  for (int e = 1; e < S42_E_COUNT; e++)
    ck_assert_msg(u22_msgs.title[0][e] && u22_msgs.title[1][e], "no title for %s", err_code(e));
  ck_assert_int_eq(u22_g_number[UG33], 33);
  ck_assert_int_eq(u22_m_number[UM39], 39);
}
END_TEST

START_TEST(examples_compile)
{
  const char *const ex[] = {fig1_9, lin_abs_inc, params_r, repeat_h, sub_l02};
  const size_t blocks[] = {19, 5, 5, 4, 8};
  for (size_t i = 0; i < sizeof ex / sizeof ex[0]; i++) {
    struct uprog u;
    ok(&u, ex[i]);
    ck_assert_uint_eq(u.p.nblocks, blocks[i]);
    ck_assert_uint_eq(tp_count(&u.d, DIAG_ERROR), 0);
    ufree(&u);
  }
  struct uprog u;
  ok(&u, fig1_9);
  const struct u22_attr *a = u22_attr(&u.p, 0);
  ck_assert_uint_eq(a->g, 1u << UG01 | 1u << UG90 | 1u << UG94 | 1u << UG97);
  ck_assert_uint_eq(a->m, 1u << UM03 | 1u << UM39);
  ck_assert_uint_eq(a->words, 1u << U22_T | 1u << U22_S);
  a = u22_attr(&u.p, 15);   /* N16 G04 E20 */
  ck_assert_uint_eq(a->g, 1u << UG04);
  ck_assert_uint_eq(a->words, 1u << U22_E);
  ck_assert_uint_eq(u.p.blocks[18].number, 19);
  struct trace t;
  run(&u.p, &t);
  ck_assert_int_eq(t.last, VM_EV_END);
  ck_assert_int_eq(t.n, 19);
  ck_assert(t.r[1].w[U22_X] == 4100 && t.r[1].w[U22_F] == 1000);
  ck_assert(t.r[4].w[U22_Z] == -5000);
  ck_assert(t.r[15].w[U22_E] == 20);
  ufree(&u);
}
END_TEST

/* ---- sec. 2: the text ---- */

START_TEST(text_start_and_leader)
{
  struct uprog u;
  bad("N1 M02\n", S42_E_SYNTAX, 1, 1, -1);
  bad("", S42_E_SYNTAX, 1, 1, -1);
  bad("(leader)\nN1 X1 %\nN2 M02\n", S42_E_SYNTAX, 1, 1, -1);   /* % not at the start of a line */
  /* a tape leader of any text, then the % line */
  ok(&u, "any leader: % ; ( : \nmore\n  % ПС (start)\nN1 M02\n");
  ck_assert_uint_eq(u.p.nblocks, 1);
  ck_assert_uint_eq(u.p.blocks[0].line, 4);
  ufree(&u);
  bad("%N1 M02\n", S42_E_SYNTAX, 1, 2, -1);
  bad("% X\nN1 M02\n", S42_E_SYNTAX, 1, 3, -1);
  bad("%\n", S42_E_SUB, 1, 1, -1);   /* no blocks at all */
  bad("%\nN1 X1\n%\nN2 M02\n", S42_E_SYNTAX, 3, 1, -1);   /* a second % */
  /* a UTF-8 BOM, CR LF and lone CR lines */
  ok(&u, "\xEF\xBB\xBF%\r\nN1 X1\r\nN2 M02\r\n");
  ck_assert_uint_eq(u.p.nblocks, 2);
  ufree(&u);
  ok(&u, "%\rN1 X1\rN2 M02");
  ck_assert_uint_eq(u.p.nblocks, 2);
  ck_assert_uint_eq(u.p.blocks[1].line, 3);
  ufree(&u);
}
END_TEST

START_TEST(text_end_marks_and_comments)
{
  struct uprog u;
  ok(&u, "% PC\nN1 X1 PC\nN2 X2 ПС (a comment after the mark) ПС\n(a comment alone is no block)\n\n  \nN3 M02 ПC\n");
  ck_assert_uint_eq(u.p.nblocks, 3);
  ck_assert_uint_eq(u.p.blocks[2].number, 3);
  ck_assert_uint_eq(u.p.blocks[2].line, 7);
  ufree(&u);
  bad("%\nN1 X1 ПС N2 X2\nN3 M02\n", S42_E_SYNTAX, 2, 10, 1);    /* one block per line */
  bad("%\nN1 X1 (no end\nN2 M02\n", S42_E_SYNTAX, 2, 7, 1);
  bad("%\nN1 X1 (a: b)\nN2 M02\n", S42_E_SYNTAX, 2, 9, 1);
  bad("%\nN1 X1 (50%)\nN2 M02\n", S42_E_SYNTAX, 2, 10, 1);
  bad("%\nN1 X1 (a ПС b)\nN2 M02\n", S42_E_SYNTAX, 2, 10, 1);
  bad("%\nN1 X1 )\nN2 M02\n", S42_E_SYNTAX, 2, 7, 1);
  /* a comment inside a block, between words */
  ok(&u, "%\nN1 X1 (here) Z2\nN2 M02\n");
  ck_assert_uint_eq(u22_attr(&u.p, 0)->words, 1u << U22_X | 1u << U22_Z);
  ufree(&u);
}
END_TEST

START_TEST(text_block_starts)
{
  struct uprog u;
  bad("%\nX100 M02\n", S42_E_SYNTAX, 2, 1, -1);                   /* D-3 */
  bad("%\nN1 X1\nG01 X2\nN3 M02\n", S42_E_SYNTAX, 3, 1, -1);
  bad("%\nN X1\nN2 M02\n", S42_E_SYNTAX, 2, 1, -1);
  bad("%\nN123456 X1\nN2 M02\n", S42_E_RANGE, 2, 1, -1);
  bad("%\n/\nN2 M02\n", S42_E_SYNTAX, 2, 1, -1);
  bad("%\nN1 N2 M02\n", S42_E_BLOCK, 2, 4, 1);
  bad("%\nN+1 M02\n", S42_E_SYNTAX, 2, 2, -1);
  /* :40 is block 40; a bare : has no number; 1 to 5 digits; '/' marks a skippable block */
  ok(&u, "%\n:40 X1\n: X2\n/N00007 X3\n/ :8 X4\nN99999 M02\n");
  ck_assert_uint_eq(u.p.blocks[0].number, 40);
  ck_assert_uint_eq(u.p.blocks[1].number, 0);
  ck_assert_uint_eq(u.p.blocks[2].number, 7);
  ck_assert_uint_eq(u.p.blocks[4].number, 99999);
  ck_assert_uint_eq(u22_attr(&u.p, 2)->skip, 1);
  ck_assert_uint_eq(u22_attr(&u.p, 3)->skip, 1);
  ck_assert_uint_eq(u22_attr(&u.p, 0)->skip, 0);
  ck_assert_uint_eq(u.p.blocks[2].col, 1);
  ufree(&u);
  /* a block without a number names itself N- in messages */
  bad("%\n: X1.5\nN2 M02\n", S42_E_SYNTAX, 2, 5, -1);
}
END_TEST

START_TEST(text_block_length)
{
  struct uprog u;
  /* 80 characters without spaces and comments: N1 (2) + 13 words of 6 = 80 */
  char src[600], line[400];
  strcpy(line, "N1");
  const char *w[] = {"X11111", "Z11111", "I11111", "K11111", "F11111", "S1111", "T001", "R11111", "R21111",
                     "R31111", "R41111", "R51111", "R61111", "M02"};
  for (size_t i = 0; i < sizeof w / sizeof w[0]; i++) {
    strcat(line, " ");
    strcat(line, w[i]);
  }
  /* 2 + 6*5 + 5 + 4 + 6*6 + 3 = 80 */
  snprintf(src, sizeof src, "%%\n%s (a long comment that does not count at all, none of it)\n", line);
  ok(&u, src);
  ufree(&u);
  snprintf(src, sizeof src, "%%\n%s9\n", line);   /* M029: 81 characters */
  bad(src, S42_E_BLOCKLEN, 2, 95, 1);
}
END_TEST

START_TEST(text_lookalikes_and_case)
{
  struct uprog u;
  /* Cyrillic Х Т М Е К Н as X T M E K H (Р is P and С is C: no addresses) */
  ok(&u, "%\nN1 Х100 Т2 М03\nN2 G04 Е20\nN3 G33 Z-100 К2500\nN4 Н1\nN5 М20\nN6 М02 ПС\n");
  ck_assert_uint_eq(u22_attr(&u.p, 3)->h, 2);
  ck_assert_uint_eq(u22_attr(&u.p, 0)->words, 1u << U22_X | 1u << U22_T);
  ck_assert_uint_eq(u22_attr(&u.p, 0)->m, 1u << UM03);
  ck_assert_uint_eq(u22_attr(&u.p, 2)->words, 1u << U22_Z | 1u << U22_K);
  ufree(&u);
  bad("%\nN1 Р1+5 M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 x100 M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 Y100 M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 Ж100 M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 X100 \x80 M02\n", S42_E_SYNTAX, 2, 9, 1);
}
END_TEST

/* ---- sec. 3: words ---- */

START_TEST(words_numbers)
{
  struct uprog u;
  bad("%\nN1 X10.5 M02\n", S42_E_SYNTAX, 2, 7, 1);
  bad("%\nN1 F10.0 M02\n", S42_E_SYNTAX, 2, 7, 1);
  bad("%\nN1 G01. M02\n", S42_E_SYNTAX, 2, 7, 1);
  bad("%\nN1 X12345678 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 Z-00000001 M02\n", S42_E_RANGE, 2, 4, 1);       /* leading zeros count */
  bad("%\nN1 F123456 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 S12345 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 T0001 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 T100 M02\n", S42_E_RANGE, 2, 4, 1);              /* T0..T99 (D-27) */
  bad("%\nN1 G04 E12345678 M02\n", S42_E_RANGE, 2, 8, 1);
  bad("%\nN1 H12345\nN2 M20\nN3 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 G001 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 M002\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 F-100 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 G33 Z-100 K123456 M02\n", S42_E_RANGE, 2, 14, 1);   /* I, K under G33: 5 digits */
  bad("%\nN1 X+ M02\n", S42_E_SYNTAX, 2, 5, 1);
  bad("%\nN1 X M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 +5 M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 X+R1 5 M02\n", S42_E_SYNTAX, 2, 9, 1);   /* spaces do not count: R15 */
  bad("%\nN1 G M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 G+1 M02\n", S42_E_SYNTAX, 2, 5, 1);
  bad("%\nN1 X+1234567 Z-1234567 I0000001 K1 F99999 S9999 T001 T\n", S42_E_BLOCK, 2, 54, 1);
  ok(&u, "%\nN1 X+1234567 Z-1234567 I0000001 K1 F99999 S9999 T099\nN2 G33 Z-7500 K99999 I-99999\nN3 M02\n");
  struct trace t;
  run(&u.p, &t);
  ck_assert(t.r[0].w[U22_X] == 1234567 && t.r[0].w[U22_Z] == -1234567 && t.r[0].w[U22_I] == 1);
  ck_assert(t.r[0].w[U22_T] == 99 && t.r[0].w[U22_S] == 9999 && t.r[0].w[U22_F] == 99999);
  ck_assert(t.r[1].w[U22_K] == 99999 && t.r[1].w[U22_I] == -99999);
  ufree(&u);
}
END_TEST

START_TEST(words_repeats)
{
  struct uprog u;
  bad("%\nN1 X1 Z2 X3 M02\n", S42_E_BLOCK, 2, 10, 1);
  bad("%\nN1 F1 F2 M02\n", S42_E_BLOCK, 2, 7, 1);
  bad("%\nN1 L01 L02 M02\nN01001 M17\nN02001 M17\n", S42_E_BLOCK, 2, 8, 1);
  bad("%\nN1 H1 H2\nN2 M20\nN3 M02\n", S42_E_BLOCK, 2, 7, 1);
  /* G, M and R repeat (L516, D-20) */
  ok(&u, "%\nN1 G01 G90 G94 M03 M08 M39 R1+1 R1+2 R2-3\nN2 X+R1 Z+R2 M02\n");
  struct trace t;
  run(&u.p, &t);
  ck_assert(t.r[1].w[U22_X] == 2 && t.r[1].w[U22_Z] == -3);   /* left to right (D-27) */
  ufree(&u);
}
END_TEST

/* ---- sec. 4, 5: G and M ---- */

START_TEST(g_and_m_tables)
{
  struct uprog u;
  const int g[] = {1, 2, 3, 4, 9, 20, 21, 23, 25, 33, 90, 91, 94, 95, 96, 97};
  for (int i = 0; i < UG_N; i++)
    ck_assert_int_eq(u22_g_number[i], g[i]);
  const int m[] = {0, 1, 2, 3, 4, 5, 8, 9, 17, 20, 30, 38, 39};
  for (int i = 0; i < UM_N; i++)
    ck_assert_int_eq(u22_m_number[i], m[i]);
  for (int n = 0; n < 100; n++) {
    char src[80];
    int known = 0;
    for (int i = 0; i < UG_N; i++)
      known |= g[i] == n;
    snprintf(src, sizeof src, "%%\nN1 G%02d X1 Z1 E1 M02\n", n);
    uc(&u, src);
    if (!known) {
      ck_assert_msg(u.rc == -1 && tp_find(&u.d, DIAG_ERROR, S42_E_FUNC, 2, 4) >= 0, "G%02d", n);
    } else {
      ck_assert_msg(tp_find(&u.d, DIAG_ERROR, S42_E_FUNC, 0, 0) < 0, "G%02d: %s", n, tp_diags(&u.d));
    }
    ufree(&u);
    known = 0;
    for (int i = 0; i < UM_N; i++)
      known |= m[i] == n;
    snprintf(src, sizeof src, "%%\nN1 M%02d\nN2 M02\n", n);
    uc(&u, src);
    ck_assert_msg(known ? tp_find(&u.d, DIAG_ERROR, S42_E_FUNC, 0, 0) < 0
                        : tp_find(&u.d, DIAG_ERROR, S42_E_FUNC, 2, 4) >= 0, "M%02d: %s", n, tp_diags(&u.d));
    ufree(&u);
  }
  /* the attr's bits */
  ok(&u, "%\nN1 G1 G9 G20 G21 G91 G95 G96 M4 M9 M38 M00 M01\nN2 M30\n");
  ck_assert_uint_eq(u22_attr(&u.p, 0)->g, 1u << UG01 | 1u << UG09 | 1u << UG20 | 1u << UG21 | 1u << UG91 |
                                           1u << UG95 | 1u << UG96);
  ck_assert_uint_eq(u22_attr(&u.p, 0)->m, 1u << UM04 | 1u << UM09 | 1u << UM38 | 1u << UM00 | 1u << UM01);
  ck_assert_uint_eq(u22_attr(&u.p, 1)->m, 1u << UM30);
  ufree(&u);
}
END_TEST

START_TEST(g_and_m_groups)
{
  bad("%\nN12 G01 G02 M02\n", S42_E_GROUP, 2, 9, 12);
  bad("%\nN1 G33 G03 M02\n", S42_E_GROUP, 2, 8, 1);
  bad("%\nN1 G90 G91 M02\n", S42_E_GROUP, 2, 8, 1);
  bad("%\nN1 G94 G95 M02\n", S42_E_GROUP, 2, 8, 1);
  bad("%\nN1 G96 G97 M02\n", S42_E_GROUP, 2, 8, 1);
  bad("%\nN1 G20 G23 M02\n", S42_E_GROUP, 2, 8, 1);   /* D-6 */
  bad("%\nN1 G23 G21 M02\n", S42_E_GROUP, 2, 8, 1);
  bad("%\nN1 G01 G01 M02\n", S42_E_GROUP, 2, 8, 1);
  bad("%\nN1 G09 G09 M02\n", S42_E_BLOCK, 2, 8, 1);
  bad("%\nN1 M03 M04 M02\n", S42_E_GROUP, 2, 8, 1);
  bad("%\nN1 M03 M05 M02\n", S42_E_GROUP, 2, 8, 1);
  bad("%\nN1 M08 M09 M02\n", S42_E_GROUP, 2, 8, 1);
  bad("%\nN1 M38 M39 M02\n", S42_E_GROUP, 2, 8, 1);
  bad("%\nN1 M02 M30\n", S42_E_GROUP, 2, 8, 1);
  struct uprog u;
  ok(&u, "%\nN1 G20 G21 G01 G90 G94 G97 G09 M03 M08 M39\nN2 G23 G04 E5 M00 M01\nN3 M02\n");
  ufree(&u);
}
END_TEST

START_TEST(g25_and_g04)
{
  struct uprog u;
  ok(&u, "%\nN1 G25 X\nN2 G25 Z\nN3 G25 X Z\nN4 Z G25 X T1\nN5 G04 E250\nN6 G01 X100 G04 E1\nN7 M02\n");
  ck_assert_uint_eq(u22_attr(&u.p, 0)->home, 1);
  ck_assert_uint_eq(u22_attr(&u.p, 1)->home, 2);
  ck_assert_uint_eq(u22_attr(&u.p, 2)->home, 3);
  ck_assert_uint_eq(u22_attr(&u.p, 3)->home, 3);
  ck_assert_uint_eq(u22_attr(&u.p, 2)->words, 0);
  ck_assert_uint_eq(u22_attr(&u.p, 3)->words, 1u << U22_T);
  ck_assert_uint_eq(u22_attr(&u.p, 2)->g, 1u << UG25);
  ck_assert_uint_eq(u22_attr(&u.p, 4)->words, 1u << U22_E);
  struct trace t;
  run(&u.p, &t);
  ck_assert(t.r[4].w[U22_E] == 250);
  ufree(&u);
  bad("%\nN1 G25\nN2 M02\n", S42_E_SYNTAX, 2, 4, 1);      /* D-31 */
  bad("%\nN1 G25 F100\nN2 M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 G25 X100\nN2 M02\n", S42_E_SYNTAX, 2, 8, 1);
  bad("%\nN1 X Z\nN2 M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 G25 I\nN2 M02\n", S42_E_SYNTAX, 2, 8, 1);
  bad("%\nN1 G04\nN2 M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 E20\nN2 M02\n", S42_E_SYNTAX, 2, 4, 1);
}
END_TEST

/* ---- sec. 7: parameters ---- */

START_TEST(params_evaluate)
{
  struct trace t;
  ok_run(params_r, &t);
  ck_assert_int_eq(t.last, VM_EV_END);
  ck_assert_str_eq(seq(&t), "1 4001 2 2005 3");
  /* ex. 4: N04001 S+R2 X+R1 Z-R1 with R1 = -1000, R2 = +50 */
  ck_assert(t.r[1].w[U22_S] == 50 && t.r[1].w[U22_X] == -1000 && t.r[1].w[U22_Z] == 1000);
  ck_assert_uint_eq(t.r[1].words, 1u << U22_S | 1u << U22_X | 1u << U22_Z);
  ck_assert_int_eq(t.r[1].depth, 1);
  /* N02005 X-R2 Z-1200+R2 */
  ck_assert(t.r[3].w[U22_X] == -50 && t.r[3].w[U22_Z] == -1150);
  ck_assert(t.reg[1] == -1000 && t.reg[2] == 50);
  /* both orders of a block: the assignments run first (DEC, sec. 7) */
  ok_run("%\nN1 X+R1 R1+5 Z-R1 R1-7\nN2 X+R1-R1 Z-R1+R1 I-R1-R1 K+5-R1 M02\n", &t);
  ck_assert(t.r[0].w[U22_X] == -7 && t.r[0].w[U22_Z] == 7);
  ck_assert(t.r[1].w[U22_X] == 0 && t.r[1].w[U22_Z] == 0 && t.r[1].w[U22_I] == 14 && t.r[1].w[U22_K] == 12);
  /* parameters start at 0 (D-17); all registers R0..R9 */
  ok_run("%\nN1 X+R0 R9-9999999 Z+R9 F+R3\nN2 M02\n", &t);
  ck_assert(t.r[0].w[U22_X] == 0 && t.r[0].w[U22_Z] == -9999999 && t.r[0].w[U22_F] == 0);
  /* the result must fit the word (L792): E-RANGE at run time */
  ok_run("%\nN1 R1+9999999\nN2 X+R1+R1\nN3 M02\n", &t);
  ck_assert_int_eq(t.last, VM_EV_ERROR);
  ck_assert_int_eq(t.err, S42_E_RANGE);
  ck_assert_int_eq(t.n, 1);
  ok_run("%\nN1 R1-5\nN2 F+R1\nN3 M02\n", &t);
  ck_assert_int_eq(t.err, S42_E_RANGE);
  ok_run("%\nN1 R1+100000\nN2 G33 Z-100 K+R1\nN3 M02\n", &t);   /* K under G33: 5 digits */
  ck_assert_int_eq(t.err, S42_E_RANGE);
  ok_run("%\nN1 R1+100\nN2 T+R1\nN3 M02\n", &t);
  ck_assert_int_eq(t.err, S42_E_RANGE);
  ok_run("%\nN1 R1+99\nN2 T+R1 S-R1+R1 M02\n", &t);
  ck_assert_int_eq(t.last, VM_EV_END);
  ck_assert(t.r[1].w[U22_T] == 99 && t.r[1].w[U22_S] == 0);
}
END_TEST

START_TEST(params_refused)
{
  bad("%\nN1 M+R1\nN2 M02\n", S42_E_SYNTAX, 2, 5, 1);          /* L746 */
  bad("%\nN1 MR1\nN2 M02\n", S42_E_SYNTAX, 2, 5, 1);
  bad("%\nN1 G+R1\nN2 M02\n", S42_E_SYNTAX, 2, 5, 1);
  bad("%\nN1 LR1\nN2 M02\n", S42_E_SYNTAX, 2, 5, 1);
  bad("%\nN1 HR1\nN2 M20\nN3 M02\n", S42_E_SYNTAX, 2, 5, 1);
  bad("%\nNR1 M02\n", S42_E_SYNTAX, 2, 2, -1);
  bad("%\nN1 R1+123456789 M02\n", S42_E_RANGE, 2, 4, 1);       /* ex. 4 */
  bad("%\nN1 R1+R2 M02\n", S42_E_SYNTAX, 2, 7, 1);
  bad("%\nN1 R M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 R1 M02\n", S42_E_SYNTAX, 2, 4, 1);
  bad("%\nN1 R1+5.5 M02\n", S42_E_SYNTAX, 2, 8, 1);
  bad("%\nN1 X+R M02\n", S42_E_SYNTAX, 2, 6, 1);
  bad("%\nN1 X+R12 M02\n", S42_E_SYNTAX, 2, 8, 1);
  bad("%\nN1 X100+200 M02\n", S42_E_SYNTAX, 2, 8, 1);         /* D-19 */
  bad("%\nN1 X+R1+R2+R3 M02\n", S42_E_SYNTAX, 2, 11, 1);
  bad("%\nN1 X+R1-5 M02\n", S42_E_SYNTAX, 2, 8, 1);
  bad("%\nN1 X+R1+ M02\n", S42_E_SYNTAX, 2, 8, 1);
  bad("%\nN1 X12345678+R1 M02\n", S42_E_RANGE, 2, 4, 1);
}
END_TEST

/* ---- sec. 6: H repeats ---- */

START_TEST(h_repeats)
{
  struct trace t;
  ok_run(repeat_h, &t);   /* ex. 2: 11, 12, 13 x10, 14 */
  ck_assert_int_eq(t.last, VM_EV_END);
  ck_assert_str_eq(seq(&t), "11 12 13 13 13 13 13 13 13 13 13 13 14");
  struct uprog u;
  ok(&u, repeat_h);
  ck_assert_uint_eq(u22_attr(&u.p, 1)->h, 11);
  ck_assert_uint_eq(u22_attr(&u.p, 1)->hreg, U22_REG_H0);
  ck_assert_uint_eq(u22_attr(&u.p, 2)->hreg, U22_REG_H0);
  ck_assert_uint_eq(u22_attr(&u.p, 2)->m, 1u << UM20);
  ck_assert_uint_eq(u22_attr(&u.p, 0)->h, 0);
  ufree(&u);
  /* H0 skips its range; H1 runs it once */
  ok_run("%\nN1 H0\nN2 X1\nN3 M20\nN4 H1\nN5 X2\nN6 M20\nN7 M02\n", &t);
  ck_assert_str_eq(seq(&t), "1 4 5 6 7");
  /* two levels */
  ok_run("%\nN1 H2\nN2 X1 H3\nN3 X2\nN4 M20\nN5 Z1 M20\nN6 M02\n", &t);
  ck_assert_str_eq(seq(&t), "1 2 3 4 3 4 3 4 5 2 3 4 3 4 3 4 5 6");
  /* an inner range of one block (its M20 alone) and H0 inside a repeat */
  ok_run("%\nN1 H2\nN2 H0\nN3 M20\nN4 M20\nN5 M02\n", &t);
  ck_assert_str_eq(seq(&t), "1 2 4 2 4 5");
  /* a sub with its own repeat called inside a repeat: each has its counter */
  ok_run("%\nN1 H2\nN2 L01\nN3 M20\nN4 M02\nN01001 H3\nN01002 X1 M20\nN01003 M17\n", &t);
  ck_assert_str_eq(seq(&t), "1 2 1001 1002 1002 1002 1003 3 2 1001 1002 1002 1002 1003 3 4");
  ok(&u, "%\nN1 H2\nN2 L01\nN3 M20\nN4 M02\nN01001 H3\nN01002 X1 M20\nN01003 M17\n");
  ck_assert_uint_ne(u22_attr(&u.p, 4)->hreg, U22_REG_H0);
  ck_assert_uint_ne(u22_attr(&u.p, 4)->hreg, U22_REG_H0 + 1);
  ufree(&u);
  /* a call in the H block and in the M20 block */
  ok_run("%\nN1 H2 L01\nN2 X1 M20 L0102\nN3 M02\nN01001 X1 M17\n", &t);
  ck_assert_str_eq(seq(&t), "1 1001 2 1001 1001 2 1001 1001 3");
  ok_run("%\nN1 H0 L01\nN2 X1 M20\nN3 M02\nN01001 X1 M17\n", &t);
  ck_assert_str_eq(seq(&t), "1 1001 3");
  /* H9999 */
  ok_run("%\nN1 H9999\nN2 M20\nN3 M02\n", &t);
  ck_assert_int_eq(t.last, VM_EV_ERROR);    /* the budget of 10000 blocks */
  ck_assert_int_eq(t.err, S42_E_LIMIT);
}
END_TEST

START_TEST(h_structure)
{
  bad("%\nN1 M20\nN2 M02\n", S42_E_SUB, 2, 4, 1);                              /* D-12 */
  bad("%\nN1 H2\nN2 X1\nN3 M02\n", S42_E_SUB, 2, 4, 1);
  bad("%\nN1 H2 M02\n", S42_E_SUB, 2, 4, 1);
  bad("%\nN1 H2\nN2 M20 M02\n", S42_E_SUB, 3, 4, 2);
  bad("%\nN1 H2\nN2 H3 M20\nN3 M20\nN4 M02\n", S42_E_SUB, 3, 4, 2);
  bad("%\nN1 H1\nN2 H1\nN3 H1\nN4 M20\nN5 M20\nN6 M20\nN7 M02\n", S42_E_NEST, 4, 4, 3);   /* D-28 */
  bad("%\nN1 L01\nN2 M02\nN01001 H2\nN01002 M17\n", S42_E_SUB, 4, 8, 1001);
  bad("%\nN1 L01\nN2 M02\nN01001 H2\nN01002 M20 M17\n", S42_E_SUB, 5, 8, 1002);
  bad("%\nN1 H2\nN2 M02\nN01001 M20\nN01002 M17\n", S42_E_SUB, 2, 4, 1);        /* a range does not cross units */
  struct uprog u;
  /* two levels in the main program and two more in a sub: counted apart (D-28) */
  ok(&u, "%\nN1 H2\nN2 H2\nN3 L01\nN4 M20\nN5 M20\nN6 M02\nN01001 H2\nN01002 H2\nN01003 M20\nN01004 M20\nN01005 M17\n");
  ufree(&u);
}
END_TEST

/* ---- sec. 6: subprograms ---- */

START_TEST(sub_calls)
{
  struct trace t;
  ok_run(sub_l02, &t);   /* ex. 3 */
  ck_assert_int_eq(t.last, VM_EV_END);
  ck_assert_str_eq(seq(&t), "101 102 103 2001 2002 2003 2004 104");
  for (int i = 0; i < t.n; i++)
    ck_assert_int_eq(t.r[i].depth, t.r[i].n >= 2001 && t.r[i].n <= 2004);
  struct uprog u;
  ok(&u, sub_l02);
  ck_assert_uint_eq(u22_attr(&u.p, 2)->sub, 2);
  ck_assert_uint_eq(u22_attr(&u.p, 2)->runs, 1);
  ck_assert_uint_eq(u.p.blocks[4].unit, 1);
  ck_assert_uint_eq(u.p.blocks[3].unit, 0);
  ufree(&u);
  /* L ss rr: rr runs; 00 none (D-16) */
  ok_run("%\nN1 L1203\nN2 L1200\nN3 M30\nN12001 X1\nN12002 M17\n", &t);
  ck_assert_str_eq(seq(&t), "1 12001 12002 12001 12002 12001 12002 2 3");
  ok(&u, "%\nN1 L1203\nN2 L1200\nN3 M30\nN12001 X1\nN12002 M17\n");
  ck_assert_uint_eq(u22_attr(&u.p, 0)->runs, 3);
  ck_assert_uint_eq(u22_attr(&u.p, 1)->runs, 0);
  ufree(&u);
  /* two levels; the second sub's words, then the call */
  ok_run("%\nN1 L01\nN2 M02\nN01001 X5 L0202 M17\nN02001 X+R1 R1+1 M17\n", &t);
  ck_assert_str_eq(seq(&t), "1 1001 2001 2001 2");
  ck_assert_int_eq(t.r[2].depth, 2);
  ck_assert(t.r[1].w[U22_X] == 5 && t.r[2].w[U22_X] == 1 && t.r[3].w[U22_X] == 1);   /* R1+1 sets R1 to 1 */
  /* subs in any order, the main program calls several; N99999 */
  ok_run("%\nN1 L99\nN2 L03\nN3 M02\nN03001 M17\nN99001 M17\n", &t);
  ck_assert_str_eq(seq(&t), "1 99001 2 3001 3");
  /* the call comes after the block's own words, END after the call */
  ok_run("%\nN1 L05 M02\nN05001 X1 M17\n", &t);
  ck_assert_str_eq(seq(&t), "1 5001");
  ck_assert_int_eq(t.last, VM_EV_END);
}
END_TEST

START_TEST(sub_structure)
{
  bad("%\nN1 L00\nN2 M02\n", S42_E_RANGE, 2, 4, 1);                  /* D-27 */
  bad("%\nN1 L0003\nN2 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 L1\nN2 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 L123\nN2 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 L12345\nN2 M02\n", S42_E_RANGE, 2, 4, 1);
  bad("%\nN1 L05\nN2 M02\n", S42_E_TARGET, 2, 4, 1);                 /* D-14 */
  bad("%\nN1 L0500\nN2 M02\n", S42_E_TARGET, 2, 4, 1);
  bad("%\nN1 M17\nN2 M02\n", S42_E_SUB, 2, 4, 1);
  bad("%\nN1 X1\nN2 X2\n", S42_E_SUB, 3, 1, 2);                       /* no M02/M30 (L498) */
  bad("%\nN1 X1\nN02001 M17\n", S42_E_SUB, 3, 8, 2001);   /* M17 in the main program */
  bad("%\nN1 L02\nN2 M02\nN2001 X1 M17\n", S42_E_SUB, 4, 1, 2001);     /* D-29 */
  bad("%\nN1 L02\nN2 M02\n:02001 X1 M17\n", S42_E_SUB, 4, 1, 2001);
  bad("%\nN1 L02\nN2 M02\nN02001 X1\n", S42_E_SUB, 4, 1, 2001);       /* no M17 */
  bad("%\nN1 L02\nN2 M02\nN02001 X1\nN03001 M17\n", S42_E_SUB, 5, 1, 3001);
  bad("%\nN1 L02\nN2 M02\nN02001 M02\n", S42_E_SUB, 4, 8, 2001);
  bad("%\nN1 L02\nN2 M02\nN02001 M17\nN02002 M17\n", S42_E_TARGET, 5, 1, 2002);
  bad("%\nN1 M02\nN00001 M17\n", S42_E_SUB, 3, 1, 1);
  /* a third level literally in the text (D-28) */
  bad("%\nN1 L01\nN2 M02\nN01001 L02 M17\nN02001 L03 M17\nN03001 X1 M17\n", S42_E_NEST, 5, 8, 2001);
  bad("%\nN1 L01\nN2 M02\nN01001 L01 M17\n", S42_E_NEST, 4, 8, 1001);
  /* a sub never called may call as it likes; a call of no runs does not nest */
  struct uprog u;
  ok(&u, "%\nN1 L01\nN2 M02\nN01001 L02 M17\nN02001 L0300 M17\nN03001 L01 M17\n");
  ufree(&u);
}
END_TEST

START_TEST(skip_blocks)
{
  struct uprog u;
  ok(&u, "%\n/N1 X1\nN2 H2\n/N3 L01\n/:4 X2\nN5 M20\nN6 M02\nN01001 X1\n/N01002 X2\nN01003 M17\n");
  ck_assert_uint_eq(u22_attr(&u.p, 0)->skip, 1);
  ck_assert_uint_eq(u22_attr(&u.p, 2)->skip, 1);
  ck_assert_uint_eq(u22_attr(&u.p, 4)->skip, 0);
  ufree(&u);
  bad("%\n/N1 H2\nN2 M20\nN3 M02\n", S42_E_SYNTAX, 2, 1, 1);
  bad("%\nN1 H2\n/N2 M20\nN3 M02\n", S42_E_SYNTAX, 3, 1, 2);
  bad("%\n/N1 M02\n", S42_E_SYNTAX, 2, 1, 1);
  bad("%\n/N1 M30\n", S42_E_SYNTAX, 2, 1, 1);
  bad("%\nN1 L01\nN2 M02\n/N01001 M17\n", S42_E_SYNTAX, 4, 1, 1001);
  bad("%\nN1 X1 / N2 M02\n", S42_E_SYNTAX, 2, 7, 1);
}
END_TEST

START_TEST(bytecode_shape)
{
  /* every block yields (MACH) and commits; the program verifies and records its stack */
  const char *const ex[] = {fig1_9, lin_abs_inc, params_r, repeat_h, sub_l02};
  for (size_t i = 0; i < sizeof ex / sizeof ex[0]; i++) {
    struct uprog u;
    ok(&u, ex[i]);
    for (size_t b = 0; b < u.p.nblocks; b++) {
      uint32_t from = u.p.blocks[b].code, to = b + 1 < u.p.nblocks ? u.p.blocks[b + 1].code : (uint32_t)u.p.ncode;
      int mach = 0;
      for (uint32_t pc = from; pc < to; pc++)
        mach += INS_OP(u.p.code[pc]) == OP_MACH;
      ck_assert_int_eq(mach, 1);
    }
    ck_assert_uint_ge(u.p.max_stack, 1);
    ufree(&u);
  }
}
END_TEST

START_TEST(diagnostics_name_the_block)
{
  struct uprog u;
  uc(&u, "%\nN12 G01 G02 M02\n");
  ck_assert_int_eq(u.rc, -1);
  ck_assert_int_eq(u.d.v[0].number, 12);
  ck_assert_msg(strstr(u.d.v[0].msg, "two G of group 1 (G01, G02)"), "%s", u.d.v[0].msg);
  ufree(&u);
  uc(&u, "%\nN1 X12345678\nN2 M02\n");
  ck_assert_msg(strstr(u.d.v[0].msg, "X: 8 digits, at most 7"), "%s", u.d.v[0].msg);
  ufree(&u);
  /* several errors, one a block, each reported */
  uc(&u, "%\nN1 G07\nN2 X1.5\nN3 M99\nN4 M02\n");
  ck_assert_uint_eq(tp_count(&u.d, DIAG_ERROR), 3);
  ufree(&u);
  /* one bad word does not hide the block's M02 (no cascade into the sub area) */
  uc(&u, "%\nN1 L01\nN2 G07 M02\nN01001 X1 M17\n");
  ck_assert_uint_eq(tp_count(&u.d, DIAG_ERROR), 1);
  ufree(&u);
  uc(&u, "%\nN1 L01\nN2 M02 (no end\nN01001 X1 M17\n");
  ck_assert_uint_eq(tp_count(&u.d, DIAG_ERROR), 1);
  ck_assert_int_eq(u.d.v[0].number, 2);
  ufree(&u);
  uc(&u, "%\nN1 L02\nN2 M02\nN2001 X1 M17\n");   /* a short N in the sub area: read on as sub 02 */
  ck_assert_uint_eq(tp_count(&u.d, DIAG_ERROR), 1);
  ufree(&u);
}
END_TEST

Suite *suite_u22(void)
{
  Suite *s = suite_create("u22");
  TCase *tc = tcase_create("u22");
  tcase_add_test(tc, registry_entry);
  tcase_add_test(tc, examples_compile);
  tcase_add_test(tc, text_start_and_leader);
  tcase_add_test(tc, text_end_marks_and_comments);
  tcase_add_test(tc, text_block_starts);
  tcase_add_test(tc, text_block_length);
  tcase_add_test(tc, text_lookalikes_and_case);
  tcase_add_test(tc, words_numbers);
  tcase_add_test(tc, words_repeats);
  tcase_add_test(tc, g_and_m_tables);
  tcase_add_test(tc, g_and_m_groups);
  tcase_add_test(tc, g25_and_g04);
  tcase_add_test(tc, params_evaluate);
  tcase_add_test(tc, params_refused);
  tcase_add_test(tc, h_repeats);
  tcase_add_test(tc, h_structure);
  tcase_add_test(tc, sub_calls);
  tcase_add_test(tc, sub_structure);
  tcase_add_test(tc, skip_blocks);
  tcase_add_test(tc, bytecode_shape);
  tcase_add_test(tc, diagnostics_name_the_block);
  suite_add_tcase(s, tc);
  return s;
}
