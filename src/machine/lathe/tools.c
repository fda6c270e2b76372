/* The lathe's tool table, --tools FILE (src/machine/lathe/lathe.h):
 *
 *   ; a comment (to the end of the line, anywhere)
 *   T1  X -12.50  Z 40.00
 *   T2  Z 3
 *
 * One tool a line: T and its number 1..99 (leading zeros allowed), then X
 * and/or Z, each at most once, with its correction in mm (X as a
 * diameter): an optional sign, up to 4 digits, an optional point and up to
 * 3 decimals (a µm is the smallest step: more decimals are refused, never
 * rounded).  An axis not given is 0.  Letters in either case; spaces and
 * tabs between a letter and its number (`X -12.5`, `X-12.5`, `T 1`) but
 * not inside a number (`X - 5` is refused); CR LF line ends.  A tool given
 * twice, a NUL byte, anything else is an error.  The table replaces the
 * one before only when the whole text is good. */
#include "lathe.h"
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define INT_DIGITS 4   /* 9999.999 mm at most */
#define DEC_DIGITS 3

struct cur {
  const char *text;
  size_t len, i;
  unsigned line;
  size_t line_start;
  const char *file;
  char *err;
  size_t n;
};

static int at(const struct cur *c) { return c->i < c->len ? (unsigned char)c->text[c->i] : -1; }

/* The column of byte index i on its line: characters, counted as UTF-8
 * lead bytes, from 1. */
static unsigned col_of(const struct cur *c, size_t i)
{
  unsigned col = 1;
  for (size_t k = c->line_start; k < i && k < c->len; k++)
    if (((unsigned char)c->text[k] & 0xC0) != 0x80)
      col++;
  return col;
}

static int fail(const struct cur *c, size_t i, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail(const struct cur *c, size_t i, const char *fmt, ...)
{
  if (c->err && c->n) {
    char m[160];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(m, sizeof m, fmt, ap);
    va_end(ap);
    snprintf(c->err, c->n, "%s:%u:%u: %s", c->file, c->line, col_of(c, i), m);
  }
  return -1;
}

static void blanks(struct cur *c)
{
  while (at(c) == ' ' || at(c) == '\t' || (at(c) == '\r' && c->i + 1 < c->len && c->text[c->i + 1] == '\n'))
    c->i++;
}

/* At the end of a line's content: its end, the text's, or a comment. */
static int at_end(const struct cur *c)
{
  int ch = at(c);
  return ch < 0 || ch == '\n' || ch == ';';
}

static int is_digit(int ch) { return ch >= '0' && ch <= '9'; }
static int is_alpha(int ch) { return (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z'); }

/* What stands at i, for a message. */
static const char *shown(const struct cur *c, char *buf, size_t n)
{
  int ch = at(c);
  if (ch < 0 || ch == '\n')
    snprintf(buf, n, "the end of the line");
  else if (ch == '\r')
    snprintf(buf, n, "a carriage return");
  else if (ch >= 0x20 && ch < 0x7f)
    snprintf(buf, n, "'%c'", ch);
  else
    snprintf(buf, n, "byte 0x%02X", (unsigned)ch);
  return buf;
}

/* After a number: the line's end, a blank, or the next word's letter. */
static int number_ends(struct cur *c)
{
  int ch = at(c);
  if (at_end(c) || ch == ' ' || ch == '\t' || ch == '\r' || is_alpha(ch))
    return 0;
  char b[40];
  return fail(c, c->i, "unexpected %s after the number", shown(c, b, sizeof b));
}

/* The tool number: 1..99. */
static int tool_number(struct cur *c, int *t)
{
  blanks(c);
  size_t s = c->i;
  long v = 0;
  int digits = 0;
  while (is_digit(at(c))) {
    if (v < 1000)
      v = v * 10 + (at(c) - '0');
    digits++;
    c->i++;
  }
  if (!digits) {
    char b[40];
    return fail(c, c->i, "expected the tool's number after T, found %s", shown(c, b, sizeof b));
  }
  if (v < 1 || v > LATHE_TOOLS - 1)
    return fail(c, s, "tool number %s%ld: tools are T1..T%d", v >= 1000 ? "over " : "", v >= 1000 ? 999L : v,
                LATHE_TOOLS - 1);
  *t = (int)v;
  return number_ends(c);
}

/* A correction in mm into µm, exactly. */
static int correction(struct cur *c, char axis, int64_t *um)
{
  blanks(c);
  size_t s = c->i;
  int neg = 0;
  if (at(c) == '+' || at(c) == '-') {
    neg = at(c) == '-';
    c->i++;   /* the digits follow the sign at once */
  }
  int64_t whole = 0, frac = 0;
  int id = 0, fd = 0;
  while (is_digit(at(c))) {
    if (++id > INT_DIGITS)
      return fail(c, s, "%c correction over %d digits before the point: at most 9999.999 mm", axis, INT_DIGITS);
    whole = whole * 10 + (at(c) - '0');
    c->i++;
  }
  if (at(c) == '.') {
    c->i++;
    while (is_digit(at(c))) {
      if (++fd > DEC_DIGITS)
        return fail(c, s, "%c correction with more than %d decimals: the table is in whole µm", axis, DEC_DIGITS);
      frac = frac * 10 + (at(c) - '0');
      c->i++;
    }
  }
  if (!id && !fd) {
    char b[40];
    if (c->i != s)   /* a sign or a point alone */
      return fail(c, s, "expected digits in the %c correction", axis);
    return fail(c, s, "expected a number in mm after %c, found %s", axis, shown(c, b, sizeof b));
  }
  for (int k = fd; k < DEC_DIGITS; k++)
    frac *= 10;
  int64_t v = whole * 1000 + frac;
  *um = neg ? -v : v;
  return number_ends(c);
}

int lathe_tools_parse(struct lathe *l, const char *text, size_t len, const char *file, char *err, size_t n)
{
  struct lathe_tool tab[LATHE_TOOLS];
  unsigned first[LATHE_TOOLS];
  memset(tab, 0, sizeof tab);
  memset(first, 0, sizeof first);
  struct cur c = {text ? text : "", text ? len : 0, 0, 1, 0, file ? file : "-", err, n};
  if (err && n)
    err[0] = 0;
  const char *nul = c.len ? memchr(c.text, 0, c.len) : NULL;
  if (nul) {
    /* its line and column */
    for (size_t k = 0; k < (size_t)(nul - c.text); k++)
      if (c.text[k] == '\n') {
        c.line++;
        c.line_start = k + 1;
      }
    return fail(&c, (size_t)(nul - c.text), "a NUL byte: not a tool table");
  }
  while (c.i < c.len) {
    blanks(&c);
    if (!at_end(&c)) {
      size_t s = c.i;
      if (at(&c) != 'T' && at(&c) != 't') {
        char b[40];
        return fail(&c, s, "expected T<n> X <mm> Z <mm>, found %s", shown(&c, b, sizeof b));
      }
      c.i++;
      int t = 0;
      if (tool_number(&c, &t))
        return -1;
      if (tab[t].has)
        return fail(&c, s, "T%d given twice (first on line %u)", t, first[t]);
      int seen[2] = {0, 0};
      int64_t d[2] = {0, 0};
      for (;;) {
        blanks(&c);
        if (at_end(&c))
          break;
        int ch = at(&c);
        int a = ch == 'X' || ch == 'x' ? LX : ch == 'Z' || ch == 'z' ? LZ : -1;
        if (a < 0) {
          char b[40];
          return fail(&c, c.i, "expected X or Z, found %s", shown(&c, b, sizeof b));
        }
        if (seen[a])
          return fail(&c, c.i, "%c given twice for T%d", a == LX ? 'X' : 'Z', t);
        seen[a] = 1;
        c.i++;
        if (correction(&c, a == LX ? 'X' : 'Z', &d[a]))
          return -1;
      }
      tab[t].has = 1;
      tab[t].d[LX] = d[LX];
      tab[t].d[LZ] = d[LZ];
      first[t] = c.line;
    }
    /* the rest of the line: a comment, then its end */
    if (at(&c) == ';')
      while (c.i < c.len && c.text[c.i] != '\n')
        c.i++;
    if (c.i < c.len) {
      if (c.text[c.i] != '\n') {
        char b[40];
        return fail(&c, c.i, "unexpected %s", shown(&c, b, sizeof b));
      }
      c.i++;
      c.line++;
      c.line_start = c.i;
    }
  }
  memcpy(l->tools, tab, sizeof tab);
  return 0;
}
