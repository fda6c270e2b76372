/* The 2С42 lexer: the significant characters of UTF-8 program text, read
 * by the parser straight from the text's bytes.  Outside text it skips
 * spaces, tabs and `;` comments, maps the Cyrillic look-alike letters to
 * Latin (noting it once per file) and turns newline, `^` and `ПС` into an
 * end-of-block mark; inside a slash argument it gives the characters as
 * they are (the lex_raw_ calls).
 *
 * The cursor p points at the byte of the character lex_peek returns: a
 * plain ASCII one (lex_val) is that byte, read inline, and so are '^' and
 * LF as the end of block they are (one space before a plain one passed
 * inline too: lex_unplain); anything else -- spaces, whitespace, comments,
 * line ends, UTF-8 -- is lexed by lex_slow when the parser first looks at
 * it, which makes the notes about it then, as a character at a time.  A
 * character of several bytes leaves p at its last byte (its value kept in
 * mbc), so that one step on
 * from any character is p + 1.  Columns are not counted: the column of p
 * is p - cb, the base moved only where a character is not one byte (and
 * at a line end).  The last line of the text (after its last line end,
 * all of it when it has none) is read from copies of LX_CHUNK bytes ended
 * by a NUL, so that the inline reads never pass the text's end; p's byte
 * index in the text is p - pb either way. */
#ifndef S42_LEX_H
#define S42_LEX_H

#include "diag.h"
#include <stddef.h>
#include <stdint.h>

#define LX_EOB (-1)   /* end of block: newline, ^ or ПС */
#define LX_EOF (-2)
#define LX_CHUNK 64   /* bytes of the last line copied at a time */

struct lex {
  const unsigned char *p;     /* the cursor (see above) */
  uintptr_t cb;               /* the column of p is p - cb */
  uintptr_t pb;               /* the byte index of p in s is p - pb */
  const unsigned char *mbend; /* p when the character there was lexed by lex_slow (NULL none) */
  int32_t mbc;                /* ... the character's value (mapped) */
  int mbcyr;                  /* ... it was a Cyrillic look-alike */
  const char *s;
  size_t n;
  size_t tail;                /* the last line starts here: from it on p reads chunk */
  size_t ca, clen;            /* the bytes in chunk: s[ca .. ca + clen) */
  unsigned line;              /* of p */
  unsigned skipped;           /* whitespace and comment characters passed since lex_block_begin */
  struct diag_list *d;
  int number;                 /* the current block's number, for diagnostics */
  int noted;                  /* look-alike note given */
  size_t note;                /* its index in d (for the block number), if given */
  int note_here;              /* ... during the current block (the parser clears it) */
  int cr_noted;               /* CR-only line ends noted */
  unsigned char chunk[LX_CHUNK + 1];
};

/* What lex_peek makes of a byte at the cursor: an ASCII byte that stands
 * for itself (all but whitespace, ';' '^' CR LF and NUL) is that
 * character, '^' and LF are LX_EOB, and anything else is LX_SLOW, lex_slow's
 * (a NUL is a character too, but ends a chunk: lex_slow tells which). */
#define LX_SLOW (-3)
extern const int16_t lex_val[256];

void lex_init(struct lex *l, const char *s, size_t n, struct diag_list *d);

/* The character at the cursor when its byte is not a plain one: skips
 * what is not significant (the cursor moves past it) and returns the next
 * significant character (mapped), LX_EOB or LX_EOF, not consumed. */
int32_t lex_slow(struct lex *l);

/* lex_slow, but the one space between words before a plain character
 * passed inline, as lex_slow would (the byte after a space is in the
 * text, or the chunk's NUL at the latest). */
static inline __attribute__((always_inline)) int32_t lex_unplain(struct lex *l)
{
  const unsigned char *p = l->p;
  if (*p == ' ') {
    int32_t c = lex_val[p[1]];
    if (c != LX_SLOW) {
      l->p = p + 1;
      l->skipped++;
      return c;
    }
  }
  return lex_slow(l);
}
/* The next significant character (mapped), LX_EOB or LX_EOF; not consumed. */
static inline __attribute__((always_inline)) int32_t lex_peek(struct lex *l)
{
  int32_t c = lex_val[*l->p];
  return c != LX_SLOW ? c : lex_unplain(l);
}
/* Consume what lex_peek returned, which is no end of block or file. */
static inline void lex_adv1(struct lex *l)
{
  l->p++;
}
/* Consume what lex_peek returned, an end of block too. */
void lex_adv(struct lex *l);
/* The byte index in the text of what lex_peek returned (of its last byte). */
static inline size_t lex_pos(const struct lex *l)
{
  return (size_t)((uintptr_t)l->p - l->pb);
}
/* Consume the end of block lex_peek returned, and with a ^ the line end
 * right after it (the end of an empty block: what lex_adv of both does). */
static inline void lex_end_block(struct lex *l)
{
  const unsigned char *p = l->p;
  if (*p == '^' && p[1] == '\n' && lex_pos(l) + 2 < l->tail) {   /* the usual end of a line */
    l->line++;
    l->p = p + 2;
    l->cb = (uintptr_t)p + 1;
    return;
  }
  lex_adv(l);
}
/* The column of what lex_peek returned (after a lex_peek). */
static inline unsigned lex_col(const struct lex *l)
{
  return (unsigned)((uintptr_t)l->p - l->cb);
}
/* The column of the character consumed last (right after a lex_adv1,
 * before the next lex_peek). */
static inline unsigned lex_prev_col(const struct lex *l)
{
  return (unsigned)((uintptr_t)l->p - 1 - l->cb);
}
/* The line of what lex_peek returned (after a lex_peek). */
static inline unsigned lex_line(const struct lex *l)
{
  return l->line;
}
/* The character after the one lex_peek returned (which is not an end). */
int32_t lex_peek2_slow(struct lex *l);
static inline int32_t lex_peek2(struct lex *l)
{
  int32_t c = lex_val[l->p[1]];
  return c != LX_SLOW ? c : lex_peek2_slow(l);
}
/* Walk the characters from the one lex_peek returned on without consuming
 * them: lex_ahead_start, then lex_ahead_next for each (the first is that
 * one), up to an end of block or file (not past it).  Those not looked at
 * yet are lexed on a copy of the cursor, and lexed again when read: their
 * notes are made the first time, as lex_peek would. */
struct lex_ahead { size_t pos; unsigned col; int first; };
static inline void lex_ahead_start(const struct lex *l, struct lex_ahead *a)
{
  a->pos = lex_pos(l) + 1;
  a->col = lex_col(l) + 1;
  a->first = 1;
}
int32_t lex_ahead_slow(struct lex *l, struct lex_ahead *a);
static inline int32_t lex_ahead_next(struct lex *l, struct lex_ahead *a)
{
  size_t pos = a->pos;
  if (!a->first && pos < l->n) {   /* a plain one (a NUL too) */
    unsigned char b = (unsigned char)l->s[pos];
    if (lex_val[b] >= 0 || b == 0) {
      a->pos = pos + 1;
      a->col++;
      return b;
    }
  }
  return lex_ahead_slow(l, a);
}
/* Raw access inside text, on the bytes at the cursor (after a consumed
 * character): the next character as written, or LX_EOB at a newline or ^
 * (which end the block even inside text), LX_EOF at the end. */
int32_t lex_raw_peek(struct lex *l);
void lex_raw_adv(struct lex *l);
/* The column of the cursor inside text. */
static inline unsigned lex_raw_col(const struct lex *l)
{
  return lex_col(l);
}
/* The character lex_peek returned was a Cyrillic look-alike. */
int lex_cyrillic(const struct lex *l);
/* The current block's number is known now: diagnostics of this block made
 * before it (the look-alike note) name it too. */
void lex_set_number(struct lex *l, int number);
/* Skip the rest of a malformed block up to (not including) its end mark. */
void lex_skip_block(struct lex *l);
/* A block's significant characters: lex_block_begin at its first one
 * (after a lex_peek of it), lex_block_len at its end mark (after a lex_peek
 * of it) with the first one's column; the characters of text count too. */
static inline void lex_block_begin(struct lex *l)
{
  l->skipped = 0;
}
static inline unsigned lex_block_len(const struct lex *l, unsigned col)
{
  return lex_col(l) - col - l->skipped;
}
/* Is the text UTF-8?  0 when it is; otherwise 1 with the line, column and
 * value of the first byte that is not, and in *enc the 8-bit Cyrillic encoding
 * ("cp1251", "koi8-u", "cp866") the text reads best in, or NULL for a
 * stray byte. */
int lex_find_bad_utf8(const char *text, size_t n, unsigned *line, unsigned *col, unsigned *byte, const char **enc);

#endif
