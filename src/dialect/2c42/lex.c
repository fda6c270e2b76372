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

/* Every ASCII byte but whitespace, ';' '^' CR LF stands for itself. */
static const uint8_t lex_plain[256] = {
  /* 0x00..0x1F: controls are characters (which no word accepts), but TAB
   * LF VT FF CR are whitespace or line ends */
  1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 1, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
  /* ' ' is whitespace, ';' a comment, '^' an end */
  0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
  1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
  /* 0x80..0xFF: UTF-8, decoded by lex_one */
};

/* The significant character at the cursor *pos (*line, *col), mapped, or
 * LX_EOB, LX_EOF; the cursor steps past it (not past the end of the file)
 * and *ccol gets its column.  *cyr is set for a Cyrillic look-alike.  The
 * notes (a look-alike, CR line ends) are made here, once a file. */
static int32_t lex_one(struct lex *l, size_t *ppos, unsigned *pline, unsigned *pcol, unsigned *ccol, int *cyr)
{
  size_t pos = *ppos, len;
  unsigned line = *pline, col = *pcol;
  int32_t c;
  for (;;) {
    if (pos >= l->n) {
      *ccol = col;
      c = LX_EOF;
      break;
    }
    unsigned char b = (unsigned char)l->s[pos];
    if (lex_plain[b]) {
      *ccol = col++;
      pos++;
      c = b;
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
        diag_add(l->d, DIAG_NOTE, 0, line, col, l->number,
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
    *ccol = col;
    pos += len;
    col++;
    if (c == '\n') {
      line++;
      col = 1;
      c = LX_EOB;
    } else if (c == '^') {
      c = LX_EOB;
    } else if (c == 0x041F) {   /* П: ПС ends the block */
      size_t len2;
      if (pos < l->n) {
        int32_t c2 = decode(l, pos, &len2);
        if (c2 == 0x0421 || c2 == 'C') {
          pos += len2;
          col++;
          c = LX_EOB;
        }
      }
    } else {
      int32_t m = lookalike(c);
      if (m) {
        if (!l->noted) {
          l->noted = 1;
          l->note = l->d->n;
          l->note_here = 1;
          diag_add(l->d, DIAG_NOTE, 0, line, *ccol, l->number,
                   "Cyrillic look-alike letters are read as the Latin ones (first here)");
        }
        *cyr = 1;
        c = m;
      }
    }
    break;
  }
  *ppos = pos;
  *pline = line;
  *pcol = col;
  return c;
}

/* What fill() does with each byte: a plain character is one of its own
 * (lex_plain); a space is skipped; a '/' ends the run after it (the text
 * of a slash argument may follow, which is not lexed); '^' and a newline
 * end the block, and the run after them; anything else is lex_one's. */
enum { LC_OTHER, LC_PLAIN, LC_SPACE, LC_SLASH, LC_CARET, LC_NL };
static uint8_t lex_class[256];

static void __attribute__((constructor)) lex_class_init(void)
{
  for (int b = 0; b < 256; b++)
    lex_class[b] = lex_plain[b] ? LC_PLAIN : LC_OTHER;
  lex_class[' '] = LC_SPACE;
  lex_class['/'] = LC_SLASH;
  lex_class['^'] = LC_CARET;
  lex_class['\n'] = LC_NL;
}

/* Lex more into the window at wn (which is below LX_WIN): a run of plain
 * characters up to the next one that is not (after a '/', an end of block,
 * or a '^' and the newline right after it), or else that one character. */
static inline __attribute__((always_inline)) void fill(struct lex *l)
{
  const unsigned char *s = (const unsigned char *)l->s;
  size_t pos = l->pos, lim = l->n;
  size_t n = l->wn, start = n;
  int32_t *wc = l->wc;
  unsigned *wcol = l->wcol;
  if (lim - pos > LX_WIN - 1 - n)   /* a byte makes one entry at most, and a ^ newline two */
    lim = pos + (LX_WIN - 1 - n);
  /* ASCII only: the column of byte p is base + p */
  unsigned base = l->col - (unsigned)pos;
  int nl = 0;
  unsigned ends = 0;   /* end marks made: they are not counted in blen */
  l->wline = l->line;
  for (; pos < lim; pos++) {
    unsigned b = s[pos], k = lex_class[b];
    if (k == LC_PLAIN) {
      wc[n] = (int32_t)b;
      wcol[n] = base + (unsigned)pos;
      n++;
      continue;
    }
    if (k == LC_SPACE)   /* the space between words: a column, nothing else */
      continue;
    if (k == LC_OTHER)
      break;
    wc[n] = k == LC_SLASH ? '/' : LX_EOB;
    wcol[n++] = base + (unsigned)pos++;
    ends = k != LC_SLASH;
    if (k == LC_CARET && pos < l->n && s[pos] == '\n') {   /* the usual end of a line: ^ and a newline */
      wc[n] = LX_EOB;
      wcol[n++] = base + (unsigned)pos++;
      ends = 2;
      k = LC_NL;
    }
    nl = k == LC_NL;
    break;
  }
  l->blen += n - start - ends;
  l->pos = pos;
  if (nl) {
    l->line++;
    l->col = 1;
  } else {
    l->col = base + (unsigned)pos;
  }
  if (n == start) {
    int cyr = 0;
    int32_t c = lex_one(l, &l->pos, &l->line, &l->col, &wcol[n], &cyr);
    wc[n++] = c;
    if (cyr)
      l->cyr = n;
    if (c >= 0)
      l->blen++;
  }
  l->wn = n;
}

/* Room for one more character in the window: what is unread moves to its
 * start when it is full. */
static void room(struct lex *l)
{
  if (l->wn < LX_WIN)
    return;
  size_t k = l->wn - l->wi;
  memmove(l->wc, l->wc + l->wi, k * sizeof *l->wc);
  memmove(l->wcol, l->wcol + l->wi, k * sizeof *l->wcol);
  l->cyr = l->cyr > l->wi ? l->cyr - l->wi : 0;
  l->wi = 0;
  l->wn = k;
}

int32_t lex_more(struct lex *l)
{
  if (l->wi >= l->wn)   /* all read: start again at 0 */
    l->wi = l->wn = l->cyr = 0;
  else
    room(l);
  fill(l);
  return l->wc[l->wi];
}

int32_t lex_peek2(struct lex *l)
{
  if (l->wi + 1 >= l->wn) {
    room(l);
    fill(l);
  }
  return l->wc[l->wi + 1];
}

void lex_ahead_start(const struct lex *l, struct lex_ahead *a)
{
  a->i = l->wi;
  a->pos = l->pos;
  a->line = l->line;
  a->col = l->col;
}

int32_t lex_ahead_next(struct lex *l, struct lex_ahead *a)
{
  if (a->i < l->wn)
    return l->wc[a->i++];
  unsigned ccol;
  int cyr = 0;
  return lex_one(l, &a->pos, &a->line, &a->col, &ccol, &cyr);
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
  size_t len;
  int32_t c = decode(l, l->pos, &len);
  l->blen++;
  l->pos += len;
  if (c == '\n' || (c == '\r' && lone_cr(l, l->pos - len))) {
    l->line++;
    l->col = 1;
  } else {
    l->col++;
  }
}

int lex_cyrillic(const struct lex *l)
{
  return l->cyr == l->wi + 1;
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
    /* ASCII, 32 and then eight bytes at a time: most programs are nothing else */
    uint64_t w8, w[4];
    while (p + 32 <= n && (memcpy(w, text + p, 32), !((w[0] | w[1] | w[2] | w[3]) & 0x8080808080808080ull)))
      p += 32;
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
