/* A compiled program: bytecode, constants, conversion rules, the block table
 * (bytecode -> block number, line, column) and a per-instruction column map.
 * Dialect-neutral: what a block *means* to the machine is kept by the front
 * end in `ext`, indexed like `blocks`; the VM never looks at it. */
#ifndef S42_PROGRAM_H
#define S42_PROGRAM_H

#include <stddef.h>
#include <stdint.h>

#define VM_NREG 128   /* register file: the dialect decides what each holds */
#define VM_NSLOT 16   /* word slots of the pending block record */

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

struct program {
  uint32_t *code;  size_t ncode, capcode;
  uint16_t *cols;                     /* column of each instruction */
  double *k;       size_t nk, capk;
  struct prog_rule *rules; size_t nrules, caprules;
  struct prog_block *blocks; size_t nblocks, capblocks;
  uint32_t entry;                     /* pc where execution starts */
  uint32_t max_stack;                 /* the deepest stack any block needs (the front end
                                         records it; vm_init refuses more than the VM has) */
  int saved_reg;                      /* register saved across calls, -1 none */
  const char *file;                   /* for messages (not owned) */
  void *ext;                          /* front end's per-block data */
  void (*ext_free)(void *);
};

void prog_init(struct program *p);
void prog_free(struct program *p);
/* Appending; each returns the new index, or -1 when out of memory or out of
 * the 24-bit operand space (the caller reports it). */
long prog_emit_grow(struct program *p, uint32_t ins, unsigned col);
static inline long prog_emit(struct program *p, uint32_t ins, unsigned col)
{
  if (p->ncode >= p->capcode)   /* full (or at the 24-bit operand space) */
    return prog_emit_grow(p, ins, col);
  p->code[p->ncode] = ins;
  p->cols[p->ncode] = (uint16_t)(col > 0xffff ? 0xffff : col);
  return (long)p->ncode++;
}
long prog_const(struct program *p, double v);
long prog_rule(struct program *p, const struct prog_rule *r);
long prog_block_add(struct program *p, const struct prog_block *b);
/* Index of the block whose code contains pc (binary search). */
size_t prog_block_at(const struct program *p, uint32_t pc);

#endif
