/* The 2С42's peephole rules over a block's code as it is emitted (peep.c). */
#ifndef S42_PEEP_H
#define S42_PEEP_H

#include "program.h"
#include "opcodes.h"
#include <stddef.h>
#include <stdint.h>

/* Fuse the instruction last emitted (or rewritten in place), at
 * p->ncode - 1, with those before it back to from (the block's BLOCK) into
 * the register forms of vm/opcodes.h: p->ncode shrinks, the columns follow.
 * Every fusion is exact (the VM raises each error of a fused instruction
 * with the code, message and column of the part that raised it).  Returns
 * 0, or -1 out of memory (the code is then left as it was). */
int peep_last(struct program *p, size_t from);

/* Whether instruction b after a is a pair a rule may fuse (then call
 * peep_last): one table, the low bits what an opcode can be first in,
 * the high bits what it can be second in. */
enum { PEEP_REG_FIRST = 1, PEEP_SETP_FIRST = 2, PEEP_REG_SECOND = 4, PEEP_SETP_SECOND = 8 };
extern const uint8_t peep_pair_tab[256];
static inline int peep_pair(uint32_t a, uint32_t b)
{
  return peep_pair_tab[INS_OP(a)] & peep_pair_tab[INS_OP(b)] >> 2;
}

#endif
