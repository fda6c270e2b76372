/* The 2С42's peephole pass (peep.h): a block's straight-line code, fused
 * into the VM's register forms (vm/opcodes.h, "register forms").
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

/* What each opcode is to the pass, one lookup (the pass looks at every
 * instruction of every block): ADDI..DIVR by arithmetic (0 ADD .. 3 DIV)
 * and operand (0 I, 1 K, 2 R) as 1 + kind * 4 + row; ADD..DIV as 1 + row. */
#define AX(op, kind, row) [op] = 1 + (kind) * 4 + (row)
static const uint8_t arith_x_tab[256] = {
  AX(OP_ADDI, 0, 0), AX(OP_SUBI, 0, 1), AX(OP_MULI, 0, 2), AX(OP_DIVI, 0, 3),
  AX(OP_ADDK, 1, 0), AX(OP_SUBK, 1, 1), AX(OP_MULK, 1, 2), AX(OP_DIVK, 1, 3),
  AX(OP_ADDR, 2, 0), AX(OP_SUBR, 2, 1), AX(OP_MULR, 2, 2), AX(OP_DIVR, 2, 3),
};
static const uint8_t arith_stack_tab[256] = {[OP_ADD] = 1, [OP_SUB] = 2, [OP_MUL] = 3, [OP_DIV] = 4};

/* The column of the ops ADDI..DIVR: which arithmetic (0 ADD .. 3 DIV) and
 * which operand (0 I, 1 K, 2 R), or -1. */
static inline int arith_x(unsigned op, int *row, int *kind)
{
  unsigned t = arith_x_tab[op & 0xff];
  if (!t)
    return -1;
  *row = (int)(t - 1) % 4;
  *kind = (int)(t - 1) / 4;
  return 0;
}

static inline int arith_stack(unsigned op)
{
  return (int)arith_stack_tab[op & 0xff] - 1;
}

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

/* Which pairs can start a fusion, by one lookup an instruction: the low
 * bits of pair_tab[op] say what op can be first in (REG_FIRST: a REG;
 * SETP_FIRST: an arithmetic or a function a SETP may follow), the high bits
 * what it can be second in; a pair (a, b) can fuse when
 * pair_tab[a] & pair_tab[b] >> 2. */
enum { REG_FIRST = 1, SETP_FIRST = 2, REG_SECOND = 4, SETP_SECOND = 8 };
static uint8_t pair_tab[256];

static void __attribute__((constructor)) pair_tab_init(void)
{
  for (unsigned op = 0; op < 256; op++) {
    unsigned t = 0;
    if (op == OP_REG)
      t |= REG_FIRST;
    if (arith_x_tab[op] || arith_stack_tab[op] || trig_store(op))
      t |= SETP_FIRST;
    if (arith_x_tab[op] || op == OP_CMPCK || op == OP_SIN || op == OP_COS)
      t |= REG_SECOND;
    if (op == OP_SETP)
      t |= SETP_SECOND;
    pair_tab[op] = (uint8_t)t;
  }
}

int peep_block(struct program *p, size_t from)
{
  uint32_t *code = p->code;
  uint16_t *cols = p->cols;
  size_t n = p->ncode, o, i = from + 1;
  /* nothing to fuse in most blocks: look before writing */
  if (i >= n)
    return 0;
  unsigned prev = pair_tab[INS_OP(code[i])];
  for (; i + 1 < n; i++) {
    unsigned t = pair_tab[INS_OP(code[i + 1])];
    if (prev & t >> 2)
      break;
    prev = t;
  }
  if (i + 1 >= n)
    return 0;
  o = i;
  while (i < n) {
    if (i + 1 >= n || !(pair_tab[INS_OP(code[i])] & pair_tab[INS_OP(code[i + 1])] >> 2)) {
      cols[o] = cols[i];   /* no fusion starts here */
      code[o++] = code[i++];
      continue;
    }
    uint32_t w0 = code[i], w1 = i + 1 < n ? code[i + 1] : 0, w2 = i + 2 < n ? code[i + 2] : 0;
    unsigned op0 = INS_OP(w0), op1 = i + 1 < n ? INS_OP(w1) : OP__COUNT, op2 = i + 2 < n ? INS_OP(w2) : OP__COUNT;
    unsigned op3 = i + 3 < n ? INS_OP(code[i + 3]) : OP__COUNT;
    int row, kind;
    if (op0 == OP_REG && INS_A(w0) < VM_NREG && arith_x(op1, &row, &kind) == 0 && INS_A(w1) < XMAX) {
      uint32_t a = INS_A(w0) | INS_A(w1) << 7;
      if (op2 == OP_SETP) {
        /* REG a; OPx; SETP d */
        uint16_t c1 = cols[i + 1], c2 = cols[i + 2];
        code[o] = INS(rstore[kind][row], a);
        cols[o++] = c1;
        code[o] = INS(OP_EXT, INS_A(w2));
        cols[o++] = c2;
        i += 3;
      } else {
        /* REG a; OPx */
        cols[o] = cols[i + 1];
        code[o++] = INS(rpush[kind][row], a);
        i += 2;
      }
      continue;
    }
    if (op0 == OP_REG && (op1 == OP_SIN || op1 == OP_COS) && w2 == w0 && op3 == (op1 == OP_SIN ? OP_COS : OP_SIN)) {
      /* REG a; SIN; REG a; COS: the sine and the cosine of one angle (the
       * second cannot fail where the first did not: the same value, the
       * same domain) */
      cols[o] = cols[i + 1];
      code[o++] = INS(op1 == OP_SIN ? OP_RSINCOS : OP_RCOSSIN, INS_A(w0));
      i += 4;
      continue;
    }
    if (op0 == OP_REG && (op1 == OP_SIN || op1 == OP_COS)) {
      /* REG a; SIN */
      cols[o] = cols[i + 1];
      code[o++] = INS(op1 == OP_SIN ? OP_RSIN : OP_RCOS, INS_A(w0));
      i += 2;
      continue;
    }
    if (op0 == OP_REG && INS_A(w0) < VM_NREG && op1 == OP_CMPCK && isfinite(p->k[INS_A(w1) >> 3])) {
      /* REG a; CMPCK rel k */
      long j = triplet(p, p->k[INS_A(w1) >> 3]);
      if (j < 0)
        return -1;
      uint16_t c1 = cols[i + 1];
      code[o] = INS(OP_CMPRK, (INS_A(w1) & 7) | INS_A(w0) << 3);
      cols[o++] = c1;
      code[o] = INS(OP_EXT, (uint32_t)j);
      cols[o++] = c1;
      i += 2;
      continue;
    }
    if (op1 == OP_SETP && trig_store(op0)) {
      /* SIN; SETP d */
      uint16_t c0 = cols[i], c1 = cols[i + 1];
      code[o] = INS(trig_store(op0), 0);
      cols[o++] = c0;
      code[o] = INS(OP_EXT, INS_A(w1));
      cols[o++] = c1;
      i += 2;
      continue;
    }
    if (op1 == OP_SETP && (arith_x(op0, &row, &kind) == 0 || (kind = -1, row = arith_stack(op0)) >= 0)) {
      /* OPx; SETP d   or   OP; SETP d */
      uint16_t c0 = cols[i], c1 = cols[i + 1];
      code[o] = kind < 0 ? INS(sstore[row], 0) : INS(xstore[kind][row], INS_A(w0));
      cols[o++] = c0;
      code[o] = INS(OP_EXT, INS_A(w1));
      cols[o++] = c1;
      i += 2;
      continue;
    }
    cols[o] = cols[i];
    code[o++] = code[i++];
  }
  p->ncode = o;
  return 0;
}
