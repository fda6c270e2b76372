/* The 2С42 lexer (src/dialect/2c42/lex.h). */
#include "lex.h"
#include "utf8.h"
#include "errors.h"
#include <string.h>

/* lex.h: a byte's character, LX_EOB ('^' LF), or LX_SLOW: every ASCII
 * byte but whitespace (TAB LF VT FF CR, the space), ';' (a comment) and
 * '^' stands for itself; controls are characters (which no word accepts);
 * 0x80..0xFF are UTF-8, decoded by scan.  NUL is a character too, but
 * LX_SLOW here: it ends a chunk (lex_slow tells which). */
#define E LX_EOB
#define S LX_SLOW
const int16_t lex_val[256] = {
  S, 1, 2, 3, 4, 5, 6, 7, 8, S, E, S, S, S, 14, 15,
  16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31,
  S, 33, 34, 35, 36, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 47,
  48, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, S, 60, 61, 62, 63,
  64, 65, 66, 67, 68, 69, 70, 71, 72, 73, 74, 75, 76, 77, 78, 79,
  80, 81, 82, 83, 84, 85, 86, 87, 88, 89, 90, 91, 92, 93, E, 95,
  96, 97, 98, 99, 100, 101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 111,
  112, 113, 114, 115, 116, 117, 118, 119, 120, 121, 122, 123, 124, 125, 126, 127,
  S, S, S, S, S, S, S, S, S, S, S, S, S, S, S, S,
  S, S, S, S, S, S, S, S, S, S, S, S, S, S, S, S,
  S, S, S, S, S, S, S, S, S, S, S, S, S, S, S, S,
  S, S, S, S, S, S, S, S, S, S, S, S, S, S, S, S,
  S, S, S, S, S, S, S, S, S, S, S, S, S, S, S, S,
  S, S, S, S, S, S, S, S, S, S, S, S, S, S, S, S,
  S, S, S, S, S, S, S, S, S, S, S, S, S, S, S, S,
  S, S, S, S, S, S, S, S, S, S, S, S, S, S, S, S,
};
#undef E
#undef S

/* Does byte b stand for itself? */
static inline int plain(unsigned char b)
{
  return lex_val[b] >= 0 || b == 0;
}

/* Decode one code point at p; *len gets its byte length.  Invalid UTF-8 is
 * returned as U+FFFD (one byte), which no word accepts. */
static int32_t decode(const struct lex *l, size_t p, size_t *len)
{
  return utf8_decode((const unsigned char *)l->s + p, l->n - p, len);
}

/* A CR not followed by LF ends a line (classic Mac OS files); in CR LF the
 * CR is only whitespace and the LF ends the line. */
static int lone_cr(const struct lex *l, size_t p)
{
  return l->s[p] == '\r' && (p + 1 >= l->n || l->s[p + 1] != '\n');
}

/* The cursor at byte pos (column col): in the text itself before its last
 * line, else in a chunk holding the `need` bytes from pos (need >= 1; at
 * the end of the text an empty one, its NUL at pos). */
static void setp(struct lex *l, size_t pos, unsigned col, size_t need)
{
  const unsigned char *p;
  if (pos < l->tail) {
    p = (const unsigned char *)l->s + pos;
    l->pb = (uintptr_t)l->s;
  } else {
    if (pos < l->ca || pos + need > l->ca + l->clen) {
      size_t k = l->n - pos < LX_CHUNK ? l->n - pos : LX_CHUNK;
      if (k)
        memcpy(l->chunk, l->s + pos, k);
      l->chunk[k] = 0;
      l->ca = pos;
      l->clen = k;
    }
    p = l->chunk + (pos - l->ca);
    l->pb = (uintptr_t)l->chunk - l->ca;
  }
  l->p = p;
  l->cb = (uintptr_t)p - col;
  l->mbend = NULL;
}

void lex_init(struct lex *l, const char *s, size_t n, struct diag_list *d)
{
  memset(l, 0, sizeof *l);
  l->s = s;
  l->n = n;
  l->line = 1;
  l->d = d;
  l->number = -1;
  size_t pos = 0;
  /* A UTF-8 byte-order mark is not part of the program. */
  if (n >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0)
    pos = 3;
  /* the last line: after the last LF or CR, which only lex_adv passes */
  size_t t = n;
  while (t > pos && s[t - 1] != '\n' && s[t - 1] != '\r')
    t--;
  l->tail = t;
  l->ca = n + 1;   /* no chunk yet */
  setp(l, pos, 1, 1);
}

/* The significant character from byte pos (column col) on, mapped, or
 * LX_EOB, LX_EOF: *pos and *col move to its start past what is not
 * significant, *len gets its bytes (0 at the end; ПС is one end of
 * block), *cyr is set for a Cyrillic look-alike.  The notes (a look-alike,
 * CR line ends) are made here, once a file. */
static int32_t scan(struct lex *l, size_t *ppos, unsigned *pcol, size_t *plen, int *cyr)
{
  size_t pos = *ppos, len = 0;
  unsigned col = *pcol;
  int32_t c;
  for (;;) {
    if (pos >= l->n) {
      c = LX_EOF;
      len = 0;
      break;
    }
    unsigned char b = (unsigned char)l->s[pos];
    if (plain(b)) {
      c = b;
      len = 1;
      break;
    }
    if (b == ' ') {
      pos++;
      col++;
      continue;
    }
    c = decode(l, pos, &len);
    if (c == '\r' && lone_cr(l, pos)) {
      if (!l->cr_noted) {
        l->cr_noted = 1;
        diag_add(l->d, DIAG_NOTE, 0, l->line, col, l->number,
                 "lines end with CR alone (an old Mac OS file): each CR is read as a line end");
      }
      c = '\n';
    }
    if (c == '\t' || c == '\r' || c == '\f' || c == '\v') {   /* (a CR here is the CR of CR LF) */
      pos += len;
      col++;
      continue;
    }
    if (c == ';') {          /* comment to the end of the line */
      while (pos < l->n && l->s[pos] != '\n' && !lone_cr(l, pos)) {
        decode(l, pos, &len);
        pos += len;
        col++;
      }
      continue;
    }
    if (c == '\n' || c == '^') {
      c = LX_EOB;
    } else if (c == 0x041F) {   /* П: ПС ends the block */
      size_t len2;
      if (pos + len < l->n) {
        int32_t c2 = decode(l, pos + len, &len2);
        if (c2 == 0x0421 || c2 == 'C') {
          len += len2;
          c = LX_EOB;
        }
      }
    } else {
      int32_t m = utf8_latin_lookalike(c);
      if (m) {
        if (!l->noted) {
          l->noted = 1;
          l->note = l->d->n;
          l->note_here = 1;
          diag_add(l->d, DIAG_NOTE, 0, l->line, col, l->number,
                   "Cyrillic look-alike letters are read as the Latin ones (first here)");
        }
        *cyr = 1;
        c = m;
      }
    }
    break;
  }
  *ppos = pos;
  *pcol = col;
  *plen = len;
  return c;
}

/* lex_slow past its short ways: the character from the cursor on, by scan. */
static int32_t __attribute__((noinline)) lex_general(struct lex *l)
{
  size_t pos = lex_pos(l), len;
  unsigned col = lex_col(l), col0 = col;
  int cyr = 0;
  int32_t c = scan(l, &pos, &col, &len, &cyr);
  l->skipped += col - col0;
  if (c < 0) {   /* the cursor at the end mark, not consumed */
    setp(l, pos, col, 1);
    return c;
  }
  setp(l, pos, col, len);
  /* at the character's last byte, its column kept */
  l->p += len - 1;
  l->cb += len - 1;
  l->mbend = l->p;
  l->mbc = c;
  l->mbcyr = cyr;
  return c;
}

int32_t lex_slow(struct lex *l)
{
  const unsigned char *p = l->p;
  if (*p == ' ') {   /* the space between words (never a character lexed here) */
    const unsigned char *q = p + 1;
    while (*q == ' ')
      q++;
    l->skipped += (unsigned)(q - p);
    l->p = q;
    int32_t c = lex_val[*q];
    if (c != LX_SLOW)
      return c;
  } else if (p == l->mbend) {
    return l->mbc;
  }
  return lex_general(l);
}

void lex_adv(struct lex *l)
{
  const unsigned char *p = l->p;
  if (p == l->mbend || lex_val[*p] >= 0 || *p == '^') {
    l->p = p + 1;
    return;
  }
  if (*p == '\n') {   /* the usual line end: the next line in the text itself, but the last */
    size_t pos = lex_pos(l) + 1;
    l->line++;
    if (pos < l->tail) {
      l->p = p + 1;
      l->cb = (uintptr_t)p;
    } else {
      setp(l, pos, 1, 1);
    }
    return;
  }
  /* an end of block (or of the file, which stays) */
  size_t pos = lex_pos(l), len;
  unsigned col = lex_col(l);
  int cyr = 0;
  int32_t c = scan(l, &pos, &col, &len, &cyr);
  if (c == LX_EOF)
    return;
  if (l->s[pos] == '\n' || l->s[pos] == '\r') {
    l->line++;
    setp(l, pos + len, 1, 1);
  } else {   /* ^, ПС */
    setp(l, pos + len, col + (len > 1 ? 2 : 1), 1);
  }
}

int32_t lex_peek2_slow(struct lex *l)
{
  size_t pos = lex_pos(l) + 1, len;
  unsigned col = lex_col(l) + 1;
  int cyr = 0;
  return scan(l, &pos, &col, &len, &cyr);
}

/* lex_ahead_next past its plain characters: the first, and what scan
 * reads. */
int32_t lex_ahead_slow(struct lex *l, struct lex_ahead *a)
{
  if (a->first) {
    a->first = 0;
    return lex_peek(l);
  }
  size_t len;
  int cyr = 0;
  int32_t c = scan(l, &a->pos, &a->col, &len, &cyr);
  a->pos += len;
  a->col++;
  return c;
}

int32_t lex_raw_peek(struct lex *l)
{
  size_t pos = lex_pos(l);
  if (pos >= l->n)
    return LX_EOF;
  size_t len;
  int32_t c = decode(l, pos, &len);
  if (c == '\n' || c == '^' || c == '\r')   /* CR alone, or the CR of CR LF */
    return LX_EOB;
  return c;
}

void lex_raw_adv(struct lex *l)
{
  size_t pos = lex_pos(l), len;
  unsigned col = lex_col(l);
  int32_t c = decode(l, pos, &len);
  if (c == '\n' || (c == '\r' && lone_cr(l, pos))) {
    l->line++;
    col = 1;
  } else {
    col++;
  }
  setp(l, pos + len, col, 1);
}

int lex_cyrillic(const struct lex *l)
{
  return l->p == l->mbend && l->mbcyr;
}

void lex_set_number(struct lex *l, int number)
{
  /* a note made in this block before its number was read is this block's */
  if (l->note_here && l->note < l->d->n)
    l->d->v[l->note].number = number;
  l->number = number;
}

void lex_skip_block(struct lex *l)
{
  for (;;) {
    int32_t c = lex_peek(l);
    if (c == LX_EOB || c == LX_EOF)
      return;
    lex_adv1(l);
  }
}

/* ---- a file that is not UTF-8 ---- */

/* The Cyrillic letter (0 = А .. 31 = Я, 32 = Ukrainian І, -1 none) that
 * byte b stands for in an 8-bit encoding. */
static int letter_cp1251(unsigned b)
{
  if (b >= 0xC0) return (int)(b & 0x1F);
  return b == 0xB2 || b == 0xB3 ? 32 : b == 0xAA || b == 0xBA || b == 0xAF || b == 0xBF ? 33 : -1;
}

static int letter_koi8(unsigned b)
{
  /* KOI8's 0xC0..0xDF (small) and 0xE0..0xFF (capital) in this order */
  static const signed char ord[32] = {30, 0, 1, 22, 4, 5, 20, 3, 21, 8, 9, 10, 11, 12, 13, 14,
                                      15, 31, 16, 17, 18, 19, 6, 2, 28, 27, 7, 24, 29, 25, 23, 26};
  if (b >= 0xC0) return ord[b & 0x1F];
  return b == 0xB6 || b == 0xA6 ? 32 : b == 0xB4 || b == 0xA4 || b == 0xB7 || b == 0xA7 ? 33 : -1;
}

static int letter_cp866(unsigned b)
{
  if (b >= 0x80 && b <= 0xAF) return (int)((b - 0x80) & 0x1F);
  if (b >= 0xE0 && b <= 0xEF) return (int)(b - 0xE0 + 16);
  return b >= 0xF2 && b <= 0xF5 ? 33 : -1;
}

/* How much the high bytes read like Russian or Ukrainian text: the common
 * letters count, bytes that are no letter count against. */
static long score(const unsigned char *s, size_t n, int (*letter)(unsigned))
{
  /* О Е А И Н Т С Р В Л К М Д П У, and І */
  static const unsigned long common = 1ul << 14 | 1ul << 5 | 1ul << 0 | 1ul << 8 | 1ul << 13 | 1ul << 18 |
                                      1ul << 17 | 1ul << 16 | 1ul << 2 | 1ul << 11 | 1ul << 10 | 1ul << 12 |
                                      1ul << 4 | 1ul << 15 | 1ul << 19 | 1ul << 32;
  long sc = 0;
  for (size_t i = 0; i < n; i++) {
    if (s[i] < 0x80)
      continue;
    int l = letter(s[i]);
    sc += l < 0 ? -2 : (common >> l) & 1 ? 3 : 1;
  }
  return sc;
}

/* The 64 bytes at t or'ed together eight at a time (in registers). */
static inline uint64_t high64(const char *t)
{
  uint64_t a, b, c, d, e, f, g, h;
  memcpy(&a, t, 8);
  memcpy(&b, t + 8, 8);
  memcpy(&c, t + 16, 8);
  memcpy(&d, t + 24, 8);
  memcpy(&e, t + 32, 8);
  memcpy(&f, t + 40, 8);
  memcpy(&g, t + 48, 8);
  memcpy(&h, t + 56, 8);
  return (a | b) | (c | d) | (e | f) | (g | h);
}

int lex_find_bad_utf8(const char *text, size_t n, unsigned *line, unsigned *col, unsigned *byte, const char **enc)
{
  struct lex l;
  struct diag_list none;
  diag_init(&none, NULL);
  lex_init(&l, text, n, &none);
  *enc = NULL;
  size_t bad = n, highs = 0, len;
  for (size_t p = lex_pos(&l); p < n; p += len) {
    /* ASCII, 64 and then eight bytes at a time: most programs are nothing else */
    while (p + 64 <= n && !(high64(text + p) & 0x8080808080808080ull))
      p += 64;
    uint64_t w8;
    while (p + 8 <= n && (memcpy(&w8, text + p, 8), !(w8 & 0x8080808080808080ull)))
      p += 8;
    if (p >= n)
      break;
    int32_t c = decode(&l, p, &len);
    if (c == 0xFFFD && len == 1) {   /* a U+FFFD written as such is a character */
      if (bad == n)
        bad = p;
      highs++;
    }
  }
  diag_free(&none);
  if (bad == n)
    return 0;
  /* line and column of the first bad byte, as the lexer counts them */
  unsigned ln = 1, cl = 1;
  for (size_t p = lex_pos(&l); p < bad; p += len) {
    int32_t c = decode(&l, p, &len);
    if (c == '\n' || (c == '\r' && lone_cr(&l, p))) {
      ln++;
      cl = 1;
    } else {
      cl++;
    }
  }
  *line = ln;
  *col = cl;
  *byte = (unsigned char)text[bad];
  /* a text in an 8-bit Cyrillic encoding reads mostly as common letters in
   * one of them (1.5 points a byte and more); a stray byte or two does not */
  const unsigned char *u = (const unsigned char *)text;
  size_t nhigh = 0;
  for (size_t p = 0; p < n; p++)
    nhigh += u[p] >= 0x80;
  long a = score(u, n, letter_cp1251), b = score(u, n, letter_koi8), c = score(u, n, letter_cp866);
  long best = a >= b && a >= c ? a : b >= c ? b : c;
  if (highs >= 4 && 2 * best >= 3 * (long)nhigh)
    *enc = a >= b && a >= c ? "cp1251" : b >= c ? "koi8-u" : "cp866";
  return 1;
}
