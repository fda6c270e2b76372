/* A session: one program running on one VM against one machine, driven by
 * a host (the headless runner, the terminal, the Modbus server).  sess_run
 * advances until the host must act -- a watched block starts, the machine
 * waits for the operator, the end, an error -- and never blocks. */
#ifndef S42_SESSION_H
#define S42_SESSION_H

#include "kp.h"
#include "kpmach.h"
#include "machine.h"
#include "plugin.h"
#include "screen.h"
#include "vm.h"

struct session;
/* What a plugin's callbacks get as "the block" (include/s42_plugin.h). */
struct s42_block {
  struct session *s;
  int plug;              /* the plugin being called */
};

enum sess_ev { SE_START, SE_WAIT, SE_END, SE_ERROR, SE_STOPPED };
/* W_PS: ПС first, then Пуск; W_FEED: the feed override is at 0 %, the move waits */
/* W_ANSWER: a number in the G27 field (G28 asks again after a refusal) */
/* W_TEACH: M19, jogs follow the programmed path until ПС, then Пуск */
/* W_SECTION: a tooth-step search waits for Пуск while the operator moves
 * the table and A to the next section (a plugin's S42_WAIT_SECTION) */
/* W_BLOCK: single block or a breakpoint: the block waits for Пуск before it starts */
enum sess_wait { W_NONE, W_PUSK, W_PS, W_FEED, W_ANSWER, W_TEACH, W_SECTION, W_BLOCK };

struct sess_row {
  uint64_t seq;
  int n;                 /* block number, -1 none */
  unsigned line;
  int depth;
  const char *motion;
  int64_t d[4];
  double f, feed, t, v;
  int has_v;
  const char *extra;     /* JSON members the plugins add (",\"osc\":\"on\""), or "" */
  int override_pct;
  int64_t jogs[4];
  int has_jogs;
  int64_t start[4];      /* machine position when the block started */
  /* the block's path as the machine takes it (plots draw it): a line or an
   * arc, `to` from the start as programmed (0: the block has none); for an
   * M19 teach-in (teach), the path the jogs followed */
  int has_path, teach;
  struct mach_path path;
};

struct session;
struct sess_sink {
  void *ctx;
  void (*row)(void *ctx, const struct session *s, const struct sess_row *r);
  void (*warn)(void *ctx, const struct session *s, const char *msg);
  /* a plugin's log line */
  void (*log)(void *ctx, const struct session *s, const char *msg);
  /* a plugin moved an axis outside the contour (oscillation) by d (0: a
   * mark where it starts); s->m.pos and s->m.t are the new point (plots) */
  void (*moved)(void *ctx, const struct session *s, int axis, int64_t d);
};

/* How a host sets a session up (sess_configure): kept, so that a new cycle
 * (sess_renew) starts the same way. */
struct sess_config {
  int en;                       /* English machine messages */
  uint64_t max_blocks;          /* E-LIMIT after that many blocks; 0 none */
  struct mach_travel travel;    /* --machine FILE; none by default */
  struct plug_set *plugins;
  struct sess_sink sink;
  int yield_all;                /* a row for every block (the trace, the terminal's listing) */
  int start_all;                /* every block's start comes back to the host */
  const uint8_t *watch;         /* per block: its start comes back (`at`, M15), or NULL */
  void (*canon)(void *ctx, const struct canon_call *c);   /* the machine's calls (--trace=canon) */
  void *canon_ctx;
};

struct sess_runtime;
struct session {
  const struct program *p;
  const struct sess_runtime *rt;  /* the dialect's runtime (src/core/sess_rt.h), from the program */
  struct sess_config cfg;       /* as the host set it up */
  struct vm vm;
  struct machine m;
  struct sess_sink sink;
  int state;             /* enum sess_ev of the last return */
  int wait;              /* enum sess_wait while state == SE_WAIT */
  int en;                /* English machine messages */
  uint64_t seq;
  uint32_t directive;    /* M18 text shown (string offset + 1), 0 none */
  struct screen scr;     /* the 2С42-65 display */
  double answer;         /* the number the last G27 took */
  int have_answer;       /* a G27 took a number that no G28 stored yet */
  int m15_seen;          /* a restart point passed: G29 extends the display */
  int window_opened;     /* M16's window opened at this block's VM_EV_START */
  /* single block and the breakpoint (the host's switches, sess_set_single) */
  int single;            /* every block waits for Пуск before it starts */
  int brk;               /* block number that waits for Пуск before it starts, 0 none */
  int go;                /* the cycle's first block: its Пуск was the cycle's start */
  int gate;              /* a block's start was returned: look at the switches before it runs */
  /* plugins: the host sets `plugins` before the first sess_run */
  struct plug_set *plugins;
  uint32_t every;        /* started plugins that see every block */
  uint32_t started;      /* plugins this run has started (reset done) */
  unsigned crashes;      /* plugins->crashes when the session last looked */
  struct s42_block blk;
  int plug_wait;         /* a plugin's run() waits for the operator */
  int run_next;          /* the plugin whose run() goes on after the wait */
  int resumed;
  int perr;              /* host->error() during a callback: the code, 0 none */
  char perrmsg[240];
  char extra[320];       /* the current row's plugin members */
  char gname[4];         /* "G50": the motion name of a plugin's G */
  /* the block in progress while waiting */
  struct kp_block mb;
  struct mach_out mo;
  int64_t jogs[4];
  int has_jogs;
  int64_t start[4];      /* position when the block started */
  /* M19 teach-in in progress */
  struct {
    int arc;             /* follows an arc (G02/G03) rather than a line */
    int junior;          /* the jogged axis that drives the move, -1 none */
    double inc[4];       /* the block's increments */
    int given[4];        /* the block has this axis word */
    int p, q;            /* arc: the plane's axes */
    double cp, cq, r;    /* arc: centre relative to the start, radius */
    double th0, th;      /* arc: start angle, current angle */
    int ccw;
    int plug;            /* follows a plugin's path (helix): its index + 1 */
    double len, u;       /* the plugin's path: length (discretes), fraction done */
    double exact[4];     /* exact displacement so far (discretes) */
    int64_t moved[4];    /* rounded displacement made */
  } teach;
};

void sess_init(struct session *s, const struct program *p);
/* The host's settings (language, budget, travel, plugins, sinks, what comes
 * back to it); after sess_init, before the first sess_run. */
void sess_configure(struct session *s, const struct sess_config *c);
/* Every block's start comes back to the host (or only the watched ones). */
void sess_set_start_all(struct session *s, int on);
/* The screen's Рус mode (the service line's R). */
void sess_set_cyrillic(struct session *s, int on);
/* The host failed the run (a restart point that cannot be saved, a restart
 * refused): the open block is rolled back and the run ends with that error. */
void sess_fail(struct session *s, int code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* The run refused before its first block (a restart refused): the error is
 * at the program's first block, column 1; nothing ran. */
void sess_refuse(struct session *s, int code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* A new cycle of the same program (reset; Пуск after M2): a fresh machine
 * and VM at block 1, with R0-R113 as they were (the 2С42 keeps its
 * parameters), the host's settings and its switches (the feed override,
 * single block, the breakpoint) kept. */
void sess_renew(struct session *s);
enum sess_ev sess_run(struct session *s);
/* Operator input.  Each returns 0 when taken, -1 when it does not fit what
 * the machine waits for (the caller decides what that means). */
int sess_key_pusk(struct session *s);
int sess_key_ps(struct session *s);
void sess_key_exit(struct session *s);
void sess_key_stop(struct session *s);
/* Пуск after a stop (a client's feed hold): back to the block boundary or
 * the wait it interrupted.  0, or -1 when the cycle was not stopped. */
int sess_resume(struct session *s);
int sess_jog(struct session *s, int axis, int64_t d);
/* The machine's travel (--machine FILE); NULL keeps none. */
void sess_set_travel(struct session *s, const struct mach_travel *t);
/* The operator script's `section`: move the table or A to the next section
 * of a tooth-step search; only while it waits for that (W_SECTION). */
int sess_section(struct session *s, int axis, int64_t d);
/* Start (init) every plugin the program uses, before its first block.
 * Returns 0; or -1 when one refuses because of the command line
 * (S42_FAIL_USAGE): msg holds its reason and *block the first block that
 * needs it.  Other failures wait for that block (E-PLUGIN there). */
int sess_start_plugins(struct session *s, char *msg, size_t n, size_t *block);
/* Type a number into the G27 field and press ПС (the script's `answer`). */
int sess_answer(struct session *s, long long v);
/* Render the screen into a grid of cells. */
void sess_screen(const struct session *s, uint32_t grid[SCR_ROWS][SCR_COLS]);
/* Correction / override from the panel: 0 applied, -1 refused (a warning
 * says why). */
int sess_correct(struct session *s, int axis, int64_t d);
int sess_override(struct session *s, int pct);
/* The override switch turned within a block's contour move at simulated
 * time now (the host's clock, from s->m.mv.t0 to s->m.mv.t1): the rest of
 * the move goes at the new speed (mach_override_at).  Returns the seconds
 * the move's end moved by. */
double sess_override_at(struct session *s, double now);
/* Is `now` within the block's contour move that takes the override
 * (mach_in_move), and that move's speed now (mm/min)? */
static inline int sess_in_move(const struct session *s, double now) { return mach_in_move(&s->m, now); }
static inline double sess_move_feed(const struct session *s) { return s->m.mv.feed; }
/* Single block: from the next block on, each block waits for Пуск (W_BLOCK)
 * before it starts.  A breakpoint: block number n waits for Пуск each time
 * it is about to start (0: none).  The switches stay as set until changed;
 * sess_init clears them.  Either makes the VM report every block's start. */
void sess_set_single(struct session *s, int on);
void sess_set_break(struct session *s, int n);
/* The operator sets parameter reg (R0-R113, or REG_D1) to v from the panel,
 * between blocks or while the machine waits -- never within a block.  It
 * goes through the VM's journal as a dialog answer does: a waiting block
 * that fails afterwards takes it back with its own changes.  0, or -1 with
 * why (the cycle is over, TK UG F are not the operator's, out of range). */
int sess_set_param(struct session *s, int reg, double v, char *why, size_t n);
/* A client (Modbus) writes R[r0 .. r0+n-1] while no block runs (idle,
 * waiting, stopped, ended, after an error): stored as they are, for this
 * cycle and the next (the 2С42 keeps its parameters).  The caller checked
 * the range and the values. */
void sess_load_params(struct session *s, unsigned r0, unsigned n, const double *v);
/* The plugins' JSON members for the dump (",\"osc\":{...}"), into buf. */
void sess_plugin_json(const struct session *s, int what, char *buf, size_t n);
/* The M15 state of the k-th started plugin that keeps one: 0 with its name
 * and bytes, 2 when that plugin keeps none, 1 when there is no k-th plugin,
 * -1 when it does not fit in cap, -2 when its save() crashed (the set's
 * plugins->v[plugins->crashed].err says how). */
int sess_plugin_state(const struct session *s, int k, char *name, size_t nname, void *buf, size_t cap,
                      size_t *len);
/* Give a restarted run a plugin's saved state (starting the plugin). */
int sess_plugin_restore(struct session *s, const char *name, const void *buf, size_t len, char *err, size_t n);
/* What the machine waits for, in words, for messages. */
const char *sess_wait_text(const struct session *s);
/* The oscillation plugin said "on" in the last block's trace members. */
int sess_oscillating(const struct session *s);
/* The current block's number (-1 none) and line. */
int sess_block_number(const struct session *s);
/* What the hosts read of a session (they never write it): the simulated
 * time, an axis's position (discretes), the block being run (its index in
 * the program), a parameter, the blocks executed, the PP jumps taken, the
 * feed override switch and whether it acts (M25/M26), the wheel
 * (WHEEL_*), cycle exit latched. */
static inline double sess_time(const struct session *s) { return s->m.t; }
static inline int64_t sess_pos(const struct session *s, int axis) { return s->m.pos[axis]; }
static inline uint32_t sess_cur(const struct session *s) { return s->vm.cur; }
static inline double sess_reg(const struct session *s, int n) { return s->vm.reg[n]; }
static inline uint64_t sess_blocks(const struct session *s) { return s->vm.blocks; }
static inline uint32_t sess_pp_jumps(const struct session *s) { return s->vm.pp_jumps; }
static inline int sess_override_pct(const struct session *s) { return s->m.override_pct; }
static inline int sess_override_allowed(const struct session *s) { return s->m.override_allowed; }
static inline int sess_wheel(const struct session *s) { return s->m.wheel; }
static inline int sess_exit_latched(const struct session *s) { return s->vm.exit_latch; }
/* ... the run's error as the VM holds it, the parameters, the axes'
 * positions, and (for the panes that show them whole) the VM and the
 * machine themselves, read-only. */
static inline const struct vm_error *sess_vm_error(const struct session *s) { return &s->vm.err; }
static inline const double *sess_regs(const struct session *s) { return s->vm.reg; }
static inline const int64_t *sess_positions(const struct session *s) { return s->m.pos; }
static inline const struct vm *sess_vm(const struct session *s) { return &s->vm; }
static inline const struct machine *sess_machine(const struct session *s) { return &s->m; }
/* The run's error (SE_ERROR: the VM raised it, or the host failed or
 * refused the run), located in the program's text. */
struct s42_error;
void sess_error(const struct session *s, struct s42_error *e);
/* Put the run's error on the machine's screen (its own message). */
void sess_show_error(struct session *s);
/* A message on the machine's screen, as the machine shows its own. */
void sess_show_message(struct session *s, const char *text);
/* The operator's keys on the machine's screen (screen_edit's ops): the
 * input field's digits, minus, ЗБ and cursor, the buffer's scroll, P5's pages. */
int sess_panel_edit(struct session *s, int op, int arg);

#endif
