/* s42 tui for a program on the neutral runner (tui.h: tmr_*): the 2У22's
 * lathe, or any dialect whose registry entry says DIALECT_RUN_MACHINE.
 * The run is stepped here a block at a time (mrun_run never blocks); at
 * machine speed each block's simulated time runs off on the wall clock
 * (pace.h) before the next block starts, so the listing's mark, the pages
 * and the waits follow the machine as an operator would see them.  The
 * terminal (tui.c) draws the pages this gives and maps the keys to
 * tmr_pusk, tmr_stop, tmr_reset and tmr_set. */
#include "tui.h"
#include "atomic.h"
#include "diag.h"
#include "dialect.h"
#include "errors.h"
#include "mrun.h"
#include "pace.h"
#include "utf8.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

struct tmr {
  tmr_say_fn say;
  void *ctx;
  int en;
  unsigned long long max_blocks;
  struct program prog;
  int have_prog;
  char *src;                 /* the text it was compiled from (the program may point into it) */
  char *path;
  struct mrun r;
  int have_run;
  int phase;                 /* enum tmr_phase */
  int sw[3];                 /* the switches, kept across runs: single, skip, optstop */
  struct pace pace;
  int paced;                 /* the last block's time is running off: the next starts at t1 */
  double t0, t1;             /* that block's start and end, simulated s */
  int fast;                  /* the last advance was as fast as possible */
  size_t nsrc;
  long cur;                  /* the block shown as current, -1 none */
  long rows;                 /* rows of this cycle */
  unsigned cycles;           /* cycles started */
  char *tools;               /* the machine's tool table (--tools), its text, or NULL */
  size_t ntools;
  char *tools_path;
};

static void sayf(struct tmr *m, int log, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void sayf(struct tmr *m, int log, const char *fmt, ...)
{
  char b[400];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(b, sizeof b, fmt, ap);
  va_end(ap);
  if (m->say)
    m->say(m->ctx, log, b);
}

static void on_warn(void *ctx, const struct mrun *r, const char *msg)
{
  struct tmr *m = ctx;
  char nb[16];
  sayf(m, 1, "%s: warning: %s", diag_block(mrun_block_number(r), nb), msg);
}

struct tmr *tmr_new(int en, unsigned long long max_blocks, tmr_say_fn say, void *ctx)
{
  struct tmr *m = calloc(1, sizeof *m);
  if (!m)
    return NULL;
  m->en = en;
  m->max_blocks = max_blocks;
  m->say = say;
  m->ctx = ctx;
  m->cur = -1;
  return m;
}

static void drop(struct tmr *m)
{
  if (m->have_run)
    mrun_free(&m->r);
  m->have_run = 0;
  if (m->have_prog)
    prog_free(&m->prog);
  m->have_prog = 0;
  free(m->src);
  m->src = NULL;
  free(m->path);
  m->path = NULL;
  m->cur = -1;
  m->paced = 0;
  m->phase = TMR_READY;
}

void tmr_free(struct tmr *m)
{
  if (m) {
    free(m->tools);
    free(m->tools_path);
  }
  if (!m)
    return;
  drop(m);
  free(m);
}

static double sim_time(const struct tmr *m)
{
  return m->have_run && m->r.rt && m->r.rt->time ? m->r.rt->time(&m->r) : 0;
}

static void apply_switches(struct tmr *m)
{
  m->r.single = m->sw[TMR_SINGLE];
  m->r.skip = m->sw[TMR_SKIP];
  m->r.optstop = m->sw[TMR_OPTSTOP];
}

int tmr_load(struct tmr *m, const struct dialect *dl, const char *src, size_t n, const char *path)
{
  drop(m);
  m->src = malloc(n + 1);
  m->path = strdup(path ? path : "(new)");
  if (!m->src || !m->path) {
    sayf(m, 1, "out of memory");
    drop(m);
    return -1;
  }
  memcpy(m->src, src, n);
  m->src[n] = 0;
  m->nsrc = n;
  struct diag_list d;
  prog_init(&m->prog);
  m->have_prog = 1;
  diag_init(&d, m->path);
  int bad = dl->compile(m->src, n, &d, &m->prog, NULL);
  diag_free(&d);
  if (bad || !m->prog.runtime) {
    sayf(m, 1, bad ? "the program does not compile: no machine for it"
                   : "the %s dialect gives no runtime for its machine", dl->name);
    drop(m);
    return -1;
  }
  struct mrun_config c;
  memset(&c, 0, sizeof c);
  c.en = m->en;
  c.max_blocks = m->max_blocks;
  c.ctx = m;
  c.warn = on_warn;
  c.rows = 1;   /* every block comes back: the pacing runs off its time */
  int bad_run = mrun_init(&m->r, &m->prog, &c);
  m->have_run = 1;
  if (bad_run) {
    sayf(m, 1, "the machine refuses the program: %s", m->r.vm.err.msg);
    drop(m);
    return -1;
  }
  if (m->tools && m->r.rt->load) {
    char err[300];
    if (m->r.rt->load(&m->r, "tools", m->tools, m->ntools, m->tools_path, err, sizeof err))
      sayf(m, 1, "%s", err);
  }
  apply_switches(m);
  m->phase = TMR_READY;
  return 0;
}

int tmr_tools(struct tmr *m, const char *path, char *err, size_t n)
{
  char *text;
  size_t len;
  if (file_read_all(path, FILE_OR_STDIN, (size_t)1 << 20, &text, &len, err, n))
    return -1;
  char *p = strdup(path);
  if (!p) {
    free(text);
    snprintf(err, n, "out of memory");
    return -1;
  }
  free(m->tools);
  free(m->tools_path);
  m->tools = text;
  m->ntools = len;
  m->tools_path = p;
  return 0;
}

static const char *wait_hint(const struct tmr *m)
{
  if (m->r.wait == MRW_BLOCK)
    return "single block (П/АВТ): Пуск (F5 or g) starts it";
  return "a programmed stop: Пуск (F5 or g) goes on";
}

/* The run's error on the message line: where, the machine's words, the code. */
static void show_error(struct tmr *m)
{
  const struct vm_error *e = &m->r.vm.err;
  const struct prog_block *b = e->block < m->prog.nblocks ? &m->prog.blocks[e->block] : NULL;
  char nb[16];
  m->cur = b ? (long)e->block : -1;
  /* the code before the words, which may not fit the line */
  sayf(m, 1, "%u:%u error %s [%s]: %s", b ? b->line : 1, e->col ? e->col : b ? b->col : 1,
       diag_block(b && b->number ? (int)b->number : -1, nb), err_code(e->code), e->msg);
}

static void begin(struct tmr *m, const char *what)
{
  apply_switches(m);
  m->phase = TMR_RUN;
  m->paced = 0;
  m->rows = 0;
  m->cur = -1;
  m->t1 = sim_time(m);
  m->cycles++;
  pace_start(&m->pace, sim_time(m));
  sayf(m, 1, "%s", what);
}

int tmr_pusk(struct tmr *m)
{
  if (!m->have_run) {
    sayf(m, 1, "Пуск: no program for the machine");
    return -1;
  }
  switch (m->phase) {
  case TMR_READY:
    begin(m, "Пуск: the cycle starts");
    return 0;
  case TMR_END: case TMR_STOPPED: case TMR_ERROR:
    mrun_renew(&m->r);   /* the machine stays where it is */
    begin(m, m->phase == TMR_END ? "Пуск after the end: a new cycle from the first block"
                                 : "Пуск: a new cycle from the first block");
    return 0;
  case TMR_HOLD:
    m->phase = TMR_RUN;
    pace_hold(&m->pace, 0);
    sayf(m, 1, "Пуск: the cycle goes on");
    return 0;
  case TMR_WAIT:
    apply_switches(m);
    if (mrun_pusk(&m->r) == 0) {
      m->phase = TMR_RUN;
      m->paced = 0;
      pace_start(&m->pace, sim_time(m));   /* the operator's time is not run off afterwards */
      return 0;
    }
    sayf(m, 1, "Пуск: the machine does not wait for it");
    return -1;
  default:
    sayf(m, 0, "the cycle is running");
    return -1;
  }
}

void tmr_stop(struct tmr *m)
{
  char nb[16];
  if (!m->have_run || (m->phase != TMR_RUN && m->phase != TMR_HOLD && m->phase != TMR_WAIT)) {
    sayf(m, 1, "Стоп: no cycle is running");
    return;
  }
  if (m->phase == TMR_RUN) {
    m->phase = TMR_HOLD;
    pace_hold(&m->pace, 1);
    sayf(m, 1, "Стоп: the feed stops -- Пуск goes on, Стоп again ends the cycle");
    return;
  }
  mrun_stop(&m->r);
  m->phase = TMR_STOPPED;
  m->paced = 0;
  sayf(m, 1, "Стоп: the cycle was stopped at %s; Пуск starts a new one",
       diag_block(mrun_block_number(&m->r), nb));
}

void tmr_reset(struct tmr *m)
{
  if (!m->have_run) {
    sayf(m, 1, "reset: no program for the machine");
    return;
  }
  if (m->phase == TMR_RUN || m->phase == TMR_HOLD || m->phase == TMR_WAIT)
    mrun_stop(&m->r);
  mrun_renew(&m->r);   /* the slides stay where they are */
  apply_switches(m);
  m->phase = TMR_READY;
  m->paced = 0;
  m->cur = -1;
  sayf(m, 1, "reset: the cycle is abandoned; Пуск starts the program from its first block");
}

void tmr_repace(struct tmr *m)
{
  if (!m->have_run)
    return;
  pace_start(&m->pace, sim_time(m));
  if (m->phase == TMR_HOLD)
    pace_hold(&m->pace, 1);   /* the hold stands */
}

int tmr_advance(struct tmr *m, int fast)
{
  if (!m->have_run || m->phase != TMR_RUN)
    return -1;
  struct timespec t0, now;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  char nb[16];
  m->fast = fast;
  for (unsigned i = 0;; i++) {
    if (m->paced && !fast) {
      double ahead = pace_ahead(&m->pace, m->t1);
      if (ahead > 0) {
        int ms = (int)ceil(ahead * 1000);
        return ms < 40 ? ms : 40;   /* the clock on the screen goes on meanwhile */
      }
    }
    m->paced = 0;
    if ((i & 15) == 15) {
      clock_gettime(CLOCK_MONOTONIC, &now);
      if ((double)(now.tv_sec - t0.tv_sec) + (double)(now.tv_nsec - t0.tv_nsec) / 1e9 > 0.02)
        return 0;   /* keep the keys and the screen alive */
    }
    apply_switches(m);
    enum mrun_ev ev = mrun_run(&m->r);
    switch (ev) {
    case MR_ROW:
      m->cur = (long)m->r.vm.cur;
      m->t0 = m->t1;
      m->t1 = sim_time(m);
      m->paced = 1;
      m->rows++;
      continue;
    case MR_START:
      continue;     /* a watched start: the terminal watches none */
    case MR_WAIT:
      m->phase = TMR_WAIT;
      m->cur = (long)m->r.vm.cur;
      sayf(m, 0, "%s waits: %s", diag_block(mrun_block_number(&m->r), nb), wait_hint(m));
      return -1;
    case MR_END:
      m->phase = TMR_END;
      sayf(m, 1, "the program ended: %llu blocks, %.2f s; Пуск starts it again",
           (unsigned long long)m->r.vm.blocks, sim_time(m));
      return -1;
    case MR_STOPPED:
      m->phase = TMR_STOPPED;
      sayf(m, 1, "the cycle was stopped");
      return -1;
    default:
      m->phase = TMR_ERROR;
      show_error(m);
      return -1;
    }
  }
}

void tmr_set(struct tmr *m, enum tmr_switch w, int on)
{
  m->sw[w] = on != 0;
  if (m->have_run)
    apply_switches(m);
}

int tmr_get(const struct tmr *m, enum tmr_switch w)
{
  return m->sw[w];
}

enum tmr_phase tmr_phase(const struct tmr *m)
{
  return (enum tmr_phase)m->phase;
}

long tmr_block(const struct tmr *m, int *number, unsigned *line)
{
  *number = -1;
  *line = 0;
  if (!m->have_run || m->cur < 0 || (size_t)m->cur >= m->prog.nblocks)
    return -1;
  const struct prog_block *b = &m->prog.blocks[m->cur];
  *number = b->number ? (int)b->number : -1;
  *line = b->line;
  return m->cur;
}

int tmr_npages(const struct tmr *m)
{
  int n = 0;
  const char *const *p = m->have_run && m->r.rt && m->r.rt->page ? m->r.rt->pages : NULL;
  while (p && p[n])
    n++;
  return n ? n : 1;   /* without the hook: one page of the last row */
}

const char *tmr_page_name(const struct tmr *m, int k)
{
  const char *const *p = m->have_run && m->r.rt && m->r.rt->page ? m->r.rt->pages : NULL;
  if (!p || !p[0])
    return "row";
  return k >= 0 && k < tmr_npages(m) ? p[k] : "?";
}

char *tmr_page(const struct tmr *m, int k)
{
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  if (!f)
    return NULL;
  if (!m->have_run)
    fputs("(no machine: the program must\n compile first)\n", f);
  else if (m->r.rt && m->r.rt->page && m->r.rt->pages && m->r.rt->pages[0]) {
    struct mrun_page pg;
    m->r.rt->page(&m->r, k, &pg);
    for (int y = 0; y < pg.rows; y++) {
      int w = pg.cols;
      while (w > 0 && (!pg.cell[y][w - 1] || pg.cell[y][w - 1] == ' '))
        w--;
      for (int x = 0; x < w; x++) {
        char u[4];
        int l = utf8_encode((int32_t)(pg.cell[y][x] ? pg.cell[y][x] : ' '), u);
        fwrite(u, 1, (size_t)l, f);
      }
      fputc('\n', f);
    }
  }
  else if (m->rows) {
    mrun_row_text(&m->r, f);   /* the last block's trace row */
    fputc('\n', f);
  } else {
    fputs("(no block has run yet)\n", f);
  }
  if (fclose(f))
    return NULL;
  return buf;
}

const char *tmr_modes(const struct tmr *m, char *b, size_t n)
{
  snprintf(b, n, "%s%s%s", m->sw[TMR_SINGLE] ? "П/АВТ" : "АВТ", m->sw[TMR_OPTSTOP] ? " ST" : "",
           m->sw[TMR_SKIP] ? " U/" : "");
  return b;
}

const char *tmr_state(const struct tmr *m, char *b, size_t n)
{
  char nb[16];
  if (!m->have_run)
    return "no machine: the program does not compile";
  switch (m->phase) {
  case TMR_READY: return "ready: Пуск starts the cycle";
  case TMR_RUN: return "running";
  case TMR_HOLD: return "feed hold (Стоп)";
  case TMR_WAIT:
    snprintf(b, n, "%s waits: %s", diag_block(mrun_block_number(&m->r), nb), wait_hint(m));
    return b;
  case TMR_END: return "end";
  case TMR_STOPPED: return "stopped";
  default: {
    const struct vm_error *e = &m->r.vm.err;
    const struct prog_block *pb = e->block < m->prog.nblocks ? &m->prog.blocks[e->block] : NULL;
    snprintf(b, n, "error %s %s", diag_block(pb && pb->number ? (int)pb->number : -1, nb), err_code(e->code));
    return b;
  }
  }
}

int tmr_same(const struct tmr *m, const char *src, size_t n)
{
  return m->have_run && m->src && m->nsrc == n && memcmp(m->src, src, n) == 0;
}

double tmr_clock(const struct tmr *m)
{
  if (!m->have_run)
    return 0;
  if (m->paced && !m->fast && (m->phase == TMR_RUN || m->phase == TMR_HOLD)) {
    double now = pace_now(&m->pace);
    return now < m->t0 ? m->t0 : now > m->t1 ? m->t1 : now;
  }
  return sim_time(m);
}

double tmr_time(const struct tmr *m)
{
  return sim_time(m);
}

unsigned tmr_cycles(const struct tmr *m)
{
  return m->cycles;
}

unsigned long long tmr_blocks(const struct tmr *m)
{
  return m->have_run ? (unsigned long long)m->r.vm.blocks : 0ULL;
}
