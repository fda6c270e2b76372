/* Tool-model parser (toolmodel.h): one pass over the lines, each value
 * checked as it is read, then the checks that involve several keys (steps
 * against teeth, the image against the smallest step).  Works on a length,
 * so NUL bytes and a missing final newline are ordinary input. */
#include "toolmodel.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

enum key { K_TEETH, K_STEPS, K_DIAMETER, K_LEAD, K_HAND, K_NOISE, K_BLUR, K_IMAGE, K_SEED, K_COUNT };
static const char *const key_names[K_COUNT] = {
  "teeth", "steps", "diameter", "lead", "hand", "noise", "blur", "image", "seed"
};

struct parser {
  const char *name;
  char *err;
  size_t errlen;
  unsigned line;
  unsigned seen[K_COUNT];          /* line of each key, 0 not seen */
  int nsteps;
};

static int fail(struct parser *p, unsigned line, const char *fmt, ...)
  __attribute__((format(printf, 3, 4)));

static int fail(struct parser *p, unsigned line, const char *fmt, ...)
{
  if (!p->err || p->errlen == 0)
    return -1;
  int n = line ? snprintf(p->err, p->errlen, "%s:%u: ", p->name, line)
               : snprintf(p->err, p->errlen, "%s: ", p->name);
  if (n < 0 || (size_t)n >= p->errlen)
    return -1;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(p->err + n, p->errlen - (size_t)n, fmt, ap);
  va_end(ap);
  return -1;
}

void tm_defaults(struct tm_model *m)
{
  memset(m, 0, sizeof *m);
  m->even = 1;
  m->hand = TM_RIGHT;
  m->image = 512;
  m->seed = 1;
}

/* A decimal number, whole token: [+-]digits[.digits][(e|E)[+-]digits].
 * strtod alone would also take "nan", "inf", hex and a locale's comma. */
static int number(const char *s, size_t n, double *out)
{
  char buf[64];
  size_t i = 0;
  if (n == 0 || n >= sizeof buf)
    return -1;
  if (s[i] == '+' || s[i] == '-')
    i++;
  size_t d0 = i;
  while (i < n && s[i] >= '0' && s[i] <= '9')
    i++;
  size_t digits = i - d0;
  if (i < n && s[i] == '.') {
    i++;
    size_t f0 = i;
    while (i < n && s[i] >= '0' && s[i] <= '9')
      i++;
    digits += i - f0;
  }
  if (digits == 0)
    return -1;
  if (i < n && (s[i] == 'e' || s[i] == 'E')) {
    i++;
    if (i < n && (s[i] == '+' || s[i] == '-'))
      i++;
    size_t e0 = i;
    while (i < n && s[i] >= '0' && s[i] <= '9')
      i++;
    if (i == e0)
      return -1;
  }
  if (i != n)
    return -1;
  memcpy(buf, s, n);
  buf[n] = 0;
  errno = 0;
  double v = strtod(buf, NULL);
  if (errno == ERANGE || !isfinite(v))
    return -1;
  *out = v;
  return 0;
}

/* A printable excerpt of a value for messages (no control bytes). */
static const char *show(const char *s, size_t n, char *buf, size_t bufn)
{
  size_t k = 0;
  for (size_t i = 0; i < n && k + 4 < bufn; i++)
    buf[k++] = (unsigned char)s[i] < 0x20 || s[i] == 0x7f ? '?' : s[i];
  if (n > 0 && k + 4 >= bufn && k < n) {
    buf[k++] = '.'; buf[k++] = '.'; buf[k++] = '.';
  }
  buf[k] = 0;
  return buf;
}

static int is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

static int integer(struct parser *p, const char *key, const char *v, size_t n,
                   double lo, double hi, double *out)
{
  char sb[48];
  if (number(v, n, out) != 0)
    return fail(p, p->line, "%s: '%s' is not a number", key, show(v, n, sb, sizeof sb));
  if (*out != floor(*out))
    return fail(p, p->line, "%s: %s is not a whole number", key, show(v, n, sb, sizeof sb));
  if (*out < lo || *out > hi)
    return fail(p, p->line, "%s: %s is outside %.0f..%.0f", key, show(v, n, sb, sizeof sb), lo, hi);
  return 0;
}

static int parse_steps(struct parser *p, struct tm_model *m, const char *v, size_t n)
{
  char sb[48];
  if (n == 4 && strncasecmp(v, "even", 4) == 0) {
    m->even = 1;
    p->nsteps = 0;
    return 0;
  }
  m->even = 0;
  p->nsteps = 0;
  size_t i = 0;
  for (;;) {
    while (i < n && is_space(v[i]))
      i++;
    size_t t0 = i;
    while (i < n && v[i] != ',' && !is_space(v[i]))
      i++;
    size_t t1 = i;
    while (i < n && is_space(v[i]))
      i++;
    if (t1 == t0)
      return fail(p, p->line, "steps: an empty item in the list (numbers separated by commas, or \"even\")");
    if (p->nsteps >= TM_MAX_TEETH)
      return fail(p, p->line, "steps: more than %d steps", TM_MAX_TEETH);
    double d;
    if (number(v + t0, t1 - t0, &d) != 0)
      return fail(p, p->line, "steps: '%s' is not a number", show(v + t0, t1 - t0, sb, sizeof sb));
    if (d <= 0)
      return fail(p, p->line, "steps: step %d is %g degrees; every step must be positive",
                  p->nsteps + 1, d);
    m->steps[p->nsteps++] = d;
    if (i >= n)
      break;
    if (v[i] == ',')
      i++;
    else if (i == t1)   /* unreachable: a token ends at a comma or a space */
      return fail(p, p->line, "steps: bad list");
  }
  return 0;
}

static int set_key(struct parser *p, struct tm_model *m, int k, const char *v, size_t n)
{
  char sb[48];
  double d;
  switch (k) {
  case K_TEETH:
    if (integer(p, "teeth", v, n, -1e18, 1e18, &d) != 0)
      return -1;
    if (d < 1 || d > TM_MAX_TEETH)
      return fail(p, p->line, "teeth: %.0f; a tool has 1 to %d teeth", d, TM_MAX_TEETH);
    m->teeth = (int)d;
    return 0;
  case K_STEPS:
    return parse_steps(p, m, v, n);
  case K_HAND:
    if (n == 5 && strncasecmp(v, "right", 5) == 0)
      m->hand = TM_RIGHT;
    else if (n == 4 && strncasecmp(v, "left", 4) == 0)
      m->hand = TM_LEFT;
    else
      return fail(p, p->line, "hand: '%s'; right or left", show(v, n, sb, sizeof sb));
    return 0;
  case K_IMAGE:
    if (integer(p, "image", v, n, -1e18, 1e18, &d) != 0)
      return -1;
    if (d < TM_MIN_IMAGE)
      return fail(p, p->line, "image: %.0f pixels is too small (at least %d)", d, TM_MIN_IMAGE);
    if (d > TM_MAX_IMAGE)
      return fail(p, p->line, "image: %.0f pixels is too large (at most %d)", d, TM_MAX_IMAGE);
    m->image = (int)d;
    return 0;
  case K_SEED:
    if (integer(p, "seed", v, n, 0, 4294967295.0, &d) != 0)
      return -1;
    m->seed = (uint32_t)d;
    return 0;
  default:
    break;
  }
  /* the real-valued keys */
  const char *key = key_names[k];
  if (number(v, n, &d) != 0)
    return fail(p, p->line, "%s: '%s' is not a number", key, show(v, n, sb, sizeof sb));
  switch (k) {
  case K_DIAMETER:
    if (d < 0)
      return fail(p, p->line, "diameter: %g µm is negative", d);
    if (d == 0)
      return fail(p, p->line, "diameter: 0; a tool has a positive diameter (µm)");
    if (d > TM_MAX_DIAMETER)
      return fail(p, p->line, "diameter: %g µm is larger than %g µm", d, TM_MAX_DIAMETER);
    m->diameter = d;
    break;
  case K_LEAD:
    if (d < 0)
      return fail(p, p->line, "lead: %g µm is negative (the hand says right or left)", d);
    if (d != 0 && d < TM_MIN_LEAD)
      return fail(p, p->line, "lead: %g µm is shorter than %g µm (0 means straight flutes)", d, TM_MIN_LEAD);
    if (d > TM_MAX_LEAD)
      return fail(p, p->line, "lead: %g µm is longer than %g µm, the largest TK", d, TM_MAX_LEAD);
    m->lead = d;
    break;
  case K_NOISE:
    if (d < 0 || d > 1)
      return fail(p, p->line, "noise: %g is outside 0..1", d);
    m->noise = d;
    break;
  case K_BLUR:
    if (d < 0)
      return fail(p, p->line, "blur: %g pixels is negative", d);
    if (d > TM_MAX_BLUR)
      return fail(p, p->line, "blur: %g pixels is more than %g", d, TM_MAX_BLUR);
    m->blur = d;
    break;
  default:
    break;
  }
  return 0;
}

static int check(struct parser *p, const struct tm_model *m)
{
  unsigned tl = p->seen[K_TEETH], sl = p->seen[K_STEPS], il = p->seen[K_IMAGE];
  if (m->teeth < 1 || m->teeth > TM_MAX_TEETH)
    return fail(p, tl, "teeth: %d; a tool has 1 to %d teeth", m->teeth, TM_MAX_TEETH);
  if (!(m->diameter > 0) || m->diameter > TM_MAX_DIAMETER)
    return fail(p, p->seen[K_DIAMETER], "diameter: %g µm is outside (0, %g]", m->diameter, TM_MAX_DIAMETER);
  if (!(m->lead >= 0) || (m->lead != 0 && m->lead < TM_MIN_LEAD) || m->lead > TM_MAX_LEAD)
    return fail(p, p->seen[K_LEAD], "lead: %g µm is outside 0 or [%g, %g]", m->lead, TM_MIN_LEAD, TM_MAX_LEAD);
  if (m->hand != TM_RIGHT && m->hand != TM_LEFT)
    return fail(p, p->seen[K_HAND], "hand: neither right nor left");
  if (!(m->noise >= 0 && m->noise <= 1))
    return fail(p, p->seen[K_NOISE], "noise: %g is outside 0..1", m->noise);
  if (!(m->blur >= 0 && m->blur <= TM_MAX_BLUR))
    return fail(p, p->seen[K_BLUR], "blur: %g pixels is outside 0..%g", m->blur, TM_MAX_BLUR);
  if (m->image < TM_MIN_IMAGE || m->image > TM_MAX_IMAGE)
    return fail(p, il, "image: %d pixels is outside %d..%d", m->image, TM_MIN_IMAGE, TM_MAX_IMAGE);
  double minstep = 360.0 / m->teeth;
  if (!m->even) {
    if (p->nsteps != m->teeth)
      return fail(p, sl, "steps: %d steps for %d teeth (one step per tooth, or \"even\")",
                  p->nsteps, m->teeth);
    double sum = 0;
    minstep = 360;
    for (int i = 0; i < m->teeth; i++) {
      if (!(m->steps[i] > 0))
        return fail(p, sl, "steps: step %d is %g degrees; every step must be positive", i + 1, m->steps[i]);
      sum += m->steps[i];
      if (m->steps[i] < minstep)
        minstep = m->steps[i];
    }
    if (fabs(sum - 360) > 0.001)
      return fail(p, sl, "steps: they sum to %.6g degrees, not 360", sum);
  }
  double px = TM_TIP_FRACTION * m->image * minstep * M_PI / 180;
  if (px < TM_MIN_STEP_PX) {
    double need = ceil(TM_MIN_STEP_PX / (TM_TIP_FRACTION * minstep * M_PI / 180));
    return fail(p, il ? il : sl, "image: %d pixels is too small for a step of %g degrees "
                "(%.1f pixels at the tip; it needs image >= %.0f)", m->image, minstep, px, need);
  }
  return 0;
}

/* Fill in even steps once the model is known to be consistent. */
static void finish(struct tm_model *m)
{
  if (m->even)
    for (int i = 0; i < m->teeth; i++)
      m->steps[i] = 360.0 / m->teeth;
  for (int i = m->teeth; i < TM_MAX_TEETH; i++)
    m->steps[i] = 0;
}

int tm_parse(struct tm_model *m, const char *text, size_t len, const char *name,
             char *err, size_t errlen)
{
  struct parser p = { name ? name : "tool", err, errlen, 0, {0}, 0 };
  struct tm_model t;
  tm_defaults(&t);
  if (err && errlen)
    err[0] = 0;
  size_t i = 0;
  if (len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0)
    i = 3;                                   /* a UTF-8 byte-order mark */
  while (i < len) {
    p.line++;
    size_t b = i;
    while (i < len && text[i] != '\n')
      i++;
    size_t e = i;
    if (i < len)
      i++;
    for (size_t c = b; c < e; c++)
      if (text[c] == ';') {
        e = c;
        break;
      }
    while (b < e && is_space(text[b]))
      b++;
    while (e > b && is_space(text[e - 1]))
      e--;
    if (b == e)
      continue;
    for (size_t c = b; c < e; c++)
      if (text[c] == 0)
        return fail(&p, p.line, "a NUL byte in the line");
    const char *eq = memchr(text + b, '=', e - b);
    if (!eq)
      return fail(&p, p.line, "expected 'key = value'");
    size_t kb = b, ke = (size_t)(eq - text);
    while (ke > kb && is_space(text[ke - 1]))
      ke--;
    size_t vb = (size_t)(eq - text) + 1;
    while (vb < e && is_space(text[vb]))
      vb++;
    char sb[48];
    if (ke == kb)
      return fail(&p, p.line, "a value without a key");
    int k = -1;
    for (int j = 0; j < K_COUNT; j++)
      if (strlen(key_names[j]) == ke - kb && strncasecmp(key_names[j], text + kb, ke - kb) == 0)
        k = j;
    if (k < 0)
      return fail(&p, p.line, "unknown key '%s' (teeth, steps, diameter, lead, hand, noise, blur, image, seed)",
                  show(text + kb, ke - kb, sb, sizeof sb));
    if (p.seen[k])
      return fail(&p, p.line, "%s: given twice (first on line %u)", key_names[k], p.seen[k]);
    p.seen[k] = p.line;
    if (vb >= e)
      return fail(&p, p.line, "%s: no value", key_names[k]);
    if (set_key(&p, &t, k, text + vb, e - vb) != 0)
      return -1;
  }
  if (!p.seen[K_TEETH])
    return fail(&p, 0, "no 'teeth' (the number of teeth, 1 to %d)", TM_MAX_TEETH);
  if (!p.seen[K_DIAMETER])
    return fail(&p, 0, "no 'diameter' (µm)");
  if (check(&p, &t) != 0)
    return -1;
  finish(&t);
  *m = t;
  return 0;
}

int tm_check(const struct tm_model *m, char *err, size_t errlen)
{
  struct parser p = { "tool", err, errlen, 0, {0}, m->even ? 0 : m->teeth };
  if (err && errlen)
    err[0] = 0;
  return check(&p, m);
}

int tm_load(struct tm_model *m, const char *path, char *err, size_t errlen)
{
  struct parser p = { path, err, errlen, 0, {0}, 0 };
  FILE *f = fopen(path, "rb");
  if (!f)
    return fail(&p, 0, "cannot open: %s", strerror(errno));
  enum { MAXLEN = 1 << 20 };
  char *buf = malloc(MAXLEN + 1);
  if (!buf) {
    fclose(f);
    return fail(&p, 0, "out of memory");
  }
  size_t n = fread(buf, 1, MAXLEN + 1, f);
  int bad = ferror(f);
  fclose(f);
  int rc;
  if (bad)
    rc = fail(&p, 0, "read error");
  else if (n > MAXLEN)
    rc = fail(&p, 0, "larger than %d bytes; not a tool model", MAXLEN);
  else
    rc = tm_parse(m, buf, n, path, err, errlen);
  free(buf);
  return rc;
}

void tm_tooth_angles(const struct tm_model *m, double *angles)
{
  double a = 0;
  for (int j = 0; j < m->teeth; j++) {
    angles[j] = a;
    a -= m->even ? 360.0 / m->teeth : m->steps[j];
  }
}
