/* Diagnostics: every error, warning and note of a compile or a run, with
 * file, line, column and block number, printed as
 *   FILE:LINE:COL: error|warning|note: N<n>: MESSAGE [E-CODE]
 * and, when the program text is known, its source line with a caret under
 * the column, as gcc and rustc print them:
 *       3 | №3 G02 G17 X+100 Z+5 ^
 *         |                  ^                                           */
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
  const char *src;         /* the program text, for the source lines (not owned), or NULL */
  size_t nsrc;
  int color;               /* colour the severities (a terminal, and no NO_COLOR) */
  int oom;                 /* the compile ran out of memory: not the program's fault (exit 4) */
};

void diag_init(struct diag_list *d, const char *file);
void diag_free(struct diag_list *d);
void diag_add(struct diag_list *d, int sev, int code, unsigned line, unsigned col, int number,
              const char *fmt, ...) __attribute__((format(printf, 7, 8)));
/* A block as the messages name it: "N12", or "N-" for none (n <= 0); buf
 * holds 16 bytes. */
const char *diag_block(int n, char buf[16]);
/* Sort by position (stable), so the first error in text order comes first. */
void diag_sort(struct diag_list *d);
const struct diag *diag_first_error(const struct diag_list *d);
void diag_print_one(FILE *f, const char *file, const struct diag *g);
/* One diagnostic with d's file, source line and colour (a run-time error). */
void diag_print_in(FILE *f, const struct diag_list *d, const struct diag *g);
void diag_print(FILE *f, const struct diag_list *d);
/* Should diagnostics on this stream be coloured: a terminal, NO_COLOR
 * unset or empty (no-color.org), TERM not "dumb". */
int diag_want_color(FILE *f);

#endif
