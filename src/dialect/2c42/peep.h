/* The 2С42's peephole pass over a block's emitted code (peep.c). */
#ifndef S42_PEEP_H
#define S42_PEEP_H

#include "program.h"
#include <stddef.h>

/* Fuse the code of the block whose BLOCK is at from -- its words, its
 * stores and its condition, up to and including its MACH or SYNC, with
 * nothing after them yet -- into the register forms of vm/opcodes.h, and
 * close the gaps: p->ncode shrinks, p->cols follows.  Every fusion is
 * exact (the VM raises each error of a fused instruction with the code,
 * message and column of the part that raised it).  Returns 0, or -1 out
 * of memory (the code is then left as it was). */
int peep_block(struct program *p, size_t from);

#endif
