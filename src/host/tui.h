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

#endif
