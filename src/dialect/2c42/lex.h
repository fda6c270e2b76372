/* The 2С42 lexer: a cursor over UTF-8 program text, driven by the parser.
 * Outside text it skips spaces, tabs and `;` comments, maps the Cyrillic
 * look-alike letters to Latin (noting it once per file) and turns newline,
 * `^` and `ПС` into an end-of-block mark; inside a slash argument it gives
 * the characters as they are. */
#ifndef S42_LEX_H
#define S42_LEX_H

#include "diag.h"
#include <stddef.h>
#include <stdint.h>

#define LX_EOB (-1)   /* end of block: newline, ^ or ПС */
#define LX_EOF (-2)

struct lex {
  const char *s;
  size_t n, pos;          /* pos: next unread byte */
  unsigned line, col;     /* of pos (1-based, columns count characters) */
  struct diag_list *d;
  int number;             /* the current block's number, for diagnostics */
  int noted;              /* look-alike note given */
  size_t note;            /* its index in d (for the block number), if given */
  int note_here;          /* ... during the current block (the parser clears it) */
  int cr_noted;           /* CR-only line ends noted */
  unsigned blen;          /* significant characters of the current block */
  /* what lex_peek saw: c, at pos, line and col (peeking skips to it); ccol
   * stays its column after it is consumed (for diagnostics).  peeked 2: a
   * plain ASCII byte, which lex_adv steps over by itself; 1: anything else,
   * which lex_adv leaves for cnext, cnline, cncol.  A block never spans
   * lines, so its characters' line is `line` until its newline is consumed. */
  int peeked;
  int32_t c;
  unsigned ccol;
  size_t cnext;
  unsigned cnline, cncol;
};

struct lex_mark { size_t pos; unsigned line, col, blen; };

void lex_init(struct lex *l, const char *s, size_t n, struct diag_list *d);

/* lex_peek's fast path, over bytes with no call: 1 for an ASCII byte that
 * is a character of its own -- not whitespace, not ';' '^' CR LF (which
 * lex_peek_slow reads: comments, line ends, UTF-8, the look-alikes, ПС). */
extern const uint8_t lex_plain[256];
int32_t lex_peek_slow(struct lex *l);

/* The next significant character (mapped), LX_EOB or LX_EOF; not consumed. */
static inline int32_t lex_peek(struct lex *l)
{
  /* the parser peeks the same character many times: answer from the cache
   * while the cursor has not moved */
  if (l->peeked)   /* cleared by everything that moves the cursor */
    return l->c;
  size_t pos = l->pos;
  unsigned col = l->col;
  while (pos < l->n) {
    unsigned char b = (unsigned char)l->s[pos];
    if (b == ' ') {   /* the space between words: a column, nothing else */
      pos++;
      col++;
      continue;
    }
    if (!lex_plain[b])
      break;
    l->pos = pos;
    l->col = l->ccol = col;
    l->peeked = 2;
    return l->c = b;
  }
  l->pos = pos;
  l->col = col;
  return lex_peek_slow(l);
}

/* Consume what lex_peek returned (a whole ПС for LX_EOB); counts it. */
static inline void lex_adv(struct lex *l)
{
  if (l->peeked == 2) {   /* a plain byte: one byte, one column */
    l->pos++;
    l->col++;
    l->blen++;
  } else {
    if (l->c >= 0)
      l->blen++;
    l->pos = l->cnext;
    l->line = l->cnline;
    l->col = l->cncol;
  }
  l->peeked = 0;
}
/* After a lex_peek that returned a digit: consume the ASCII digits that
 * follow one another from there, as lex_peek and lex_adv would one by one;
 * *t gets the first, the count is returned (at least 1). */
static inline size_t lex_digit_run(struct lex *l, const char **t)
{
  size_t p = l->pos;   /* the digit peeked: pos is its place */
  while (p < l->n && l->s[p] >= '0' && l->s[p] <= '9')
    p++;
  size_t k = p - l->pos;
  *t = l->s + l->pos;
  l->peeked = 0;
  l->blen += (unsigned)k;
  l->col += (unsigned)k;
  l->pos = p;
  return k;
}
/* Raw access inside text: the next character as written, or LX_EOB at a
 * newline or ^ (which end the block even inside text), LX_EOF at the end. */
int32_t lex_raw_peek(struct lex *l);
void lex_raw_adv(struct lex *l);
/* The character lex_peek returned was a Cyrillic look-alike. */
int lex_cyrillic(const struct lex *l);
/* The current block's number is known now: diagnostics of this block made
 * before it (the look-alike note) name it too. */
void lex_set_number(struct lex *l, int number);
/* Skip the rest of a malformed block up to (not including) its end mark. */
void lex_skip_block(struct lex *l);
struct lex_mark lex_mark(const struct lex *l);
void lex_reset(struct lex *l, struct lex_mark m);
/* Is the text UTF-8?  0 when it is; otherwise 1 with the line, column and
 * value of the first byte that is not, and in *enc the 8-bit Cyrillic encoding
 * ("cp1251", "koi8-u", "cp866") the text reads best in, or NULL for a
 * stray byte. */
int lex_find_bad_utf8(const char *text, size_t n, unsigned *line, unsigned *col, unsigned *byte, const char **enc);

#endif
