/* The neutral runner (src/core/mrun.h). */
#include "mrun.h"
#include "diag.h"
#include "errors.h"
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

int mrun_init(struct mrun *r, const struct program *p, const struct mrun_config *c)
{
  memset(r, 0, sizeof *r);
  r->p = p;
  r->rt = p->runtime;
  r->cfg = *c;
  r->go = 1;
  r->state = MR_ROW;
  int bad = vm_init(&r->vm, p);
  r->vm.max_blocks = c->max_blocks;
  r->vm.watch = c->watch;
  r->st = calloc(1, r->rt && r->rt->size ? r->rt->size : 1);
  if (!r->st) {
    vm_fail(&r->vm, S42_E_LIMIT, "out of memory");
    return -1;
  }
  if (r->rt && r->rt->reset)
    r->rt->reset(r);
  return bad ? -1 : 0;
}

void mrun_renew(struct mrun *r)
{
  vm_init(&r->vm, r->p);
  r->vm.max_blocks = r->cfg.max_blocks;
  r->vm.watch = r->cfg.watch;
  r->state = MR_ROW;
  r->wait = MRW_NONE;
  r->at_start = r->stop_after = 0;
  r->go = 1;
  if (r->rt->renew)
    r->rt->renew(r);
  else if (r->rt->reset) {
    memset(r->st, 0, r->rt->size ? r->rt->size : 1);
    r->rt->reset(r);
  }
}

void mrun_free(struct mrun *r)
{
  free(r->st);
  r->st = NULL;
  free(r->jn.call);
  free(r->jn.text);
  memset(&r->jn, 0, sizeof r->jn);
}

/* ---- the journal ---- */

static void jn_call(void *ctx, const struct canon_call *c)
{
  struct mrun_journal *j = &((struct mrun *)ctx)->jn;
  if (j->ncall == j->capcall) {
    size_t nc = j->capcall ? j->capcall * 2 : 32;
    struct canon_call *v = nc > j->capcall ? realloc(j->call, nc * sizeof *v) : NULL;
    if (!v) {
      j->oom = 1;
      return;
    }
    j->call = v;
    j->capcall = nc;
  }
  j->call[j->ncall++] = *c;
}

static void jn_warn(void *ctx, const char *msg)
{
  struct mrun_journal *j = &((struct mrun *)ctx)->jn;
  size_t len = strlen(msg) + 1;
  if (j->ntext + len > j->captext) {
    size_t nc = j->captext ? j->captext : 256;
    while (nc < j->ntext + len)
      nc *= 2;
    char *v = realloc(j->text, nc);
    if (!v) {
      j->oom = 1;
      return;
    }
    j->text = v;
    j->captext = nc;
  }
  memcpy(j->text + j->ntext, msg, len);
  j->ntext += len;
  j->nwarn++;
}

struct canon_sink mrun_sink(struct mrun *r)
{
  struct canon_sink s = {jn_call, jn_warn, r};
  return s;
}

static void jn_clear(struct mrun_journal *j)
{
  j->ncall = j->ntext = j->nwarn = 0;
  j->oom = 0;
}

/* The block committed: its warnings, then its records, to the host. */
static void jn_release(struct mrun *r)
{
  struct mrun_journal *j = &r->jn;
  for (size_t k = 0, off = 0; k < j->nwarn; k++) {
    const char *w = j->text + off;
    off += strlen(w) + 1;
    if (r->cfg.warn)
      r->cfg.warn(r->cfg.ctx, r, w);
  }
  if (r->cfg.canon)
    for (size_t k = 0; k < j->ncall; k++)
      r->cfg.canon(r->cfg.ctx, &j->call[k]);
  jn_clear(j);
}

void mrun_fail(struct mrun *r, int code, const char *fmt, ...)
{
  char msg[sizeof r->vm.err.msg];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  vm_fail(&r->vm, code, "%s", msg);
}

void mrun_warn(struct mrun *r, const char *fmt, ...)
{
  char msg[240];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  jn_warn(r, msg);
}

int mrun_block_number(const struct mrun *r)
{
  uint32_t n = r->p->blocks[r->vm.cur].number;
  return n ? (int)n : -1;
}

int mrun_pusk(struct mrun *r)
{
  if (r->state != MR_WAIT)
    return -1;
  if (r->wait == MRW_BLOCK)
    r->go = 1;             /* the block that waited starts now */
  r->wait = MRW_NONE;
  r->state = MR_ROW;
  return 0;
}

void mrun_stop(struct mrun *r)
{
  if (r->state != MR_END && r->state != MR_ERROR)
    r->state = MR_STOPPED;
}

enum mrun_ev mrun_run(struct mrun *r)
{
  if (r->state == MR_END || r->state == MR_ERROR || r->state == MR_STOPPED)
    return (enum mrun_ev)r->state;
  if (r->state == MR_WAIT && r->wait != MRW_NONE)
    return MR_WAIT;
  if (r->stop_after) {
    r->stop_after = 0;
    r->wait = MRW_STOP;
    return (enum mrun_ev)(r->state = MR_WAIT);
  }
  /* a watched start or a single block's wait that was answered: the block goes on */
  r->vm.start_all = r->single || r->skip;
  for (;;) {
    int was_start = r->at_start;
    r->at_start = 0;
    enum vm_event ev = was_start ? VM_EV_START : vm_run(&r->vm);
    if (ev == VM_EV_START) {
      uint32_t b = r->vm.cur;
      if (!was_start && r->cfg.watch && r->cfg.watch[b]) {
        r->at_start = 1;   /* the host acts at this block's start; the next call goes on from here */
        r->wait = MRW_NONE;
        return (enum mrun_ev)(r->state = MR_WAIT);
      }
      if (r->skip && r->rt->skippable && r->rt->skippable(r, b) && vm_skip(&r->vm) == 0)
        continue;
      if (r->single && !r->go) {
        r->at_start = 1;
        r->wait = MRW_BLOCK;
        return (enum mrun_ev)(r->state = MR_WAIT);
      }
      r->go = 0;
      continue;
    }
    if (ev == VM_EV_BLOCK) {
      r->go = 0;
      jn_clear(&r->jn);
      int st = r->rt->block ? r->rt->block(r) : 0;
      if (st >= 0 && r->jn.oom) {
        mrun_fail(r, S42_E_LIMIT, "out of memory for the block's %zu calls and %zu warnings", r->jn.ncall,
                  r->jn.nwarn);
        st = -1;
      }
      if (st < 0) {
        jn_clear(&r->jn);  /* a failed block leaves no trace, no call */
        continue;          /* mrun_fail ended the VM: the next vm_run says VM_EV_ERROR */
      }
      jn_release(r);
      r->seq++;
      r->stop_after = st > 0;   /* the row is out first; the next call waits */
      r->state = MR_ROW;
      return MR_ROW;
    }
    if (ev == VM_EV_END)
      return (enum mrun_ev)(r->state = MR_END);
    return (enum mrun_ev)(r->state = MR_ERROR);
  }
}

void mrun_row_json(const struct mrun *r, FILE *out)
{
  fprintf(out, "{\"seq\":%llu,\"n\":", (unsigned long long)r->seq);
  int n = mrun_block_number(r);
  if (n >= 0)
    fprintf(out, "%d", n);
  else
    fputs("null", out);
  fprintf(out, ",\"line\":%u,\"depth\":%d", r->p->blocks[r->vm.cur].line, r->vm.depth);
  if (r->rt->row_json)
    r->rt->row_json(r, out);
  fputc('}', out);
}

void mrun_row_text(const struct mrun *r, FILE *out)
{
  char nb[16];
  fprintf(out, "%6llu %-6s L%-4u", (unsigned long long)r->seq, diag_block(mrun_block_number(r), nb),
          r->p->blocks[r->vm.cur].line);
  if (r->rt->row_text)
    r->rt->row_text(r, out);
}
