/* The 2С42's peephole rules (peep.h): a block's straight-line code, fused
 * into the VM's register forms (vm/opcodes.h, "register forms") as it is
 * emitted.
 *
 *   REG a; ADDI x; SETP d        RADDIP a|x<<7, EXT d    (and SUB MUL DIV, I K R)
 *   REG a; ADDI x                RADDI a|x<<7
 *   ADDI x; SETP d               ADDIP x, EXT d
 *   ADD; SETP d                  ADDP, EXT d
 *   REG a; CMPCK rel k           CMPRK rel|a<<3, EXT j   (K[j] K[j+1] K[j+2]: K[k], its bounds)
 *   REG a; SIN / COS             RSIN a / RCOS a
 *   REG a; SIN; REG a; COS       RSINCOS a               (COS first: RCOSSIN a)
 *   SIN; SETP d                  SINP, EXT d             (and COS ASIN ACOS ATAN)
 *
 * Each instruction, as it is emitted (or rewritten in place at the end),
 * is fused with those before it: REG a; ADDI x becomes RADDI when the ADDI
 * comes, and RADDI; SETP then RADDIP; RSIN a; REG a; COS becomes RSINCOS.
 * No rule's result is the first part of another but these two, and a REG
 * is the second part of none: taken one instruction at a time from the
 * left, the rules fuse what a pass over the finished code, from the left
 * and longest first, would.
 *
 * Why each is safe: a block's code runs straight through (vm/verify.c), no
 * jump lands inside it, and the parts touch nothing between them that the
 * next part reads: the fused instruction reads the same registers in the
 * same order and stores last, as the parts did.  The arithmetic's column
 * stays on the first word, the store's goes to the EXT word, so an error
 * says what and where it said before.  Operands that do not fit (a
 * register, integer or constant index from 2^17 on) are left unfused. */
#include "peep.h"
#include "opcodes.h"
#include "vmmath.h"
#include <math.h>
#include <string.h>

#define XMAX (1u << 17)   /* the x of a|x<<7 */

/* What each opcode is to the rules, one lookup: ADDI..DIVR by arithmetic
 * (0 ADD .. 3 DIV) and operand (0 I, 1 K, 2 R) as 1 + kind * 4 + row;
 * ADD..DIV as 1 + row; RADDI..RDIVR likewise (the register push forms). */
#define AX(op, kind, row) [op] = 1 + (kind) * 4 + (row)
static const uint8_t arith_x_tab[256] = {
  AX(OP_ADDI, 0, 0), AX(OP_SUBI, 0, 1), AX(OP_MULI, 0, 2), AX(OP_DIVI, 0, 3),
  AX(OP_ADDK, 1, 0), AX(OP_SUBK, 1, 1), AX(OP_MULK, 1, 2), AX(OP_DIVK, 1, 3),
  AX(OP_ADDR, 2, 0), AX(OP_SUBR, 2, 1), AX(OP_MULR, 2, 2), AX(OP_DIVR, 2, 3),
};
static const uint8_t rpush_tab[256] = {
  AX(OP_RADDI, 0, 0), AX(OP_RSUBI, 0, 1), AX(OP_RMULI, 0, 2), AX(OP_RDIVI, 0, 3),
  AX(OP_RADDK, 1, 0), AX(OP_RSUBK, 1, 1), AX(OP_RMULK, 1, 2), AX(OP_RDIVK, 1, 3),
  AX(OP_RADDR, 2, 0), AX(OP_RSUBR, 2, 1), AX(OP_RMULR, 2, 2), AX(OP_RDIVR, 2, 3),
};
static const uint8_t arith_stack_tab[256] = {[OP_ADD] = 1, [OP_SUB] = 2, [OP_MUL] = 3, [OP_DIV] = 4};

/* The function-and-store form of a function, 0 none. */
static inline unsigned trig_store(unsigned op)
{
  switch (op) {
  case OP_SIN: return OP_SINP;
  case OP_COS: return OP_COSP;
  case OP_ASIN: return OP_ASINP;
  case OP_ACOS: return OP_ACOSP;
  case OP_ATAN: return OP_ATANP;
  default: return 0;
  }
}

/* The opcodes, by arithmetic and operand, of each form. */
static const uint8_t rpush[3][4] = {{OP_RADDI, OP_RSUBI, OP_RMULI, OP_RDIVI},
                                    {OP_RADDK, OP_RSUBK, OP_RMULK, OP_RDIVK},
                                    {OP_RADDR, OP_RSUBR, OP_RMULR, OP_RDIVR}};
static const uint8_t rstore[3][4] = {{OP_RADDIP, OP_RSUBIP, OP_RMULIP, OP_RDIVIP},
                                     {OP_RADDKP, OP_RSUBKP, OP_RMULKP, OP_RDIVKP},
                                     {OP_RADDRP, OP_RSUBRP, OP_RMULRP, OP_RDIVRP}};
static const uint8_t xstore[3][4] = {{OP_ADDIP, OP_SUBIP, OP_MULIP, OP_DIVIP},
                                     {OP_ADDKP, OP_SUBKP, OP_MULKP, OP_DIVKP},
                                     {OP_ADDRP, OP_SUBRP, OP_MULRP, OP_DIVRP}};
static const uint8_t sstore[4] = {OP_ADDP, OP_SUBP, OP_MULP, OP_DIVP};

/* Which pairs a rule can fuse (peep_pair): REG first before an
 * arithmetic with an operand, CMPCK, SIN or COS second; an arithmetic, a
 * function of trig_store or a register push form first before SETP. */
#define RF PEEP_REG_FIRST
#define SF PEEP_SETP_FIRST
#define RS PEEP_REG_SECOND
#define SS PEEP_SETP_SECOND
const uint8_t peep_pair_tab[256] = {
  [OP_REG] = RF, [OP_SETP] = SS,
  [OP_ADDI] = SF | RS, [OP_SUBI] = SF | RS, [OP_MULI] = SF | RS, [OP_DIVI] = SF | RS,
  [OP_ADDK] = SF | RS, [OP_SUBK] = SF | RS, [OP_MULK] = SF | RS, [OP_DIVK] = SF | RS,
  [OP_ADDR] = SF | RS, [OP_SUBR] = SF | RS, [OP_MULR] = SF | RS, [OP_DIVR] = SF | RS,
  [OP_ADD] = SF, [OP_SUB] = SF, [OP_MUL] = SF, [OP_DIV] = SF,
  [OP_SIN] = SF | RS, [OP_COS] = SF | RS, [OP_ASIN] = SF, [OP_ACOS] = SF, [OP_ATAN] = SF,
  [OP_CMPCK] = RS,
  [OP_RADDI] = SF, [OP_RSUBI] = SF, [OP_RMULI] = SF, [OP_RDIVI] = SF,
  [OP_RADDK] = SF, [OP_RSUBK] = SF, [OP_RMULK] = SF, [OP_RDIVK] = SF,
  [OP_RADDR] = SF, [OP_RSUBR] = SF, [OP_RMULR] = SF, [OP_RDIVR] = SF,
};

/* K[b] with its bounds as three constants in a row (the last three reused
 * when they are these); the index, or -1. */
static long triplet(struct program *p, double b)
{
  double t[3];
  t[0] = b;
  vm_rel_bounds(b, &t[1], &t[2]);
  if (p->nk >= 3 && memcmp(&p->k[p->nk - 3], t, sizeof t) == 0)
    return (long)p->nk - 3;
  return prog_consts(p, t, 3);
}

int peep_last(struct program *p, size_t from)
{
  uint32_t *code = p->code;
  size_t n = p->ncode;
  if (n < from + 2)
    return 0;
  uint32_t w0 = code[n - 2], w1 = code[n - 1];
  unsigned op0 = INS_OP(w0), op1 = INS_OP(w1);
  unsigned t;
  if (op0 == OP_REG) {
    if (INS_A(w0) < VM_NREG && (t = arith_x_tab[op1]) != 0 && INS_A(w1) < XMAX) {
      /* REG a; OPx: the SETP that may follow makes it RADDIP and EXT */
      if (prog_col_copy(p, n - 2, n - 1))
        return -1;
      code[n - 2] = INS(rpush[(t - 1) / 4][(t - 1) % 4], INS_A(w0) | INS_A(w1) << 7);
      p->ncode = n - 1;
      return 0;
    }
    if (op1 == OP_SIN || op1 == OP_COS) {
      unsigned first = op1 == OP_SIN ? OP_RCOS : OP_RSIN;
      if (n >= from + 3 && code[n - 3] == INS(first, INS_A(w0))) {
        /* REG a; SIN; REG a; COS, the first two already RSIN a: the sine
         * and the cosine of one angle (the second cannot fail where the
         * first did not: the same value, the same domain) */
        code[n - 3] = INS(op1 == OP_COS ? OP_RSINCOS : OP_RCOSSIN, INS_A(w0));
        p->ncode = n - 2;
        return 0;
      }
      /* REG a; SIN */
      if (prog_col_copy(p, n - 2, n - 1))
        return -1;
      code[n - 2] = INS(op1 == OP_SIN ? OP_RSIN : OP_RCOS, INS_A(w0));
      p->ncode = n - 1;
      return 0;
    }
    if (INS_A(w0) < VM_NREG && op1 == OP_CMPCK && isfinite(p->k[INS_A(w1) >> 3])) {
      /* REG a; CMPCK rel k */
      long j = triplet(p, p->k[INS_A(w1) >> 3]);
      if (j < 0)
        return -1;
      if (prog_col_copy(p, n - 2, n - 1))
        return -1;
      code[n - 2] = INS(OP_CMPRK, (INS_A(w1) & 7) | INS_A(w0) << 3);
      code[n - 1] = INS(OP_EXT, (uint32_t)j);
      return 0;
    }
    return 0;
  }
  if (op1 != OP_SETP)
    return 0;
  if ((t = rpush_tab[op0]) != 0) {
    /* REG a; OPx; SETP d, the first two already fused */
    code[n - 2] = INS(rstore[(t - 1) / 4][(t - 1) % 4], INS_A(w0));
    code[n - 1] = INS(OP_EXT, INS_A(w1));
  } else if (trig_store(op0)) {
    /* SIN; SETP d */
    code[n - 2] = INS(trig_store(op0), 0);
    code[n - 1] = INS(OP_EXT, INS_A(w1));
  } else if ((t = arith_x_tab[op0]) != 0) {
    /* OPx; SETP d */
    code[n - 2] = INS(xstore[(t - 1) / 4][(t - 1) % 4], INS_A(w0));
    code[n - 1] = INS(OP_EXT, INS_A(w1));
  } else if ((t = arith_stack_tab[op0]) != 0) {
    /* OP; SETP d */
    code[n - 2] = INS(sstore[t - 1], 0);
    code[n - 1] = INS(OP_EXT, INS_A(w1));
  }
  return 0;
}
