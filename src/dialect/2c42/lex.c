/* The 2С42 lexer (src/dialect/2c42/lex.h). */
#include "lex.h"
#include "utf8.h"
#include "errors.h"
#include <string.h>

void lex_init(struct lex *l, const char *s, size_t n, struct diag_list *d)
{
  memset(l, 0, sizeof *l);
  l->s = s;
  l->n = n;
  l->line = l->col = 1;
  l->d = d;
  l->number = -1;
  /* A UTF-8 byte-order mark is not part of the program. */
  if (n >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0)
    l->pos = 3;
}

/* Decode one code point at p; *len gets its byte length.  Invalid UTF-8 is
 * returned as U+FFFD (one byte), which no word accepts. */
static int32_t decode(const struct lex *l, size_t p, size_t *len)
{
  return utf8_decode((const unsigned char *)l->s + p, l->n - p, len);
}


/* Cyrillic capitals that look like Latin ones: А В С Е Н К М О Р Т Х. */
static int32_t lookalike(int32_t c)
{
  return utf8_latin_lookalike(c);
}

/* A CR not followed by LF ends a line (classic Mac OS files); in CR LF the
 * CR is only whitespace and the LF ends the line. */
static int lone_cr(const struct lex *l, size_t p)
{
  return l->s[p] == '\r' && (p + 1 >= l->n || l->s[p + 1] != '\n');
}

static void step(struct lex *l, size_t len, int32_t c)
{
  int eol = c == '\n' || (c == '\r' && lone_cr(l, l->pos));
  l->pos += len;
  if (eol) {
    l->line++;
    l->col = 1;
  } else {
    l->col++;
  }
}

/* Every ASCII byte but whitespace, ';' '^' CR LF stands for itself. */
const uint8_t lex_plain[256] = {
  /* 0x00..0x1F: controls are characters (which no word accepts), but TAB
   * LF VT FF CR are whitespace or line ends */
  1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 1, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
  /* ' ' is whitespace (lex_peek skips it itself), ';' a comment, '^' an end */
  0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
  /* 0x80..0xFF: UTF-8, decoded by lex_peek_slow */
};

int32_t lex_peek_slow(struct lex *l)
{
  if (l->peeked)
    return l->c;
  l->peeked = 1;
  /* the end of nearly every block first: ^ or a newline right here */
  if (l->pos < l->n && (l->s[l->pos] == '^' || l->s[l->pos] == '\n')) {
    int nl = l->s[l->pos] == '\n';
    l->c = LX_EOB;
    l->ccol = l->col;
    l->cnext = l->pos + 1;
    l->cnline = l->line + (unsigned)nl;
    l->cncol = nl ? 1 : l->col + 1;
    return LX_EOB;
  }
  for (;;) {
    if (l->pos >= l->n) {
      l->c = LX_EOF;
      l->cnext = l->pos;
      l->cnline = l->line;
      l->ccol = l->cncol = l->col;
      return LX_EOF;
    }
    size_t len;
    int32_t c = decode(l, l->pos, &len);
    if (c == '\r' && lone_cr(l, l->pos)) {
      if (!l->cr_noted) {
        l->cr_noted = 1;
        diag_add(l->d, DIAG_NOTE, 0, l->line, l->col, l->number,
                 "lines end with CR alone (an old Mac OS file): each CR is read as a line end");
      }
      c = '\n';
    }
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      step(l, len, c);
      continue;
    }
    if (c == ';') {          /* comment to the end of the line */
      while (l->pos < l->n && l->s[l->pos] != '\n' && !lone_cr(l, l->pos)) {
        c = decode(l, l->pos, &len);
        step(l, len, c);
      }
      continue;
    }
    l->c = c;
    l->ccol = l->col;
    l->cnext = l->pos + len;
    l->cnline = l->line;
    l->cncol = l->col + 1;
    if (c == '\n') {
      l->cnline = l->line + 1;
      l->cncol = 1;
      l->c = LX_EOB;
    } else if (c == '^') {
      l->c = LX_EOB;
    } else if (c == 0x041F) {   /* П: ПС ends the block */
      size_t len2;
      if (l->cnext < l->n) {
        int32_t c2 = decode(l, l->cnext, &len2);
        if (c2 == 0x0421 || c2 == 'C') {
          l->cnext += len2;
          l->cncol++;
          l->c = LX_EOB;
        }
      }
    } else {
      int32_t m = lookalike(c);
      if (m) {
        if (!l->noted) {
          l->noted = 1;
          l->note = l->d->n;
          l->note_here = 1;
          diag_add(l->d, DIAG_NOTE, 0, l->line, l->col, l->number,
                   "Cyrillic look-alike letters are read as the Latin ones (first here)");
        }
        l->c = m;
      }
    }
    return l->c;
  }
}

int32_t lex_raw_peek(struct lex *l)
{
  if (l->pos >= l->n)
    return LX_EOF;
  size_t len;
  int32_t c = decode(l, l->pos, &len);
  if (c == '\n' || c == '^' || c == '\r')   /* CR alone, or the CR of CR LF */
    return LX_EOB;
  return c;
}

void lex_raw_adv(struct lex *l)
{
  l->peeked = 0;
  size_t len;
  int32_t c = decode(l, l->pos, &len);
  l->blen++;
  step(l, len, c);
}

int lex_cyrillic(const struct lex *l)
{
  return l->peeked && l->pos < l->n && (unsigned char)l->s[l->pos] >= 0x80;
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
    lex_adv(l);
  }
}

struct lex_mark lex_mark(const struct lex *l)
{
  struct lex_mark m = {l->pos, l->line, l->col, l->blen};
  return m;
}

void lex_reset(struct lex *l, struct lex_mark m)
{
  l->pos = m.pos;
  l->line = m.line;
  l->col = m.col;
  l->blen = m.blen;
  l->peeked = 0;
  lex_peek(l);   /* what lex_adv consumes must be this position's character */
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

int lex_find_bad_utf8(const char *text, size_t n, unsigned *line, unsigned *col, unsigned *byte, const char **enc)
{
  struct lex l;
  struct diag_list none;
  diag_init(&none, NULL);
  lex_init(&l, text, n, &none);
  *enc = NULL;
  size_t bad = n, highs = 0, len;
  for (size_t p = l.pos; p < n; p += len) {
    /* ASCII, eight bytes at a time: most programs are nothing else */
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
  for (size_t p = l.pos; p < bad; p += len) {
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
