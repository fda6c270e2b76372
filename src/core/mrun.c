/* The runner (src/core/mrun.h). */
#include "mrun.h"
#include "diag.h"
#include "error.h"
#include "errors.h"
#include "report.h"
#include "utf8.h"
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* A program without a runtime runs on the VM alone (src/core/vmonly.c). */
extern const struct mrun_rt mrun_vm_only;

/* The blocks whose start comes back: the host's and the restart points.
 * 0, or -1 out of memory. */
static int build_watch(struct mrun *r)
{
  free(r->watch);
  r->watch = NULL;
  const struct program *p = r->p;
  int points = r->cfg.state_path && r->rt->restart_point;
  if (!r->cfg.watch && !points)
    return 0;
  r->watch = calloc(p->nblocks ? p->nblocks : 1, 1);
  if (!r->watch)
    return -1;
  for (size_t b = 0; b < p->nblocks; b++)
    r->watch[b] = (r->cfg.watch && r->cfg.watch[b]) || (points && r->rt->restart_point(r, (uint32_t)b));
  return 0;
}

static void vm_setup(struct mrun *r)
{
  r->vm.max_blocks = r->cfg.max_blocks;
  r->vm.watch = r->watch;
  r->vm.yield_all = r->cfg.every || r->rt->every;
}

int mrun_init(struct mrun *r, const struct program *p, const struct mrun_config *c)
{
  memset(r, 0, sizeof *r);
  r->p = p;
  r->rt = p->runtime ? p->runtime : &mrun_vm_only;
  r->cfg = *c;
  r->go = 1;
  r->override = 100;
  r->state = MR_ROW;
  int bad = vm_init(&r->vm, p);
  r->st = calloc(1, r->rt->size ? r->rt->size : 1);
  if (!r->st || build_watch(r)) {
    vm_fail(&r->vm, S42_E_LIMIT, "out of memory");
    r->state = MR_ERROR;
    if (r->st && r->rt->reset)
      r->rt->reset(r);
    return -1;
  }
  vm_setup(r);
  if (r->rt->reset)
    r->rt->reset(r);
  if (bad)
    r->state = MR_ERROR;
  return bad ? -1 : 0;
}

void mrun_renew(struct mrun *r)
{
  double reg[VM_NREG];
  memcpy(reg, r->vm.reg, sizeof reg);
  vm_init(&r->vm, r->p);
  vm_setup(r);
  r->state = MR_ROW;
  r->wait = MRW_NONE;
  r->at_start = r->stop_after = r->resume = r->in_block = 0;
  r->go = 1;
  r->saves = 0;
  r->jn.ncall = r->jn.ntext = r->jn.nwarn = 0;
  r->jn.oom = 0;
  if (r->rt->renew)
    r->rt->renew(r, reg);
  else if (r->rt->reset) {
    memset(r->st, 0, r->rt->size ? r->rt->size : 1);
    r->rt->reset(r);
  }
}

void mrun_free(struct mrun *r)
{
  if (r->rt && r->rt->release)
    r->rt->release(r);
  free(r->st);
  r->st = NULL;
  free(r->watch);
  r->watch = NULL;
  free(r->jn.call);
  free(r->jn.text);
  memset(&r->jn, 0, sizeof r->jn);
}

/* ---- the journal ---- */

static void jn_call(void *ctx, const struct canon_call *c)
{
  struct mrun *r = ctx;
  struct mrun_journal *j = &r->jn;
  if (!r->in_block) {   /* a call outside a block's work (the end): out at once */
    if (r->cfg.canon)
      r->cfg.canon(r->cfg.ctx, c);
    return;
  }
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
  struct mrun *r = ctx;
  struct mrun_journal *j = &r->jn;
  if (!r->in_block) {   /* between blocks (a jog at its limit): at once */
    if (r->cfg.warn)
      r->cfg.warn(r->cfg.ctx, r, msg);
    return;
  }
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

/* The block committed (or reached a wait): its warnings, then its
 * records, to the host. */
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

/* ---- the runtime's services ---- */

void mrun_fail(struct mrun *r, int code, const char *fmt, ...)
{
  char msg[sizeof r->vm.err.msg];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  vm_fail(&r->vm, code, "%s", msg);
}

void mrun_refuse(struct mrun *r, int code, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(r->vm.err.msg, sizeof r->vm.err.msg, fmt, ap);
  va_end(ap);
  r->vm.err.code = code;
  r->vm.err.block = 0;
  r->vm.err.col = 1;
  r->vm.done = 1;
  r->state = MR_ERROR;
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

void mrun_log(struct mrun *r, const char *msg)
{
  if (r->cfg.log)
    r->cfg.log(r->cfg.ctx, r, msg);
}

void mrun_moved(struct mrun *r, int kind, int axis, int64_t d, const int64_t pos[CANON_AXES], double t)
{
  if (!r->cfg.moved)
    return;
  struct mrun_move m;
  m.kind = kind;
  m.axis = axis;
  m.d = d;
  memcpy(m.pos, pos, sizeof m.pos);
  m.t = t;
  r->cfg.moved(r->cfg.ctx, r, &m);
}

int mrun_block_number(const struct mrun *r)
{
  if (!r->p || r->vm.cur >= r->p->nblocks)
    return -1;
  uint32_t n = r->p->blocks[r->vm.cur].number;
  return n ? (int)n : -1;
}

double mrun_time(const struct mrun *r)
{
  return r->rt && r->rt->time ? r->rt->time(r) : 0;
}

/* ---- the loop ---- */

/* What the runtime's block() or resume() returned: the event for the
 * host, or -1 to run on. */
static int after_block(struct mrun *r, int st)
{
  r->in_block = 0;
  if (st != MRB_FAIL && r->jn.oom) {
    mrun_fail(r, S42_E_LIMIT, "out of memory for the block's %zu calls and %zu warnings", r->jn.ncall,
              r->jn.nwarn);
    st = MRB_FAIL;
  }
  if (st == MRB_FAIL) {
    jn_clear(&r->jn);   /* a failed block leaves no trace, no call */
    return -1;          /* mrun_fail ended the VM: the next vm_run says VM_EV_ERROR */
  }
  jn_release(r);
  if (st == MRB_WAIT) {
    if (r->wait == MRW_NONE)
      r->wait = MRW_PUSK;
    return r->state = MR_WAIT;
  }
  r->seq++;
  r->stop_after = st == MRB_STOP;
  if (r->cfg.rows)
    return r->state = MR_ROW;   /* the row is out first; the next call waits */
  if (r->stop_after) {
    r->stop_after = 0;
    r->wait = MRW_STOP;
    return r->state = MR_WAIT;
  }
  return -1;
}

/* A restart point starts: save the snapshot there. */
static int save_point(struct mrun *r)
{
  char err[512];
  if (mrun_save(r, r->cfg.state_path, err, sizeof err)) {
    mrun_fail(r, S42_E_STATE, "cannot save the %s restart state: %s", r->rt->restart_word ? r->rt->restart_word : "",
              err);
    return -1;
  }
  r->saves++;
  return 0;
}

enum mrun_ev mrun_run(struct mrun *r)
{
  if (r->state == MR_END || r->state == MR_ERROR || r->state == MR_STOPPED)
    return (enum mrun_ev)r->state;
  if (r->state == MR_WAIT) {
    if (!r->resume)
      return MR_WAIT;
    r->resume = 0;
    r->wait = MRW_NONE;
    r->state = MR_ROW;
    r->in_block = 1;
    int ev = after_block(r, r->rt->resume ? r->rt->resume(r) : MRB_DONE);
    if (ev >= 0)
      return (enum mrun_ev)ev;
  } else if (r->stop_after) {
    r->stop_after = 0;
    r->wait = MRW_STOP;
    return (enum mrun_ev)(r->state = MR_WAIT);
  }
  r->state = MR_ROW;
  r->vm.start_all = r->single || r->skip || r->brk || r->cfg.starts;
  for (;;) {
    int was_start = r->at_start;
    r->at_start = 0;
    enum vm_event ev;
    if (was_start) {
      ev = VM_EV_START;
    } else {
      r->vm.sw = r->rt->switches && !r->cfg.rows && !r->cfg.every ? r->rt->switches(r) : 0;
      ev = vm_run(&r->vm);
    }
    if (ev == VM_EV_START) {
      uint32_t b = r->vm.cur;
      if (!was_start) {
        if (r->rt->start)
          r->rt->start(r);
        int point = r->cfg.state_path && r->rt->restart_point && r->rt->restart_point(r, b);
        r->at_start = 1;   /* the VM stands at this block's start (a snapshot is taken here) */
        if (point && save_point(r)) {
          r->at_start = 0;
          continue;   /* the VM ended with E-STATE */
        }
        if (r->cfg.starts || (r->cfg.watch && r->cfg.watch[b]) || point)
          return (enum mrun_ev)(r->state = MR_START);   /* the host acts here; the next call goes on */
        r->at_start = 0;
      }
      if (r->skip && r->rt->skippable && r->rt->skippable(r, b) && vm_skip(&r->vm) == 0)
        continue;
      int n = mrun_block_number(r);
      if (!r->go && (r->single || (r->brk && n == r->brk))) {
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
      r->in_block = 1;
      int e = after_block(r, r->rt->block ? r->rt->block(r) : MRB_DONE);
      if (e >= 0)
        return (enum mrun_ev)e;
      continue;
    }
    if (ev == VM_EV_END) {
      if (r->rt->end)
        r->rt->end(r);
      return (enum mrun_ev)(r->state = MR_END);
    }
    if (r->rt->failed)
      r->rt->failed(r);
    return (enum mrun_ev)(r->state = MR_ERROR);
  }
}

/* ---- the operator ---- */

static int refuse(char *why, size_t n, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int refuse(char *why, size_t n, const char *fmt, ...)
{
  if (why && n) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, n, fmt, ap);
    va_end(ap);
  }
  return -1;
}

int mrun_pusk(struct mrun *r)
{
  struct mrun_input in = {.kind = MRI_PUSK};
  return mrun_input(r, &in, NULL, 0);
}

void mrun_stop(struct mrun *r)
{
  if (r->state != MR_END && r->state != MR_ERROR)
    r->state = MR_STOPPED;
}

int mrun_resume(struct mrun *r)
{
  if (r->state != MR_STOPPED)
    return -1;
  r->state = r->wait != MRW_NONE ? MR_WAIT : MR_ROW;
  return 0;
}

int mrun_override(struct mrun *r, int pct, double now, double *shift)
{
  double d = 0;
  if (shift)
    *shift = 0;
  if (!r->rt->override)
    return -1;
  int e = r->rt->override(r, pct, now, &d);
  if (e < 0)
    return -1;
  r->override = pct;
  if (shift)
    *shift = d;
  if (e == 1 && r->state == MR_WAIT && r->wait == MRW_FEED)
    r->resume = 1;
  return e;
}

int mrun_input(struct mrun *r, const struct mrun_input *in, char *why, size_t n)
{
  const char *no = r->rt->refuses ? r->rt->refuses(r, in) : NULL;
  if (no)
    return refuse(why, n, "%s", no);
  switch (in->kind) {
  case MRI_STOP:
    mrun_stop(r);
    return 0;
  case MRI_EXIT:
    r->vm.exit_latch = 1;
    return 0;
  case MRI_MODE:
    if (in->axis == MRM_SINGLE)
      r->single = in->n != 0;
    else if (in->axis == MRM_SKIP)
      r->skip = in->n != 0;
    else if (in->axis == MRM_OPTSTOP)
      r->optstop = in->n != 0;
    else
      return refuse(why, n, "no such switch");
    return 0;
  case MRI_BREAK:
    r->brk = in->n > 0 ? (int)in->n : 0;
    return 0;
  case MRI_OVERRIDE:
    if (in->n < 0 || in->n > 150)
      return refuse(why, n, "the feed override is 0..150 %%, not %lld", (long long)in->n);
    if (mrun_override(r, (int)in->n, mrun_time(r), NULL) < 0)
      return refuse(why, n, "the feed override was refused");
    return 0;
  case MRI_PUSK:
    if (r->state == MR_WAIT && (r->wait == MRW_BLOCK || r->wait == MRW_STOP)) {
      if (r->wait == MRW_BLOCK)
        r->go = 1;   /* the block that waited starts now */
      r->wait = MRW_NONE;
      r->state = MR_ROW;
      return 0;
    }
    break;
  default:
    break;
  }
  if (!r->rt->input)
    return refuse(why, n, "the machine does not wait for it");
  int e = r->rt->input(r, in, why, n);
  if (e > 0 && r->state == MR_WAIT)
    r->resume = 1;
  return e < 0 ? -1 : 0;
}

int mrun_set_param(struct mrun *r, int k, double v, char *why, size_t n)
{
  if (r->state != MR_WAIT && r->state != MR_START && !(r->state == MR_ROW && !r->in_block))
    return refuse(why, n, "the cycle is over");
  if (!r->rt->set_param)
    return refuse(why, n, "the %s has no parameters the panel sets", r->rt->machine ? r->rt->machine : "machine");
  return r->rt->set_param(r, k, v, why, n);
}

void mrun_load_params(struct mrun *r, unsigned r0, unsigned n, const double *v)
{
  if (r0 < VM_NREG && n <= VM_NREG - r0)
    memcpy(&r->vm.reg[r0], v, n * sizeof *v);
}

const char *mrun_wait_text(const struct mrun *r, char *buf, size_t n)
{
  if (r->rt->wait_text) {
    const char *w = r->rt->wait_text(r, buf, n);
    if (w)
      return w;
  }
  switch (r->wait) {
  case MRW_BLOCK:
    return r->single ? "Пуск to start the block (single block; key PUSK)"
                     : "Пуск to start the block (breakpoint; key PUSK)";
  case MRW_STOP:
    return "Пуск after a programmed stop (key PUSK)";
  case MRW_PUSK: return "Пуск (key PUSK)";
  case MRW_PS: return "ПС, then Пуск (key PS, key PUSK)";
  case MRW_ANSWER: return "a number in the input field (answer N)";
  case MRW_TEACH: return "teach-in jogs ended by ПС (jog, key PS)";
  case MRW_SECTION: return "Пуск in the next section (section moves, then key PUSK)";
  case MRW_FEED: return "a feed override above 0 % (override N)";
  default: return "nothing";
  }
}

/* ---- what the hosts read ---- */

void mrun_error(const struct mrun *r, struct s42_error *e)
{
  const struct vm_error *v = &r->vm.err;
  const struct prog_block *b = r->p && v->block < r->p->nblocks ? &r->p->blocks[v->block] : NULL;
  memset(e, 0, sizeof *e);
  e->code = v->code;
  e->number = b && b->number ? (int)b->number : -1;
  e->line = b ? b->line : 1;
  e->col = v->col ? v->col : b ? b->col : 1;
  e->aux = v->aux;
  snprintf(e->msg, sizeof e->msg, "%s", v->msg);
}

void mrun_info(const struct mrun *r, struct canon_info *in)
{
  memset(in, 0, sizeof *in);
  if (r->rt->info)
    r->rt->info(r, in);
  if (!in->kind)
    in->kind = "none";
  if (!in->name)
    in->name = "VM";
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
  fprintf(out, "%6llu ", (unsigned long long)r->seq);
  if (r->rt->row_text)
    r->rt->row_text(r, out);
}

static void error_json(const struct mrun_rt *rt, const struct program *p, FILE *out, const struct s42_error *e,
                       int en)
{
  fprintf(out, "{\"code\":\"%s\",\"n\":", err_code(e->code));
  if (e->number >= 0)
    fprintf(out, "%d", e->number);
  else
    fputs("null", out);
  fprintf(out, ",\"line\":%u,\"col\":%u,\"message\":", e->line, e->col);
  json_string(out, e->msg);
  if (rt->error_machine) {
    char machine[200];
    s42_error_machine(e, p, en, machine, sizeof machine);
    fputs(",\"machine\":", out);
    json_string(out, machine);
  }
  fputc('}', out);
}

void mrun_dump(const struct mrun *r, FILE *out, const char *status, const struct s42_error *e)
{
  fprintf(out, "{\"status\":\"%s\",\"error\":", status);
  if (e)
    error_json(r->rt, r->p, out, e, r->cfg.en);
  else
    fputs("null", out);
  fputs(",\"blocks\":", out);
  if (r->rt->blocks_json)
    r->rt->blocks_json(r, out);
  else
    fprintf(out, "%llu", (unsigned long long)r->vm.blocks);
  if (r->rt->dump_json)
    r->rt->dump_json(r, out);
  fputs("}\n", out);
}

void mrun_dump_refused(const struct mrun_rt *rt, FILE *out, const struct s42_error *e, int en,
                       const struct program *p)
{
  if (!rt)
    rt = &mrun_vm_only;
  fputs("{\"status\":\"error\",\"error\":", out);
  error_json(rt, p, out, e, en);
  fputs(",\"blocks\":0", out);
  /* the machine at power-on: a runner with no program, its state reset */
  struct mrun r;
  memset(&r, 0, sizeof r);
  r.rt = rt;
  r.cfg.en = en;
  r.st = calloc(1, rt->size ? rt->size : 1);
  if (r.st && rt->reset && rt->dump_json) {
    rt->reset(&r);
    rt->dump_json(&r, out);
  } else if (rt->dump_json) {
    rt->dump_json(&r, out);
  } else {
    fputs(",\"time\":0,\"pos\":{}", out);
  }
  if (rt->release)
    rt->release(&r);
  free(r.st);
  fputs("}\n", out);
}

void mrun_page_text(struct mrun_page *pg, const char *text, size_t len)
{
  memset(pg, 0, sizeof *pg);
  int row = 0, col = 0;
  const unsigned char *u = (const unsigned char *)text;
  for (size_t i = 0; i < len;) {
    if (u[i] == '\n') {
      if (col > pg->cols)
        pg->cols = col;
      row++;
      col = 0;
      i++;
      continue;
    }
    size_t l;
    int32_t c = utf8_decode(u + i, len - i, &l);
    i += l;
    if (row < MRUN_PAGE_ROWS && col < MRUN_PAGE_COLS)
      pg->cell[row][col] = (uint32_t)c;
    col++;
  }
  if (col > 0) {
    if (col > pg->cols)
      pg->cols = col;
    row++;
  }
  pg->rows = row < MRUN_PAGE_ROWS ? row : MRUN_PAGE_ROWS;
  if (pg->cols > MRUN_PAGE_COLS)
    pg->cols = MRUN_PAGE_COLS;
}
