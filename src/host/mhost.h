/* `s42 run` for a dialect on the neutral runner (src/core/mrun.h): the
 * headless run with its trace (text, JSON, canon), its dump and the
 * operator script (contracts.md secs. 3 and 8). */
#ifndef S42_MHOST_H
#define S42_MHOST_H

#include "diag.h"
#include "program.h"
#include <stdint.h>

struct canon_call;

struct mhost_opts {
  const char *program;          /* for messages */
  const char *operator_file;    /* --operator, or NULL */
  const char *tools;            /* --tools FILE (the machine's tool table), or NULL */
  int trace, json, canon, dump, en;
  uint64_t max_blocks;
  /* s42 plot: an observer of the run (lplot.c) -- where the tool starts
   * (mm as the canonical calls print them), each canonical call, how the
   * run ended; NULL members are not called */
  struct mhost_watch {
    void *ctx;
    void (*start)(void *ctx, const double pos[4]);
    void (*call)(void *ctx, const struct canon_call *c);
    void (*result)(void *ctx, const char *status, const char *code, int n);
  } watch;
};

/* The dump of a program that did not compile (e: its first error): the
 * machine rt drives, at power-on, nothing run. */
struct s42_error;
struct mrun_rt;
void mhost_dump_refused(const struct mrun_rt *rt, const struct s42_error *e);
/* Run p (compiled, d its diagnostics); the exit status of contracts.md sec. 1. */
int mhost_run(const struct mhost_opts *o, const struct program *p, const struct diag_list *d);

#endif
