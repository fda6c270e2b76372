/* `s42 disasm`: the bytecode block by block, each headed by its source line. */
#ifndef S42_DISASM_H
#define S42_DISASM_H

#include "program.h"
#include <stdio.h>

/* src/n: the program text, for the source lines (may be NULL). */
void vm_disasm(FILE *f, const struct program *p, const char *src, size_t n);
/* The opcode table as Markdown (docs/opcodes.md). */
void vm_opcodes_md(FILE *f);

#endif
