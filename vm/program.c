/* Growing arrays of a compiled program (vm/program.h). */
#include "program.h"
#include "opcodes.h"
#include <float.h>
#include <stdlib.h>
#include <string.h>

void prog_init(struct program *p)
{
  memset(p, 0, sizeof *p);
  p->saved_reg = -1;
  p->lim = (struct prog_limits){
    .depth = VM_DEPTH_MAX, .arrays = VM_ARRAYS_MAX, .cells = VM_CELLS_MAX,
    .param_lo = -DBL_MAX, .param_hi = DBL_MAX, .cell_lo = -DBL_MAX, .cell_hi = DBL_MAX,
    .angle = 1.0, .trig_max = DBL_MAX, .atan_max = DBL_MAX, .log_max = DBL_MAX,
  };
}

void prog_free(struct program *p)
{
  free(p->code);
  free(p->cols);
  free(p->colx);
  free(p->k);
  free(p->rules);
  free(p->blocks);
  if (p->ext_free)
    p->ext_free(p->ext);
  prog_init(p);
}

static int grow(void **ptr, size_t *cap, size_t need, size_t elem)
{
  if (need <= *cap)
    return 0;
  size_t n = *cap ? *cap * 2 : 64;
  while (n < need)
    n *= 2;
  void *q = realloc(*ptr, n * elem);
  if (!q)
    return -1;
  *ptr = q;
  *cap = n;
  return 0;
}

long prog_emit_grow(struct program *p, uint32_t ins, unsigned col)
{
  if (p->ncode >= PROG_MAX_CODE)
    return -1;
  size_t cap = p->capcode;
  if (grow((void **)&p->code, &p->capcode, p->ncode + 1, sizeof *p->code))
    return -1;
  if (p->capcode > PROG_MAX_CODE)
    p->capcode = PROG_MAX_CODE;   /* prog_emit's fast path stops there */
  if (cap != p->capcode) {
    uint8_t *c = realloc(p->cols, p->capcode * sizeof *c);
    if (!c)
      return -1;
    p->cols = c;
  }
  if (prog_col_set(p, p->ncode, col))
    return -1;
  p->code[p->ncode] = ins;
  return (long)p->ncode++;
}

/* The first entry of colx at or after pc. */
static size_t colx_at(const struct program *p, size_t pc)
{
  size_t lo = 0, hi = p->ncolx;
  if (hi && p->colx[hi - 1].pc < pc)
    return hi;   /* (the common case: a column added at the end) */
  while (lo < hi) {
    size_t mid = (lo + hi) / 2;
    if (p->colx[mid].pc < pc)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

unsigned prog_col_big(const struct program *p, size_t pc)
{
  size_t i = colx_at(p, pc);
  return i < p->ncolx && p->colx[i].pc == pc ? p->colx[i].col : 0;
}

int prog_col_set_big(struct program *p, size_t pc, unsigned col)
{
  if (col < PROG_COLBIG) {
    p->cols[pc] = (uint8_t)col;
    return 0;
  }
  size_t i = colx_at(p, pc);
  if (i == p->ncolx || p->colx[i].pc != pc) {
    if (grow((void **)&p->colx, &p->capcolx, p->ncolx + 1, sizeof *p->colx))
      return -1;
    memmove(&p->colx[i + 1], &p->colx[i], (p->ncolx - i) * sizeof *p->colx);
    p->ncolx++;
    p->colx[i].pc = (uint32_t)pc;
  }
  p->colx[i].col = (uint16_t)(col > 0xffff ? 0xffff : col);
  p->cols[pc] = PROG_COLBIG;
  return 0;
}

/* The kseen slot of a constant's bits. */
static inline unsigned kslot(double v)
{
  uint64_t b;
  memcpy(&b, &v, sizeof b);
  return (unsigned)((b * 0x9E3779B97F4A7C15ull) >> 58);
}

long prog_const(struct program *p, double v)
{
  /* Reuse the last few constants: programs repeat the same numbers.  The
   * latest constant of these bits is the one to reuse; kseen remembers it
   * (unless another of the same slot came since: then the search) */
  unsigned h = kslot(v);
  uint32_t s = p->kseen[h];
  if (s && s + 8 > p->nk && memcmp(&p->k[s - 1], &v, sizeof v) == 0)
    return (long)s - 1;
  for (size_t i = p->nk, n = 0; i-- > 0 && n < 8; n++)
    if (memcmp(&p->k[i], &v, sizeof v) == 0) {
      p->kseen[h] = (uint32_t)i + 1;
      return (long)i;
    }
  if (p->nk >= INS_AMAX || grow((void **)&p->k, &p->capk, p->nk + 1, sizeof *p->k))
    return -1;
  p->k[p->nk] = v;
  p->kseen[h] = (uint32_t)p->nk + 1;
  return (long)p->nk++;
}

long prog_consts(struct program *p, const double *v, size_t n)
{
  if (p->nk + n > INS_AMAX || grow((void **)&p->k, &p->capk, p->nk + n, sizeof *p->k))
    return -1;
  memcpy(p->k + p->nk, v, n * sizeof *v);
  for (size_t i = 0; i < n; i++)   /* the latest of their bits now */
    p->kseen[kslot(v[i])] = (uint32_t)(p->nk + i) + 1;
  p->nk += n;
  return (long)(p->nk - n);
}

long prog_rule(struct program *p, const struct prog_rule *r)
{
  for (size_t i = 0; i < p->nrules; i++)
    if (memcmp(&p->rules[i], r, sizeof *r) == 0)
      return (long)i;
  if (p->nrules >= 0x3fff || grow((void **)&p->rules, &p->caprules, p->nrules + 1, sizeof *p->rules))
    return -1;
  p->rules[p->nrules] = *r;
  return (long)p->nrules++;
}

long prog_block_add(struct program *p, const struct prog_block *b)
{
  if (p->nblocks > INS_AMAX || grow((void **)&p->blocks, &p->capblocks, p->nblocks + 1, sizeof *p->blocks))
    return -1;
  p->blocks[p->nblocks] = *b;
  return (long)p->nblocks++;
}

size_t prog_block_at(const struct program *p, uint32_t pc)
{
  size_t lo = 0, hi = p->nblocks;
  while (hi - lo > 1) {
    size_t mid = (lo + hi) / 2;
    if (p->blocks[mid].code <= pc)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}
