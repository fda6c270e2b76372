/* The VM (vm/vm.h) on compiled programs, driven directly: arithmetic,
 * functions and their domains, arrays, transactions, subs, limits, the
 * operational jump, watched blocks, and many VMs on one program; and on
 * hand-assembled programs, what the VM takes from the program -- the
 * limits, the message table, 32-bit block numbers -- and RETEND. */
#include "suites.h"
#include "ast.h"
#include "disasm.h"
#include "errors.h"
#include "kp.h"
#include "kpmsg.h"
#include "msgs.h"
#include "verify.h"
#include "vmmath.h"
#include "opcodes.h"
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static struct tprog t;
static struct vm *vm;
static struct program hp;   /* a hand-assembled program */

static void setup(void)
{
  memset(&t, 0, sizeof t);
  prog_init(&t.p);
  diag_init(&t.d, "t.kp");
  vm = calloc(1, sizeof *vm);
  prog_init(&hp);
}

static void teardown(void)
{
  tp_free(&t);
  free(vm);
  prog_free(&hp);
}

/* ---- hand assembly: hblock opens a block (its BLOCK), hemit adds an
 * instruction; each returns the pc of what it added ---- */

static uint32_t hemit(int op, uint32_t a)
{
  long pc = prog_emit(&hp, INS(op, a), 1);
  ck_assert_int_ge(pc, 0);
  return (uint32_t)pc;
}

static uint32_t hblock(uint32_t number, uint16_t unit)
{
  struct prog_block b = {.code = (uint32_t)hp.ncode, .line = (uint32_t)hp.nblocks + 1, .number = number, .col = 1,
                         .unit = unit};
  long i = prog_block_add(&hp, &b);
  ck_assert_int_ge(i, 0);
  return hemit(OP_BLOCK, (uint32_t)i);
}

/* The hand-assembled program, entered at entry, must verify; then a VM on it. */
static void hstart(uint32_t entry)
{
  char msg[300];
  uint32_t need;
  hp.entry = entry;
  hp.max_stack = VM_STACK;
  ck_assert_msg(prog_verify_need(&hp, &need, msg, sizeof msg) == 0, "%s", msg);
  hp.max_stack = need;
  ck_assert_msg(prog_verify(&hp, msg, sizeof msg) == 0, "%s", msg);
  ck_assert_int_eq(vm_init(vm, &hp), 0);
}

/* A sub of one block at pc 0 (block 0, number sub_n, unit 1) that adds 1 to
 * r1 and ends with `end`; the main program calls it `count` times, then
 * ends with main_end.  Returns the main program's entry. */
static uint32_t sub_and_main(int end, uint32_t count, int main_end)
{
  hblock(10, 1);
  hemit(OP_REG, 1);
  hemit(OP_ADDI, 1);
  hemit(OP_SETP, 1);
  hemit(OP_COMMIT, 0);
  hemit(end, 0);
  uint32_t entry = hblock(1, 0);
  hemit(OP_COMMIT, 0);
  hemit(OP_INT, count);
  hemit(OP_CALL, 0);
  hblock(2, 0);
  hemit(OP_COMMIT, 0);
  hemit(main_end, 0);
  return entry;
}

/* Compile (must succeed) and start a VM on it. */
static void load(const char *src)
{
  tp_free(&t);
  tp_compile(&t, src);
  ck_assert_msg(t.rc == 0, "does not compile:\n%s", tp_diags(&t.d));
  vm_init(vm, &t.p);
}

static enum vm_event run(const char *src)
{
  load(src);
  return tp_run(vm);
}

#define R(n) (vm->reg[(n)])

static void assert_error(int code, int number)
{
  ck_assert_msg(vm->err.code == code, "error %s (%s), expected %s", err_code(vm->err.code), vm->err.msg,
                err_code(code));
  ck_assert_uint_eq(vm_block_number(vm, vm->err.block), (unsigned)number);
}

/* ---- arithmetic ---- */

START_TEST(seed_expression_1)
{
  ck_assert_int_eq(run("N1 R0+10000 R1-200 G01 X+20100-R0/R1 R2+X F1\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(2), 20150);
  ck_assert_double_eq(R(1), -200);
}
END_TEST

START_TEST(seed_expression_2)
{
  ck_assert_int_eq(run("N1 R10+30000\nN2 X+600%SI(20000) Y+800%CO(20000)/TG(R10) R1+X R2+Y F1\nN3 M2\n"),
                   VM_EV_END);
  ck_assert_double_eq(R(1), 205);
  ck_assert_double_eq(R(2), 1302);
}
END_TEST

START_TEST(seed_expression_3)
{
  ck_assert_int_eq(run("N1 R1+100 R2+200 R3+50 G01 A+20%ASI(R1/R2) X-1000%R3 R4+A R5+X F1\nN2 M2\n"),
                   VM_EV_END);
  ck_assert_double_eq(R(4), 600000);
  ck_assert_double_eq(R(5), -50000);
}
END_TEST

START_TEST(seed_expression_garbled_asi)
{
  /* language.md 19.5: R0 = 1/(2 P1), A = -10 ASI(R0) = -91578.51 -> -91579 */
  ck_assert_int_eq(run("N1 R0+1/(2%P1) A-10%ASI(R0) R1+A F1\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), -91579);
}
END_TEST

START_TEST(parameters_keep_reals)
{
  ck_assert_int_eq(run("N1 R1+1/2 R2+R1+R1 R3-R1%%2\nN2 R4+R3%4 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 0.5);
  ck_assert_double_eq(R(2), 1);
  ck_assert_double_eq(R(3), -0.25);
  ck_assert_double_eq(R(4), -1);
}
END_TEST

START_TEST(sign_rules_at_run_time)
{
  ck_assert_int_eq(run("N1 R1+2 R8-R1%%2 R9+5%-R1%%2 R10+(R1+1)%%R1\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(8), -4);
  ck_assert_double_eq(R(9), -20);
  ck_assert_double_eq(R(10), 9);
}
END_TEST

START_TEST(axis_rounds_half_away_from_zero)
{
  ck_assert_int_eq(run("N1 R1+5/2 X+R1 Y-R1 Z+R1-1/10 R2+X R3+Y R4+Z F1\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(2), 3);
  ck_assert_double_eq(R(3), -3);
  ck_assert_double_eq(R(4), 2);
}
END_TEST

START_TEST(assignments_left_to_right)
{
  ck_assert_int_eq(run("N1 R1+1 R2+R1+1 R1+R2+R1 R3+R1\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(3), 3);
}
END_TEST

START_TEST(condition_sees_later_words)
{
  /* the condition is evaluated after every word of the block */
  ck_assert_int_eq(run("N1 P(X:R:5)3 X+5 F1\nN2 M2\nN3 R1+1 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 1);
}
END_TEST

START_TEST(conditions_and_or)
{
  const char *src =
    "N1 P(((R1:R:0) S (R2:R:0)) U (R3:M:1000))5\n"
    "N2 R9+2 M2\n"
    "N5 R9+5 M2\n";
  load(src);
  vm->reg[1] = 1; vm->reg[2] = 0; vm->reg[3] = 999;
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(9), 5);
  vm_init(vm, &t.p);
  vm->reg[1] = 1; vm->reg[2] = 1; vm->reg[3] = 999;
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(9), 2);
  vm_init(vm, &t.p);
  vm->reg[1] = 0; vm->reg[2] = 1; vm->reg[3] = 1000;
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(9), 2);
}
END_TEST

START_TEST(relations_with_tolerance)
{
  ck_assert(vm_rel(1.0, 1.0 + 1e-10, 2));
  ck_assert(!vm_rel(1.0, 1.0 + 1e-10, 4));
  ck_assert(!vm_rel(1.0, 1.0 + 1e-10, 1));
  ck_assert(vm_rel(1e6, 1e6 + 1e-4, 2));
  ck_assert(vm_rel(0.0, 1e-8, 1));
  ck_assert(!vm_rel(0.0, 1e-8, 2));
  ck_assert(vm_rel(5, 3, 4) && vm_rel(5, 3, 6) && vm_rel(5, 3, 5) && vm_rel(5, 3, 7));
  ck_assert(!vm_rel(5, 3, 0) && !vm_rel(5, 5, 5) && vm_rel(5, 5, 3));
}
END_TEST

START_TEST(one_third_times_three_equals_one)
{
  ck_assert_int_eq(run("N1 R1+1/3 R2+R1+R1+R1 P(R2:R:1)3\nN2 M2\nN3 R3+1 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(3), 1);
}
END_TEST

START_TEST(m20_integer_part)
{
  ck_assert_int_eq(run("N1 R1+7/2 R2-7/2 R3+7/2 M20/R1R2/\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 3);
  ck_assert_double_eq(R(2), -3);
  ck_assert_double_eq(R(3), 3.5);
}
END_TEST

/* ---- functions and their domains ---- */

START_TEST(functions_values)
{
  ck_assert_int_eq(run("N1 R0+30000 R1+SI(R0) R2+CO(R0%2) R3+TG(R0+15000) R4+ASI(R1) R5+ACO(R2) "
                       "R6+ATG(R3) R7+LO(R0)\nN2 M2\n"), VM_EV_END);
  ck_near(R(1), 0.5, 1e-15);
  ck_near(R(2), 0.5, 1e-15);
  ck_near(R(3), 1, 1e-15);
  ck_near(R(4), 30000, 1e-9);
  ck_near(R(5), 60000, 1e-9);
  ck_near(R(6), 45000, 1e-9);
  ck_near(R(7), log(30000), 1e-15);
}
END_TEST

START_TEST(domain_asi)
{
  ck_assert_int_eq(run("N1 R1+2\nN2 R2+5 R3+ASI(R1)\nN3 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_DOMAIN, 2);
  ck_assert_uint_eq(vm->err.col, 12);
  ck_assert_double_eq(R(2), 0);        /* rolled back */
  ck_assert_uint_eq(vm->blocks, 1);
}
END_TEST

START_TEST(domain_log)
{
  ck_assert_int_eq(run("N1 R1+LO(R0)\nN2 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_DOMAIN, 1);
  ck_assert_int_eq(run("N1 R0-1 R1+LO(R0)\nN2 M2\n"), VM_EV_ERROR);
  ck_assert_int_eq(run("N1 R0+9999999 R1+LO(R0)\nN2 M2\n"), VM_EV_END);
}
END_TEST

START_TEST(domain_trig)
{
  ck_assert_int_eq(run("N1 R0+2304001 R1+SI(R0)\nN2 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_DOMAIN, 1);
  ck_assert_int_eq(run("N1 R0-2304000 R1+CO(R0)\nN2 M2\n"), VM_EV_END);
  ck_near(R(1), cos(144 * M_PI / 180), 1e-12);   /* -2304 deg = -6 turns - 144 */
  ck_assert_int_eq(run("N1 R0+90000 R1+TG(R0)\nN2 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_DOMAIN, 1);
  ck_assert_int_eq(run("N1 R0-270000 R1+TG(R0)\nN2 M2\n"), VM_EV_ERROR);
  ck_assert_int_eq(run("N1 R0+180000 R1+TG(R0)\nN2 M2\n"), VM_EV_END);
  ck_near(R(1), 0, 1e-12);
  ck_assert_int_eq(run("N1 R0+90001 R1+TG(R0)\nN2 M2\n"), VM_EV_END);
}
END_TEST

START_TEST(domain_acos_atan)
{
  ck_assert_int_eq(run("N1 R0-11/10 R1+ACO(R0)\nN2 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_DOMAIN, 1);
  ck_assert_int_eq(run("N1 R0+9999999 R1+ATG(R0+1)\nN2 M2\n"), VM_EV_ERROR);
  ck_assert_int_eq(run("N1 R0-9999999 R1+ATG(R0)\nN2 M2\n"), VM_EV_END);
  ck_near(R(1), -90000, 0.01);
}
END_TEST

START_TEST(div0_at_run_time)
{
  ck_assert_int_eq(run("N1 R1+5\nN2 R2+1 R3+R2/R0\nN3 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_DIV0, 2);
  ck_assert_uint_eq(vm->err.col, 14);
  ck_assert_double_eq(R(1), 5);
  ck_assert_double_eq(R(2), 0);
  ck_assert_uint_eq(vm->blocks, 1);
}
END_TEST

START_TEST(power_domain)
{
  ck_assert_int_eq(run("N1 R1-4 R2+R1%%(1/2)\nN2 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_DOMAIN, 1);
  ck_assert_int_eq(run("N1 R1-2 R2+R1%%3\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(2), -8);
}
END_TEST

START_TEST(range_at_run_time)
{
  ck_assert_int_eq(run("N1 R1+9999999\nN2 R2+R1+1\nN3 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_RANGE, 2);
  ck_assert_int_eq(run("N1 R1+999999\nN2 X+R1+1 F1\nN3 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_RANGE, 2);
  ck_assert_uint_eq(vm->err.col, 4);
}
END_TEST

/* The superinstructions (ADDI, DIVI, MULR, SETP...) fail exactly as the
 * instructions they replace did: code, message and column. */
START_TEST(superinstructions_same_errors)
{
  ck_assert_int_eq(run("N1 R1+5\nN2 R2+R1/0\nN3 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_DIV0, 2);
  ck_assert_str_eq(vm->err.msg, "division of 5 by zero");
  ck_assert_uint_eq(vm->err.col, 9);
  ck_assert_int_eq(run("N1 R1+9999999\nN2 R2+R1+1\nN3 M2\n"), VM_EV_ERROR);
  ck_assert_str_eq(vm->err.msg, "R2 = 10000000 is outside -9999999..9999999");
  ck_assert_uint_eq(vm->err.col, 4);
  ck_assert_int_eq(run("N1 R1+9999999\nN2 R2+R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1"
                       "%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1%R1\nN3 M2\n"),
                   VM_EV_ERROR);
  assert_error(S42_E_RANGE, 2);
  ck_assert_msg(strncmp(vm->err.msg, "intermediate result too large", 29) == 0, "%s", vm->err.msg);
  /* a loop through CMPC and CJCOND, with a jump back through CJMP */
  ck_assert_int_eq(run("N1 R1+0\nN2 R1+R1+1 P(R1:M:10)2\nN3 R2+R2-1/2 P4\nN4 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 10);
  ck_assert_double_eq(R(2), -0.5);
  ck_assert_uint_eq(vm->blocks, 13);
  /* the same against a register (CMPCR) and a fractional constant (CMPCK),
   * with the tolerance of equality kept */
  ck_assert_int_eq(run("N1 R3+7 R1+0\nN2 R1+R1+1 P(R1:M:R3)2\nN3 R4+1/10+2/10 P(R4:R:3/10)5\nN4 R5+1\nN5 M2\n"),
                   VM_EV_END);
  ck_assert_double_eq(R(1), 7);
  ck_assert_double_eq(R(5), 0);
}
END_TEST

/* ---- the register forms (src/dialect/2c42/peep.c) against their parts ---- */

/* One block of code (op, operand, column each), COMMIT and END, run on a VM
 * whose registers r1..r3 are a, b, d: what it ended with. */
struct outcome { enum vm_event ev; int code; unsigned col; char msg[200]; double reg[4]; uint8_t jflag; };

static struct outcome run_code(const uint32_t (*ins)[3], int n, double a, double b, double lo, double hi)
{
  struct program p;
  struct vm *v = calloc(1, sizeof *v);
  struct outcome o;
  char msg[300];
  prog_init(&p);
  p.lim.param_lo = lo;
  p.lim.param_hi = hi;
  p.lim.angle = 0.001;
  p.lim.trig_max = 2304000;
  static const double ks[] = {0, 2.5, 1e308, -7, 3, 0.5};
  for (size_t i = 0; i < sizeof ks / sizeof *ks; i++)
    prog_consts(&p, &ks[i], 1);
  double kt[3] = {1000000};
  vm_rel_bounds(kt[0], &kt[1], &kt[2]);
  prog_consts(&p, kt, 3);   /* K[6..8]: CMPRK's */
  struct prog_block bl = {.code = 0, .line = 1, .number = 1, .col = 1};
  prog_block_add(&p, &bl);
  prog_emit(&p, INS(OP_BLOCK, 0), 1);
  for (int i = 0; i < n; i++)
    prog_emit(&p, INS(ins[i][0], ins[i][1]), ins[i][2]);
  prog_emit(&p, INS(OP_COMMIT, 0), 90);
  prog_emit(&p, INS(OP_END, 0), 91);
  p.max_stack = VM_STACK;
  ck_assert_msg(prog_verify(&p, msg, sizeof msg) == 0, "%s", msg);
  ck_assert_int_eq(vm_init(v, &p), 0);
  v->reg[1] = a;
  v->reg[2] = b;
  v->reg[3] = -1;
  memset(&o, 0, sizeof o);
  o.ev = vm_run(v);
  o.code = v->err.code;
  o.col = v->err.col;
  snprintf(o.msg, sizeof o.msg, "%s", v->err.msg);
  memcpy(o.reg, v->reg, sizeof o.reg);
  o.jflag = v->jflag;
  free(v);
  prog_free(&p);
  return o;
}

static void same_outcome(const struct outcome *x, const struct outcome *y, const char *what, double a, double b)
{
  ck_assert_msg(x->ev == y->ev && x->code == y->code && x->col == y->col && strcmp(x->msg, y->msg) == 0 &&
                  memcmp(x->reg, y->reg, sizeof x->reg) == 0 && x->jflag == y->jflag,
                "%s with r1 = %g, r2 = %g: the parts give event %d, %d at column %u \"%s\", r3 = %g, jflag %d; "
                "the fused form event %d, %d at column %u \"%s\", r3 = %g, jflag %d",
                what, a, b, x->ev, x->code, x->col, x->msg, x->reg[3], x->jflag, y->ev, y->code, y->col, y->msg,
                y->reg[3], y->jflag);
}

/* RSINCOS and RCOSSIN take both values from one sincos: that it gives
 * exactly sin's and cos's results is the C library's, so it is checked
 * here over every 7th 0.001-degree angle of the 2С42's range (and the half
 * steps beside them, in radians as the VM computes them), random doubles
 * of that range and random bit patterns. */
START_TEST(sincos_is_sin_and_cos)
{
  double (*volatile fs)(double) = sin, (*volatile fc)(double) = cos;   /* no folding into sincos */
  const double rad = 0.001 * (M_PI / 180.0);
  uint64_t x = 88172645463325252ULL;
  long differ = 0, n = 0;
  for (long i = -2304000; i <= 2304000 + 2000000; i += 7) {
    double arg;
    if (i <= 2304000)
      arg = (i % 2 ? i + 0.5 : i) * rad;
    else {
      x ^= x << 13, x ^= x >> 7, x ^= x << 17;
      uint64_t bits = x;
      if (i % 2)
        memcpy(&arg, &bits, sizeof arg);   /* any double */
      else
        arg = ((double)(bits >> 11) / 9007199254740992.0 * 2 - 1) * 2304000 * rad;
    }
    double s, c, s1 = fs(arg), c1 = fc(arg);
    sincos(arg, &s, &c);
    n++;
    if (memcmp(&s, &s1, sizeof s) != 0 || memcmp(&c, &c1, sizeof c) != 0) {
      if (differ++ < 3)
        fprintf(stderr, "sincos(%a) = %a, %a; sin, cos = %a, %a\n", arg, s, c, s1, c1);
    }
  }
  ck_assert_msg(differ == 0, "sincos differs from sin and cos for %ld of %ld arguments", differ, n);
}
END_TEST

START_TEST(register_forms_as_their_parts)
{
  static const double vals[] = {5, 0, -3, 0.5, 9999999, -9999999, 1e308, -1e308, INFINITY, -INFINITY, NAN,
                                1000000, 999999.999, 1000000.001, 999999.99, 1e-300};
  static const int base[4] = {OP_ADD, OP_SUB, OP_MUL, OP_DIV};
  static const int withx[3][4] = {{OP_ADDI, OP_SUBI, OP_MULI, OP_DIVI}, {OP_ADDK, OP_SUBK, OP_MULK, OP_DIVK},
                                  {OP_ADDR, OP_SUBR, OP_MULR, OP_DIVR}};
  static const int rpush[3][4] = {{OP_RADDI, OP_RSUBI, OP_RMULI, OP_RDIVI}, {OP_RADDK, OP_RSUBK, OP_RMULK, OP_RDIVK},
                                  {OP_RADDR, OP_RSUBR, OP_RMULR, OP_RDIVR}};
  static const int xstore[3][4] = {{OP_ADDIP, OP_SUBIP, OP_MULIP, OP_DIVIP},
                                   {OP_ADDKP, OP_SUBKP, OP_MULKP, OP_DIVKP},
                                   {OP_ADDRP, OP_SUBRP, OP_MULRP, OP_DIVRP}};
  static const int rstore[3][4] = {{OP_RADDIP, OP_RSUBIP, OP_RMULIP, OP_RDIVIP},
                                   {OP_RADDKP, OP_RSUBKP, OP_RMULKP, OP_RDIVKP},
                                   {OP_RADDRP, OP_RSUBRP, OP_RMULRP, OP_RDIVRP}};
  static const uint32_t xs[3][3] = {{0, 3, 131071}, {0, 1, 2}, {2, 1, 3}};   /* integers, constants, registers */
  static const double ranges[3][2] = {{-9999999, 9999999}, {-DBL_MAX, DBL_MAX}, {-INFINITY, INFINITY}};
  int n = sizeof vals / sizeof *vals;
  for (int rg = 0; rg < 3; rg++)
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) {
        double a = vals[i], b = vals[j], lo = ranges[rg][0], hi = ranges[rg][1];
        for (int op = 0; op < 4; op++) {
          /* ADD; SETP against ADDP */
          uint32_t u0[4][3] = {{OP_REG, 1, 10}, {OP_REG, 2, 15}, {(uint32_t)base[op], 0, 20}, {OP_SETP, 3, 30}};
          uint32_t f0[4][3] = {{OP_REG, 1, 10}, {OP_REG, 2, 15}, {OP_ADDP + (uint32_t)op, 0, 20}, {OP_EXT, 3, 30}};
          struct outcome x = run_code(u0, 4, a, b, lo, hi), y = run_code(f0, 4, a, b, lo, hi);
          same_outcome(&x, &y, vm_ops[OP_ADDP + op].name, a, b);
          for (int kind = 0; kind < 3; kind++)
            for (int xi = 0; xi < 3; xi++) {
              uint32_t xv = xs[kind][xi];
              uint32_t u[3][3] = {{OP_REG, 1, 10}, {(uint32_t)withx[kind][op], xv, 20}, {OP_SETP, 3, 30}};
              uint32_t fp[2][3] = {{(uint32_t)rpush[kind][op], 1 | xv << 7, 20}, {OP_SETP, 3, 30}};
              uint32_t fx[3][3] = {{OP_REG, 1, 10}, {(uint32_t)xstore[kind][op], xv, 20}, {OP_EXT, 3, 30}};
              uint32_t fr[2][3] = {{(uint32_t)rstore[kind][op], 1 | xv << 7, 20}, {OP_EXT, 3, 30}};
              x = run_code(u, 3, a, b, lo, hi);
              y = run_code(fp, 2, a, b, lo, hi);
              same_outcome(&x, &y, vm_ops[rpush[kind][op]].name, a, b);
              y = run_code(fx, 3, a, b, lo, hi);
              same_outcome(&x, &y, vm_ops[xstore[kind][op]].name, a, b);
              y = run_code(fr, 2, a, b, lo, hi);
              same_outcome(&x, &y, vm_ops[rstore[kind][op]].name, a, b);
            }
        }
      }
  /* RSIN, RCOS against REG; SIN and REG; COS, in their domain and out */
  static const double angles[] = {0, 30000, -45000, 2304000, -2304000, 2304001, 1e308, INFINITY, NAN, 1234.5};
  for (size_t i = 0; i < sizeof angles / sizeof *angles; i++)
    for (int c = 0; c < 2; c++) {
      uint32_t u[3][3] = {{OP_REG, 1, 10}, {c ? OP_COS : OP_SIN, 0, 20}, {OP_SETP, 3, 30}};
      uint32_t f[2][3] = {{c ? OP_RCOS : OP_RSIN, 1, 20}, {OP_SETP, 3, 30}};
      struct outcome x = run_code(u, 3, angles[i], 0, -9999999, 9999999), y = run_code(f, 2, angles[i], 0, -9999999, 9999999);
      same_outcome(&x, &y, c ? "RCOS" : "RSIN", angles[i], 0);
      /* RSINCOS, RCOSSIN against REG; SIN; REG; COS and the other way:
       * both values (their difference, stored: a sum would hide a swap) */
      uint32_t u2[6][3] = {{OP_REG, 1, 10}, {c ? OP_COS : OP_SIN, 0, 20}, {OP_REG, 1, 25},
                           {c ? OP_SIN : OP_COS, 0, 30}, {OP_SUB, 0, 35}, {OP_SETP, 3, 40}};
      uint32_t f2[3][3] = {{c ? OP_RCOSSIN : OP_RSINCOS, 1, 20}, {OP_SUB, 0, 35}, {OP_SETP, 3, 40}};
      x = run_code(u2, 6, angles[i], 0, -9999999, 9999999);
      y = run_code(f2, 3, angles[i], 0, -9999999, 9999999);
      same_outcome(&x, &y, c ? "RCOSSIN" : "RSINCOS", angles[i], 0);
    }
  /* the functions with their store against FN; SETP (ASIN of values out
   * of its domain, results out of a narrow parameter range) */
  static const int fns[5][2] = {{OP_SIN, OP_SINP}, {OP_COS, OP_COSP}, {OP_ASIN, OP_ASINP}, {OP_ACOS, OP_ACOSP},
                                {OP_ATAN, OP_ATANP}};
  static const double args[] = {0, 0.5, -1, 1, 1.5, 30000, 2304001, 1e7, INFINITY, NAN};
  for (int fn = 0; fn < 5; fn++)
    for (size_t i = 0; i < sizeof args / sizeof *args; i++)
      for (int rg = 0; rg < 2; rg++) {
        double lo = rg ? -0.25 : -9999999, hi = rg ? 0.25 : 9999999;
        uint32_t u[3][3] = {{OP_REG, 1, 10}, {(uint32_t)fns[fn][0], 0, 20}, {OP_SETP, 3, 30}};
        uint32_t f[3][3] = {{OP_REG, 1, 10}, {(uint32_t)fns[fn][1], 0, 20}, {OP_EXT, 3, 30}};
        struct outcome x = run_code(u, 3, args[i], 0, lo, hi), y = run_code(f, 3, args[i], 0, lo, hi);
        same_outcome(&x, &y, vm_ops[fns[fn][1]].name, args[i], 0);
      }
  /* CMPRK against REG; CMPCK, every relation, near its constant and far */
  for (uint32_t rel = 0; rel < 8; rel++)
    for (int i = 0; i < n; i++) {
      uint32_t u[2][3] = {{OP_REG, 1, 10}, {OP_CMPCK, rel | 6 << 3, 20}};
      uint32_t f[2][3] = {{OP_CMPRK, rel | 1 << 3, 20}, {OP_EXT, 6, 20}};
      struct outcome x = run_code(u, 2, vals[i], 0, -DBL_MAX, DBL_MAX), y = run_code(f, 2, vals[i], 0, -DBL_MAX, DBL_MAX);
      same_outcome(&x, &y, "CMPRK", vals[i], 0);
      /* a walk through the tolerance band, one ulp at a time near its edges */
      double lo, hi;
      vm_rel_bounds(1000000, &lo, &hi);
      double edges[] = {lo, hi, 1000000 - 1e-3, 1000000 + 1e-3, 1000000 - 2e-3, 1000000 + 2e-3};
      for (size_t e = 0; e < sizeof edges / sizeof *edges; e++) {
        double v = edges[e];
        for (int s = 0; s < 8; s++, v = nextafter(v, -INFINITY)) {
          x = run_code(u, 2, v, 0, -DBL_MAX, DBL_MAX);
          y = run_code(f, 2, v, 0, -DBL_MAX, DBL_MAX);
          same_outcome(&x, &y, "CMPRK", v, 0);
        }
      }
    }
}
END_TEST

/* vm_rel_bounds: outside the bounds the tolerant compare is plainly < or >,
 * for constants of every size (the proof in vm/vmmath.h, sampled). */
START_TEST(rel_bounds_hold)
{
  static const double bs[] = {0, 1, -1, 0.5, 1e-12, 1000000, -9999999, 123456.789, 1e15, -1e300, DBL_MAX, -DBL_MAX};
  for (size_t i = 0; i < sizeof bs / sizeof *bs; i++) {
    double b = bs[i], lo, hi;
    vm_rel_bounds(b, &lo, &hi);
    ck_assert(lo < b && b < hi);
    /* near +-DBL_MAX a bound overflows to an infinity: no finite number is
     * beyond it, so the fast path never applies there */
    double v = lo;
    for (int s = 0; s < 64 && isfinite(v); s++, v = nextafter(v, -INFINITY))
      ck_assert_msg(vm_rel_got(v, b) == 1, "%.17g vs %.17g", v, b);
    v = hi;
    for (int s = 0; s < 64 && isfinite(v); s++, v = nextafter(v, INFINITY))
      ck_assert_msg(vm_rel_got(v, b) == 4, "%.17g vs %.17g", v, b);
    for (double f = 2; f < 1e300; f *= 1e10) {
      ck_assert(vm_rel_got(lo - f * fabs(lo) - f, b) == 1 || !isfinite(lo - f * fabs(lo) - f));
      ck_assert(vm_rel_got(hi + f * fabs(hi) + f, b) == 4 || !isfinite(hi + f * fabs(hi) + f));
    }
  }
}
END_TEST

START_TEST(feed_clamped_at_run_time)
{
  load("N1 R1+7000 F+R1 X+1\nN2 M2\n");
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);
  ck_assert_double_eq(R(REG_F), 6000);
  ck_assert_uint_ne(vm->clamped, 0);
  ck_assert_double_eq(vm->clamped_from, 7000);
  ck_assert_str_eq(t.p.rules[vm->clamped - 1].name, "F");
}
END_TEST

/* ---- arrays ---- */

START_TEST(seed_array_reamer)
{
  load("№1 TT1 T11+90000 T11+80000 T11+110000 T11+80000 T11+0 T01 ^\n"
       "№2 G01 A+50 F100 ^\n"
       "№3 G01 G09 X+100000 F2000 ^\n"
       "№4 G01 G09 X-100000 ^\n"
       "№5 G01 A+T11 P(A:R:0)7 F1000 ^\n"
       "№6 P3 ^\n"
       "№7 M02 ^\n");
  double seen[16];
  int n = 0;
  enum vm_event ev;
  while ((ev = vm_run(vm)) == VM_EV_BLOCK)
    if (kp_attr(&t.p, vm->cur)->slots & (1u << SL_A))
      seen[n++] = vm->w[SL_A];
  ck_assert_int_eq(ev, VM_EV_END);
  static const double want[] = {50, 90000, 80000, 110000, 80000, 0};
  ck_assert_int_eq(n, 6);
  for (int i = 0; i < 6; i++)
    ck_assert_double_eq(seen[i], want[i]);
  ck_assert_int_eq(vm->arr[0].ptr, 5);
  ck_assert_int_eq(vm->arr[0].len, 5);
}
END_TEST

START_TEST(array_reads_past_length)
{
  ck_assert_int_eq(run("N1 T11+5 T11+6 T01\nN2 R1+T11 R2+T11 R3+T11 R4+T21\nN3 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 5);
  ck_assert_double_eq(R(2), 6);
  ck_assert_double_eq(R(3), 0);
  ck_assert_double_eq(R(4), 0);
  ck_assert_int_eq(vm->arr[0].ptr, 3);
  ck_assert_int_eq(vm->arr[0].len, 2);
}
END_TEST

START_TEST(array_modes)
{
  ck_assert_int_eq(run("N1 T12+1 T12+2 T12+3 T22+4 T32+9\n"
                       "N2 R1+T32 R2+T22 T04 R3+T32 T02 R4+T12\nN3 M2\n"), VM_EV_END);
  /* cells: 1 9 3 4? no: T22 wrote 4 at 3, T32 moved back to 2 and wrote 9 */
  ck_assert_double_eq(vm->arr[1].cell[0], 1);
  ck_assert_double_eq(vm->arr[1].cell[1], 2);
  ck_assert_double_eq(vm->arr[1].cell[2], 9);
  ck_assert_double_eq(vm->arr[1].cell[3], 4);
  ck_assert_int_eq(vm->arr[1].len, 4);
  ck_assert_double_eq(R(1), 2);        /* back from 2 to 1 */
  ck_assert_double_eq(R(2), 2);        /* stays at 1 */
  ck_assert_double_eq(R(3), 4);        /* T04: pointer to length 4, back to 3 */
  ck_assert_double_eq(R(4), 1);
  ck_assert_int_eq(vm->arr[1].ptr, 1);
  ck_assert_int_eq(vm->arr[0].len, 0);
}
END_TEST

START_TEST(array_zero)
{
  ck_assert_int_eq(run("N1 T11+5 T12+6\nN2 TT2\nN3 M2\n"), VM_EV_END);
  ck_assert_double_eq(vm->arr[0].cell[0], 5);
  ck_assert_double_eq(vm->arr[1].cell[0], 0);
  ck_assert_int_eq(vm->arr[1].ptr, 0);
  ck_assert_int_eq(vm->arr[1].len, 0);
  ck_assert_int_eq(run("N1 T11+5 T12+6\nN2 TT\nN3 M2\n"), VM_EV_END);
  ck_assert_int_eq(vm->arr[0].len, 0);
  ck_assert_int_eq(vm->arr[0].ptr, 0);
}
END_TEST

START_TEST(array_plus_bound)
{
  /* fifteen writes fill the array, the sixteenth fails */
  ck_assert_int_eq(run("N1 TT1\nN2 R1+R1+1 T11+R1 P(R1:M:20)2\nN3 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_ARRAYP, 2);
  ck_assert_int_eq(vm->err.aux, 1);
  ck_assert_uint_eq(vm->err.col, 12);
  ck_assert_double_eq(R(1), 15);       /* the 16th block rolled back */
  ck_assert_int_eq(vm->arr[0].ptr, 15);
  ck_assert_double_eq(vm->arr[0].cell[14], 15);
  ck_assert_uint_eq(vm->blocks, 16);
}
END_TEST

START_TEST(array_plus_bound_on_read)
{
  ck_assert_int_eq(run("N1 T12+1 T12+1 T12+1 T12+1 T12+1 T12+1 T12+1 T12+1 T12+1 T12+1 T12+1 T12+1 T12+1 "
                       "T12+1 T12+1\nN2 R1+T22\nN3 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_ARRAYP, 2);
  ck_assert_int_eq(vm->err.aux, 2);
}
END_TEST

START_TEST(array_minus_bound)
{
  ck_assert_int_eq(run("N1 T11+1\nN2 R1+T31 R2+T32\nN3 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_ARRAYM, 2);
  ck_assert_int_eq(vm->err.aux, 2);
  ck_assert_double_eq(R(1), 0);
  ck_assert_int_eq(vm->arr[0].ptr, 1);   /* the T31 of the failed block undone */
}
END_TEST

START_TEST(array_cell_range)
{
  ck_assert_int_eq(run("N1 R1+9999999 T11+R1+1\nN2 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_RANGE, 1);
  ck_assert_int_eq(vm->arr[0].len, 0);
}
END_TEST

/* ---- transactions ---- */

START_TEST(rollback_registers_and_arrays)
{
  ck_assert_int_eq(run("N1 T11+7 R1+1 D1+5\nN2 T11+8 TT1 R1+2 D1+6 R2+R1/R0\nN3 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_DIV0, 2);
  ck_assert_double_eq(R(1), 1);
  ck_assert_double_eq(R(REG_D1), 5);
  ck_assert_double_eq(R(2), 0);
  ck_assert_double_eq(vm->arr[0].cell[0], 7);
  ck_assert_double_eq(vm->arr[0].cell[1], 0);
  ck_assert_int_eq(vm->arr[0].ptr, 1);
  ck_assert_int_eq(vm->arr[0].len, 1);
}
END_TEST

START_TEST(rollback_register_written_twice)
{
  ck_assert_int_eq(run("N1 R1+1\nN2 R1+2 R1+3 R1+R1/R0\nN3 M2\n"), VM_EV_ERROR);
  ck_assert_double_eq(R(1), 1);
}
END_TEST

START_TEST(host_failure_rolls_back)
{
  load("N1 R1+1\nN2 R1+2 M3 T11+4\nN3 M2\n");
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);
  ck_assert_uint_eq(vm->cur, 1);
  ck_assert_double_eq(R(1), 2);
  vm_set_reg(vm, 5, 42);
  vm_fail(vm, S42_E_WHEEL, "wheel %d", 3);
  ck_assert_int_eq(vm_run(vm), VM_EV_ERROR);
  ck_assert_int_eq(vm->err.code, S42_E_WHEEL);
  ck_assert_str_eq(vm->err.msg, "wheel 3");
  ck_assert_uint_eq(vm->err.block, 1);
  ck_assert_double_eq(R(1), 1);
  ck_assert_double_eq(R(5), 0);
  ck_assert_int_eq(vm->arr[0].len, 0);
  ck_assert_uint_eq(vm->blocks, 1);
  ck_assert_int_eq(vm_run(vm), VM_EV_ERROR);   /* stays failed */
}
END_TEST

START_TEST(host_register_write_commits)
{
  load("N1 M3\nN2 M2\n");
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);
  vm_set_reg(vm, 7, 12.5);
  vm_set_reg(vm, 500, 1);              /* ignored */
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(7), 12.5);
  ck_assert_int_eq(vm_run(vm), VM_EV_END);
}
END_TEST

/* ---- subs ---- */

START_TEST(sub_repeats_h_times)
{
  ck_assert_int_eq(run("N5 R1+R1+1 M17\nN1 L5 H3\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 3);
  ck_assert_int_eq(run("N5 R1+R1+1 M17\nN1 L5\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 1);
  ck_assert_int_eq(run("N5 R1+R1+1 M17\nN1 L5 H0\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 0);
  ck_assert_int_eq(run("N5 R1+R1+1 M17\nN1 L5 H+5/2\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 3);        /* 2.5 rounds to 3 */
  ck_assert_uint_eq(vm->blocks, 5);
}
END_TEST

START_TEST(sub_runs_after_calling_block)
{
  /* the calling block's own words happen first, the sub sees them */
  ck_assert_int_eq(run("N5 R2+R1 M17\nN1 L5 R1+7\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(2), 7);
}
END_TEST

START_TEST(sub_restores_f)
{
  /* F is register 117; record it at every block */
  load("N5 R1+R1+1 M3\nN6 F200 M17\nN1 F1000 L5 H2\nN2 M2\n");
  vm->yield_all = 1;
  double f[16];
  int n = 0;
  enum vm_event ev;
  while ((ev = vm_run(vm)) == VM_EV_BLOCK && n < 16)
    f[n++] = vm->reg[REG_F];
  ck_assert_int_eq(ev, VM_EV_END);
  ck_assert_int_eq(n, 6);             /* 1, 5, 6, 5, 6, 2 */
  ck_assert_double_eq(f[0], 1000);
  ck_assert_double_eq(f[1], 1000);    /* the sub starts with its caller's F */
  ck_assert_double_eq(f[2], 200);
  ck_assert_double_eq(f[3], 1000);    /* the second run too */
  ck_assert_double_eq(f[4], 200);
  ck_assert_double_eq(f[5], 1000);    /* restored on return */
  ck_assert_double_eq(R(REG_F), 1000);
  ck_assert_double_eq(R(1), 2);
}
END_TEST

START_TEST(seed_subs_nesting_order)
{
  load("№10 G02 G19 G09 X-20000 Z+0 I-10000 K+0 F200 L11 H2 M17 ^\n"
       "№11 G09 Z+20000 M17 ^\n"
       "№01 R1+1 ^\n"   /* G07 in the seed: the VM test needs no plugin */
       "№02 G09 X+40000 Y-10000 F1000 L10 H2 ^\n"
       "№03 G09 Z-80000 M02 ^\n");
  vm->yield_all = 1;
  unsigned order[32];
  double f[32];
  int depth[32];
  int n = 0;
  enum vm_event ev;
  while ((ev = vm_run(vm)) == VM_EV_BLOCK && n < 32) {
    f[n] = vm->reg[REG_F];
    depth[n] = vm->depth;
    order[n++] = vm_block_number(vm, vm->cur);
  }
  ck_assert_int_eq(ev, VM_EV_END);
  static const unsigned want[] = {1, 2, 10, 11, 11, 10, 11, 11, 3};
  static const int wdepth[] = {0, 0, 1, 2, 2, 1, 2, 2, 0};
  ck_assert_int_eq(n, 9);
  for (int i = 0; i < n; i++) {
    ck_assert_uint_eq(order[i], want[i]);
    ck_assert_int_eq(depth[i], wdepth[i]);
  }
  ck_assert_double_eq(f[2], 200);
  ck_assert_double_eq(f[3], 200);
  ck_assert_double_eq(f[7], 200);
  ck_assert_double_eq(f[8], 1000);
}
END_TEST

START_TEST(m2_in_sub_ends_program)
{
  ck_assert_int_eq(run("N5 R1+1 M2\nN1 L5\nN2 R2+1 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 1);
  ck_assert_double_eq(R(2), 0);
  ck_assert_int_eq(vm->depth, 1);
}
END_TEST

START_TEST(word_operand_sees_only_left)
{
  /* Y+X before X reads 0; after it, the rounded value */
  ck_assert_int_eq(run("N1 Y+X+1 X+5 Z+X R1+Y R2+Z F1\nN2 X+1/2 A+X%10 R3+A F1\nN3 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 1);
  ck_assert_double_eq(R(2), 5);
  ck_assert_double_eq(R(3), 10);
}
END_TEST

START_TEST(sub_keeps_caller_condition)
{
  /* the sub's own condition does not leak into the caller's jump */
  ck_assert_int_eq(run("N5 P(R1:R:0)6\nN6 M17\nN1 R1+1 L5 P(R1:R:1)3\nN2 M2\nN3 R2+1 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(2), 1);
}
END_TEST

START_TEST(caller_jump_after_return)
{
  /* the return takes the calling block's jump itself (RET then JCOND in
   * one): by the caller's condition, not the sub's, either way */
  ck_assert_int_eq(run("N5 P(R1:R:1)6\nN6 M17\nN1 R1+1 L5 P(R1:R:0)3\nN2 R2+2 M2\nN3 R2+1 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(2), 2);
  /* a sub repeated H times returns to the jump once, after the last */
  ck_assert_int_eq(run("N5 R3+R3+1 M17\nN1 R1+R1+1 L5 H3 P(R1:M:4)1\nN2 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 4);
  ck_assert_double_eq(R(3), 12);
  ck_assert_uint_eq(vm->blocks, 4 + 12 + 1);
  ck_assert_int_eq(vm->depth, 0);
}
END_TEST

START_TEST(h_out_of_range_at_run_time)
{
  ck_assert_int_eq(run("N5 M17\nN1 R1-1\nN2 L5 H+R1\nN3 M2\n"), VM_EV_ERROR);
  assert_error(S42_E_RANGE, 2);
}
END_TEST

/* A chain: MP calls sub 2, sub k calls sub k+1 ... up to sub `last`. */
static const char *chain(int last, char *buf, size_t n)
{
  size_t k = 0;
  k += (size_t)snprintf(buf + k, n - k, "N%d R1+R1+1 M17\n", last);
  for (int s = last - 1; s >= 2; s--)
    k += (size_t)snprintf(buf + k, n - k, "N%d R5+R5+1 L%d M17\n", s, s + 1);
  snprintf(buf + k, n - k, "N1 L2\nN999 M2\n");
  return buf;
}

START_TEST(nest_eight_levels)
{
  char src[1024];
  ck_assert_int_eq(run(chain(9, src, sizeof src)), VM_EV_END);   /* subs 2..9: 8 levels */
  ck_assert_double_eq(R(1), 1);
  ck_assert_int_eq(vm->depth, 0);
}
END_TEST

START_TEST(nest_ninth_level)
{
  char src[1024];
  ck_assert_int_eq(run(chain(10, src, sizeof src)), VM_EV_ERROR);
  assert_error(S42_E_NEST, 9);         /* raised at the calling block */
  ck_assert_double_eq(R(1), 0);
  ck_assert_double_eq(R(5), 8);        /* the calling block itself ran */
  ck_assert_uint_eq(vm->blocks, 9);
}
END_TEST

/* ---- a block's control in one dispatch: MACHS, BLOCKR, CCALL ---- */

/* The opcode of block b's instruction k. */
static unsigned op_at(size_t b, uint32_t k)
{
  return INS_OP(t.p.code[t.p.blocks[b].code + k]);
}

/* Events until the end, each VM_EV_BLOCK's block number in got[]. */
static int block_yields(int *got, int max)
{
  int n = 0;
  for (;;) {
    enum vm_event ev = vm_run(vm);
    if (ev == VM_EV_BLOCK) {
      ck_assert_int_lt(n, max);
      got[n++] = (int)vm_block_number(vm, vm->cur);
      continue;
    }
    ck_assert_int_eq(ev, VM_EV_END);
    return n;
  }
}

START_TEST(switch_block_yields_only_for_a_change)
{
  const char *src = "N1 M23\nN2 M22 M26\nN3 R1+R1+1 M23 P(R1:M:3)3\nN4 M23 F100\nN5 M2\n";
  load(src);
  ck_assert_uint_eq(op_at(0, 1), OP_MACHS);
  ck_assert_uint_eq(INS_A(t.p.code[t.p.blocks[0].code + 1]), 1u);              /* CORR, to off */
  ck_assert_uint_eq(INS_A(t.p.code[t.p.blocks[1].code + 1]), 3u | 3u << 12);   /* both, to on */
  /* nothing published: every such block is the host's, as MACH */
  int got[16], n = block_yields(got, 16);
  int all[] = {1, 2, 3, 3, 3, 4, 5};
  ck_assert_int_eq(n, 7);
  for (int i = 0; i < n; i++)
    ck_assert_int_eq(got[i], all[i]);
  /* published: a block yields only when a switch it sets stands otherwise;
   * the host's machine work then turns it, and it publishes the new state */
  load(src);
  uint32_t sw = 0;   /* both off at power-on */
  vm->sw = VM_SW_HELD | sw;
  int want[] = {2, 3, 4, 5};
  for (int i = 0; i < 4; i++) {
    ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);
    ck_assert_int_eq((int)vm_block_number(vm, vm->cur), want[i]);
    if (want[i] == 2)
      sw = 3;
    if (want[i] == 3)
      sw &= ~1u;
    vm->sw = VM_SW_HELD | sw;
  }
  ck_assert_int_eq(vm_run(vm), VM_EV_END);
  ck_assert_double_eq(R(1), 3);
  ck_assert_uint_eq(vm->blocks, 7);
  /* every block watched: all of them come back, published or not */
  load(src);
  vm->sw = VM_SW_HELD;
  vm->yield_all = 1;
  ck_assert_int_eq(block_yields(got, 16), 7);
}
END_TEST

START_TEST(switch_block_only_with_nothing_else)
{
  /* anything else for the machine or the display keeps MACH */
  const char *machs[] = {"N1 M25\nN2 M2\n", "N1 M22 M26 R1+1\nN2 M2\n"};
  const char *mach[] = {"N1 M23 F100\nN2 M2\n", "N1 M23 G04 X+10\nN2 M2\n", "N1 M23 M15\nN2 M2\n",
                        "N1 M23 M3\nN2 M2\n", "N1 M23 X+1 F1\nN2 M2\n", "N1 M23 G33 /A/\nN2 M2\n"};
  for (size_t i = 0; i < sizeof machs / sizeof *machs; i++) {
    load(machs[i]);
    ck_assert_msg(op_at(0, 1) == OP_MACHS || op_at(0, 3) == OP_MACHS || op_at(0, 2) == OP_MACHS, "%s", machs[i]);
  }
  for (size_t i = 0; i < sizeof mach / sizeof *mach; i++) {
    load(mach[i]);
    for (uint32_t pc = t.p.blocks[0].code; pc < t.p.blocks[1].code; pc++)
      ck_assert_msg(INS_OP(t.p.code[pc]) != OP_MACHS, "%s", mach[i]);
  }
}
END_TEST

START_TEST(lone_m17_runs_at_once)
{
  const char *src = "N10 M17\nN1 R1+0\nN2 R1+R1+1 L10 P(R1:M:3)2\nN3 M2\n";
  load(src);
  ck_assert_uint_eq(op_at(0, 0), OP_BLOCKR);
  ck_assert_uint_eq(op_at(2, 6), OP_CCALL);
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(1), 3);
  ck_assert_uint_eq(vm->blocks, 8);   /* N1, three N2 and N10, N3 */
  ck_assert_int_eq(vm->depth, 0);
  /* every block watched: the sub's block comes back as any block */
  load(src);
  vm->yield_all = 1;
  int got[16], n = block_yields(got, 16);
  int all[] = {1, 2, 10, 2, 10, 2, 10, 3};
  ck_assert_int_eq(n, 8);
  for (int i = 0; i < n; i++)
    ck_assert_int_eq(got[i], all[i]);
  /* the sub's block watched: it starts as any block, then runs on */
  load(src);
  uint8_t w[4] = {1, 0, 0, 0};
  vm->watch = w;
  int starts = 0;
  for (enum vm_event ev; (ev = vm_run(vm)) != VM_EV_END;) {
    ck_assert_int_ne(ev, VM_EV_ERROR);
    if (ev == VM_EV_START) {
      ck_assert_uint_eq(vm->cur, 0);
      starts++;
    }
  }
  ck_assert_int_eq(starts, 3);
  ck_assert_uint_eq(vm->blocks, 8);
  /* the budget stops it at its start, as BLOCK does */
  load(src);
  vm->max_blocks = 2;
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  assert_error(S42_E_LIMIT, 10);
  ck_assert_uint_eq(vm->blocks, 2);
}
END_TEST

START_TEST(blockr_in_the_main_program)
{
  /* by hand (the compiler refuses M17 in the main program): the fused RET
   * raises E-SUB as the plain one does, at the RET's column */
  uint32_t entry = hblock(1, 0);
  hp.code[entry] = INS(OP_BLOCKR, 0);
  hemit(OP_SYNC, 0);
  hemit(OP_COMMIT, 0);
  prog_emit(&hp, INS(OP_RET, 0), 7);
  hstart(entry);
  ck_assert_int_eq(vm_run(vm), VM_EV_ERROR);
  ck_assert_int_eq(vm->err.code, S42_E_SUB);
  ck_assert_uint_eq(vm->err.col, 7);
  ck_assert_uint_eq(vm->blocks, 1);
}
END_TEST

START_TEST(ccall_nests_as_call)
{
  /* subs called without H: CCALL; the ninth level fails at the L word */
  char src[1024];
  load(chain(10, src, sizeof src));
  ck_assert_uint_eq(op_at(t.p.nblocks - 2, 2), OP_CCALL);   /* N1 L2: BLOCK, SYNC, CCALL */
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  assert_error(S42_E_NEST, 9);
  ck_assert_uint_eq(vm->err.col, 12);   /* "N9 R5+R5+1 L10 M17": the L */
  ck_assert_uint_eq(vm->blocks, 9);
}
END_TEST

/* ---- limits, PP, watch ---- */

START_TEST(limit_max_blocks)
{
  load("N1 R1+R1+1 P(R1:M:1000)1\nN2 M2\n");
  vm->max_blocks = 5;
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  assert_error(S42_E_LIMIT, 1);
  ck_assert_double_eq(R(1), 5);
  ck_assert_uint_eq(vm->blocks, 5);
}
END_TEST

START_TEST(limit_exactly_enough)
{
  load("N1 R1+R1+1 P(R1:M:4)1\nN2 M2\n");
  vm->max_blocks = 5;
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_uint_eq(vm->blocks, 5);
}
END_TEST

START_TEST(limit_lowered_between_runs)
{
  /* the host lowers the budget below the blocks run while a block is
   * open: that block still counts, and the next one is refused */
  load("N1 R1+1 M3\nN2 R1+R1+1 M3\nN3 R1+R1+1 M3\nN4 M2\n");
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);   /* N1's M3 */
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);   /* N2's M3 */
  ck_assert_uint_eq(vm->blocks, 1);
  vm->max_blocks = 1;
  ck_assert_int_eq(vm_run(vm), VM_EV_ERROR);
  assert_error(S42_E_LIMIT, 3);
  ck_assert_uint_eq(vm->blocks, 2);
  ck_assert_double_eq(R(1), 2);
  /* and raised again, a budget of exactly the blocks run */
  load("N1 R1+1 M3\nN2 R1+R1+1 M3\nN3 M2\n");
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);
  vm->max_blocks = 2;
  ck_assert_int_eq(vm_run(vm), VM_EV_ERROR);
  assert_error(S42_E_LIMIT, 3);
  ck_assert_uint_eq(vm->blocks, 2);
}
END_TEST

START_TEST(pp_without_latch)
{
  ck_assert_int_eq(run("N1 R1+R1+1 PP3 P(R1:M:100)1\nN2 M2\nN3 R2+1 M2\n"), VM_EV_END);
  ck_assert_double_eq(R(1), 100);
  ck_assert_double_eq(R(2), 0);
  ck_assert_uint_eq(vm->pp_jumps, 0);
}
END_TEST

START_TEST(pp_with_latch_wins_over_p)
{
  load("N1 R1+R1+1 PP3 P(R1:M:100)1\nN2 M2\nN3 R2+1 M2\n");
  vm->exit_latch = 1;
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(1), 1);
  ck_assert_double_eq(R(2), 1);
  ck_assert_uint_eq(vm->pp_jumps, 1);
  ck_assert_int_eq(vm->exit_latch, 0);
}
END_TEST

START_TEST(pp_latch_taken_by_next_pp_block)
{
  load("N1 R1+R1+1 P(R1:M:100)1\nN2 R3+1 PP4\nN3 M2\nN4 R2+1 M2\n");
  vm->yield_all = 1;
  enum vm_event ev;
  while ((ev = vm_run(vm)) == VM_EV_BLOCK)
    if (vm->reg[1] == 3)
      vm->exit_latch = 1;              /* pressed during the loop */
  ck_assert_int_eq(ev, VM_EV_END);
  ck_assert_double_eq(R(1), 100);      /* the loop has no PP: it goes on */
  ck_assert_double_eq(R(3), 1);
  ck_assert_double_eq(R(2), 1);
}
END_TEST

START_TEST(latch_cleared_at_m2)
{
  load("N1 R1+1\nN2 M2\n");
  vm->exit_latch = 1;
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_int_eq(vm->exit_latch, 0);
}
END_TEST

START_TEST(watch_yields_start)
{
  load("N1 R1+1\nN2 R2+1\nN3 M2\n");
  uint8_t watch[3] = {0, 1, 0};
  vm->watch = watch;
  ck_assert_int_eq(vm_run(vm), VM_EV_START);
  ck_assert_uint_eq(vm->cur, 1);
  ck_assert_double_eq(R(1), 1);
  ck_assert_double_eq(R(2), 0);        /* not run yet */
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);   /* N3 has M2 */
  ck_assert_double_eq(R(2), 1);
  ck_assert_int_eq(vm_run(vm), VM_EV_END);
}
END_TEST

/* A watch array that flags no block watches nothing (the VM then runs its
 * plain dispatch table); one handed over anew is read anew. */
START_TEST(watch_array_read_when_handed_over)
{
  load("N1 R1+1\nN2 R2+1\nN3 R3+1\nN4 M2\n");
  uint8_t none[4] = {0, 0, 0, 0}, third[4] = {0, 0, 1, 0};
  vm->watch = none;
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);   /* N4 has M2 */
  ck_assert_double_eq(R(3), 1);
  load("N1 R1+1\nN2 R2+1\nN3 R3+1\nN4 M2\n");
  vm->watch = none;
  none[1] = 1;   /* changed in place before the VM first saw it: read */
  ck_assert_int_eq(vm_run(vm), VM_EV_START);
  ck_assert_uint_eq(vm->cur, 1);
  vm->watch = third;
  ck_assert_int_eq(vm_run(vm), VM_EV_START);
  ck_assert_uint_eq(vm->cur, 2);
  ck_assert_double_eq(R(2), 1);
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);
  ck_assert_int_eq(vm_run(vm), VM_EV_END);
}
END_TEST

START_TEST(start_all_and_yield_all)
{
  load("N1 R1+1\nN2 R2+1\nN3 M2\n");
  vm->start_all = 1;
  vm->yield_all = 1;
  enum vm_event want[] = {VM_EV_START, VM_EV_BLOCK, VM_EV_START, VM_EV_BLOCK, VM_EV_START, VM_EV_BLOCK,
                          VM_EV_END};
  for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
    ck_assert_int_eq(vm_run(vm), want[i]);
  ck_assert_uint_eq(vm->blocks, 3);
}
END_TEST

START_TEST(sync_blocks_do_not_yield)
{
  load("N1 R1+1\nN2 R2+1\nN3 M2\n");
  ck_assert_int_eq(vm_run(vm), VM_EV_BLOCK);   /* only N3, for its M2 */
  ck_assert_uint_eq(vm->cur, 2);
  ck_assert_uint_eq(vm->blocks, 2);
}
END_TEST

START_TEST(many_vms_one_program)
{
  load("N1 R1+R0 R2+0\nN2 R2+R2+R1 R3+R3+1 X+1 F1 P(R3:M:10)2\nN3 M2\n");
  enum { NV = 12 };
  struct vm *v = calloc(NV, sizeof *v);
  int done[NV] = {0};
  for (int i = 0; i < NV; i++) {
    vm_init(&v[i], &t.p);
    v[i].reg[0] = i;
  }
  /* interleave: one event of each VM in turn */
  for (int left = NV; left > 0;) {
    for (int i = 0; i < NV; i++) {
      if (done[i])
        continue;
      enum vm_event ev = vm_run(&v[i]);
      if (ev == VM_EV_END || ev == VM_EV_ERROR) {
        ck_assert_int_eq(ev, VM_EV_END);
        done[i] = 1;
        left--;
      }
    }
  }
  for (int i = 0; i < NV; i++) {
    ck_assert_double_eq(v[i].reg[2], 10.0 * i);
    ck_assert_uint_eq(v[i].blocks, 12);
  }
  free(v);
}
END_TEST

START_TEST(vm_math_direct)
{
  double r;
  char msg[100];
  ck_assert_int_eq(vm_math(&t.p, OP_DIV, 1, 0, &r, msg, sizeof msg), S42_E_DIV0);
  ck_assert_int_eq(vm_math(&t.p, OP_POW, 0, -1, &r, msg, sizeof msg), S42_E_DIV0);
  ck_assert_int_eq(vm_math(&t.p, OP_POW, -8, 1.0 / 3, &r, msg, sizeof msg), S42_E_DOMAIN);
  ck_assert_int_eq(vm_math(&t.p, OP_MUL, 1e300, 1e300, &r, msg, sizeof msg), S42_E_RANGE);
  ck_assert_int_eq(vm_math(&t.p, OP_LOG, 0, 0, &r, msg, sizeof msg), S42_E_DOMAIN);
  ck_assert_int_eq(vm_math(&t.p, OP_NEG, 3, 0, &r, msg, sizeof msg), 0);
  ck_assert_double_eq(r, -3);
  ck_assert_int_eq(vm_math(&t.p, OP_POW, 2, 10, &r, msg, sizeof msg), 0);
  ck_assert_double_eq(r, 1024);
}
END_TEST

/* ---- what the VM takes from the program ---- */

/* Every detail message a 2С42 run can raise, byte for byte as before the
 * texts moved into the dialect's table (kpmsg.h). */
START_TEST(kp_messages_exact)
{
  static const struct { const char *src, *msg; } c[] = {
    {"N1 R1+2 R2+ASI(R1)\nN2 M2\n", "ASI(2): argument outside -1..1"},
    {"N1 R1-11/10 R2+ACO(R1)\nN2 M2\n", "ACO(-1.1): argument outside -1..1"},
    {"N1 R0+2304001 R1+SI(R0)\nN2 M2\n", "SI(2304001): argument outside -2304000..2304000"},
    {"N1 R0-2304001 R1+CO(R0)\nN2 M2\n", "CO(-2304001): argument outside -2304000..2304000"},
    {"N1 R0+2304001 R1+TG(R0)\nN2 M2\n", "TG(2304001): argument outside -2304000..2304000"},
    {"N1 R0+90000 R1+TG(R0)\nN2 M2\n", "TG(90000): tangent of an odd multiple of 90 degrees"},
    {"N1 R0+9999999 R1+ATG(R0+1)\nN2 M2\n", "ATG(10000000): argument outside -9999999..9999999"},
    {"N1 R1+LO(R0)\nN2 M2\n", "LO(0): argument outside 0 (excluded)..9999999"},
    {"N1 R0+9999999 R1+LO(R0+1)\nN2 M2\n", "LO(10000000): argument outside 0 (excluded)..9999999"},
    {"N1 R1+5\nN2 R2+1 R3+R1/R0\nN3 M2\n", "division of 5 by zero"},
    {"N1 R1-4 R2+R1%%(1/2)\nN2 M2\n", "power: negative base -4 with the fractional exponent 0.5"},
    {"N1 R1-1 R2+R0%%R1\nN2 M2\n", "power: zero to the negative exponent -1"},
    {"N1 R1+9999999\nN2 R2+R1+1\nN3 M2\n", "R2 = 10000000 is outside -9999999..9999999"},
    {"N1 R1+999999\nN2 X+R1+1 F1\nN3 M2\n", "X = 1000000 is outside -999999..999999"},
    {"N1 R1+9999999 T11+R1+1\nN2 M2\n", "array 1: value 10000000 outside -9999999..9999999"},
    {"N1 R1+T31\nN2 M2\n", "array 1: pointer already at cell 0, cannot move back"},
    {"N1 TT1\nN2 R1+R1+1 T11+R1 P(R1:M:20)2\nN3 M2\n", "array 1: pointer at 15, past the last cell 14"},
  };
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
    ck_assert_int_eq(run(c[i].src), VM_EV_ERROR);
    ck_assert_str_eq(vm->err.msg, c[i].msg);
  }
  char src[1024];
  ck_assert_int_eq(run(chain(10, src, sizeof src)), VM_EV_ERROR);
  ck_assert_str_eq(vm->err.msg, "a 9th nested sub call (at most 8 levels)");
  load("N1 R1+R1+1 P(R1:M:1000)1\nN2 M2\n");
  vm->max_blocks = 5;
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  ck_assert_str_eq(vm->err.msg, "the budget of 5 blocks ran out (--max-blocks)");
  /* M17 at depth 0, which no 2С42 program that compiles reaches */
  hp.msgs = &kp_msgs;
  hstart(sub_and_main(OP_RET, 1, OP_RET));
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  assert_error(S42_E_SUB, 2);
  ck_assert_str_eq(vm->err.msg, "M17 reached in the main program");
}
END_TEST

/* The 2С42's program carries the 2С42-65's limits and table, complete (no
 * text falls back to the VM's), and the table's formats pass the check. */
START_TEST(kp_program_carries_limits_and_texts)
{
  load("N1 M2\n");
  const struct prog_limits *l = &t.p.lim;
  ck_assert_uint_eq(l->depth, 8);
  ck_assert_uint_eq(l->arrays, 2);
  ck_assert_uint_eq(l->cells, 15);
  ck_assert_double_eq(l->param_lo, -9999999);
  ck_assert_double_eq(l->param_hi, 9999999);
  ck_assert_double_eq(l->cell_lo, -9999999);
  ck_assert_double_eq(l->cell_hi, 9999999);
  ck_assert_double_eq(l->angle, 0.001);
  ck_assert_double_eq(180.0 / l->angle, 180000.0);   /* exact: the unit of SI CO TG is as it was */
  ck_assert_double_eq(l->trig_max, 2304000);
  ck_assert_double_eq(l->atan_max, 9999999);
  ck_assert_double_eq(l->log_max, 9999999);
  ck_assert_ptr_eq(t.p.msgs, &kp_msgs);
  char msg[200];
  ck_assert_msg(vm_msgs_check(&kp_msgs, msg, sizeof msg) == 0, "%s", msg);
  ck_assert_msg(vm_msgs_check(&vm_msgs_neutral, msg, sizeof msg) == 0, "%s", msg);
  for (int en = 0; en < 2; en++) {
    ck_assert_ptr_nonnull(kp_msgs.screen[en]);
    for (int e = 0; e < S42_E_COUNT; e++)
      ck_assert_msg(kp_msgs.title[en][e] != NULL, "no title for %s", err_code(e));
  }
  for (int i = 0; i < VMSG__COUNT; i++)
    ck_assert_msg(kp_msgs.detail[i] != NULL, "no detail %d", i);
}
END_TEST

/* The machine's line: the dialect's title (with the array's number) in its
 * screen format; the VM's neutral line with no table. */
START_TEST(machine_line_from_the_table)
{
  char buf[200];
  vm_msg_machine(buf, sizeof buf, &kp_msgs, S42_E_ARC, 12, 0, 0);
  ck_assert_str_eq(buf, "помилка в КП №12: помилка дуги");
  vm_msg_machine(buf, sizeof buf, &kp_msgs, S42_E_ARC, -1, 0, 1);
  ck_assert_str_eq(buf, "error in block -: arc error");
  vm_msg_machine(buf, sizeof buf, &kp_msgs, S42_E_ARRAYP, 3, 2, 0);
  ck_assert_str_eq(buf, "помилка в КП №3: Порушена межа масиву 2 +");
  vm_msg_machine(buf, sizeof buf, &kp_msgs, S42_E_ARRAYM, 3, 1, 1);
  ck_assert_str_eq(buf, "error in block 3: array 1 bound broken –");
  vm_msg_machine(buf, sizeof buf, &kp_msgs, S42_E_NEST, 9999999, 0, 0);
  ck_assert_str_eq(buf, "помилка в КП №9999999: понад 8 рівнів вкладеності ПП");
  vm_msg_machine(buf, sizeof buf, NULL, S42_E_NEST, 5, 0, 0);
  ck_assert_str_eq(buf, "error in block 5: calls nested too deep");
  /* a table's missing entries fall back to the VM's */
  static const struct vm_msgs part = {.name = "part", .title = {[1] = {[S42_E_ARC] = "bad arc"}}};
  vm_msg_machine(buf, sizeof buf, &part, S42_E_ARC, 7, 0, 1);
  ck_assert_str_eq(buf, "error in block 7: bad arc");
  vm_msg_machine(buf, sizeof buf, &part, S42_E_ARC, 7, 0, 0);
  ck_assert_str_eq(buf, "error in block 7: arc error");
  ck_assert_str_eq(vm_msg_detail(&part, VMSG_NEST), "a call %d levels deep (at most %d)");
}
END_TEST

/* A table whose format does not take its arguments as declared is refused
 * by the check, and by prog_verify for a program that carries it. */
START_TEST(message_formats_checked)
{
  char msg[200];
  ck_assert_int_eq(vm_format_check("a %dth call (at most %d)", "dd", msg, sizeof msg), 0);
  ck_assert_int_eq(vm_format_check("100%% of %d", "dd", msg, sizeof msg), 0);   /* a leading part */
  ck_assert_int_eq(vm_format_check("%5.2s|%-3u|%04x|%llu", "suuL", msg, sizeof msg), 0);
  ck_assert_int_eq(vm_format_check("%s", "d", msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "format \"%s\": conversion 1 takes a string where the argument is an int");
  ck_assert_int_eq(vm_format_check("%d %d", "d", msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "format \"%d %d\": conversion 2, but it has 1 argument");
  ck_assert_int_eq(vm_format_check("%n", "d", msg, sizeof msg), -1);
  ck_assert_int_eq(vm_format_check("%*d", "dd", msg, sizeof msg), -1);
  ck_assert_int_eq(vm_format_check("%1$d", "d", msg, sizeof msg), -1);
  ck_assert_int_eq(vm_format_check("%ld", "d", msg, sizeof msg), -1);
  ck_assert_int_eq(vm_format_check("%g", "s", msg, sizeof msg), -1);
  ck_assert_int_eq(vm_format_check("50%", "", msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "format \"50%\": it ends inside a conversion");
  static const struct vm_msgs bad = {.name = "a bad table", .detail = {[VMSG_NEST] = "call %s too deep"}};
  ck_assert_int_eq(vm_msgs_check(&bad, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "detail NEST \"call %s too deep\": conversion 1 takes a string where the argument is an int");
  static const struct vm_msgs badt = {.title = {[0] = {[S42_E_ARC] = "%s"}}};
  ck_assert_int_eq(vm_msgs_check(&badt, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "title of E-ARC (own language) \"%s\": conversion 1 takes a string where the argument is an int");
  hp.msgs = &bad;
  hp.entry = sub_and_main(OP_RET, 1, OP_END);
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the message table of a bad table: detail NEST \"call %s too deep\": conversion 1 takes a "
                        "string where the argument is an int");
}
END_TEST

/* The call depth is the program's: the 2С42's 8 above, 3 here, with the
 * message from the program's table or the VM's. */
START_TEST(depth_from_the_program)
{
  /* a sub that calls itself: level 1 from the main program, 2, 3, then the 4th fails */
  hblock(5, 1);
  hemit(OP_REG, 1);
  hemit(OP_ADDI, 1);
  hemit(OP_SETP, 1);
  hemit(OP_COMMIT, 0);
  hemit(OP_INT, 1);
  hemit(OP_CALL, 0);
  uint32_t entry = hblock(1, 0);
  hemit(OP_COMMIT, 0);
  hemit(OP_INT, 1);
  hemit(OP_CALL, 0);
  hblock(2, 0);
  hemit(OP_COMMIT, 0);
  hemit(OP_END, 0);
  hp.lim.depth = 3;
  hstart(entry);
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  assert_error(S42_E_NEST, 5);
  ck_assert_str_eq(vm->err.msg, "a call 4 levels deep (at most 3)");
  ck_assert_double_eq(R(1), 3);        /* each level's block committed before its call */
  ck_assert_int_eq(vm->depth, 3);
  hp.msgs = &kp_msgs;
  hstart(entry);
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  ck_assert_str_eq(vm->err.msg, "a 4th nested sub call (at most 3 levels)");
  /* up to the VM's bound, and no further */
  hp.lim.depth = VM_DEPTH_MAX;
  hstart(entry);
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  ck_assert_int_eq(vm->depth, VM_DEPTH_MAX);
  ck_assert_double_eq(R(1), VM_DEPTH_MAX);
  hp.lim.depth = VM_DEPTH_MAX + 1;
  hp.msgs = NULL;
  ck_assert_int_eq(vm_init(vm, &hp), -1);
  ck_assert_int_eq(vm_run(vm), VM_EV_ERROR);
  assert_error(S42_E_LIMIT, 1);
  ck_assert_str_eq(vm->err.msg, "the program nests calls 257 deep; this VM has 256 levels");
  char msg[200];
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the program nests calls 257 deep; the VM holds 256");
}
END_TEST

/* Arrays, their cells and the value ranges are the program's. */
START_TEST(arrays_and_ranges_from_the_program)
{
  /* write r1 into array 1 three times, then a fourth: E-ARRAY+ past cell 2 */
  uint32_t entry = hblock(1, 0);
  hemit(OP_AZERO, 1);
  for (int i = 0; i < 4; i++) {
    hemit(OP_REG, 1);
    hemit(OP_AWR, 0 | 1 << 2);
  }
  hemit(OP_COMMIT, 0);
  hemit(OP_END, 0);
  hp.lim.arrays = 1;
  hp.lim.cells = 3;
  hstart(entry);
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  assert_error(S42_E_ARRAYP, 1);
  ck_assert_str_eq(vm->err.msg, "array 1: pointer at 3, past the last cell 2");
  ck_assert_int_eq(vm->arr[0].ptr, 0);   /* rolled back */
  /* array 2 of a program with one array is refused before it runs */
  hp.code[3] = INS(OP_AWR, 1 | 1 << 2);
  char msg[200];
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "pc 3: AWR of array 2 but there is 1 array");
  hp.code[3] = INS(OP_AWR, 0 | 1 << 2);
  hp.code[1] = INS(OP_AZERO, 3);
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "pc 1: AZERO of arrays 3, not a mask of the 1 array (1..1)");
  hp.code[1] = INS(OP_AZERO, 1);
  /* the cell range: r1 = 5 is outside -4..4 */
  hp.lim.cells = 4;
  hp.lim.cell_lo = -4;
  hp.lim.cell_hi = 4;
  hstart(entry);
  vm->reg[1] = 5;
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  assert_error(S42_E_RANGE, 1);
  ck_assert_str_eq(vm->err.msg, "array 1: value 5 outside -4..4");
  hstart(entry);
  vm->reg[1] = 4;
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_int_eq(vm->arr[0].len, 4);
  ck_assert_double_eq(vm->arr[0].cell[3], 4);
  /* the host loads no more than the program's cells, into its arrays only */
  double v[5] = {1, 2, 3, 4, 5};
  vm_load_array(vm, 0, v, 5);
  ck_assert_int_eq(vm->arr[0].len, 4);
  vm_load_array(vm, 1, v, 2);
  ck_assert_int_eq(vm->arr[1].len, 0);
  vm_load_array(vm, 0, v, 2);
  ck_assert_int_eq(vm->arr[0].len, 2);
  /* more arrays or cells than the VM holds: refused by vm_init and verify */
  hp.lim.cells = VM_CELLS_MAX + 1;
  ck_assert_int_eq(vm_init(vm, &hp), -1);
  assert_error(S42_E_LIMIT, 1);
  ck_assert_str_eq(vm->err.msg, "the program has 1 arrays of 65 cells; this VM has 4 of 64");
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the program has 1 arrays of 65 cells; the VM holds 4 of 64");
  hp.lim.cells = 4;
  hp.lim.cell_lo = 1;
  hp.lim.cell_hi = 0;
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the array cell range 1..0 is empty");
}
END_TEST

START_TEST(parameter_range_from_the_program)
{
  uint32_t entry = hblock(1, 0);
  hemit(OP_REG, 2);
  hemit(OP_SETP, 3);
  hemit(OP_COMMIT, 0);
  hemit(OP_END, 0);
  hp.lim.param_lo = 0;
  hp.lim.param_hi = 100;
  hstart(entry);
  vm->reg[2] = -1;
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  assert_error(S42_E_RANGE, 1);
  ck_assert_str_eq(vm->err.msg, "r3 = -1 is outside 0..100");
  hp.msgs = &kp_msgs;
  hstart(entry);
  vm->reg[2] = 101;
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  ck_assert_str_eq(vm->err.msg, "R3 = 101 is outside 0..100");
  hstart(entry);
  vm->reg[2] = 100;
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(3), 100);
  /* with prog_init's limits nothing finite is out of range */
  hp.lim.param_lo = -DBL_MAX;
  hp.lim.param_hi = DBL_MAX;
  hstart(entry);
  vm->reg[2] = 1e300;
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
}
END_TEST

/* The angle unit and the functions' domains: degrees here, 0.001 deg for
 * the 2С42; constant folding takes the same (vm_math on the program). */
START_TEST(angle_unit_and_domains_from_the_program)
{
  double r;
  char msg[200];
  hp.lim.angle = 1.0;
  hp.lim.trig_max = 360;
  ck_assert_int_eq(vm_math(&hp, OP_SIN, 90, 0, &r, msg, sizeof msg), 0);
  ck_assert_double_eq(r, 1);
  ck_assert_int_eq(vm_math(&hp, OP_ASIN, 1, 0, &r, msg, sizeof msg), 0);
  ck_assert_double_eq(r, 90);
  ck_assert_int_eq(vm_math(&hp, OP_ATAN, 1, 0, &r, msg, sizeof msg), 0);
  ck_near(r, 45, 1e-12);
  ck_assert_int_eq(vm_math(&hp, OP_TAN, 90, 0, &r, msg, sizeof msg), S42_E_DOMAIN);
  ck_assert_str_eq(msg, "TAN(90): tangent of an odd multiple of 90 degrees");
  ck_assert_int_eq(vm_math(&hp, OP_TAN, -270, 0, &r, msg, sizeof msg), S42_E_DOMAIN);
  ck_assert_int_eq(vm_math(&hp, OP_TAN, 180, 0, &r, msg, sizeof msg), 0);
  ck_assert_int_eq(vm_math(&hp, OP_COS, 361, 0, &r, msg, sizeof msg), S42_E_DOMAIN);
  ck_assert_str_eq(msg, "COS(361): argument outside -360..360");
  hp.lim.angle = 0.001;   /* the 2С42's unit: exactly the old arithmetic */
  hp.lim.trig_max = 2304000;
  ck_assert_int_eq(vm_math(&hp, OP_SIN, 20000, 0, &r, msg, sizeof msg), 0);
  ck_assert_double_eq(r, sin(20000 * (M_PI / 180000.0)));
  ck_assert_int_eq(vm_math(&hp, OP_ACOS, 0.5, 0, &r, msg, sizeof msg), 0);
  ck_assert_double_eq(r, acos(0.5) / (M_PI / 180000.0));
  ck_assert_int_eq(vm_math(&hp, OP_TAN, 90000, 0, &r, msg, sizeof msg), S42_E_DOMAIN);
  hp.lim.atan_max = 10;
  hp.lim.log_max = 100;
  ck_assert_int_eq(vm_math(&hp, OP_ATAN, -11, 0, &r, msg, sizeof msg), S42_E_DOMAIN);
  ck_assert_str_eq(msg, "ATAN(-11): argument outside -10..10");
  ck_assert_int_eq(vm_math(&hp, OP_LOG, 101, 0, &r, msg, sizeof msg), S42_E_DOMAIN);
  ck_assert_str_eq(msg, "LOG(101): argument outside 0 (excluded)..100");
  hp.msgs = &kp_msgs;
  ck_assert_int_eq(vm_math(&hp, OP_LOG, 101, 0, &r, msg, sizeof msg), S42_E_DOMAIN);
  ck_assert_str_eq(msg, "LO(101): argument outside 0 (excluded)..100");
  /* a unit that is no unit is refused by verify */
  hp.entry = hblock(1, 0);
  hemit(OP_COMMIT, 0);
  hemit(OP_END, 0);
  hp.lim.angle = 0;
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the angle unit is 0 degrees, not a positive number");
  hp.lim.angle = 1;
  hp.lim.log_max = 0;
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), -1);
}
END_TEST

/* Block numbers are 32 bits: the 2У22's 5 digits, FMS-3000's 7. */
START_TEST(block_numbers_32_bit)
{
  hblock(9999999, 1);
  hemit(OP_COMMIT, 0);
  hemit(OP_RET, 0);
  uint32_t entry = hblock(99999, 0);
  hemit(OP_COMMIT, 0);
  hemit(OP_INT, 1);
  hemit(OP_CALL, 0);
  hblock(4294967295u, 0);
  hemit(OP_COMMIT, 0);
  hemit(OP_END, 0);
  hstart(entry);
  ck_assert_uint_eq(vm_block_number(vm, 0), 9999999);
  ck_assert_uint_eq(vm_block_number(vm, 1), 99999);
  ck_assert_uint_eq(vm_block_number(vm, 2), 4294967295u);
  vm->start_all = 1;
  ck_assert_int_eq(vm_run(vm), VM_EV_START);
  ck_assert_uint_eq(vm_block_number(vm, vm->cur), 99999);
  ck_assert_int_eq(vm_run(vm), VM_EV_START);
  ck_assert_uint_eq(vm_block_number(vm, vm->cur), 9999999);
  /* the disassembler prints them whole, in the headers and at the call */
  char *buf = NULL;
  size_t n = 0;
  FILE *f = open_memstream(&buf, &n);
  vm_disasm(f, &hp, NULL, 0);
  fclose(f);
  ck_assert_ptr_nonnull(strstr(buf, "; N9999999 line 1\n"));
  ck_assert_ptr_nonnull(strstr(buf, "; N99999 line 2\n"));
  ck_assert_ptr_nonnull(strstr(buf, "; N4294967295 line 3\n"));
  ck_assert_ptr_nonnull(strstr(buf, "CALL    0000\t; N9999999\n"));
  free(buf);
  char line[200];
  vm_msg_machine(line, sizeof line, &kp_msgs, S42_E_SUB, 9999999, 0, 1);
  ck_assert_str_eq(line, "error in block 9999999: bad program structure");
}
END_TEST

/* ---- RETEND: return when called, end otherwise ---- */

START_TEST(retend_returns_from_a_call)
{
  hstart(sub_and_main(OP_RETEND, 1, OP_END));
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(1), 1);
  ck_assert_int_eq(vm->depth, 0);
  ck_assert_uint_eq(vm->blocks, 3);   /* N1, N10, N2 */
}
END_TEST

START_TEST(retend_repeats_as_ret)
{
  /* a count of 3: it runs again twice, then returns, as RET does */
  hstart(sub_and_main(OP_RETEND, 3, OP_END));
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(1), 3);
  ck_assert_uint_eq(vm->blocks, 5);
  hstart(sub_and_main(OP_RET, 3, OP_END));
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(1), 3);
  ck_assert_uint_eq(vm->blocks, 5);
}
END_TEST

START_TEST(retend_ends_the_main_program)
{
  /* the main program's last block ends with RETEND: the program ends there */
  hstart(sub_and_main(OP_RETEND, 1, OP_RETEND));
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(1), 1);
  ck_assert_uint_eq(vm_block_number(vm, vm->cur), 2);
  ck_assert_int_eq(vm_run(vm), VM_EV_END);   /* and stays ended */
  ck_assert_uint_eq(vm->blocks, 3);
  /* RET there is E-SUB, with the VM's neutral text */
  hstart(sub_and_main(OP_RETEND, 1, OP_RET));
  ck_assert_int_eq(tp_run(vm), VM_EV_ERROR);
  assert_error(S42_E_SUB, 2);
  ck_assert_str_eq(vm->err.msg, "return from the main program");
}
END_TEST

START_TEST(retend_restores_the_saved_register)
{
  /* as RET: the register saved across calls comes back on return */
  hp.saved_reg = 7;
  hblock(10, 1);
  hemit(OP_INT, 9);
  hemit(OP_SETP, 7);
  hemit(OP_COMMIT, 0);
  hemit(OP_RETEND, 0);
  uint32_t entry = hblock(1, 0);
  hemit(OP_INT, 5);
  hemit(OP_SETP, 7);
  hemit(OP_COMMIT, 0);
  hemit(OP_INT, 1);
  hemit(OP_CALL, 0);
  hblock(2, 0);
  hemit(OP_REG, 7);
  hemit(OP_SETP, 8);
  hemit(OP_COMMIT, 0);
  hemit(OP_RETEND, 0);
  hstart(entry);
  vm->yield_all = 1;
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  ck_assert_double_eq(R(7), 5);
  ck_assert_double_eq(R(8), 5);
}
END_TEST

START_TEST(retend_in_verify_and_disasm)
{
  char msg[200];
  hp.entry = sub_and_main(OP_RETEND, 1, OP_RETEND);
  hp.max_stack = 1;
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), 0);   /* the code may end with it */
  /* control leaves the block there: only after its COMMIT */
  hp.code[4] = INS(OP_RETEND, 0);
  hp.code[5] = INS(OP_COMMIT, 0);
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "pc 4: RETEND before block 0 is committed: control leaves a block only after its COMMIT");
  hp.code[4] = INS(OP_COMMIT, 0);
  hp.code[5] = INS(OP_RETEND, 1);
  ck_assert_int_eq(prog_verify(&hp, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "pc 5: RETEND takes no operand but has 1");
  hp.code[5] = INS(OP_RETEND, 0);
  char *buf = NULL;
  size_t n = 0;
  FILE *f = open_memstream(&buf, &n);
  vm_disasm(f, &hp, NULL, 0);
  fclose(f);
  ck_assert_ptr_nonnull(strstr(buf, "0005  RETEND\n"));
  free(buf);
  ck_assert_int_eq(vm_ops[OP_RETEND].pop, 0);
  ck_assert_int_eq(vm_ops[OP_RETEND].push, 0);
}
END_TEST

Suite *suite_vm(void)
{
  Suite *s = suite_create("vm");
  TCase *tc = tcase_create("arithmetic");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, seed_expression_1);
  tcase_add_test(tc, seed_expression_2);
  tcase_add_test(tc, seed_expression_3);
  tcase_add_test(tc, seed_expression_garbled_asi);
  tcase_add_test(tc, parameters_keep_reals);
  tcase_add_test(tc, sign_rules_at_run_time);
  tcase_add_test(tc, axis_rounds_half_away_from_zero);
  tcase_add_test(tc, assignments_left_to_right);
  tcase_add_test(tc, condition_sees_later_words);
  tcase_add_test(tc, word_operand_sees_only_left);
  tcase_add_test(tc, conditions_and_or);
  tcase_add_test(tc, relations_with_tolerance);
  tcase_add_test(tc, one_third_times_three_equals_one);
  tcase_add_test(tc, m20_integer_part);
  tcase_add_test(tc, functions_values);
  tcase_add_test(tc, domain_asi);
  tcase_add_test(tc, domain_log);
  tcase_add_test(tc, domain_trig);
  tcase_add_test(tc, domain_acos_atan);
  tcase_add_test(tc, div0_at_run_time);
  tcase_add_test(tc, power_domain);
  tcase_add_test(tc, range_at_run_time);
  tcase_add_test(tc, feed_clamped_at_run_time);
  tcase_add_test(tc, vm_math_direct);
  suite_add_tcase(s, tc);

  tc = tcase_create("arrays");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, seed_array_reamer);
  tcase_add_test(tc, array_reads_past_length);
  tcase_add_test(tc, array_modes);
  tcase_add_test(tc, array_zero);
  tcase_add_test(tc, array_plus_bound);
  tcase_add_test(tc, array_plus_bound_on_read);
  tcase_add_test(tc, array_minus_bound);
  tcase_add_test(tc, array_cell_range);
  suite_add_tcase(s, tc);

  tc = tcase_create("transactions");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, rollback_registers_and_arrays);
  tcase_add_test(tc, rollback_register_written_twice);
  tcase_add_test(tc, host_failure_rolls_back);
  tcase_add_test(tc, host_register_write_commits);
  suite_add_tcase(s, tc);

  tc = tcase_create("subs");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, sub_repeats_h_times);
  tcase_add_test(tc, sub_runs_after_calling_block);
  tcase_add_test(tc, sub_restores_f);
  tcase_add_test(tc, seed_subs_nesting_order);
  tcase_add_test(tc, m2_in_sub_ends_program);
  tcase_add_test(tc, sub_keeps_caller_condition);
  tcase_add_test(tc, caller_jump_after_return);
  tcase_add_test(tc, h_out_of_range_at_run_time);
  tcase_add_test(tc, nest_eight_levels);
  tcase_add_test(tc, nest_ninth_level);
  suite_add_tcase(s, tc);

  tc = tcase_create("control");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, limit_max_blocks);
  tcase_add_test(tc, limit_exactly_enough);
  tcase_add_test(tc, limit_lowered_between_runs);
  tcase_add_test(tc, pp_without_latch);
  tcase_add_test(tc, pp_with_latch_wins_over_p);
  tcase_add_test(tc, pp_latch_taken_by_next_pp_block);
  tcase_add_test(tc, latch_cleared_at_m2);
  tcase_add_test(tc, watch_yields_start);
  tcase_add_test(tc, watch_array_read_when_handed_over);
  tcase_add_test(tc, start_all_and_yield_all);
  tcase_add_test(tc, sync_blocks_do_not_yield);
  tcase_add_test(tc, many_vms_one_program);
  tcase_add_test(tc, superinstructions_same_errors);
  tcase_add_test(tc, register_forms_as_their_parts);
  tcase_add_test(tc, sincos_is_sin_and_cos);
  tcase_add_test(tc, rel_bounds_hold);
  tcase_add_test(tc, switch_block_yields_only_for_a_change);
  tcase_add_test(tc, switch_block_only_with_nothing_else);
  tcase_add_test(tc, lone_m17_runs_at_once);
  tcase_add_test(tc, blockr_in_the_main_program);
  tcase_add_test(tc, ccall_nests_as_call);
  suite_add_tcase(s, tc);

  tc = tcase_create("program");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, kp_messages_exact);
  tcase_add_test(tc, kp_program_carries_limits_and_texts);
  tcase_add_test(tc, machine_line_from_the_table);
  tcase_add_test(tc, message_formats_checked);
  tcase_add_test(tc, depth_from_the_program);
  tcase_add_test(tc, arrays_and_ranges_from_the_program);
  tcase_add_test(tc, parameter_range_from_the_program);
  tcase_add_test(tc, angle_unit_and_domains_from_the_program);
  tcase_add_test(tc, block_numbers_32_bit);
  suite_add_tcase(s, tc);

  tc = tcase_create("retend");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, retend_returns_from_a_call);
  tcase_add_test(tc, retend_repeats_as_ret);
  tcase_add_test(tc, retend_ends_the_main_program);
  tcase_add_test(tc, retend_restores_the_saved_register);
  tcase_add_test(tc, retend_in_verify_and_disasm);
  suite_add_tcase(s, tc);
  return s;
}
