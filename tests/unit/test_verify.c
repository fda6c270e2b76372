/* The bytecode verifier (vm/verify.h) and the program's maximum stack:
 * every program the repository holds that compiles verifies, with the
 * maximum stack the compiler recorded exactly what the verifier finds;
 * hand-corrupted programs are refused with the message that says why;
 * vm_init refuses a program that needs more stack than the VM has; and a
 * program the verifier accepts, however it was mutated, runs without
 * tripping a sanitizer.  The make target passes S42_SRCDIR and S42_PLUGINS. */
#include "suites.h"
#include "errors.h"
#include "msgs.h"
#include "opcodes.h"
#include "plugin.h"
#include "session.h"
#include "verify.h"
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Subs first, a loop, a call with H, the operational jump, arrays, a
 * constant and an expression four values deep (block N3). */
static const char rich[] =
  "№5 R2+R2+1 T11+R2%3 ^\n"
  "№6 M17 ^\n"
  "№1 R1+3 R3+25000 R4-7 T0 L5 H2 ^\n"
  "№2 R1+R1-1 P(R1:B:0)2 ^\n"
  "№3 G01 X+R3%(R1+R2%(R4-R5)) F100 R5+T21 ^\n"
  "№4 PP7 P7 ^\n"
  "№7 TT M02 ^\n";
/* its code, as tp_disasm shows it (the pcs the messages below name):
 *  0 BLOCK 0   1 RADDIP r2 1  2 EXT r2  3 RMULI r2 3  4 AWR 1.1
 *  5 SYNC      6 COMMIT
 *  7 BLOCKR 1  8 SYNC     9 COMMIT  10 RET   (a lone M17: BLOCKR)
 * 11 BLOCK 2  12 INT 3   13 SETP r1 14 INT 25000 15 SETP r3 16 CONST 0
 * 17 SETP r4  18 APTR0 3 19 INT 2   20 SET w7   21 SYNC    22 COMMIT
 * 23 WORD w7  24 CALL 0000
 * 25 BLOCK 3  26 RSUBIP r1 1  27 EXT r1  28 CMPRK > r1  29 EXT 2 (K[2] = 0
 *             with its bounds K[3], K[4])  30 SYNC  31 CJCOND 0025
 * 32 BLOCK 4  33 REG r3  34 REG r1  35 REG r2  36 RSUBR r4 r5
 * 37 MUL      38 ADD     39 MUL     40 SET w0  41 INT 100  42 SET r117
 * 43 ARD 1.2  44 SETP r5 45 MACH    46 COMMIT
 * 47 BLOCK 5  48 SYNC    49 COMMIT  50 PPJ 0052  51 JMP 0052
 * 52 BLOCK 6  53 AZERO 3 54 MACH    55 COMMIT  56 END  57 END
 * (the peephole pass, src/dialect/2c42/peep.c, fused the register forms;
 * a jump's operand is the block it goes to, shown as the pc it starts at:
 * CALL 0 is block 0, CJCOND 3 block 3, PPJ 6 and JMP 6 block 6) */

static struct tprog t;
static char msg[300];

static void setup(void)
{
  memset(&t, 0, sizeof t);
  prog_init(&t.p);
  diag_init(&t.d, "t.kp");
  msg[0] = 0;
}

static void teardown(void)
{
  tp_free(&t);
}

static void load(const char *src)
{
  tp_free(&t);
  tp_compile(&t, src);
  ck_assert_msg(t.rc == 0, "does not compile:\n%s", tp_diags(&t.d));
}

/* The rich program with instruction pc replaced by ins: refused, saying want. */
static void refused(uint32_t pc, uint32_t ins, const char *want)
{
  load(rich);
  ck_assert_uint_eq(t.p.ncode, 58);
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), 0);
  t.p.code[pc] = ins;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, want);
}

/* ---- what the compiler emits ---- */

START_TEST(rich_program_verifies)
{
  load(rich);
  uint32_t need = 99;
  ck_assert_msg(prog_verify_need(&t.p, &need, msg, sizeof msg) == 0, "%s", msg);
  ck_assert_uint_eq(need, 4);
  ck_assert_uint_eq(t.p.max_stack, 4);
  /* the instructions the comment above lists */
  ck_assert_uint_eq(t.p.code[1], INS(OP_RADDIP, 2 | 1 << 7));
  ck_assert_uint_eq(t.p.code[2], INS(OP_EXT, 2));
  ck_assert_uint_eq(t.p.code[24], INS(OP_CALL, 0));
  ck_assert_uint_eq(t.p.code[28], INS(OP_CMPRK, 4 | 1 << 3));
  ck_assert_uint_eq(t.p.code[29], INS(OP_EXT, 2));
  ck_assert_uint_eq(t.p.code[39], INS(OP_MUL, 0));
  ck_assert_uint_eq(t.p.code[31], INS(OP_CJCOND, 3));
  ck_assert_uint_eq(t.p.code[50], INS(OP_PPJ, 6));
  ck_assert_uint_eq(t.p.code[51], INS(OP_JMP, 6));
}
END_TEST

START_TEST(max_stack_known)
{
  /* nothing on the stack but the values stored one at a time */
  load("N1 G01 X+1000 F500\nN2 M2\n");
  ck_assert_uint_eq(t.p.max_stack, 1);
  /* a call's count is a value on the stack too; a call without H is
   * CCALL, which needs none */
  load("N5 M17\nN1 L5 H2\nN2 M2\n");
  ck_assert_uint_eq(t.p.max_stack, 1);
  load("N5 M17\nN1 L5\nN2 M2\n");
  ck_assert_uint_eq(t.p.max_stack, 0);
  /* a chain of fused operands needs one value, products in a sum two */
  load("N1 R1+R2+R3+R4+R5\nN2 M2\n");
  ck_assert_uint_eq(t.p.max_stack, 1);
  load("N1 R1+R2%R3+R4%R5\nN2 M2\n");
  ck_assert_uint_eq(t.p.max_stack, 2);
  /* a fused right operand adds no depth: R1, R2 then SUBR r3 */
  load("N1 R1+R1%(R2-R3)\nN2 M2\n");
  ck_assert_uint_eq(t.p.max_stack, 2);
  /* right-nested: one more value per level; the deepest block counts */
  load("N1 R9+R1\nN2 R9+R1%(R2+R3%(R4-R5%(R6+R7%(R8-R1))))\nN3 M2\n");
  ck_assert_uint_eq(t.p.max_stack, 8);
  uint32_t need = 0;
  ck_assert_msg(prog_verify_need(&t.p, &need, msg, sizeof msg) == 0, "%s", msg);
  ck_assert_uint_eq(need, 8);
  /* a condition compared against a register fuses into CMPCR: one value;
   * against an expression, CMPC takes both sides */
  load("N1 R1+1 P(R1+R2:M:R3)1\nN2 M2\n");
  ck_assert_uint_eq(t.p.max_stack, 1);
  load("N1 R1+1 P(R1:M:R2+R3%R4)1\nN2 M2\n");
  ck_assert_uint_eq(t.p.max_stack, 3);
}
END_TEST

/* Every program of the repository and of the fuzz corpora that compiles
 * verifies, and records the maximum stack the verifier finds. */
struct tally { size_t files, compiled, deepest; const char *deepest_file; uint32_t max; };

static char *slurp(const char *path, size_t *n)
{
  FILE *f = fopen(path, "rb");
  if (!f)
    return NULL;
  size_t cap = 4096, len = 0;
  char *buf = malloc(cap);
  size_t r;
  while (buf && (r = fread(buf + len, 1, cap - len, f)) > 0) {
    len += r;
    if (len == cap) {
      char *q = realloc(buf, cap *= 2);
      if (!q) {
        free(buf);
        buf = NULL;
      }
      buf = q;
    }
  }
  fclose(f);
  *n = len;
  return buf;
}

static void check_file(const char *path, struct plug_set *ps, struct tally *ty)
{
  size_t n;
  char *src = slurp(path, &n);
  ck_assert_msg(src != NULL, "cannot read %s", path);
  struct program p;
  struct diag_list d;
  prog_init(&p);
  diag_init(&d, path);
  ty->files++;
  if (comp_program_with(src, n, &d, &p, ps) == 0) {
    uint32_t need = 0;
    int r = prog_verify_need(&p, &need, msg, sizeof msg);
    ck_assert_msg(r == 0, "%s compiles but does not verify: %s", path, msg);
    ck_assert_msg(need == p.max_stack, "%s: the compiler records a stack of %u, the verifier finds %u", path,
                  p.max_stack, need);
    ty->compiled++;
    if (need > ty->max)
      ty->max = need;
  }
  prog_free(&p);
  diag_free(&d);
  free(src);
}

static int has_suffix(const char *s, const char *suf)
{
  size_t a = strlen(s), b = strlen(suf);
  return a >= b && strcmp(s + a - b, suf) == 0;
}

/* Every regular file under dir (only *.kp unless all), recursively. */
static void walk(const char *dir, int all, struct plug_set *ps, struct tally *ty)
{
  DIR *dp = opendir(dir);
  if (!dp)
    return;
  struct dirent *e;
  while ((e = readdir(dp))) {
    if (e->d_name[0] == '.')
      continue;
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    struct stat st;
    if (stat(path, &st))
      continue;
    if (S_ISDIR(st.st_mode))
      walk(path, all, ps, ty);
    else if (S_ISREG(st.st_mode) && (all || has_suffix(e->d_name, ".kp")))
      check_file(path, ps, ty);
  }
  closedir(dp);
}

static const char *srcdir(void)
{
  const char *d = getenv("S42_SRCDIR");
  ck_assert_msg(d != NULL, "S42_SRCDIR is not set (run through make unit)");
  return d;
}

START_TEST(everything_that_compiles_verifies)
{
  struct plug_set *ps = calloc(1, sizeof *ps);
  ck_assert_ptr_nonnull(ps);
  plug_scan(ps, getenv("S42_PLUGINS"));
  char dir[4096];
  /* the bundled programs: every one compiles */
  struct tally ty = {0};
  snprintf(dir, sizeof dir, "%s/programs", srcdir());
  walk(dir, 0, ps, &ty);
  ck_assert_uint_ge(ty.files, 30);
  size_t bundled = ty.compiled;
  ck_assert_uint_ge(bundled, 11);
  /* the guide, the tutorial, the benchmarks, the tests' programs */
  static const char *const kp[] = {"docs", "bench", "tests", "../shared/conformance"};
  for (size_t i = 0; i < sizeof kp / sizeof *kp; i++) {
    snprintf(dir, sizeof dir, "%s/%s", srcdir(), kp[i]);
    walk(dir, 0, ps, &ty);
  }
  /* the fuzz corpora and regressions, whatever their names */
  static const char *const any[] = {"tests/fuzz/corpus/compile", "tests/fuzz/corpus/vm", "tests/fuzz/regress"};
  size_t before = ty.compiled;
  for (size_t i = 0; i < sizeof any / sizeof *any; i++) {
    snprintf(dir, sizeof dir, "%s/%s", srcdir(), any[i]);
    walk(dir, 1, ps, &ty);
  }
  ck_assert_uint_ge(ty.compiled - before, 500);
  ck_assert_uint_ge(ty.max, 4);
  plug_free(ps);
  free(ps);
}
END_TEST

/* ---- hand-corrupted programs ---- */

START_TEST(bad_opcode)
{
  char want[80];
  snprintf(want, sizeof want, "pc 3: opcode %d is no instruction (there are %d)", OP__COUNT, OP__COUNT);
  refused(3, INS(OP__COUNT, 0), want);
  refused(0, 0xff, "block 0 starts at pc 0 with opcode 255, not BLOCK 0");
}
END_TEST

START_TEST(constant_out_of_range)
{
  refused(16, INS(OP_CONST, 40), "pc 16: CONST 40 but the program has 5 constants");
  refused(28, INS(OP_CMPCK, 4 | 5 << 3), "pc 28: CMPCK with constant 5 but the program has 5 constants");
  refused(44, INS(OP_ADDK, 9), "pc 44: ADDK 9 but the program has 5 constants");
  refused(3, INS(OP_RMULK, 2 | 9 << 7), "pc 3: RMULK r2 9 but the program has 5 constants");
  /* CMPRK's constant and its bounds: three, as vm_rel_bounds makes them */
  refused(29, INS(OP_EXT, 3), "pc 29: CMPRK constants 3..5 but the program has 5 constants");
  refused(29, INS(OP_EXT, 0), "pc 29: CMPRK with constant 0 = -7: its bounds are 0..0, not "
          "-7.0000000279999997..-6.9999999720000003");
}
END_TEST

START_TEST(operand_out_of_range)
{
  refused(33, INS(OP_REG, 128), "pc 33: REG r128 but there are 128 registers");
  refused(2, INS(OP_EXT, 128), "pc 2: RADDIP r128 but there are 128 registers");
  refused(36, INS(OP_RSUBR, 4 | 128 << 7), "pc 36: RSUBR r4 r128 but there are 128 registers");
  refused(28, INS(OP_CMPRK, 4 | 200 << 3), "pc 28: CMPRK with r200 but there are 128 registers");
  refused(23, INS(OP_WORD, 16), "pc 23: WORD w16 but there are 16 word slots");
  refused(20, INS(OP_SET, 7 | 9 << 10), "pc 20: SET with rule 9 but the program has 3 rules");
  refused(20, INS(OP_SET, 144), "pc 20: SET into 144, neither a register (0..127) nor a word slot (128..143)");
  refused(4, INS(OP_AWR, 2 | 1 << 2), "pc 4: AWR of array 3 but there are 2 arrays");
  refused(43, INS(OP_ARD, 0), "pc 43: ARD in mode 0, not 1 (then advance), 2 (stay) or 3 (back first)");
  refused(18, INS(OP_APTR0, 4), "pc 18: APTR0 of arrays 4, not a mask of the 2 arrays (1..3)");
  refused(53, INS(OP_AZERO, 0), "pc 53: AZERO of arrays 0, not a mask of the 2 arrays (1..3)");
  refused(5, INS(OP_SYNC, 1), "pc 5: SYNC takes no operand but has 1");
  /* MACHS: a mask of switches, and a state within it */
  load("N1 M23 M26\nN2 M2\n");
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), 0);
  ck_assert_uint_eq(t.p.code[1], INS(OP_MACHS, 3 | 2 << 12));
  t.p.code[1] = INS(OP_MACHS, 1 | 2 << 12);
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "pc 1: MACHS switches 1 state 2: the mask is empty or the state sets a switch outside it");
  t.p.code[1] = INS(OP_MACHS, 0);
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "pc 1: MACHS switches 0 state 0: the mask is empty or the state sets a switch outside it");
  /* a two-word instruction has its EXT word, and an EXT word its instruction */
  refused(27, INS(OP_SYNC, 0), "pc 26: RSUBIP is two words but no EXT word follows it (block 3)");
  refused(26, INS(OP_REG, 1), "pc 27: EXT after no two-word instruction (block 3): it only follows one");
  /* a CMP relation: 0 (an empty relation, "never") is fine, 8 is not */
  load("N1 R1+1 P(R1::R2)1\nN2 M2\n");
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), 0);
  size_t i = 0;
  while (INS_OP(t.p.code[i]) != OP_CMPCR)
    i++;
  t.p.code[i] = INS(OP_CMPCR, 2 << 3 | 0);
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), 0);
  load("N1 R1+1 P(R1+R2::R3+R4)1\nN2 M2\n");
  i = 0;
  while (INS_OP(t.p.code[i]) != OP_CMPC)
    i++;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), 0);
  t.p.code[i] = INS(OP_CMPC, 8);
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  char want[80];
  snprintf(want, sizeof want, "pc %zu: CMPC relation 8, not 0..7 (1 <, 2 =, 4 >)", i);
  ck_assert_str_eq(msg, want);
}
END_TEST

START_TEST(jump_into_nowhere)
{
  /* the operand is a block: past the last one it is nowhere */
  refused(51, INS(OP_JMP, 7), "pc 51: JMP to block 7 but the program has 7 blocks");
  refused(31, INS(OP_CJCOND, 58), "pc 31: CJCOND to block 58 but the program has 7 blocks");
  refused(24, INS(OP_CALL, INS_AMAX), "pc 24: CALL to block 16777215 but the program has 7 blocks");
  refused(50, INS(OP_PPJ, 100000), "pc 50: PPJ to block 100000 but the program has 7 blocks");
  /* any block is somewhere: the jump lands on its BLOCK, never inside one */
  load(rich);
  t.p.code[51] = INS(OP_JMP, 2);
  t.p.code[31] = INS(OP_CJCOND, 6);
  ck_assert_msg(prog_verify(&t.p, msg, sizeof msg) == 0, "%s", msg);
}
END_TEST

START_TEST(unbalanced_stack)
{
  /* a pop of a value nobody pushed */
  refused(12, INS(OP_NEG, 0), "pc 12: NEG pops 1 value but the stack holds 0 (block 2)");
  refused(34, INS(OP_SETP, 9), "pc 38: ADD pops 2 values but the stack holds 1 (block 4)");
  refused(1, INS(OP_ADDIP, 1), "pc 1: ADDIP pops 1 value but the stack holds 0 (block 0)");
  /* a value left where the VM leaves the block or closes it */
  refused(44, INS(OP_NEG, 0), "pc 45: MACH with 1 value left on the stack (block 4): it needs the stack empty");
  refused(21, INS(OP_INT, 1), "pc 22: COMMIT with 1 value left on the stack (block 2): it needs the stack empty");
  refused(50, INS(OP_INT, 5), "pc 51: JMP with 1 value left on the stack (block 5): it needs the stack empty");
  /* or at its end */
  refused(24, INS(OP_INT, 1), "pc 24: block 2 ends with 2 values left on the stack");
  refused(6, INS(OP_INT, 7), "pc 6: block 0 ends with 1 value left on the stack");
}
END_TEST

START_TEST(transaction)
{
  /* control leaves a block only once it is committed */
  refused(22, INS(OP_INT, 1), "pc 24: CALL before block 2 is committed: control leaves a block only after its COMMIT");
  refused(31, INS(OP_JCOND, 3), "pc 31: JCOND before block 3 is committed: control leaves a block only after its "
          "COMMIT");
  refused(9, INS(OP_SYNC, 0), "block 1: BLOCKR at pc 7 is not followed by SYNC, COMMIT and RET in its block");
  load(rich);
  t.p.code[7] = INS(OP_BLOCK, 1);   /* the plain BLOCK: the RET's own check */
  t.p.code[9] = INS(OP_SYNC, 0);
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "pc 10: RET before block 1 is committed: control leaves a block only after its COMMIT");
  /* BLOCKR only where SYNC, COMMIT and RET follow it in its block */
  refused(0, INS(OP_BLOCKR, 0), "block 0: BLOCKR at pc 0 is not followed by SYNC, COMMIT and RET in its block");
  refused(47, INS(OP_BLOCKR, 5), "block 5: BLOCKR at pc 47 is not followed by SYNC, COMMIT and RET in its block");
  /* CCALL commits: nothing of the block's work after it, once */
  load("N5 M17\nN1 R1+1 L5\nN2 M2\n");
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), 0);
  uint32_t cc = t.p.blocks[1].code;
  while (INS_OP(t.p.code[cc]) != OP_CCALL)
    cc++;
  t.p.code[cc - 1] = INS(OP_COMMIT, 0);   /* its SYNC */
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "pc 8: CCALL commits block 1 a second time (first at pc 7)");
  /* once */
  refused(45, INS(OP_COMMIT, 0), "pc 46: COMMIT commits block 4 a second time (first at pc 45)");
  refused(6, INS(OP_SYNC, 0), "pc 6: block 0 ends without COMMIT, CJMP or CJCOND: its transaction never closes");
  /* and its work is done before */
  refused(56, INS(OP_MACH, 0), "pc 56: MACH after block 6 is committed (pc 55): a block's work is done inside its "
          "transaction");
  refused(23, INS(OP_ARD, 0 | 1 << 2), "pc 23: ARD after block 2 is committed (pc 22): a block's work is done inside "
          "its transaction");
}
END_TEST

START_TEST(block_mismatch)
{
  refused(25, INS(OP_BLOCK, 4), "block 3 starts at pc 25 with BLOCK 4, not BLOCK 3");
  refused(28, INS(OP_BLOCK, 3), "pc 28: BLOCK 3 but block 3 starts at pc 25");
  refused(28, INS(OP_BLOCK, 7), "pc 28: BLOCK 7 but the program has 7 blocks");
  refused(25, INS(OP_SYNC, 0), "block 3 starts at pc 25 with SYNC, not BLOCK 3");
  /* the block table itself */
  load(rich);
  t.p.blocks[4].code = 20;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "block 4 starts at pc 20, not after block 3 (pc 25)");
  load(rich);
  t.p.blocks[0].code = 1;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "block 0 starts at pc 1: the code before it belongs to no block");
  load(rich);
  t.p.blocks[6].code = 58;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "block 6 starts at pc 58 but the program has 58 instructions");
}
END_TEST

START_TEST(entry_and_end)
{
  load(rich);
  t.p.entry = 12;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "entry 0012 is INT 3, not the start of a block");
  t.p.entry = 70;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "entry 0070 but the program has 58 instructions");
  /* the code may not run off its end */
  load(rich);
  t.p.ncode = 56;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "pc 55: the code ends with COMMIT, which runs on past its end (the last instruction must be "
                   "END, JMP, CJMP, RET or RETEND)");
  t.p.ncode = 0;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the program has no instructions");
  load(rich);
  t.p.nblocks = 0;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the program has no blocks");
  /* the register saved across calls, the rules' error codes */
  load(rich);
  t.p.saved_reg = 128;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the register saved across calls is 128, not -1 (none) or 0..127");
  load(rich);
  t.p.rules[1].err = S42_E_COUNT;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  char want[80];
  snprintf(want, sizeof want, "rule 1 (%s): error code %d is not one of vm/errors.h", t.p.rules[1].name, S42_E_COUNT);
  ck_assert_str_eq(msg, want);
  memcpy(t.p.rules[1].name, "ABCDEFGHIJKLM", sizeof t.p.rules[1].name);
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "rule 1: its name is not terminated");
}
END_TEST

START_TEST(max_stack_understated)
{
  load(rich);
  t.p.max_stack = 3;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "block 4 (pc 32) needs a stack of 4 values but the program records 3");
  t.p.max_stack = 400;   /* more than needed is no error */
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), 0);
}
END_TEST

/* The program's limits and message table are part of what is verified:
 * within what the VM holds, each range a range, the angle unit a unit, and
 * every format of the table taking the arguments the VM gives it. */
START_TEST(limits_and_messages)
{
  load(rich);
  struct prog_limits keep = t.p.lim;
  t.p.lim.depth = VM_DEPTH_MAX + 1;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the program nests calls 257 deep; the VM holds 256");
  t.p.lim = keep;
  t.p.lim.arrays = VM_ARRAYS_MAX + 1;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the program has 5 arrays of 15 cells; the VM holds 4 of 64");
  t.p.lim = keep;
  t.p.lim.arrays = 1;   /* the rich program uses array 2 (T21 in N3) */
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "pc 18: APTR0 of arrays 3, not a mask of the 1 array (1..1)");
  t.p.lim = keep;
  t.p.lim.param_lo = NAN;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the parameter range nan..9999999 is empty");
  t.p.lim = keep;
  t.p.lim.angle = INFINITY;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the angle unit is inf degrees, not a positive number");
  t.p.lim = keep;
  t.p.lim.trig_max = -1;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "a function's domain is empty (SIN COS TAN |x| <= -1, ATAN |x| <= 9999999, LOG 0 < x <= 9999999)");
  t.p.lim = keep;
  static const struct vm_msgs bad = {.name = "a test", .screen = {[1] = "error %d"}};
  t.p.msgs = &bad;
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), -1);
  ck_assert_str_eq(msg, "the message table of a test: error line (English) \"error %d\": conversion 1 takes an int "
                        "where the argument is a string");
  t.p.msgs = NULL;   /* the VM's own texts */
  ck_assert_int_eq(prog_verify(&t.p, msg, sizeof msg), 0);
}
END_TEST

/* ---- vm_init and the VM's stack ---- */

START_TEST(vm_init_refuses_deep_stack)
{
  struct vm *vm = calloc(1, sizeof *vm);
  ck_assert_ptr_nonnull(vm);
  load(rich);
  t.p.max_stack = VM_STACK;   /* exactly what the VM has: runs */
  ck_assert_int_eq(vm_init(vm, &t.p), 0);
  ck_assert_int_eq(tp_run(vm), VM_EV_END);
  t.p.max_stack = VM_STACK + 1;
  ck_assert_int_eq(vm_init(vm, &t.p), -1);
  ck_assert_int_eq(vm_run(vm), VM_EV_ERROR);
  ck_assert_int_eq(vm_run(vm), VM_EV_ERROR);
  ck_assert_int_eq(vm->err.code, S42_E_LIMIT);
  ck_assert_str_eq(vm->err.msg, "the program needs a stack of 513 values; this VM has 512");
  ck_assert_uint_eq(vm->err.block, 2);   /* the entry block, N1 */
  ck_assert_uint_eq(vm->cur, 2);
  ck_assert_uint_eq(vm->blocks, 0);
  ck_assert_double_eq(vm->reg[1], 0);    /* nothing ran */
  free(vm);
  /* through a session: the run ends at once with the error */
  struct session *s = calloc(1, sizeof *s);
  ck_assert_ptr_nonnull(s);
  sess_init(s, &t.p);
  ck_assert_int_eq(sess_run(s), SE_ERROR);
  ck_assert_int_eq(s->vm.err.code, S42_E_LIMIT);
  ck_assert_int_eq(sess_block_number(s), 1);
  free(s);
}
END_TEST

/* A mutated program the verifier accepts is safe to run, and stops within
 * its block budget: one word of the code replaced by a random one (its own
 * opcode with another operand, a random opcode with a small operand, or any
 * 32 bits), thousands of times; under make asan a run that reads or writes
 * out of bounds fails here, and a loop the budget does not stop hangs. */
static uint32_t rnd(uint64_t *s)
{
  *s = *s * 6364136223846793005ull + 1442695040888963407ull;
  return (uint32_t)(*s >> 33);
}

START_TEST(accepted_mutants_run_safely)
{
  static const char *const srcs[] = {
    rich,
    "N1 R1+5 R2+0\nN2 R2+R2+SI(R1%1000)/CO(R1) T11+R2 R1+R1-1 P(R1:B:0)2\nN3 T0 R3+T21+T11 G01 X+R3 F100\nN4 M2\n",
  };
  struct vm *vm = calloc(1, sizeof *vm);
  ck_assert_ptr_nonnull(vm);
  uint64_t seed = 42;
  size_t accepted = 0, tried = 0;
  for (size_t k = 0; k < sizeof srcs / sizeof *srcs; k++) {
    load(srcs[k]);
    for (int i = 0; i < 6000; i++) {
      uint32_t pc = rnd(&seed) % (uint32_t)t.p.ncode, old = t.p.code[pc];
      uint32_t r = rnd(&seed);
      uint32_t a = rnd(&seed) % 80;
      t.p.code[pc] = r % 3 == 0 ? INS(INS_OP(old), a) : r % 3 == 1 ? INS(r % (OP__COUNT + 2), a) : rnd(&seed);
      tried++;
      if (prog_verify(&t.p, msg, sizeof msg) == 0) {
        accepted++;
        vm_init(vm, &t.p);
        vm->max_blocks = 300;
        vm->yield_all = (int)(r >> 8) & 1;
        for (int ev = 0; ev < 400; ev++) {
          enum vm_event e = vm_run(vm);
          if (e == VM_EV_END || e == VM_EV_ERROR)
            break;
          if ((r >> 9) & 1)
            vm->exit_latch = 1;
        }
      }
      t.p.code[pc] = old;
    }
  }
  /* many an operand mutation verifies; hardly any random word does */
  ck_assert_uint_gt(accepted, tried / 10);
  ck_assert_uint_lt(accepted, tried / 2);
  free(vm);
}
END_TEST

Suite *suite_verify(void)
{
  Suite *s = suite_create("verify");
  TCase *tc = tcase_create("accepts");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, rich_program_verifies);
  tcase_add_test(tc, max_stack_known);
  tcase_add_test(tc, everything_that_compiles_verifies);
  suite_add_tcase(s, tc);

  tc = tcase_create("refuses");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, bad_opcode);
  tcase_add_test(tc, constant_out_of_range);
  tcase_add_test(tc, operand_out_of_range);
  tcase_add_test(tc, jump_into_nowhere);
  tcase_add_test(tc, unbalanced_stack);
  tcase_add_test(tc, transaction);
  tcase_add_test(tc, block_mismatch);
  tcase_add_test(tc, entry_and_end);
  tcase_add_test(tc, max_stack_understated);
  tcase_add_test(tc, limits_and_messages);
  suite_add_tcase(s, tc);

  tc = tcase_create("vm");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, vm_init_refuses_deep_stack);
  tcase_add_test(tc, accepted_mutants_run_safely);
  suite_add_tcase(s, tc);
  return s;
}
