/* The dialects: one front end each (src/dialect/NAME/), found by name
 * (--dialect) or by the program file's extension.  The list is generated
 * by the build from the dialects' module.mk files (each appends its name
 * to DIALECTS): no table here is edited by hand to add one. */
#ifndef S42_DIALECT_H
#define S42_DIALECT_H

#include "diag.h"
#include "program.h"
#include <stddef.h>

struct plug_set;

struct dialect {
  const char *name;        /* "2c42": --dialect, s42 dialects */
  const char *ext;         /* ".kp": the file extension that chooses it */
  const char *controller;  /* "2С42-65", as the seeds name it */
  const char *machine;     /* the machine model it drives ("grinder"; "none") */
  /* Compile src (n bytes) into p with diagnostics in d: 0 when it can run,
   * -1 when it has errors.  plugins: the plugin functions known (may be
   * NULL where the dialect has none). */
  int (*compile)(const char *src, size_t n, struct diag_list *d, struct program *p, const struct plug_set *plugins);
  /* How its programs run (enum dialect_run). */
  int run;
  /* DIALECT_RUN_MACHINE: the runtime its programs carry (a struct
   * mrun_rt), for the machine at power-on when a program does not compile
   * (the dump of a check-time error); NULL otherwise */
  const void *runtime;
};

enum dialect_run {
  /* blocks run on the VM alone against no machine (its registers, jumps
   * and calls; the dump's pos is empty) */
  DIALECT_RUN_VM,
  /* the 2С42 runtime runs it (the session: dialogs, the grinder, the
   * panel, plugins) */
  DIALECT_RUN_SESSION,
  /* the neutral runner (src/core/mrun.h) with the dialect's runtime and
   * machine (program.runtime is a struct mrun_rt) */
  DIALECT_RUN_MACHINE
};

/* The registered dialects, NULL-terminated, in the order the build lists them. */
extern const struct dialect *const dialect_list[];
/* By name, or NULL. */
const struct dialect *dialect_by_name(const char *name);
/* By the file's extension; a file whose extension no dialect claims is the
 * 2С42's (contracts.md sec. 8). */
const struct dialect *dialect_by_file(const char *path);
/* The names, comma-separated, for a message ("2c42, fixture"). */
void dialect_names(char *buf, size_t n);

#endif
