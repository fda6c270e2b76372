/* Disassembler and opcode documentation, both from the one opcode table. */
#include "disasm.h"
#include "opcodes.h"
#include <string.h>

static const char *const opd_names[] = {"", "K", "I", "REG", "SLOT", "SET", "ARR", "MASK", "REL", "RELK", "RELR", "PC", "BLK"};

static void operand(FILE *f, const struct program *p, uint32_t ins)
{
  uint32_t a = INS_A(ins);
  int op = (int)INS_OP(ins);
  switch (vm_ops[op].opd) {
  case OPD_NONE: break;
  case OPD_K: fprintf(f, "%u\t; %.17g", a, a < p->nk ? p->k[a] : 0.0); break;
  case OPD_I: fprintf(f, "%u", a); break;
  case OPD_REG: fprintf(f, "r%u", a); break;
  case OPD_SLOT: fprintf(f, "w%u", a); break;
  case OPD_SET: {
    unsigned dest = a & 0x3ff, r = a >> 10;
    if (dest < VM_NREG)
      fprintf(f, "r%u", dest);
    else
      fprintf(f, "w%u", dest - VM_NREG);
    if (r < p->nrules) {
      const struct prog_rule *ru = &p->rules[r];
      fprintf(f, "\t; %s %.10g..%.10g%s%s", ru->name, ru->lo, ru->hi, ru->round ? " round" : "",
              ru->clamp_hi ? " clamp" : "");
    }
    break;
  }
  case OPD_ARR: fprintf(f, "%u.%u", (a & 3) + 1, a >> 2); break;
  case OPD_MASK: fprintf(f, "%u", a); break;
  case OPD_REL: case OPD_RELK: case OPD_RELR: {
    static const char *const rel[8] = {"never", "<", "=", "<=", ">", "!=", ">=", "always"};
    fprintf(f, "%s", rel[a & 7]);
    if (vm_ops[op].opd == OPD_RELR)
      fprintf(f, " r%u", a >> 3);
    else if (vm_ops[op].opd == OPD_RELK)
      fprintf(f, " %u\t; %.17g", a >> 3, (a >> 3) < p->nk ? p->k[a >> 3] : 0.0);
    break;
  }
  case OPD_PC: {
    size_t b = prog_block_at(p, a);
    fprintf(f, "%04u", a);
    if (b < p->nblocks && p->blocks[b].code == a) {
      if (p->blocks[b].number)
        fprintf(f, "\t; N%u", p->blocks[b].number);
    }
    break;
  }
  case OPD_BLK: fprintf(f, "%u", a); break;
  }
}

static void source_line(FILE *f, const char *src, size_t n, unsigned line)
{
  if (!src)
    return;
  const char *p = src, *end = src + n;
  for (unsigned l = 1; l < line && p < end; l++) {
    const char *q = memchr(p, '\n', (size_t)(end - p));
    if (!q)
      return;
    p = q + 1;
  }
  const char *q = memchr(p, '\n', (size_t)(end - p));
  if (!q)
    q = end;
  if (q > p && q[-1] == '\r')
    q--;
  fprintf(f, ": %.*s", (int)(q - p), p);
}

void vm_disasm(FILE *f, const struct program *p, const char *src, size_t n)
{
  fprintf(f, "; %zu blocks, %zu instructions, %zu constants, entry %04u\n", p->nblocks, p->ncode, p->nk, p->entry);
  size_t b = 0;
  for (uint32_t pc = 0; pc < p->ncode; pc++) {
    while (b < p->nblocks && p->blocks[b].code == pc) {
      const struct prog_block *pb = &p->blocks[b];
      fprintf(f, "\n; ");
      if (pb->number)
        fprintf(f, "N%u", pb->number);
      else
        fprintf(f, "N-");
      fprintf(f, " line %u", pb->line);
      source_line(f, src, n, pb->line);
      fputc('\n', f);
      b++;
    }
    uint32_t ins = p->code[pc];
    int op = (int)INS_OP(ins);
    if (op >= OP__COUNT) {
      fprintf(f, "%04u  ??? %08x\n", pc, ins);
      continue;
    }
    if (vm_ops[op].opd == OPD_NONE) {
      fprintf(f, "%04u  %s", pc, vm_ops[op].name);
    } else {
      fprintf(f, "%04u  %-8s", pc, vm_ops[op].name);
      operand(f, p, ins);
    }
    fputc('\n', f);
  }
}

void vm_opcodes_md(FILE *f)
{
  fprintf(f, "# s42 bytecode\n\nGenerated from `vm/opcodes.h` (`make docs`); do not edit.\n\n"
             "Every instruction is one 32-bit word: the opcode in the low 8 bits, the operand A in the high 24.\n\n"
             "| opcode | operand | pops | pushes | meaning |\n|---|---|---|---|---|\n");
  for (int i = 0; i < OP__COUNT; i++)
    fprintf(f, "| `%s` | %s | %d | %d | %s |\n", vm_ops[i].name, opd_names[vm_ops[i].opd], vm_ops[i].pop,
            vm_ops[i].push, vm_ops[i].doc);
}
