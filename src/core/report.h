/* Trace rows and the final dump, as text and JSON (contracts.md section 2).
 * Numbers are printed in the C locale with fixed formats. */
#ifndef S42_REPORT_H
#define S42_REPORT_H

#include "diag.h"
#include "session.h"
#include <stdio.h>

struct trace_ctx {
  FILE *out;
  int json;
};

void report_row(void *ctx, const struct session *s, const struct sess_row *r);
void json_string(FILE *f, const char *s);
void json_num(FILE *f, double v);

/* The dump: status "end" | "error" | "stopped".  s may be NULL when the
 * program did not compile (err then names the first check-time error);
 * err NULL: "error":null.  en: the machine message's language. */
struct s42_error;
void report_dump(FILE *f, const char *status, const struct s42_error *err, const struct program *p, int en,
                 const struct session *s);
/* The machine's message for an error, in the texts of program p (its
 * dialect's table, vm/msgs.h; NULL: the VM's neutral ones): the 2С42-65's
 * "помилка в КП №n: ..." (number <= 0: "-"). */
void report_machine_msg(char *buf, size_t n, const struct program *p, int code, int number, int aux, int en);

#endif
