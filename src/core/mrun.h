/* The runner: the one thing that steps a VM, for every dialect.  A program
 * runs on the VM against the machine its dialect's runtime drives (struct
 * mrun_rt, from program.runtime; a program without one runs on the VM
 * alone).  The runner keeps what every machine's operator has -- Пуск and
 * Стоп, single block, block skip, optional stop, a breakpoint, the feed
 * override, the block budget -- and what every host needs: the waits
 * before, inside and after a block (a kind and a hint), one operator-input
 * record that answers them, the open block's journal of canonical records
 * and warnings (released at commit, dropped on failure), the rows, the
 * restart snapshot and the one error record.  The runtime does a block's
 * machine work through the canonical table (src/core/canon.h) and says how
 * its rows, dump, pages and register map read.
 *
 * mrun_run never blocks: it returns when the host must act (a block is
 * about to start, a row, a wait, the end, an error, a stop). */
#ifndef S42_MRUN_H
#define S42_MRUN_H

#include "canon.h"
#include "program.h"
#include "vm.h"
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

struct mrun;
struct s42_error;

enum mrun_ev {
  MR_ROW,        /* a block ran (cfg.rows): its row can be read (mrun_row_json) */
  MR_WAIT,       /* the machine waits for the operator: r->wait says for what */
  MR_END,        /* the program ended */
  MR_ERROR,      /* the run failed (mrun_error): the block was rolled back */
  MR_STOPPED,    /* the operator stopped the cycle (Стоп) */
  MR_START       /* a block is about to start (cfg.starts, a watched block, a restart point) */
};

/* What the machine waits for. */
enum mrun_wait {
  MRW_NONE,
  MRW_STOP,      /* a programmed stop after the block (M00; M01 with optional stop on): Пуск */
  MRW_BLOCK,     /* single block or the breakpoint: the block waits for Пуск before it starts */
  MRW_PUSK,      /* inside a block: Пуск (a manual-mode stop, the end of a dialog, a plugin's) */
  MRW_PS,        /* inside a block: ПС, then Пуск */
  MRW_ANSWER,    /* inside a block: a number in the input field, then ПС */
  MRW_TEACH,     /* inside a block: teach-in jogs drive the programmed path until ПС */
  MRW_SECTION,   /* inside a block: moves to the next section of a search, then Пуск */
  MRW_FEED       /* inside a block: the feed override is at 0 %, the move waits for it */
};

/* The operator's input: a key, a number, a move, a switch.  One record
 * for every host (the operator script, the terminal's keys, a Modbus
 * client). */
enum mrun_in {
  MRI_PUSK,      /* Пуск */
  MRI_PS,        /* ПС */
  MRI_STOP,      /* Стоп: the cycle stops */
  MRI_EXIT,      /* cycle exit, latched until a block takes it */
  MRI_ANSWER,    /* n: a number typed into the field, then ПС */
  MRI_JOG,       /* axis, n counts: a hand move (manual mode, teach-in) */
  MRI_SECTION,   /* axis, n (and axis2, n2; axis2 -1 none): a search's section move */
  MRI_CORRECT,   /* axis, n: an operational correction while the cycle runs */
  MRI_OVERRIDE,  /* n %: the feed override switch (0..150) */
  MRI_MODE,      /* axis the switch (MRM_*), n 1 on, 0 off */
  MRI_BREAK,     /* n: the breakpoint's block number, 0 none */
  MRI_ZERO,      /* v[]: the part zero, mm of each axis in the machine's order (NaN: keep) */
  MRI_KEY,       /* axis a panel key of the runtime's own (its edit keys), n its argument */
  MRI_NKIND
};
enum mrun_mode { MRM_SINGLE, MRM_SKIP, MRM_OPTSTOP };

struct mrun_input {
  int kind;                /* enum mrun_in */
  int axis, axis2;
  int64_t n, n2;
  double v[CANON_AXES];
};

/* A move the operator or a plugin made outside the program's calls (a jog,
 * a correction, a section move, teach-in, oscillation): the plot draws it
 * apart, the terminal's readouts follow it. */
enum mrun_move_kind { MRV_JOG, MRV_CORRECT, MRV_SECTION, MRV_TEACH, MRV_DISPLACE };
struct mrun_move {
  int kind;                /* enum mrun_move_kind */
  int axis;
  int64_t d;               /* counts; 0 with kind MRV_DISPLACE: a mark where it starts */
  int64_t pos[CANON_AXES]; /* where the axes are after it */
  double t;                /* simulated time */
};

/* The runtime's view of a panel for the terminal: its pages as grids of
 * characters (the 2С42-65's 16x32 screen; the 2У22's DG and DI). */
#define MRUN_PAGE_ROWS 24
#define MRUN_PAGE_COLS 40
struct mrun_page {
  int rows, cols;          /* used (at most the above) */
  uint32_t cell[MRUN_PAGE_ROWS][MRUN_PAGE_COLS];   /* characters (0: blank) */
  uint8_t attr[MRUN_PAGE_ROWS][MRUN_PAGE_COLS];    /* MRUN_A_* */
};
enum { MRUN_A_BOLD = 1, MRUN_A_REVERSE = 2, MRUN_A_DIM = 4 };
/* A page from UTF-8 text (lines ended by newlines; what does not fit is
 * cut at the page's edges), for a runtime that writes its page as text. */
void mrun_page_text(struct mrun_page *pg, const char *text, size_t len);

/* The Modbus map's source, filled by the runtime (contracts.md sec. 6:
 * what each dialect publishes). */
#define MRUN_MAP_REGS 128
struct mrun_view {
  int64_t pos[4];          /* input registers 10-17: four axes in counts (the runtime's choice) */
  int naxes;
  char axis_name[4];
  int nregs;               /* parameters published at 100.. and 600.. (R0..R<nregs-1>) */
  double reg[MRUN_MAP_REGS];
  int bits;                /* discrete inputs 5 and 6: MRUN_BIT_* */
  double feed;             /* the last block's contour speed, mm/min */
  int override_eff;        /* the feed override in effect, % (input register 5) */
};
enum { MRUN_BIT_SPINDLE = 1, MRUN_BIT_AUX = 2 };

/* Block results of the runtime's block() and resume(). */
enum { MRB_FAIL = -1, MRB_DONE = 0, MRB_STOP = 1, MRB_WAIT = 2 };

/* The dialect's runtime on the runner (program.runtime).  Its state -- the
 * machine and the modal state of the language -- lives in r->st (size
 * bytes, zeroed, then reset).  NULL members: the runtime has none. */
struct mrun_rt {
  size_t size;
  const char *machine;     /* its machine's name, for messages ("ВЗ-208Ф3") */
  int tool_table;          /* --tool is the machine's tool table (as --tools), not a plugin's model */
  /* every block comes back to the runtime (VM-alone runs list them all) */
  int every;
  /* a new cycle: the machine at power-on (r->st is zeroed first) */
  void (*reset)(struct mrun *r);
  /* before the first block (the plugins the program uses started): 0, or
   * -1 when the run must not start because of the command line (why says
   * so, *block the first block that needs what is missing) */
  int (*prepare)(struct mrun *r, char *why, size_t n, uint32_t *block);
  /* what the state holds outside r->st is freed (mrun_free) */
  void (*release)(struct mrun *r);
  /* the program ended (VM_EV_END); the run failed (VM_EV_ERROR) */
  void (*end)(struct mrun *r);
  void (*failed)(struct mrun *r);
  /* a new cycle after the end (Пуск after M02, the terminal's reset): the
   * machine stays where it is; reg holds the registers as they were (a
   * dialect that keeps its parameters copies them back).  NULL: reset */
  void (*renew)(struct mrun *r, const double *reg);
  /* is block b (index) one that block skip passes over ('/')? */
  int (*skippable)(const struct mrun *r, uint32_t b);
  /* a block is about to start (VM_EV_START: a watched block, every block
   * under single block, a breakpoint or cfg.starts) */
  void (*start)(struct mrun *r);
  /* VM_EV_BLOCK: the block's machine work, its words in r->vm.w: MRB_DONE;
   * MRB_STOP done, then a programmed stop; MRB_WAIT it waits for the
   * operator inside the block (mrun_wait said for what); MRB_FAIL it
   * failed (having called mrun_fail: nothing of the block stays). */
  int (*block)(struct mrun *r);
  /* An input while the machine waits inside a block (or, for JOG, CORRECT,
   * KEY, ZERO, between blocks): -1 it does not fit (why says so), 0 taken,
   * 1 taken and the wait is over (resume() goes on with the block). */
  int (*input)(struct mrun *r, const struct mrun_input *in, char *why, size_t n);
  /* the block goes on after its wait: as block() */
  int (*resume)(struct mrun *r);
  /* Would the runtime refuse this input outright (an action its machine
   * does not have: block skip on the 2С42-65, a part zero on the grinder)?
   * NULL: none refused; else the reason ("the 2С42-65 has no block skip"). */
  const char *(*refuses)(const struct mrun *r, const struct mrun_input *in);
  /* The feed override switch moved to pct while the host's clock is at
   * simulated time now (within the last block's move, or not): -1 refused
   * (M25: a warning says why), 0 taken, 1 taken and a MRW_FEED wait is
   * over, 2 taken and the move at `now` stands (0 %) until it rises.  The
   * seconds the move's end moved by go to *shift. */
  int (*override)(struct mrun *r, int pct, double now, double *shift);
  /* The switches the VM may take as they stand (vm.sw: a MACHS block whose
   * switches already stand so stays in the VM); 0: every MACHS yields */
  uint32_t (*switches)(const struct mrun *r);
  /* is block b a restart point (its start saves the restart snapshot)? */
  int (*restart_point)(const struct mrun *r, uint32_t b);
  /* The restart snapshot's blob: the runtime's state at a block's start
   * (its bytes into buf, at most cap; the length, or > cap when it does not
   * fit), and back: restore checks every field against the program and
   * its range (0, or -1 with err naming the field: snapshot.h's checker;
   * `shown` names the file). */
  size_t (*save)(const struct mrun *r, void *buf, size_t cap, char *err, size_t n);
  int (*restore)(struct mrun *r, const void *buf, size_t len, const char *shown, char *err, size_t n);
  /* What core checks the VM part of a snapshot against: the word that
   * makes a restart point ("M15"; NULL: a restart goes on at any block
   * start), register k's name and range (0: unused, it must be 0; whole:
   * a whole number), the most a repeat count may have left. */
  const char *restart_word;
  int (*reg_range)(const struct mrun *r, int k, char *name, size_t n, double *lo, double *hi, int *whole);
  uint32_t repeat_max;
  /* the JSON members of the block's row after seq n line depth (contracts.md sec. 8) */
  void (*row_json)(const struct mrun *r, FILE *out);
  /* the text trace's row after its sequence number ("%6llu ") */
  void (*row_text)(const struct mrun *r, FILE *out);
  /* the dump's "blocks" value (NULL: the count of blocks run) */
  void (*blocks_json)(const struct mrun *r, FILE *out);
  /* the dump's members after "status", "error", "blocks": "time", "pos"
   * and the machine's own; r may hold no program (p NULL): the machine at
   * power-on for a program that did not compile */
  void (*dump_json)(const struct mrun *r, FILE *out);
  /* the error object has the machine's own words ("machine") */
  int error_machine;
  /* the diagnostic's note with the machine's words, after this prefix
   * (Ukrainian, English); NULL: no note */
  const char *note_uk, *note_en;
  /* the simulated time, seconds */
  double (*time)(const struct mrun *r);
  /* a file the machine reads (what: "tools", "machine"): 0, or -1 with
   * "FILE:LINE:COL: message" in err, -2 when it reads no such file (err:
   * why, for "s42: PROGRAM: ...") */
  int (*load)(struct mrun *r, const char *what, const char *text, size_t len, const char *file, char *err,
              size_t nerr);
  /* The machine's pages, for a terminal and --screen: their names,
   * NULL-terminated, and page k as a grid. */
  const char *const *pages;
  void (*page)(const struct mrun *r, int k, struct mrun_page *pg);
  /* --screen: the machine's display as text lines on out */
  void (*screen)(const struct mrun *r, FILE *out);
  /* where the tool is, as the canonical records count it: counts of each axis */
  void (*position)(const struct mrun *r, int64_t pos[CANON_AXES]);
  /* the machine's description (kind, axes, units): canon_info */
  void (*info)(const struct mrun *r, struct canon_info *in);
  /* What the machine waits for, in words (English, for stderr): NULL the
   * runner's own for MRW_BLOCK and MRW_STOP */
  const char *(*wait_text)(const struct mrun *r, char *buf, size_t n);
  /* the Modbus map's source */
  void (*view)(const struct mrun *r, struct mrun_view *v);
  /* a message on the machine's own display (the run's error in its words) */
  void (*show)(struct mrun *r, const char *text);
  /* the operator sets parameter k to v from the panel (between blocks or
   * in a wait, journaled as the block's): 0, or -1 with why */
  int (*set_param)(struct mrun *r, int k, double v, char *why, size_t n);
};

/* What the host gets back and how it set the run up. */
struct mrun_config {
  int en;                                   /* English messages (else Ukrainian) */
  uint64_t max_blocks;                      /* E-LIMIT after that many blocks; 0 none */
  int rows;                                 /* MR_ROW after every block that ran */
  int every;                                /* a row even for a block with no machine work (a trace) */
  int starts;                               /* MR_START before every block */
  void *ctx;
  /* a warning the machine or the runtime raised (at the block's commit) */
  void (*warn)(void *ctx, const struct mrun *r, const char *msg);
  /* each canonical record of a committed block (--trace=canon, the plot) */
  void (*canon)(void *ctx, const struct canon_call *c);
  /* a move outside the program's calls, at once */
  void (*moved)(void *ctx, const struct mrun *r, const struct mrun_move *m);
  /* a line for the log (a plugin's note) */
  void (*log)(void *ctx, const struct mrun *r, const char *msg);
  const uint8_t *watch;                     /* per block: its start comes back (MR_START), or NULL */
  /* the restart snapshot: saved at every restart point's start when set
   * (a failed save ends the run with E-STATE) */
  const char *state_path;
  uint64_t prog_hash;                       /* the program text's (a snapshot is of one text) */
};

/* The open block's journal: the records its machine reported and the
 * warnings it raised, held until the block commits (then given to the
 * host: cfg.warn, then cfg.canon) and dropped when it fails.  It grows
 * with the block; running out of memory fails the block (E-LIMIT), it
 * never drops an entry.  A block that waits shows the operator what it did
 * up to the wait: the journal is released then, as a real machine cannot
 * take back a move it made before it stopped to wait. */
struct mrun_journal {
  struct canon_call *call;
  size_t ncall, capcall;
  char *text;                /* the warnings, each ended by a NUL */
  size_t ntext, captext;
  size_t nwarn;
  int oom;                   /* an entry did not fit in memory: the block fails */
};

struct mrun {
  const struct program *p;
  const struct mrun_rt *rt;
  struct mrun_config cfg;
  struct vm vm;
  void *st;                  /* the runtime's state */
  int state;                 /* enum mrun_ev of the last return */
  int wait;                  /* enum mrun_wait while state == MR_WAIT (and kept while stopped in a wait) */
  int single, skip, optstop; /* the operator's switches: single block, block skip, optional stop */
  int brk;                   /* the breakpoint: a block number that waits for Пуск before it starts, 0 none */
  int override;              /* the feed override switch, % (100 at first) */
  int go;                    /* the cycle's first block needs no Пуск of its own */
  uint64_t seq;              /* rows out */
  unsigned long saves;       /* restart snapshots saved in this cycle */
  int at_start;              /* the last return is a block's start (vm.cur): the next goes on there */
  int stop_after;            /* the row just out ends in a programmed stop */
  int resume;                /* a wait inside the block is over: resume() is due */
  int in_block;              /* the runtime is doing a block's work (the journal is open) */
  uint8_t *watch;            /* the host's watched blocks and the restart points, or NULL */
  struct mrun_journal jn;
};

/* 0; -1 when out of memory or the program needs more than the VM holds
 * (the run then fails with that error at once). */
int mrun_init(struct mrun *r, const struct program *p, const struct mrun_config *c);
void mrun_free(struct mrun *r);
enum mrun_ev mrun_run(struct mrun *r);
/* A new cycle of the same program from its first block (after the end,
 * an error or a stop): the VM afresh, the runtime's renew, the switches
 * kept. */
void mrun_renew(struct mrun *r);
/* The operator's input: 0 taken, -1 it does not fit what the machine does
 * now or the machine has no such thing (why says so). */
int mrun_input(struct mrun *r, const struct mrun_input *in, char *why, size_t n);
/* Shorthands of mrun_input. */
int mrun_pusk(struct mrun *r);
void mrun_stop(struct mrun *r);
/* Пуск after a stop (a client's feed hold): back to the block boundary or
 * the wait it interrupted.  0, or -1 when the cycle was not stopped. */
int mrun_resume(struct mrun *r);
/* The feed override moves to pct while the host's clock is at simulated
 * time now: the runtime's override() (-1 refused, 0, 1 a wait ended, 2 the
 * move stands), the move's end moved by *shift seconds. */
int mrun_override(struct mrun *r, int pct, double now, double *shift);

/* The operator sets parameter k to v from the panel, between blocks or
 * while the machine waits -- never within a block that runs: 0, or -1 with
 * why (the cycle is over, not one of the machine's parameters, out of
 * range).  A waiting block that fails afterwards takes it back. */
int mrun_set_param(struct mrun *r, int k, double v, char *why, size_t n);
/* A client (Modbus) writes R[r0 .. r0+n-1] while no block runs: stored as
 * they are, for this cycle and the next.  The caller checked the range and
 * the values against the view's nregs. */
void mrun_load_params(struct mrun *r, unsigned r0, unsigned n, const double *v);

/* For the runtime. */
/* The block waits for the operator inside it: the runtime returns MRB_WAIT. */
static inline int mrun_wait(struct mrun *r, int kind)
{
  r->wait = kind;
  return MRB_WAIT;
}
/* The runtime's block failed: roll it back, the run ends with that error. */
void mrun_fail(struct mrun *r, int code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* The run refused before its first block (a restart refused): the error is
 * at the program's first block, column 1; nothing ran. */
void mrun_refuse(struct mrun *r, int code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* A warning from the runtime or its machine, to the host: into the open
 * block's journal (at once between blocks). */
void mrun_warn(struct mrun *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* A note for the host's log (a plugin's), at once. */
void mrun_log(struct mrun *r, const char *msg);
/* Where the runtime's machine reports its records and warnings: the open
 * block's journal. */
struct canon_sink mrun_sink(struct mrun *r);
/* A move outside the program's calls, to the host at once. */
void mrun_moved(struct mrun *r, int kind, int axis, int64_t d, const int64_t pos[CANON_AXES], double t);

/* For the hosts. */
/* The block being run: its number as written (-1 none). */
int mrun_block_number(const struct mrun *r);
/* The run's error located in the text (MR_ERROR; or a refused run). */
void mrun_error(const struct mrun *r, struct s42_error *e);
/* What the machine waits for, in words (English, for stderr). */
const char *mrun_wait_text(const struct mrun *r, char *buf, size_t n);
/* The simulated time, s (0 without a runtime). */
double mrun_time(const struct mrun *r);
/* The row of the block that just ran, a JSON object on one line (no newline), and as text. */
void mrun_row_json(const struct mrun *r, FILE *out);
void mrun_row_text(const struct mrun *r, FILE *out);
/* The dump (contracts.md sec. 2 and 8), a line: status "end" | "error" |
 * "stopped", e the error or NULL. */
void mrun_dump(const struct mrun *r, FILE *out, const char *status, const struct s42_error *e);
/* The dump of a program that did not compile (e: its first error): the
 * machine rt drives, at power-on, nothing run. */
void mrun_dump_refused(const struct mrun_rt *rt, FILE *out, const struct s42_error *e, int en,
                       const struct program *p);
/* The machine's description (its kind and axes), or a machine of none. */
void mrun_info(const struct mrun *r, struct canon_info *in);

/* The restart snapshot (the VM's state at a block's start and the
 * runtime's blob), saved atomically: 0, or -1 with err. */
int mrun_save(struct mrun *r, const char *path, char *err, size_t n);
/* Go on from a snapshot of this program text: 0, or -1 with err (missing,
 * damaged, another program or version, a field that does not fit). */
int mrun_restore(struct mrun *r, const char *path, char *err, size_t n);
int mrun_restore_bytes(struct mrun *r, const void *data, size_t len, const char *shown, char *err, size_t n);
/* FNV-1a of a program text: the snapshot's program hash. */
uint64_t mrun_hash(const void *data, size_t n);

#endif
