/* s42 tui (src/host/tui.h): the curses front end.  It owns the loop: advance the
 * session at machine speed, draw, then poll the keyboard and the other
 * sources with a timeout -- never a blocking wait.  The 2С42-65 screen is
 * the session's rendered grid, only copied here; everything else on the
 * terminal (listing, editor, parameters page, machine state, messages) is
 * drawn from the session and the text buffer each pass.  The estimated
 * cycle time comes from a forked copy of the session run headless, read
 * back through a pipe in the same poll. */
#define NCURSES_WIDECHAR 1
#include "tui.h"
#include "cycle.h"
#include "dialect.h"
#include "error.h"
#include "compile.h"
#include "errors.h"
#include "kp.h"
#include "mrun.h"
#include "pace.h"
#include "kpreport.h"
#include "state.h"
#include "tuitext.h"
/* curses.h declares its own screen_init (and struct screen only as the
 * opaque SCREEN, which ncurses never lets us look into): rename its
 * screen_init away so display/screen.h's stays the one in use. */
#define screen_init curses_scr_init_unused
#include <curses.h>
#undef screen_init
#include "curses_dl.h"   /* ncursesw through dlopen: main.c loads it for s42 tui */
#include <errno.h>
#include <fcntl.h>
#include <langinfo.h>
#include <locale.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#include <wchar.h>

#define LOGN 200            /* messages kept */
#define LOGW 200            /* characters per message */
#define NCHG 24             /* registers that changed last */
#define INPUTMAX 1000          /* characters of the input line */
#define MAXSRC_FD 64
#define SCR_H (SCR_ROWS + 2)   /* the framed 2С42 screen */
#define SCR_W (SCR_COLS + 2)
#define SIDE_MIN 24         /* narrowest listing worth drawing beside the machine */
#define MACH_W 20           /* the machine pane when the terminal is narrow */
#define NPITEM (114 + 4 + 2 * (1 + KP_CELLS))   /* the parameters page: R0-R113, D1 TK UG F, two arrays */
#define PCOLW 22            /* one column of the parameters page */
#define EST_SECONDS 5       /* the estimate's computation gives up after this (a loop): "at least" */
#define BIT(x, n) (((x) >> (n)) & 1)

enum { R_IDLE, R_RUN, R_DONE };                 /* no run yet; a cycle is on; it ended */
enum { F_PANEL, F_EDIT, F_PARAMS };             /* where the keys go */
enum { IN_NONE, IN_INSERT, IN_REPLACE, IN_OPEN, IN_SAVEAS, IN_QUIT, IN_OPENASK, IN_QUITRUN, IN_OVERWRITE,
       IN_FIND, IN_GOTO, IN_PARAM, IN_BREAK };
/* the estimate of the cycle time: none yet; the cycle's end; a lower
 * bound (the operator must act first, or it ran too long); an error */
enum { EST_NONE, EST_END, EST_LEAST, EST_ERROR };

/* What the estimate's child process writes back through its pipe. */
struct est_result {
  int kind;
  double t;                 /* simulated time where it stopped */
  uint64_t blocks;          /* blocks done there */
  int resumed;              /* the session's plugin resumes in that block */
};

struct tui {
  struct tui_opts o;
  const struct tui_source *src;
  int nsrc;
  int utf8;                 /* the terminal takes UTF-8; otherwise one ASCII stand-in per character */
  int colors;
  /* the program text */
  struct tui_text text;
  char *path;
  int dirty;                /* the text is not what was read or saved last */
  struct tui_disk disk;     /* the file as it was read or saved (a save compares) */
  uint64_t saved_hash;      /* the text as read or saved: an undo back to it is not a change */
  size_t saved_len;
  char *save_to;            /* IN_OVERWRITE: the save that waits for y */
  unsigned gen;             /* bumped by every edit */
  unsigned char *mark;      /* per line after the last check: 0, 1 warning, 2 error */
  size_t nmark, nerr, nwarn;
  int checked;
  /* the run */
  int run;
  unsigned run_gen;         /* the text generation the run was compiled from */
  struct program prog;
  int have_prog;
  char *run_src;
  struct cycle cyc;          /* the run's setup: the restart point's file, the M15 saves */
  int restart_pending;
  struct session s;
  struct pace pace;
  int fast, held;
  int ovr_held;             /* the override went to 0 % within a move: it stands until the switch leaves 0 */
  int single, brk;          /* single block (П/АВТ), the breakpoint's block number (0 none): the panel's switches */
  int stopped_mid;          /* Стоп ended the cycle during a held move: the axes stay where they stopped */
  int osc;                  /* the oscillation plugin says it is on */
  int override;             /* the feed override switch, % */
  double last_t;            /* simulated time at the end of the last row */
  double wait_t;            /* simulated time when the machine began to wait */
  struct {
    int valid;
    int64_t from[4], to[4];
    double t0, t1, feed;
    double ts, fs;          /* the override last turned within it: then (s), the share of it made by then */
    unsigned line;
    int n;
  } cur;                    /* the last block carried out: its motion in time */
  double regs[114];
  struct { int reg, n; double v; int how; } chg[NCHG];   /* how: 0 a block, 1 restart, 2 the panel */
  int nchg;
  unsigned runs;            /* cycles started: the estimate knows which it is for */
  uint64_t pp_seen;         /* operational jumps reported */
  struct {
    pid_t pid;              /* the child computing it, 0 none */
    int fd;                 /* its pipe, -1 none */
    int kind;               /* the last result, EST_* */
    double total;
    uint64_t at_blocks;     /* EST_LEAST: where it stopped */
    int at_resumed;
    unsigned run;           /* the run it belongs to */
    int override, latch;    /* what it assumed: the feed override, cycle exit pressed */
  } est;
  struct screen idle;       /* what the 2С42 screen shows before the first run */
  int cyr;                  /* Рус: Cyrillic keyboard mode */
  int64_t jog_step;
  /* the terminal */
  int focus;
  size_t ecur, etop, ltop;
  int ecol;                 /* the editor's view: first column shown (long lines scroll) */
  int help, help_top;
  int page;                 /* the parameters page is shown (in the listing's place) */
  int psel, pcol;           /* its selected item, its first column shown */
  int prows;                /* its rows per column, as last drawn */
  char find[INPUTMAX];         /* the last search */
  long hl_line;             /* the match shown, -1 none */
  int hl_col, hl_len;       /* its column and length in characters */
  int hl_show;              /* bring it into view at the next draw */
  struct {
    int kind;
    uint32_t b[INPUTMAX];
    int n, cur;
    int sel;                /* the pre-filled text is selected: typing replaces it */
    int before;             /* IN_INSERT: before the cursor's line */
    int reg;                /* IN_PARAM: the parameter */
    char prompt[640];
  } input;
  char log[LOGN][LOGW];
  int nlog;
  char msg[LOGW];           /* the message line */
  int msg_wait;             /* it says what the machine waits for */
  int quit;
  /* the dialect of the text; a machine on the neutral runner (the 2У22) */
  const struct dialect *dl;
  int lathe;                /* dl runs on the neutral runner: its panel, not the 2С42's */
  struct tmr *m;            /* its machine and run (tui_mrun.c), NULL none */
  int mpage;                /* the machine's page shown (DG, DI) */
};

/* ---- terminal restore on every exit path ---- */

static volatile sig_atomic_t got_sig;
static int curses_on;
static struct termios tty0;
static int tty_saved;
static char restore_seq[128];  /* rmkx, cnorm, rmcup: written by the fatal-signal handler */
static size_t restore_len;
static const int fatal_sigs[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
static struct sigaction old_fatal[5], old_quit[3];
static const int quit_sigs[] = {SIGINT, SIGTERM, SIGHUP};

static void on_quit_signal(int sig)
{
  got_sig = sig;
}

/* A crash: put the terminal back with async-signal-safe calls only, then
 * hand the signal to whoever had it (the default action, or a sanitizer). */
static void on_fatal_signal(int sig)
{
  if (tty_saved)
    tcsetattr(STDIN_FILENO, TCSANOW, &tty0);
  if (restore_len) {
    ssize_t w = write(STDOUT_FILENO, restore_seq, restore_len);
    (void)w;
  }
  for (size_t i = 0; i < sizeof fatal_sigs / sizeof fatal_sigs[0]; i++)
    if (fatal_sigs[i] == sig)
      sigaction(sig, &old_fatal[i], NULL);
  /* returning re-raises: a fault faults again, abort() raises again */
}

static void curses_off(void)
{
  if (curses_on) {
    curses_on = 0;
    endwin();
  }
}

static void add_restore(const char *cap)
{
  const char *s = tigetstr((char *)cap);
  if (!s || s == (char *)-1)
    return;
  size_t n = strlen(s);
  if (restore_len + n < sizeof restore_seq) {
    memcpy(restore_seq + restore_len, s, n);
    restore_len += n;
  }
}

static void signals_on(void)
{
  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sigemptyset(&sa.sa_mask);
  sa.sa_handler = on_quit_signal;   /* no SA_RESTART: poll() returns at once */
  for (int i = 0; i < 3; i++)
    sigaction(quit_sigs[i], &sa, &old_quit[i]);
  sa.sa_handler = on_fatal_signal;
  sa.sa_flags = SA_NODEFER;
  for (int i = 0; i < 5; i++)
    sigaction(fatal_sigs[i], &sa, &old_fatal[i]);
}

static void signals_off(void)
{
  for (int i = 0; i < 3; i++)
    sigaction(quit_sigs[i], &old_quit[i], NULL);
  for (int i = 0; i < 5; i++)
    sigaction(fatal_sigs[i], &old_fatal[i], NULL);
}

/* ---- messages ---- */

static void say(struct tui *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void say(struct tui *t, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(t->msg, sizeof t->msg, fmt, ap);
  va_end(ap);
  t->msg_wait = 0;
  if (t->nlog == LOGN) {
    memmove(t->log[0], t->log[1], sizeof t->log[0] * (LOGN - 1));
    t->nlog--;
  }
  snprintf(t->log[t->nlog++], LOGW, "%s", t->msg);
}

/* The message line only, not the log (hints that repeat at every wait). */
static void note(struct tui *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void note(struct tui *t, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(t->msg, sizeof t->msg, fmt, ap);
  va_end(ap);
  t->msg_wait = 0;
}

static const char *bname(int n, char buf[16])
{
  return diag_block(n, buf);
}

/* A block for messages: its number, or its line when it has none. */
static const char *blockname(int n, unsigned line, char buf[24])
{
  if (n > 0)
    snprintf(buf, 24, "N%d", n);
  else
    snprintf(buf, 24, "line %u", line);
  return buf;
}

/* Вихід з циклу was taken: the PP block that jumped, the block it went to. */
static void exit_taken(struct tui *t, int from_n, unsigned from_line, int to_n, unsigned to_line)
{
  char a[24], b[24];
  t->pp_seen = sess_pp_jumps(&t->s);
  say(t, "cycle exit: %s → %s", blockname(from_n, from_line, a), blockname(to_n, to_line, b));
}

/* ---- the check ---- */

/* Compile the text; keep the marks; with loud, every diagnostic goes to the
 * messages.  Returns the number of errors. */
static size_t check(struct tui *t, int loud)
{
  size_t n;
  char *src = tui_text_join(&t->text, &n);
  if (!src) {
    say(t, "out of memory");
    return 1;
  }
  struct program p;
  struct diag_list d;
  prog_init(&p);
  diag_init(&d, t->path ? t->path : "(new)");
  if (t->dl && t->dl->run != DIALECT_RUN_SESSION)
    t->dl->compile(src, n, &d, &p, t->o.plugins);
  else
    comp_program_with(src, n, &d, &p, t->o.plugins);
  free(t->mark);
  t->nmark = t->text.n;
  t->mark = calloc(t->nmark ? t->nmark : 1, 1);
  for (size_t i = 0; i < d.n; i++) {
    const struct diag *g = &d.v[i];
    int lvl = g->sev == DIAG_ERROR ? 2 : g->sev == DIAG_WARNING ? 1 : 0;
    if (t->mark && g->line >= 1 && g->line <= t->nmark && t->mark[g->line - 1] < lvl)
      t->mark[g->line - 1] = (unsigned char)lvl;
    if (loud) {
      char nb[16];
      say(t, "%u:%u %s %s: %s%s%s%s", g->line, g->col,
          g->sev == DIAG_ERROR ? "error" : g->sev == DIAG_WARNING ? "warning" : "note",
          bname(g->number, nb), g->msg, g->code ? " [" : "", g->code ? err_code(g->code) : "",
          g->code ? "]" : "");
    }
  }
  t->nerr = d.nerr;
  t->nwarn = d.nwarn;
  t->checked = 1;
  if (loud)
    say(t, "check: %zu error%s, %zu warning%s", d.nerr, d.nerr == 1 ? "" : "s", d.nwarn,
        d.nwarn == 1 ? "" : "s");
  size_t e = d.nerr;
  prog_free(&p);
  diag_free(&d);
  free(src);
  return e;
}

/* ---- the run ---- */

/* Register reg took v (in block n; how: 0 the program, 1 the restart, 2
 * the panel): first in the list of those that changed last. */
static void chg_add(struct tui *t, int reg, double v, int n, int how)
{
  int k = 0;
  while (k < t->nchg && t->chg[k].reg != reg)
    k++;
  if (k == t->nchg)
    k = t->nchg < NCHG ? t->nchg++ : NCHG - 1;
  memmove(&t->chg[1], &t->chg[0], (size_t)k * sizeof t->chg[0]);
  t->chg[0].reg = reg;
  t->chg[0].v = v;
  t->chg[0].n = n;
  t->chg[0].how = how;
}

static void on_row(void *ctx, const struct session *s, const struct sess_row *r)
{
  struct tui *t = ctx;
  /* a PP jump runs after its block's row: this row is the block it went to */
  if (sess_pp_jumps(s) != t->pp_seen && t->cur.valid)
    exit_taken(t, t->cur.n, t->cur.line, r->n, r->line);
  t->cur.valid = 1;
  memcpy(t->cur.from, r->start, sizeof t->cur.from);
  memcpy(t->cur.to, sess_positions(s), sizeof t->cur.to);
  t->cur.t0 = t->last_t;
  t->cur.t1 = r->t;
  t->cur.ts = t->cur.t0;
  t->cur.fs = 0;
  t->cur.feed = r->feed;
  t->cur.line = r->line;
  t->cur.n = r->n;
  t->osc = sess_oscillating(s);
  t->last_t = r->t;
  for (int i = 0; i < 114; i++) {
    double v = sess_reg(s, i);
    if (v == t->regs[i] || (isnan(v) && isnan(t->regs[i])))
      continue;
    t->regs[i] = v;
    chg_add(t, i, v, r->n, 0);
  }
}

static void on_warn(void *ctx, const struct session *s, const char *msg)
{
  struct tui *t = ctx;
  char nb[16];
  say(t, "%s: warning: %s", bname(sess_block_number(s), nb), msg);
}

static void on_log(void *ctx, const struct session *s, const char *msg)
{
  (void)s;
  say(ctx, "%s", msg);
}

static void est_stop(struct tui *t);

static void end_run(struct tui *t)
{
  est_stop(t);
  if (t->have_prog)
    prog_free(&t->prog);
  t->have_prog = 0;
  free(t->run_src);
  t->run_src = NULL;
  cycle_free(&t->cyc);
  t->run = R_IDLE;
  tmr_free(t->m);
  t->m = NULL;
}

/* The machine's own message for the run's error, on line 16 and below. */
static void show_error(struct tui *t)
{
  struct s42_error e;
  char nb[16];
  sess_error(&t->s, &e);
  sess_show_error(&t->s);
  say(t, "%u:%u error %s: %s [%s]", e.line, e.col, bname(e.number, nb), e.msg, err_code(e.code));
}

/* After a restart: the dialog area as the program's dialog left it before
 * the restart point (the G33 headings, each G27 line with the number its
 * G28 stored, now in the restored parameters), and the parameters the
 * state holds as "changed last".  The state keeps no screen buffer: the
 * program text and the parameters say what it held. */
static void restored(struct tui *t)
{
  struct session *s = &t->s;
  kp_restore_dialog(s);
  /* the first NCHG parameters that are not 0, R0 at the top */
  int regs[NCHG], n = 0;
  for (int i = 0; i < 114 && n < NCHG; i++)
    if (sess_reg(s, i) != 0)
      regs[n++] = i;
  t->nchg = 0;
  while (n > 0) {
    n--;
    chg_add(t, regs[n], sess_reg(s, regs[n]), sess_block_number(s), 1);
  }
}

static void start_run(struct tui *t)
{
  size_t n;
  char *src = tui_text_join(&t->text, &n);
  if (!src) {
    say(t, "out of memory");
    return;
  }
  if (check(t, 0)) {
    check(t, 1);
    say(t, "the program has %zu error%s: the cycle does not start", t->nerr, t->nerr == 1 ? "" : "s");
    free(src);
    return;
  }
  end_run(t);
  struct diag_list d;
  prog_init(&t->prog);
  diag_init(&d, t->path ? t->path : "(new)");
  int bad = comp_program_with(src, n, &d, &t->prog, t->o.plugins);
  diag_free(&d);
  t->have_prog = 1;
  if (bad) {   /* check() said it compiles; only memory could fail here */
    say(t, "the program does not compile: the cycle does not start");
    free(src);
    end_run(t);
    return;
  }
  t->run_src = src;
  t->run_gen = t->gen;
  struct sess_config cfg;
  memset(&cfg, 0, sizeof cfg);
  cfg.en = t->o.en;
  cfg.max_blocks = t->o.max_blocks;
  cfg.travel = t->o.travel;
  cfg.plugins = t->o.plugins;
  cfg.sink.ctx = t;
  cfg.sink.row = on_row;
  cfg.sink.warn = on_warn;
  cfg.sink.log = on_log;
  cfg.start_all = 1;   /* one block per sess_run: the loop paces them */
  cfg.yield_all = 1;   /* a row for every block, for the listing */
  char why[300], nb[16];
  size_t fb = 0;
  int setup = cycle_setup(&t->cyc, &t->s, &t->prog, src, n, &cfg, t->path, t->o.state, t->restart_pending, why,
                          sizeof why, &fb);
  sess_set_cyrillic(&t->s, t->cyr);
  if (setup == CYCLE_PLUGIN) {   /* --tool missing or bad, as s42 run says */
    const struct prog_block *b = &t->prog.blocks[fb];
    say(t, "%s; %u:%u %s needs it: the cycle does not start", why, b->line, b->col,
        bname(b->number ? (int)b->number : -1, nb));
    end_run(t);
    return;
  }
  if (setup == CYCLE_OOM) {
    say(t, "out of memory: the cycle does not start");
    end_run(t);
    return;
  }
  t->run = R_RUN;
  t->osc = 0;
  t->held = 0;
  t->ovr_held = 0;
  sess_set_single(&t->s, t->single);
  sess_set_break(&t->s, t->brk);
  t->stopped_mid = 0;
  t->cur.valid = 0;
  t->nchg = 0;
  if (setup == CYCLE_NO_NAME && t->cyc.has_m15)
    say(t, "M15: %s", why);
  if (t->restart_pending) {
    t->restart_pending = 0;
    char err[160];
    if (cycle_restart(&t->cyc, err, sizeof err)) {
      t->run = R_DONE;
      show_error(t);
      return;
    }
    say(t, "restart: the cycle goes on at the M15 block %s", bname(sess_block_number(&t->s), nb));
    restored(t);
  }
  t->runs++;
  t->pp_seen = sess_pp_jumps(&t->s);
  if (t->override != 100 && sess_override(&t->s, t->override) == 0)
    say(t, "feed override %d %%", t->override);
  memcpy(t->regs, sess_regs(&t->s), sizeof t->regs);
  t->last_t = t->wait_t = sess_time(&t->s);
  pace_start(&t->pace, sess_time(&t->s));
  say(t, "Пуск: the cycle starts");
}

/* The wait has just ended (a key): the clock goes on from here, so the
 * time the operator took is not run off at full speed afterwards. */
static void resumed(struct tui *t)
{
  pace_start(&t->pace, t->wait_t);
  t->held = 0;
}

static const char *wait_hint(const struct session *s)
{
  switch (s->wait) {
  case W_ANSWER: return "type the number, then ПС (Enter)";
  case W_PUSK: return "Пуск (F5 or g) continues";
  case W_PS: return "ПС (Enter), then Пуск";
  case W_TEACH: return "jog the junior axis, then ПС (Enter)";
  case W_SECTION: return "jog the table (x X) and A (a A) to section 2, then Пуск (F5 or g)";
  case W_FEED: return "the feed override is at 0 %: raise it (>)";
  case W_BLOCK: return s->single ? "single block: Пуск (F5 or g) starts it" : "breakpoint: Пуск (F5 or g) starts it";
  default: return "";
  }
}

/* the neutral runner's panel (below, with the panel keys) */
static int lathe_advance(struct tui *t);
static void lathe_pusk(struct tui *t);
static void lathe_stop(struct tui *t);

/* Run blocks while they are due.  Returns the poll timeout, ms (-1 idle). */
static int advance(struct tui *t)
{
  if (t->lathe)
    return lathe_advance(t);
  if (t->run != R_RUN || t->held || t->ovr_held || t->s.state == SE_WAIT)
    return -1;
  struct timespec t0, now;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  for (unsigned i = 0;; i++) {
    if (!t->fast && t->cur.valid) {
      double ahead = pace_ahead(&t->pace, t->cur.t1);
      if (ahead > 0) {
        int ms = (int)ceil(ahead * 1000);
        return ms < 40 ? ms : 40;   /* redraw the motion meanwhile */
      }
    }
    if ((i & 63) == 63) {
      clock_gettime(CLOCK_MONOTONIC, &now);
      if ((double)(now.tv_sec - t0.tv_sec) + (double)(now.tv_nsec - t0.tv_nsec) / 1e9 > 0.02)
        return 0;   /* keep the keys and the screen alive */
    }
    char nb[16];
    enum sess_ev ev = sess_run(&t->s);
    switch (ev) {
    case SE_START:
      {
        int saved = cycle_m15(&t->cyc);
        if (saved < 0) {   /* as s42 run: the cycle ends there with E-STATE */
          t->run = R_DONE;
          show_error(t);
          return -1;
        }
        if (saved && t->cyc.saves == 1)   /* once in the log; a loop would fill it */
          say(t, "%s: M15 restart point saved in %s", bname(sess_block_number(&t->s), nb), t->cyc.state_path);
        else if (saved)
          note(t, "%s: M15 restart point saved in %s (%lu)", bname(sess_block_number(&t->s), nb), t->cyc.state_path,
               t->cyc.saves);
      }
      continue;
    case SE_WAIT:
      t->wait_t = sess_time(&t->s);
      note(t, "%s waits: %s", bname(sess_block_number(&t->s), nb), wait_hint(&t->s));
      t->msg_wait = 1;
      return -1;
    case SE_END:
      t->run = R_DONE;
      say(t, "the program ended (M2): %llu blocks, %.2f s", (unsigned long long)sess_blocks(&t->s), sess_time(&t->s));
      return -1;
    case SE_STOPPED:
      t->run = R_DONE;
      say(t, "the cycle was stopped");
      return -1;
    default:
      t->run = R_DONE;
      show_error(t);
      return -1;
    }
  }
}

/* ---- panel keys ---- */

/* Before a key that may run a plugin for seconds (a tooth search goes on
 * at Пуск): the sources (the Modbus server) show the cycle running, not
 * the wait the key ends, while this thread computes. */
static void sources_busy(struct tui *t)
{
  for (int i = 0; i < t->nsrc; i++)
    if (t->src[i].busy)
      t->src[i].busy(t->src[i].ctx, t);
}

static void press_pusk(struct tui *t)
{
  if (t->lathe) {
    lathe_pusk(t);
    return;
  }
  if (t->run != R_RUN) {
    start_run(t);
    return;
  }
  if (t->held) {
    t->held = 0;
    if (t->ovr_held) {
      say(t, "Пуск: the feed override is at 0 %%: the motion goes on when it is raised (>)");
      return;
    }
    pace_hold(&t->pace, 0);
    say(t, "Пуск: the motion goes on");
    return;
  }
  if (t->ovr_held) {
    say(t, "the feed override is at 0 %%: raise it (>) and the motion goes on");
    return;
  }
  if (t->s.state == SE_WAIT)
    sources_busy(t);
  if (t->s.state == SE_WAIT && sess_key_pusk(&t->s) == 0) {
    resumed(t);
    return;
  }
  if (t->s.state == SE_WAIT)
    say(t, "Пуск does not fit here: %s", wait_hint(&t->s));
  else
    say(t, "the cycle is running");
}

static void press_stop(struct tui *t)
{
  if (t->lathe) {
    lathe_stop(t);
    return;
  }
  if (t->run != R_RUN) {
    say(t, "Стоп: no cycle is running");
    return;
  }
  if (!t->held && t->s.state != SE_WAIT) {
    pace_hold(&t->pace, 1);
    t->held = 1;
    say(t, "Стоп: feed hold -- Пуск goes on, Стоп again stops the cycle");
    return;
  }
  sess_key_stop(&t->s);
  t->stopped_mid = t->held;   /* the pace stays held: the readouts keep the stopping point */
  t->held = 0;
  t->ovr_held = 0;
  t->run = R_DONE;
  say(t, "Стоп: the cycle was stopped");
}

static void press_ps(struct tui *t)
{
  if (t->lathe) {
    say(t, "ПС: this panel has no entry that waits for it");
    return;
  }
  if (t->run != R_RUN || t->s.state != SE_WAIT) {
    say(t, "ПС: the machine does not wait for it");
    return;
  }
  if (t->s.wait == W_ANSWER) {
    double v = screen_field_value(&t->s.scr);
    sess_answer(&t->s, (long long)llround(v));
    if (t->s.state != SE_WAIT)
      resumed(t);
    return;
  }
  sources_busy(t);
  if (sess_key_ps(&t->s) == 0)
    return;
  say(t, "ПС does not fit here: %s", wait_hint(&t->s));
}

static void press_exit(struct tui *t)
{
  if (t->lathe) {
    say(t, "Вихід з циклу: the %s has no cycle exit (r resets, Стоп stops)", t->dl->controller);
    return;
  }
  if (t->run != R_RUN) {
    say(t, "Вихід з циклу: no cycle is running");
    return;
  }
  sess_key_exit(&t->s);
  say(t, "Вихід з циклу: the next PP jump will be taken");
}

static void press_rus(struct tui *t)
{
  t->cyr = !t->cyr;
  t->idle.cyr = t->cyr;
  if (t->run != R_IDLE)
    sess_set_cyrillic(&t->s, t->cyr);
}

/* The share of the current block's motion made at simulated time now. */
static double cur_frac(const struct tui *t, double now)
{
  if (now >= t->cur.t1 || t->cur.t1 <= t->cur.ts)
    return 1;
  if (now <= t->cur.ts)
    return t->cur.fs;
  return t->cur.fs + (1 - t->cur.fs) * (now - t->cur.ts) / (t->cur.t1 - t->cur.ts);
}

/* The switch turned while a block's move is under way: the rest of it goes
 * at the new speed at once (the machine's time follows); at 0 % the move
 * stands where it is until the switch leaves 0. */
static void override_in_move(struct tui *t)
{
  if ((t->fast && !t->ovr_held) || !t->cur.valid || t->s.state == SE_WAIT)
    return;   /* fast: the block is done before the switch can turn, unless 0 % holds it */
  double now = pace_now(&t->pace);
  if (now >= t->cur.t1 || !sess_in_move(&t->s, now))
    return;
  if (sess_override_pct(&t->s) == 0) {
    t->ovr_held = 1;
    pace_hold(&t->pace, 1);
    return;
  }
  double f = cur_frac(t, now);
  double d = sess_override_at(&t->s, now);
  t->cur.fs = f;
  t->cur.ts = now;
  t->cur.t1 += d;
  t->last_t += d;
  t->cur.feed = sess_move_feed(&t->s);
  if (t->ovr_held) {
    t->ovr_held = 0;
    if (!t->held)
      pace_hold(&t->pace, 0);
  }
}

static void set_override(struct tui *t, int pct)
{
  if (pct < 0)
    pct = 0;
  if (pct > 150)
    pct = 150;
  if (t->run == R_RUN) {
    int held = t->s.state == SE_WAIT && t->s.wait == W_FEED;
    if (sess_override(&t->s, pct))
      return;   /* M25: the screen says so */
    if (held && t->s.state != SE_WAIT)
      resumed(t);   /* the move held at 0 % goes */
    else
      override_in_move(t);
  }
  t->override = pct;
  say(t, "feed override %d %%%s", pct, t->ovr_held ? ": the move stands" : "");
}

static void set_single(struct tui *t, int on)
{
  t->single = on;
  if (t->run == R_RUN)
    sess_set_single(&t->s, on);
  say(t, on ? "single block (П): each block waits for Пуск before it starts" : "automatic (АВТ): blocks run on");
}

/* The breakpoint: a block number, or empty / 0 for none. */
static void set_break(struct tui *t, const char *s)
{
  while (*s == ' ')
    s++;
  if (*s == 'N' || *s == 'n')
    s++;
  char *end;
  errno = 0;
  long n = *s ? strtol(s, &end, 10) : 0;
  if (*s) {
    while (*end == ' ')
      end++;
  }
  if (*s && (*end || errno || n < 0 || n > 999)) {
    say(t, "the breakpoint is a block number 1..999 (empty or 0: none)");
    return;
  }
  int have = 0;
  for (size_t b = 0; n > 0 && t->have_prog && b < t->prog.nblocks; b++)
    have |= t->prog.blocks[b].number == n;
  t->brk = (int)n;
  if (t->run == R_RUN)
    sess_set_break(&t->s, t->brk);
  char nb[16];
  if (!n)
    say(t, "no breakpoint");
  else if (t->have_prog && !have)
    say(t, "breakpoint at N%ld: warning: the program has no such block", n);
  else
    say(t, "breakpoint at %s: it waits for Пуск before it starts (Пуск runs to it)", bname((int)n, nb));
}

static void jog(struct tui *t, int axis, int sign)
{
  static const char names[] = "XYZA";
  int64_t d = sign * t->jog_step;
  if (t->run == R_RUN && t->s.state == SE_WAIT && t->s.wait == W_SECTION) {
    sess_section(&t->s, axis, d);   /* the tooth search's move to section 2 */
    return;
  }
  if (t->run == R_RUN && t->s.state == SE_WAIT &&
      (t->s.wait == W_PUSK || t->s.wait == W_PS || t->s.wait == W_TEACH)) {
    sess_jog(&t->s, axis, d);
    return;
  }
  if (t->run == R_RUN && t->s.state != SE_WAIT) {
    if (sess_correct(&t->s, axis, d) == 0)
      say(t, "correction %c %+lld", names[axis], (long long)d);
    return;
  }
  say(t, "jogs move the machine in manual mode (G20), in M19 teach-in, or as corrections (M22) while the cycle runs");
}

/* ---- the input line ---- */

/* init: the text it starts with; a name (open, save as, a parameter's
 * value) comes selected, so that typing replaces it as in a form's field */
static void input_open(struct tui *t, int kind, const char *prompt, const char *init)
{
  t->input.kind = kind;
  snprintf(t->input.prompt, sizeof t->input.prompt, "%s", prompt);
  t->input.n = init ? screen_decode(init, t->input.b, INPUTMAX) : 0;
  t->input.cur = t->input.n;
  t->input.sel = t->input.n > 0 && (kind == IN_OPEN || kind == IN_SAVEAS || kind == IN_PARAM || kind == IN_FIND ||
                              kind == IN_GOTO || kind == IN_BREAK);
}

/* The input line as UTF-8 (malloc'd). */
static char *input_text(const struct tui *t)
{
  char *s = malloc((size_t)t->input.n * 4 + 1), *p = s;
  if (!s)
    return NULL;
  for (int i = 0; i < t->input.n; i++)
    p += tui_utf8(t->input.b[i], p);
  *p = 0;
  return s;
}

static int can_edit(struct tui *t)
{
  if (t->run == R_RUN) {
    say(t, "the cycle is running: stop it (Стоп twice) before changing the program");
    return 0;
  }
  return 1;
}

/* The text is what was read or saved last exactly when its bytes are. */
static void set_saved(struct tui *t)
{
  size_t n;
  char *b = tui_text_join(&t->text, &n);
  if (!b)
    return;
  t->saved_hash = tui_hash(b, n);
  t->saved_len = n;
  free(b);
  t->dirty = 0;
}

static void edited(struct tui *t)
{
  size_t n;
  char *b = tui_text_join(&t->text, &n);
  t->dirty = !b || n != t->saved_len || tui_hash(b, n) != t->saved_hash;
  free(b);
  t->gen++;
  t->hl_line = -1;
  if (t->ecur >= t->text.n && t->text.n)
    t->ecur = t->text.n - 1;
  check(t, 0);
}

static void set_dialect(struct tui *t, const char *path);
static void lathe_opened(struct tui *t);

/* A name that is not there yet: an empty text of that name, which the
 * first save creates (as an editor opens a new file). */
static int new_file(struct tui *t, const char *path)
{
  char *p = strdup(path);
  if (!p) {
    say(t, "out of memory");
    return -1;
  }
  tui_text_free(&t->text);
  free(t->path);
  t->path = p;
  memset(&t->disk, 0, sizeof t->disk);
  set_saved(t);
  t->gen++;
  t->ecur = t->etop = t->ltop = 0;
  t->ecol = 0;
  t->hl_line = -1;
  if (t->run != R_RUN)
    end_run(t);
  set_dialect(t, path);
  check(t, 0);
  say(t, "%s: a new file (the first save creates it)", path);
  return 0;
}

/* No file at path, but its directory is there: a new file can be made. */
static int creatable(const char *path)
{
  struct stat st;
  if (stat(path, &st) == 0 || errno != ENOENT || lstat(path, &st) == 0)
    return 0;
  char *d = strdup(path);
  if (!d)
    return 0;
  char *slash = strrchr(d, '/');
  int ok;
  if (!slash)
    ok = 1;
  else {
    slash[slash == d ? 1 : 0] = 0;
    ok = stat(d, &st) == 0 && S_ISDIR(st.st_mode);
  }
  free(d);
  return ok;
}

static int load_file(struct tui *t, const char *path)
{
  char err[512];
  if (creatable(path))
    return new_file(t, path);
  struct tui_disk d;
  if (tui_text_load(&t->text, path, &d, err, sizeof err)) {
    say(t, "cannot open %s", err);
    return -1;
  }
  char *p = strdup(path);
  if (!p) {
    say(t, "out of memory");
    return -1;
  }
  free(t->path);
  t->path = p;
  t->disk = d;
  set_saved(t);
  t->gen++;
  t->ecur = t->etop = t->ltop = 0;
  t->ecol = 0;
  t->hl_line = -1;
  if (t->run != R_RUN)
    end_run(t);
  set_dialect(t, path);
  size_t e = check(t, 0);
  lathe_opened(t);
  say(t, "%s: %zu lines; %zu error%s", path, t->text.n, e, e == 1 ? "" : "s");
  return 0;
}

static void save_now(struct tui *t, const char *path)
{
  char err[512];
  struct tui_disk d;
  if (tui_text_save(&t->text, path, &d, err, sizeof err)) {
    say(t, "not saved: %s (the file on disk is as it was)", err);
    return;
  }
  if (path != t->path) {
    char *p = strdup(path);
    if (p) {
      free(t->path);
      t->path = p;
    }
  }
  t->disk = d;
  set_saved(t);
  say(t, "saved %s (%zu line%s)", t->path, t->text.n, t->text.n == 1 ? "" : "s");
}

/* A save never overwrites silently what it did not read: the file changed
 * on disk since it was read (another editor, a second s42 tui), or save as
 * names another file that is there. */
static void save(struct tui *t, const char *path)
{
  int same = t->path && (path == t->path || strcmp(path, t->path) == 0);
  char q[600];
  struct stat st;
  if (same && tui_disk_changed(path, &t->disk)) {
    snprintf(q, sizeof q, "%s %s since it was read: overwrite it? (y/n) ", path,
             t->disk.exists && stat(path, &st) != 0 ? "was removed" : "changed on disk");
  } else if (!same && stat(path, &st) == 0) {
    snprintf(q, sizeof q, "%s exists: replace it? (y/n) ", path);
  } else {
    save_now(t, path);
    return;
  }
  char *p = strdup(path);
  if (!p) {
    say(t, "out of memory");
    return;
  }
  free(t->save_to);
  t->save_to = p;
  input_open(t, IN_OVERWRITE, q, NULL);
}

static void set_param(struct tui *t, int reg, const char *val);
static void find(struct tui *t, int dir);
static void go_to(struct tui *t, const char *s);

static void input_commit(struct tui *t)
{
  int kind = t->input.kind;
  char *s = input_text(t);
  t->input.kind = IN_NONE;
  if (!s) {
    say(t, "out of memory");
    return;
  }
  switch (kind) {
  case IN_INSERT: {
    size_t at = !t->text.n || t->input.before ? t->ecur : t->ecur + 1;
    if (tui_text_insert(&t->text, at, s) == 0) {
      t->ecur = at;
      edited(t);
      say(t, "line %zu inserted", at + 1);
    }
    break;
  }
  case IN_REPLACE:
    if (tui_text_replace(&t->text, t->ecur, s) == 0) {
      edited(t);
      say(t, "line %zu replaced", t->ecur + 1);
    }
    break;
  case IN_OPEN:
    if (*s)
      load_file(t, s);
    break;
  case IN_SAVEAS:
    if (*s)
      save(t, s);
    break;
  case IN_FIND:
    if (*s) {
      snprintf(t->find, sizeof t->find, "%s", s);
      find(t, 1);
    }
    break;
  case IN_GOTO:
    go_to(t, s);
    break;
  case IN_PARAM:
    set_param(t, t->input.reg, s);
    break;
  case IN_BREAK:
    set_break(t, s);
    break;
  default:
    break;
  }
  free(s);
}

static void input_key(struct tui *t, int fn, wint_t c)
{
  if (t->input.kind == IN_QUITRUN) {
    /* q again quits (asking about unsaved changes next); any other key
     * closes the question and the cycle goes on */
    int again = (!fn && (c == 'q' || c == 'Q')) || (fn && c == KEY_F(10));
    t->input.kind = IN_NONE;
    if (!again) {
      say(t, "the cycle goes on");
      return;
    }
    if (t->dirty)
      input_open(t, IN_QUIT, "the text has unsaved changes: quit anyway? (y/n) ", NULL);
    else
      t->quit = 1;
    return;
  }
  if (t->input.kind == IN_QUIT || t->input.kind == IN_OPENASK || t->input.kind == IN_OVERWRITE) {
    int yes = !fn && (c == 'y' || c == 'Y');
    int kind = t->input.kind;
    t->input.kind = IN_NONE;
    if (!yes) {
      say(t, kind == IN_OVERWRITE ? "not saved" : "cancelled");
      return;
    }
    if (kind == IN_QUIT) {
      t->quit = 1;
    } else if (kind == IN_OVERWRITE) {
      char *p = t->save_to;
      t->save_to = NULL;
      if (p)
        save_now(t, p);
      free(p);
    } else {
      input_open(t, IN_OPEN, "open file: ", t->path);
    }
    return;
  }
  int sel = t->input.sel;
  t->input.sel = 0;
  if (fn) {
    switch (c) {
    case KEY_LEFT: if (t->input.cur > 0 && !sel) t->input.cur--; return;
    case KEY_RIGHT: if (t->input.cur < t->input.n) t->input.cur++; return;
    case KEY_HOME: t->input.cur = 0; return;
    case KEY_END: t->input.cur = t->input.n; return;
    case KEY_BACKSPACE:
      c = 127;
      break;
    case KEY_DC:
      if (sel) {
        t->input.n = t->input.cur = 0;
      } else if (t->input.cur < t->input.n) {
        memmove(&t->input.b[t->input.cur], &t->input.b[t->input.cur + 1], sizeof t->input.b[0] * (size_t)(t->input.n - t->input.cur - 1));
        t->input.n--;
      }
      return;
    case KEY_ENTER:
      input_commit(t);
      return;
    case KEY_F(4):
      t->input.sel = sel;
      press_rus(t);
      return;
    default:
      t->input.sel = sel;
      return;
    }
  }
  if (c == 127 || c == 8) {
    if (sel) {
      t->input.n = t->input.cur = 0;   /* a selected name goes at once */
    } else if (t->input.cur > 0) {
      memmove(&t->input.b[t->input.cur - 1], &t->input.b[t->input.cur], sizeof t->input.b[0] * (size_t)(t->input.n - t->input.cur));
      t->input.n--;
      t->input.cur--;
    }
    return;
  }
  if (c == '\r' || c == '\n') {
    input_commit(t);
    return;
  }
  if (c == 27 || c == 7) {   /* Esc, Ctrl-G */
    t->input.kind = IN_NONE;
    say(t, "cancelled");
    return;
  }
  if (c == 18) {             /* Ctrl-R: Рус */
    t->input.sel = sel;
    press_rus(t);
    return;
  }
  if (c == 21) {             /* Ctrl-U: clear */
    t->input.n = t->input.cur = 0;
    return;
  }
  if (c < 0x20 || c == 0x7F || (c >= 0x80 && c < 0xA0)) {
    t->input.sel = sel;
    return;
  }
  if (c >= 0x80 && !t->utf8) {
    t->input.sel = sel;
    say(t, "this terminal is not UTF-8: type Cyrillic in Рус mode (F4)");
    return;
  }
  uint32_t ch = (uint32_t)c;
  int enc = t->input.kind == IN_INSERT || t->input.kind == IN_REPLACE || t->input.kind == IN_FIND;
  if (t->cyr && enc)
    ch = tui_cyr_key(ch);
  if (sel)
    t->input.n = t->input.cur = 0;   /* typing replaces the selected text */
  if (t->input.n >= INPUTMAX)
    return;
  memmove(&t->input.b[t->input.cur + 1], &t->input.b[t->input.cur], sizeof t->input.b[0] * (size_t)(t->input.n - t->input.cur));
  t->input.b[t->input.cur++] = ch;
  t->input.n++;
}

/* ---- keys ---- */

static void ask_quit(struct tui *t)
{
  if (t->run == R_RUN)
    input_open(t, IN_QUITRUN, "a cycle is running: q again to quit, any other key goes on ", NULL);
  else if (t->dirty)
    input_open(t, IN_QUIT, "the text has unsaved changes: quit anyway? (y/n) ", NULL);
  else
    t->quit = 1;
}

static void ask_open(struct tui *t)
{
  if (!can_edit(t))
    return;
  if (t->dirty)
    input_open(t, IN_OPENASK, "the text has unsaved changes: open another file anyway? (y/n) ", NULL);
  else
    input_open(t, IN_OPEN, "open file: ", t->path);
}

static void ask_save(struct tui *t, int as)
{
  if (as || !t->path)
    input_open(t, IN_SAVEAS, "save as: ", t->path);
  else
    save(t, t->path);
}

/* ---- the editor: search, go to a line, the view across long lines ---- */

/* Characters (code points) in the first `bytes` bytes of a UTF-8 line. */
static int u8cols(const char *s, size_t bytes)
{
  int n = 0;
  for (size_t i = 0; i < bytes && s[i]; i++)
    n += ((unsigned char)s[i] & 0xC0) != 0x80;
  return n;
}

/* The next (dir 1) or previous (-1) line holding the last search, from the
 * cursor's; the cursor goes there and the view scrolls to show it. */
static void find(struct tui *t, int dir)
{
  if (!t->find[0]) {
    say(t, "no search yet: / searches");
    return;
  }
  size_t from = dir > 0 ? t->ecur + 1 : (t->ecur ? t->ecur - 1 : t->text.n);
  if (from >= t->text.n)
    from = dir > 0 ? 0 : (t->text.n ? t->text.n - 1 : 0);
  size_t byte;
  int wrapped;
  long i = tui_text_find(&t->text, from, dir, t->find, &byte, &wrapped);
  if (i < 0) {
    t->hl_line = -1;
    say(t, "not found: %s", t->find);
    return;
  }
  t->ecur = (size_t)i;
  t->hl_line = i;
  t->hl_col = u8cols(t->text.line[i], byte);
  t->hl_len = u8cols(t->find, strlen(t->find));
  t->hl_show = 1;
  t->focus = F_EDIT;
  if (wrapped)
    say(t, "%s: line %ld (the search went on from the %s)", t->find, i + 1, dir > 0 ? "top" : "bottom");
  else
    say(t, "%s: line %ld", t->find, i + 1);
}

static void go_to(struct tui *t, const char *s)
{
  char *end;
  errno = 0;
  long n = strtol(s, &end, 10);
  while (*end == ' ')
    end++;
  if (!*s || *end || errno || n < 1) {
    say(t, "go to line: '%s' is not a line number", s);
    return;
  }
  if (!t->text.n) {
    say(t, "the text is empty");
    return;
  }
  if ((size_t)n > t->text.n) {
    say(t, "the text has %zu lines: the cursor goes to the last", t->text.n);
    n = (long)t->text.n;
  }
  t->ecur = (size_t)n - 1;
  t->ecol = 0;
}

/* ---- the parameters page ---- */

/* Item i of the page: R0-R113, D1, TK, UG, F, then each array's pointer
 * and length and its 15 cells.  Its text; *reg the register it sets from
 * the panel, or -1 when it is read-only. */
static void pitem(const struct tui *t, int i, char *b, size_t n, int *reg)
{
  const struct vm *vm = t->run != R_IDLE ? sess_vm(&t->s) : NULL;
  *reg = -1;
  if (i < 114) {
    *reg = i;
    snprintf(b, n, "R%-4d%14.10g", i, vm ? vm->reg[i] : 0.0);
    return;
  }
  if (i < 118) {
    static const char *const name[4] = {"D1", "TK", "UG", "F"};
    if (i == 114)
      *reg = REG_D1;
    snprintf(b, n, "%-5s%14.10g", name[i - 114], vm ? vm->reg[i] : 0.0);
    return;
  }
  int k = (i - 118) / (1 + KP_CELLS), c = (i - 118) % (1 + KP_CELLS) - 1;
  const struct vm_array *a = vm ? &vm->arr[k] : NULL;
  if (c < 0)
    snprintf(b, n, "array %d: ptr %d len %d", k + 1, a ? a->ptr : 0, a ? a->len : 0);
  else
    snprintf(b, n, "%c%-2d %15.10g", a && a->ptr == c ? '>' : ' ', c, a ? a->cell[c] : 0.0);
}

static void page_open(struct tui *t)
{
  if (t->lathe) {   /* the machine's own pages, in turn */
    int n = t->m ? tmr_npages(t->m) : 1;
    t->mpage = (t->mpage + 1) % n;
    return;
  }
  if (t->focus == F_PARAMS) {
    t->page = 0;
    t->focus = F_PANEL;
    return;
  }
  t->page = 1;
  t->focus = F_PARAMS;
  note(t, "parameters: arrows choose, = sets one (while the machine waits or in a feed hold), p closes");
}

/* The operator sets a parameter: only when no block is under way -- the
 * machine waits, or a feed hold stopped it -- and through the session,
 * journaled as a dialog answer is. */
static void set_param(struct tui *t, int reg, const char *val)
{
  char name[8], *end;
  snprintf(name, sizeof name, reg == REG_D1 ? "D1" : "R%d", reg);
  errno = 0;
  double v = strtod(val, &end);
  while (*end == ' ')
    end++;
  if (!*val || *end || errno == ERANGE) {
    say(t, "%s: '%s' is not a number: not set", name, val);
    return;
  }
  if (t->run == R_IDLE) {
    say(t, "%s: not set: no cycle is on (the parameters are 0 when Пуск starts one)", name);
    return;
  }
  if (t->run == R_DONE) {
    say(t, "%s: not set: the cycle has ended (the next Пуск starts with every parameter at 0)", name);
    return;
  }
  if (!t->held && t->s.state != SE_WAIT) {
    say(t, "%s: not set: a block is running (Стоп holds the feed, then set it)", name);
    return;
  }
  char why[200], nb[16];
  if (sess_set_param(&t->s, reg, v, why, sizeof why)) {
    say(t, "%s: not set: %s", name, why);
    return;
  }
  if (reg < 114) {
    t->regs[reg] = v;
    chg_add(t, reg, v, sess_block_number(&t->s), 2);
  }
  say(t, "%s = %.10g, set from the panel at %s", name, v, bname(sess_block_number(&t->s), nb));
}

/* Keys while the page has the focus (1 taken); the rest go to the panel,
 * so that digits and Enter still answer a dialog. */
static int page_key(struct tui *t, int fn, wint_t c)
{
  int *p = &t->psel, rows = t->prows > 0 ? t->prows : 1;
  if (fn) {
    switch (c) {
    case KEY_UP: if (*p > 0) (*p)--; return 1;
    case KEY_DOWN: if (*p + 1 < NPITEM) (*p)++; return 1;
    case KEY_LEFT: *p = *p >= rows ? *p - rows : 0; return 1;
    case KEY_RIGHT: *p = *p + rows < NPITEM ? *p + rows : NPITEM - 1; return 1;
    case KEY_PPAGE: *p = *p >= rows ? *p - rows : 0; return 1;
    case KEY_NPAGE: *p = *p + rows < NPITEM ? *p + rows : NPITEM - 1; return 1;
    case KEY_HOME: *p = 0; return 1;
    case KEY_END: *p = NPITEM - 1; return 1;
    default: return 0;
    }
  }
  if (c == 27 || c == 'p') {
    page_open(t);   /* closes it */
    return 1;
  }
  if (c == '=') {   /* Enter stays ПС: a dialog goes on with the page open */
    char b[64], pr[32];
    int reg;
    pitem(t, *p, b, sizeof b, &reg);
    if (reg < 0) {
      say(t, *p >= 115 && *p <= 116 ? "TK and UG are read-only: a tooth search with M10 sets them"
             : "read-only: the program sets it");
      return 1;
    }
    snprintf(pr, sizeof pr, reg == REG_D1 ? "set D1 = " : "set R%d = ", reg);
    char v[40];
    snprintf(v, sizeof v, "%.10g", t->run != R_IDLE ? sess_reg(&t->s, reg) : 0.0);
    input_open(t, IN_PARAM, pr, v);
    t->input.reg = reg;
    return 1;
  }
  return 0;
}

static void edit_key(struct tui *t, int fn, wint_t c)
{
  size_t n = t->text.n;
  if (fn) {
    switch (c) {
    case KEY_UP: if (t->ecur > 0) t->ecur--; return;
    case KEY_DOWN: if (t->ecur + 1 < n) t->ecur++; return;
    case KEY_PPAGE: t->ecur = t->ecur > 10 ? t->ecur - 10 : 0; return;
    case KEY_NPAGE: t->ecur = t->ecur + 10 < n ? t->ecur + 10 : (n ? n - 1 : 0); return;
    case KEY_HOME: t->ecur = 0; return;
    case KEY_END: t->ecur = n ? n - 1 : 0; return;
    case KEY_LEFT: t->ecol = t->ecol > 8 ? t->ecol - 8 : 0; return;   /* the view across long lines */
    case KEY_RIGHT: t->ecol += 8; return;   /* drawing stops it at the longest line */
    case KEY_IC: c = 'i'; break;
    case KEY_DC: c = 'd'; break;
    case KEY_ENTER: c = 'e'; break;
    default: return;
    }
  }
  switch (c) {
  case 'i':
  case 'I':
    if (can_edit(t)) {
      char p[48];
      snprintf(p, sizeof p, "insert %s line %zu: ", c == 'I' ? "before" : "after", t->ecur + 1);
      input_open(t, IN_INSERT, t->text.n ? p : "new block: ", NULL);
      t->input.before = c == 'I';
    }
    return;
  case 'e':
  case '\r':
  case '\n':
    if (!n) {
      say(t, "the text is empty: i inserts a block");
      return;
    }
    if (can_edit(t)) {
      char p[40];
      snprintf(p, sizeof p, "line %zu: ", t->ecur + 1);
      input_open(t, IN_REPLACE, p, t->text.line[t->ecur]);
    }
    return;
  case 'd':
    if (n && can_edit(t) && tui_text_delete(&t->text, t->ecur) == 0) {
      edited(t);
      say(t, "line %zu deleted (u brings it back)", t->ecur + 1);
    }
    return;
  case 'u':
    if (can_edit(t)) {
      if (tui_text_undo(&t->text)) {
        say(t, "nothing to undo");
      } else {
        edited(t);
        say(t, "undone");
      }
    }
    return;
  case 'c': check(t, 1); return;
  case 'w': ask_save(t, 0); return;
  case 'W': ask_save(t, 1); return;
  case 'o': ask_open(t); return;
  case 'q': ask_quit(t); return;
  case 'k': if (t->ecur > 0) t->ecur--; return;
  case 'j': if (t->ecur + 1 < n) t->ecur++; return;
  case '/': input_open(t, IN_FIND, "search: ", t->find); return;
  case 'n': find(t, 1); return;
  case 'N': find(t, -1); return;
  case ':': input_open(t, IN_GOTO, "go to line: ", NULL); return;
  case 'p': page_open(t); return;
  default: return;
  }
}

/* ---- the neutral runner's panel (the 2У22): the run, the keys ---- */

/* The dialect of a file: --dialect's, else its extension's. */
static void set_dialect(struct tui *t, const char *path)
{
  t->dl = t->o.dialect ? t->o.dialect : path ? dialect_by_file(path) : dialect_by_name("2c42");
  t->lathe = t->dl && t->dl->run == DIALECT_RUN_MACHINE;
  t->mpage = 0;
}

static void lathe_said(void *ctx, int log, const char *msg)
{
  struct tui *t = ctx;
  if (log)
    say(t, "%s", msg);
  else
    note(t, "%s", msg);
}

/* t->run as the 2С42's panel keeps it (the editor, quit, the title ask it). */
static void lathe_sync(struct tui *t)
{
  if (!t->m) {
    t->run = R_IDLE;
    return;
  }
  switch (tmr_phase(t->m)) {
  case TMR_RUN: case TMR_HOLD: case TMR_WAIT: t->run = R_RUN; break;
  case TMR_READY: t->run = R_IDLE; break;
  default: t->run = R_DONE; break;
  }
}

/* The machine of the neutral runner, with its tool table (--tools). */
static struct tmr *lathe_new(struct tui *t)
{
  struct tmr *m = tmr_new(t->o.en, t->o.max_blocks, lathe_said, t);
  char err[600];
  if (m && t->o.tools && tmr_tools(m, t->o.tools, err, sizeof err))
    say(t, "--tools %s", err);
  return m;
}

/* The machine for the text as it is now (at power-on): 0, or -1 (the text
 * has errors, or the runner refused it; said). */
static int lathe_prepare(struct tui *t)
{
  if (!t->lathe)
    return -1;
  if (!t->m)
    t->m = lathe_new(t);
  size_t n;
  char *src = t->m ? tui_text_join(&t->text, &n) : NULL;
  if (!src) {
    say(t, "out of memory");
    return -1;
  }
  int bad = tmr_load(t->m, t->dl, src, n, t->path);
  free(src);
  t->run_gen = bad ? t->gen - 1 : t->gen;   /* a failed one is tried again at Пуск */
  lathe_sync(t);
  return bad ? -1 : 0;
}

/* After a file was read (or a new one named): its dialect, its machine. */
static void lathe_opened(struct tui *t)
{
  if (t->lathe && t->nerr == 0 && t->text.n)
    lathe_prepare(t);
}

static void lathe_pusk(struct tui *t)
{
  if (t->run != R_RUN && t->m && t->run_gen != t->gen) {
    size_t n;
    char *src = tui_text_join(&t->text, &n);
    if (src && tmr_same(t->m, src, n))
      t->run_gen = t->gen;   /* edited back to what the machine has: it stays */
    free(src);
  }
  if (t->run != R_RUN && (!t->m || t->run_gen != t->gen)) {
    /* a new cycle of the text as it is now: checked, compiled anew */
    if (!t->text.n) {
      say(t, "the text is empty: Tab, then i, writes a block");
      return;
    }
    if (check(t, 0)) {
      check(t, 1);
      say(t, "the program has %zu error%s: the cycle does not start", t->nerr, t->nerr == 1 ? "" : "s");
      return;
    }
    int had = t->m != NULL && t->run != R_IDLE;
    if (lathe_prepare(t))
      return;
    if (had)
      say(t, "the text changed: compiled anew, the machine is at power-on");
  }
  tmr_pusk(t->m);
  lathe_sync(t);
}

static void lathe_stop(struct tui *t)
{
  if (!t->m) {
    say(t, "Стоп: no cycle is running");
    return;
  }
  tmr_stop(t->m);
  lathe_sync(t);
}

static int lathe_advance(struct tui *t)
{
  if (!t->m)
    return -1;
  int ms = tmr_advance(t->m, t->fast);
  lathe_sync(t);
  return ms;
}

static void lathe_switch(struct tui *t, enum tmr_switch w)
{
  static const char *const on_text[3] = {
    "П/АВТ: single block, each block waits for Пуск before it starts",
    "U/: block skip on, the blocks written with / are passed over",
    "ST: optional stop on, M01 waits for Пуск",
  };
  static const char *const off_text[3] = {
    "АВТ: automatic, the blocks run on",
    "U/ off: the blocks written with / run",
    "ST off: M01 does not stop",
  };
  if (!t->m)
    t->m = lathe_new(t);
  if (!t->m) {
    say(t, "out of memory");
    return;
  }
  int on = !tmr_get(t->m, w);
  tmr_set(t->m, w, on);
  say(t, "%s", on ? on_text[w] : off_text[w]);
}

static void lathe_key(struct tui *t, int fn, wint_t c)
{
  if (fn) {
    if (c == KEY_ENTER)
      press_ps(t);
    return;
  }
  if (c >= '1' && c <= '9') {   /* a page by its place */
    int k = (int)(c - '1');
    if (t->m && k < tmr_npages(t->m))
      t->mpage = k;
    return;
  }
  switch (c) {
  case '\r': case '\n': press_ps(t); return;
  case 'g': lathe_pusk(t); return;
  case 's': lathe_stop(t); return;
  case 'e': press_exit(t); return;
  case 'b': lathe_switch(t, TMR_SINGLE); return;
  case 'u': lathe_switch(t, TMR_SKIP); return;
  case 't': lathe_switch(t, TMR_OPTSTOP); return;
  case 'r':
    if (t->m && t->run_gen == t->gen)
      tmr_reset(t->m);
    else if (t->m)
      say(t, "reset: the machine is idle; Пуск compiles the text anew and starts the cycle");
    else
      say(t, "reset: no machine yet");
    lathe_sync(t);
    return;
  case 'p': page_open(t); return;
  case 'P': {
    int n = t->m ? tmr_npages(t->m) : 1;
    t->mpage = (t->mpage + n - 1) % n;
    return;
  }
  case 'f':
    t->fast = !t->fast;
    if (!t->fast && t->m)
      tmr_repace(t->m);   /* machine speed from here */
    say(t, t->fast ? "speed: as fast as possible" : "speed: machine speed");
    return;
  case 'q': ask_quit(t); return;
  case 'w': ask_save(t, 0); return;
  case 'o': ask_open(t); return;
  case 'c': check(t, 1); return;
  default: return;
  }
}

/* The panel's keys on the 2С42 screen: the running session's, or the idle one's. */
static int panel_edit(struct tui *t, int op, int arg)
{
  return t->run != R_IDLE ? sess_panel_edit(&t->s, op, arg) : screen_edit(&t->idle, op, arg);
}

static void lathe_key(struct tui *t, int fn, wint_t c);

static void panel_key(struct tui *t, int fn, wint_t c)
{
  if (t->lathe) {
    lathe_key(t, fn, c);
    return;
  }
  int field = t->run == R_RUN && t->s.state == SE_WAIT && t->s.wait == W_ANSWER;
  const struct screen *sc = t->run != R_IDLE ? &t->s.scr : &t->idle;
  if (fn) {
    switch (c) {
    case KEY_BACKSPACE: c = 127; break;
    case KEY_LEFT: panel_edit(t, SCREEN_MOVE, -1); return;
    case KEY_RIGHT: panel_edit(t, SCREEN_MOVE, 1); return;
    case KEY_UP: panel_edit(t, SCREEN_SCROLL, -1); return;
    case KEY_DOWN: panel_edit(t, SCREEN_SCROLL, 1); return;
    case KEY_ENTER: press_ps(t); return;
    default: return;
    }
  }
  if (c >= '0' && c <= '9') {
    if (field)
      panel_edit(t, SCREEN_DIGIT, (int)(c - '0'));
    else
      say(t, "digits go into the input field of a G27 dialog");
    return;
  }
  /* the P5 results of a tooth search: + and - page through the steps */
  if (sc->p5 && !field && (c == '+' || c == '-')) {
    if (panel_edit(t, SCREEN_P5_PAGE, c == '+' ? 1 : -1))
      say(t, c == '+' ? "the last steps are shown" : "the first steps are shown");
    return;
  }
  switch (c) {
  case 127: case 8: panel_edit(t, SCREEN_BACKSPACE, 0); return;
  case '-': panel_edit(t, SCREEN_MINUS, 0); return;
  case '\r': case '\n': press_ps(t); return;
  case 'g': press_pusk(t); return;
  case 's': press_stop(t); return;
  case 'e': press_exit(t); return;
  case 'q': ask_quit(t); return;
  case 'f':
    t->fast = !t->fast;
    if (!t->fast && t->run == R_RUN)
      pace_start(&t->pace, sess_time(&t->s));   /* machine speed from here */
    say(t, t->fast ? "speed: as fast as possible" : "speed: machine speed");
    return;
  case 'j':
    t->jog_step = t->jog_step >= 10000 ? 1 : t->jog_step * 10;
    say(t, "jog step %lld discretes", (long long)t->jog_step);
    return;
  case 'x': jog(t, 0, -1); return;
  case 'X': jog(t, 0, 1); return;
  case 'y': jog(t, 1, -1); return;
  case 'Y': jog(t, 1, 1); return;
  case 'z': jog(t, 2, -1); return;
  case 'Z': jog(t, 2, 1); return;
  case 'a': jog(t, 3, -1); return;
  case 'A': jog(t, 3, 1); return;
  case '<': set_override(t, t->override - 10); return;
  case '>': case '+': case '=': set_override(t, t->override + 10); return;
  case 'w': ask_save(t, 0); return;
  case 'o': ask_open(t); return;
  case 'c': check(t, 1); return;
  case 'p': page_open(t); return;
  case 'b': set_single(t, !t->single); return;
  case 'B': {
    char init[16] = "";
    if (t->brk)
      snprintf(init, sizeof init, "%d", t->brk);
    input_open(t, IN_BREAK, "breakpoint at block (empty: none): N", init);
    return;
  }
  default: return;
  }
}

static int help_lines(const struct tui *t);

/* Tab: the panel and the editor in turn (the parameters page closes) */
static void focus_next(struct tui *t)
{
  t->focus = t->focus == F_EDIT ? F_PANEL : F_EDIT;
  t->page = 0;
}

static void key(struct tui *t, int fn, wint_t c)
{
  if (t->help) {
    /* the arrows scroll a help taller than the terminal; any other key closes it */
    int rows = LINES - 2, max = help_lines(t) - rows;
    if (fn && (c == KEY_DOWN || c == KEY_NPAGE) && max > 0) {
      t->help_top += c == KEY_DOWN ? 1 : rows;
      if (t->help_top > max)
        t->help_top = max;
      return;
    }
    if (fn && (c == KEY_UP || c == KEY_PPAGE)) {
      t->help_top -= c == KEY_UP ? 1 : rows;
      if (t->help_top < 0)
        t->help_top = 0;
      return;
    }
    if (fn && c == KEY_RESIZE)
      return;
    t->help = 0;
    return;
  }
  if (t->input.kind) {
    if (fn && c == KEY_RESIZE)
      return;
    input_key(t, fn, c);
    return;
  }
  if (fn) {
    switch (c) {
    case KEY_RESIZE: return;   /* the next draw lays out anew */
    case KEY_F(1): t->help = 1; t->help_top = 0; return;
    case KEY_F(2): ask_save(t, 0); return;
    case KEY_F(3): ask_open(t); return;
    case KEY_F(4): press_rus(t); return;
    case KEY_F(5): press_pusk(t); return;
    case KEY_F(6): press_stop(t); return;
    case KEY_F(7): press_exit(t); return;
    case KEY_F(8): check(t, 1); return;
    case KEY_F(9): panel_key(t, 0, 'f'); return;
    case KEY_F(10): ask_quit(t); return;
    case KEY_BTAB: focus_next(t); return;
    default: break;
    }
  } else {
    switch (c) {
    case '\t': focus_next(t); return;
    case 18: press_rus(t); return;   /* Ctrl-R */
    case '?': t->help = 1; t->help_top = 0; return;
    default: break;
    }
  }
  if (t->focus == F_EDIT)
    edit_key(t, fn, c);
  else if (t->focus == F_PARAMS && page_key(t, fn, c))
    return;
  else
    panel_key(t, fn, c);
}

/* ---- drawing ---- */

static struct tui *T;   /* the one terminal, for the drawing helpers */

static void cell(int y, int x, uint32_t c, attr_t a)
{
  if (c == 0)
    c = ' ';
  if (c == '\t')
    c = ' ';
  if (T->utf8) {
    wchar_t w[2] = {(wchar_t)c, 0};
    if (c < 0x20 || c == 0x7F || (c >= 0x80 && c < 0xA0) || (c >= 0x80 && wcwidth((wchar_t)c) != 1))
      w[0] = '?';
    cchar_t cc;
    setcchar(&cc, w, a, 0, NULL);
    mvadd_wch(y, x, &cc);
  } else {
    mvaddch(y, x, (chtype)(unsigned char)tui_ascii(c) | a);
  }
}

/* UTF-8 text at y, x in at most w columns; pad: fill the rest with blanks.
 * Returns the columns written. */
static int text(int y, int x, int w, const char *s, attr_t a, int pad)
{
  if (w <= 0)
    return 0;
  uint32_t *cp = malloc(sizeof *cp * (size_t)w);
  int n = cp ? screen_decode(s, cp, w) : 0;
  for (int i = 0; i < n; i++)
    cell(y, x + i, cp[i], a);
  if (pad)
    for (int i = n; i < w; i++)
      cell(y, x + i, ' ', a);
  free(cp);
  return n;
}

static void textf(int y, int x, int w, attr_t a, const char *fmt, ...) __attribute__((format(printf, 5, 6)));
static void textf(int y, int x, int w, attr_t a, const char *fmt, ...)
{
  char b[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(b, sizeof b, fmt, ap);
  va_end(ap);
  text(y, x, w, b, a, 1);
}

/* Characters (code points) of a UTF-8 string. */
static int ulen(const char *s)
{
  return u8cols(s, strlen(s));
}

static void frame(int y, int x, int h, int w, const char *title, attr_t a)
{
  if (h < 2 || w < 2)
    return;
  cell(y, x, 0x250C, a);
  cell(y, x + w - 1, 0x2510, a);
  cell(y + h - 1, x, 0x2514, a);
  cell(y + h - 1, x + w - 1, 0x2518, a);
  for (int i = 1; i < w - 1; i++) {
    cell(y, x + i, 0x2500, a);
    cell(y + h - 1, x + i, 0x2500, a);
  }
  for (int i = 1; i < h - 1; i++) {
    cell(y + i, x, 0x2502, a);
    cell(y + i, x + w - 1, 0x2502, a);
  }
  if (title && w > 6) {
    char b[256];
    snprintf(b, sizeof b, " %s ", title);
    text(y, x + 2, w - 4, b, a | A_BOLD, 0);
  }
}

/* A titled rule: the top of a pane too low for a whole frame. */
static void rule(int y, int x, int w, const char *title, attr_t a)
{
  for (int i = 0; i < w; i++)
    cell(y, x + i, 0x2500, a);
  if (title && w > 6) {
    char b[256];
    snprintf(b, sizeof b, " %s ", title);
    text(y, x + 1, w - 2, b, a | A_BOLD, 0);
  }
}

struct layout {
  int ok;
  int sy, sx;              /* the framed 2С42 screen */
  int lx, lw;              /* the listing, the editor or the parameters page (lw 0: none) */
  int py, ph;              /* its rows */
  int rx, rw;              /* the machine pane (rw 0: none) */
  int ry, rh;
  int gx, gw, gy, gh;      /* the messages (gh 0: none) */
  int gframe;              /* framed; else a rule on top */
};

/* Where everything goes in a w x h terminal, by what an operator needs
 * most: the 2С42 screen; then, at the panel, the machine (positions, feeds,
 * the block, the time), then the listing; in the editor or on the
 * parameters page, that pane before the machine.  When the screen leaves
 * little height for the messages, they go below the machine pane too. */
static struct layout lay_out(const struct tui *t, int w, int h)
{
  struct layout l;
  memset(&l, 0, sizeof l);
  if (w < SCR_W || h < SCR_H + 3)
    return l;
  l.ok = 1;
  l.py = l.ry = l.sy = 1;
  l.ph = l.rh = h - 3;
  int side = w - SCR_W;
  if (side >= 2 * SIDE_MIN) {
    l.lw = side / 2;
    l.rw = side - l.lw;
  } else if (t->focus != F_PANEL) {
    l.lw = side >= MACH_W ? side : 0;
  } else if (side >= MACH_W + SIDE_MIN - 2) {
    l.rw = MACH_W;
    l.lw = side - MACH_W;
  } else if (side >= MACH_W) {
    l.rw = side;
  }
  l.lx = 0;
  l.sx = l.lw ? l.lw : l.rw ? 0 : (w - SCR_W) / 2;
  l.rx = l.sx + SCR_W;
  l.gx = l.sx;
  l.gw = SCR_W;
  l.gy = l.sy + SCR_H;
  l.gh = l.ph - SCR_H;
  if (l.gh < 5 && l.rw) {
    /* low: the machine pane as tall as the screen, the messages under both */
    l.rh = SCR_H;
    l.gw = SCR_W + l.rw;
  }
  if (l.gh < 2)
    l.gh = 0;
  l.gframe = l.gh >= 5;
  return l;
}

static long run_line(const struct tui *t)
{
  if (t->lathe) {
    int n;
    unsigned line;
    if (!t->m || t->run_gen != t->gen || tmr_block(t->m, &n, &line) < 0)
      return -1;
    return (long)line - 1;
  }
  if (t->run == R_IDLE || t->run_gen != t->gen)
    return -1;
  if (t->s.state == SE_ERROR)
    return sess_vm_error(&t->s)->block < t->prog.nblocks ? (long)t->prog.blocks[sess_vm_error(&t->s)->block].line - 1 : -1;
  if (t->s.state == SE_WAIT || !t->cur.valid)
    return (long)t->prog.blocks[sess_cur(&t->s)].line - 1;
  return (long)t->cur.line - 1;
}

/* The block the panel shows as running: its number (-1 none) and line. */
static int shown_block(const struct tui *t, unsigned *line)
{
  *line = 0;
  if (t->run == R_IDLE)
    return -1;
  if (t->s.state == SE_ERROR && sess_vm_error(&t->s)->block < t->prog.nblocks) {
    const struct prog_block *b = &t->prog.blocks[sess_vm_error(&t->s)->block];
    *line = b->line;
    return b->number ? (int)b->number : -1;
  }
  if (t->s.state == SE_WAIT || !t->cur.valid) {
    const struct prog_block *b = &t->prog.blocks[sess_cur(&t->s)];
    *line = b->line;
    return b->number ? (int)b->number : -1;
  }
  *line = t->cur.line;
  return t->cur.n;
}

static void draw_listing(struct tui *t, const struct layout *l)
{
  int h = l->ph, w = l->lw;
  char title[200];
  const char *name = t->path ? t->path : "(new program)";
  const char *base = strrchr(name, '/') ? strrchr(name, '/') + 1 : name;
  int edit = t->focus == F_EDIT;
  snprintf(title, sizeof title, "%s%s%s", edit ? "edit: " : "", base, t->dirty ? " *" : "");
  frame(l->py, l->lx, h, w, title, edit ? A_BOLD : A_NORMAL);
  int rows = h - 2, cols = w - 2;
  if (rows <= 0 || cols <= 4)
    return;
  long rl = run_line(t);
  size_t n = t->text.n;
  /* what to keep in view: the editor's cursor, or the running block */
  long want = edit ? (long)t->ecur : rl;
  size_t top = edit ? t->etop : t->ltop;
  if (want >= 0) {
    if ((size_t)want < top)
      top = (size_t)want > (size_t)rows / 3 ? (size_t)want - (size_t)rows / 3 : 0;
    else if ((size_t)want >= top + (size_t)rows)
      top = (size_t)want - (size_t)rows / 3;
  }
  if (top > 0 && top + (size_t)rows > n)
    top = n > (size_t)rows ? n - (size_t)rows : 0;
  if (edit)
    t->etop = top;
  else
    t->ltop = top;
  int digits = 2;
  for (size_t k = n; k >= 100 && digits < 12; k /= 10)
    digits++;
  if (!n) {
    text(l->py + 1, l->lx + 1, cols, t->path ? "(empty)" : "(no program: F3 opens one,", A_DIM, 1);
    if (!t->path)
      text(l->py + 2, l->lx + 1, cols, " Tab then i writes one)", A_DIM, 1);
  }
  /* the editor's view across long lines: the gutter stays, the text
   * scrolls; a search's match is brought into view once */
  int tw = cols - (digits + 3);
  if (tw < 1)
    tw = 1;
  int col = edit ? t->ecol : 0;
  if (edit) {
    int longest = 0;
    for (int r = 0; r < rows && top + (size_t)r < n; r++) {
      int len = ulen(t->text.line[top + (size_t)r]);
      longest = len > longest ? len : longest;
    }
    if (t->hl_line >= 0 && t->hl_show) {
      if (t->hl_col < col || t->hl_col + t->hl_len > col + tw)
        col = t->hl_col + t->hl_len <= tw ? 0 : t->hl_col - tw / 3;
      t->hl_show = 0;
    }
    if (col > longest - tw + 1)
      col = longest - tw + 1;
    if (col < 0)
      col = 0;
    t->ecol = col;
  }
  uint32_t *cp = malloc(sizeof *cp * (size_t)(col + tw + 1));
  for (int r = 0; r < rows && top + (size_t)r < n; r++) {
    size_t i = top + (size_t)r;
    int y = l->py + 1 + r, x = l->lx + 1;
    int running = (long)i == rl, cursor = edit && i == t->ecur;
    attr_t a = A_NORMAL;
    if (running)
      a = t->colors ? COLOR_PAIR(1) | A_BOLD : A_REVERSE;
    else if (cursor)
      a = t->colors ? COLOR_PAIR(2) : A_UNDERLINE | A_BOLD;
    int mk = i < t->nmark ? t->mark[i] : 0;
    char num[24], g[48];
    int nl = snprintf(num, sizeof num, "%zu", i + 1);
    g[0] = mk == 2 ? '!' : mk == 1 ? '~' : ' ';
    g[1] = running ? '>' : cursor ? '*' : ' ';
    int k = 2;
    for (int pad = digits - nl; pad > 0; pad--)
      g[k++] = ' ';
    snprintf(g + k, sizeof g - (size_t)k, "%s ", num);
    int used = text(y, x, cols, g, a, 0);
    if (!cp)
      continue;
    /* one more than fits: in the editor a line cut at an edge shows … there */
    int len = screen_decode(t->text.line[i], cp, col + tw + 1);
    for (int c = 0; c < cols - used; c++) {
      int at = col + c;
      uint32_t ch = at < len ? cp[at] : ' ';
      if (edit && ((c == 0 && col > 0 && at < len) || (c == tw - 1 && at + 1 < len)))
        ch = 0x2026;
      attr_t ca = a;
      if ((long)i == t->hl_line && at >= t->hl_col && at < t->hl_col + t->hl_len)
        ca = a | A_REVERSE;
      cell(y, x + used + c, ch, ca);
    }
  }
  free(cp);
}

/* The parameters page, in the listing's place: R0-R113, D1, TK, UG, F and
 * both arrays (pointer, length, cells; > marks the pointer's cell), in as
 * many columns as fit; the selected one is set by Enter. */
static void draw_page(struct tui *t, const struct layout *l)
{
  int focus = t->focus == F_PARAMS;
  frame(l->py, l->lx, l->ph, l->lw, t->run == R_IDLE ? "parameters (no cycle yet)" : "parameters",
        focus ? A_BOLD : A_NORMAL);
  int rows = l->ph - 2, cols = l->lw - 2;
  if (rows <= 0 || cols <= 4)
    return;
  int cw = cols < PCOLW ? cols : PCOLW, ncol = cols / cw;
  t->prows = rows;
  int sc = t->psel / rows;
  if (sc < t->pcol)
    t->pcol = sc;
  if (sc >= t->pcol + ncol)
    t->pcol = sc - ncol + 1;
  for (int c = 0; c < ncol; c++)
    for (int r = 0; r < rows; r++) {
      int i = (t->pcol + c) * rows + r, reg;
      char b[64] = "";
      if (i < NPITEM)
        pitem(t, i, b, sizeof b, &reg);
      attr_t a = i == t->psel && focus ? A_REVERSE : i >= 118 && (i - 118) % (1 + KP_CELLS) == 0 ? A_BOLD : A_NORMAL;
      text(l->py + 1 + r, l->lx + 1 + c * cw, cw - (c + 1 < ncol ? 1 : 0), b, a, 1);
    }
}

static void shown_pos(const struct tui *t, double pos[4], double *tm, double *feed)
{
  for (int a = 0; a < 4; a++)
    pos[a] = 0;
  *tm = 0;
  *feed = 0;
  if (t->run == R_IDLE)
    return;
  for (int a = 0; a < 4; a++)
    pos[a] = (double)sess_pos(&t->s, a);
  *tm = sess_time(&t->s);
  if (t->fast || !t->cur.valid || t->s.state == SE_WAIT || (t->run != R_RUN && !t->stopped_mid))
    return;
  double now = pace_now(&t->pace);
  if (now >= t->cur.t1 || t->cur.t1 <= t->cur.t0)
    return;
  double f = cur_frac(t, now);
  for (int a = 0; a < 4; a++)
    pos[a] = (double)t->cur.from[a] + (double)(t->cur.to[a] - t->cur.from[a]) * f;
  *tm = now > t->cur.t0 ? now : t->cur.t0;
  *feed = t->run == R_RUN && !t->held && !t->ovr_held ? t->cur.feed : 0;   /* a feed hold shows 0 */
}


/* What the machine waits for, as the header and the message line both say
 * it (the message line is made anew at every draw, so that a wait that
 * follows another within one key -- a tooth search's -- is not described
 * by the one before). */
static const char *wait_text(const struct tui *t, char *b, size_t n)
{
  char nb[16];
  snprintf(b, n, "%s waits: %s", bname(sess_block_number(&t->s), nb), wait_hint(&t->s));
  return b;
}

static const char *state_text(const struct tui *t, char *b, size_t n)
{
  /* why Пуск would not start: said before anything else */
  if (t->run != R_RUN && (t->run == R_IDLE || t->gen != t->run_gen)) {
    if (!t->path && !t->text.n)
      return "no program: F3 opens one";
    if (!t->text.n)
      return "empty: Tab, then i writes a block";
    if (t->nerr) {
      snprintf(b, n, "%zu error%s: F8 lists %s", t->nerr, t->nerr == 1 ? "" : "s", t->nerr == 1 ? "it" : "them");
      return b;
    }
  }
  if (t->lathe)
    return t->m ? tmr_state(t->m, b, n) : "no machine: the program must compile";
  if (t->run == R_IDLE)
    return "ready: Пуск starts the cycle";
  if (t->run == R_DONE) {
    switch (t->s.state) {
    case SE_END: return "end (M2)";
    case SE_STOPPED: return "stopped";
    default: return "error";
    }
  }
  if (t->held)
    return "feed hold (Стоп)";
  if (t->s.state == SE_WAIT)
    return wait_text(t, b, n);
  return "running";
}

/* The title: the state first, then the file's name (cut from the left
 * when long), the speed and the program's name last. */
static void draw_title(struct tui *t, int W)
{
  char sb[300], name[600], b[1200];
  const char *st = state_text(t, sb, sizeof sb);
  const char *path = t->path ? t->path : "(new program)";
  const char *mod = t->dirty ? " [modified]" : "";
  char speed[64], nb[16];
  snprintf(speed, sizeof speed, "%s%s%s%s", t->fast ? "fast" : "machine speed", t->single ? "  |  single block" : "",
           t->brk ? "  |  break " : "", t->brk ? bname(t->brk, nb) : "");
  const char *rus0 = t->cyr ? "  |  Рус" : "";
  char rus[64];   /* where the speed is left out: single block still shown, as П */
  snprintf(rus, sizeof rus, "%s%s", rus0, t->single ? "  |  П" : "");
  snprintf(name, sizeof name, "%s", path);
  for (int v = 0; v < 4; v++) {
    if (v == 0)
      snprintf(b, sizeof b, " s42 tui  %s%s  |  %s  |  %s%s", name, mod, st, speed, rus0);
    else if (v == 1)
      snprintf(b, sizeof b, " %s%s  |  %s  |  %s%s", name, mod, st, speed, rus0);
    else if (v == 2)
      snprintf(b, sizeof b, " %s%s  |  %s%s", name, mod, st, rus);
    else {
      /* the name's end (the file, not the directories) in what is left */
      int room = W - (ulen(mod) + ulen(st) + ulen(rus) + 6);
      if (room >= 4) {
        uint32_t cp[140];
        int len = screen_decode(path, cp, 140), keep = room - 1 < len ? room - 1 : len;
        char *q = name;
        for (int i = len - keep; i < len; i++)
          q += tui_utf8(cp[i], q);
        *q = 0;
        snprintf(b, sizeof b, " …%s%s  |  %s%s", name, mod, st, rus);
      } else {
        snprintf(b, sizeof b, " %s%s", st, rus);
      }
    }
    if (ulen(b) <= W)
      break;
  }
  textf(0, 0, W, A_REVERSE, "%s", b);
}

/* The estimated cycle time and the part done, as text; "" when none. */
static void est_text(const struct tui *t, double tm, int wide, char *b, size_t n)
{
  b[0] = 0;
  int done = t->run == R_DONE && t->s.state == SE_END;   /* the cycle's own time */
  if (t->run == R_IDLE || (!done && t->est.run != t->runs))
    return;
  double total = done ? sess_time(&t->s) : t->est.total;
  const char *lab = wide ? "estimate" : "of";
  if (!done && t->est.kind == EST_NONE) {
    snprintf(b, n, "%s %s", lab, t->est.pid ? "..." : "unknown");
    return;
  }
  if (!done && t->est.kind == EST_LEAST) {
    snprintf(b, n, wide ? "%s ≥ %.2f s" : "%s ≥%.2f s", lab, total);
    return;
  }
  int pct = done || total <= 0 ? 100 : (int)floor(100 * tm / total + 1e-9);
  if (!done && pct > 99)
    pct = 99;   /* 100 % is the end, when it comes */
  if (pct < 0)
    pct = 0;
  if (wide)
    snprintf(b, n, "%s %9.2f s %3d %%%s", lab, total, pct, !done && t->est.kind == EST_ERROR ? " error" : "");
  else
    snprintf(b, n, "%s %7.2f s %3d%%%s", lab, total, pct, !done && t->est.kind == EST_ERROR ? "!" : "");
}

static void draw_machine(struct tui *t, const struct layout *l)
{
  int x = l->rx + 1, w = l->rw - 2, y = l->ry + 1, end = l->ry + l->rh - 1;
  frame(l->ry, l->rx, l->rh, l->rw, "machine", A_NORMAL);
  if (w <= 4)
    return;
  int wide = w >= 28;   /* narrower: the same, in shorter forms */
  double pos[4], tm, feed;
  shown_pos(t, pos, &tm, &feed);
  static const char *const ax[4] = {"X", "Y", "Z", "A"};
  for (int a = 0; a < 4 && y < end; a++)
    textf(y++, x, w, A_BOLD, wide ? "%s %12.3f %s" : "%s%11.3f %s", ax[a], pos[a] / 1000.0, a == 3 ? "deg" : "mm");
  const struct machine *m = t->run != R_IDLE ? sess_machine(&t->s) : NULL;
  double f = t->run != R_IDLE ? sess_reg(&t->s, REG_F) : 0;
  if (y < end) textf(y++, x, w, A_NORMAL, wide ? "F    %8.0f mm/min" : "F   %6.0f mm/min", f);
  if (y < end) textf(y++, x, w, A_NORMAL, wide ? "feed %10.1f mm/min" : "feed %6.1f mm/min", feed);
  if (y < end)
    textf(y++, x, w, A_NORMAL, wide ? "F%%   %8d %%%s" : "F%%  %6d %%%s", m ? m->override_pct : t->override,
          m && !m->override_allowed ? " (M25)" : "");
  const char *wheel = !m || m->wheel == WHEEL_OFF ? "off" : m->wheel == WHEEL_CW ? "cw" : "ccw";
  const char *corr = m && m->corr_allowed ? "M22" : "M23";
  if (y < end) {
    if (wide)
      textf(y++, x, w, A_NORMAL, "wheel %-4s osc %-3s %s", wheel, m && t->osc ? "on" : "off", corr);
    else
      textf(y++, x, w, A_NORMAL, "wheel %-4s osc %s", wheel, m && t->osc ? "on" : "off");
  }
  unsigned line;
  int bn = shown_block(t, &line);
  char nb[16];
  if (y < end) {
    if (line)
      textf(y++, x, w, A_BOLD, wide ? "block %s  line %u" : "%s  line %u", bname(bn, nb), line);
    else
      text(y++, x, w, wide ? "block -" : "N-", A_NORMAL, 1);
  }
  if (y < end) textf(y++, x, w, A_NORMAL, wide ? "time %10.2f s %s" : "time %7.2f s %s", tm, t->fast ? "fast" : "x1");
  char eb[80];
  est_text(t, tm, wide, eb, sizeof eb);
  if (y < end) text(y++, x, w, eb, A_NORMAL, 1);
  if (wide) {
    if (y < end) textf(y++, x, w, A_NORMAL, "jog step %lld", (long long)t->jog_step);
  } else if (y < end) {
    textf(y++, x, w, A_NORMAL, "%s  jog %lld", corr, (long long)t->jog_step);
  }
  if (y < end) textf(y++, x, w, A_NORMAL, "blocks %llu", t->run != R_IDLE ? (unsigned long long)sess_blocks(&t->s) : 0ULL);
  if (y < end) text(y++, x, w, wide ? "registers changed last" : "changed last", A_BOLD, 1);
  for (int k = 0; k < t->nchg && y < end; k++) {
    const char *by = t->chg[k].how == 1 ? "restart" : t->chg[k].how == 2 ? "panel" : bname(t->chg[k].n, nb);
    if (wide)
      textf(y++, x, w, k == 0 ? A_BOLD : A_NORMAL, "R%-3d %14.10g  %s", t->chg[k].reg, t->chg[k].v, by);
    else
      textf(y++, x, w, k == 0 ? A_BOLD : A_NORMAL, "R%-3d%9.7g %s", t->chg[k].reg, t->chg[k].v,
            t->chg[k].how == 1 ? "rst" : t->chg[k].how == 2 ? "set" : by);
  }
  while (y < end)
    text(y++, x, w, "", A_NORMAL, 1);
}

static void draw_screen(struct tui *t, const struct layout *l)
{
  uint32_t g[SCR_ROWS][SCR_COLS];
  if (t->run != R_IDLE)
    sess_screen(&t->s, g);
  else
    screen_render(&t->idle, NULL, t->o.en, g);
  frame(l->sy, l->sx, SCR_H, SCR_W, "2С42-65", A_NORMAL);
  for (int r = 0; r < SCR_ROWS; r++)
    for (int c = 0; c < SCR_COLS; c++)
      cell(l->sy + 1 + r, l->sx + 1 + c, g[r][c], r == 0 || r == SCR_ROWS - 1 ? A_BOLD : A_NORMAL);
}

/* UTF-8 text wrapped at words into rows y0..y1 (inclusive) of width w at
 * x, from the bottom up: the rows it took, or -1 when it did not fit. */
static int wrapped_up(int *y, int ytop, int x, int w, const char *s, attr_t a)
{
  uint32_t cp[LOGW];
  int st[LOGW], ln[LOGW];
  int n = screen_decode(s, cp, LOGW);
  int rows = tui_wrap(cp, n, w, st, ln, LOGW);
  for (int r = rows - 1; r >= 0 && *y >= ytop; r--, (*y)--) {
    for (int c = 0; c < w; c++)
      cell(*y, x + c, c < ln[r] ? cp[st[r] + c] : ' ', a);
  }
  return rows;
}

static void draw_log(struct tui *t, const struct layout *l, int W)
{
  if (!l->gh)
    return;
  int top, w, x = l->gx;
  if (l->gframe) {
    frame(l->gy, l->gx, l->gh, l->gw, "messages", A_NORMAL);
    top = l->gy + 1;
    w = l->gw - 2;
    x++;
  } else {
    rule(l->gy, l->gx, l->gw, "messages", A_NORMAL);
    top = l->gy + 1;
    w = l->gw;
  }
  int y = l->gframe ? l->gy + l->gh - 2 : l->gy + l->gh - 1;
  /* the newest at the bottom, each wrapped at words; the newest is left to
   * the message line below when it is there whole */
  int i = t->nlog - 1;
  if (i >= 0 && !t->input.kind && strcmp(t->log[i], t->msg) == 0 && ulen(t->msg) <= W)
    i--;
  for (; i >= 0 && y >= top; i--)
    wrapped_up(&y, top, x, w, t->log[i], i == t->nlog - 1 ? A_BOLD : A_NORMAL);
}

/* The key line: as many as fit, the least needed going first; "F1 keys"
 * and "q quit" always stay. */
struct hint {
  const char *s;
  int prio;                 /* 0 always, then 1 (most needed) .. */
};
static const struct hint help_panel[] = {
  {"g Пуск", 1}, {"s Стоп", 1}, {"e Вихід", 2}, {"Enter ПС", 1}, {"BS ЗБ", 5}, {"^R Рус", 4},
  {"xyza/XYZA jog", 6}, {"<> F%", 3}, {"b single", 3}, {"f speed", 5}, {"p params", 3}, {"Tab editor", 2}, {"F1 keys", 0},
  {"q quit", 0}, {NULL, 0},
};
static const struct hint help_edit[] = {
  {"arrows move", 4}, {"i insert", 1}, {"Enter replace", 1}, {"d delete", 2}, {"u undo", 2}, {"/ search", 2},
  {": line", 5}, {"c check", 3}, {"w save", 1}, {"o open", 4}, {"^R Рус", 6}, {"Tab panel", 2}, {"F1 keys", 0},
  {"q quit", 0}, {NULL, 0},
};
static const struct hint help_page[] = {
  {"arrows choose", 1}, {"= set", 1}, {"p close", 1}, {"Enter ПС", 2}, {"g Пуск", 2}, {"s Стоп", 2}, {"Tab editor", 3},
  {"F1 keys", 0}, {"q quit", 0}, {NULL, 0},
};
static const struct hint help_input[] = {
  {"type", 3}, {"F4/^R Рус", 4}, {"Left/Right Home End", 5}, {"BS Del", 5}, {"^U clear", 4}, {"Enter done", 0},
  {"Esc cancel", 0}, {NULL, 0},
};

static void draw_keys(int y, int W, const struct hint *h)
{
  char b[600];
  int maxp = 0;
  for (const struct hint *k = h; k->s; k++)
    maxp = k->prio > maxp ? k->prio : maxp;
  for (int p = maxp; p >= 0; p--) {
    size_t n = 0;
    b[0] = 0;
    for (const struct hint *k = h; k->s; k++)
      if (k->prio <= p)
        n += (size_t)snprintf(b + n, sizeof b - n, "%s%s", n ? " " : "", k->s);
    if (ulen(b) <= W || p == 0)
      break;
  }
  text(y, 0, W, b, A_REVERSE, 1);
}

static const char *const help_full[] = {
  "s42 tui: the 2С42-65 panel",
  "",
  "0-9, -        the number in a G27 field; - makes it negative",
  "Backspace     ЗБ: erase a digit",
  "Left Right    move the cursor in the field",
  "Up Down       scroll the input buffer (P6)",
  "Enter         ПС: end the entry, confirm a directive",
  "F5, g         Пуск: start the cycle, go on after a wait or Стоп",
  "F6, s         Стоп: feed hold; again (or in a wait) stops the cycle",
  "F7, e         Вихід з циклу: cycle exit, taken by the next PP",
  "F4, Ctrl-R    Рус: Cyrillic keyboard mode (table 3.4)",
  "x y z a       jog X Y Z A minus (G20, M19; a correction under M22)",
  "X Y Z A       jog plus;  j: jog step 1 10 100 1000 10000",
  "< >           feed override -10 % / +10 % (+ too, but on P5:)",
  "+ -           P5 search results: the next / previous 8 steps",
  "b             single block (П/АВТ): each block waits for Пуск",
  "B             breakpoint: block N waits for Пуск (run to N)",
  "F9, f         machine speed / as fast as possible",
  "p             parameters page: R0-R113, D1, TK, UG, the arrays;",
  "              arrows choose, = sets one (in a wait or a feed",
  "              hold), p or Esc closes; the panel's keys still work",
  "Tab           panel / program editor",
  "editor        Up Down PgUp PgDn Home End: the cursor's line;",
  "              Left Right: the view across long lines",
  "              i I insert after/before, Enter e replace, d delete,",
  "              u undo, c F8 check, w F2 save, W save as, o F3 open",
  "              / search, n N next / previous match, : go to line",
  "prompts       typing replaces a name given; Esc cancels",
  "F10, q        quit (while a cycle runs: q twice)",
  "",
  "any key closes this; Up Down scroll it when it is cut",
};

static const char *const help_lathe[] = {
  "s42 tui: the 2У22 panel (the 16Б16Ф3 lathe)",
  "",
  "F5, g         Пуск: start the cycle, go on after a wait or Стоп;",
  "              after the end (M02, M30) a new cycle from the start",
  "F6, s         Стоп: the feed stops; again (or in a wait) it ends",
  "              the cycle",
  "b             П/АВТ: single block, each block waits for Пуск",
  "u             U/: block skip, the blocks written with / are passed",
  "t             ST: optional stop, M01 waits for Пуск",
  "r             reset: the cycle is abandoned (the slides stay), Пуск",
  "              starts the program from its first block",
  "p P, 1 2      the machine's pages in turn, or by place: DG (position",
  "              X Ø / Z, following error, part zero, slides), DI (the",
  "              mode, the block, G F S, spindle, T and its corrections,",
  "              R0-R9)",
  "F9, f         machine speed / as fast as possible",
  "Tab           panel / program editor",
  "editor        Up Down PgUp PgDn Home End: the cursor's line;",
  "              Left Right: the view across long lines",
  "              i I insert after/before, Enter e replace, d delete,",
  "              u undo, c F8 check, w F2 save, W save as, o F3 open",
  "              / search, n N next / previous match, : go to line",
  "F4, Ctrl-R    Рус: Cyrillic keyboard mode in the editor",
  "prompts       typing replaces a name given; Esc cancels",
  "F10, q        quit (while a cycle runs: q twice)",
  "",
  "any key closes this; Up Down scroll it when it is cut",
};

static const char *const *help_text(const struct tui *t)
{
  return t->lathe ? help_lathe : help_full;
}

static int help_lines(const struct tui *t)
{
  return t->lathe ? (int)(sizeof help_lathe / sizeof help_lathe[0]) : (int)(sizeof help_full / sizeof help_full[0]);
}

static void draw_help(struct tui *t)
{
  int n = help_lines(t), h = n + 2, w = 72;
  int H = LINES, W = COLS;
  if (h > H)
    h = H;
  if (w > W)
    w = W;
  int y = (H - h) / 2, x = (W - w) / 2;
  int top = t->help_top > n - (h - 2) ? n - (h - 2) : t->help_top;
  if (top < 0)
    top = 0;
  frame(y, x, h, w, top + h - 2 < n ? "keys (Down: more)" : "keys", A_BOLD);
  for (int i = 0; i < h - 2; i++)
    text(y + 1 + i, x + 1, w - 2, help_text(t)[top + i], A_NORMAL, 1);
}

/* ---- the neutral runner's panel (the 2У22): drawing ---- */

#define MPAGE_W (MRUN_PAGE_COLS + 2)   /* the framed machine page */

/* The page's lines (into v, at most max; pointers into text, the newlines
 * made ends).  Returns how many. */
static int page_lines(char *text_, char **v, int max)
{
  int n = 0;
  for (char *p = text_; p && *p && n < max;) {
    char *nl = strchr(p, '\n');
    v[n++] = p;
    if (!nl)
      break;
    *nl = 0;
    p = nl + 1;
  }
  return n;
}

/* The machine's page in a frame at y, x (h rows, w columns): its name and
 * the others' as tabs in the top edge, the one shown in reverse. */
static void draw_mpage(struct tui *t, int y, int x, int h, int w)
{
  frame(y, x, h, w, NULL, A_NORMAL);
  int np = t->m ? tmr_npages(t->m) : 0;
  if (t->mpage >= np)
    t->mpage = 0;
  int cx = x + 2;
  if (np == 0)
    cx += text(y, cx, w - 4, t->dl ? " 2У22 " : " machine ", A_BOLD, 0);
  for (int k = 0; k < np && cx < x + w - 4; k++) {
    char b[40];
    snprintf(b, sizeof b, " %s ", tmr_page_name(t->m, k));
    cx += text(y, cx, x + w - 2 - cx, b, k == t->mpage ? A_REVERSE | A_BOLD : A_NORMAL, 0);
    if (k + 1 < np && cx < x + w - 2)
      cell(y, cx++, 0x2500, A_NORMAL);
  }
  int rows = h - 2;
  if (!t->m) {
    text(y + 1, x + 1, w - 2, t->nerr ? "(no machine: the program has errors," : "(no machine yet:", A_DIM, 1);
    if (rows > 1)
      text(y + 2, x + 1, w - 2, t->nerr ? " F8 lists them)" : " Пуск sets it up)", A_DIM, 1);
    return;
  }
  char *pg = tmr_page(t->m, t->mpage);
  char *v[64];
  int n = page_lines(pg, v, 64);
  for (int r = 0; r < rows; r++)
    text(y + 1 + r, x + 1, w - 2, r < n ? v[r] : "", r == 0 ? A_BOLD : A_NORMAL, 1);
  free(pg);
}

/* The most lines any of the machine's pages has now. */
static int mpage_rows(const struct tui *t)
{
  if (!t->m)
    return 2;
  int most = 1;
  for (int k = 0; k < tmr_npages(t->m); k++) {
    char *pg = tmr_page(t->m, k), *v[64];
    int n = page_lines(pg, v, 64);
    most = n > most ? n : most;
    free(pg);
  }
  return most;
}

/* The mode line: the modes as the 2У22 names them, what the machine does
 * or waits for, the block, the time. */
static void draw_modeline(struct tui *t, int y, int W)
{
  char mb[64], sb[300], bb[48] = "", nb[16];
  const char *modes = "АВТ", *st = "no machine";
  if (t->m) {
    modes = tmr_modes(t->m, mb, sizeof mb);
    st = tmr_state(t->m, sb, sizeof sb);
    int num;
    unsigned line;
    if (tmr_block(t->m, &num, &line) >= 0)
      snprintf(bb, sizeof bb, "  |  %s line %u", bname(num, nb), line);
  } else if (t->nerr) {
    st = "the program has errors: F8 lists them";
  }
  int x = text(y, 0, W, " ", A_REVERSE, 0);
  x += text(y, x, W - x, modes, A_REVERSE | A_BOLD, 0);
  x += text(y, x, W - x, " ", A_REVERSE, 0);
  char cb[24] = "";
  if (t->m && tmr_cycles(t->m))
    snprintf(cb, sizeof cb, "cycle %u  ", tmr_cycles(t->m));
  textf(y, x, W - x, A_BOLD, "  %s%s  |  %s%.2f s  %llu blocks", st, bb, cb, t->m ? tmr_clock(t->m) : 0.0,
        t->m ? tmr_blocks(t->m) : 0ULL);
}

static const struct hint help_lathe_panel[] = {
  {"g Пуск", 1}, {"s Стоп", 1}, {"b П/АВТ", 2}, {"u U/", 2}, {"t ST", 2}, {"r reset", 3}, {"p page", 1},
  {"f speed", 4}, {"Tab editor", 2}, {"F1 keys", 0}, {"q quit", 0}, {NULL, 0},
};

/* The lathe's terminal: the title; the listing (or the editor) on the
 * left, the machine's page on the right with the messages under it; the
 * mode line; the message line; the keys. */
static void draw_lathe(struct tui *t)
{
  int H = LINES, W = COLS;
  erase();
  curs_set(0);
  if (W < MPAGE_W || H < 10) {
    char m[160];
    snprintf(m, sizeof m, "the terminal is %dx%d: s42 tui needs at least %dx%d here; q quits", W, H, MPAGE_W, 10);
    uint32_t cp[160];
    int st[160], ln[160], n = screen_decode(m, cp, 160), rows = tui_wrap(cp, n, W, st, ln, 160);
    for (int r = 0, y = H > rows ? (H - rows) / 2 : 0; r < rows && y + r < H; r++)
      for (int c = 0; c < ln[r]; c++)
        cell(y + r, c, cp[st[r] + c], A_BOLD);
    refresh();
    return;
  }
  draw_title(t, W);
  int ph = H - 4;   /* rows 1 .. H-4 */
  struct layout l;
  memset(&l, 0, sizeof l);
  l.ok = 1;
  l.py = 1;
  l.ph = ph;
  int side = W - MPAGE_W, px = -1, pw = MPAGE_W;
  if (side >= SIDE_MIN) {
    l.lw = side;
    px = side;
  } else if (t->focus == F_EDIT) {
    l.lw = W;
  } else {
    px = (W - MPAGE_W) / 2;
  }
  if (l.lw)
    draw_listing(t, &l);
  if (px >= 0) {
    int want = mpage_rows(t) + 2;
    int h = want < ph ? want : ph;
    if (ph - h < 3)
      h = ph;   /* no room for the messages under it */
    draw_mpage(t, 1, px, h, pw);
    if (ph - h >= 3) {
      l.gx = px;
      l.gw = pw;
      l.gy = 1 + h;
      l.gh = ph - h;
      l.gframe = l.gh >= 5;
      draw_log(t, &l, W);
    }
  }
  draw_modeline(t, H - 3, W);
  int my = H - 2, cy = -1, cx = 0;
  if (t->input.kind) {
    int pl = text(my, 0, W, t->input.prompt, A_BOLD, 0);
    int avail = W - pl - 1;
    if (avail < 1)
      avail = 1;
    int first = t->input.cur > avail ? t->input.cur - avail : 0;
    for (int i = 0; pl + i < W; i++) {
      int k = first + i;
      cell(my, pl + i, k < t->input.n ? t->input.b[k] : ' ', k < t->input.n && t->input.sel ? A_REVERSE : A_NORMAL);
    }
    cy = my;
    cx = pl + t->input.cur - first < W ? pl + t->input.cur - first : W - 1;
  } else {
    text(my, 0, W, t->msg, A_NORMAL, 1);
  }
  draw_keys(H - 1, W, t->input.kind ? help_input : t->focus == F_EDIT ? help_edit : help_lathe_panel);
  if (t->help)
    draw_help(t);
  if (cy >= 0 && !t->help) {
    move(cy, cx);
    curs_set(1);
  }
  refresh();
}

static void draw(struct tui *t)
{
  if (t->lathe) {
    draw_lathe(t);
    return;
  }
  int H = LINES, W = COLS;
  if (t->msg_wait) {
    if (t->run == R_RUN && t->s.state == SE_WAIT) {
      wait_text(t, t->msg, sizeof t->msg);   /* the wait now, which may follow another */
    } else {
      t->msg[0] = 0;   /* the wait is over */
      t->msg_wait = 0;
    }
  }
  erase();
  curs_set(0);   /* shown again only on the input line */
  struct layout l = lay_out(t, W, H);
  if (!l.ok) {
    char m[160];
    snprintf(m, sizeof m, "the terminal is %dx%d: s42 tui needs at least %dx%d; q quits", W, H, SCR_W, SCR_H + 3);
    uint32_t cp[160];
    int st[160], ln[160], n = screen_decode(m, cp, 160), rows = tui_wrap(cp, n, W, st, ln, 160);
    for (int r = 0, y = H > rows ? (H - rows) / 2 : 0; r < rows && y + r < H; r++)
      for (int c = 0; c < ln[r]; c++)
        cell(y + r, c, cp[st[r] + c], A_BOLD);
    refresh();
    return;
  }
  draw_title(t, W);
  if (l.lw) {
    if (t->page)
      draw_page(t, &l);
    else
      draw_listing(t, &l);
  }
  if (l.rw)
    draw_machine(t, &l);
  draw_screen(t, &l);
  draw_log(t, &l, W);
  /* the message / input line */
  int my = H - 2;
  int cy = -1, cx = 0;
  if (t->input.kind) {
    int pl = text(my, 0, W, t->input.prompt, A_BOLD, 0);
    int avail = W - pl - 1;
    if (avail < 1)
      avail = 1;
    int first = t->input.cur > avail ? t->input.cur - avail : 0;
    for (int i = 0; pl + i < W; i++) {
      int k = first + i;
      cell(my, pl + i, k < t->input.n ? t->input.b[k] : ' ', k < t->input.n && t->input.sel ? A_REVERSE : A_NORMAL);
    }
    cy = my;
    cx = pl + t->input.cur - first < W ? pl + t->input.cur - first : W - 1;
  } else {
    text(my, 0, W, t->msg, A_NORMAL, 1);
  }
  draw_keys(H - 1, W, t->input.kind ? help_input : t->focus == F_EDIT ? help_edit : t->focus == F_PARAMS ? help_page : help_panel);
  if (t->help)
    draw_help(t);
  if (cy >= 0 && !t->help) {
    /* the terminal's cursor where the next character goes */
    move(cy, cx);
    curs_set(1);
  }
  refresh();
}

/* ---- the estimate of the cycle time ---- */

/* The estimate is a headless run of the same cycle from where it is now:
 * a child process (fork) goes on with a copy of the session as fast as it
 * can, pressing Пуск and ПС where the machine waits for them, and writes
 * back the simulated time where it ended.  A wait only the operator can
 * end -- a dialog's number not given yet, teach-in, a tooth search's
 * moves, a feed override of 0 % -- or EST_SECONDS of computing stops it
 * there: "at least" that much.  The loop polls its pipe, so the terminal
 * never waits for it; it is computed again whenever the operator changes
 * what it assumed (an answer, the end of such a wait, the override, cycle
 * exit).  A child of its own process group, so that Ctrl-C in the
 * terminal does not reach it; it never touches the terminal. */

static void est_stop(struct tui *t)
{
  if (t->est.pid > 0) {
    kill(t->est.pid, SIGKILL);
    while (waitpid(t->est.pid, NULL, 0) < 0 && errno == EINTR)
      ;
  }
  if (t->est.fd >= 0)
    close(t->est.fd);
  t->est.pid = 0;
  t->est.fd = -1;
}

static _Noreturn void est_child(struct tui *t, int fd)
{
  setpgid(0, 0);
  for (int i = 0; i < 3; i++)
    signal(quit_sigs[i], SIG_DFL);
  /* nothing of it reaches the terminal (a plugin writing to stderr), and
   * it holds none of the parent's connections (the Modbus server's) open */
  int nul = open("/dev/null", O_RDWR);
  if (nul >= 0) {
    dup2(nul, 0);
    dup2(nul, 1);
    dup2(nul, 2);
  }
  long maxfd = sysconf(_SC_OPEN_MAX);
  if (maxfd < 0 || maxfd > 65536)
    maxfd = 65536;
  for (int i = 3; i < maxfd; i++)
    if (i != fd)
      close(i);
  if (nice(10) < 0) {
    /* as it was: only slower for the terminal */
  }
  struct session *s = &t->s;
  memset(&s->sink, 0, sizeof s->sink);
  s->single = 0;   /* the estimate runs on without stopping at single blocks and the breakpoint */
  s->brk = 0;
  struct est_result r;
  memset(&r, 0, sizeof r);
  r.kind = EST_LEAST;
  struct timespec t0, now;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  for (unsigned long i = 1;; i++) {
    if ((i & 1023) == 0) {
      clock_gettime(CLOCK_MONOTONIC, &now);
      if ((double)(now.tv_sec - t0.tv_sec) + (double)(now.tv_nsec - t0.tv_nsec) / 1e9 > EST_SECONDS)
        break;
    }
    enum sess_ev ev = sess_run(s);
    if (ev == SE_START)
      continue;
    if (ev == SE_WAIT) {
      if (!s->plug_wait && (s->wait == W_PUSK || s->wait == W_BLOCK) && sess_key_pusk(s) == 0)
        continue;
      if (!s->plug_wait && s->wait == W_PS && sess_key_ps(s) == 0)
        continue;
      break;   /* the operator must act: at least this much */
    }
    r.kind = ev == SE_END ? EST_END : ev == SE_ERROR ? EST_ERROR : EST_LEAST;
    break;
  }
  r.t = sess_time(s);
  r.blocks = sess_blocks(s);
  r.resumed = s->resumed;
  ssize_t w = write(fd, &r, sizeof r);
  (void)w;
  _exit(0);
}

static void est_start(struct tui *t)
{
  est_stop(t);
  if (t->est.run != t->runs)
    t->est.kind = EST_NONE;   /* a new cycle: the last one's says nothing */
  t->est.run = t->runs;
  t->est.override = sess_override_pct(&t->s);
  t->est.latch = sess_exit_latched(&t->s);
  int p[2];
  if (pipe(p))
    return;
  pid_t pid = fork();
  if (pid == 0) {
    close(p[0]);
    est_child(t, p[1]);
  }
  close(p[1]);
  if (pid < 0) {
    close(p[0]);
    return;   /* no estimate: "unknown" */
  }
  fcntl(p[0], F_SETFD, FD_CLOEXEC);
  fcntl(p[0], F_SETFL, O_NONBLOCK);
  t->est.pid = pid;
  t->est.fd = p[0];
}

/* The child's pipe is readable: its result, or its end without one. */
static void est_read(struct tui *t)
{
  struct est_result r;
  ssize_t n = read(t->est.fd, &r, sizeof r);
  if (n < 0 && (errno == EAGAIN || errno == EINTR))
    return;
  if (n == (ssize_t)sizeof r) {
    t->est.kind = r.kind;
    t->est.total = r.t;
    t->est.at_blocks = r.blocks;
    t->est.at_resumed = r.resumed;
  }
  /* it ends right after writing; one that failed without a word: unknown */
  est_stop(t);
}

/* After each pass of the loop: start or restart the estimate when what it
 * assumed no longer holds; and a cycle exit taken into a waiting block,
 * whose row comes only when the wait ends. */
static void watch(struct tui *t)
{
  if (t->lathe)
    return;   /* no estimate for the neutral runner */
  if (t->run == R_RUN && t->s.state == SE_WAIT && sess_pp_jumps(&t->s) != t->pp_seen && t->cur.valid)
    exit_taken(t, t->cur.n, t->cur.line, sess_block_number(&t->s), t->prog.blocks[sess_cur(&t->s)].line);
  if (t->run != R_RUN) {
    if (t->est.pid)
      est_stop(t);   /* the cycle is over: its own time is exact now */
    return;
  }
  int want = t->est.run != t->runs || sess_override_pct(&t->s) != t->est.override ||
             (sess_exit_latched(&t->s) && !t->est.latch);
  if (!want && !t->est.pid && t->est.kind == EST_LEAST)   /* the operator did what stopped it */
    want = sess_blocks(&t->s) > t->est.at_blocks ||
           (sess_blocks(&t->s) == t->est.at_blocks && t->s.resumed > t->est.at_resumed);
  if (want)
    est_start(t);
}

/* ---- the loop ---- */

void tui_press(struct tui *t, enum tui_key k)
{
  if (t->lathe) {
    if (k == TUI_PUSK)
      lathe_pusk(t);
    else if (k == TUI_STOP)
      lathe_stop(t);
    else if (k == TUI_RESET)
      lathe_key(t, 0, 'r');
    return;
  }
  switch (k) {
  case TUI_PUSK: press_pusk(t); break;
  case TUI_STOP: press_stop(t); break;
  case TUI_PS: press_ps(t); break;
  case TUI_EXIT: press_exit(t); break;
  case TUI_RESET:
    if (t->run == R_RUN)
      sess_key_stop(&t->s);
    t->held = 0;
    t->ovr_held = 0;
    if (t->run != R_IDLE)
      end_run(t);
    say(t, "reset: the machine is idle; Пуск starts the cycle");
    break;
  }
}

void tui_motion(const struct tui *t, struct tui_motion *m)
{
  memset(m, 0, sizeof *m);
  m->block = -1;
  if (t->run == R_IDLE || !t->cur.valid)
    return;
  m->held = t->run == R_RUN && (t->held || t->ovr_held);
  m->feed = m->held ? 0 : t->cur.feed;
  double now = pace_now(&t->pace), len = t->cur.t1 - t->cur.t0;
  if (t->run == R_RUN && !t->fast && len > 0 && now < t->cur.t1) {
    m->active = 1;
    m->frac = cur_frac(t, now);
    /* as one even motion that has the same rest: what the map interpolates */
    m->dur = m->frac < 1 ? (t->cur.t1 - now) / (1 - m->frac) : len;
    for (int a = 0; a < 4; a++)
      m->d[a] = t->cur.to[a] - t->cur.from[a];
    m->block = t->cur.n;
  } else if (m->held) {
    m->active = 1;   /* held between blocks: nothing moves */
    m->frac = 1;
  }
}

int tui_override_pct(const struct tui *t)
{
  return t->override;
}

void tui_set_single(struct tui *t, int on)
{
  if (t->lathe)
    return;   /* the 2С42's switches: a source serves that machine */
  if (!on != !t->single)
    set_single(t, on != 0);
}

void tui_set_break(struct tui *t, int n)
{
  if (t->lathe)
    return;
  char b[16];
  snprintf(b, sizeof b, "%d", n);
  if (n != t->brk)
    set_break(t, b);
}

int tui_single(const struct tui *t)
{
  return t->single;
}

int tui_break(const struct tui *t)
{
  return t->brk;
}

void tui_say(struct tui *t, const char *msg)
{
  say(t, "%s", msg);
}

int tui_override(struct tui *t, int pct)
{
  if (pct < 0 || pct > 150)
    return -1;
  if (t->run == R_RUN && !sess_override_allowed(&t->s))
    return -1;
  set_override(t, pct);
  return 0;
}

const struct session *tui_session(const struct tui *t)
{
  return t->run == R_IDLE || t->lathe ? NULL : &t->s;
}

static int loop(struct tui *t)
{
  struct pollfd pfd[2 + MAXSRC_FD];
  int first[16], count[16];
  while (!t->quit && !got_sig) {
    int timeout = advance(t);
    watch(t);
    for (int i = 0; i < t->nsrc; i++)
      if (t->src[i].update)
        t->src[i].update(t->src[i].ctx, t);
    draw(t);
    int n = 1;
    pfd[0].fd = STDIN_FILENO;
    pfd[0].events = POLLIN;
    pfd[0].revents = 0;
    for (int i = 0; i < t->nsrc && i < 16; i++) {
      first[i] = n;
      count[i] = t->src[i].fds ? t->src[i].fds(t->src[i].ctx, pfd + n, 1 + MAXSRC_FD - n) : 0;
      if (count[i] < 0)
        count[i] = 0;
      n += count[i];
    }
    int est = -1;   /* the estimate's pipe */
    if (t->est.fd >= 0) {
      est = n++;
      pfd[est].fd = t->est.fd;
      pfd[est].events = POLLIN;
      pfd[est].revents = 0;
    }
    if (timeout < 0)
      timeout = 500;
    for (int i = 0; i < t->nsrc; i++)
      if (t->src[i].poll_timeout)
        timeout = t->src[i].poll_timeout(t->src[i].ctx, timeout);
    int r = poll(pfd, (nfds_t)n, timeout);
    if (est >= 0 && pfd[est].revents)
      est_read(t);
    if (r < 0 && errno != EINTR) {
      curses_off();
      fprintf(stderr, "s42 tui: poll: %s\n", strerror(errno));
      return 4;
    }
    if (got_sig)
      break;
    if (pfd[0].revents & (POLLHUP | POLLERR | POLLNVAL)) {
      t->quit = 1;   /* the terminal is gone */
      break;
    }
    wint_t c;
    int k;
    while ((k = get_wch(&c)) != ERR && !t->quit) {
      key(t, k == KEY_CODE_YES, c);
      advance(t);   /* what is due now (a dialog's next field) is there for the next key */
    }
    for (int i = 0; r > 0 && i < t->nsrc && i < 16; i++) {
      int any = 0;
      for (int j = 0; j < count[i]; j++)
        any |= pfd[first[i] + j].revents != 0;
      if (any && t->src[i].ready)
        t->src[i].ready(t->src[i].ctx, t, pfd + first[i], count[i]);
    }
  }
  return got_sig ? 128 + got_sig : 0;
}

int tui_main(const struct tui_opts *o, const struct tui_source *src, int nsrc)
{
  if (!isatty(STDIN_FILENO) || !isatty(STDOUT_FILENO)) {
    fprintf(stderr, "s42 tui: stdin and stdout must be a terminal (s42 run is the headless emulator)\n");
    return 2;
  }
  static struct tui tt;   /* large (the log); one terminal per process */
  struct tui *t = &tt;
  memset(t, 0, sizeof *t);
  t->o = *o;
  t->src = src;
  t->nsrc = nsrc;
  t->override = 100;
  t->jog_step = 1000;
  t->fast = !o->realtime;
  t->restart_pending = o->restart;
  t->est.fd = -1;
  t->hl_line = -1;
  tui_text_init(&t->text);
  screen_init(&t->idle);
  t->idle.en = o->en;
  T = t;
  /* only LC_CTYPE: numbers keep their '.' */
  setlocale(LC_CTYPE, "");
  const char *cs = nl_langinfo(CODESET);
  t->utf8 = cs && (strcmp(cs, "UTF-8") == 0 || strcmp(cs, "utf8") == 0);
  if (o->program && creatable(o->program)) {
    /* a name that is not there yet: an empty text that its first save creates */
    t->path = strdup(o->program);
    set_saved(t);
    set_dialect(t, o->program);
    check(t, 0);
    say(t, "%s: a new file (the first save creates it).  Tab, then i, writes a block; F1 shows the keys",
        o->program);
  } else if (o->program) {
    char err[512];
    if (tui_text_load(&t->text, o->program, &t->disk, err, sizeof err)) {
      fprintf(stderr, "s42 tui: %s\n", err);
      tui_text_free(&t->text);
      return 4;
    }
    t->path = strdup(o->program);
    set_saved(t);
    set_dialect(t, o->program);
    check(t, 0);
    lathe_opened(t);
    say(t, "%s: %zu lines, %zu error%s, %zu warning%s.  Пуск (F5 or g) starts the cycle; F1 shows the keys",
        o->program, t->text.n, t->nerr, t->nerr == 1 ? "" : "s", t->nwarn, t->nwarn == 1 ? "" : "s");
  } else {
    set_dialect(t, NULL);
    say(t, "no program: F3 (or o) opens one; Tab, then i, writes one.  F1 shows the keys");
  }
  if (tcgetattr(STDIN_FILENO, &tty0) == 0)
    tty_saved = 1;
  /* ours before newterm, so ncurses leaves SIGINT, SIGTERM and SIGHUP to us */
  signals_on();
  SCREEN *scr = newterm(NULL, stdout, stdin);
  if (!scr) {
    signals_off();
    fprintf(stderr, "s42 tui: cannot use the terminal '%s'\n", getenv("TERM") ? getenv("TERM") : "(TERM unset)");
    tui_text_free(&t->text);
    free(t->path);
    free(t->mark);
    return 4;
  }
  curses_on = 1;
  atexit(curses_off);
  add_restore("rmkx");
  add_restore("cnorm");
  add_restore("sgr0");
  add_restore("rmcup");
  cbreak();
  noecho();
  nonl();
  intrflush(stdscr, FALSE);
  keypad(stdscr, TRUE);
  nodelay(stdscr, TRUE);
  set_escdelay(25);
  if (has_colors() && start_color() == OK) {
    use_default_colors();
    init_pair(1, COLOR_BLACK, COLOR_GREEN);
    init_pair(2, COLOR_BLACK, COLOR_CYAN);
    t->colors = 1;
  }
  int rc = loop(t);
  est_stop(t);
  curses_off();
  delscreen(scr);
  signals_off();
  if (t->run != R_IDLE || t->have_prog || t->m)
    end_run(t);
  tui_text_free(&t->text);
  free(t->path);
  free(t->mark);
  free(t->save_to);
  T = NULL;
  return rc;
}
