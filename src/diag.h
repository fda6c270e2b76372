/* Diagnostics: every error, warning and note of a compile or a run, with
 * file, line, column and block number, printed as
 *   FILE:LINE:COL: error|warning|note: N<n>: MESSAGE [E-CODE]          */
#ifndef S42_DIAG_H
#define S42_DIAG_H

#include <stddef.h>
#include <stdio.h>

enum diag_sev { DIAG_ERROR, DIAG_WARNING, DIAG_NOTE };

#define DIAG_KEEP 1000     /* diagnostics kept; more are counted, not stored */

struct diag {
  int sev, code;           /* code: vm/errors.h, 0 for plain warnings/notes */
  unsigned line, col;
  int number;              /* block number, -1 for a block without one */
  char msg[240];
};

struct diag_list {
  struct diag *v;
  size_t n, cap;
  size_t nerr, nwarn, dropped;
  const char *file;
};

void diag_init(struct diag_list *d, const char *file);
void diag_free(struct diag_list *d);
void diag_add(struct diag_list *d, int sev, int code, unsigned line, unsigned col, int number,
              const char *fmt, ...) __attribute__((format(printf, 7, 8)));
/* Sort by position (stable), so the first error in text order comes first. */
void diag_sort(struct diag_list *d);
const struct diag *diag_first_error(const struct diag_list *d);
void diag_print_one(FILE *f, const char *file, const struct diag *g);
void diag_print(FILE *f, const struct diag_list *d);

#endif
