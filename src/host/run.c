/* The one headless host (src/host/run.h). */
#include "run.h"
#include "atomic.h"
#include "canon.h"
#include "error.h"
#include "errors.h"
#include "modbus.h"
#include "mrun.h"
#include "operator.h"
#include "pace.h"
#include "report.h"
#include "utf8.h"
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { EXIT_END = 0, EXIT_PROGRAM = 1, EXIT_USAGE = 2, EXIT_STOPPED = 3, EXIT_IO = 4 };
#define MAX_SIDE_FILE ((size_t)1 << 20)

struct host {
  const struct run_opts *o;
  const struct program *p;
  struct mrun r;
  struct opscript ops;
  size_t next;                 /* the next ordered action */
  size_t unfit;                /* 1 + the action reported as not fitting a wait, 0 none */
  uint8_t *watch;              /* blocks an `at` names */
  unsigned *runs;              /* per block index: how often it started (the `at` runs) */
  unsigned *runs_n;            /* per block number (1..nnum-1): the same, for the warnings */
  size_t nnum;
  struct canon_trace canon;
  struct pace pace;
  int interruptible;           /* --realtime: SIGINT and SIGTERM stop at a block boundary */
  /* --modbus: the server, what it publishes, and where the machine was at
   * the last row or wait (a row's motion goes from there, on the wall clock) */
  struct mb_server *mb;
  struct mb_machine mm;
  double last_t;
  int64_t last_pos[4];
  /* the wait the script's next action did not fit, left to a client: not
   * tried again until the machine waits for something else */
  struct { size_t next; uint64_t seq; uint32_t cur; int wait; } unfit_wait;
  int stop;                    /* how it stopped: enum run_stop */
};

static volatile sig_atomic_t quit_signal;

static void on_quit(int sig)
{
  quit_signal = sig;
}

/* ---- sinks ---- */

static void warn(void *ctx, const struct mrun *r, const char *msg)
{
  struct host *h = ctx;
  const struct prog_block *b = &r->p->blocks[r->vm.cur];
  int n = mrun_block_number(r);
  /* FILE:LINE:COL: warning: N<n>: MESSAGE, as contracts.md sec. 1 */
  fprintf(stderr, "%s:%u:%u: warning: N", h->o->program, b->line, b->col);
  if (n >= 0)
    fprintf(stderr, "%d", n);
  else
    fputc('-', stderr);
  fprintf(stderr, ": %s\n", msg);
}

static void note(void *ctx, const struct mrun *r, const char *msg)
{
  (void)ctx;
  (void)r;
  fprintf(stderr, "s42: note: %s\n", msg);
}

static void canon_line(void *ctx, const char *text)
{
  (void)ctx;
  puts(text);
}

static void on_call(void *ctx, const struct canon_call *c)
{
  struct host *h = ctx;
  if (h->o->canon)
    canon_trace_call(&h->canon, c);
  if (h->o->watch && h->o->watch->call)
    h->o->watch->call(h->o->watch->ctx, c);
}

static void mark_position(struct host *h);

static void on_moved(void *ctx, const struct mrun *r, const struct mrun_move *m)
{
  struct host *h = ctx;
  if (h->mb)
    mark_position(h);          /* a hand move shows at once, not in the block's motion */
  if (h->o->watch && h->o->watch->moved)
    h->o->watch->moved(h->o->watch->ctx, r, m);
}

/* ---- the operator script as the runner's input ---- */

/* The input record of a script action. */
static void input_of(const struct op_action *a, struct mrun_input *in)
{
  memset(in, 0, sizeof *in);
  in->axis2 = -1;
  switch (a->kind) {
  case OA_KEY:
    in->kind = a->key == OPKEY_PUSK ? MRI_PUSK : a->key == OPKEY_PS ? MRI_PS : a->key == OPKEY_EXIT ? MRI_EXIT
                                                                                                   : MRI_STOP;
    break;
  case OA_ANSWER:
    in->kind = MRI_ANSWER;
    in->n = a->n;
    break;
  case OA_JOG: case OA_CORRECT: case OA_SECTION:
    in->kind = a->kind == OA_JOG ? MRI_JOG : a->kind == OA_CORRECT ? MRI_CORRECT : MRI_SECTION;
    in->axis = a->axis;
    in->n = a->n;
    in->axis2 = a->axis2;
    in->n2 = a->n2;
    break;
  case OA_OVERRIDE:
    in->kind = MRI_OVERRIDE;
    in->n = a->n;
    break;
  case OA_MODE:
    in->kind = MRI_MODE;
    in->axis = a->n2 == OPMODE_SKIP ? MRM_SKIP : a->n2 == OPMODE_OPTSTOP ? MRM_OPTSTOP : MRM_SINGLE;
    in->n = a->n;
    break;
  case OA_BREAK:
    in->kind = MRI_BREAK;
    in->n = a->n;
    break;
  case OA_ZERO:
    in->kind = MRI_ZERO;
    for (int k = 0; k < CANON_AXES && k < OPS_NAXES; k++)
      in->v[k] = a->axis & (1 << k) ? (double)a->zero[k] / 1000.0 : NAN;
    break;
  default:
    in->kind = MRI_NKIND;
    break;
  }
}

static int has_number(const struct program *p, int n)
{
  for (size_t b = 0; b < p->nblocks; b++)
    if ((int)p->blocks[b].number == n)
      return 1;
  return 0;
}

/* Before the run: every action is one this machine has, every `at` and
 * `break` names a block the program has.  0, or -1 after saying why. */
static int check_script(struct host *h)
{
  int bad = 0;
  for (int pass = 0; pass < 2; pass++) {
    const struct op_action *v = pass ? h->ops.at : h->ops.v;
    size_t n = pass ? h->ops.nat : h->ops.n;
    for (size_t i = 0; i < n; i++) {
      const struct op_action *a = &v[i];
      struct mrun_input in;
      input_of(a, &in);
      const char *why = h->r.rt->refuses ? h->r.rt->refuses(&h->r, &in) : NULL;
      char what[96];
      if (why) {
        fprintf(stderr, "%s:%u:%u: error: %s: %s\n", h->o->operator_file, a->line, a->col,
                ops_describe(a, what, sizeof what), why);
        bad = 1;
      }
      if (pass && !has_number(h->p, a->at_number)) {
        fprintf(stderr, "%s:%u:%u: error: at N%d: the program has no block N%d, so this never fires\n",
                h->o->operator_file, a->line, a->col, a->at_number, a->at_number);
        bad = 1;
      }
      if (!pass && a->kind == OA_BREAK && a->n && !has_number(h->p, (int)a->n)) {
        fprintf(stderr, "%s:%u:%u: error: break N%lld: the program has no block N%lld, so it never waits there\n",
                h->o->operator_file, a->line, a->col, (long long)a->n, (long long)a->n);
        bad = 1;
      }
    }
  }
  return bad ? -1 : 0;
}

/* An action that does not wait: applied as the runner's input (a refusal
 * the machine reports itself, as a warning or on its screen). */
static void apply(struct host *h, const struct op_action *a)
{
  struct mrun_input in;
  char why[240];
  input_of(a, &in);
  if (mrun_input(&h->r, &in, why, sizeof why) && a->kind == OA_ZERO)
    fprintf(stderr, "%s:%u:%u: warning: zero refused: %s\n", h->o->operator_file, a->line, a->col, why);
}

/* A block boundary: the immediate actions at the head of the script. */
static void boundary(struct host *h)
{
  while (h->next < h->ops.n && !ops_is_waiting(&h->ops.v[h->next]) && h->r.state != MR_STOPPED)
    apply(h, &h->ops.v[h->next++]);
}

/* A watched block starts: its `at` actions for this run of it. */
static void at_start(struct host *h)
{
  uint32_t b = h->r.vm.cur;
  if (!h->watch || !h->watch[b])
    return;
  unsigned run = ++h->runs[b];
  int num = mrun_block_number(&h->r);
  if (num > 0 && (size_t)num < h->nnum)
    h->runs_n[num]++;
  for (size_t i = 0; i < h->ops.nat; i++) {
    struct op_action *a = &h->ops.at[i];
    if (!a->fired && a->at_number == num && a->at_run == run) {
      a->fired = 1;
      apply(h, a);
    }
  }
}

/* The machine waits: take the script's fitting actions.  0 when the wait is
 * over, -1 when the script has nothing that fits (stop, status 3). */
static int serve_wait(struct host *h)
{
  char what[96], nb[16], wt[300];
  struct mrun *r = &h->r;
  while (r->state == MR_WAIT && !r->resume) {
    const struct prog_block *b = &h->p->blocks[r->vm.cur];
    if (h->next >= h->ops.n) {
      if (h->mb)
        return -1;             /* a client serves this wait */
      fprintf(stderr, "%s:%u:%u: error: %s: the machine waits for %s and the operator script has no more actions\n",
              h->o->program, b->line, b->col, diag_block(mrun_block_number(r), nb), mrun_wait_text(r, wt, sizeof wt));
      return -1;
    }
    const struct op_action *a = &h->ops.v[h->next];
    int ok;
    if (!ops_is_waiting(a)) {
      apply(h, a);
      ok = 0;
    } else {
      struct mrun_input in;
      input_of(a, &in);
      char why[240];
      if (h->mb)               /* a tooth search may go on inside the key: reads show it running */
        mb_publish_running(h->mb, &h->mm);
      ok = mrun_input(r, &in, why, sizeof why);
    }
    if (ok && h->mb) {         /* it waits for a client instead (the action may fit a later wait) */
      h->unfit_wait.next = h->next + 1;
      h->unfit_wait.seq = r->seq;
      h->unfit_wait.cur = r->vm.cur;
      h->unfit_wait.wait = r->wait;
      return -1;
    }
    if (ok) {
      h->unfit = h->next + 1;
      fprintf(stderr, "%s:%u:%u: error: %s: the machine waits for %s; the operator script's next action "
              "(line %u: %s) does not fit\n", h->o->program, b->line, b->col, diag_block(mrun_block_number(r), nb),
              mrun_wait_text(r, wt, sizeof wt), a->line, ops_describe(a, what, sizeof what));
      return -1;
    }
    h->next++;
  }
  return 0;
}

/* ---- served over Modbus TCP (--modbus) ---- */

static void view_now(const struct mrun *r, struct mrun_view *v)
{
  if (r->rt->view)
    r->rt->view(r, v);
  else
    memset(v, 0, sizeof *v);
}

/* From here on a row's motion starts where the machine is now (a wait, a
 * hand move: what the machine did up to it shows at once). */
static void mark_position(struct host *h)
{
  if (h->r.in_block)
    return;                    /* a move within a block's work (oscillation): the block's row has it */
  struct mrun_view v;
  view_now(&h->r, &v);
  memcpy(h->last_pos, v.pos, sizeof h->last_pos);
  h->last_t = mrun_time(&h->r);
}

/* A row under --modbus: the contour speed the map shows, and with
 * --realtime the block's motion on the wall clock while the loop goes on
 * serving -- back to back when blocks follow each other, from now after a
 * wait. */
static void mb_row(struct host *h)
{
  struct mrun *r = &h->r;
  struct mb_machine *mm = &h->mm;
  struct mrun_view v;
  view_now(r, &v);
  double t = mrun_time(r), dur = t - h->last_t, now = mb_now();
  int64_t d[4];
  for (int a = 0; a < 4; a++)
    d[a] = v.pos[a] - h->last_pos[a];
  memcpy(h->last_pos, v.pos, sizeof h->last_pos);
  h->last_t = t;
  mm->feed = v.feed;
  if (!h->o->realtime || dur <= 0)
    return;
  double start = mm->motion.end > 0 && now - mm->motion.end < 0.05 ? mm->motion.end : now;
  mb_motion_start(mm, start, dur, d, v.feed, mrun_block_number(r));
}

/* Reset, and Пуск after the end: the program from its first block, the
 * runtime's new cycle (the 2С42: a fresh machine, R0-R113 kept; the 2У22:
 * the lathe where it is, R0-R9 at 0), the switches kept. */
static void new_cycle(struct host *h)
{
  mrun_renew(&h->r);
  memset(&h->mm.motion, 0, sizeof h->mm.motion);
  h->mm.ovr_held = 0;
  h->mm.feed = 0;
  mark_position(h);
  memset(h->runs, 0, (h->p->nblocks ? h->p->nblocks : 1) * sizeof *h->runs);
  memset(h->runs_n, 0, h->nnum * sizeof *h->runs_n);
}

/* A block's motion is under way on the wall clock (not held). */
static int in_motion(const struct mb_machine *mm, double now)
{
  return mm->motion.active && !mm->motion.held && now < mm->motion.end;
}

/* The script's next action was found not to fit this very wait. */
static int unfit_again(const struct host *h)
{
  const struct mrun *r = &h->r;
  return h->unfit_wait.next == h->next + 1 && h->unfit_wait.seq == r->seq && h->unfit_wait.cur == r->vm.cur &&
         h->unfit_wait.wait == r->wait;
}

/* Does the runner go on when stepped (not idle, waiting, stopped or over)? */
static int runnable(const struct mrun *r)
{
  return r->state == MR_ROW || r->state == MR_START || (r->state == MR_WAIT && r->resume);
}

/* A panel key from a client (contracts.md sec. 6, README "Modbus"). */
static void mb_press(struct host *h, int k)
{
  struct mrun *r = &h->r;
  struct mb_machine *mm = &h->mm;
  double now = mb_now();
  int moving = in_motion(mm, now);
  struct mrun_input in;
  memset(&in, 0, sizeof in);
  in.axis2 = -1;
  switch (k) {
  case MB_KEY_PUSK:
    if (mm->idle) {
      mm->idle = 0;
    } else if (mm->ovr_held) {
      if (r->state == MR_STOPPED)
        mrun_resume(r);        /* the Стоп is over; the override at 0 % still holds the move */
    } else if (r->state == MR_STOPPED || mm->motion.held) {
      if (mm->motion.held) {
        double len = mm->motion.end - mm->motion.start;
        mm->motion.start = now - mm->motion.held_frac * len;
        mm->motion.end = mm->motion.start + len;
        mm->motion.held = 0;
      }
      mb_publish_running(h->mb, mm);
      mrun_resume(r);
    } else if (r->state == MR_END) {
      new_cycle(h);
    } else if (!moving) {
      if (r->state == MR_WAIT)
        mb_publish_running(h->mb, mm);   /* a tooth search may go on inside the key */
      mrun_pusk(r);            /* a Пуск that fits no wait does nothing */
    }
    break;
  case MB_KEY_STOP:
    if (mm->idle || r->state == MR_END || r->state == MR_ERROR)
      break;
    if (moving) {
      mm->motion.held_frac = (now - mm->motion.start) / (mm->motion.end - mm->motion.start);
      mm->motion.held = 1;
    }
    mrun_stop(r);
    break;
  case MB_KEY_PS:
    if (!mm->idle && !moving) {
      if (r->state == MR_WAIT)
        mb_publish_running(h->mb, mm);
      in.kind = MRI_PS;
      mrun_input(r, &in, NULL, 0);   /* a machine without ПС refuses it: nothing happens */
    }
    break;
  case MB_KEY_EXIT:
    if (!mm->idle) {
      in.kind = MRI_EXIT;      /* taken by the next block that asks (the 2С42's PP) */
      mrun_input(r, &in, NULL, 0);
    }
    break;
  case MB_KEY_RESET:
    new_cycle(h);
    mm->idle = 1;
    break;
  default:
    break;
  }
}

static void row_out(struct host *h);

/* Serve the machine until SIGINT or SIGTERM.  Without an operator script
 * the cycle waits for a client's Пуск; with one, a wait the script cannot
 * serve waits for a client.  The exit status: 0 the cycle had reached its
 * end, 1 an error, 3 otherwise; 4 when the server failed or a restart
 * point's save did. */
static int mb_loop(struct host *h)
{
  struct mrun *r = &h->r;
  struct mb_machine *mm = &h->mm;
  const struct run_opts *o = h->o;
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_quit;     /* no SA_RESTART: poll() returns at once */
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, NULL);
  sigaction(SIGTERM, &sa, NULL);
  r->cfg.starts = 1;           /* back to the loop at every block: the map shows the block about to run */
  mark_position(h);
  mb_publish(h->mb, mm);
  fprintf(stderr, "s42: Modbus TCP on %s%s\n", mb_address(h->mb),
          mm->idle ? "; the cycle starts with Пуск (coil 0)" : "");
  int told = -1;               /* the state last reported on stderr */
  char nb[16];
  while (!quit_signal) {
    double now = mb_now();
    if (mm->motion.active && !mm->motion.held && now >= mm->motion.end)
      mm->motion.active = 0;
    int timeout = 100;
    if (!mm->idle && !mm->motion.active && runnable(r))
      timeout = 0;
    else if (in_motion(mm, now) && (mm->motion.end - now) * 1000 < timeout)
      timeout = (int)((mm->motion.end - now) * 1000) + 1;
    if (mb_poll(h->mb, mm, timeout)) {
      fprintf(stderr, "s42: Modbus: poll: %s\n", strerror(errno));
      return EXIT_IO;
    }
    for (int k; (k = mb_key(h->mb)) != MB_KEY_NONE;)
      mb_press(h, k);
    mb_publish(h->mb, mm);
    /* run the machine for a couple of milliseconds, or up to a paced motion;
     * the server thread answers meanwhile from what was published (a trace
     * that blocks or a plugin that computes stops only this loop) */
    double until = mb_now() + 0.002;
    unsigned steps = 0;
    while (!mm->idle && !mm->motion.active && !quit_signal) {
      if (r->state == MR_WAIT && !r->resume) {
        if (h->next >= h->ops.n || unfit_again(h) || serve_wait(h))
          break;               /* a client serves this wait */
        continue;
      }
      if (!runnable(r))
        break;
      enum mrun_ev ev = mrun_run(r);
      if (ev == MR_START) {
        at_start(h);
        boundary(h);
        mb_publish(h->mb, mm); /* the block about to run, should it take long */
      } else if (ev == MR_ROW) {
        row_out(h);
        boundary(h);
      } else if (ev == MR_WAIT) {
        mark_position(h);
      }
      /* the clock is read every 32 blocks: it costs as much as one */
      if ((++steps % 32 == 0 || (ev != MR_START && ev != MR_ROW)) && mb_now() >= until)
        break;
    }
    mb_publish(h->mb, mm);
    if (r->state == MR_ERROR && r->vm.err.code == S42_E_STATE)
      return EXIT_IO;          /* a restart point could not be saved: the server ends (status 4) */
    if (r->state != told && (r->state == MR_END || r->state == MR_ERROR)) {
      if (r->state == MR_END) {
        const struct prog_block *b = &h->p->blocks[r->vm.cur];
        fprintf(stderr, "%s:%u:%u: note: %s: the program reached its end; Пуск runs it again\n", o->program,
                b->line, b->col, diag_block(mrun_block_number(r), nb));
      } else {
        struct s42_error e;
        mrun_error(r, &e);
        fprintf(stderr, "%s:%u:%u: note: %s: the cycle stopped with %s (%s); reset (coil 4) to start again\n",
                o->program, e.line, e.col, diag_block(e.number, nb), err_code(e.code), e.msg);
      }
    }
    told = r->state;
  }
  if (r->state == MR_STOPPED && r->wait == MRW_NONE) {
    const struct prog_block *b = &h->p->blocks[r->vm.cur];
    fprintf(stderr, "%s:%u:%u: note: %s: the cycle was stopped (key STOP)\n", o->program, b->line, b->col,
            diag_block(mrun_block_number(r), nb));
  }
  return r->state == MR_END ? EXIT_END : r->state == MR_ERROR ? EXIT_PROGRAM : EXIT_STOPPED;
}

/* ---- the run ---- */

static int load_side(struct host *h, const char *what, const char *path)
{
  char *text, err[600];
  size_t n;
  if (file_read_all(path, FILE_OR_STDIN, MAX_SIDE_FILE, &text, &n, err, sizeof err)) {
    fprintf(stderr, "s42: %s\n", err);
    return EXIT_IO;
  }
  int rc = 0, e = h->r.rt->load ? h->r.rt->load(&h->r, what, text, n, path, err, sizeof err) : -2;
  if (e == -2 && !h->r.rt->load)
    snprintf(err, sizeof err, "the %s reads no %s file", h->r.rt->machine ? h->r.rt->machine : "machine", what);
  if (e == -2)
    fprintf(stderr, "s42: %s: %s\n", h->o->program, err);
  else if (e)
    fprintf(stderr, "%s\n", err);
  if (e)
    rc = EXIT_USAGE;
  free(text);
  return rc;
}

/* The run's error on stderr: the diagnostic, then the machine's words. */
static void print_error(const struct host *h, const struct diag_list *d, const struct s42_error *e)
{
  struct diag g;
  s42_error_diag(e, &g);
  diag_print_in(stderr, d, &g);
  const struct mrun_rt *rt = h->r.rt;
  const char *pre = h->o->en ? rt->note_en : rt->note_uk;
  if (!pre)
    return;
  char m[200];
  s42_error_machine(e, h->p, h->o->en, m, sizeof m);
  fprintf(stderr, "%s:%u:%u: note: %s%s\n", h->o->program, e->line, e->col, pre, m);
}

static const char *status_name(int st)
{
  return st == EXIT_END ? "end" : st == EXIT_STOPPED ? "stopped" : "error";
}

/* A block ran: its row on the trace and to the watcher; paced (--realtime)
 * by sleeping, or under --modbus by its motion on the wall clock. */
static void row_out(struct host *h)
{
  struct mrun *r = &h->r;
  const struct run_opts *o = h->o;
  if (h->mb)
    mb_row(h);
  else if (o->realtime)
    pace_sleep_until(&h->pace, mrun_time(r));
  if (o->trace) {
    if (o->json)
      mrun_row_json(r, stdout);
    else
      mrun_row_text(r, stdout);
    putchar('\n');
    if (o->realtime || h->mb)
      fflush(stdout);
  }
  if (o->watch && o->watch->row)
    o->watch->row(o->watch->ctx, r);
}

/* The loop: 0 end, 1 program error, 3 stopped, 4 a save of the restart
 * state failed. */
static int loop(struct host *h)
{
  struct mrun *r = &h->r;
  const struct run_opts *o = h->o;
  char nb[16];
  boundary(h);
  for (;;) {
    r->cfg.starts = h->interruptible || (h->next < h->ops.n && !ops_is_waiting(&h->ops.v[h->next]));
    if (h->interruptible && quit_signal && r->state != MR_WAIT) {
      const struct prog_block *b = &h->p->blocks[r->vm.cur];
      fprintf(stderr, "%s:%u:%u: note: %s: stopped by %s before this block\n", o->program, b->line, b->col,
              diag_block(mrun_block_number(r), nb), quit_signal == SIGINT ? "Ctrl-C (SIGINT)" : "SIGTERM");
      mrun_stop(r);
      h->stop = RUN_STOP_OTHER;
      return EXIT_STOPPED;
    }
    enum mrun_ev ev = mrun_run(r);
    switch (ev) {
    case MR_START:
      at_start(h);
      boundary(h);
      if (r->state == MR_STOPPED) {
        const struct prog_block *b = &h->p->blocks[r->vm.cur];
        fprintf(stderr, "%s:%u:%u: note: %s: the cycle was stopped (key STOP)\n", o->program, b->line, b->col,
                diag_block(mrun_block_number(r), nb));
        h->stop = RUN_STOP_KEY;
        return EXIT_STOPPED;
      }
      continue;
    case MR_ROW:
      row_out(h);
      boundary(h);
      continue;
    case MR_WAIT:
      if (serve_wait(h) == 0) {
        if (r->state != MR_STOPPED)
          continue;
        h->stop = RUN_STOP_KEY;   /* Стоп while it waited */
        return EXIT_STOPPED;
      }
      if (r->state == MR_WAIT)
        mrun_stop(r);
      h->stop = RUN_STOP_SCRIPT;
      return EXIT_STOPPED;
    case MR_STOPPED: {
      const struct prog_block *b = &h->p->blocks[r->vm.cur];
      fprintf(stderr, "%s:%u:%u: note: %s: the cycle was stopped (key STOP)\n", o->program, b->line, b->col,
              diag_block(mrun_block_number(r), nb));
      h->stop = RUN_STOP_KEY;
      return EXIT_STOPPED;
    }
    case MR_END:
      return EXIT_END;
    default:
      return r->vm.err.code == S42_E_STATE ? EXIT_IO : EXIT_PROGRAM;
    }
  }
}

static void free_host(struct host *h)
{
  mrun_free(&h->r);
  free(h->watch);
  free(h->runs);
  free(h->runs_n);
  ops_free(&h->ops);
}

int run_headless(const struct run_opts *o, const struct program *p, const struct diag_list *d, const char *src,
                 size_t n)
{
  struct host h;
  memset(&h, 0, sizeof h);
  h.o = o;
  h.p = p;
  canon_trace_init(&h.canon, canon_line, NULL);
  const struct mrun_rt *rt = p->runtime;
  if (!rt || !rt->machine) {
    /* on the VM alone: nothing of a machine to drive */
    if (o->watch || o->mb || o->operator_file || o->state || o->restart || o->tools || o->machine) {
      fprintf(stderr, "s42: %s: this dialect runs its blocks on the VM alone: plot, --modbus, --operator, "
              "--state, --restart, --tool and --machine need a machine\n", o->program);
      return EXIT_USAGE;
    }
  }
  if (o->operator_file) {
    char *text, err[600];
    size_t len;
    int rr = file_read_all(o->operator_file, FILE_OR_STDIN, MAX_SIDE_FILE, &text, &len, err, sizeof err);
    if (rr) {
      fprintf(stderr, "s42: %s%s\n", err, rr == -2 ? " [E-LIMIT]" : "");
      return EXIT_IO;
    }
    int bad = ops_parse(text, len, o->operator_file, &h.ops, stderr);
    free(text);
    if (bad)
      return EXIT_USAGE;
  }
  size_t nb = p->nblocks ? p->nblocks : 1;
  h.watch = calloc(nb, 1);
  h.runs = calloc(nb, sizeof *h.runs);
  h.nnum = 1;
  for (size_t b = 0; b < p->nblocks; b++)
    if (p->blocks[b].number >= h.nnum)
      h.nnum = p->blocks[b].number + 1;
  h.runs_n = calloc(h.nnum, sizeof *h.runs_n);
  if (!h.watch || !h.runs || !h.runs_n) {
    fprintf(stderr, "s42: out of memory\n");
    free_host(&h);
    return EXIT_IO;
  }
  int any_watch = 0;
  for (size_t i = 0; i < h.ops.nat; i++)
    for (size_t b = 0; b < p->nblocks; b++)
      if ((int)p->blocks[b].number == h.ops.at[i].at_number)
        h.watch[b] = any_watch = 1;
  /* the restart state: where a restart point saves, or a run that stops */
  char *state_path = NULL;
  int points = 0;
  for (size_t b = 0; rt && rt->restart_point && b < p->nblocks && !points; b++) {
    struct mrun probe;
    memset(&probe, 0, sizeof probe);
    probe.p = p;
    probe.rt = rt;
    points = rt->restart_point(&probe, (uint32_t)b);
  }
  int stop_saves = rt && rt->save && !rt->restart_word && o->state;
  if (points || o->restart || stop_saves) {
    if (o->state) {
      state_path = strdup(o->state);
    } else if ((state_path = malloc(strlen(o->program) + 7)) != NULL) {
      sprintf(state_path, "%s.state", o->program);
    }
    if (!state_path) {
      fprintf(stderr, "s42: out of memory\n");
      free_host(&h);
      return EXIT_IO;
    }
  }
  struct mrun_config c;
  memset(&c, 0, sizeof c);
  c.en = o->en;
  c.max_blocks = o->max_blocks;
  c.rows = o->trace || o->realtime || o->watch || o->mb;
  c.every = o->trace;
  c.ctx = &h;
  c.warn = warn;
  c.log = note;
  c.canon = on_call;
  c.moved = on_moved;
  c.watch = any_watch ? h.watch : NULL;
  c.state_path = points ? state_path : NULL;
  c.prog_hash = mrun_hash(src, n);
  int rc = EXIT_END, ran = 0;
  struct s42_error e, *ep = NULL;
  if (mrun_init(&h.r, p, &c)) {
    mrun_error(&h.r, &e);
    fprintf(stderr, "s42: %s: %s\n", o->program, e.msg);
    rc = EXIT_PROGRAM;
    ep = &e;
  } else if (o->operator_file && check_script(&h)) {
    fprintf(stderr, "%s: note: the operator script %s is refused: the run does not start\n", o->program,
            o->operator_file);
    rc = EXIT_USAGE;
  }
  if (rc == EXIT_END && o->tools)
    rc = load_side(&h, "tools", o->tools);
  if (rc == EXIT_END && o->machine)
    rc = load_side(&h, "machine", o->machine);
  if (rc == EXIT_END && h.r.rt->prepare) {
    /* the plugins the program uses start now: one that cannot because of
     * the command line (no --tool for G10) stops the run before it begins */
    char why[300], nbuf[16];
    uint32_t fb = 0;
    if (h.r.rt->prepare(&h.r, why, sizeof why, &fb)) {
      const struct prog_block *b = &p->blocks[fb];
      fprintf(stderr, "s42: %s\n", why);
      fprintf(stderr, "%s:%u:%u: note: %s: the first block that needs it\n", o->program, b->line, b->col,
              diag_block(b->number ? (int)b->number : -1, nbuf));
      rc = EXIT_USAGE;
    }
  }
  if (rc == EXIT_END && o->restart) {
    char serr[512];
    if (mrun_restore(&h.r, state_path, serr, sizeof serr)) {
      fprintf(stderr, "%s:1:1: error: N-: restart refused: %s [E-STATE]\n", o->program, serr);
      mrun_refuse(&h.r, S42_E_STATE, "restart refused: %s", serr);
      mrun_error(&h.r, &e);
      snprintf(e.msg, sizeof e.msg, "%s", serr);   /* the dump says why; stderr said "restart refused" */
      e.number = -1;
      ep = &e;
      rc = EXIT_PROGRAM;
    }
  }
  if (rc == EXIT_END && o->mb) {
    /* the server listens once the run is set up, so that what would refuse
     * it (a script, a plugin's option, a restart) is said first */
    char err[300];
    int bad = 0;
    if (!(h.mb = mb_open(o->mb, err, sizeof err, &bad))) {
      fprintf(stderr, "s42: %s\n", err);
      rc = bad ? EXIT_USAGE : EXIT_IO;
    } else if (*mb_warning(h.mb)) {
      fprintf(stderr, "s42: warning: %s\n", mb_warning(h.mb));
    }
    h.mm.r = &h.r;
    h.mm.idle = !o->operator_file;   /* without a script the cycle starts with a client's Пуск */
  }
  if (rc == EXIT_END) {
    ran = 1;
    if (o->watch && o->watch->start)
      o->watch->start(o->watch->ctx, &h.r);
    h.interruptible = o->realtime && !o->mb;
    h.pace.stop = NULL;
    if (h.interruptible) {
      /* --realtime takes as long as the machine would: Ctrl-C (or SIGTERM)
       * stops it at the next block boundary with the dump of that moment */
      struct sigaction sa;
      memset(&sa, 0, sizeof sa);
      sa.sa_handler = on_quit;   /* no SA_RESTART: the pacing sleep returns at once */
      sigemptyset(&sa.sa_mask);
      sigaction(SIGINT, &sa, NULL);
      sigaction(SIGTERM, &sa, NULL);
      h.pace.stop = &quit_signal;
    }
    pace_start(&h.pace, mrun_time(&h.r));   /* a restart goes on from the saved time */
    rc = h.mb ? mb_loop(&h) : loop(&h);
    if (h.mb) {
      mb_close(h.mb);
      h.mb = NULL;
    }
    if (rc == EXIT_PROGRAM || (rc == EXIT_IO && h.r.state == MR_ERROR)) {
      mrun_error(&h.r, &e);
      print_error(&h, d, &e);
      ep = &e;
    }
    if (rc == EXIT_STOPPED && stop_saves && !(o->mb && h.mm.idle)) {   /* (idle under --modbus: nothing ran) */
      char serr[512];
      if (mrun_save(&h.r, state_path, serr, sizeof serr))
        fprintf(stderr, "%s: warning: the run stopped, but where it stopped is not saved: %s\n", o->program, serr);
      else
        fprintf(stderr, "%s: note: where the run stopped is saved in %s (--restart goes on from there)\n",
                o->program, state_path);
    }
  }
  if (o->operator_file && ran)
    ops_warn_unused(&h.ops, h.next, h.unfit, h.runs_n, o->operator_file, stderr);
  if (o->dump && (rc == EXIT_END || rc == EXIT_PROGRAM || rc == EXIT_STOPPED || (rc == EXIT_IO && ep)))
    mrun_dump(&h.r, stdout, status_name(rc == EXIT_IO ? EXIT_PROGRAM : rc), ep);
  if (o->watch && o->watch->result && rc != EXIT_USAGE && (rc != EXIT_IO || ep))
    o->watch->result(o->watch->ctx, &h.r, rc == EXIT_IO ? EXIT_PROGRAM : rc, ep ? err_code(ep->code) : NULL,
                     ep ? ep->number : -1, ep ? ep->line : 0, h.stop);
  if (o->screen && h.r.rt->screen && rc != EXIT_USAGE) {
    if (ep && h.r.rt->show) {   /* the error on the machine's display, in its words */
      char m[200];
      s42_error_machine(ep, p, o->en, m, sizeof m);
      h.r.rt->show(&h.r, m);
    }
    h.r.rt->screen(&h.r, stdout);
  }
  if (fflush(stdout) || ferror(stdout)) {
    fprintf(stderr, "s42: error writing the output\n");
    rc = EXIT_IO;
  }
  free(state_path);
  free_host(&h);
  return rc;
}

void run_dump_refused(const void *rt, const struct program *p, const struct s42_error *e, int en)
{
  mrun_dump_refused(rt, stdout, e, en, p);
}
