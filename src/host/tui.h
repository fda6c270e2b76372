/* s42 tui: the 2С42-65 panel in a terminal (ncursesw).  The 16x32 screen
 * from the session's model in the middle, the program listing and editor,
 * the machine's state and a key map around it; runs at machine speed in one
 * loop that never blocks, waiting in poll() on the keyboard and on any
 * other sources a host adds (the Modbus server, later). */
#ifndef S42_TUI_H
#define S42_TUI_H

#include "session.h"
#include <poll.h>

struct tui_opts {
  const char *program;        /* NULL: start with an empty text */
  const char *state;          /* --state FILE */
  int restart;                /* --restart: the first Пуск continues from M15 */
  int realtime;               /* machine speed (the default); 0: as fast as possible */
  int en;                     /* --lang en */
  unsigned long long max_blocks;
  struct plug_set *plugins;   /* src/core/plugin.h: the functions plugins bring (may be NULL) */
  struct mach_travel travel;  /* --machine FILE: each axis's travel (none: has[] all 0) */
  /* --dialect: the dialect of every file opened; NULL: each file's by its
   * extension (dialect_by_file).  A dialect that runs on the neutral
   * runner (DIALECT_RUN_MACHINE: the 2У22) gets its machine's panel
   * (tui_mrun.c) instead of the 2С42's. */
  const struct dialect *dialect;
  const char *tools;          /* --tools FILE: the lathe's tool table (the neutral runner's machine) */
};

struct tui;

/* Another file-descriptor source for the loop.  Before every poll the loop
 * asks each source for the descriptors it waits on; when some are ready it
 * hands them back; after the machine advanced it lets the source mirror the
 * state.  A source acts on the machine only through tui_press and
 * tui_override, as a key would, so the panel and the source agree. */
struct tui_source {
  void *ctx;
  int (*fds)(void *ctx, struct pollfd *pfd, int max);          /* how many filled */
  void (*ready)(void *ctx, struct tui *t, const struct pollfd *pfd, int n);
  void (*update)(void *ctx, struct tui *t);                    /* may be NULL */
  int (*poll_timeout)(void *ctx, int want_ms);   /* may be NULL: a shorter poll timeout it needs */
  /* may be NULL: a key that may compute for long (Пуск or ПС answering a
   * plugin's wait) is about to be applied: show the cycle running meanwhile */
  void (*busy)(void *ctx, struct tui *t);
};

/* TUI_RESET: abandon the cycle, back to idle (a Modbus client's reset) */
enum tui_key { TUI_PUSK, TUI_STOP, TUI_PS, TUI_EXIT, TUI_RESET };

/* The block whose motion the terminal is playing out at machine speed. */
struct tui_motion {
  int active;                 /* a motion is under way (or held mid-way) */
  int held;                   /* feed hold (Стоп) */
  double frac;                /* part done, 0..1 */
  double dur;                 /* its simulated (= wall, at machine speed) seconds */
  double feed;                /* its contour speed, mm/min; of the last block when none */
  int64_t d[4];               /* its increments, discretes */
  int block;                  /* its number, -1 none */
};

/* Run the terminal until the operator quits.  Returns the exit status: 0,
 * 2 when stdin/stdout are not a terminal, 4 when the terminal or the
 * program file cannot be used, 128 + n after signal n (the terminal is
 * restored first). */
int tui_main(const struct tui_opts *o, const struct tui_source *src, int nsrc);

/* For sources: press a panel key; set the feed override (0 taken, -1
 * refused); the session of the current run (NULL before the first). */
void tui_press(struct tui *t, enum tui_key k);
int tui_override(struct tui *t, int pct);
const struct session *tui_session(const struct tui *t);
void tui_motion(const struct tui *t, struct tui_motion *m);
/* The feed override switch, %. */
int tui_override_pct(const struct tui *t);
/* Single block and the breakpoint (0 none): set them as the panel's keys
 * do (b, B), and read them back. */
void tui_set_single(struct tui *t, int on);
void tui_set_break(struct tui *t, int n);
int tui_single(const struct tui *t);
int tui_break(const struct tui *t);
/* A line in the messages pane, as a source reports. */
void tui_say(struct tui *t, const char *msg);

/* ---- for tui.c: a program on the neutral runner (tui_mrun.c) ----
 * The machine of a DIALECT_RUN_MACHINE dialect (src/core/mrun.h) as the
 * terminal runs it: the compiled program, the run, its pacing at machine
 * speed (src/host/pace.h: each block's simulated time runs off on the wall
 * clock before the next block starts) and the operator's switches.  No
 * curses here: the terminal draws what these give.  Messages go out
 * through say (log 0: the message line only). */
struct tmr;
struct dialect;
enum tmr_phase {
  TMR_READY,      /* the machine is there; Пуск starts the cycle */
  TMR_RUN,        /* the cycle runs */
  TMR_HOLD,       /* Стоп: the feed stopped mid-cycle; Пуск goes on */
  TMR_WAIT,       /* the machine waits for Пуск (single block, M00, M01 with ST) */
  TMR_END,        /* the program ended (M02, M30) */
  TMR_STOPPED,    /* Стоп ended the cycle */
  TMR_ERROR       /* the run failed (tmr_error) */
};
enum tmr_switch { TMR_SINGLE, TMR_SKIP, TMR_OPTSTOP };
typedef void (*tmr_say_fn)(void *ctx, int log, const char *msg);

struct tmr *tmr_new(int en, unsigned long long max_blocks, tmr_say_fn say, void *ctx);
void tmr_free(struct tmr *m);
/* Compile src with dl and set the machine up at power-on for it: 0, or -1
 * (it does not compile, or the runner refused it: said). */
int tmr_load(struct tmr *m, const struct dialect *dl, const char *src, size_t n, const char *path);
/* The machine's tool table (--tools FILE), read now and given to every
 * run set up from here on: 0, or -1 with err. */
int tmr_tools(struct tmr *m, const char *path, char *err, size_t n);
/* Пуск: start the cycle (a new one after the end, a stop or an error: the
 * machine stays where it is), end a wait or a hold.  0, or -1 (said why). */
int tmr_pusk(struct tmr *m);
/* Стоп: a hold while the cycle runs; in a hold or a wait the cycle ends. */
void tmr_stop(struct tmr *m);
/* Reset: the cycle is abandoned; the next Пуск starts at the first block. */
void tmr_reset(struct tmr *m);
/* Run what is due (fast: as fast as possible, else at machine speed).
 * Returns the poll timeout, ms (-1: nothing to do until a key). */
int tmr_advance(struct tmr *m, int fast);
/* The machine speed goes on from now (after fast). */
void tmr_repace(struct tmr *m);
void tmr_set(struct tmr *m, enum tmr_switch w, int on);
int tmr_get(const struct tmr *m, enum tmr_switch w);
enum tmr_phase tmr_phase(const struct tmr *m);
/* The block shown as current (its index in the program, -1 none), its
 * number as written (-1 none) and line. */
long tmr_block(const struct tmr *m, int *number, unsigned *line);
/* The machine's pages (the 2У22's DG, DI): how many, a name, the text of
 * page k (malloc'd lines, each ended by a newline; NULL out of memory). */
int tmr_npages(const struct tmr *m);
const char *tmr_page_name(const struct tmr *m, int k);
char *tmr_page(const struct tmr *m, int k);
/* The modes as the 2У22 shows them: "АВТ", "П/АВТ", then "ST", "U/". */
const char *tmr_modes(const struct tmr *m, char *b, size_t n);
/* What the machine does or waits for, in a few words ("running",
 * "N13 waits: single block: Пуск (F5 or g) starts it", "end (M02)"). */
const char *tmr_state(const struct tmr *m, char *b, size_t n);
/* Simulated time, s: of the machine; as the clock on the screen shows it
 * (within a block that runs off at machine speed); blocks run. */
double tmr_time(const struct tmr *m);
double tmr_clock(const struct tmr *m);
unsigned long long tmr_blocks(const struct tmr *m);
unsigned tmr_cycles(const struct tmr *m);
/* The machine's program was compiled from exactly these n bytes. */
int tmr_same(const struct tmr *m, const char *src, size_t n);

#endif
