/* Bytecode verification (vm/verify.h).  One linear pass: the block table
 * first, then each block's instructions from its BLOCK with the stack
 * effects of vm/opcodes.h.  A block's code runs straight through (its jumps
 * and calls come last, with the stack empty), so walking it in order is
 * exact: together with "every jump lands on a BLOCK" this proves the stack
 * of every path the VM can take. */
#include "verify.h"
#include "errors.h"
#include "msgs.h"
#include "opcodes.h"
#include "vmmath.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static int bad(char *msg, size_t n, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int bad(char *msg, size_t n, const char *fmt, ...)
{
  if (msg && n) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, n, fmt, ap);
    va_end(ap);
  }
  return -1;
}

static const char *plural(size_t n)
{
  return n == 1 ? "" : "s";
}

/* Instructions that may run with values on the stack: they compute, store
 * or test and go on to the next instruction.  Every other one must find the
 * stack empty (after its own pops): the VM may leave vm_run there (BLOCK,
 * MACH, SYNC, END), whose stack is a local, or go elsewhere (jumps, CALL,
 * RET), or close the block (COMMIT).  An opcode added to vm/opcodes.h is of
 * that strict kind until it is listed here. */
static int may_hold(int op)
{
  switch (op) {
  case OP_CONST: case OP_INT: case OP_REG: case OP_WORD:
  case OP_NEG: case OP_ADD: case OP_SUB: case OP_MUL: case OP_DIV: case OP_POW:
  case OP_SIN: case OP_COS: case OP_TAN: case OP_ASIN: case OP_ACOS: case OP_ATAN: case OP_LOG:
  case OP_SET: case OP_ARD: case OP_AWR: case OP_AZERO: case OP_APTR0: case OP_APTREND:
  case OP_CMP: case OP_AND: case OP_OR: case OP_COND: case OP_TRUNC:
  case OP_ADDI: case OP_SUBI: case OP_MULI: case OP_DIVI:
  case OP_ADDK: case OP_SUBK: case OP_MULK: case OP_DIVK:
  case OP_ADDR: case OP_SUBR: case OP_MULR: case OP_DIVR:
  case OP_SETP: case OP_CMPC: case OP_CMPCK: case OP_CMPCR: case OP_CMPRK: case OP_RSIN: case OP_RCOS:
  case OP_RSINCOS: case OP_RCOSSIN:
    return 1;
  default:
    return op >= OP_RADDI && op <= OP_ATANP;   /* the register forms compute or store */
  }
}

/* The register forms that store (SETP's fused forms). */
static int stores_param(int op)
{
  return op >= OP_ADDP && op <= OP_ATANP;
}

/* A block is a transaction: it closes once, with COMMIT or one of the two
 * that commit and jump; control leaves it only after that (so every loop
 * counts blocks against the budget, and nothing runs with a transaction
 * left open across blocks), and its work -- stores, array words, the
 * machine's turn -- comes before. */
static int commits(int op)
{
  return op == OP_COMMIT || op == OP_CJMP || op == OP_CJCOND || op == OP_CCALL;
}

static int leaves(int op)
{
  return op == OP_CALL || op == OP_CCALL || op == OP_PPJ || op == OP_JMP || op == OP_JCOND || op == OP_RET || op == OP_RETEND ||
         op == OP_END;
}

static int works(int op)
{
  switch (op) {
  case OP_SET: case OP_SETP: case OP_AWR: case OP_ARD: case OP_AZERO: case OP_APTR0: case OP_APTREND:
  case OP_TRUNC: case OP_MACH: case OP_MACHS: case OP_SYNC:
    return 1;
  default:
    return stores_param(op);
  }
}

/* Instructions that never go on to the next one: the code may end with one. */
static int stops(int op)
{
  return op == OP_END || op == OP_JMP || op == OP_CJMP || op == OP_RET || op == OP_RETEND;
}

/* pc starts a block: what a jump, a call or the entry may target (the
 * compiler targets nothing else). */
static int block_start(const struct program *p, uint32_t pc)
{
  if (pc >= p->ncode || !vm_op_starts_block(INS_OP(p->code[pc])))
    return 0;
  uint32_t b = INS_A(p->code[pc]);
  return b < p->nblocks && p->blocks[b].code == pc;
}

/* What stands at pc, for a message: "SET", "BLOCK 3". */
static const char *what(const struct program *p, uint32_t pc, char *buf, size_t n)
{
  unsigned op = INS_OP(p->code[pc]);
  if (op >= OP__COUNT)
    snprintf(buf, n, "opcode %u", op);
  else if (vm_ops[op].opd == OPD_NONE)
    snprintf(buf, n, "%s", vm_ops[op].name);
  else
    snprintf(buf, n, "%s %u", vm_ops[op].name, INS_A(p->code[pc]));
  return buf;
}

/* The operand a, of kind kind, of the instruction op at pc (or of its EXT
 * word there). */
static int operand_of(const struct program *p, uint32_t pc, int op, int kind, uint32_t a, char *msg, size_t n)
{
  const char *name = vm_ops[op].name;
  switch (kind) {
  case OPD_NONE:
    if (a)
      return bad(msg, n, "pc %u: %s takes no operand but has %u", pc, name, a);
    return 0;
  case OPD_K:
    if (a >= p->nk)
      return bad(msg, n, "pc %u: %s %u but the program has %zu constant%s", pc, name, a, p->nk, plural(p->nk));
    return 0;
  case OPD_I:
    return 0;
  case OPD_REG:
    if (a >= VM_NREG)
      return bad(msg, n, "pc %u: %s r%u but there are %d registers", pc, name, a, VM_NREG);
    return 0;
  case OPD_SLOT:
    if (a >= VM_NSLOT)
      return bad(msg, n, "pc %u: %s w%u but there are %d word slots", pc, name, a, VM_NSLOT);
    return 0;
  case OPD_SET: {
    unsigned dest = a & 0x3ff, r = a >> 10;
    if (dest >= VM_NREG + VM_NSLOT)
      return bad(msg, n, "pc %u: %s into %u, neither a register (0..%d) nor a word slot (%d..%d)", pc, name, dest,
                 VM_NREG - 1, VM_NREG, VM_NREG + VM_NSLOT - 1);
    if (r >= p->nrules)
      return bad(msg, n, "pc %u: %s with rule %u but the program has %zu rule%s", pc, name, r, p->nrules,
                 plural(p->nrules));
    return 0;
  }
  case OPD_ARR:
    if ((a & 3) >= p->lim.arrays)
      return bad(msg, n, "pc %u: %s of array %u but there %s %u arra%s", pc, name, (a & 3) + 1,
                 p->lim.arrays == 1 ? "is" : "are", p->lim.arrays, p->lim.arrays == 1 ? "y" : "ys");
    if ((a >> 2) < 1 || (a >> 2) > 3)
      return bad(msg, n, "pc %u: %s in mode %u, not 1 (then advance), 2 (stay) or 3 (back first)", pc, name, a >> 2);
    return 0;
  case OPD_MASK:
    if (a < 1 || a >= 1u << p->lim.arrays)
      return bad(msg, n, "pc %u: %s of arrays %u, not a mask of the %u array%s (1..%u)", pc, name, a,
                 p->lim.arrays, plural(p->lim.arrays), (1u << p->lim.arrays) - 1);
    return 0;
  case OPD_REL:
    /* 0 is an empty relation ("never"), which the language allows */
    if (a > 7)
      return bad(msg, n, "pc %u: %s relation %u, not 0..7 (1 <, 2 =, 4 >)", pc, name, a);
    return 0;
  case OPD_RELK:
    if ((a >> 3) >= p->nk)
      return bad(msg, n, "pc %u: %s with constant %u but the program has %zu constant%s", pc, name, a >> 3, p->nk,
                 plural(p->nk));
    return 0;
  case OPD_RELR:
    if ((a >> 3) >= VM_NREG)
      return bad(msg, n, "pc %u: %s with r%u but there are %d registers", pc, name, a >> 3, VM_NREG);
    return 0;
  case OPD_PC:   /* a block: the jump lands on its BLOCK (the table is checked first) */
    if (a >= p->nblocks)
      return bad(msg, n, "pc %u: %s to block %u but the program has %zu block%s", pc, name, a, p->nblocks,
                 plural(p->nblocks));
    return 0;
  case OPD_BLK:
    if (a >= p->nblocks)
      return bad(msg, n, "pc %u: %s %u but the program has %zu block%s", pc, name, a, p->nblocks, plural(p->nblocks));
    if (p->blocks[a].code != pc)
      return bad(msg, n, "pc %u: %s %u but block %u starts at pc %u", pc, name, a, a, p->blocks[a].code);
    return 0;
  case OPD_RI:
    return 0;
  case OPD_RK:
    if ((a >> 7) >= p->nk)
      return bad(msg, n, "pc %u: %s r%u %u but the program has %zu constant%s", pc, name, a & 127, a >> 7, p->nk,
                 plural(p->nk));
    return 0;
  case OPD_RR:
    if ((a >> 7) >= VM_NREG)
      return bad(msg, n, "pc %u: %s r%u r%u but there are %d registers", pc, name, a & 127, a >> 7, VM_NREG);
    return 0;
  case OPD_SW:
    if (!(a & 0xfffu) || ((a >> 12) & ~a & 0xfffu))
      return bad(msg, n, "pc %u: %s switches %u state %u: the mask is empty or the state sets a switch outside it", pc,
                 name, a & 0xfffu, a >> 12);
    return 0;
  case OPD_KT: {
    double lo, hi;
    if (p->nk < 3 || a > p->nk - 3)
      return bad(msg, n, "pc %u: %s constants %u..%u but the program has %zu constant%s", pc, name, a, a + 2, p->nk,
                 plural(p->nk));
    if (!isfinite(p->k[a]))
      return bad(msg, n, "pc %u: %s with constant %u = %.17g, not a finite number", pc, name, a, p->k[a]);
    vm_rel_bounds(p->k[a], &lo, &hi);
    if (memcmp(&lo, &p->k[a + 1], sizeof lo) || memcmp(&hi, &p->k[a + 2], sizeof hi))
      return bad(msg, n, "pc %u: %s with constant %u = %.17g: its bounds are %.17g..%.17g, not %.17g..%.17g", pc,
                 name, a, p->k[a], p->k[a + 1], p->k[a + 2], lo, hi);
    return 0;
  }
  default:
    return bad(msg, n, "pc %u: %s has operand kind %d, which the verifier does not know", pc, name, kind);
  }
}

static int operand(const struct program *p, uint32_t pc, char *msg, size_t n)
{
  uint32_t ins = p->code[pc];
  int op = (int)INS_OP(ins);
  return operand_of(p, pc, op, vm_ops[op].opd, INS_A(ins), msg, n);
}

/* lo..hi a range (not NaN, lo <= hi). */
static int range_ok(double lo, double hi)
{
  return lo <= hi;
}

/* The program's limits: within what the VM holds, and each one sane. */
static int limits(const struct program *p, char *msg, size_t n)
{
  const struct prog_limits *l = &p->lim;
  if (l->depth > VM_DEPTH_MAX)
    return bad(msg, n, "the program nests calls %u deep; the VM holds %d", l->depth, VM_DEPTH_MAX);
  if (l->arrays > VM_ARRAYS_MAX || l->cells > VM_CELLS_MAX)
    return bad(msg, n, "the program has %u arrays of %u cells; the VM holds %d of %d", l->arrays, l->cells,
               VM_ARRAYS_MAX, VM_CELLS_MAX);
  if (!range_ok(l->param_lo, l->param_hi))
    return bad(msg, n, "the parameter range %.10g..%.10g is empty", l->param_lo, l->param_hi);
  if (!range_ok(l->cell_lo, l->cell_hi))
    return bad(msg, n, "the array cell range %.10g..%.10g is empty", l->cell_lo, l->cell_hi);
  if (!(l->angle > 0 && isfinite(l->angle)))
    return bad(msg, n, "the angle unit is %.10g degrees, not a positive number", l->angle);
  if (!(l->trig_max >= 0) || !(l->atan_max >= 0) || !(l->log_max > 0))
    return bad(msg, n, "a function's domain is empty (SIN COS TAN |x| <= %.10g, ATAN |x| <= %.10g, LOG 0 < x <= %.10g)",
               l->trig_max, l->atan_max, l->log_max);
  char why[200];
  if (vm_msgs_check(p->msgs, why, sizeof why))
    return bad(msg, n, "the message table%s%s: %s", p->msgs->name ? " of " : "", p->msgs->name ? p->msgs->name : "",
               why);
  return 0;
}

/* The block table, the entry and what the code needs around it. */
static int table(const struct program *p, char *msg, size_t n)
{
  char buf[40];
  if (limits(p, msg, n))
    return -1;
  if (p->ncode == 0)
    return bad(msg, n, "the program has no instructions");
  if (!p->code || !p->cols)
    return bad(msg, n, "the program's code or its column map is missing");
  if (p->ncode > PROG_MAX_CODE)
    return bad(msg, n, "the program has %zu instructions; at most %u run", p->ncode, PROG_MAX_CODE);
  if (p->nblocks == 0 || !p->blocks)
    return bad(msg, n, "the program has no blocks");
  if (p->nblocks > (size_t)INS_AMAX + 1)
    return bad(msg, n, "the program has %zu blocks; BLOCK numbers only %u", p->nblocks, INS_AMAX + 1);
  if ((p->nk && !p->k) || (p->nrules && !p->rules))
    return bad(msg, n, "the program's constants or rules are missing");
  for (size_t b = 0; b < p->nblocks; b++) {
    uint32_t c = p->blocks[b].code;
    if (b == 0 && c != 0)
      return bad(msg, n, "block 0 starts at pc %u: the code before it belongs to no block", c);
    if (b > 0 && c <= p->blocks[b - 1].code)
      return bad(msg, n, "block %zu starts at pc %u, not after block %zu (pc %u)", b, c, b - 1,
                 p->blocks[b - 1].code);
    if (c >= p->ncode)
      return bad(msg, n, "block %zu starts at pc %u but the program has %zu instruction%s", b, c, p->ncode,
                 plural(p->ncode));
    if (p->code[c] != INS(OP_BLOCK, b) && p->code[c] != INS(OP_BLOCKR, b))
      return bad(msg, n, "block %zu starts at pc %u with %s, not BLOCK %zu", b, c, what(p, c, buf, sizeof buf), b);
    /* BLOCKR runs the three after it itself when nothing watches */
    if (p->code[c] == INS(OP_BLOCKR, b) &&
        (c + 3 >= p->ncode || (b + 1 < p->nblocks && p->blocks[b + 1].code < c + 4) ||
         p->code[c + 1] != INS(OP_SYNC, 0) || p->code[c + 2] != INS(OP_COMMIT, 0) || p->code[c + 3] != INS(OP_RET, 0)))
      return bad(msg, n, "block %zu: BLOCKR at pc %u is not followed by SYNC, COMMIT and RET in its block", b, c);
  }
  if (p->entry >= p->ncode)
    return bad(msg, n, "entry %04u but the program has %zu instruction%s", p->entry, p->ncode, plural(p->ncode));
  if (!block_start(p, p->entry))
    return bad(msg, n, "entry %04u is %s, not the start of a block", p->entry, what(p, p->entry, buf, sizeof buf));
  uint32_t last = (uint32_t)p->ncode - 1;
  unsigned op = INS_OP(p->code[last]);
  if (op < OP__COUNT && !stops((int)op))
    return bad(msg, n, "pc %u: the code ends with %s, which runs on past its end (the last instruction must be "
               "END, JMP, CJMP, RET or RETEND)", last, vm_ops[op].name);
  if (p->saved_reg < -1 || p->saved_reg >= VM_NREG)
    return bad(msg, n, "the register saved across calls is %d, not -1 (none) or 0..%d", p->saved_reg, VM_NREG - 1);
  for (size_t r = 0; r < p->nrules; r++) {
    const struct prog_rule *ru = &p->rules[r];
    if (!memchr(ru->name, 0, sizeof ru->name))
      return bad(msg, n, "rule %zu: its name is not terminated", r);
    if (ru->err <= S42_E_NONE || ru->err >= S42_E_COUNT)
      return bad(msg, n, "rule %zu (%s): error code %u is not one of vm/errors.h", r, ru->name, ru->err);
  }
  return 0;
}

int prog_verify_need(const struct program *p, uint32_t *need, char *msg, size_t n)
{
  uint32_t max = 0;
  size_t deepest = 0;
  if (need)
    *need = 0;
  if (table(p, msg, n))
    return -1;
  for (size_t b = 0; b < p->nblocks; b++) {
    uint32_t from = p->blocks[b].code;
    uint32_t to = b + 1 < p->nblocks ? p->blocks[b + 1].code : (uint32_t)p->ncode;
    uint32_t depth = 0, commit = UINT32_MAX;
    for (uint32_t pc = from; pc < to; pc++) {
      unsigned op = INS_OP(p->code[pc]);
      if (op >= OP__COUNT)
        return bad(msg, n, "pc %u: opcode %u is no instruction (there are %d)", pc, op, OP__COUNT);
      if (op == OP_EXT)
        return bad(msg, n, "pc %u: EXT after no two-word instruction (block %zu): it only follows one", pc, b);
      if (operand(p, pc, msg, n))
        return -1;
      const struct vm_opinfo *o = &vm_ops[op];
      if (o->ext != OPD_NONE) {
        /* two words: the EXT word is this instruction's, and never runs */
        if (pc + 1 >= to || INS_OP(p->code[pc + 1]) != OP_EXT)
          return bad(msg, n, "pc %u: %s is two words but no EXT word follows it (block %zu)", pc, o->name, b);
        if (operand_of(p, pc + 1, (int)op, o->ext, INS_A(p->code[pc + 1]), msg, n))
          return -1;
      }
      if (depth < (uint32_t)o->pop)
        return bad(msg, n, "pc %u: %s pops %d value%s but the stack holds %u (block %zu)", pc, o->name, o->pop,
                   plural((size_t)o->pop), depth, b);
      depth -= (uint32_t)o->pop;
      if (commits((int)op) && commit != UINT32_MAX)
        return bad(msg, n, "pc %u: %s commits block %zu a second time (first at pc %u)", pc, o->name, b, commit);
      if (commits((int)op))
        commit = pc;
      else if (leaves((int)op) && commit == UINT32_MAX)
        return bad(msg, n, "pc %u: %s before block %zu is committed: control leaves a block only after its COMMIT",
                   pc, o->name, b);
      else if (works((int)op) && commit != UINT32_MAX)
        return bad(msg, n, "pc %u: %s after block %zu is committed (pc %u): a block's work is done inside its "
                   "transaction", pc, o->name, b, commit);
      if (depth && !may_hold((int)op))
        return bad(msg, n, "pc %u: %s with %u value%s left on the stack (block %zu): it needs the stack empty", pc,
                   o->name, depth, plural(depth), b);
      depth += (uint32_t)o->push;
      if (depth > max) {
        max = depth;
        deepest = b;
        if (need)
          *need = max;
      }
      if (o->ext != OPD_NONE)
        pc++;   /* its EXT word, checked above */
    }
    if (depth)
      return bad(msg, n, "pc %u: block %zu ends with %u value%s left on the stack", to - 1, b, depth, plural(depth));
    if (commit == UINT32_MAX)
      return bad(msg, n, "pc %u: block %zu ends without COMMIT, CJMP or CJCOND: its transaction never closes",
                 to - 1, b);
  }
  if (p->max_stack < max)
    return bad(msg, n, "block %zu (pc %u) needs a stack of %u values but the program records %u", deepest,
               p->blocks[deepest].code, max, p->max_stack);
  return 0;
}

int prog_verify(const struct program *p, char *msg, size_t n)
{
  return prog_verify_need(p, NULL, msg, n);
}
