/* Diagnostic list (src/diag.h). */
#include "diag.h"
#include "errors.h"
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

void diag_init(struct diag_list *d, const char *file)
{
  memset(d, 0, sizeof *d);
  d->file = file;
}

void diag_free(struct diag_list *d)
{
  free(d->v);
  d->v = NULL;
  d->n = d->cap = 0;
}

void diag_add(struct diag_list *d, int sev, int code, unsigned line, unsigned col, int number,
              const char *fmt, ...)
{
  if (sev == DIAG_ERROR)
    d->nerr++;
  else if (sev == DIAG_WARNING)
    d->nwarn++;
  if (d->n >= DIAG_KEEP) {
    d->dropped++;
    return;
  }
  if (d->n == d->cap) {
    size_t nc = d->cap ? d->cap * 2 : 16;
    struct diag *v = realloc(d->v, nc * sizeof *v);
    if (!v) {
      d->dropped++;
      return;
    }
    d->v = v;
    d->cap = nc;
  }
  struct diag *g = &d->v[d->n++];
  g->sev = sev;
  g->code = code;
  g->line = line;
  g->col = col;
  g->number = number;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(g->msg, sizeof g->msg, fmt, ap);
  va_end(ap);
}

void diag_sort(struct diag_list *d)
{
  /* A stable insertion sort of indices: diagnostics arrive nearly in
   * order, and ties keep the order they were found in. */
  size_t n = d->n;
  if (n < 2)
    return;
  struct diag *tmp = malloc(n * sizeof *tmp);
  size_t *idx = malloc(n * sizeof *idx);
  if (!tmp || !idx) {
    free(tmp);
    free(idx);
    return;
  }
  memcpy(tmp, d->v, n * sizeof *tmp);
  for (size_t i = 0; i < n; i++)
    idx[i] = i;
  for (size_t i = 1; i < n; i++) {
    size_t v = idx[i], j = i;
    while (j > 0 && (tmp[idx[j - 1]].line > tmp[v].line ||
                     (tmp[idx[j - 1]].line == tmp[v].line && tmp[idx[j - 1]].col > tmp[v].col))) {
      idx[j] = idx[j - 1];
      j--;
    }
    idx[j] = v;
  }
  for (size_t i = 0; i < n; i++)
    d->v[i] = tmp[idx[i]];
  free(tmp);
  free(idx);
}

const struct diag *diag_first_error(const struct diag_list *d)
{
  for (size_t i = 0; i < d->n; i++)
    if (d->v[i].sev == DIAG_ERROR)
      return &d->v[i];
  return NULL;
}

void diag_print_one(FILE *f, const char *file, const struct diag *g)
{
  static const char *const sev[] = {"error", "warning", "note"};
  char nb[16];
  if (g->number >= 0)
    snprintf(nb, sizeof nb, "N%d", g->number);
  else
    strcpy(nb, "N-");
  fprintf(f, "%s:%u:%u: %s: %s: %s", file ? file : "-", g->line, g->col, sev[g->sev], nb, g->msg);
  if (g->code)
    fprintf(f, " [%s]", err_code(g->code));
  fputc('\n', f);
}

void diag_print(FILE *f, const struct diag_list *d)
{
  for (size_t i = 0; i < d->n; i++)
    diag_print_one(f, d->file, &d->v[i]);
  if (d->dropped)
    fprintf(f, "%s: note: %zu more diagnostics not shown\n", d->file ? d->file : "-", d->dropped);
}
