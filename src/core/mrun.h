/* The neutral runner: a program of a dialect run on the VM against the
 * machine its runtime drives (the 2У22 on the lathe; a dialect whose
 * registry entry says DIALECT_RUN_MACHINE).  It steps the VM, keeps the
 * operator's waits and switches (single block, block skip, optional stop),
 * the block budget and the trace rows; the dialect's runtime (struct
 * mrun_rt, from program.runtime) does each block's machine work through
 * its machine's canonical calls and says how the block, the machine and
 * the dump read in JSON.  mrun_run never blocks: it returns when the host
 * must act (a row, a wait, the end, an error).  It knows no language and no
 * machine. */
#ifndef S42_MRUN_H
#define S42_MRUN_H

#include "canon.h"
#include "program.h"
#include "vm.h"
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

struct mrun;

enum mrun_ev {
  MR_ROW,        /* a block ran: its row can be read (mrun_row_json) */
  MR_WAIT,       /* the machine waits for Пуск (r->wait says why) */
  MR_END,        /* the program ended */
  MR_ERROR,      /* the run failed (mrun_error): the block was rolled back */
  MR_STOPPED     /* the operator stopped the cycle (key STOP) */
};

enum mrun_wait {
  MRW_NONE,
  MRW_STOP,      /* a programmed stop after the block (M00; M01 with optional stop on) */
  MRW_BLOCK      /* single block: the next block waits for Пуск before it starts */
};

/* The dialect's runtime on the runner (program.runtime of a
 * DIALECT_RUN_MACHINE program).  Its state -- the machine and the modal
 * state of the language -- lives in r->st (size bytes, zeroed, then reset). */
struct mrun_rt {
  size_t size;
  /* a new cycle: the machine at power-on (r->st is zeroed first) */
  void (*reset)(struct mrun *r);
  /* is block b (index) one that block skip passes over ('/')? */
  int (*skippable)(const struct mrun *r, uint32_t b);
  /* VM_EV_BLOCK: the block's machine work, its words in r->vm.w.  0 done;
   * 1 done, then a programmed stop (M00, or M01 while r->optstop); -1 it
   * failed (having called mrun_fail: nothing of the block stays). */
  int (*block)(struct mrun *r);
  /* the JSON members of the block's row after seq n line depth: "motion",
   * "pos", "feed", "t" and the dialect's own (contracts.md sec. 8) */
  void (*row_json)(const struct mrun *r, FILE *out);
  /* the text trace's row after the block's name and line */
  void (*row_text)(const struct mrun *r, FILE *out);
  /* the dump's members after "status", "error", "blocks": "time", "pos"
   * and the machine's own */
  void (*dump_json)(const struct mrun *r, FILE *out);
  /* the operator's `zero X <mm> Z <mm>` (the part zero, values in mm in
   * the machine's axis order; NaN: keep that axis): 0, or -1 with why */
  int (*zero)(struct mrun *r, const double *mm, int n, char *why, size_t nwhy);
  /* the simulated time, seconds */
  double (*time)(const struct mrun *r);
  /* a file the machine reads (what: "tools", the --tools table): 0, or -1
   * with "FILE:LINE:COL: message" in err */
  int (*load)(struct mrun *r, const char *what, const char *text, size_t len, const char *file, char *err,
              size_t nerr);
  /* a new cycle after the end (Пуск after M02, the terminal's reset): the
   * machine stays where it is, the language's state is at power-on; NULL:
   * reset */
  void (*renew)(struct mrun *r);
  /* The machine's display pages (the 2У22's DG and DI), for a terminal:
   * their names, NULL-terminated, and page k's text -- lines of at most
   * MRUN_PAGE_COLS columns, UTF-8, each ended by a newline. */
  const char *const *pages;
  void (*page)(const struct mrun *r, int k, FILE *out);
  /* where the tool is, as the canonical calls print it: mm (deg) of X Y Z
   * A, a lathe's X its radius (a plot's starting point) */
  void (*position)(const struct mrun *r, double pos[4]);
};

#define MRUN_PAGE_COLS 40

/* What the host gets back and how it set the run up. */
struct mrun_config {
  int en;                                   /* English messages (else Ukrainian) */
  uint64_t max_blocks;                      /* E-LIMIT after that many blocks; 0 none */
  void *ctx;
  /* a warning the machine or the runtime raised */
  void (*warn)(void *ctx, const struct mrun *r, const char *msg);
  /* each canonical call of the machine (--trace=canon), or NULL */
  void (*canon)(void *ctx, const struct canon_call *c);
  const uint8_t *watch;                     /* per block: its start comes back (MR_WAIT with
                                               MRW_NONE: an `at`), or NULL */
};

/* The open block's journal: the records its machine reported and the
 * warnings it raised, in order, held until the block commits (then given
 * to the host: cfg.warn, then cfg.canon) and dropped when it fails.  It
 * grows with the block; running out of memory fails the block (E-LIMIT),
 * it never drops an entry. */
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
  int wait;                  /* enum mrun_wait while state == MR_WAIT */
  int at_start;              /* the last MR_WAIT is a watched block's start (vm.cur) */
  int single, skip, optstop; /* the operator's switches: П/АВТ, U/, ST */
  int go;                    /* the cycle's first block needs no Пуск of its own */
  int stop_after;            /* the row just out ends in a programmed stop */
  uint64_t seq;              /* rows out */
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
/* Пуск: ends a wait (0), or -1 when nothing waits for it. */
int mrun_pusk(struct mrun *r);
/* Стоп: the cycle stops (MR_STOPPED at the next mrun_run). */
void mrun_stop(struct mrun *r);
/* The runtime's block failed: roll it back, the run ends with that error. */
void mrun_fail(struct mrun *r, int code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* A warning from the runtime or its machine, to the host: into the open
 * block's journal. */
void mrun_warn(struct mrun *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Where the runtime's machine reports its records and warnings: the open
 * block's journal. */
struct canon_sink mrun_sink(struct mrun *r);
/* The block being run: its number as written (-1 none). */
int mrun_block_number(const struct mrun *r);
/* The row of the block that just ran, a JSON object on one line (no newline). */
void mrun_row_json(const struct mrun *r, FILE *out);
void mrun_row_text(const struct mrun *r, FILE *out);

#endif
