/* Operator script parser (src/host/operator.h). */
#include "operator.h"
#include "nearest.h"
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const keys[] = {"PUSK", "PS", "EXIT", "STOP"};
static const char *const actions[] = {"answer", "key", "jog", "correct", "override", "section", "mode", "break", "at",
                                      "zero"};
static const char *const modes[] = {"single", "skip", "optstop"};

int ops_is_waiting(const struct op_action *a)
{
  switch (a->kind) {
  case OA_ANSWER: case OA_JOG: case OA_SECTION: return 1;
  case OA_KEY: return a->key == OPKEY_PUSK || a->key == OPKEY_PS;
  default: return 0;
  }
}

const char *ops_describe(const struct op_action *a, char *buf, size_t n)
{
  static const char ax[] = "XYZA";
  switch (a->kind) {
  case OA_ANSWER: snprintf(buf, n, "answer %lld", (long long)a->n); break;
  case OA_KEY: snprintf(buf, n, "key %s", keys[a->key]); break;
  case OA_JOG: snprintf(buf, n, "jog %c %+lld", ax[a->axis], (long long)a->n); break;
  case OA_CORRECT: snprintf(buf, n, "correct %c %+lld", ax[a->axis], (long long)a->n); break;
  case OA_OVERRIDE: snprintf(buf, n, "override %lld", (long long)a->n); break;
  case OA_MODE:
    if (a->n2 == OPMODE_SINGLE && !a->n)
      snprintf(buf, n, "mode auto");
    else
      snprintf(buf, n, "mode %s %s", modes[a->n2 >= 0 && a->n2 < 3 ? a->n2 : 0], a->n ? "on" : "off");
    break;
  case OA_ZERO: snprintf(buf, n, "zero"); break;
  case OA_BREAK:
    if (a->n)
      snprintf(buf, n, "break N%lld", (long long)a->n);
    else
      snprintf(buf, n, "break off");
    break;
  default:
    if (a->axis2 >= 0)
      snprintf(buf, n, "section %c %+lld %c %+lld", ax[a->axis], (long long)a->n, ax[a->axis2], (long long)a->n2);
    else
      snprintf(buf, n, "section %c %+lld", ax[a->axis], (long long)a->n);
  }
  return buf;
}

/* A line being read: w is where the last word (or the lack of one) is,
 * for the column of a message. */
struct cur { const char *p, *end, *line, *w; };

static int delim(char ch)
{
  return ch == ' ' || ch == '\t' || ch == '\r' || ch == ';';
}

static void skipws(struct cur *c)
{
  while (c->p < c->end && (*c->p == ' ' || *c->p == '\t' || *c->p == '\r'))
    c->p++;
}

/* The next word into buf (check_words made sure it fits). */
static int word(struct cur *c, char *buf, size_t n)
{
  skipws(c);
  c->w = c->p;
  size_t k = 0;
  while (c->p < c->end && !delim(*c->p)) {
    if (k + 1 < n)
      buf[k++] = *c->p;
    c->p++;
  }
  buf[k] = 0;
  return k > 0;
}

/* 1-based column of `at` in its line, in characters (UTF-8). */
static unsigned column(const char *line, const char *at)
{
  unsigned col = 1;
  for (const char *q = line; q < at; q++)
    col += ((unsigned char)*q & 0xC0) != 0x80;
  return col;
}

/* Nothing is cut short: a word longer than OPS_WORD_MAX bytes, or one with
 * a NUL byte, refuses its line (`override 000...0150` is not `override 0`).
 * A comment is free text.  NULL, or the message with *at at the word. */
static const char *check_words(const char *p, const char *e, const char **at)
{
  static char msg[96];
  while (p < e && *p != ';') {
    if (delim(*p)) {
      p++;
      continue;
    }
    const char *w = p;
    int nul = 0;
    while (p < e && !delim(*p))
      nul |= *p++ == 0;
    *at = w;
    if (nul)
      return "a NUL byte inside a word";
    if (p - w > OPS_WORD_MAX) {
      snprintf(msg, sizeof msg, "a word of %zu characters: at most %d (it is not read cut short)", (size_t)(p - w),
               OPS_WORD_MAX);
      return msg;
    }
  }
  return NULL;
}

/* A whole number with an optional sign, within lo..hi. */
static int integer(const char *w, int64_t lo, int64_t hi, int64_t *out)
{
  if (!*w)
    return 0;
  const char *p = w;
  if (*p == '+' || *p == '-')
    p++;
  if (!*p)
    return 0;
  for (const char *q = p; *q; q++)
    if (!isdigit((unsigned char)*q))
      return 0;
  errno = 0;
  long long v = strtoll(w, NULL, 10);
  if (errno || v < lo || v > hi)
    return 0;
  *out = v;
  return 1;
}

/* Millimetres with at most 3 decimals, |v| <= 10000, into µm. */
static int millimetres(const char *w, int64_t *um)
{
  const char *p = w;
  int neg = *p == '-';
  if (*p == '+' || *p == '-')
    p++;
  int64_t v = 0;
  int digits = 0, dec = -1;
  for (; *p; p++) {
    if (*p == '.' && dec < 0) {
      dec = 0;
      continue;
    }
    if (!isdigit((unsigned char)*p) || dec >= 3 || ++digits > 8)
      return 0;
    v = v * 10 + (*p - '0');
    if (dec >= 0)
      dec++;
  }
  if (!digits)
    return 0;
  for (int i = dec < 0 ? 0 : dec; i < 3; i++)
    v *= 10;
  if (v > 10000000)
    return 0;
  *um = neg ? -v : v;
  return 1;
}

static int axis(const char *w)
{
  if (strlen(w) != 1)
    return -1;
  const char *p = strchr("XYZA", *w);
  return p && *w ? (int)(p - "XYZA") : -1;
}

/* Parse one action from the cursor into a; returns NULL or an error text. */
static const char *action(struct cur *c, struct op_action *a)
{
  static char msg[160];
  char w[OPS_WORD_MAX + 1], w2[OPS_WORD_MAX + 1];
  if (!word(c, w, sizeof w))
    return "empty action";
  a->axis2 = -1;
  if (strcmp(w, "answer") == 0) {
    a->kind = OA_ANSWER;
    if (!word(c, w, sizeof w))
      return "answer needs a number";
    const char *d = w + (*w == '-' || *w == '+');
    if (strlen(d) > 7)
      return "answer: at most 7 digits fit the field";
    if (!integer(w, -9999999, 9999999, &a->n))
      return "answer needs a whole number (at most 7 digits, optional -)";
  } else if (strcmp(w, "key") == 0) {
    a->kind = OA_KEY;
    if (!word(c, w, sizeof w))
      return "key needs a name: PUSK, PS, EXIT or STOP";
    a->key = -1;
    for (int i = 0; i < 4; i++)
      if (strcmp(w, keys[i]) == 0)
        a->key = i;
    if (a->key < 0) {
      const char *m = nearest_word(w, keys, 4);
      if (m)
        snprintf(msg, sizeof msg, "unknown key '%.40s': did you mean %s? (PUSK, PS, EXIT, STOP)", w, m);
      else
        snprintf(msg, sizeof msg, "unknown key '%.40s' (PUSK, PS, EXIT, STOP)", w);
      return msg;
    }
  } else if (strcmp(w, "jog") == 0 || strcmp(w, "correct") == 0 || strcmp(w, "section") == 0) {
    a->kind = w[0] == 'j' ? OA_JOG : w[0] == 'c' ? OA_CORRECT : OA_SECTION;
    if (!word(c, w, sizeof w) || (a->axis = axis(w)) < 0)
      return "expected an axis X, Y, Z or A";
    if (!word(c, w2, sizeof w2) || !integer(w2, -99999999, 99999999, &a->n))
      return "expected a signed number of discretes";
    if (a->kind == OA_SECTION) {
      skipws(c);
      if (c->p < c->end && *c->p != ';') {
        if (!word(c, w, sizeof w) || (a->axis2 = axis(w)) < 0 || a->axis2 == a->axis)
          return "section: expected a second, different axis";
        if (!word(c, w2, sizeof w2) || !integer(w2, -99999999, 99999999, &a->n2))
          return "expected a signed number of discretes";
      }
    }
  } else if (strcmp(w, "override") == 0) {
    a->kind = OA_OVERRIDE;
    if (!word(c, w, sizeof w) || !integer(w, 0, 150, &a->n))
      return "override takes a percentage 0..150";
  } else if (strcmp(w, "mode") == 0) {
    a->kind = OA_MODE;
    a->n2 = -1;
    if (!word(c, w, sizeof w))
      w[0] = 0;
    if (strcmp(w, "auto") == 0) {
      a->n2 = OPMODE_SINGLE;
      a->n = 0;
      return NULL;
    }
    for (int i = 0; i < 3; i++)
      if (strcmp(w, modes[i]) == 0)
        a->n2 = i;
    if (a->n2 < 0)
      return "mode is single, skip or optstop, then on or off (or: mode single, mode auto)";
    skipws(c);
    if (c->p >= c->end || *c->p == ';') {
      if (a->n2 != OPMODE_SINGLE)
        return "mode skip and mode optstop take on or off";
      a->n = 1;        /* `mode single`: on */
      return NULL;
    }
    if (!word(c, w2, sizeof w2) || (strcmp(w2, "on") != 0 && strcmp(w2, "off") != 0))
      return "a mode is switched on or off";
    a->n = strcmp(w2, "on") == 0;
  } else if (strcmp(w, "zero") == 0) {
    /* the part zero: zero X <mm> Z <mm> ... (any axes, each once, decimals
     * allowed; which the machine has is its runtime's to say) */
    a->kind = OA_ZERO;
    a->axis = 0;
    while (skipws(c), c->p < c->end && *c->p != ';') {
      const char *p = word(c, w, sizeof w) && strlen(w) == 1 && w[0] ? strchr(OPS_AXES, w[0]) : NULL;
      if (!p)
        return "zero takes axes and millimetres (X Y Z A B C): zero X 0 Z 300.5";
      int k = (int)(p - OPS_AXES);
      if (a->axis & (1 << k))
        return "zero: an axis given twice";
      if (!word(c, w2, sizeof w2) || !millimetres(w2, &a->zero[k]))
        return "zero: expected millimetres, e.g. 300.5 (at most 3 decimals, |value| <= 10000)";
      a->axis |= 1 << k;
    }
    if (!a->axis)
      return "zero takes axes and millimetres (X Y Z A B C): zero X 0 Z 300.5";
  } else if (strcmp(w, "break") == 0) {
    a->kind = OA_BREAK;
    if (!word(c, w, sizeof w))
      return "break needs a block: break N54 (it waits for key PUSK before N54 starts), or break off";
    if (strcmp(w, "off") == 0)
      a->n = 0;
    else if (w[0] != 'N' || w[1] == '+' || w[1] == '-' || !integer(w + 1, 1, 99999, &a->n))
      return "break needs a block: break N54 (block 1..99999), or break off";
  } else {
    const char *m = nearest_word(w, actions, sizeof actions / sizeof actions[0]);
    if (m)
      snprintf(msg, sizeof msg, "unknown action '%.40s': did you mean %s? (answer, key, jog, correct, override, "
               "section, mode, break, at, zero)", w, m);
    else
      snprintf(msg, sizeof msg, "unknown action '%.40s' (answer, key, jog, correct, override, section, mode, "
               "break, at, zero)", w);
    return msg;
  }
  skipws(c);
  c->w = c->p;
  if (c->p < c->end && *c->p != ';')
    return "unexpected text after the action";
  return NULL;
}

int ops_parse(const char *text, size_t len, const char *file, struct opscript *s, FILE *err)
{
  memset(s, 0, sizeof *s);
  size_t cap = 0, capat = 0;
  int bad = 0;
  unsigned line = 0;
  const char *p = text, *end = text + len;
  while (p < end) {
    line++;
    const char *e = memchr(p, '\n', (size_t)(end - p));
    if (!e)
      e = end;
    struct cur c = {p, e, p, p};
    p = e + 1;
    skipws(&c);
    if (c.p >= c.end || *c.p == ';')
      continue;
    struct op_action a;
    memset(&a, 0, sizeof a);
    a.line = line;
    a.col = column(c.line, c.p);
    a.at_number = -1;
    const char *at = c.p;
    const char *msg = check_words(c.p, c.end, &at);
    if (msg) {
      fprintf(err, "%s:%u:%u: error: %s\n", file, line, column(c.line, at), msg);
      bad = 1;
      continue;
    }
    char w[OPS_WORD_MAX + 1];
    struct cur save = c;
    if (word(&c, w, sizeof w) && strcmp(w, "at") == 0) {
      char t[OPS_WORD_MAX + 1];
      if (!word(&c, t, sizeof t) || t[0] != 'N') {
        msg = "at needs a block: at N54 or at N54#3";
      } else {
        char *hash = strchr(t, '#');
        int64_t nb = 0, run = 1;
        if (hash)
          *hash = 0;
        if (!integer(t + 1, 1, 99999, &nb) || t[1] == '+' || t[1] == '-' ||
            (hash && (!integer(hash + 1, 1, 1000000000, &run) || hash[1] == '+' || hash[1] == '-')))
          msg = "at needs a block: at N54 or at N54#3 (block 1..99999, run from 1)";
        a.at_number = (int)nb;
        a.at_run = (unsigned)run;
      }
      if (!msg) {
        skipws(&c);
        const char *act = c.p;
        msg = action(&c, &a);
        if (!msg && ops_is_waiting(&a)) {
          c.w = act;
          msg = "at fires at a block's start: only key EXIT, key STOP, correct, override, mode and break";
        }
      }
    } else {
      c = save;
      msg = action(&c, &a);
    }
    if (msg) {
      fprintf(err, "%s:%u:%u: error: %s\n", file, line, column(c.line, c.w), msg);
      bad = 1;
      continue;
    }
    struct op_action **v = a.at_number >= 0 ? &s->at : &s->v;
    size_t *n = a.at_number >= 0 ? &s->nat : &s->n, *cp = a.at_number >= 0 ? &capat : &cap;
    if (*n == *cp) {
      size_t nc = *cp ? *cp * 2 : 16;
      struct op_action *q = realloc(*v, nc * sizeof *q);
      if (!q) {
        fprintf(err, "%s: out of memory\n", file);
        ops_free(s);
        return -1;
      }
      *v = q;
      *cp = nc;
    }
    (*v)[(*n)++] = a;
  }
  if (bad) {
    ops_free(s);
    return -1;
  }
  return 0;
}

void ops_free(struct opscript *s)
{
  free(s->v);
  free(s->at);
  memset(s, 0, sizeof *s);
}

int ops_check_at(const struct opscript *s, const unsigned char have[1000], const char *file, FILE *err)
{
  int bad = 0;
  for (size_t i = 0; i < s->nat; i++) {
    const struct op_action *a = &s->at[i];
    if (a->at_number >= 1 && a->at_number <= 999 && have[a->at_number])
      continue;
    fprintf(err, "%s:%u:%u: error: at N%d: the program has no block N%d, so this never fires\n", file, a->line,
            a->col, a->at_number, a->at_number);
    bad = 1;
  }
  for (size_t i = 0; i < s->n; i++) {
    const struct op_action *a = &s->v[i];
    if (a->kind != OA_BREAK || a->n == 0 || have[a->n])
      continue;
    fprintf(err, "%s:%u:%u: error: break N%lld: the program has no block N%lld, so it never waits there\n", file,
            a->line, a->col, (long long)a->n, (long long)a->n);
    bad = 1;
  }
  return bad ? -1 : 0;
}

void ops_warn_unused(const struct opscript *s, size_t next, size_t skip, const unsigned *runs, const char *file,
                     FILE *err)
{
  char what[96];
  for (size_t i = next; i < s->n; i++)
    if (i + 1 != skip)
      fprintf(err, "%s:%u:%u: warning: %s was not used: the run ended before it\n", file, s->v[i].line, s->v[i].col,
              ops_describe(&s->v[i], what, sizeof what));
  for (size_t i = 0; i < s->nat; i++) {
    const struct op_action *a = &s->at[i];
    if (a->fired)
      continue;
    unsigned ran = runs && a->at_number >= 0 && a->at_number < 1000 ? runs[a->at_number] : 0;
    char times[48];
    if (ran == 0)
      snprintf(times, sizeof times, "never started");
    else if (ran == 1)
      snprintf(times, sizeof times, "started only once");
    else
      snprintf(times, sizeof times, "started only %u times", ran);
    fprintf(err, "%s:%u:%u: warning: at N%d#%u %s never fired: block N%d %s\n", file, a->line, a->col, a->at_number,
            a->at_run, ops_describe(a, what, sizeof what), a->at_number, times);
  }
}
