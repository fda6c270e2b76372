/* A program whose dialect has no machine yet runs on the VM alone: its
 * registers, jumps and calls, no machine (contracts.md sec. 8's trace and
 * dump with an empty pos).  The runtime of every such program: each block
 * comes back to it, to be listed in the dump's "blocks". */
#include "mrun.h"
#include "diag.h"
#include "errors.h"
#include "report.h"
#include <stdlib.h>
#include <string.h>

struct vmo {
  int *run;              /* the block numbers run, in order (-1 none) */
  size_t n, cap;
  int oom;
};

static int block(struct mrun *r)
{
  struct vmo *s = r->st;
  if (s->n == s->cap) {
    size_t nc = s->cap ? s->cap * 2 : 256;
    int *v = realloc(s->run, nc * sizeof *v);
    if (!v) {
      mrun_fail(r, S42_E_LIMIT, "out of memory for the list of blocks run");
      return MRB_FAIL;
    }
    s->run = v;
    s->cap = nc;
  }
  s->run[s->n++] = mrun_block_number(r);
  return MRB_DONE;
}

static void release(struct mrun *r)
{
  struct vmo *s = r->st;
  if (s) {
    free(s->run);
    s->run = NULL;
    s->n = s->cap = 0;
  }
}

static void renew(struct mrun *r, const double *reg)
{
  (void)reg;
  release(r);
}

static void row_json(const struct mrun *r, FILE *out)
{
  (void)r;
  fputs(",\"motion\":\"none\",\"pos\":{},\"feed\":0,\"t\":0", out);
}

static void row_text(const struct mrun *r, FILE *out)
{
  char nb[16];
  fprintf(out, "%-5s L%-4u none  t 0.0000", diag_block(mrun_block_number(r), nb), r->p->blocks[r->vm.cur].line);
}

static void blocks_json(const struct mrun *r, FILE *out)
{
  const struct vmo *s = r->st;
  fputc('[', out);
  for (size_t i = 0; s && i < s->n; i++) {
    if (s->run[i] > 0)
      fprintf(out, "%s%d", i ? "," : "", s->run[i]);
    else
      fprintf(out, "%snull", i ? "," : "");
  }
  fputc(']', out);
}

static void dump_json(const struct mrun *r, FILE *out)
{
  fputs(",\"time\":0,\"pos\":{},\"r\":{", out);
  int first = 1;
  for (int k = 0; r->p && k < VM_NREG; k++)
    if (r->vm.reg[k] != 0) {
      fprintf(out, "%s\"%d\":", first ? "" : ",", k);
      json_num(out, r->vm.reg[k]);
      first = 0;
    }
  fputc('}', out);
}

const struct mrun_rt mrun_vm_only = {
  .size = sizeof(struct vmo),
  .every = 1,
  .block = block,
  .release = release,
  .renew = renew,
  .row_json = row_json,
  .row_text = row_text,
  .blocks_json = blocks_json,
  .dump_json = dump_json,
};
