/* A compiled program: bytecode, constants, conversion rules, the block table
 * (bytecode -> block number, line, column) and a per-instruction column map
 * (prog_col),
 * and what the VM is to enforce and say for it: the dialect's limits
 * (`lim`: call depth, arrays, value ranges, the angle unit and the
 * functions' domains) and its message texts (`msgs`, vm/msgs.h).
 * Dialect-neutral: what a block *means* to the machine is kept by the front
 * end in `ext`, indexed like `blocks`; the VM never looks at it. */
#ifndef S42_PROGRAM_H
#define S42_PROGRAM_H

#include "opcodes.h"
#include <stddef.h>
#include <stdint.h>

#define VM_NREG 128   /* register file: the dialect decides what each holds */
#define VM_NSLOT 16   /* word slots of the pending block record */
/* The VM's fixed upper bounds; a program's limits (struct prog_limits) lie
 * at or below them, and vm_init refuses a program whose limits do not. */
#define VM_DEPTH_MAX 256   /* nested calls (FMS-3000 allows 65535: s42 stops at 256) */
#define VM_ARRAYS_MAX 4    /* arrays: the 2 bits of an ARR operand */
#define VM_CELLS_MAX 64    /* cells of one array */

/* How SET converts and checks a value before storing it. */
struct prog_rule {
  double lo, hi;
  uint8_t round;     /* round half away from zero first */
  uint8_t clamp_hi;  /* above hi: store hi instead of failing (2: and the front end
                        already warned, the value being known when it checked) */
  uint8_t err;       /* error code (vm/errors.h) when outside lo..hi */
  char name[13];     /* the word, for the message ("X", "R12", "F") */
};

struct prog_block {
  uint32_t code;     /* first instruction (its BLOCK) */
  uint32_t line;
  uint32_t number;   /* 0: the block has no number (the 2С42 has 3 digits, 2У22 5, FMS-3000 7) */
  uint16_t col;
  uint16_t unit;     /* 0 = main program, 1.. = subs in text order */
};

/* What the VM enforces, set by the front end for its dialect (prog_init
 * gives the VM's upper bounds and no ranges: a front end that sets nothing
 * gets a VM that refuses only what it cannot hold). */
struct prog_limits {
  uint32_t depth;              /* nested calls at most (E-NEST beyond); <= VM_DEPTH_MAX */
  uint32_t arrays;             /* arrays the ARR and MASK operands may name; <= VM_ARRAYS_MAX */
  uint32_t cells;              /* cells of each array (E-ARRAY+ past them); <= VM_CELLS_MAX */
  double param_lo, param_hi;   /* what SETP stores (E-RANGE outside) */
  double cell_lo, cell_hi;     /* what AWR stores (E-RANGE outside) */
  double angle;                /* degrees per unit of SIN COS TAN's argument and of ASIN ACOS ATAN's result */
  double trig_max;             /* SIN COS TAN: |x| <= trig_max (E-DOMAIN outside) */
  double atan_max;             /* ATAN: |x| <= atan_max */
  double log_max;              /* LOG: 0 < x <= log_max */
};

struct vm_msgs;   /* vm/msgs.h */

/* A column of 255 or more (few: a block is at most 320 characters) is
 * PROG_COLBIG in program.cols and kept in program.colx by its pc. */
#define PROG_COLBIG 255u
struct prog_colx { uint32_t pc; uint16_t col; };

struct program {
  uint32_t *code;  size_t ncode, capcode;
  uint8_t *cols;                      /* column of each instruction (prog_col), PROG_COLBIG: in colx */
  struct prog_colx *colx;  size_t ncolx, capcolx;   /* the columns of PROG_COLBIG or more, by pc */
  double *k;       size_t nk, capk;
  uint32_t kseen[64];                 /* prog_const's memory: 1 + the index of the latest constant
                                         of each hash of its bits (a hint, checked), 0 none */
  struct prog_rule *rules; size_t nrules, caprules;
  struct prog_block *blocks; size_t nblocks, capblocks;
  uint32_t entry;                     /* pc where execution starts */
  uint32_t max_stack;                 /* the deepest stack any block needs (the front end
                                         records it; vm_init refuses more than the VM has) */
  int saved_reg;                      /* register saved across calls, -1 none */
  struct prog_limits lim;             /* the dialect's limits (above) */
  const struct vm_msgs *msgs;         /* the dialect's texts (not owned); NULL: the VM's neutral ones */
  const char *file;                   /* for messages (not owned) */
  void *ext;                          /* front end's per-block data */
  const void *runtime;                /* the front end's runtime for the session (src/core/sess_rt.h) */
  void (*ext_free)(void *);
};

void prog_init(struct program *p);
void prog_free(struct program *p);
/* The most instructions a program may have: a jump's or a call's operand
 * is a block (OPD_PC), so the code is not bound by the 24-bit operand
 * space; 2^30 instructions (4 GiB of code) is far beyond the blocks a
 * program may have (INS_AMAX + 1) at any realistic length. */
#define PROG_MAX_CODE 0x40000000u
/* Appending; each returns the new index, or -1 when out of memory or out of
 * its space: PROG_MAX_CODE instructions, the 24-bit operand space for
 * constants and blocks (the caller reports it). */
long prog_emit_grow(struct program *p, uint32_t ins, unsigned col);
static inline long prog_emit(struct program *p, uint32_t ins, unsigned col)
{
  if (p->ncode >= p->capcode || col >= PROG_COLBIG)   /* full (or at PROG_MAX_CODE); a column for colx */
    return prog_emit_grow(p, ins, col);
  p->code[p->ncode] = ins;
  p->cols[p->ncode] = (uint8_t)col;
  return (long)p->ncode++;
}

/* The column of instruction pc (< ncode): 1.., 0 none; at most 65535. */
unsigned prog_col_big(const struct program *p, size_t pc);
static inline unsigned prog_col(const struct program *p, size_t pc)
{
  unsigned c = p->cols[pc];
  return c != PROG_COLBIG ? c : prog_col_big(p, pc);
}
/* Set the column of instruction pc (< capcode); 0, or -1 out of memory. */
int prog_col_set_big(struct program *p, size_t pc, unsigned col);
static inline int prog_col_set(struct program *p, size_t pc, unsigned col)
{
  if (col >= PROG_COLBIG)
    return prog_col_set_big(p, pc, col);
  p->cols[pc] = (uint8_t)col;
  return 0;
}
/* Instruction `to` takes the column of `from`. */
static inline int prog_col_copy(struct program *p, size_t to, size_t from)
{
  if (p->cols[from] == PROG_COLBIG)
    return prog_col_set_big(p, to, prog_col_big(p, from));
  p->cols[to] = p->cols[from];
  return 0;
}
long prog_const(struct program *p, double v);
/* n constants in a row, none reused; the index of the first, or -1. */
long prog_consts(struct program *p, const double *v, size_t n);
long prog_rule(struct program *p, const struct prog_rule *r);
long prog_block_add(struct program *p, const struct prog_block *b);
/* prog_block_add, its common case inline. */
static inline long prog_block_push(struct program *p, const struct prog_block *b)
{
  if (p->nblocks >= p->capblocks || p->nblocks > INS_AMAX)   /* full (or past the 24-bit operands) */
    return prog_block_add(p, b);
  p->blocks[p->nblocks] = *b;
  return (long)p->nblocks++;
}
/* Index of the block whose code contains pc (binary search). */
size_t prog_block_at(const struct program *p, uint32_t pc);

#endif
