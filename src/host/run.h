/* `s42 run` (and the run under `s42 plot`): the one headless host, for
 * every dialect.  It steps the runner (src/core/mrun.h), takes the operator
 * script's actions as the runner's input records, prints the trace (text,
 * JSON, canon), the dump and the machine's screen, paces the run at
 * machine speed, serves it over Modbus, and hands what the machine did to
 * a watcher (the plot).  It knows no language and no machine: what
 * differs comes from the runtime the program carries. */
#ifndef S42_RUN_H
#define S42_RUN_H

#include "diag.h"
#include "program.h"
#include <stddef.h>
#include <stdint.h>

struct canon_call;
struct mrun;
struct mrun_move;
struct mb_opts;

/* A watcher of the run (the plot): NULL members are not called. */
struct run_watch {
  void *ctx;
  /* the run starts: the machine is set up (its kind, where the tool is) */
  void (*start)(void *ctx, const struct mrun *r);
  /* each canonical record of a committed block, each move outside them,
   * each row (a block ran) */
  void (*call)(void *ctx, const struct canon_call *c);
  void (*moved)(void *ctx, const struct mrun *r, const struct mrun_move *m);
  void (*row)(void *ctx, const struct mrun *r);
  /* how it ended: status 0 end, 1 program error, 3 stopped (stop: how,
   * enum run_stop); code, n, line: the error's (NULL, -1, 0 none) */
  void (*result)(void *ctx, const struct mrun *r, int status, const char *code, int n, unsigned line, int stop);
};

/* How a run stopped (status 3): Стоп (the key STOP), the operator script
 * had nothing that fits what the machine waits for, or otherwise (a
 * signal under --realtime). */
enum run_stop { RUN_STOP_OTHER, RUN_STOP_KEY, RUN_STOP_SCRIPT };

struct run_opts {
  const char *program;          /* its path, for messages and the restart state's default name */
  const char *operator_file;    /* --operator, or NULL */
  const char *tools;            /* --tools / a lathe's --tool: the machine's tool table, or NULL */
  const char *machine;          /* --machine FILE, or NULL */
  const char *state;            /* --state FILE, or NULL */
  int trace, json, canon, dump, screen, restart, realtime, en;
  uint64_t max_blocks;
  const struct mb_opts *mb;     /* --modbus, or NULL */
  const struct run_watch *watch;
};

/* Run p (compiled from src, n bytes; d its diagnostics): the exit status
 * of contracts.md sec. 1. */
int run_headless(const struct run_opts *o, const struct program *p, const struct diag_list *d, const char *src,
                 size_t n);
/* The dump of a program that did not compile (e: its first error), in the
 * format of the dialect whose runtime is rt (NULL: none). */
struct s42_error;
void run_dump_refused(const void *rt, const struct program *p, const struct s42_error *e, int en);

#endif
