/* The 2С42's trace rows and final dump, as text and JSON (contracts.md
 * section 2).  Numbers are printed in the C locale with fixed formats
 * (src/core/report.h). */
#ifndef S42_KPREPORT_H
#define S42_KPREPORT_H

#include "diag.h"
#include "report.h"
#include "session.h"
#include <stdio.h>

struct trace_ctx {
  FILE *out;
  int json;
};

void report_row(void *ctx, const struct session *s, const struct sess_row *r);

/* The dump: status "end" | "error" | "stopped".  s may be NULL when the
 * program did not compile (err then names the first check-time error);
 * err NULL: "error":null.  en: the machine message's language. */
struct s42_error;
void report_dump(FILE *f, const char *status, const struct s42_error *err, const struct program *p, int en,
                 const struct session *s);

#endif
