/* Diagnostic list (src/core/diag.h). */
#include "diag.h"
#include "errors.h"
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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

const char *diag_block(int n, char buf[16])
{
  if (n > 0)
    snprintf(buf, 16, "N%d", n);
  else
    snprintf(buf, 16, "N-");
  return buf;
}

static void print_head(FILE *f, const char *file, const struct diag *g, int color)
{
  static const char *const sev[] = {"error", "warning", "note"};
  static const char *const sgr[] = {"\033[1;31m", "\033[1;35m", "\033[1;36m"};
  char nb[16];
  if (g->number >= 0)
    snprintf(nb, sizeof nb, "N%d", g->number);
  else
    strcpy(nb, "N-");
  int s = g->sev >= 0 && g->sev <= 2 ? g->sev : 0;
  fprintf(f, "%s:%u:%u: %s%s%s: %s: %s", file ? file : "-", g->line, g->col, color ? sgr[s] : "", sev[s],
          color ? "\033[0m" : "", nb, g->msg);
  if (g->code)
    fprintf(f, " [%s]", err_code(g->code));
  fputc('\n', f);
}

void diag_print_one(FILE *f, const char *file, const struct diag *g)
{
  print_head(f, file, g, 0);
}

/* Where lines start, as the lexer reads them: LF ends a line, and so does a
 * CR that no LF follows (CR LF is one line end). */
struct cursor { const char *s; size_t n, pos; unsigned line; };

static int eol_at(const struct cursor *c, size_t p, size_t *len)
{
  if (c->s[p] == '\n') { *len = 1; return 1; }
  if (c->s[p] == '\r') {
    if (p + 1 < c->n && c->s[p + 1] == '\n') { *len = 2; return 1; }
    *len = 1;
    return 1;
  }
  return 0;
}

/* Move the cursor to the start of `line` (forward only); 0 when the text
 * has no such line. */
static int seek_line(struct cursor *c, unsigned line)
{
  size_t len;
  while (c->line < line) {
    while (c->pos < c->n && !eol_at(c, c->pos, &len))
      c->pos++;
    if (c->pos >= c->n)
      return 0;
    c->pos += len;
    c->line++;
  }
  return c->line == line;
}

/* The length in bytes of the UTF-8 sequence at p, 0 when invalid. */
static size_t u8len(const unsigned char *p, size_t left)
{
  unsigned char b = p[0];
  size_t k = b < 0x80 ? 1 : (b & 0xE0) == 0xC0 ? 2 : (b & 0xF0) == 0xE0 ? 3 : (b & 0xF8) == 0xF0 ? 4 : 0;
  if (k == 0 || k > left)
    return 0;
  for (size_t i = 1; i < k; i++)
    if ((p[i] & 0xC0) != 0x80)
      return 0;
  return k;
}

#define SHOW_COLS 100   /* a longer line is shown as a window round the column */

/* The source line at the cursor and a caret under column col (columns
 * count characters); what cannot be shown as it is (control characters,
 * bytes that are not UTF-8) shows as '?'. */
static void print_source(FILE *f, const struct cursor *c, unsigned col, int color)
{
  const unsigned char *s = (const unsigned char *)c->s;
  size_t p = c->pos, len;
  unsigned first = col > SHOW_COLS / 2 ? col - SHOW_COLS / 2 : 1, k = 1;
  /* skip to the window's first character */
  while (p < c->n && !eol_at(c, p, &len) && k < first) {
    size_t u = u8len(s + p, c->n - p);
    p += u ? u : 1;
    k++;
  }
  char line[SHOW_COLS * 4 + 8], mark[SHOW_COLS + 8];
  size_t nl = 0, nm = 0;
  if (first > 1)
    nl += (size_t)snprintf(line, sizeof line, "...");
  for (; p < c->n && !eol_at(c, p, &len) && k < first + SHOW_COLS; k++) {
    size_t u = u8len(s + p, c->n - p);
    int tab = s[p] == '\t';
    if (u == 1 && (s[p] < 0x20 || s[p] == 0x7F) && !tab)
      u = 0;
    if (u) {
      memcpy(line + nl, s + p, u);
      nl += u;
      p += u;
    } else {
      line[nl++] = '?';
      p++;
    }
    if (k < col)
      mark[nm++] = tab ? '\t' : ' ';
  }
  int more = p < c->n && !eol_at(c, p, &len);
  if (more)
    nl += (size_t)snprintf(line + nl, sizeof line - nl, "...");
  line[nl] = 0;
  mark[nm] = 0;
  if (col > k)
    return;   /* the column is past the shown part of the line */
  fprintf(f, "%5u | %s\n      | %s%s%s\n", c->line, line, first > 1 ? "   " : "", mark,
          color ? "\033[1;32m^\033[0m" : "^");
}

static void print_in(FILE *f, const struct diag_list *d, const struct diag *g, struct cursor *c)
{
  print_head(f, d->file, g, d->color);
  if (d->src && g->line > 0 && g->col > 0) {
    if (c->line > g->line) {   /* out of order: from the start again */
      c->pos = 0;
      c->line = 1;
    }
    if (seek_line(c, g->line))
      print_source(f, c, g->col, d->color);
  }
}

static void cursor_init(struct cursor *c, const struct diag_list *d)
{
  c->s = d->src;
  c->n = d->nsrc;
  c->pos = d->src && d->nsrc >= 3 && memcmp(d->src, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;   /* not the byte-order mark */
  c->line = 1;
}

void diag_print_in(FILE *f, const struct diag_list *d, const struct diag *g)
{
  struct cursor c;
  cursor_init(&c, d);
  print_in(f, d, g, &c);
}

void diag_print(FILE *f, const struct diag_list *d)
{
  struct cursor c;
  cursor_init(&c, d);
  for (size_t i = 0; i < d->n; i++)
    print_in(f, d, &d->v[i], &c);
  if (d->dropped)
    fprintf(f, "%s: note: %zu more diagnostics not shown\n", d->file ? d->file : "-", d->dropped);
}

int diag_want_color(FILE *f)
{
  const char *nc = getenv("NO_COLOR"), *term = getenv("TERM");
  return isatty(fileno(f)) && !(nc && *nc) && !(term && strcmp(term, "dumb") == 0);
}
