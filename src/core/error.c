/* The one error record (src/core/error.h). */
#include "error.h"
#include "errors.h"
#include "report.h"
#include <stdio.h>
#include <string.h>

void s42_error_of_diag(struct s42_error *e, const struct diag *g)
{
  memset(e, 0, sizeof *e);
  e->code = g ? g->code : S42_E_SYNTAX;
  e->number = g ? g->number : -1;
  e->line = g ? g->line : 0;
  e->col = g ? g->col : 0;
  snprintf(e->msg, sizeof e->msg, "%s", g ? g->msg : "");
}

void s42_error_diag(const struct s42_error *e, struct diag *g)
{
  memset(g, 0, sizeof *g);
  g->sev = DIAG_ERROR;
  g->code = e->code;
  g->line = e->line;
  g->col = e->col;
  g->number = e->number;
  snprintf(g->msg, sizeof g->msg, "%.*s", (int)sizeof g->msg - 1, e->msg);
}

void s42_error_machine(const struct s42_error *e, const struct program *p, int en, char *buf, size_t n)
{
  report_machine_msg(buf, n, p, e->code, e->number, e->aux, en);
}
