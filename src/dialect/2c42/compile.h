/* The 2С42 compiler: text -> program (bytecode, block table, attributes),
 * with every static check of language.md and all diagnostics in one pass. */
#ifndef S42_COMPILE_H
#define S42_COMPILE_H

#include "diag.h"
#include "program.h"
#include <stddef.h>

/* Compile src (n bytes).  Diagnostics go to d.  Returns 0 when the program
 * can run (no errors), -1 otherwise (p still holds what was built). */
int comp_program(const char *src, size_t n, struct diag_list *d, struct program *p);
/* The same, knowing the functions of these plugins (src/core/plugin.h); with
 * NULL, every function the language leaves to a plugin is E-PLUGIN. */
struct plug_set;
int comp_program_with(const char *src, size_t n, struct diag_list *d, struct program *p,
                      const struct plug_set *plugins);

/* What every 2С42 program carries for the VM (comp_program sets it first):
 * the 2С42-65's limits in p->lim -- 8 nested sub calls, 2 arrays of 15
 * cells, parameters and cells within +-9999999, angles in 0.001 deg with
 * SI CO TG for |x| <= 2304000, ATG +-9999999, LO 0..9999999 -- its message
 * table (kpmsg.h) and F as the register saved across calls. */
#define KP_DEPTH 8
#define KP_ARRAYS 2
#define KP_CELLS 15
void comp_setup(struct program *p);

#endif
