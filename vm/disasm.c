/* Disassembler and opcode documentation, both from the one opcode table. */
#include "disasm.h"
#include "opcodes.h"
#include <string.h>

static const char *const opd_names[] = {"", "K", "I", "REG", "SLOT", "SET", "ARR", "MASK", "REL", "RELK", "RELR", "PC", "BLK",
                                        "RI", "RK", "RR", "KT", "SW"};
_Static_assert(sizeof opd_names / sizeof *opd_names == OPD_SW + 1, "a name for every operand kind");

static double kat(const struct program *p, uint32_t a)
{
  return a < p->nk ? p->k[a] : 0.0;
}

/* The operand a of kind opd. */
static void operand_of(FILE *f, const struct program *p, int opd, uint32_t a)
{
  switch (opd) {
  case OPD_NONE: break;
  case OPD_K: fprintf(f, "%u\t; %.17g", a, kat(p, a)); break;
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
    if (opd == OPD_RELR)
      fprintf(f, " r%u", a >> 3);
    else if (opd == OPD_RELK)
      fprintf(f, " %u\t; %.17g", a >> 3, kat(p, a >> 3));
    break;
  }
  case OPD_PC:   /* a block: printed as where it starts */
    if (a < p->nblocks) {
      fprintf(f, "%04u", p->blocks[a].code);
      if (p->blocks[a].number)
        fprintf(f, "\t; N%u", p->blocks[a].number);
    } else {
      fprintf(f, "block %u\t; no such block", a);
    }
    break;
  case OPD_BLK: fprintf(f, "%u", a); break;
  case OPD_RI: fprintf(f, "r%u %u", a & 127, a >> 7); break;
  case OPD_RK: fprintf(f, "r%u %u\t; %.17g", a & 127, a >> 7, kat(p, a >> 7)); break;
  case OPD_RR: fprintf(f, "r%u r%u", a & 127, a >> 7); break;
  case OPD_KT:
    fprintf(f, "%u\t; %.17g (%.17g..%.17g)", a, kat(p, a), kat(p, a + 1), kat(p, a + 2));
    break;
  case OPD_SW: fprintf(f, "%u %u\t; mask, state", a & 0xfffu, a >> 12); break;
  }
}

static void operand(FILE *f, const struct program *p, uint32_t ins)
{
  operand_of(f, p, vm_ops[INS_OP(ins)].opd, INS_A(ins));
}

/* Where the last source line shown began: blocks come in line order, so
 * each line is found from the one before (the whole listing is linear in
 * the text; from the text's start each time it was quadratic: a 100,000-
 * block program took half a minute). */
struct srcpos { const char *p; unsigned line; };

static void source_line(FILE *f, const char *src, size_t n, unsigned line, struct srcpos *at)
{
  if (!src)
    return;
  if (!at->p || line < at->line)
    *at = (struct srcpos){src, 1};
  const char *p = at->p, *end = src + n;
  for (unsigned l = at->line; l < line && p < end; l++) {
    const char *q = memchr(p, '\n', (size_t)(end - p));
    if (!q)
      return;
    p = q + 1;
    *at = (struct srcpos){p, l + 1};
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
  int owner = -1;   /* the two-word instruction whose EXT word comes next */
  struct srcpos at = {NULL, 0};
  for (uint32_t pc = 0; pc < p->ncode; pc++) {
    while (b < p->nblocks && p->blocks[b].code == pc) {
      const struct prog_block *pb = &p->blocks[b];
      fprintf(f, "\n; ");
      if (pb->number)
        fprintf(f, "N%u", pb->number);
      else
        fprintf(f, "N-");
      fprintf(f, " line %u", pb->line);
      source_line(f, src, n, pb->line, &at);
      fputc('\n', f);
      b++;
    }
    uint32_t ins = p->code[pc];
    int op = (int)INS_OP(ins);
    if (op >= OP__COUNT) {
      fprintf(f, "%04u  ??? %08x\n", pc, ins);
      owner = -1;
      continue;
    }
    if (op == OP_EXT && owner >= 0) {
      fprintf(f, "%04u  %-8s", pc, vm_ops[op].name);
      operand_of(f, p, vm_ops[owner].ext, INS_A(ins));
      owner = -1;
    } else if (op == OP_EXT) {
      fprintf(f, "%04u  %-8s%u", pc, vm_ops[op].name, INS_A(ins));
    } else if (vm_ops[op].opd == OPD_NONE) {
      fprintf(f, "%04u  %s", pc, vm_ops[op].name);
    } else {
      fprintf(f, "%04u  %-8s", pc, vm_ops[op].name);
      operand(f, p, ins);
    }
    if (op != OP_EXT)
      owner = vm_op_len((unsigned)op) == 2 ? op : -1;
    fputc('\n', f);
  }
}

void vm_opcodes_md(FILE *f)
{
  fprintf(f, "# s42 bytecode\n\nGenerated from `vm/opcodes.h` (`make docs`); do not edit.\n\n"
             "Every instruction is one 32-bit word: the opcode in the low 8 bits, the operand A in the high 24.\n\n"
             "An instruction with an EXT operand is two words: an `EXT` word follows it, whose A is that operand "
             "and whose entry in the column map is the column of the instruction's last part (the store).\n\n"
             "A jump's or a call's operand (PC) is a block's index, not an instruction's address: control goes to "
             "that block's `BLOCK`, which the compiler and the verifier make the only place a jump lands; so a "
             "program's code is not bound by the 24-bit operand, only its blocks are (16,777,216).\n\n"
             "| opcode | operand | EXT operand | pops | pushes | meaning |\n|---|---|---|---|---|---|\n");
  for (int i = 0; i < OP__COUNT; i++)
    fprintf(f, "| `%s` | %s | %s | %d | %d | %s |\n", vm_ops[i].name, opd_names[vm_ops[i].opd],
            opd_names[vm_ops[i].ext], vm_ops[i].pop, vm_ops[i].push, vm_ops[i].doc);
}
