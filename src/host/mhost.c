/* `s42 run` on the neutral runner (src/host/mhost.h). */
#include "mhost.h"
#include "atomic.h"
#include "canon.h"
#include "error.h"
#include "errors.h"
#include "mrun.h"
#include "operator.h"
#include "report.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { EXIT_END = 0, EXIT_PROGRAM = 1, EXIT_USAGE = 2, EXIT_STOPPED = 3, EXIT_IO = 4 };
#define MAX_SIDE_FILE ((size_t)1 << 20)

struct mhost {
  const struct mhost_opts *o;
  struct mrun r;
  struct opscript ops;
  size_t next;                 /* the next ordered action */
  uint8_t *watch;              /* blocks an `at` names */
  unsigned *runs;              /* per block index: how often it started (the `at` runs) */
  struct canon_trace canon;
  int stopped_by_script;
};

static void warn(void *ctx, const struct mrun *r, const char *msg)
{
  struct mhost *h = ctx;
  const struct prog_block *b = &r->p->blocks[r->vm.cur];
  int n = mrun_block_number(r);
  /* FILE:LINE:COL: warning: N<n>: MESSAGE, as contracts.md sec. 1 and the 2С42's */
  fprintf(stderr, "%s:%u:%u: warning: N", h->o->program, b->line, b->col);
  if (n >= 0)
    fprintf(stderr, "%d", n);
  else
    fputc('-', stderr);
  fprintf(stderr, ": %s\n", msg);
}

static void canon_line(void *ctx, const char *text)
{
  (void)ctx;
  puts(text);
}

static void canon_call(void *ctx, const struct canon_call *c)
{
  struct mhost *h = ctx;
  if (h->o->canon)
    canon_trace_call(&h->canon, c);
  if (h->o->watch.call)
    h->o->watch.call(h->o->watch.ctx, c);
}

/* The actions that do not fit this machine: refused before the run. */
static int check_script(const struct mhost *h)
{
  int bad = 0;
  for (int pass = 0; pass < 2; pass++) {
    const struct op_action *v = pass ? h->ops.at : h->ops.v;
    size_t n = pass ? h->ops.nat : h->ops.n;
    for (size_t i = 0; i < n; i++) {
      const struct op_action *a = &v[i];
      const char *why = NULL;
      switch (a->kind) {
      case OA_KEY:
        if (a->key != OPKEY_PUSK && a->key != OPKEY_STOP)
          why = "this machine's panel has Пуск and Стоп (key PUSK, key STOP)";
        break;
      case OA_MODE: case OA_ZERO:
        break;
      default:
        why = "not an action of this machine (key PUSK, key STOP, mode single|skip|optstop on|off, zero X Z, at)";
        break;
      }
      char what[96];
      if (why) {
        fprintf(stderr, "%s:%u:%u: error: %s: %s\n", h->o->operator_file, a->line, a->col,
                ops_describe(a, what, sizeof what), why);
        bad = 1;
      }
      if (pass) {
        int found = 0;
        for (size_t b = 0; b < h->r.p->nblocks && !found; b++)
          found = (int)h->r.p->blocks[b].number == a->at_number;
        if (!found) {
          fprintf(stderr, "%s:%u:%u: error: at N%d: the program has no block N%d, so this never fires\n",
                  h->o->operator_file, a->line, a->col, a->at_number, a->at_number);
          bad = 1;
        }
      }
    }
  }
  return bad;
}

static void apply(struct mhost *h, const struct op_action *a)
{
  struct mrun *r = &h->r;
  char why[160];
  switch (a->kind) {
  case OA_KEY:
    if (a->key == OPKEY_STOP) {
      mrun_stop(r);
      h->stopped_by_script = 1;
    }
    break;
  case OA_MODE:
    if (a->n2 == OPMODE_SINGLE)
      r->single = (int)a->n;
    else if (a->n2 == OPMODE_SKIP)
      r->skip = (int)a->n;
    else
      r->optstop = (int)a->n;
    break;
  case OA_ZERO: {
    double v[2] = {a->axis & 1 ? (double)a->n / 1000.0 : NAN, a->axis & 2 ? (double)a->n2 / 1000.0 : NAN};
    if (!r->rt->zero || r->rt->zero(r, v, 2, why, sizeof why))
      fprintf(stderr, "%s:%u:%u: warning: zero refused: %s\n", h->o->operator_file, a->line, a->col,
              r->rt->zero ? why : "this machine has no part zero");
    break;
  }
  default:
    break;
  }
}

/* A block boundary: the immediate actions at the head of the script. */
static void boundary(struct mhost *h)
{
  while (h->next < h->ops.n && !ops_is_waiting(&h->ops.v[h->next]) && h->r.state != MR_STOPPED)
    apply(h, &h->ops.v[h->next++]);
}

static void error_json(const struct mrun *r)
{
  const struct vm_error *e = &r->vm.err;
  const struct prog_block *b = e->block < r->p->nblocks ? &r->p->blocks[e->block] : NULL;
  printf("{\"code\":\"%s\",\"n\":", err_code(e->code));
  if (b && b->number)
    printf("%u", (unsigned)b->number);
  else
    fputs("null", stdout);
  printf(",\"line\":%u,\"col\":%u,\"message\":", b ? b->line : 1, e->col ? e->col : b ? b->col : 1);
  json_string(stdout, e->msg);
  putchar('}');
}

void mhost_dump_refused(const struct mrun_rt *rt, const struct s42_error *e)
{
  printf("{\"status\":\"error\",\"error\":{\"code\":\"%s\",\"n\":", err_code(e->code));
  if (e->number >= 0)
    printf("%d", e->number);
  else
    fputs("null", stdout);
  printf(",\"line\":%u,\"col\":%u,\"message\":", e->line, e->col);
  json_string(stdout, e->msg);
  fputs("},\"blocks\":0", stdout);
  /* the machine at power-on: a runner with no program, its state reset */
  struct mrun r;
  memset(&r, 0, sizeof r);
  r.rt = rt;
  r.st = rt ? calloc(1, rt->size ? rt->size : 1) : NULL;
  if (r.st && rt->reset && rt->dump_json) {
    rt->reset(&r);
    rt->dump_json(&r, stdout);
  } else {
    fputs(",\"time\":0,\"pos\":{}", stdout);
  }
  free(r.st);
  puts("}");
}

static void print_error(const struct mhost *h, const struct diag_list *d)
{
  const struct vm_error *e = &h->r.vm.err;
  const struct prog_block *b = e->block < h->r.p->nblocks ? &h->r.p->blocks[e->block] : NULL;
  struct diag g;
  memset(&g, 0, sizeof g);
  g.sev = DIAG_ERROR;
  g.code = e->code;
  g.line = b ? b->line : 1;
  g.col = e->col ? e->col : b ? b->col : 1;
  g.number = b && b->number ? (int)b->number : -1;
  snprintf(g.msg, sizeof g.msg, "%s", e->msg);
  diag_print_in(stderr, d, &g);
  /* the machine's words for it, in its language (--lang; the dialect's table) */
  char m[200];
  report_machine_msg(m, sizeof m, h->r.p, e->code, g.number, e->aux, h->o->en);
  fprintf(stderr, "%s:%u:%u: note: %s\n", h->o->program, g.line, g.col, m);
}

static int run(struct mhost *h, const struct diag_list *d)
{
  struct mrun *r = &h->r;
  const struct mhost_opts *o = h->o;
  boundary(h);
  if (o->watch.start && r->rt->position) {   /* where the tool starts (after a `zero` at the head of the script) */
    double pos[4];
    r->rt->position(r, pos);
    o->watch.start(o->watch.ctx, pos);
  }
  for (;;) {
    enum mrun_ev ev = mrun_run(r);
    if (ev == MR_ROW) {
      if (o->trace) {
        if (o->json)
          mrun_row_json(r, stdout);
        else
          mrun_row_text(r, stdout);
        putchar('\n');
      }
      boundary(h);
      continue;
    }
    if (ev == MR_WAIT) {
      char nb[16];
      if (r->wait == MRW_NONE) {     /* a watched block starts: its `at` actions */
        unsigned run_no = ++h->runs[r->vm.cur];
        for (size_t i = 0; i < h->ops.nat; i++) {
          struct op_action *a = &h->ops.at[i];
          if (!a->fired && a->at_number == mrun_block_number(r) && a->at_run == run_no) {
            a->fired = 1;
            apply(h, a);
          }
        }
        continue;
      }
      const struct op_action *a = h->next < h->ops.n ? &h->ops.v[h->next] : NULL;
      if (a && a->kind == OA_KEY && a->key == OPKEY_PUSK) {
        h->next++;
        mrun_pusk(r);
        boundary(h);
        continue;
      }
      const char *why = r->wait == MRW_BLOCK ? "single block: it waits for Пуск before it starts"
                        : "a programmed stop: it waits for Пуск";
      char what[96];
      fprintf(stderr, "%s: %s: %s; the operator script has %s\n", o->program,
              diag_block(mrun_block_number(r), nb), why,
              a ? ops_describe(a, what, sizeof what) : "no action left (key PUSK)");
      mrun_stop(r);
      return EXIT_STOPPED;
    }
    if (ev == MR_STOPPED) {
      char nb[16];
      fprintf(stderr, "%s: stopped (key STOP) after %s\n", o->program, diag_block(mrun_block_number(r), nb));
      return EXIT_STOPPED;
    }
    if (ev == MR_END)
      return EXIT_END;
    print_error(h, d);
    return EXIT_PROGRAM;
  }
}

int mhost_run(const struct mhost_opts *o, const struct program *p, const struct diag_list *d)
{
  struct mhost h;
  memset(&h, 0, sizeof h);
  h.o = o;
  canon_trace_init(&h.canon, canon_line, NULL);
  if (o->operator_file) {
    char *text, err[600];
    size_t n;
    int rr = file_read_all(o->operator_file, FILE_OR_STDIN, MAX_SIDE_FILE, &text, &n, err, sizeof err);
    if (rr) {
      fprintf(stderr, "s42: %s\n", err);
      return EXIT_IO;
    }
    int bad = ops_parse(text, n, o->operator_file, &h.ops, stderr);
    free(text);
    if (bad)
      return EXIT_USAGE;
  }
  h.watch = calloc(p->nblocks ? p->nblocks : 1, 1);
  h.runs = calloc(p->nblocks ? p->nblocks : 1, sizeof *h.runs);
  if (!h.watch || !h.runs) {
    fprintf(stderr, "s42: out of memory\n");
    free(h.watch);
    free(h.runs);
    ops_free(&h.ops);
    return EXIT_IO;
  }
  for (size_t i = 0; i < h.ops.nat; i++)
    for (size_t b = 0; b < p->nblocks; b++)
      if ((int)p->blocks[b].number == h.ops.at[i].at_number)
        h.watch[b] = 1;
  struct mrun_config c;
  memset(&c, 0, sizeof c);
  c.en = o->en;
  c.max_blocks = o->max_blocks;
  c.ctx = &h;
  c.warn = warn;
  c.canon = canon_call;
  c.watch = h.ops.nat ? h.watch : NULL;
  int rc = EXIT_END;
  if (mrun_init(&h.r, p, &c)) {
    fprintf(stderr, "s42: %s: %s\n", o->program, h.r.vm.err.msg);
    rc = EXIT_PROGRAM;
  } else if (o->operator_file && check_script(&h)) {
    fprintf(stderr, "%s: note: the operator script %s is refused: the run does not start\n", o->program,
            o->operator_file);
    rc = EXIT_USAGE;
  } else if (o->tools) {
    char *text, err[600];
    size_t n;
    if (file_read_all(o->tools, 0, MAX_SIDE_FILE, &text, &n, err, sizeof err)) {
      fprintf(stderr, "s42: %s\n", err);
      rc = EXIT_IO;
    } else {
      if (!h.r.rt->load || h.r.rt->load(&h.r, "tools", text, n, o->tools, err, sizeof err)) {
        fprintf(stderr, "%s\n", h.r.rt->load ? err : "s42: --tools: this machine has no tool table");
        rc = EXIT_USAGE;
      }
      free(text);
    }
  }
  if (rc == EXIT_END) {
    rc = run(&h, d);
    if (o->watch.result) {
      int n = -1;
      if (rc == EXIT_PROGRAM) {
        uint32_t b = h.r.vm.err.block;
        n = b < p->nblocks && p->blocks[b].number ? (int)p->blocks[b].number : -1;
      }
      o->watch.result(o->watch.ctx, rc == EXIT_END ? "end" : rc == EXIT_PROGRAM ? "error" : "stopped",
                      rc == EXIT_PROGRAM ? err_code(h.r.vm.err.code) : NULL, n);
    }
    if (o->dump) {
      const char *status = rc == EXIT_END ? "end" : rc == EXIT_PROGRAM ? "error" : "stopped";
      printf("{\"status\":\"%s\",\"error\":", status);
      if (rc == EXIT_PROGRAM)
        error_json(&h.r);
      else
        fputs("null", stdout);
      printf(",\"blocks\":%llu", (unsigned long long)h.r.vm.blocks);
      if (h.r.rt->dump_json)
        h.r.rt->dump_json(&h.r, stdout);
      puts("}");
    }
    if (o->operator_file)
      ops_warn_unused(&h.ops, h.next, 0, NULL, o->operator_file, stderr);
  }
  if (fflush(stdout) || ferror(stdout)) {
    fprintf(stderr, "s42: cannot write the output\n");
    rc = EXIT_IO;
  }
  mrun_free(&h.r);
  free(h.watch);
  free(h.runs);
  ops_free(&h.ops);
  return rc;
}
