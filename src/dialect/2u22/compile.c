/* The 2У22 front end (spec/dialects/2u22.md): the text into blocks, each
 * block's words, the checks the text alone decides (D-33) and the bytecode
 * of u22.h.  Three steps:
 *
 *   lex_line    one line of text into the characters of its block: spaces,
 *               comments and the end mark ПС/PC dropped, look-alike
 *               Cyrillic capitals mapped to Latin, each with its column;
 *   parse_block those characters into a struct blk (its words, G and M,
 *               R assignments, L, H), with the digit limits of Table 1.1,
 *               the groups of Tables 1.2 and 1.3, repeated addresses;
 *   structure   (as each block is read) the main program and the sub area
 *               (D-14, D-29), the H ranges (sec. 6, D-12), skippable blocks;
 *               then, once every block is read, the calls (E-TARGET) and
 *               their nesting (E-NEST, D-28); and last emit.
 *
 * Decisions of this front end where the spec is silent (DEC):
 *  - the first line whose first non-blank character is % starts the
 *    program; after the % only blanks, ПС and comments; a later % is
 *    E-SYNTAX;
 *  - ПС/PC (either letter Latin or Cyrillic) ends the block: anything but
 *    blanks, comments and more marks after it on the line is E-SYNTAX (one
 *    block per line); inside a comment it is E-SYNTAX, as % and : are;
 *  - lowercase letters are no addresses (E-SYNTAX); look-alikes map as the
 *    2С42's do, so Cyrillic Н is H and Р is P (no address);
 *  - digits are counted as written (leading zeros count: X00000001 is 8);
 *    G and M 1-2 digits, N 1-5 (exactly 5 in the sub area); T 3 digits
 *    but T0..T99 (D-27); F S T E H are not negative (E-RANGE for a literal,
 *    the word's rule at run time for a parameter); G M N L H take no sign;
 *  - a function written twice is E-GROUP when it has a group, else
 *    E-BLOCK; M02 M17 M30 count as one group (a block ends one thing);
 *    G04 without E, and E without G04, are E-SYNTAX; with G25, X and Z are
 *    bare letters (G25 X100 E-SYNTAX);
 *  - R assignments take a number only (R1+R2 E-SYNTAX) and run before the
 *    block's words take their values (see emit_block);
 *  - one L and one H a block (a second is E-BLOCK); H and M20 in one block,
 *    and M20 with M02, M30 or M17 (the range would hold the end, and H0
 *    could not skip it) are E-SUB; M02 or M30 in a sub is E-SUB (a sub ends
 *    with M17); two subs of one number are E-TARGET;
 *  - E-NEST at check time follows the calls from the main program whose
 *    count is not 00; a sub never called is not followed;
 *  - each sub that has an H repeat gets its own pair of counters (u22.h).
 */
#include "u22.h"
#include "utf8.h"
#include "u22c.h"
#include "errors.h"
#include "opcodes.h"
#include "verify.h"
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- lexing */

/* One character of a block: the code point (look-alikes mapped to Latin)
 * and its column in the line (columns count characters, as diag does). */
struct ch {
  int32_t c;
  unsigned col;
};

#define CH_KEEP (U22_BLOCK_MAX + 2)   /* characters kept of a block; more is E-BLOCKLEN anyway */


/* Cyrillic capitals that look like Latin ones: А В С Е Н К М О Р Т Х (as
 * the 2С42 lexer maps them). */
static int32_t lookalike(int32_t c)
{
  int l = utf8_latin_lookalike(c);
  return l ? l : c;
}

static int blank(int32_t c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

/* A character for a message: "'Y'", "U+0416". */
static const char *show(int32_t c, char buf[32])
{
  if (c > 0x20 && c < 0x7F)
    snprintf(buf, 32, "'%c'", (char)c);
  else if (c == UTF8_BAD)
    snprintf(buf, 32, "a byte that is not UTF-8");
  else
    snprintf(buf, 32, "U+%04X", (unsigned)c);
  return buf;
}

struct cc;
static void err(struct cc *c, int code, unsigned line, unsigned col, int number, const char *fmt, ...)
  __attribute__((format(printf, 6, 7)));

/* The compile. */
struct blk;
struct cc {
  struct diag_list *d;
  struct program *p;
  struct blk *b;
  size_t nb, capb;
  int oom;
};

static void err(struct cc *c, int code, unsigned line, unsigned col, int number, const char *fmt, ...)
{
  char msg[240];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  diag_add(c->d, DIAG_ERROR, code, line, col, number, "%s", msg);
}

/* The end mark at s: ПС or PC, either letter Latin or Cyrillic (L585);
 * its length in bytes, or 0. */
static size_t end_mark(const unsigned char *s, size_t left)
{
  size_t l1, l2;
  if (!left)
    return 0;
  int32_t a = utf8_decode(s, left, &l1);
  if (a != 0x041F && a != 'P' && a != 0x0420)
    return 0;
  if (l1 >= left)
    return 0;
  int32_t b = utf8_decode(s + l1, left - l1, &l2);
  if (b != 0x0421 && b != 'C')
    return 0;
  return l1 + l2;
}

/* One line [s, e) of a program into the characters of its block (out,
 * CH_KEEP at most kept; *count gets them all).  0, or -1 after an error
 * was reported (*count: the characters kept before it). */
static int lex_line(struct cc *c, const unsigned char *s, const unsigned char *e, unsigned line, int number,
                    struct ch *out, size_t *count)
{
  unsigned col = 1, mark_col = 0;
  size_t n = 0;
  char b1[32];
  while (s < e) {
    size_t len;
    int32_t ch = utf8_decode(s, (size_t)(e - s), &len);
    if (blank(ch)) {
      s += len;
      col++;
      continue;
    }
    if (ch == '(') {
      unsigned open = col;
      const unsigned char *q = s + len;
      unsigned qc = col + 1;
      for (;;) {
        if (q >= e) {
          err(c, S42_E_SYNTAX, line, open, number, "comment not closed: ')' missing before the end of the line");
          goto fail;
        }
        size_t ql, ml = end_mark(q, (size_t)(e - q));
        int32_t k = utf8_decode(q, (size_t)(e - q), &ql);
        if (k == ')')
          break;
        if (k == '%' || k == ':' || ml) {
          err(c, S42_E_SYNTAX, line, qc, number, "a comment may not hold %s (L500: no %%, : or ПС in a comment)",
              ml ? "the end mark ПС" : k == '%' ? "'%'" : "':'");
          goto fail;
        }
        q += ql;
        qc++;
      }
      s = q + 1;
      col = qc + 1;
      continue;
    }
    size_t ml = end_mark(s, (size_t)(e - s));
    if (ml) {
      if (!mark_col)
        mark_col = col;
      s += ml;
      col += 2;
      continue;
    }
    if (mark_col) {
      err(c, S42_E_SYNTAX, line, col, number, "%s after the end mark ПС (column %u): one block per line", show(ch, b1),
          mark_col);
      goto fail;
    }
    if (ch == ')') {
      err(c, S42_E_SYNTAX, line, col, number, "')' without '('");
      goto fail;
    }
    if (n < CH_KEEP)
      out[n] = (struct ch){lookalike(ch), col};
    n++;
    s += len;
    col++;
  }
  *count = n;
  return 0;
fail:
  *count = n < CH_KEEP ? n : CH_KEEP;   /* what came before the error, for salvage_ends */
  return -1;
}

/* The number of the block a line holds, for the lexer's messages: N and
 * its digits at its start (after blanks and '/'); -1 none. */
static int line_number(const unsigned char *s, const unsigned char *e)
{
  while (s < e && (blank(*s) || *s == '/'))
    s++;
  if (s >= e || *s != 'N')
    return -1;
  long x = 0;
  int nd = 0;
  for (s++; s < e && *s >= '0' && *s <= '9' && nd < 6; s++, nd++)
    x = x * 10 + (*s - '0');
  return nd && nd <= 5 ? (int)x : -1;
}

/* --------------------------------------------------------------- parsing */

/* A word with a value: X Z I K F S T E (enum u22_slot). */
struct word {
  unsigned col;          /* the address's column; 0: not given */
  int bare;              /* a letter alone (G25's X and Z) */
  int neg;               /* the first term's sign is '-' */
  int ndig;              /* digits of the constant term (0: none) */
  long long k;           /* the constant term, unsigned */
  int r1;                /* the first term is R r1 (-1: a constant) */
  int r2, neg2;          /* the second term: + R r2 or - R r2 (-1: none) */
};

struct assign {
  int reg;
  long long v;
  unsigned col;
};

#define MAX_ASSIGN (U22_BLOCK_MAX / 3 + 1)   /* R0+0 is 4 characters; R00 3 */

struct blk {
  unsigned line, col;      /* its first character */
  int number;              /* the N's value; -1: none (a bare ':') */
  int ndig;                /* digits of its N or ':' number */
  int colon;               /* written with ':' */
  int skip;                /* '/' */
  uint16_t g, m, words;
  unsigned gcol[UG_N], mcol[UM_N];
  struct word w[U22_NSLOT];
  struct assign ra[MAX_ASSIGN];
  int nra;
  int sub, runs;           /* L ss rr (sub 0: none) */
  unsigned lcol;
  int h;                   /* H n: 1 + n (0: none) */
  unsigned hcol;
  int home;                /* G25's axes: 1 X, 2 Z */
  int bad;                 /* an error was reported for it */
  /* structure */
  int unit;                /* 0 main, 1.. subs in text order */
  int hreg;                /* the counter register of its H or M20 */
  long back;               /* M20: the block its range starts at */
  long past;               /* H: the block after its range's M20 */
};

static const char slot_name[U22_NSLOT] = {'X', 'Z', 'I', 'K', 'F', 'S', 'T', 'E'};

static int slot_of(int32_t a)
{
  for (int s = 0; s < U22_NSLOT; s++)
    if (slot_name[s] == a)
      return s;
  return -1;
}

static int isdig(const struct ch *v, size_t i, size_t n)
{
  return i < n && v[i].c >= '0' && v[i].c <= '9';
}

/* The digits at v[*i]: their value (capped) and count. */
static int digits(const struct ch *v, size_t *i, size_t n, long long *val)
{
  int nd = 0;
  long long x = 0;
  while (isdig(v, *i, n)) {
    if (x < 1000000000000LL)
      x = x * 10 + (v[*i].c - '0');
    nd++;
    (*i)++;
  }
  *val = x;
  return nd;
}

static long long pow10ll(int d)
{
  long long x = 1;
  while (d-- > 0)
    x *= 10;
  return x;
}

/* Groups of Table 1.2 (and D-6's overrides); 0: none. */
static int g_group(int g)
{
  switch (g) {
  case UG01: case UG02: case UG03: case UG33: return 1;
  case UG90: case UG91: return 2;
  case UG94: case UG95: return 3;
  case UG96: case UG97: return 4;
  default: return 0;
  }
}

/* Groups of Table 1.3; DEC: M02 M17 M30 (the ends) are one group too: a
 * block ends one thing. */
static int m_group(int m)
{
  switch (m) {
  case UM03: case UM04: case UM05: return 'A';
  case UM08: case UM09: return 'B';
  case UM38: case UM39: return 'C';
  case UM02: case UM17: case UM30: return 'E';
  default: return 0;
  }
}

static int g_index(long long num)
{
  for (int g = 0; g < UG_N; g++)
    if (u22_g_number[g] == num)
      return g;
  return -1;
}

static int m_index(long long num)
{
  for (int m = 0; m < UM_N; m++)
    if (u22_m_number[m] == num)
      return m;
  return -1;
}

/* The block's own name in messages is diag's ("N12: ..."); these report at
 * a column of the block. */
#define BERR(code, col, ...) do { err(c, code, b->line, col, b->number, __VA_ARGS__); b->bad = 1; } while (0)

/* After an error the rest of the block is not read; its ends (M02 M30 M17)
 * are still looked for, so that one bad word does not make the program
 * seem to run on into the sub area. */
static void salvage_ends(struct blk *b, const struct ch *v, size_t n)
{
  for (size_t i = 0; i + 1 < n; i++) {
    if (v[i].c != 'M')
      continue;
    size_t j = i + 1;
    long long x;
    int nd = digits(v, &j, n, &x);
    int m = nd && nd <= 2 ? m_index(x) : -1;
    if (m == UM02 || m == UM30 || m == UM17)
      b->m |= (uint16_t)(1u << m);
  }
}

/* A word's value: [sign] (digits | R d) [sign R d] (D-19). */
static int parse_value(struct cc *c, struct blk *b, const struct ch *v, size_t *i, size_t n, int32_t a,
                       struct word *w)
{
  unsigned sign = 0;
  w->r1 = w->r2 = -1;
  if (*i < n && (v[*i].c == '+' || v[*i].c == '-')) {
    sign = v[*i].col;
    w->neg = v[*i].c == '-';
    (*i)++;
  }
  if (*i < n && v[*i].c == 'R') {
    unsigned rc = v[*i].col;
    (*i)++;
    if (!isdig(v, *i, n)) {
      BERR(S42_E_SYNTAX, rc, "%c: R needs its number, R0..R9", (char)a);
      return -1;
    }
    w->r1 = v[*i].c - '0';
    (*i)++;
  } else if (isdig(v, *i, n)) {
    w->ndig = digits(v, i, n, &w->k);
  } else if (!sign) {
    w->bare = 1;
    return 0;
  } else {
    BERR(S42_E_SYNTAX, sign, "%c: a sign without a number or R0..R9 after it", (char)a);
    return -1;
  }
  if (*i < n && v[*i].c == '.') {
    BERR(S42_E_SYNTAX, v[*i].col, "%c: no decimal point: values are whole numbers (X, Z in 0.01 mm)", (char)a);
    return -1;
  }
  if (*i < n && (v[*i].c == '+' || v[*i].c == '-')) {
    if (*i + 1 < n && v[*i + 1].c == 'R') {
      w->neg2 = v[*i].c == '-';
      unsigned rc = v[*i + 1].col;
      *i += 2;
      if (!isdig(v, *i, n)) {
        BERR(S42_E_SYNTAX, rc, "%c: R needs its number, R0..R9", (char)a);
        return -1;
      }
      w->r2 = v[*i].c - '0';
      (*i)++;
      if (*i < n && (v[*i].c == '+' || v[*i].c == '-' || v[*i].c == '.' || isdig(v, *i, n))) {
        BERR(S42_E_SYNTAX, v[*i].col, "%c: a value is [sign] number-or-R [sign R]: nothing more may follow (D-19)",
             (char)a);
        return -1;
      }
    } else {
      BERR(S42_E_SYNTAX, v[*i].col, "%c: only a parameter (+R1, -R2) may follow the value (D-19)", (char)a);
      return -1;
    }
  }
  /* an R here starts the next word, an assignment (X+R1 R1+5: spaces do not count) */
  if (w->r1 >= 0 && isdig(v, *i, n)) {
    BERR(S42_E_SYNTAX, v[*i].col, "%c: a parameter is R0..R9, one digit", (char)a);
    return -1;
  }
  return 0;
}

/* A plain number after G M L H and the block's N: no sign, no parameter. */
static int plain(struct cc *c, struct blk *b, const struct ch *v, size_t *i, size_t n, int32_t a, unsigned col,
                 long long *val)
{
  if (*i < n && (v[*i].c == '+' || v[*i].c == '-') && !(*i + 1 < n && v[*i + 1].c == 'R')) {
    BERR(S42_E_SYNTAX, v[*i].col, "%c takes no sign", (char)a);
    return -1;
  }
  if (*i < n && (v[*i].c == 'R' || v[*i].c == '+' || v[*i].c == '-')) {
    BERR(S42_E_SYNTAX, v[*i].col, "a parameter may not stand under %c (L746: not under L, M, N, G, H)", (char)a);
    return -1;
  }
  int nd = digits(v, i, n, val);
  if (!nd) {
    BERR(S42_E_SYNTAX, col, "%c without its number", (char)a);
    return -1;
  }
  if (*i < n && v[*i].c == '.') {
    BERR(S42_E_SYNTAX, v[*i].col, "%c: no decimal point: numbers are whole", (char)a);
    return -1;
  }
  return nd;
}

static int too_many(struct cc *c, struct blk *b, unsigned col, const char *what, int nd, int max)
{
  if (nd <= max)
    return 0;
  BERR(S42_E_RANGE, col, "%s: %d digits, at most %d (Table 1.1)", what, nd, max);
  return -1;
}

/* The ranges of the words' values (Table 1.1, D-27): lo..hi. */
static void word_range(int s, int g33, long long *lo, long long *hi)
{
  switch (s) {
  case U22_X: case U22_Z: *hi = pow10ll(U22_DIG_XZIK) - 1; *lo = -*hi; return;
  case U22_I: case U22_K: *hi = pow10ll(g33 ? U22_DIG_IK33 : U22_DIG_XZIK) - 1; *lo = -*hi; return;
  case U22_F: *lo = 0; *hi = pow10ll(U22_DIG_F) - 1; return;
  case U22_S: *lo = 0; *hi = pow10ll(U22_DIG_S) - 1; return;
  case U22_T: *lo = 0; *hi = 99; return;            /* T0..T99 (D-27), 3 digits written */
  default: *lo = 0; *hi = pow10ll(U22_DIG_E) - 1; return;
  }
}

static int word_digits(int s, int g33)
{
  switch (s) {
  case U22_I: case U22_K: return g33 ? U22_DIG_IK33 : U22_DIG_XZIK;
  case U22_F: return U22_DIG_F;
  case U22_S: return U22_DIG_S;
  case U22_T: return U22_DIG_T;
  case U22_E: return U22_DIG_E;
  default: return U22_DIG_XZIK;
  }
}

/* What is checked once the whole block is read: digits (I K under G33),
 * literal values, G25's bare letters, G04 and E. */
static void block_end(struct cc *c, struct blk *b)
{
  int g33 = !!(b->g & (1u << UG33)), g25 = !!(b->g & (1u << UG25));
  for (int s = 0; s < U22_NSLOT && !b->bad; s++) {
    struct word *w = &b->w[s];
    if (!w->col)
      continue;
    char nm[32];
    snprintf(nm, sizeof nm, "%c%s", slot_name[s], g33 && (s == U22_I || s == U22_K) ? " under G33" : "");
    if (w->bare) {
      if (g25 && (s == U22_X || s == U22_Z)) {
        b->home |= s == U22_X ? 1 : 2;
        continue;
      }
      if (s == U22_X || s == U22_Z)
        BERR(S42_E_SYNTAX, w->col, "%c without a value (a bare axis letter only with G25)", slot_name[s]);
      else
        BERR(S42_E_SYNTAX, w->col, "%c without a value", slot_name[s]);
      return;
    }
    if (g25 && (s == U22_X || s == U22_Z)) {
      BERR(S42_E_SYNTAX, w->col, "G25 names its axes by bare letters: %c, not %c with a value (D-31)", slot_name[s],
           slot_name[s]);
      return;
    }
    if (too_many(c, b, w->col, nm, w->ndig, word_digits(s, g33)))
      return;
    if (w->r1 < 0 && w->r2 < 0) {
      long long lo, hi, x = w->neg ? -w->k : w->k;
      word_range(s, g33, &lo, &hi);
      if (x < lo || x > hi) {
        BERR(S42_E_RANGE, w->col, "%c%lld is outside %lld..%lld", slot_name[s], x, lo, hi);
        return;
      }
    }
    b->words |= (uint16_t)(1u << s);
  }
  if (b->bad)
    return;
  if (g25 && !b->home)
    BERR(S42_E_SYNTAX, b->gcol[UG25], "G25 without an axis letter: write G25 X, G25 Z or G25 X Z (D-31)");
  else if ((b->g & (1u << UG04)) && !b->w[U22_E].col)
    BERR(S42_E_SYNTAX, b->gcol[UG04], "G04 without E: the dwell is E in 0.1 s (G04 E20 = 2 s)");
  else if (b->w[U22_E].col && !(b->g & (1u << UG04)))
    BERR(S42_E_SYNTAX, b->w[U22_E].col, "E (a dwell in 0.1 s) only with G04");
}

/* The words after the block's N or ':'. */
static void parse_words(struct cc *c, struct blk *b, const struct ch *v, size_t i, size_t n)
{
  char b1[32];
  while (i < n) {
    int32_t a = v[i].c;
    unsigned col = v[i].col;
    i++;
    long long x;
    int nd, s = slot_of(a);
    if (s >= 0) {
      struct word *w = &b->w[s];
      if (w->col) {
        BERR(S42_E_BLOCK, col, "a second %c in the block (the first at column %u; only G, M and R repeat, L516)",
             (char)a, w->col);
        return;
      }
      w->col = col;
      if (parse_value(c, b, v, &i, n, a, w))
        return;
      continue;
    }
    switch (a) {
    case 'G': case 'M': {
      if ((nd = plain(c, b, v, &i, n, a, col, &x)) < 0)
        return;
      if (too_many(c, b, col, a == 'G' ? "G" : "M", nd, 2))
        return;
      int f = a == 'G' ? g_index(x) : m_index(x);
      if (f < 0) {
        BERR(S42_E_FUNC, col, "%c%02lld is no 2У22 function (Table %s)", (char)a, x, a == 'G' ? "1.2" : "1.3");
        return;
      }
      uint16_t *set = a == 'G' ? &b->g : &b->m;
      unsigned *fcol = a == 'G' ? b->gcol : b->mcol;
      const int *num = a == 'G' ? u22_g_number : u22_m_number;
      int grp = a == 'G' ? g_group(f) : m_group(f);
      if (*set & (1u << f)) {
        BERR(grp ? S42_E_GROUP : S42_E_BLOCK, col, "%c%02d twice in the block", (char)a, num[f]);
        return;
      }
      int n1 = a == 'G' ? UG_N : UM_N;
      for (int o = 0; o < n1; o++) {
        if (!(*set & (1u << o)))
          continue;
        int og = a == 'G' ? g_group(o) : m_group(o);
        int clash = grp && og == grp;
        /* D-6: G20 and G21 go together; G23 withdraws both */
        if (a == 'G' && ((f == UG23 && (o == UG20 || o == UG21)) || (o == UG23 && (f == UG20 || f == UG21))))
          clash = 1;
        if (clash) {
          if (a == 'G' && (f == UG23 || o == UG23))
            BERR(S42_E_GROUP, col, "G%02d with G%02d: G23 withdraws the overrides G20 and G21 allow (D-6)", num[o],
                 num[f]);
          else if (a == 'G')
            BERR(S42_E_GROUP, col, "two G of group %d (G%02d, G%02d)", grp, num[o], num[f]);
          else if (grp == 'E')
            BERR(S42_E_GROUP, col, "two ends in one block (M%02d, M%02d)", num[o], num[f]);
          else
            BERR(S42_E_GROUP, col, "two M of group %c (M%02d, M%02d)", grp, num[o], num[f]);
          return;
        }
      }
      *set |= (uint16_t)(1u << f);
      fcol[f] = col;
      break;
    }
    case 'L':
      if (b->lcol) {
        BERR(S42_E_BLOCK, col, "a second L in the block (one call a block)");
        return;
      }
      b->lcol = col;
      if ((nd = plain(c, b, v, &i, n, a, col, &x)) < 0)
        return;
      if (nd != 2 && nd != 4) {
        BERR(S42_E_RANGE, col, "L takes 2 digits (L12: sub 12 once) or 4 (L1205: sub 12 five times), not %d (D-27)",
             nd);
        return;
      }
      b->sub = (int)(nd == 2 ? x : x / 100);
      b->runs = (int)(nd == 2 ? 1 : x % 100);
      if (b->sub == 0) {
        BERR(S42_E_RANGE, col, "L: there is no sub 00 (subs are 01..99)");
        return;
      }
      break;
    case 'H':
      if (b->hcol) {
        BERR(S42_E_BLOCK, col, "a second H in the block");
        return;
      }
      b->hcol = col;
      if ((nd = plain(c, b, v, &i, n, a, col, &x)) < 0)
        return;
      if (too_many(c, b, col, "H", nd, U22_DIG_H))
        return;
      b->h = (int)x + 1;
      break;
    case 'R': {
      if (!isdig(v, i, n)) {
        BERR(S42_E_SYNTAX, col, "R needs its number: R0..R9 (R1+50 sets R1 to 50)");
        return;
      }
      int r = v[i++].c - '0';
      int neg = 0;
      if (i < n && (v[i].c == '+' || v[i].c == '-'))
        neg = v[i++].c == '-';
      if (i < n && v[i].c == 'R') {
        BERR(S42_E_SYNTAX, v[i].col, "R%d: an assignment takes a number, not a parameter (sec. 7)", r);
        return;
      }
      nd = digits(v, &i, n, &x);
      if (!nd) {
        BERR(S42_E_SYNTAX, col, "R%d without a value (R%d+50, R%d-1000)", r, r, r);
        return;
      }
      if (i < n && v[i].c == '.') {
        BERR(S42_E_SYNTAX, v[i].col, "R%d: no decimal point: values are whole numbers", r);
        return;
      }
      char nm[8];
      snprintf(nm, sizeof nm, "R%d", r);
      if (too_many(c, b, col, nm, nd, U22_DIG_R))
        return;
      if (b->nra >= MAX_ASSIGN) {   /* cannot happen within 80 characters */
        BERR(S42_E_BLOCKLEN, col, "too many R assignments in one block");
        return;
      }
      b->ra[b->nra++] = (struct assign){r, neg ? -x : x, col};
      break;
    }
    case 'N':
      BERR(S42_E_BLOCK, col, "a second N in the block: N only starts a block");
      return;
    case '.':
      BERR(S42_E_SYNTAX, col, "no decimal point: values are whole numbers (X, Z in 0.01 mm)");
      return;
    case '+': case '-':
      BERR(S42_E_SYNTAX, col, "a sign without its address");
      return;
    case '%':
      BERR(S42_E_SYNTAX, col, "'%%' only starts the program, on a line of its own");
      return;
    case ':': case '/':
      BERR(S42_E_SYNTAX, col, "'%c' only at the start of a block", (char)a);
      return;
    default:
      if (a >= '0' && a <= '9')
        BERR(S42_E_SYNTAX, col, "a number without its address");
      else if (a >= 'A' && a <= 'Z')
        BERR(S42_E_SYNTAX, col, "'%c' is no 2У22 address (N G X Z I K F S T M L H R E, Table 1.1)", (char)a);
      else if (a >= 'a' && a <= 'z')
        BERR(S42_E_SYNTAX, col, "'%c': addresses are capital letters", (char)a);
      else
        BERR(S42_E_SYNTAX, col, "unexpected %s", show(a, b1));
      return;
    }
  }
  block_end(c, b);
}

/* A block's characters into b.  sub_area: after the main program's end,
 * where every block carries a 5-digit N (D-29). */
static void parse_block(struct cc *c, struct blk *b, const struct ch *v, size_t n, int sub_area)
{
  size_t i = 0;
  char b1[32];
  b->number = -1;
  if (v[i].c == '/') {
    b->skip = 1;
    i++;
  }
  if (i < n && v[i].c == 'N') {
    unsigned col = v[i].col;
    i++;
    long long x;
    int nd = plain(c, b, v, &i, n, 'N', col, &x);
    if (nd < 0)
      return;
    b->ndig = nd;
    if (nd > U22_DIG_N) {
      BERR(S42_E_RANGE, col, "N: %d digits, at most %d (Table 1.1)", nd, U22_DIG_N);
      return;
    }
    b->number = (int)x;
    if (sub_area && nd != 5)   /* reported, and read on as the sub number/1000's block */
      BERR(S42_E_SUB, col, "a block of the sub area needs a 5-digit N ssbbb (N02001: sub 02, block 001), not %d "
           "digit%s (D-29)", nd, nd == 1 ? "" : "s");
  } else if (i < n && v[i].c == ':') {
    unsigned col = v[i].col;
    i++;
    b->colon = 1;
    long long x = 0;
    int nd = digits(v, &i, n, &x);
    if (nd > U22_DIG_N) {
      BERR(S42_E_RANGE, col, ":: %d digits, at most %d", nd, U22_DIG_N);
      return;
    }
    b->ndig = nd;
    b->number = nd ? (int)x : -1;
    if (sub_area)
      BERR(S42_E_SUB, col, "':' in the sub area: its blocks need a 5-digit N ssbbb (D-29)");
  } else {
    unsigned col = i < n ? v[i].col : v[0].col;
    if (i < n && v[i].c == '%')
      BERR(S42_E_SYNTAX, col, "a second '%%': the program has one start");
    else if (i < n)
      BERR(S42_E_SYNTAX, col, "a block starts with N and its number or with ':', not %s (D-3)", show(v[i].c, b1));
    else
      BERR(S42_E_SYNTAX, col, "'/' without a block: a block starts with N and its number or with ':'");
    return;
  }
  parse_words(c, b, v, i, n);
}

/* ------------------------------------------------------------- structure */

/* The state of the text as it is read. */
struct st {
  int sub_area;            /* the main program has ended */
  int unit;                /* the unit being read */
  int open;                /* a sub is open (its first block read, no M17 yet) */
  int ss;                  /* its number */
  long first[100];         /* sub ss: its first block, -1 none */
  int hs[3];               /* the open H blocks of the unit */
  int nh;
  int hbase;               /* the unit's H counter registers: hbase, hbase + 1 */
  int next_hbase;
  long last_main;          /* the main program's last block read */
};

static int has_m(const struct blk *b, int m)
{
  return !!(b->m & (1u << m));
}

/* The H ranges still open when a unit ends. */
static void close_unit(struct cc *c, struct st *t, const char *what)
{
  for (int k = 0; k < t->nh; k++) {
    struct blk *h = &c->b[t->hs[k]];
    err(c, S42_E_SUB, h->line, h->hcol, h->number, "H has no M20 before the end of the %s: its range never ends "
        "(D-12)", what);
  }
  t->nh = 0;
}

static void structure(struct cc *c, struct st *t, long bi)
{
  struct blk *b = &c->b[bi];
  int ends = has_m(b, UM02) || has_m(b, UM30);
  int m17 = has_m(b, UM17), m20 = has_m(b, UM20);
  if (!t->sub_area) {
    b->unit = 0;
    t->last_main = bi;
    if (m17)
      err(c, S42_E_SUB, b->line, b->mcol[UM17] ? b->mcol[UM17] : b->col, b->number,
          "M17 in the main program: M17 ends a subprogram (the main program ends with M02 or M30)");
  } else {
    if (ends)
      err(c, S42_E_SUB, b->line, b->mcol[has_m(b, UM02) ? UM02 : UM30] ? b->mcol[has_m(b, UM02) ? UM02 : UM30] : b->col,
          b->number, "M%02d in a subprogram: a subprogram ends with M17", has_m(b, UM02) ? 2 : 30);
    if (b->number >= 0) {
      int ss = b->number / 1000;
      if (!t->open) {
        t->open = 1;
        t->ss = ss;
        t->unit++;
        t->nh = 0;
        t->hbase = 0;
        if (ss == 0)
          err(c, S42_E_SUB, b->line, b->col, b->number, "sub 00: subprograms are numbered 01..99 (N01001..)");
        else if (t->first[ss] >= 0)
          err(c, S42_E_TARGET, b->line, b->col, b->number, "sub %02d defined twice (first at line %u)", ss,
              c->b[t->first[ss]].line);
        else
          t->first[ss] = bi;
      } else if (ss != t->ss) {
        err(c, S42_E_SUB, b->line, b->col, b->number,
            "N%05d in sub %02d before its M17: a subprogram's blocks all carry its number", b->number, t->ss);
      }
    }
    b->unit = t->unit;
  }
  /* block skip: skipping these would break the structure (vm_skip goes on
   * with the next block in the text) */
  if (b->skip) {
    const char *why = NULL;
    if (b->h)
      why = "H (its range would start without its counter)";
    else if (m20)
      why = "M20 (its repeat would not close)";
    else if (m17)
      why = "M17 (the subprogram would not end)";
    else if (ends)
      why = has_m(b, UM02) ? "M02 (the program would not end)" : "M30 (the program would not end)";
    if (why)
      err(c, S42_E_SYNTAX, b->line, b->col, b->number, "'/' on a block with %s: such a block cannot be skipped", why);
  }
  /* H ranges (sec. 6) */
  if (b->h && m20) {
    err(c, S42_E_SUB, b->line, b->hcol, b->number, "H and M20 in one block: a block either starts a repeat or ends one");
  } else if (m20) {
    if (!t->nh) {
      err(c, S42_E_SUB, b->line, b->mcol[UM20], b->number, "M20 without an H before it: no repeat to end (D-12)");
    } else if (ends || m17) {
      err(c, S42_E_SUB, b->line, b->mcol[UM20], b->number,
          "M20 with M%02d: the repeat's range would hold the end of the %s (D-12)", m17 ? 17 : has_m(b, UM02) ? 2 : 30,
          m17 ? "subprogram" : "program");
      t->nh--;
    } else {
      struct blk *h = &c->b[t->hs[--t->nh]];
      b->hreg = h->hreg;
      b->back = t->hs[t->nh] + 1;
      h->past = bi + 1;
    }
  } else if (b->h) {
    if (t->nh >= 2) {
      err(c, S42_E_NEST, b->line, b->hcol, b->number, "a third H inside two open repeats: H nests two levels (L699)");
      if (t->nh < 3)   /* kept open, so that its M20 is not reported too */
        t->hs[t->nh++] = (int)bi;
    } else {
      if (!t->hbase) {
        if (t->unit == 0) {
          t->hbase = U22_REG_H0;
        } else if (t->next_hbase + 1 < VM_NREG) {
          t->hbase = t->next_hbase;
          t->next_hbase += 2;
        } else {
          err(c, S42_E_LIMIT, b->line, b->hcol, b->number, "more subprograms with H repeats than s42 has counters "
              "for (%d)", (VM_NREG - U22_REG_H0 - 2) / 2);
        }
      }
      b->hreg = t->hbase + t->nh;
      t->hs[t->nh++] = (int)bi;
    }
  }
  if (!t->sub_area && ends) {
    close_unit(c, t, "program");
    t->sub_area = 1;
  } else if (t->sub_area && m17) {
    close_unit(c, t, "subprogram");
    t->open = 0;
  }
}

/* ------------------------------------------------------------- emitting */

struct patch {
  size_t pc;
  long to;                 /* block index */
};

struct em {
  struct cc *c;
  struct patch *v;
  size_t n, cap;
  long rule[U22_NSLOT][2];
  long k0;
};

static void emit(struct em *e, int op, uint32_t a, unsigned col)
{
  if (prog_emit(e->c->p, INS(op, a), col) < 0)
    e->c->oom = 1;
}

static void emit_jump(struct em *e, int op, long to, unsigned col)
{
  if (e->n == e->cap) {
    size_t nc = e->cap ? e->cap * 2 : 32;
    struct patch *v = realloc(e->v, nc * sizeof *v);
    if (!v) {
      e->c->oom = 1;
      return;
    }
    e->v = v;
    e->cap = nc;
  }
  e->v[e->n++] = (struct patch){e->c->p->ncode, to};
  emit(e, op, 0, col);
}

static void emit_num(struct em *e, long long x, unsigned col)
{
  if (x >= 0 && x <= (long long)INS_AMAX) {
    emit(e, OP_INT, (uint32_t)x, col);
  } else {
    long k = prog_const(e->c->p, (double)x);
    if (k < 0 || (unsigned long)k > INS_AMAX)
      e->c->oom = 1;
    else
      emit(e, OP_CONST, (uint32_t)k, col);
  }
}

static long rule_of(struct em *e, int s, int g33)
{
  int k = g33 && (s == U22_I || s == U22_K);
  if (e->rule[s][k] >= 0)
    return e->rule[s][k];
  long long lo, hi;
  word_range(s, k, &lo, &hi);
  struct prog_rule r = {.lo = (double)lo, .hi = (double)hi, .err = S42_E_RANGE};
  r.name[0] = slot_name[s];
  long ri = prog_rule(e->c->p, &r);
  if (ri < 0)
    e->c->oom = 1;
  return e->rule[s][k] = ri;
}

static void emit_block(struct em *e, long bi)
{
  struct cc *c = e->c;
  struct program *p = c->p;
  struct blk *b = &c->b[bi];
  struct prog_block pb = {0};
  pb.code = (uint32_t)p->ncode;
  pb.line = b->line;
  pb.col = (uint16_t)(b->col > 0xffff ? 0xffff : b->col);
  pb.number = b->number > 0 ? (uint32_t)b->number : 0;
  pb.unit = (uint16_t)b->unit;
  long pbi = prog_block_add(p, &pb);
  if (pbi != bi) {
    c->oom = 1;
    return;
  }
  emit(e, OP_BLOCK, (uint32_t)bi, b->col);
  /* DEC (sec. 7, D-27): the block's R assignments run first, left to right,
   * then its words take their values: `N001 ... L04 R2+50 R1-1000` sets the
   * parameters for the call, and `X+R1 R1+5` moves to the new R1 -- the
   * order u22.h gives the runtime. */
  for (int k = 0; k < b->nra; k++) {
    long long x = b->ra[k].v;
    if (x >= 0) {
      emit_num(e, x, b->ra[k].col);
    } else {
      emit_num(e, -x, b->ra[k].col);
      emit(e, OP_NEG, 0, b->ra[k].col);
    }
    emit(e, OP_SETP, (uint32_t)b->ra[k].reg, b->ra[k].col);
  }
  int g33 = !!(b->g & (1u << UG33));
  for (int s = 0; s < U22_NSLOT; s++) {
    if (!(b->words & (1u << s)))
      continue;
    const struct word *w = &b->w[s];
    if (w->r1 >= 0) {
      emit(e, OP_REG, (uint32_t)w->r1, w->col);
      if (w->neg)
        emit(e, OP_NEG, 0, w->col);
    } else {
      emit_num(e, w->neg ? -w->k : w->k, w->col);
    }
    if (w->r2 >= 0)
      emit(e, w->neg2 ? OP_SUBR : OP_ADDR, (uint32_t)w->r2, w->col);
    long r = rule_of(e, s, g33);
    if (r >= 0)
      emit(e, OP_SET, (uint32_t)(VM_NREG + s) | (uint32_t)r << 10, w->col);
  }
  emit(e, OP_MACH, 0, b->col);
  int m20 = has_m(b, UM20);
  if (b->h > 1) {          /* H n, n > 0: the counter of its level */
    emit_num(e, b->h - 1, b->hcol);
    emit(e, OP_SETP, (uint32_t)b->hreg, b->hcol);
  }
  if (m20) {               /* one run of the range done: count it, go back while runs are left */
    unsigned mc = b->mcol[UM20];
    emit(e, OP_REG, (uint32_t)b->hreg, mc);
    emit(e, OP_SUBI, 1, mc);
    emit(e, OP_SETP, (uint32_t)b->hreg, mc);
    emit(e, OP_REG, (uint32_t)b->hreg, mc);
    emit(e, OP_CMPCK, 4u | (uint32_t)e->k0 << 3, mc);
  }
  int h0 = b->h == 1;
  if (b->sub) {            /* the block's own work first, then the sub (L748, D-11) */
    emit(e, OP_COMMIT, 0, b->col);
    emit_num(e, b->runs, b->lcol);
    emit_jump(e, OP_CALL, -1 - b->sub, b->lcol);   /* to < 0: sub -1 - to, resolved below */
    if (m20)
      emit_jump(e, OP_JCOND, b->back, b->mcol[UM20]);
    else if (h0)
      emit_jump(e, OP_JMP, b->past, b->hcol);
  } else if (m20) {
    emit_jump(e, OP_CJCOND, b->back, b->mcol[UM20]);
  } else if (h0) {         /* H0: the range does not run (D-27) */
    emit_jump(e, OP_CJMP, b->past, b->hcol);
  } else {
    emit(e, OP_COMMIT, 0, b->col);
  }
  if (has_m(b, UM02) || has_m(b, UM30))
    emit(e, OP_END, 0, b->mcol[has_m(b, UM02) ? UM02 : UM30]);
  else if (has_m(b, UM17))
    emit(e, OP_RET, 0, b->mcol[UM17]);
}

static void ext_free(void *v)
{
  struct u22_ext *x = v;
  if (x)
    free(x->a);
  free(x);
}

/* The calls' nesting from the main program (D-28): a call made at depth 2
 * is a third level, E-NEST where the text shows it. */
static void nest(struct cc *c, const struct st *t, long from, int depth, uint8_t (*seen)[3], uint8_t *reported)
{
  for (long i = from; i < (long)c->nb; i++) {
    struct blk *b = &c->b[i];
    if (b->unit != c->b[from].unit)
      break;
    if (!b->sub || !b->runs || t->first[b->sub] < 0)
      continue;
    if (depth >= 2) {
      if (!reported[i]) {
        reported[i] = 1;
        err(c, S42_E_NEST, b->line, b->lcol, b->number, "L%02d: a third level of subprograms (a sub calls one more, "
            "L748: two levels)", b->sub);
      }
      continue;
    }
    if (seen[b->sub][depth + 1])
      continue;
    seen[b->sub][depth + 1] = 1;
    nest(c, t, t->first[b->sub], depth + 1, seen, reported);
  }
}

int u22_compile(const char *src, size_t n, struct diag_list *d, struct program *p)
{
  struct cc c = {.d = d, .p = p};
  d->src = src;
  d->nsrc = n;
  const unsigned char *s = (const unsigned char *)src, *end = s + n;
  if (n >= 3 && memcmp(s, "\xEF\xBB\xBF", 3) == 0)
    s += 3;
  /* lines: LF, CR LF, or a lone CR ends one */
  unsigned line = 0;
  int started = 0;
  struct st t;
  memset(&t, 0, sizeof t);
  for (int k = 0; k < 100; k++)
    t.first[k] = -1;
  t.next_hbase = U22_REG_H0 + 2;
  t.last_main = -1;
  struct ch v[CH_KEEP];
  while (s < end) {
    const unsigned char *ls = s, *le = s;
    while (le < end && *le != '\n' && !(*le == '\r' && (le + 1 >= end || le[1] != '\n')))
      le++;
    s = le < end ? le + 1 : le;
    line++;
    if (!started) {
      /* the tape leader: lines before the one that starts with % (D-26) */
      const unsigned char *q = ls;
      while (q < le && blank(*q))
        q++;
      if (q < le && *q == '%') {
        started = 1;
        size_t cnt = 0;
        if (lex_line(&c, q + 1, le, line, -1, v, &cnt) == 0 && cnt) {
          /* columns of the rest of the line: lex_line counted from the % */
          unsigned base = 1;
          for (const unsigned char *r = ls; r <= q; r++)
            if ((*r & 0xC0) != 0x80)
              base++;
          err(&c, S42_E_SYNTAX, line, base + v[0].col - 1, -1, "text after %% on its line: the blocks start on the "
              "next line");
        }
      }
      continue;
    }
    size_t cnt = 0;
    int lexbad = lex_line(&c, ls, le, line, line_number(ls, le), v, &cnt);
    if (!cnt)
      continue;   /* blank, or a comment only: no block (D-26) */
    if (c.nb == c.capb) {
      size_t nc = c.capb ? c.capb * 2 : 64;
      struct blk *nbv = realloc(c.b, nc * sizeof *nbv);
      if (!nbv) {
        c.oom = 1;
        break;
      }
      c.b = nbv;
      c.capb = nc;
    }
    long bi = (long)c.nb++;
    struct blk *b = &c.b[bi];
    memset(b, 0, sizeof *b);
    b->line = line;
    b->col = v[0].col;
    b->number = -1;
    b->back = b->past = -1;
    size_t kept = cnt < CH_KEEP ? cnt : CH_KEEP;
    if (lexbad) {
      /* reported; its structure as far as it can be seen, so that one bad
       * comment does not make the program seem to run on */
      b->number = line_number(ls, le);
      b->bad = 1;
      salvage_ends(b, v, kept);
    } else if (cnt > U22_BLOCK_MAX) {
      b->number = line_number(ls, le);   /* for the message */
      err(&c, S42_E_BLOCKLEN, line, v[U22_BLOCK_MAX].col, b->number, "the block has %zu characters, at most %d "
          "(L502: spaces, comments and ПС not counted)", cnt, U22_BLOCK_MAX);
      b->bad = 1;
      salvage_ends(b, v, kept);
    } else {
      parse_block(&c, b, v, cnt, t.sub_area);
      if (b->bad)
        salvage_ends(b, v, cnt);
    }
    structure(&c, &t, bi);
  }
  if (!started) {
    err(&c, S42_E_SYNTAX, 1, 1, -1, "no '%%': a 2У22 program starts with %% on a line of its own (L498)");
  } else if (!d->nerr) {
    if (!c.nb) {
      err(&c, S42_E_SUB, line ? line : 1, 1, -1, "the program has no blocks: it needs at least one with M02 or M30");
    } else if (!t.sub_area) {
      struct blk *b = &c.b[c.nb - 1];
      err(&c, S42_E_SUB, b->line, b->col, b->number,
          "the main program does not end: its last block has no M02 or M30 (L498)");
    } else if (t.open) {
      struct blk *b = &c.b[c.nb - 1];
      err(&c, S42_E_SUB, b->line, b->col, b->number, "sub %02d has no M17: a subprogram ends with M17", t.ss);
    }
  }
  /* the calls: every sub named exists (D-14), and no third level (D-28) */
  for (size_t i = 0; i < c.nb; i++) {
    struct blk *b = &c.b[i];
    if (b->sub && t.first[b->sub] < 0)
      err(&c, S42_E_TARGET, b->line, b->lcol, b->number, "L%02d: no subprogram %02d (its blocks would be N%02d001..)",
          b->sub, b->sub, b->sub);
  }
  if (c.nb && !c.oom) {
    uint8_t seen[100][3];
    uint8_t *reported = calloc(c.nb, 1);
    memset(seen, 0, sizeof seen);
    if (reported)
      nest(&c, &t, 0, 0, seen, reported);
    else
      c.oom = 1;
    free(reported);
  }
  if (c.nb > (size_t)INS_AMAX + 1) {   /* BLOCK's 24-bit operand numbers them (vm/opcodes.h) */
    const struct blk *over = &c.b[(size_t)INS_AMAX + 1];
    err(&c, S42_E_LIMIT, over->line, over->col, over->number, "more than %zu blocks: the program is too long",
        (size_t)INS_AMAX + 1);
  }
  if (c.oom) {
    d->oom = 1;
    err(&c, S42_E_LIMIT, line ? line : 1, 1, -1, "out of memory");
  }
  if (d->nerr) {
    free(c.b);
    return -1;
  }

  /* the program */
  p->lim.depth = 2;                  /* a sub may call one more (L748) */
  p->lim.arrays = 0;
  p->lim.cells = 0;
  p->lim.param_lo = -9999999;        /* R: 7 digits (D-27) */
  p->lim.param_hi = 9999999;
  p->saved_reg = -1;                 /* nothing is restored on return (D-15) */
  p->msgs = &u22_msgs;
  p->runtime = &u22_runtime;
  p->entry = 0;
  struct u22_ext *x = calloc(1, sizeof *x);
  if (x)
    x->a = calloc(c.nb, sizeof *x->a);
  if (!x || !x->a) {
    ext_free(x);
    free(c.b);
    d->oom = 1;
    err(&c, S42_E_LIMIT, 1, 1, -1, "out of memory");
    return -1;
  }
  x->n = x->cap = c.nb;
  x->unit = 0.01;                    /* D-1 */
  p->ext = x;
  p->ext_free = ext_free;
  struct em e = {.c = &c};
  for (int s2 = 0; s2 < U22_NSLOT; s2++)
    e.rule[s2][0] = e.rule[s2][1] = -1;
  e.k0 = prog_const(p, 0.0);
  if (e.k0 < 0)
    c.oom = 1;
  for (size_t i = 0; i < c.nb && !c.oom; i++) {
    struct blk *b = &c.b[i];
    emit_block(&e, (long)i);
    x->a[i] = (struct u22_attr){.g = b->g, .m = b->m, .words = b->words, .skip = (uint8_t)b->skip,
                                .home = (uint8_t)b->home, .sub = (uint8_t)b->sub,
                                .runs = (uint8_t)(b->sub ? b->runs : 0), .h = (uint16_t)b->h,
                                .hreg = (uint8_t)b->hreg};
  }
  for (size_t i = 0; i < e.n && !c.oom; i++) {
    long to = e.v[i].to;
    uint32_t blk = (uint32_t)(to < 0 ? t.first[-1 - to] : to);   /* a jump's operand is the block (OPD_PC) */
    p->code[e.v[i].pc] = INS(INS_OP(p->code[e.v[i].pc]), blk);
  }
  free(e.v);
  free(c.b);
  if (c.oom) {
    d->oom = 1;
    err(&c, S42_E_LIMIT, 1, 1, -1, "out of memory");
    return -1;
  }
  uint32_t need = 0;
  char msg[200];
  if (prog_verify_need(p, &need, msg, sizeof msg) == 0 || need) {
    p->max_stack = need;
    if (prog_verify(p, msg, sizeof msg) == 0)
      return 0;
  }
  err(&c, S42_E_SYNTAX, 1, 1, -1, "internal: the 2У22 bytecode does not verify: %s", msg);
  return -1;
}
