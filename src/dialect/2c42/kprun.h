/* The 2С42 runtime on the runner (src/core/mrun.h), inside its folder: the
 * state a run of a 2С42 program keeps in r->st -- the grinder, the
 * 2С42-65's screen, the dialog, teach-in, M16's window, the plugins the
 * program uses and the block in progress -- shared by the runtime's files:
 * kprun.c (the block's work, the waits, the operator's input), kphost.c
 * (the plugin ABI's host side), kprow.c (rows, dump, screen, Modbus
 * view) and kpstate.c (the restart snapshot's blob). */
#ifndef S42_KPRUN_H
#define S42_KPRUN_H

#include "kp.h"
#include "kpmach.h"
#include "machine.h"
#include "mrun.h"
#include "plugin.h"
#include "screen.h"
#include <stdint.h>

/* What a plugin's callbacks get as "the block" (include/s42_plugin.h). */
struct s42_block {
  struct mrun *r;
  int plug;              /* the plugin being called */
};

/* The block's trace row, as it was when the block finished. */
struct kp_row {
  const char *motion;
  int64_t d[4];
  double f, feed, t, v;
  int has_v;
  int override_pct;
  int64_t jogs[4];
  int has_jogs;
};

/* What goes on with the block when its wait is over. */
enum kp_cont { KC_FINISH, KC_PLUGIN, KC_EXEC };

struct kp_state {
  struct machine m;
  struct mach_travel travel;    /* --machine FILE; none by default (kept across cycles) */
  struct screen scr;            /* the 2С42-65 display */
  int en;                       /* English machine messages */
  uint32_t directive;    /* M18 text shown (string offset + 1), 0 none */
  double answer;         /* the number the last G27 took */
  int have_answer;       /* a G27 took a number that no G28 stored yet */
  int m15_seen;          /* a restart point passed: G29 extends the display */
  int window_opened;     /* M16's window opened at this block's VM_EV_START */
  int cont;              /* enum kp_cont: the rest of the block after its wait */
  /* plugins (the program's set, from its compile) */
  struct plug_set *plugins;
  uint32_t every;        /* started plugins that see every block */
  uint32_t started;      /* plugins this run has started (reset done) */
  struct s42_block blk;
  int plug_wait;         /* a plugin's run() waits for the operator */
  int run_next;          /* the plugin whose run() goes on after the wait */
  int resumed;
  int perr;              /* host->error() during a callback: the code, 0 none */
  unsigned crashes;      /* plugins->crashes when the runtime last looked (the crash guard) */
  char perrmsg[240];
  char extra[320];       /* the current row's plugin members */
  char gname[4];         /* "G50": the motion name of a plugin's G */
  /* the block in progress while waiting */
  struct kp_block mb;
  struct mach_out mo;
  int64_t jogs[4];
  int has_jogs;
  int64_t start[4];      /* position when the block started */
  struct kp_row row;     /* the last row */
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

static inline struct kp_state *kp_st(const struct mrun *r) { return r->st; }

/* Internal results of the block's steps: done (the row is ready), a wait
 * (r->wait says which), failed (the VM holds the error). */
enum { K_DONE = MRB_DONE, K_WAIT = MRB_WAIT, K_FAIL = MRB_FAIL };

/* kphost.c: the plugin host */
extern const struct s42_host kp_host;
/* The plugins of the block (mask): start those not started yet; their
 * phase `which` (0 check, 1 before the motion, 2 after); then run() each in
 * turn (a wait stops there), ending with the runtime's after(): K_*. */
int kp_plug_start_block(struct mrun *r, uint32_t mask);
int kp_plug_phase(struct mrun *r, uint32_t mask, int which);
int kp_run_plugins(struct mrun *r);
/* The plugin whose G is the block's motion, or -1. */
int kp_motion_plugin(const struct mrun *r);
/* A plugin crashed since the runtime last looked (plugin.h's crash guard):
 * K_FAIL with the VM failed (its E-PLUGIN), else 0. */
int kp_plug_crashed(struct mrun *r);
/* A plugin callback's status: 0 fine, else K_FAIL with the VM failed. */
int kp_plug_status(struct mrun *r, int i, int res, const char *phase);
/* Is the block's motion a contour move (the core's or a plugin's)? */
int kp_contour_block(const struct mrun *r);
/* Start (init) every plugin the program uses, before its first block:
 * 0, or -1 when one refuses because of the command line. */
int kp_start_plugins(struct mrun *r, char *msg, size_t n, uint32_t *block);
/* The plugins' JSON members for a row or the dump, into buf. */
void kp_plugin_json(const struct mrun *r, int what, char *buf, size_t n);
/* The k-th started plugin's restart state (0, 2 none kept, 1 no such, -1 too big), and back. */
int kp_plugin_state(const struct mrun *r, int k, char *name, size_t nname, void *buf, size_t cap, size_t *len);
int kp_plugin_restore(struct mrun *r, const char *name, const void *buf, size_t len, char *err, size_t n);
/* the plugins' advance() as simulated time passes */
void kp_tick(void *ctx, double dt);

/* kprun.c: what kphost.c calls back */
int kp_after_motion(struct mrun *r);
void kp_warn(struct mrun *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The block's row (its members as the block leaves them). */
void kp_emit_row(struct mrun *r);

/* kprow.c */
void kp_row_json(const struct mrun *r, FILE *out);
void kp_row_text(const struct mrun *r, FILE *out);
void kp_dump_json(const struct mrun *r, FILE *out);
void kp_screen(const struct mrun *r, FILE *out);
void kp_page(const struct mrun *r, int k, struct mrun_page *pg);
void kp_view(const struct mrun *r, struct mrun_view *v);

/* kpstate.c: the restart snapshot's blob */
size_t kp_save(const struct mrun *r, void *buf, size_t cap, char *err, size_t n);
int kp_restore(struct mrun *r, const void *buf, size_t len, const char *shown, char *err, size_t n);
int kp_reg_range(const struct mrun *r, int k, char *name, size_t n, double *lo, double *hi, int *whole);
/* After a restart: the dialog area as the program's dialog left it. */
void kp_restore_screen(struct mrun *r);

/* The runtime itself (kprun.c), which compile.c puts in the program. */
extern const struct mrun_rt kp_mrun_runtime;

#endif
