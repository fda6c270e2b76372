/* One error record for every boundary: a compile's first error, the VM's
 * run-time error, a run the host refused or failed -- as the dump, the
 * diagnostics on stderr, the terminal's message line and the machine's
 * screen all show it.  The VM raises a code and a message at a block
 * (struct vm_error); the record locates it in the text once. */
#ifndef S42_ERROR_H
#define S42_ERROR_H

#include "diag.h"
#include <stddef.h>

struct s42_error {
  int code;            /* vm/errors.h */
  int number;          /* the block's number, -1 none */
  unsigned line, col;  /* where, in the program text */
  int aux;             /* code-specific: the array of E-ARRAY+/- */
  char msg[520];
};

/* From a diagnostic (a compile's first error). */
void s42_error_of_diag(struct s42_error *e, const struct diag *g);
/* As a diagnostic, to print with diag_print_in. */
void s42_error_diag(const struct s42_error *e, struct diag *g);
/* The machine's own message, in the texts of program p (its dialect's;
 * NULL: the VM's neutral ones): "помилка в КП №5: ділення на нуль". */
struct program;
void s42_error_machine(const struct s42_error *e, const struct program *p, int en, char *buf, size_t n);

#endif
