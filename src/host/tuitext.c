/* The terminal's program text, keyboard map, ASCII fallback and word wrap
 * (src/host/tuitext.h).  No curses here: the unit tests drive it directly. */
#include "tuitext.h"
#include "atomic.h"
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void tui_text_init(struct tui_text *t)
{
  memset(t, 0, sizeof *t);
  t->final_eol = 1;
}

static void free_lines(char **v, size_t n)
{
  for (size_t i = 0; i < n; i++)
    free(v[i]);
  free(v);
}

void tui_text_free(struct tui_text *t)
{
  free_lines(t->line, t->n);
  free_lines(t->old, t->nold);
  tui_text_init(t);
}

/* A deep copy of the lines, for undo.  0, or -1 when out of memory. */
static int snapshot(struct tui_text *t)
{
  char **v = malloc((t->n ? t->n : 1) * sizeof *v);
  if (!v)
    return -1;
  for (size_t i = 0; i < t->n; i++) {
    if (!(v[i] = strdup(t->line[i]))) {
      free_lines(v, i);
      return -1;
    }
  }
  free_lines(t->old, t->nold);
  t->old = v;
  t->nold = t->n;
  t->have_old = 1;
  return 0;
}

static int reserve(struct tui_text *t, size_t n)
{
  if (n <= t->cap)
    return 0;
  size_t cap = t->cap ? t->cap : 64;
  while (cap < n)
    cap *= 2;
  char **v = realloc(t->line, cap * sizeof *v);
  if (!v)
    return -1;
  t->line = v;
  t->cap = cap;
  return 0;
}

int tui_text_set(struct tui_text *t, const char *buf, size_t n, char *err, size_t errn)
{
  if (memchr(buf, 0, n)) {
    snprintf(err, errn, "it holds a NUL byte: not a program text");
    return -1;
  }
  /* \r\n line ends are taken off (and put back on save) only when every
   * line has one: a stray \r in a mixed file stays where it was.  A file
   * with no \n but \r has CR-only line ends (old Mac OS), as the compiler
   * reads them: its lines are split at \r and saved with \r. */
  size_t lf = 0, crlf = 0, cr = 0;
  for (size_t i = 0; i < n; i++)
    if (buf[i] == '\n') {
      lf++;
      crlf += i > 0 && buf[i - 1] == '\r';
    } else if (buf[i] == '\r') {
      cr++;
    }
  struct tui_text nt;
  tui_text_init(&nt);
  nt.cr = !lf && cr;
  char eolc = nt.cr ? '\r' : '\n';
  nt.final_eol = n == 0 || buf[n - 1] == eolc;
  nt.crlf = lf && crlf == lf;
  for (size_t i = 0; i < n;) {
    const char *e = memchr(buf + i, eolc, n - i);
    size_t len = e ? (size_t)(e - (buf + i)) : n - i;
    size_t next = i + len + (e ? 1 : 0);
    if (e && nt.crlf)
      len--;
    char *l = malloc(len + 1);
    if (!l || reserve(&nt, nt.n + 1)) {
      free(l);
      tui_text_free(&nt);
      snprintf(err, errn, "out of memory");
      return -1;
    }
    memcpy(l, buf + i, len);
    l[len] = 0;
    nt.line[nt.n++] = l;
    i = next;
  }
  tui_text_free(t);
  *t = nt;
  return 0;
}

uint64_t tui_hash(const void *p, size_t n)
{
  const unsigned char *b = p;
  uint64_t h = 1469598103934665603ULL;
  for (size_t i = 0; i < n; i++) {
    h ^= b[i];
    h *= 1099511628211ULL;
  }
  return h;
}

static long long mtime_ns(const struct stat *st)
{
  return (long long)st->st_mtim.tv_sec * 1000000000LL + st->st_mtim.tv_nsec;
}

void tui_disk_of(const char *path, const char *buf, size_t n, struct tui_disk *d)
{
  struct stat st;
  memset(d, 0, sizeof *d);
  if (stat(path, &st) == 0) {
    d->exists = 1;
    d->size = (long long)st.st_size;
    d->mtime_ns = mtime_ns(&st);
  }
  d->hash = tui_hash(buf, n);
  d->len = n;
}

int tui_disk_changed(const char *path, const struct tui_disk *d)
{
  struct stat st;
  int now = stat(path, &st) == 0;
  if (now != d->exists)
    return 1;
  if (!now)
    return 0;
  if ((long long)st.st_size != d->size)
    return 1;
  if (mtime_ns(&st) == d->mtime_ns)
    return 0;
  /* the same size at another time: only the bytes tell */
  char *b, err[256];
  size_t n;
  if (file_read_all(path, FILE_REGULAR, FILE_MAX_PROGRAM, &b, &n, err, sizeof err))
    return 1;
  int changed = n != d->len || tui_hash(b, n) != d->hash;
  free(b);
  return changed;
}

int tui_text_load(struct tui_text *t, const char *path, struct tui_disk *d, char *err, size_t errn)
{
  /* a regular file only: a FIFO or a device is refused, not waited on */
  char *b;
  size_t n;
  int r = file_read_all(path, FILE_REGULAR, FILE_MAX_PROGRAM, &b, &n, err, errn);
  if (r == -2)
    snprintf(err, errn, "%s: too large (over %zu MiB)", path, FILE_MAX_PROGRAM >> 20);
  if (r)
    return -1;
  char why[128];
  r = tui_text_set(t, b, n, why, sizeof why);
  if (r == 0 && d)
    tui_disk_of(path, b, n, d);
  free(b);
  if (r)
    snprintf(err, errn, "%s: %s", path, why);
  return r;
}

char *tui_text_join(const struct tui_text *t, size_t *n)
{
  const char *eol = t->crlf ? "\r\n" : t->cr ? "\r" : "\n";
  size_t el = strlen(eol), total = 1;
  for (size_t i = 0; i < t->n; i++)
    total += strlen(t->line[i]) + el;
  char *b = malloc(total), *p = b;
  if (!b)
    return NULL;
  for (size_t i = 0; i < t->n; i++) {
    size_t len = strlen(t->line[i]);
    memcpy(p, t->line[i], len);
    p += len;
    if (i + 1 < t->n || t->final_eol) {
      memcpy(p, eol, el);
      p += el;
    }
  }
  *p = 0;
  *n = (size_t)(p - b);
  return b;
}

int tui_text_insert(struct tui_text *t, size_t i, const char *s)
{
  if (i > t->n || reserve(t, t->n + 1))
    return -1;
  char *l = strdup(s);
  if (!l || snapshot(t)) {
    free(l);
    return -1;
  }
  memmove(&t->line[i + 1], &t->line[i], (t->n - i) * sizeof *t->line);
  t->line[i] = l;
  t->n++;
  return 0;
}

int tui_text_replace(struct tui_text *t, size_t i, const char *s)
{
  if (i >= t->n)
    return -1;
  char *l = strdup(s);
  if (!l || snapshot(t)) {
    free(l);
    return -1;
  }
  free(t->line[i]);
  t->line[i] = l;
  return 0;
}

int tui_text_delete(struct tui_text *t, size_t i)
{
  if (i >= t->n || snapshot(t))
    return -1;
  free(t->line[i]);
  memmove(&t->line[i], &t->line[i + 1], (t->n - i - 1) * sizeof *t->line);
  t->n--;
  return 0;
}

int tui_text_undo(struct tui_text *t)
{
  if (!t->have_old)
    return -1;
  char **v = t->line;
  size_t n = t->n;
  t->line = t->old;
  t->n = t->nold;
  t->cap = t->nold ? t->nold : 1;
  t->old = v;
  t->nold = n;
  /* undo twice is redo */
  return 0;
}

long tui_text_find(const struct tui_text *t, size_t from, int dir, const char *needle, size_t *byte,
                   int *wrapped)
{
  *wrapped = 0;
  if (!needle[0] || !t->n)
    return -1;
  if (from >= t->n)
    from = dir > 0 ? 0 : t->n - 1;
  size_t i = from;
  for (size_t k = 0; k < t->n; k++) {
    const char *m = strstr(t->line[i], needle);
    if (m) {
      *byte = (size_t)(m - t->line[i]);
      *wrapped = dir > 0 ? i < from : i > from;
      return (long)i;
    }
    i = dir > 0 ? (i + 1 == t->n ? 0 : i + 1) : (i == 0 ? t->n - 1 : i - 1);
  }
  return -1;
}

int tui_text_save(const struct tui_text *t, const char *path, struct tui_disk *d, char *err, size_t errn)
{
  /* a symbolic link keeps pointing at the program: write its target */
  char real[PATH_MAX];
  const char *target = realpath(path, real) ? real : path;
  struct stat st;
  mode_t mode;
  if (stat(target, &st) == 0) {
    if (!S_ISREG(st.st_mode)) {
      snprintf(err, errn, "%s: not a regular file", path);
      return -1;
    }
    mode = st.st_mode & 07777;
  } else {
    mode_t um = umask(0);
    umask(um);
    mode = 0666 & ~um;
  }
  size_t n;
  char *buf = tui_text_join(t, &n);
  if (!buf) {
    snprintf(err, errn, "out of memory");
    return -1;
  }
  struct iovec v = {buf, n};
  int rc = atomic_write(target, path, mode, &v, 1, err, errn);
  if (rc == 0 && d)
    tui_disk_of(target, buf, n, d);
  free(buf);
  return rc;
}

uint32_t tui_cyr_key(uint32_t k)
{
  /* Table 3.4, A..Z.  The seed's cell for ')' is damaged; the layout is the
   * KOI-7 one (@ [ \ ] ^ _ -> Ю Ш Э Щ Ч Ъ) with the 2С42's keys * : + ( % )
   * in their places, so ')' gives Ъ. */
  static const uint16_t az[26] = {
    0x410, 0x411, 0x426, 0x414, 0x415, 0x424, 0x413, 0x425, 0x418, 0x419, 0x41A, 0x41B, 0x41C,
    0x41D, 0x41E, 0x41F, 0x42F, 0x420, 0x421, 0x422, 0x423, 0x416, 0x412, 0x42C, 0x42B, 0x417,
  };
  if (k >= 'A' && k <= 'Z')
    return az[k - 'A'];
  if (k >= 'a' && k <= 'z')
    return az[k - 'a'];
  switch (k) {
  case '*': return 0x42E;   /* Ю */
  case ':': return 0x428;   /* Ш */
  case '+': return 0x42D;   /* Э */
  case '(': return 0x429;   /* Щ */
  case '%': return 0x427;   /* Ч */
  case ')': return 0x42A;   /* Ъ */
  default: return k;
  }
}

char tui_ascii(uint32_t c)
{
  /* А..Я, one column each */
  static const char cyr[33] = "ABVGDEZZIJKLMNOPRSTUFHCCSS'Y'EUA";
  if (c >= 0x20 && c < 0x7F)
    return (char)c;
  if (c >= 0x410 && c <= 0x42F)
    return cyr[c - 0x410];
  if (c >= 0x430 && c <= 0x44F) {
    char a = cyr[c - 0x430];
    return a >= 'A' && a <= 'Z' ? (char)(a - 'A' + 'a') : a;
  }
  switch (c) {
  case 0x401: case 0x404: return 'E';          /* Ё Є */
  case 0x451: case 0x454: return 'e';
  case 0x406: case 0x407: return 'I';          /* І Ї */
  case 0x456: case 0x457: return 'i';
  case 0x490: return 'G';                      /* Ґ */
  case 0x491: return 'g';
  case 0x2116: return 'N';                     /* № */
  case 0xB0: return 'o';                       /* ° */
  case 0xB5: return 'u';                       /* µ */
  case 0x2013: case 0x2014: case 0x2212: return '-';
  case 0xAB: case 0xBB: return '"';
  case 0x2500: case 0x2550: return '-';        /* box drawing */
  case 0x2502: case 0x2551: return '|';
  case 0x250C: case 0x2510: case 0x2514: case 0x2518: case 0x251C: case 0x2524: case 0x252C:
  case 0x2534: case 0x253C: return '+';
  case 0x2191: return '^';                     /* arrows */
  case 0x2193: return 'v';
  case 0x2190: return '<';
  case 0x2192: return '>';
  case 0x25B6: return '>';
  case 0x2026: return '$';                     /* … a line cut at the pane's edge */
  case 0x2264: return '<';                     /* ≤ ≥ */
  case 0x2265: return '>';
  default: return '?';
  }
}

int tui_utf8(uint32_t c, char u[4])
{
  if (c < 0x80) {
    u[0] = (char)c;
    return 1;
  }
  if (c < 0x800) {
    u[0] = (char)(0xC0 | (c >> 6));
    u[1] = (char)(0x80 | (c & 0x3F));
    return 2;
  }
  if (c < 0x10000) {
    u[0] = (char)(0xE0 | (c >> 12));
    u[1] = (char)(0x80 | ((c >> 6) & 0x3F));
    u[2] = (char)(0x80 | (c & 0x3F));
    return 3;
  }
  u[0] = (char)(0xF0 | ((c >> 18) & 0x07));
  u[1] = (char)(0x80 | ((c >> 12) & 0x3F));
  u[2] = (char)(0x80 | ((c >> 6) & 0x3F));
  u[3] = (char)(0x80 | (c & 0x3F));
  return 4;
}

int tui_wrap(const uint32_t *s, int n, int w, int *start, int *len, int max)
{
  int rows = 0, i = 0;
  if (w < 1)
    w = 1;
  while (i < n && s[i] == ' ')
    i++;
  if (i >= n || max < 1) {
    if (max >= 1) {
      start[0] = 0;
      len[0] = 0;
    }
    return 1;
  }
  while (i < n && rows < max) {
    int end = i + w;
    if (end >= n) {
      end = n;
    } else if (s[end] != ' ') {
      /* back to the last space in the row, unless the word fills it all */
      int b = end;
      while (b > i && s[b - 1] != ' ')
        b--;
      if (b > i)
        end = b;
    }
    int e = end;
    while (e > i && s[e - 1] == ' ')
      e--;
    start[rows] = i;
    len[rows] = e - i;
    rows++;
    i = end;
    while (i < n && s[i] == ' ')
      i++;
  }
  return rows;
}
