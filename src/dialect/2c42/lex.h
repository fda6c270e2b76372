/* The 2С42 lexer: the significant characters of UTF-8 program text, lexed
 * ahead into a window the parser reads.  Outside text it skips spaces,
 * tabs and `;` comments, maps the Cyrillic look-alike letters to Latin
 * (noting it once per file) and turns newline, `^` and `ПС` into an
 * end-of-block mark; inside a slash argument it gives the characters as
 * they are (the lex_raw_ calls, on the bytes after the window).
 *
 * The window: wc[wi..wn) are characters lexed and not yet consumed, wcol
 * their columns.  A run of plain ASCII is lexed in one go; anything else
 * (whitespace but the space, comments, line ends, UTF-8) one character at
 * a time and only when the parser asks for it, so that a note about it is
 * made when the parser first looks at it -- the lexer never lexes a
 * character the parser would not have looked at yet, but for plain ones,
 * which note nothing.  A run ends after a '/' (the text of a slash
 * argument may follow, which is not lexed) and never goes past the end of
 * the block. */
#ifndef S42_LEX_H
#define S42_LEX_H

#include "diag.h"
#include <stddef.h>
#include <stdint.h>

#define LX_EOB (-1)   /* end of block: newline, ^ or ПС */
#define LX_EOF (-2)
#define LX_WIN 256    /* characters the window holds */

struct lex {
  const char *s;
  size_t n, pos;          /* pos: the next byte not lexed */
  unsigned line, col;     /* of pos (1-based, columns count characters) */
  unsigned wline;         /* the line of the window's characters (a block's are on one) */
  struct diag_list *d;
  int number;             /* the current block's number, for diagnostics */
  int noted;              /* look-alike note given */
  size_t note;            /* its index in d (for the block number), if given */
  int note_here;          /* ... during the current block (the parser clears it) */
  int cr_noted;           /* CR-only line ends noted */
  unsigned blen;          /* significant characters lexed in the current block */
  size_t wi, wn;          /* the window: next to read, end (size_t: no int or unsigned store aliases them) */
  unsigned cyr;           /* 1 + the window index of a Cyrillic look-alike lexed, 0 none */
  int32_t wc[LX_WIN];     /* the characters (mapped), LX_EOB or LX_EOF */
  unsigned wcol[LX_WIN];  /* their columns */
};

void lex_init(struct lex *l, const char *s, size_t n, struct diag_list *d);

/* Lexes at least one more character into the window (at wn); the window
 * restarts at 0 when everything in it was read.  Returns wc[wi]. */
int32_t lex_more(struct lex *l);

/* The next significant character (mapped), LX_EOB or LX_EOF; not consumed. */
static inline int32_t lex_peek(struct lex *l)
{
  return l->wi < l->wn ? l->wc[l->wi] : lex_more(l);
}
/* Consume what lex_peek returned. */
static inline void lex_adv(struct lex *l)
{
  l->wi++;
}
/* The column of what lex_peek returned (after a lex_peek). */
static inline unsigned lex_col(const struct lex *l)
{
  return l->wcol[l->wi];
}
/* The column of the character consumed last (right after a lex_adv, before
 * the next lex_peek, which may restart the window). */
static inline unsigned lex_prev_col(const struct lex *l)
{
  return l->wcol[l->wi - 1];
}
/* The line of what lex_peek returned (after a lex_peek). */
static inline unsigned lex_line(const struct lex *l)
{
  return l->wline;
}
/* The character after the one lex_peek returned (which is not an end). */
int32_t lex_peek2(struct lex *l);
/* Walk the characters from the one lex_peek returned on without consuming
 * them: lex_ahead_start, then lex_ahead_next for each (the first is that
 * one), up to an end of block or file (not past it).  Those after the
 * window are lexed on a copy of the cursor, and lexed again when read:
 * their notes are made the first time, as lex_peek would. */
struct lex_ahead { unsigned i; size_t pos; unsigned line, col; };
void lex_ahead_start(const struct lex *l, struct lex_ahead *a);
int32_t lex_ahead_next(struct lex *l, struct lex_ahead *a);
/* Raw access inside text, on the bytes after the window (which must be
 * read to its end): the next character as written, or LX_EOB at a newline
 * or ^ (which end the block even inside text), LX_EOF at the end. */
int32_t lex_raw_peek(struct lex *l);
void lex_raw_adv(struct lex *l);
/* The character lex_peek returned was a Cyrillic look-alike. */
int lex_cyrillic(const struct lex *l);
/* The current block's number is known now: diagnostics of this block made
 * before it (the look-alike note) name it too. */
void lex_set_number(struct lex *l, int number);
/* Skip the rest of a malformed block up to (not including) its end mark. */
void lex_skip_block(struct lex *l);
/* Is the text UTF-8?  0 when it is; otherwise 1 with the line, column and
 * value of the first byte that is not, and in *enc the 8-bit Cyrillic encoding
 * ("cp1251", "koi8-u", "cp866") the text reads best in, or NULL for a
 * stray byte. */
int lex_find_bad_utf8(const char *text, size_t n, unsigned *line, unsigned *col, unsigned *byte, const char **enc);

#endif
