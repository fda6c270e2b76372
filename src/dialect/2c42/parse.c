/* The 2С42 parser (src/dialect/2c42/parse.h): recursive descent over the lexer's cursor.
 * A syntax error reports one diagnostic and abandons the rest of its block
 * (longjmp to parse_block); the next block is parsed as usual, so one run
 * reports the mistakes of every block. */
#include "parse.h"
#include "utf8.h"
#include "plugin.h"
#include "errors.h"
#include "opcodes.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DEPTH 200          /* nested parentheses / signs in one expression */
/* A block of 320 characters holds far fewer nodes; the bound keeps the
 * compiler's walks over a left-deep chain (1+1+1+...) from exhausting the
 * stack on a garbage file, which is still parsed to report its errors. */
#define MAX_NODES 4096

struct arena_chunk { struct arena_chunk *next; size_t size; };

void *arena_alloc(struct arena *a, size_t n)
{
  n = (n + 15) & ~(size_t)15;
  if (a->used + n > a->cap) {
    /* Keep the full chunk on a list until the reset; start a bigger one. */
    size_t cap = a->cap ? a->cap * 2 : 16384;
    while (cap < n + sizeof(struct arena_chunk) + 16)
      cap *= 2;
    char *buf = malloc(cap);
    if (!buf) {
      if (a->oom)
        longjmp(*a->oom, 2);   /* the parser reports it at the block, and the compile fails */
      return NULL;
    }
    if (a->buf) {
      struct arena_chunk *c = (struct arena_chunk *)a->buf;
      c->next = a->more;
      a->more = c;
    }
    a->buf = buf;
    a->cap = cap;
    a->used = 32;   /* room for the chunk header, 16-aligned */
  }
  void *p = a->buf + a->used;
  a->used += n;
  return p;
}

void arena_reset(struct arena *a)
{
  while (a->more) {
    struct arena_chunk *c = a->more;
    a->more = c->next;
    free(c);
  }
  a->used = 32;
}

void arena_free(struct arena *a)
{
  arena_reset(a);
  free(a->buf);
  memset(a, 0, sizeof *a);
}

/* ---- errors ---- */

/* The parser's state is struct parser (parse.h): s, the parser itself,
 * with its block (s->b) and where an error leaves to (s->jb). */

static void fail(struct parser *s, int code, unsigned col, const char *fmt, ...)
  __attribute__((format(printf, 4, 5), noreturn));
static void fail(struct parser *s, int code, unsigned col, const char *fmt, ...)
{
  char msg[240];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  diag_add(s->d, DIAG_ERROR, code, s->b->line, col, s->b->number, "%s", msg);
  s->b->bad = 1;
  longjmp(s->jb, 1);
}

static const char *show(int32_t c, char *buf)
{
  if (c == LX_EOB)
    return "the end of the block";
  if (c == LX_EOF)
    return "the end of the file";
  if (c == 0xFFFD) {
    strcpy(buf, "invalid UTF-8");
    return buf;
  }
  if (c < 32 || c == 127) {
    snprintf(buf, 32, "character 0x%02X", (unsigned)c);
    return buf;
  }
  buf[0] = '\'';
  int n = utf8_encode(c, buf + 1);
  buf[n + 1] = '\'';
  buf[n + 2] = 0;
  return buf;
}

/* Inline everywhere: a peek is a load and a compare. */
#define HOT static inline __attribute__((always_inline))
HOT int32_t peek(struct parser *s) { return lex_peek(&s->lx); }
/* The column of the character peek() returns. */
HOT unsigned pcol(struct parser *s) { lex_peek(&s->lx); return lex_col(&s->lx); }
/* The column of the character peek() returned, right after it. */
HOT unsigned here(struct parser *s) { return lex_col(&s->lx); }
/* Consume the character peek() returned (every adv follows a peek of its
 * character: the cursor is at it, not at the whitespace before it). */
HOT void adv(struct parser *s) { lex_adv1(&s->lx); }

/* expect()'s error, out of its way. */
static void __attribute__((noinline, cold, noreturn)) not_expected(struct parser *s, int32_t got, const char *what)
{
  char buf[32];
  fail(s, S42_E_SYNTAX, pcol(s), "expected %s, found %s", what, show(got, buf));
}

HOT void expect(struct parser *s, int32_t c, const char *what)
{
  int32_t got = peek(s);
  if (got != c)
    not_expected(s, got, what);
  adv(s);
}

static int accept(struct parser *s, int32_t c)
{
  if (peek(s) == c) {
    adv(s);
    return 1;
  }
  return 0;
}

static int isdig(int32_t c) { return c >= '0' && c <= '9'; }

/* n (< 1000) in decimal, NUL-terminated. */
static void fmt_uint(char *p, unsigned n)
{
  char t[4];
  int k = 0;
  do t[k++] = (char)('0' + n % 10); while ((n /= 10) && k < 3);
  while (k)
    *p++ = t[--k];
  *p = 0;
}

/* number()'s errors, out of its way: its frame holds no message buffer. */
static void __attribute__((noinline, cold, noreturn)) no_number(struct parser *s, const char *what)
{
  char buf[32];
  fail(s, S42_E_SYNTAX, pcol(s), "expected %s, found %s", what, show(peek(s), buf));
}

static void __attribute__((noinline, cold, noreturn)) long_number(struct parser *s, unsigned col, const char *what,
                                                                 int nd, int maxdig)
{
  fail(s, S42_E_RANGE, col, "%s has %d digits; at most %d are allowed", what, nd, maxdig);
}

/* The digits of a number split by whitespace (or by a chunk's end), from
 * the cursor at the first digit after it; nd digits (but leading zeros) so
 * far, worth v. */
static unsigned long __attribute__((noinline)) number_more(struct lex *l, unsigned long v, size_t *pnd)
{
  size_t nd = *pnd;
  do {
    const unsigned char *p = l->p;
    if (!nd)   /* leading zeros */
      while (*p == '0')
        p++;
    const unsigned char *q = p;
    for (unsigned d; (d = (unsigned)*p - '0') <= 9; p++)
      v = v * 10 + d;
    nd += (size_t)(p - q);
    l->p = p;
  } while (lex_val[*l->p] == LX_SLOW && isdig(lex_unplain(l)));
  *pnd = nd;
  return v;
}

/* An unsigned integer of at most `maxdig` significant digits, whose first
 * digit lex_peek returned: leading zeros are insignificant however many
 * (`G001`, `№0002`, language.md sec. 9), and whitespace between digits too,
 * as everywhere outside text.  The digits are read from the text's bytes,
 * up to one that is not plain (lex_slow's then: more digits may follow).
 * *next gets the character after the number (peek()'s). */
HOT long digits(struct parser *s, int maxdig, const char *what, int32_t *next)
{
  struct lex *l = &s->lx;
  const unsigned char *p = l->p;
  const unsigned char *first = p;
  while (*p == '0')   /* leading zeros */
    p++;
  const unsigned char *q = p;
  unsigned long v = 0;   /* (wraps past 20 digits: then too long anyway) */
  for (unsigned d; (d = (unsigned)*p - '0') <= 9; p++)
    v = v * 10 + d;
  size_t nd = (size_t)(p - q);
  uintptr_t cb = l->cb;
  l->p = p;
  int32_t c = lex_val[*p];
  if (c == LX_SLOW && isdig(c = lex_unplain(l))) {   /* (a space after it: past it) */
    v = number_more(l, v, &nd);
    c = lex_peek(l);
  }
  *next = c;
  if (nd > (size_t)maxdig)
    long_number(s, (unsigned)((uintptr_t)first - cb), what, (int)nd, maxdig);
  return (long)v;
}

/* The same, the first digit not looked at yet. */
HOT long number_to(struct parser *s, int maxdig, const char *what, int32_t *next)
{
  if (!isdig(lex_peek(&s->lx)))
    no_number(s, what);
  return digits(s, maxdig, what, next);
}
HOT long number(struct parser *s, int maxdig, const char *what)
{
  int32_t next;
  return number_to(s, maxdig, what, &next);
}

/* ---- expressions ---- */

/* expr := term { (+|-) term }      term := unary { (/|%) unary }
 * unary := (+|-) unary | power     power := primary [ %% unary ]
 * expr() is one loop over its operands; an operand (unary) is parsed
 * inline, its leaves -- numbers, parameters, X Y Z -- without a call; a
 * parenthesis, a function, a chain of signs and a power recurse.  Every way
 * an expression nests passes through unary's depth check, bounded
 * whatever the text: the depth counts as it always did (a sign two, a
 * parenthesis at an operand's start one, each operand one), so that deep
 * nesting fails where and as it did. */

static void __attribute__((noinline, cold, noreturn)) too_many_nodes(struct parser *s, unsigned col)
{
  fail(s, S42_E_BLOCKLEN, col, "block too long to analyse (over %d terms)", MAX_NODES);
}

/* The block's nodes are in one array of MAX_NODES, made at the first
 * node (as arena_alloc would: out of memory leaves the block); its end is
 * the bound on them. */
static size_t __attribute__((noinline, cold)) node_room(struct parser *s, unsigned col)
{
  struct parser *p = s;
  if (p->nodes >= MAX_NODES)
    too_many_nodes(s, col);
  p->nodebuf = malloc(MAX_NODES * sizeof *p->nodebuf);
  if (!p->nodebuf)
    longjmp(s->jb, 2);
  p->nodecap = MAX_NODES;
  return p->nodes;
}

HOT struct expr *node(struct parser *s, int kind, unsigned col)
{
  struct parser *p = s;
  size_t k = p->nodes;
  if (k >= p->nodecap)
    k = node_room(s, col);
  p->nodes = k + 1;
  struct expr *e = &p->nodebuf[k];
  /* the fields a node of this kind has are set by the caller: its value,
   * index, operator, operands (fk by the compiler's fold, which visits
   * every node before anything reads it) */
  e->kind = (uint8_t)kind;
  e->need = 1;
  e->col = col;
  return e;
}

/* The stack n's code needs at most, once its operands are in: an
 * operator needs its left operand's, or one more than its right's
 * beside the left's value -- but for a number or a parameter on the
 * right of + - % /, which the code generator fuses into the operator
 * (gen: a superinstruction), pushing nothing more.  A bound: folding
 * constants only lowers it. */
HOT void need_of(struct expr *n, int fuses)
{
  unsigned r = n->b->need + 1u;
  if (fuses && (n->b->kind == EX_NUM || n->b->kind == EX_REG))
    r = 1;
  n->need = (uint16_t)(n->a->need > r ? n->a->need : r > 0xffff ? 0xffff : r);
}
HOT void need2(struct expr *n)
{
  need_of(n, n->kind == EX_BIN && n->op != OP_POW);
}
/* The same for a + - / or % node (expr_rest's). */
HOT void need_arith(struct expr *n)
{
  need_of(n, 1);
}

static struct expr *expr(struct parser *s, size_t d);
static struct expr *unary(struct parser *s, size_t d);

static struct expr *call(struct parser *s, int op, unsigned col, int skip, size_t d)
{
  for (int i = 0; i < skip; i++)
    adv(s);
  expect(s, '(', "'(' after the function name");
  struct expr *e = node(s, EX_FN, col);
  e->op = (uint8_t)op;
  e->a = expr(s, d);
  e->need = e->a->need;
  expect(s, ')', "')' closing the function argument");
  return e;
}

/* The operands that are not a number, a parameter or X Y Z. */
static struct expr *__attribute__((noinline)) primary_other(struct parser *s, int32_t c, unsigned col, size_t d)
{
  char buf[32];
  struct expr *e;
  switch (c) {
  case '(':
    adv(s);
    s->paren++;
    e = expr(s, d);
    expect(s, ')', "')'");
    s->paren--;
    return e;
  case 'A': {
    int32_t c2 = lex_peek2(&s->lx);
    if (c2 == 'S') { adv(s); peek(s); adv(s); if (peek(s) != 'I') fail(s, S42_E_SYNTAX, col, "unknown function: did you mean ASI(...)?"); return call(s, OP_ASIN, col, 1, d); }
    if (c2 == 'C') { adv(s); peek(s); adv(s); if (peek(s) != 'O') fail(s, S42_E_SYNTAX, col, "unknown function: did you mean ACO(...)?"); return call(s, OP_ACOS, col, 1, d); }
    if (c2 == 'T') { adv(s); peek(s); adv(s); if (peek(s) != 'G') fail(s, S42_E_SYNTAX, col, "unknown function: did you mean ATG(...)?"); return call(s, OP_ATAN, col, 1, d); }
    adv(s);
    s->b->slotrd = 1;
    e = node(s, EX_SLOT, col);
    e->idx = SL_A;
    return e;
  }
  case 'S':
    adv(s);
    if (peek(s) != 'I') fail(s, S42_E_SYNTAX, col, "unknown operand: did you mean SI(...)?");
    return call(s, OP_SIN, col, 1, d);
  case 'C':
    adv(s);
    if (peek(s) != 'O') fail(s, S42_E_SYNTAX, col, "unknown operand: did you mean CO(...)?");
    return call(s, OP_COS, col, 1, d);
  case 'L':
    adv(s);
    if (peek(s) != 'O') fail(s, S42_E_SYNTAX, col, "unknown operand: did you mean LO(...)?");
    return call(s, OP_LOG, col, 1, d);
  case 'P':
    adv(s);
    if (peek(s) != '1')
      fail(s, S42_E_SYNTAX, col, "P as an operand is the constant P1 (pi); found %s", show(peek(s), buf));
    adv(s);
    if (isdig(peek(s)))
      fail(s, S42_E_SYNTAX, col, "P1 is the constant pi; P followed by more digits is not an operand");
    e = node(s, EX_NUM, col);
    e->v = 3.141592;   /* the machine's value of P1 */
    e->idx = ~0u;      /* no integer */
    return e;
  case 'U':
    adv(s);
    if (peek(s) != 'G') fail(s, S42_E_SYNTAX, col, "unknown operand: did you mean UG?");
    adv(s);
    e = node(s, EX_REG, col);
    e->idx = REG_UG;
    return e;
  case 'D':
    adv(s);
    if (peek(s) != '1') fail(s, S42_E_SYNTAX, col, "unknown operand: did you mean D1?");
    adv(s);
    e = node(s, EX_REG, col);
    e->idx = REG_D1;
    return e;
  case 'T': {
    adv(s);
    int32_t c2 = peek(s);
    if (c2 == 'K') {
      adv(s);
      e = node(s, EX_REG, col);
      e->idx = REG_TK;
      return e;
    }
    if (c2 == 'G')
      return call(s, OP_TAN, col, 1, d);
    if (isdig(c2)) {
      int d1 = c2 - '0';
      adv(s);
      int d2 = isdig(peek(s)) ? peek(s) - '0' : -1;
      if (d1 >= 1 && d1 <= 3 && (d2 == 1 || d2 == 2)) {
        adv(s);
        e = node(s, EX_ARR, col);
        e->idx = (unsigned)(d2 - 1) | (unsigned)d1 << 2;
        return e;
      }
    }
    fail(s, S42_E_SYNTAX, col, "as an operand T is TK, TG(...) or an array read T11 T21 T31 T12 T22 T32");
  }
  default:
    fail(s, S42_E_SYNTAX, col, "expected a number, parameter or function, found %s", show(c, buf));
  }
}

/* An operand; c is its first character, which peek() returned.  *next
 * gets the character after it. */
HOT struct expr *primary(struct parser *s, int32_t c, size_t d, int32_t *next)
{
  unsigned col = here(s);
  struct expr *e;
  if (isdig(c)) {
    e = node(s, EX_NUM, col);
    long n = digits(s, 7, "a number", next);
    e->v = (double)n;
    e->idx = (unsigned)n;   /* (seven digits at most: an instruction's INT) */
    return e;
  }
  if (c == 'R') {
    adv(s);
    long n = number_to(s, 3, "a parameter number after R", next);
    if (n > 113)
      fail(s, S42_E_RANGE, col, "parameter R%ld does not exist (R0..R113)", n);
    e = node(s, EX_REG, col);
    e->idx = (unsigned)n;
    return e;
  }
  if (c == 'X' || c == 'Y' || c == 'Z') {
    adv(s);
    s->b->slotrd = 1;
    e = node(s, EX_SLOT, col);
    e->idx = c == 'X' ? SL_X : c == 'Y' ? SL_Y : SL_Z;
    *next = peek(s);
    return e;
  }
  e = primary_other(s, c, col, d);
  *next = peek(s);
  return e;
}

/* The %% after the primary b and its exponent (right-associative through
 * unary). */
static struct expr *__attribute__((noinline)) power_rest(struct parser *s, struct expr *b, size_t d)
{
  unsigned col = pcol(s);
  adv(s);
  peek(s);   /* (the second '%' may follow whitespace: the cursor to it) */
  adv(s);
  struct expr *e = node(s, EX_BIN, col);
  e->op = OP_POW;
  e->a = b;
  e->b = unary(s, d);
  need2(e);
  return e;
}

/* power := primary [ %% unary ]; c the primary's first character, which
 * peek() returned.  *next gets the character after it (peek()'s: the
 * operand parsers hand it on, and their callers look at it no more). */
HOT struct expr *power(struct parser *s, int32_t c, size_t d, int32_t *next)
{
  int32_t n;
  struct expr *b = primary(s, c, d, &n);
  if (n == '%' && lex_peek2(&s->lx) == '%') {
    b = power_rest(s, b, d);
    n = peek(s);
  }
  *next = n;
  return b;
}

/* A sign applies to the factor that follows, power included: -2%%2 = -4.
 * c is the operand's first character, which peek() returned. */
HOT struct expr *unary_inner(struct parser *s, int32_t c, size_t d, int32_t *next)
{
  if (c == '+' || c == '-') {
    unsigned col = here(s);
    adv(s);
    /* two levels for a sign, both told at the sign's column */
    if (d + 2 > MAX_DEPTH)
      fail(s, S42_E_SYNTAX, col, "expression nested too deeply");
    /* unary() of what follows, without the call when it is no sign and no
     * parenthesis (unary's check, the same as the one above, passes) */
    struct expr *u;
    int32_t c2 = peek(s);
    if (c2 == '+' || c2 == '-' || c2 == '(') {
      u = unary(s, d + 1);
      *next = peek(s);
    } else {
      u = power(s, c2, d + 2, next);
    }
    if (c == '+')
      return u;
    struct expr *e = node(s, EX_NEG, col);
    e->a = u;
    e->need = u->need;
    return e;
  }
  if (c == '(') {
    if (d + 1 > MAX_DEPTH)
      fail(s, S42_E_SYNTAX, pcol(s), "expression nested too deeply");
    return power(s, c, d + 1, next);
  }
  return power(s, c, d, next);
}

/* unary: one level more, checked at the character consumed last (the
 * operator, sign or parenthesis before the operand: at the top of a word's
 * value the depth is 0 and the check passes). */
HOT struct expr *operand(struct parser *s, size_t d, int32_t *next)
{
  if (d + 1 > MAX_DEPTH)
    fail(s, S42_E_SYNTAX, lex_prev_col(&s->lx), "expression nested too deeply");
  return unary_inner(s, peek(s), d + 1, next);
}

static struct expr *__attribute__((noinline)) unary(struct parser *s, size_t d)
{
  int32_t next;
  return operand(s, d, &next);
}

/* The same left-deep trees as term inside expr, made in the same order:
 * `mul` is the / or % waiting for its right operand, `top` the + or -
 * waiting for its right term.  e is the first operand, parsed, and c the
 * character after it; *next gets the one after the expression. */
HOT struct expr *expr_rest(struct parser *s, struct expr *e, int32_t c, size_t d, int32_t *next)
{
  struct expr *top = NULL, *mul = NULL;
  for (;;) {
    if (mul) {
      mul->b = e;
      need_arith(mul);
      e = mul;
      mul = NULL;
    }
    if (c == '/' && s->slash_ends && s->paren == 0)
      ;   /* the slash that closes G28 /min:max/: the term ends */
    else if (c == '/' || (c == '%' && lex_peek2(&s->lx) != '%')) {
      unsigned col = here(s);
      adv(s);
      mul = node(s, EX_BIN, col);
      mul->op = c == '/' ? OP_DIV : OP_MUL;
      mul->a = e;
      e = operand(s, d, &c);
      continue;
    }
    if (top) {   /* the term is whole: the right operand of the + or - */
      top->b = e;
      need_arith(top);
      e = top;
      top = NULL;
    }
    if (c != '+' && c != '-') {
      *next = c;
      return e;
    }
    unsigned col = here(s);
    adv(s);
    top = node(s, EX_BIN, col);
    top->op = c == '+' ? OP_ADD : OP_SUB;
    top->a = e;
    e = operand(s, d, &c);
  }
}

HOT struct expr *expr_in(struct parser *s, size_t d)
{
  int32_t c;
  struct expr *e = operand(s, d, &c);
  return expr_rest(s, e, c, d, &c);
}

/* expr(), out of line: where expressions nest */
static struct expr *__attribute__((noinline)) expr(struct parser *s, size_t d)
{
  return expr_in(s, d);
}

/* word_value's errors, out of its way; a parameter's name (rn >= 0, R12)
 * made only here. */
static void __attribute__((noinline, cold, noreturn)) no_value(struct parser *s, const char *word, int rn, int sign)
{
  char buf[32], name[8];
  if (rn >= 0) {
    name[0] = 'R';
    fmt_uint(name + 1, (unsigned)rn);
    word = name;
  }
  int32_t c = peek(s);
  if (sign && c != '+' && c != '-')
    fail(s, S42_E_SYNTAX, pcol(s), "%s needs a sign and a value (%s+... or %s-...), found %s", word, word, word,
         show(c, buf));
  fail(s, S42_E_SYNTAX, pcol(s), "%s needs a value", word);
}

/* A word's value: its sign (required when `sign` is set) starts the first
 * term: X-R3+100 is (-R3)+100.  The word's name for the errors, or rn for
 * a parameter's; *next gets the character after the value. */
HOT struct expr *word_value(struct parser *s, const char *word, int rn, int sign, int32_t *next)
{
  int32_t c = peek(s);
  if ((sign && c != '+' && c != '-') || c == LX_EOB || c == LX_EOF)
    no_value(s, word, rn, sign);
  /* a word's value: nothing around it (operand()'s check at depth 0 passes) */
  struct expr *e = unary_inner(s, c, 1, &c);
  return expr_rest(s, e, c, 0, next);
}

/* ---- conditions ---- */

static struct expr *cond(struct parser *s, size_t d);

/* Does the parenthesis at the cursor hold a comparison (a ':' at its own
 * level) rather than a nested condition? */
static int is_comparison(struct parser *s)
{
  struct lex_ahead a;
  lex_ahead_start(&s->lx, &a);
  int depth = 0;
  for (;;) {
    int32_t c = lex_ahead_next(&s->lx, &a);
    if (c == LX_EOB || c == LX_EOF)
      return 0;
    if (c == '(') {
      depth++;
    } else if (c == ')') {
      if (--depth == 0)
        return 0;
    } else if (c == ':' && depth == 1) {
      return 1;
    }
  }
}

static struct expr *prim(struct parser *s, size_t d)
{
  char buf[32];
  unsigned col = pcol(s);
  if (peek(s) != '(')
    fail(s, S42_E_SYNTAX, col, "expected '(' starting a condition, found %s", show(peek(s), buf));
  if (++d > MAX_DEPTH)
    fail(s, S42_E_SYNTAX, col, "condition nested too deeply");
  struct expr *e;
  if (is_comparison(s)) {
    adv(s);
    e = node(s, EX_CMP, col);
    e->a = expr(s, d);
    expect(s, ':', "':' before the relation");
    unsigned rcol = pcol(s), mask = 0;
    while (peek(s) == 'B' || peek(s) == 'M' || peek(s) == 'R') {
      unsigned bit = peek(s) == 'M' ? 1u : peek(s) == 'R' ? 2u : 4u;
      if (mask & bit)
        fail(s, S42_E_SYNTAX, rcol, "relation repeats a letter (use R B M BR MR BM BMR)");
      mask |= bit;
      adv(s);
    }
    if (peek(s) != ':')
      fail(s, S42_E_SYNTAX, pcol(s), "relation must be R, B, M, BR or RB, MR or RM, BM, BMR or empty, found %s",
           show(peek(s), buf));
    adv(s);
    e->op = (uint8_t)mask;
    e->b = expr(s, d);
    need2(e);
    expect(s, ')', "')' closing the comparison");
  } else {
    adv(s);
    e = cond(s, d);
    expect(s, ')', "')' closing the condition");
  }
  return e;
}

static struct expr *conjunction(struct parser *s, size_t d)
{
  struct expr *e = prim(s, d);
  while (peek(s) == 'U') {
    unsigned col = pcol(s);
    adv(s);
    struct expr *n = node(s, EX_AND, col);
    n->a = e;
    n->b = prim(s, d);
    need2(n);
    e = n;
  }
  return e;
}

static struct expr *cond(struct parser *s, size_t d)
{
  struct expr *e = conjunction(s, d);
  while (peek(s) == 'S') {
    unsigned col = pcol(s);
    adv(s);
    struct expr *n = node(s, EX_OR, col);
    n->a = e;
    n->b = conjunction(s, d);
    need2(n);
    e = n;
  }
  return e;
}

/* ---- slash arguments ---- */

/* Read raw text up to the next '/' (not consumed).  Newline or ^ before it
 * is E-TEXT: the argument was not closed. */
static void raw_text(struct parser *s, struct text *t, const char *fn)
{
  struct lex *l = &s->lx;
  char buf[1024];
  size_t n = 0;
  unsigned nch = 0;
  t->col = lex_raw_col(l);
  for (;;) {
    int32_t c = lex_raw_peek(l);
    if (c == '/')
      break;
    if (c == LX_EOB || c == LX_EOF) {
      lex_peek(l);
      fail(s, S42_E_TEXT, t->col, "%s: text not closed with '/' before the end of the block", fn);
    }
    if (c == 0 || c == 0xFFFD) {   /* a C string cannot hold a NUL; U+FFFD stands for bad bytes */
      unsigned col = lex_raw_col(l);
      lex_peek(l);
      fail(s, S42_E_TEXT, col, "%s: text holds %s", fn, c ? "invalid UTF-8" : "a NUL byte");
    }
    char u[4];
    int k = utf8_encode(c, u);
    if (n + (size_t)k < sizeof buf - 1) {
      memcpy(buf + n, u, (size_t)k);
      n += (size_t)k;
    }
    nch++;
    lex_raw_adv(l);
  }
  buf[n] = 0;
  t->s = arena_alloc(&s->ar, n + 1);
  if (!t->s)
    longjmp(s->jb, 2);
  memcpy(t->s, buf, n + 1);
  t->nchars = nch;
}

/* The opening slash; its column. */
static unsigned open_slash(struct parser *s, const char *fn, int code)
{
  char buf[32];
  unsigned col = pcol(s);
  if (peek(s) != '/')
    fail(s, code, col, "%s needs its argument in slashes (/.../), found %s", fn, show(peek(s), buf));
  adv(s);
  return col;
}

/* Where a text argument goes: each has its own place in the block. */
static struct text *text_of(struct block *b, const struct kp_word *w)
{
  return w->kind == 'M' ? &b->m18 : w->number == 27 ? &b->g27 : &b->g33;
}

/* The slash argument of the function w (words.h: its kind). */
static void slash_arg(struct parser *s, struct block *b, const struct kp_word *w)
{
  struct lex *l = &s->lx;
  const char *fn = w->code;
  switch (w->slash) {
  case KP_SA_PROMPT: case KP_SA_TEXT: {
    open_slash(s, fn, S42_E_TEXT);
    struct text *t = text_of(b, w);
    raw_text(s, t, fn);
    lex_raw_adv(l);   /* closing '/' */
    if (w->slash == KP_SA_PROMPT) {
      b->g27form = ':';
      if (peek(s) == ':') adv(s);
      else if (peek(s) == '-') { adv(s); b->g27form = '-'; }
    }
    break;
  }
  case KP_SA_LINES: {
    unsigned scol = open_slash(s, fn, S42_E_TEXT);
    for (;;) {
      if (b->ng29 >= MAX_LINES)   /* said at the opening slash, the character last looked at outside text */
        fail(s, S42_E_TEXT, scol, "G29: more than %d lines", MAX_LINES);
      struct text *t = &b->g29[b->ng29++];
      memset(t, 0, sizeof *t);   /* no stale text from an earlier block if this one fails */
      raw_text(s, t, fn);
      lex_raw_adv(l);
      if (lex_raw_peek(l) == '/') {
        lex_raw_adv(l);
        break;
      }
    }
    break;
  }
  case KP_SA_BOUNDS:
    open_slash(s, fn, S42_E_SYNTAX);
    b->g28col = pcol(s);
    s->slash_ends = 1;
    b->g28min = expr(s, 0);
    expect(s, ':', "':' between the G28 bounds /min:max/ (divide inside parentheses: /(R1/2):R2/)");
    b->g28max = expr(s, 0);
    expect(s, '/', "'/' closing the G28 bounds");
    s->slash_ends = 0;
    b->g28reg = -2;   /* the R word must follow */
    break;
  case KP_SA_AXIS: {
    open_slash(s, fn, S42_E_SYNTAX);
    b->g37col = pcol(s);
    int32_t c = peek(s);
    if (c == 'X' || c == 'Y' || c == 'Z' || c == 'A') {
      b->g37axis = (char)c;
      adv(s);
    } else if (c != '/') {
      fail(s, S42_E_AXIS, pcol(s), "G37 takes one axis letter: G37 /Y/");
    }
    expect(s, '/', "'/' closing G37 /Y/");
    break;
  }
  case KP_SA_PARAMS:
    open_slash(s, fn, S42_E_SYNTAX);
    while (peek(s) == 'R') {
      unsigned col = pcol(s);
      adv(s);
      long r = number(s, 3, "a parameter number");
      if (r > 113)
        fail(s, S42_E_RANGE, col, "parameter R%ld does not exist (R0..R113)", r);
      if (b->nm20 >= MAX_ITEMS)
        fail(s, S42_E_SYNTAX, col, "M20: too many parameters");
      b->m20col[b->nm20] = col;
      b->m20[b->nm20++] = (unsigned)r;
    }
    if (b->nm20 == 0)
      fail(s, S42_E_SYNTAX, pcol(s), "M20 lists parameters: M20 /R12R15/");
    expect(s, '/', "'/' closing the M20 list");
    break;
  case KP_SA_CORR:
    open_slash(s, fn, S42_E_SYNTAX);
    while (peek(s) == 'R') {
      struct m16_item it;
      it.col = pcol(s);
      adv(s);
      long r = number(s, 3, "a parameter number");
      if (r > 113)
        fail(s, S42_E_RANGE, it.col, "parameter R%ld does not exist (R0..R113)", r);
      int32_t sg = peek(s);
      if (sg != '+' && sg != '-')
        fail(s, S42_E_SYNTAX, pcol(s), "M16: expected + or - and an axis after R%ld", r);
      adv(s);
      int32_t ax = peek(s);
      if (ax != 'X' && ax != 'Y' && ax != 'Z' && ax != 'A')
        fail(s, S42_E_AXIS, pcol(s), "M16: expected an axis X, Y, Z or A after R%ld%c", r, (char)sg);
      adv(s);
      it.reg = (unsigned)r;
      it.sign = sg == '-' ? -1 : 1;
      it.axis = (char)ax;
      if (b->nm16 >= MAX_ITEMS)
        fail(s, S42_E_SYNTAX, it.col, "M16: too many items");
      b->m16[b->nm16++] = it;
    }
    if (b->nm16 == 0)
      fail(s, S42_E_SYNTAX, pcol(s), "M16 lists corrections to store: M16 /R1+X R2-Z//");
    expect(s, '/', "'//' closing the M16 list");
    accept(s, '/');
    break;
  default:
    break;
  }
}

static int takes_slash(const struct kp_word *w)
{
  return w->slash != KP_SA_NONE;
}

/* ---- words ---- */

HOT struct word *new_word(struct parser *s, int kind, char letter, unsigned col)
{
  struct block *b = s->b;
  if (b->nw >= MAX_WORDS)
    fail(s, S42_E_BLOCKLEN, col, "too many words in one block");
  size_t i = b->nw++;
  struct word *w = &b->w[i];
  /* what else a word of this kind has is set by the caller, but a jump's
   * target number, read even when it did not parse */
  w->kind = (uint8_t)kind;
  w->letter = letter;
  w->col = col;
  w->num = 0;
  if (!(b->wkinds & (1u << kind))) {
    b->wkinds |= (uint16_t)(1u << kind);
    b->wfirst[kind] = (uint8_t)i;
  }
  return w;
}

/* A word the block may have once: `there` says it has it already. */
HOT void once(struct parser *s, int there, const char *name, unsigned col)
{
  if (there)
    fail(s, S42_E_SYNTAX, col, "%s appears twice in the block", name);
}

/* A word; c its first character, which peek() returned.  Returns the
 * character after the word (peek()'s). */
static inline __attribute__((always_inline)) int32_t word(struct parser *s, int32_t c)
{
  char buf[32];
  struct block *b = s->b;
  unsigned col = here(s);
  struct word *w;
  switch (c) {
  case 'G': case 'M': {
    adv(s);
    int32_t next;
    long n = number_to(s, 2, c == 'G' ? "a G function number" : "an M function number", &next);
    const struct kp_word *kw = kp_word((char)c, (int)n);
    int valid = kw != NULL;
    if (!valid && n < (c == 'G' ? 64 : 32))   /* a function a plugin adds */
      valid = plug_find(s->plugins, (char)c, (int)n, NULL) >= 0;
    if (!valid) {
      diag_add(s->d, DIAG_ERROR, S42_E_FUNC, b->line, col, b->number,
               "%c%02ld is not a function of the 2С42 or of a plugin found", (char)c, n);
      b->bad = 1;
      return peek(s);
    }
    if (c == 'G') {
      if (b->g & (1ull << n))
        fail(s, S42_E_GROUP, col, "G%02ld appears twice in the block", n);
      b->g |= 1ull << n;
      b->gcol[n] = col;
    } else {
      if (b->m & (1u << n))
        fail(s, S42_E_SYNTAX, col, "M%02ld appears twice in the block", n);
      b->m |= 1u << n;
      b->mcol[n] = col;
    }
    w = new_word(s, c == 'G' ? WK_G : WK_M, (char)c, col);
    w->num = (int)n;
    if (c == 'G')
      b->gw[b->ngw++] = (uint8_t)(b->nw - 1);
    if (kw && kw->slash != KP_SA_NONE) {
      b->slashed = 1;
      slash_arg(s, b, kw);
      return peek(s);
    }
    return next;
  }
  case 'X': case 'Y': case 'Z': case 'A': case 'I': case 'J': case 'K': case 'H': {
    char name[2] = {(char)c, 0};
    unsigned slot = c == 'X' ? SL_X : c == 'Y' ? SL_Y : c == 'Z' ? SL_Z : c == 'A' ? SL_A
                  : c == 'I' ? SL_I : c == 'J' ? SL_J : c == 'K' ? SL_K : SL_H;
    once(s, b->wslots & (1u << slot), name, col);
    adv(s);
    int32_t next;
    struct expr *e = word_value(s, name, -1, c != 'H', &next);
    w = new_word(s, WK_SLOT, (char)c, col);
    w->e = e;
    w->idx = slot;
    b->wslots |= (uint16_t)(1u << slot);
    b->slotcol[slot] = col;
    return next;
  }
  case 'F': {
    once(s, b->wF >= 0, "F", col);
    adv(s);
    int32_t next;
    struct expr *e = word_value(s, "F", -1, 0, &next);
    w = new_word(s, WK_REG, 'F', col);
    w->e = e;
    w->idx = REG_F;
    b->wF = b->nw - 1;
    return next;
  }
  case 'L': {
    once(s, b->wkinds & (1u << WK_L), "L", col);
    adv(s);
    int32_t next;
    long n = number_to(s, 3, "the first block number of a sub after L", &next);
    w = new_word(s, WK_L, 'L', col);
    w->num = (int)n;
    return next;
  }
  case 'R': {
    adv(s);
    int32_t next;
    long n = number_to(s, 3, "a parameter number after R", &next);
    if (n > 113)
      fail(s, S42_E_RANGE, col, "parameter R%ld does not exist (R0..R113)", n);
    if (b->g28reg == -2) {        /* G28 /min:max/ Rn: where the answer goes */
      b->g28reg = (int)n;
      return next;
    }
    struct expr *e = word_value(s, NULL, (int)n, 1, &next);
    w = new_word(s, WK_REG, 'R', col);
    w->num = (int)n;
    w->idx = (unsigned)n;
    w->e = e;
    return next;
  }
  case 'D': {
    adv(s);
    if (peek(s) != '1')
      fail(s, S42_E_SYNTAX, col, "the only D word is D1 (tool diameter)");
    adv(s);
    once(s, b->hasD, "D1", col);
    int32_t next;
    struct expr *e = word_value(s, "D1", -1, 1, &next);
    w = new_word(s, WK_REG, 'D', col);
    b->hasD = 1;
    w->idx = REG_D1;
    w->e = e;
    return next;
  }
  case 'T': {
    adv(s);
    if (peek(s) == 'T') {            /* TT1 TT2 TT */
      adv(s);
      unsigned mask = 3;
      if (peek(s) == '1' || peek(s) == '2') {
        mask = (unsigned)(peek(s) - '0');
        adv(s);
      }
      w = new_word(s, WK_AOP, 'T', col);
      w->op = OP_AZERO;
      w->idx = mask;
      return peek(s);
    }
    if (peek(s) == 'K')
      fail(s, S42_E_SYNTAX, col, "TK is read-only: only a tooth-step search with M10 sets it");
    if (!isdig(peek(s)))
      fail(s, S42_E_SYNTAX, col, "T word: expected TT, T0, T01..T04 or T11..T32, found %s", show(peek(s), buf));
    int d1 = peek(s) - '0';
    adv(s);
    int d2 = isdig(peek(s)) ? peek(s) - '0' : -1;
    if (d2 >= 0)
      adv(s);
    if (d1 == 0) {
      w = new_word(s, WK_AOP, 'T', col);
      if (d2 == -1) { w->op = OP_APTR0; w->idx = 3; }
      else if (d2 == 1 || d2 == 2) { w->op = OP_APTR0; w->idx = (unsigned)d2; }
      else if (d2 == 3 || d2 == 4) { w->op = OP_APTREND; w->idx = (unsigned)d2 - 2; }
      else fail(s, S42_E_SYNTAX, col, "T0%d is not an array operation (T0, T01, T02, T03, T04)", d2);
      return peek(s);
    }
    if (d1 > 3 || (d2 != 1 && d2 != 2))
      fail(s, S42_E_SYNTAX, col, "T%d%s is not an array word (T11 T21 T31 T12 T22 T32)", d1,
           d2 >= 0 ? (char[]){(char)('0' + d2), 0} : "");
    char name[4] = {'T', (char)('0' + d1), (char)('0' + d2), 0};
    int32_t next;
    struct expr *e = word_value(s, name, -1, 1, &next);
    w = new_word(s, WK_AWR, 'T', col);
    w->idx = (unsigned)(d2 - 1) | (unsigned)d1 << 2;
    w->e = e;
    return next;
  }
  case 'P': {
    adv(s);
    if (peek(s) == 'P') {
      adv(s);
      once(s, b->wkinds & (1u << WK_PP), "PP", col);
      w = new_word(s, WK_PP, 'P', col);
      int32_t next;
      w->num = (int)number_to(s, 3, "the target block number after PP", &next);
      return next;
    }
    if (b->wkinds & (1u << WK_P | 1u << WK_PCOND))
      fail(s, S42_E_SYNTAX, col, "two jumps P in one block");
    if (peek(s) == '(') {
      b->cond = cond(s, 0);
      w = new_word(s, WK_PCOND, 'P', col);
      int32_t next;
      w->num = (int)number_to(s, 3, "the target block number after the condition", &next);
      return next;
    }
    w = new_word(s, WK_P, 'P', col);
    int32_t next;
    w->num = (int)number_to(s, 3, "the target block number after P", &next);
    return next;
  }
  case '/': {
    char list[160];
    fail(s, S42_E_SYNTAX, col, "a slash argument must follow its function (%s)",
         kp_codes(list, sizeof list, takes_slash));
  }
  case 'N':
    fail(s, S42_E_SYNTAX, col, "a block number may only start the block");
  case 'U':
    fail(s, S42_E_SYNTAX, col, "UG is read-only: only a tooth-step search with M10 sets it");
  default:   /* (№ here, not as a case: the cases then span '/'..'Z', one bound) */
    if (c == 0x2116)
      fail(s, S42_E_SYNTAX, col, "a block number may only start the block");
    if (c >= 'a' && c <= 'z')
      fail(s, S42_E_SYNTAX, col, "unexpected %s: addresses are capital letters", show(c, buf));
    fail(s, S42_E_SYNTAX, col, "unexpected %s: not a word of the 2С42", show(c, buf));
  }
}

void parse_init(struct parser *p, const char *src, size_t n, struct diag_list *d)
{
  memset(p, 0, sizeof *p);
  p->d = d;
  lex_init(&p->lx, src, n, d);
}

void parse_free(struct parser *p)
{
  free(p->nodebuf);
  p->nodebuf = NULL;
  p->nodecap = 0;
  arena_free(&p->ar);
}

/* The block's header cleared (words are counted by nw); its slash
 * arguments too when `all` is set or it had any (b->slashed): only a
 * block with a slash argument changes them, from their cleared values. */
static inline void clear_block(struct block *b, int all)
{
  b->number = -1;
  b->ncol = 0;
  b->len = 0;
  b->bad = 0;
  b->g = 0;
  b->m = 0;
  b->nw = 0;
  b->wslots = b->wkinds = 0;
  b->wF = -1;
  b->hasD = 0;
  b->ngw = 0;
  b->slotrd = 0;
  b->cond = NULL;
  if (!all && !b->slashed)
    return;
  b->slashed = 0;
  memset(&b->g27, 0, sizeof b->g27);
  memset(&b->g33, 0, sizeof b->g33);
  memset(&b->m18, 0, sizeof b->m18);
  b->g27form = 0;
  b->ng29 = 0;
  b->g28min = b->g28max = NULL;
  b->g28reg = -1;
  b->g37axis = 0;
  b->nm16 = 0;
  b->nm20 = 0;
}

/* The first character of the next non-empty block, or LX_EOF. */
HOT int32_t first_char(struct lex *l)
{
  for (;;) {
    int32_t c = lex_peek(l);
    if (c != LX_EOB)
      return c;
    lex_adv(l);   /* (an end of block: lex_adv, not lex_adv1) */
  }
}

/* The start of the next non-empty block: 0 at the end of the text.  b
 * is cleared (clear_block's `all`: its slash arguments too, or only if it
 * had any). */
HOT int block_start(struct parser *p, struct block *b, int all)
{
  struct lex *l = &p->lx;
  arena_reset(&p->ar);
  clear_block(b, all);
  p->nodes = 0;
  l->number = -1;   /* before the first peek: a note there is this block's */
  l->note_here = 0;
  if (first_char(l) == LX_EOF)
    return 0;
  b->line = lex_line(l);
  b->col = lex_col(l);
  lex_block_begin(l);   /* the block's characters are counted from here */
  b->badnum = 0;
  return 1;
}

/* The block's number and words, after block_start: an error leaves by
 * longjmp (fail). */
static void block_words(struct parser *s)
{
  struct lex *l = &s->lx;
  struct block *b = s->b;
  int32_t c = lex_peek(l);
  if (c == 'H' && lex_cyrillic(l)) {
    /* Н, the Cyrillic N, looks like a Latin H: a block number meant */
    if (isdig(lex_peek2(l))) {
      b->badnum = 1;
      fail(s, S42_E_SYNTAX, b->col, "Cyrillic Н at the block start reads as the letter H: did you mean N "
           "(the block number, N1 or №1)?");
    }
  }
  if (c == 'N' || c == 0x2116) {   /* N12, №12, № 12 */
    b->ncol = lex_col(l);
    b->badnum = 1;
    lex_adv1(l);
    long n = number_to(s, 3, "a block number", &c);
    if (n < 1 || n > 999)
      fail(s, S42_E_RANGE, b->ncol, "block number %ld outside 1..999", n);
    b->number = (int)n;
    b->badnum = 0;
    lex_set_number(l, (int)n);
  }
  while (c != LX_EOB && c != LX_EOF)   /* (c: the character peek() returned) */
    c = word(s, c);
  if (b->g28reg == -2)
    fail(s, S42_E_SYNTAX, b->g28col, "G28 /min:max/ must be followed by the parameter: G28 /min:max/ R3");
}

/* The block's end, after its words or a longjmp out of them (`jumped` 1:
 * a syntax error; 2: out of memory). */
HOT void block_end(struct parser *p, struct block *b, int jumped)
{
  struct lex *l = &p->lx;
  if (jumped == 2) {   /* said once: the blocks after it are not read either */
    if (!p->d->oom)
      diag_add(p->d, DIAG_ERROR, S42_E_SYNTAX, b->line, b->col, b->number,
               "out of memory: the program could not be read from this block on");
    p->d->oom = 1;
    b->bad = 1;
  }
  if (jumped)
    lex_skip_block(l);
  p->paren = p->slash_ends = p->nodes = 0;
  b->len = lex_block_len(l, b->col);   /* (the cursor at the end mark, looked at) */
  if (lex_peek(l) == LX_EOB)
    lex_end_block(l);   /* (the empty block of a line end after a ^ too, which first_char would skip) */
}

int parse_block(struct parser *p, struct block *b)
{
  p->b = b;
  if (!block_start(p, b, 1))
    return 0;
  p->ar.oom = &p->jb;
  int jumped = setjmp(p->jb);
  if (!jumped)
    block_words(p);
  block_end(p, b, jumped);
  p->ar.oom = NULL;
  return 1;
}

void parse_all(struct parser *p, struct block *b, int (*each)(void *ctx, struct block *b), void *ctx)
{
  /* one setjmp for the whole text: after a longjmp out of a block's words
   * the loop goes on from that block's end (nothing here changes after
   * the setjmp but what p and b point to) */
  p->b = b;
  p->ar.oom = &p->jb;
  clear_block(b, 1);   /* then each block's clear_block leaves its slash arguments as they are when it had none */
  int jumped = setjmp(p->jb);
  if (jumped) {
    block_end(p, b, jumped);
    if (each(ctx, b))
      goto out;
  }
  while (block_start(p, b, 0)) {
    block_words(p);
    block_end(p, b, 0);
    if (each(ctx, b))
      break;
  }
out:
  p->ar.oom = NULL;
}
