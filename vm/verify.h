/* A compiled program's bytecode checked before it runs: the VM trusts its
 * program (no bounds checks in the dispatch loop), so whatever a front end
 * built is verified here, in the tests and the fuzzers. */
#ifndef S42_VERIFY_H
#define S42_VERIFY_H

#include "program.h"
#include <stddef.h>
#include <stdint.h>

/* 0 when p is safe to run; -1 with the first problem in msg ("pc 17: CONST 40
 * but the program has 12 constants").  Checked: every opcode and every
 * operand for its kind (constant, register, slot, rule, array, mask,
 * relation, jump target, block); the block table (blocks in code order, each
 * starting with its own BLOCK) and the entry; the stack of every block
 * (never below 0, empty wherever the VM may leave the block, and at its
 * end); each block a transaction (one COMMIT, CJMP or CJCOND, its work
 * before it, jumps, calls and the end after it -- so every loop counts
 * against the block budget); that the code cannot run off its end; the
 * rules and the register saved across calls; the program's limits (within
 * the VM's bounds, each range non-empty, the angle unit positive, the array
 * operands within lim.arrays) and its message table (every format against
 * the arguments vm/msgs.h declares); and that p->max_stack is no less than
 * what the deepest block needs.  Linear in the program's size. */
int prog_verify(const struct program *p, char *msg, size_t n);
/* The same, and *need (when not NULL) is the deepest stack any block
 * reaches, as far as the walk got. */
int prog_verify_need(const struct program *p, uint32_t *need, char *msg, size_t n);

#endif
