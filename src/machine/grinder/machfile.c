/* The machine file of --machine (src/machine/grinder/machfile.h). */
#include "machfile.h"
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TRAVEL_MAX_MM 100000.0   /* 100 m: anything larger is a typing mistake */

/* A number in mm (deg for A): an optional sign, digits, an optional decimal
 * point; 0 with *v, -1 when there is none at *p. */
static int num(const char **p, double *v)
{
  const char *s = *p;
  char *end;
  if (!(isdigit((unsigned char)*s) || ((*s == '-' || *s == '+') && (isdigit((unsigned char)s[1]) || s[1] == '.')) ||
        (*s == '.' && isdigit((unsigned char)s[1]))))
    return -1;
  *v = strtod(s, &end);
  if (end == s || !isfinite(*v))
    return -1;
  *p = end;
  return 0;
}

static void skip(const char **p)
{
  while (**p == ' ' || **p == '\t')
    (*p)++;
}

int machfile_parse(const char *text, size_t n, const char *file, struct mach_travel *t, FILE *err)
{
  memset(t, 0, sizeof *t);
  int bad = 0, seen[4] = {0};
  unsigned line = 0;
  for (size_t i = 0; i < n;) {
    size_t e = i;
    while (e < n && text[e] != '\n' && text[e] != '\r')
      e++;
    line++;
    char buf[256];
    size_t len = e - i;
    int toolong = len >= sizeof buf;
    memcpy(buf, text + i, toolong ? sizeof buf - 1 : len);
    buf[toolong ? sizeof buf - 1 : len] = 0;
    i = e + (e < n && text[e] == '\r' && e + 1 < n && text[e + 1] == '\n' ? 2 : e < n ? 1 : 0);
    if (memchr(text + (e - len), 0, len)) {
      fprintf(err, "%s:%u:1: error: a NUL byte: not a machine file\n", file, line);
      bad = 1;
      continue;
    }
    char *c = strchr(buf, ';');
    if (c)
      *c = 0;
    const char *p = buf;
    skip(&p);
    if (!*p)
      continue;
    if (toolong) {
      fprintf(err, "%s:%u:1: error: a line over %zu characters\n", file, line, sizeof buf - 1);
      bad = 1;
      continue;
    }
    const char *start = p;
    if (strncmp(p, "travel", 6) != 0 || (p[6] != ' ' && p[6] != '\t')) {
      fprintf(err, "%s:%u:%u: error: expected `travel AXIS = MIN .. MAX` (the only key of a machine file)\n", file,
              line, (unsigned)(p - buf) + 1);
      bad = 1;
      continue;
    }
    p += 6;
    skip(&p);
    int ax = *p == 'x' || *p == 'X' ? 0 : *p == 'y' || *p == 'Y' ? 1 : *p == 'z' || *p == 'Z' ? 2
           : *p == 'a' || *p == 'A' ? 3 : -1;
    if (ax < 0 || (p[1] != ' ' && p[1] != '\t' && p[1] != '=')) {
      fprintf(err, "%s:%u:%u: error: travel of which axis: x, y, z or a\n", file, line, (unsigned)(p - buf) + 1);
      bad = 1;
      continue;
    }
    p++;
    skip(&p);
    if (*p != '=') {
      fprintf(err, "%s:%u:%u: error: expected '=' after the axis\n", file, line, (unsigned)(p - buf) + 1);
      bad = 1;
      continue;
    }
    p++;
    skip(&p);
    if (seen[ax]++) {
      fprintf(err, "%s:%u:%u: error: the travel of %c is given twice\n", file, line, (unsigned)(start - buf) + 1,
              "XYZA"[ax]);
      bad = 1;
      continue;
    }
    if (strncmp(p, "none", 4) == 0) {
      p += 4;
      skip(&p);
      if (*p) {
        fprintf(err, "%s:%u:%u: error: nothing may follow `none`\n", file, line, (unsigned)(p - buf) + 1);
        bad = 1;
      }
      continue;
    }
    double lo, hi;
    const char *q = p;
    if (num(&p, &lo) || (skip(&p), strncmp(p, "..", 2) != 0) || (p += 2, skip(&p), num(&p, &hi)) ||
        (skip(&p), *p)) {
      fprintf(err, "%s:%u:%u: error: expected MIN .. MAX in mm (deg for A), or none\n", file, line,
              (unsigned)(q - buf) + 1);
      bad = 1;
      continue;
    }
    if (!(lo <= 0 && hi >= 0)) {
      fprintf(err, "%s:%u:%u: error: the travel %g .. %g mm of %c must hold 0, where the program starts\n", file,
              line, (unsigned)(q - buf) + 1, lo, hi, "XYZA"[ax]);
      bad = 1;
      continue;
    }
    if (lo < -TRAVEL_MAX_MM || hi > TRAVEL_MAX_MM) {
      fprintf(err, "%s:%u:%u: error: a travel beyond %.0f mm is not a machine's\n", file, line,
              (unsigned)(q - buf) + 1, TRAVEL_MAX_MM);
      bad = 1;
      continue;
    }
    t->has[ax] = 1;
    t->lo[ax] = (int64_t)llround(lo * 1000);
    t->hi[ax] = (int64_t)llround(hi * 1000);
  }
  return bad ? -1 : 0;
}
