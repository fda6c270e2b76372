/* The 2С42 compiler (src/dialect/2c42/compile.h).  Blocks are parsed one at a time and
 * compiled at once into bytecode (the parse arena is reset per block); the
 * static checks of a block run on its parse; program structure (units,
 * jump and call targets, running off a unit's end, reachability) is checked
 * at the end on a compact per-block summary, and targets are patched in. */
#include "compile.h"
#include "kprun.h"
#include "geom.h"
#include "kpmach.h"
#include "errors.h"
#include "kp.h"
#include "kpmsg.h"
#include "opcodes.h"
#include "parse.h"
#include "peep.h"
#include "plugin.h"
#include "vmmath.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The most blocks a program may have (README "Limits"): as many as BLOCK's
 * 24-bit operand numbers (vm/opcodes.h), 16,777,216. */
#define COMP_MAX_BLOCKS ((size_t)INS_AMAX + 1)

/* What the structure checks need of each block, kept small: it lives for
 * the whole compile (number, line and column are in program.blocks).  A
 * flags byte for every block; the calls and jumps, which most blocks have
 * not, in a list of their own in block order (struct summ, SF_JUMPS). */
/* SF_NONUM: the block's number did not parse -- it may be the one a
 * structure check misses, which then says nothing (one mistake, one error) */
enum { SF_M17 = 1, SF_M2 = 2, SF_UNCOND = 4, SF_BAD = 8, SF_NONUM = 16, SF_JUMPS = 32 };
#define NOPC 0xffffu       /* no instruction to patch */
struct summ {
  uint32_t i;              /* the block */
  int16_t L, P, PP;        /* targets, -1 none */
  uint16_t callpc, jpc, pppc;  /* instructions to patch, from the block's first; NOPC none.
                                  Each has the column of its word (L, P or P(...), PP): the
                                  structure checks' errors read it there (summ_col) */
};

struct comp {
  struct program *p;
  struct kp_ext *x;
  struct diag_list *d;
  struct block *b;
  uint8_t *sf;             /* each block's SF_ flags */
  size_t ns, capsf;
  struct summ *s;          /* the blocks with SF_JUMPS */
  size_t nj, capj;
  int oom;
  int toolong;             /* the code reached the VM's 24-bit operand space (said at the block) */
  int toomany;             /* more blocks than COMP_MAX_BLOCKS (said at the block) */
  int seen_g34;            /* text order: a G34 came before */
  int prev_g27;            /* the previous block had G27 */
  /* within a block: which slots are given, with known constant values */
  uint16_t given;
  uint16_t isconst;
  uint16_t badslot;        /* a slot whose word was refused (its checks would cascade) */
  /* store() folds an expression, then generates its code: gen reads the
   * fold of each node from the node (its memo argument) instead of folding each subtree
   * again -- unless the expression reads the slot being stored, whose
   * given and constant bits change in between (reads_slot) */
  uint64_t core_g;         /* the functions no plugin has (core_masks) */
  uint32_t core_m;
  /* the G and M numbers by what their rows say (core_masks): the questions
   * a block asks of its functions in number order are the lowest bit of
   * its g (m) and one of these */
  uint64_t g_table, g_own, g_dialog, g_plane, g_arc, g_sep, g_nodir;
  uint32_t m_own;
  double kval[SL__COUNT];
  const struct plug_set *plugins;
  uint32_t plugmask;       /* plugins the current block calls */
  int plug_g;              /* a group-1 G of a plugin that is not the language's, 0 none */
  size_t bstart;           /* the current block's first instruction */
  unsigned need;           /* the most stack the block's expressions need (the parser's bound) */
  int plane, arc;          /* the block's plane (plane_of) and arc G (first_g of g_arc, -1 none): check_block's */
  uint32_t ruleidx[16][2];  /* 1 + the program's rule of each kind (enum rule_kind, clamp 2 or not), 0 none yet */
  struct aslot *ah;        /* the attributes kept lately (keep_attr) */
  struct fcache {          /* blocks whose functions passed check_block's checks (keyed there) */
    uint64_t g;
    uint32_t m, k;
    int8_t arc;
    uint8_t plane;
  } fc[64];
  /* structure's index of the block numbers, made as the blocks come: the
   * first block of each number 1..999 (1 + its index, 0 none) and how many
   * have it; and the SF_ flags any block had at its start (SF_BAD, SF_NONUM) */
  uint32_t first1[1000];
  uint32_t count[1000];
  unsigned anyf;
};

static uint16_t col16(unsigned col)
{
  return (uint16_t)(col > 0xffff ? 0xffff : col);
}

/* An instruction of the current block, as an offset for struct summ. */
static uint16_t boff(struct comp *c, long pc)
{
  if (pc < 0 || (size_t)pc - c->bstart >= NOPC) {
    c->oom = 1;   /* cannot happen within MAX_NODES; refuse rather than patch wrongly */
    return NOPC;
  }
  return (uint16_t)((size_t)pc - c->bstart);
}

static void *grow(void *v, size_t *cap, size_t need, size_t elem, int *oom)
{
  if (need <= *cap)
    return v;
  size_t n = *cap ? *cap * 2 : 256;
  while (n < need)
    n *= 2;
  void *q = realloc(v, n * elem);
  if (!q) {
    *oom = 1;
    return v;
  }
  *cap = n;
  return q;
}

static void err(struct comp *c, int code, unsigned col, const char *fmt, ...)
  __attribute__((format(printf, 4, 5)));
static void err(struct comp *c, int code, unsigned col, const char *fmt, ...)
{
  char msg[240];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  diag_add(c->d, DIAG_ERROR, code, c->b->line, col ? col : c->b->col, c->b->number, "%s", msg);
}

static void warn(struct comp *c, unsigned col, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void warn(struct comp *c, unsigned col, const char *fmt, ...)
{
  char msg[240];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  diag_add(c->d, DIAG_WARNING, 0, c->b->line, col ? col : c->b->col, c->b->number, "%s", msg);
}

#define STACK_DELTA(name, opd, ext, pop, push, doc) [OP_##name] = (push) - (pop),
static const int8_t stack_delta[256] = {S42_OPCODES(STACK_DELTA)};   /* vm_ops' push - pop, by opcode */

/* The peephole rules on the instruction at the end (peep.c): called
 * where the second part of a pair they fuse is made -- a function (SIN,
 * COS), an arithmetic with an operand (gen's fusion), CMPCK
 * (fuse_compare), SETP (store) -- when the pair can fuse. */
static inline void peep_end(struct comp *c)
{
  size_t n = c->p->ncode;
  if (n > c->bstart + 1 && peep_pair(c->p->code[n - 2], c->p->code[n - 1]) && peep_last(c->p, c->bstart))
    c->oom = 1;
}

static long __attribute__((noinline)) emit_grow(struct comp *c, uint32_t ins, unsigned col)
{
  long i = prog_emit_grow(c->p, ins, col);
  if (i < 0) {
    if (c->p->ncode >= PROG_MAX_CODE && !c->toolong) {
      /* not memory: the code's own limit (vm/program.h) */
      c->toolong = 1;
      diag_add(c->d, DIAG_ERROR, S42_E_LIMIT, c->b->line, c->b->col, c->b->number,
               "more than %u instructions: the program is too long", PROG_MAX_CODE);
    }
    c->oom = 1;
  }
  return i;
}

/* prog_emit, inline: a block emits a dozen instructions */
static inline __attribute__((always_inline)) long emit(struct comp *c, int op, uint32_t a, unsigned col)
{
  struct program *p = c->p;
  size_t n = p->ncode;
  if (__builtin_expect(n >= p->capcode || col >= PROG_COLBIG, 0))   /* full (or at PROG_MAX_CODE); a column for colx */
    return emit_grow(c, INS(op, a), col);
  uint32_t *code = p->code;
  uint8_t *cols = p->cols;
  code[n] = INS(op, a);
  cols[n] = (uint8_t)col;
  p->ncode = n + 1;
  return (long)n;
}

/* The deepest stack of the current block's code, from the stack effects of
 * vm/opcodes.h: walked once the block is emitted, superinstructions fused,
 * so the count is exact.  A block's code runs straight through (vm/verify.c
 * proves the same walk safe).  The walk is needed only when the block's
 * peak as emit() counts it (struct comp) is over the deepest so far. */

static uint32_t block_stack(const struct comp *c)
{
  int depth = 0, max = 0;
  const uint32_t *code = c->p->code;
  for (size_t pc = c->bstart, n = c->p->ncode; pc < n; pc++) {
    depth += stack_delta[INS_OP(code[pc])];
    if (depth > max)
      max = depth;
  }
  return (uint32_t)max;
}

static void __attribute__((noinline)) emit_const(struct comp *c, double v, unsigned col)
{
  long k = prog_const(c->p, v);
  if (k < 0)
    c->oom = 1;
  emit(c, OP_CONST, (uint32_t)(k < 0 ? 0 : k), col);
}

static inline void emit_num(struct comp *c, double v, unsigned col)
{
  /* an integer in 0..INS_AMAX (the conversion is exact there: no floor call) */
  if (v >= 0 && v <= INS_AMAX && v == (double)(uint32_t)v && !(v == 0 && signbit(v)))
    emit(c, OP_INT, (uint32_t)v, col);
  else
    emit_const(c, v, col);
}

/* ---- constant folding ---- */

static inline int fold(struct comp *c, struct expr *e, double *v, int *failed);

static int fold_node(struct comp *c, const struct expr *e, double *v, int *failed)
{
  double a, b;
  char msg[200];
  int e1, e2;
  switch (e->kind) {
  case EX_NUM:
    *v = e->v;
    return 1;
  case EX_SLOT:
    if (!(c->given & (1u << e->idx))) {
      *v = 0;
      return 1;
    }
    if (c->isconst & (1u << e->idx)) {
      *v = c->kval[e->idx];
      return 1;
    }
    return 0;
  case EX_NEG:
    if (!fold(c, e->a, &a, failed))
      return 0;
    *v = -a;
    return 1;
  case EX_BIN:
    e1 = fold(c, e->a, &a, failed);
    e2 = fold(c, e->b, &b, failed);
    if (!e1 || !e2 || *failed)
      return 0;
    break;
  case EX_FN:
    if (!fold(c, e->a, &a, failed) || *failed)
      return 0;
    b = 0;
    break;
  case EX_CMP:
    e1 = fold(c, e->a, &a, failed);
    e2 = fold(c, e->b, &b, failed);
    if (!e1 || !e2 || *failed)
      return 0;
    *v = vm_rel(a, b, e->op);
    return 1;
  case EX_AND: case EX_OR:
    e1 = fold(c, e->a, &a, failed);
    e2 = fold(c, e->b, &b, failed);
    if (!e1 || !e2 || *failed)
      return 0;
    *v = e->kind == EX_AND ? (a != 0 && b != 0) : (a != 0 || b != 0);
    return 1;
  default:
    return 0;
  }
  int code = vm_math(c->p, e->op, a, b, v, msg, sizeof msg);
  if (code) {
    err(c, code, e->col, "%s", msg);
    *failed = 1;
    return 0;
  }
  return 1;
}

/* Returns 1 and *v when e is constant.  A folding error (E-DIV0, E-DOMAIN on
 * literals) is reported here, once, and *failed set.  Every node's answer
 * is kept in it (e->fk, e->v) for gen. */
static inline int fold(struct comp *c, struct expr *e, double *v, int *failed)
{
  int k;
  if (e->kind == EX_NUM) {   /* the leaves without a call */
    *v = e->v;
    k = 1;
  } else if (e->kind == EX_REG || e->kind == EX_ARR) {
    k = 0;
  } else if (e->kind == EX_NEG && (e->a->kind == EX_NUM || e->a->kind == EX_REG || e->a->kind == EX_ARR)) {
    /* a sign on a leaf (X-2000, -R3): fold_node's EX_NEG without the call */
    struct expr *a = e->a;
    k = a->kind == EX_NUM;
    a->fk = k ? 1 : 2;
    if (k)
      e->v = *v = -a->v;
  } else {
    k = fold_node(c, e, v, failed);
    if (k)
      e->v = *v;
  }
  e->fk = k ? 1 : 2;
  return k;
}

/* Is v (> 0) a power of two, as frexp(v) == 0.5 says, from its bits
 * (without the call): a normal number with no mantissa bits, or a
 * subnormal one with one; not the infinity. */
static inline int is_pow2(double v)
{
  uint64_t b;
  memcpy(&b, &v, sizeof b);
  uint64_t ex = b >> 52 & 0x7ff, man = b & ((1ull << 52) - 1);
  return ex == 0 ? man && !(man & (man - 1)) : ex < 0x7ff && !man;
}

/* The superinstruction for binary `op` with a right operand pushed by
 * `push` (INT, CONST or REG), or -1. */
static int fuse_operand(int op, int push)
{
  static const uint8_t tab[4][3] = {
    {OP_ADDI, OP_ADDK, OP_ADDR}, {OP_SUBI, OP_SUBK, OP_SUBR},
    {OP_MULI, OP_MULK, OP_MULR}, {OP_DIVI, OP_DIVK, OP_DIVR},
  };
  int row = op == OP_ADD ? 0 : op == OP_SUB ? 1 : op == OP_MUL ? 2 : op == OP_DIV ? 3 : -1;
  int col = push == OP_INT ? 0 : push == OP_CONST ? 1 : push == OP_REG ? 2 : -1;
  return row < 0 || col < 0 ? -1 : tab[row][col];
}

/* CMPC whose right operand is one push of a constant, an integer or a
 * register: one instruction (the loop test of nearly every cycle). */
static void fuse_compare(struct comp *c)
{
  size_t n = c->p->ncode;
  if (n < 2)
    return;
  uint32_t rel = INS_A(c->p->code[n - 1]) & 7, push = c->p->code[n - 2];
  long idx = -1;
  int op = OP_CMPCK;
  switch (INS_OP(push)) {
  case OP_CONST: idx = (long)INS_A(push); break;
  case OP_INT: idx = prog_const(c->p, (double)INS_A(push)); break;
  case OP_REG: idx = (long)INS_A(push); op = OP_CMPCR; break;
  default: return;
  }
  if (idx < 0 || (uint32_t)idx > INS_AMAX >> 3)
    return;
  c->p->code[n - 2] = INS(op, rel | (uint32_t)idx << 3);
  if (prog_col_copy(c->p, n - 2, n - 1))
    c->oom = 1;
  c->p->ncode = n - 1;
  peep_end(c);
}

static void gen(struct comp *c, struct expr *e, int memo);

/* The first place TK or UG is read (for the warning when no M10 sets them). */
static void __attribute__((noinline)) uses_tk(struct comp *c, const struct expr *e)
{
  if (!c->x->uses_tk) {
    c->x->uses_tk = 1;
    c->x->tk_line = c->b->line;
    c->x->tk_col = e->col;
    c->x->tk_number = c->b->number;
  }
}

static inline __attribute__((always_inline)) void gen_reg(struct comp *c, const struct expr *e)
{
  emit(c, OP_REG, e->idx, e->col);
  if (e->idx == REG_TK || e->idx == REG_UG)
    uses_tk(c, e);
}

/* gen() of e, its leaves without a call: with the folds kept (memo), a
 * constant node and a register are one push. */
static inline __attribute__((always_inline)) void gen_in(struct comp *c, struct expr *e, int memo)
{
  if (memo) {
    if (e->kind == EX_NUM && e->idx <= INS_AMAX) {   /* emit_num's INT, the parser's integer */
      emit(c, OP_INT, e->idx, e->col);
      return;
    }
    if (e->kind <= EX_FN && e->fk == 1) {
      emit_num(c, e->v, e->col);
      return;
    }
    if (e->kind == EX_REG) {
      gen_reg(c, e);
      return;
    }
  }
  gen(c, e, memo);
}

static void gen(struct comp *c, struct expr *e, int memo)
{
  double v;
  int failed = 0;
  if (e->kind != EX_CMP && e->kind != EX_AND && e->kind != EX_OR &&
      (memo ? e->fk == 1 && (v = e->v, 1) : fold(c, e, &v, &failed))) {
    emit_num(c, v, e->col);
    return;
  }
  switch (e->kind) {
  case EX_NUM:
    emit_num(c, e->v, e->col);
    return;
  case EX_REG:
    gen_reg(c, e);
    return;
  case EX_SLOT:
    if (c->given & (1u << e->idx))
      emit(c, OP_WORD, e->idx, e->col);
    else
      emit_num(c, 0, e->col);
    return;
  case EX_ARR:
    emit(c, OP_ARD, e->idx, e->col);
    return;
  case EX_NEG:
    gen_in(c, e->a, memo);
    emit(c, OP_NEG, 0, e->col);
    return;
  case EX_FN:
    gen_in(c, e->a, memo);
    emit(c, e->op, 0, e->col);
    peep_end(c);
    return;
  case EX_BIN: {
    gen_in(c, e->a, memo);
    size_t mark = c->p->ncode;
    gen_in(c, e->b, memo);
    /* superinstruction: an operator whose right operand is one push */
    uint32_t last = mark < c->p->ncode ? c->p->code[mark] : 0;
    int fused = fuse_operand(e->op, (int)INS_OP(last));
    if (c->p->ncode == mark + 1 && fused >= 0) {
      /* x / 2^n is x * 2^-n to the bit: a multiplication is cheaper */
      double dv = fused == OP_DIVI ? (double)INS_A(last) : fused == OP_DIVK ? c->p->k[INS_A(last)] : 0;
      if (dv > 0 && is_pow2(dv)) {
        long k = prog_const(c->p, 1.0 / dv);
        if (k >= 0) {
          fused = OP_MULK;
          last = INS(OP_CONST, (uint32_t)k);
        }
      }
      c->p->code[mark] = INS(fused, INS_A(last));
      if (prog_col_set(c->p, mark, e->col))
        c->oom = 1;
      peep_end(c);
      return;
    }
    emit(c, e->op, 0, e->col);
    return;
  }
  case EX_CMP:
    gen_in(c, e->a, memo);
    gen_in(c, e->b, memo);
    emit(c, OP_CMP, e->op, e->col);
    return;
  case EX_AND: case EX_OR:
    gen_in(c, e->a, memo);
    gen_in(c, e->b, memo);
    emit(c, e->kind == EX_AND ? OP_AND : OP_OR, 0, e->col);
    return;
  }
}

/* ---- conversion rules ---- */

/* The rule of each word a block stores: its name (the word, as messages
 * say it), its range, rounding and clamping.  A parameter's (RK_PARAM) is
 * implied by SETP and has no name of its own. */
enum rule_kind { RK_X, RK_Y, RK_Z, RK_A, RK_I, RK_J, RK_K, RK_H, RK_MIN, RK_MAX, RK_OSCF, RK_SRCHF,
                 RK_G04X, RK_F, RK_D1, RK_PARAM, RK__COUNT };
_Static_assert((int)RK_X == (int)SL_X && (int)RK_H == (int)SL_H && (int)RK_SRCHF == (int)SL_SRCHF,
               "a slot's rule kind is its number");
struct wrule { const char *name; double lo, hi; int round, clamp; };
static const struct wrule wrules[RK__COUNT] = {
  [RK_X] = {"X", -999999, 999999, 1, 0},
  [RK_Y] = {"Y", -999999, 999999, 1, 0},
  [RK_Z] = {"Z", -999999, 999999, 1, 0},
  [RK_A] = {"A", -9999999, 9999999, 1, 0},
  [RK_I] = {"I", -4000000, 4000000, 1, 0},
  [RK_J] = {"J", -4000000, 4000000, 1, 0},
  [RK_K] = {"K", -4000000, 4000000, 1, 0},
  [RK_H] = {"H", 0, 30000, 1, 0},
  [RK_MIN] = {"G28 min", -9999999, 9999999, 0, 0},
  [RK_MAX] = {"G28 max", -9999999, 9999999, 0, 0},
  [RK_OSCF] = {"G07 F", 0, 6000, 1, 1},
  [RK_SRCHF] = {"M12 F", 0, 6000, 1, 1},
  [RK_G04X] = {"G04 X", 0, 999999, 1, 0},
  [RK_F] = {"F", 0, 6000, 1, 1},
  [RK_D1] = {"D1", 0, 400000, 0, 0},
  [RK_PARAM] = {NULL, -9999999, 9999999, 0, 0},
};

/* The rule of word slot `slot` (its kind is the slot's number, but for
 * G04's X). */
static inline int slot_rule(const struct block *b, int slot)
{
  return slot == SL_X && ((b->g >> 4) & 1) ? RK_G04X : slot;
}

/* The program's rule for kind rk (clamp 2: a clamp already warned of), in
 * the program's table by the first word that needs it (rule_add). */
static uint32_t __attribute__((noinline)) rule_add(struct comp *c, int rk, int clamp, uint32_t *idx)
{
  const struct wrule *w = &wrules[rk];
  struct prog_rule r;
  memset(&r, 0, sizeof r);
  r.lo = w->lo;
  r.hi = w->hi;
  r.round = (uint8_t)w->round;
  r.clamp_hi = (uint8_t)clamp;
  r.err = (uint8_t)S42_E_RANGE;
  snprintf(r.name, sizeof r.name, "%s", w->name);
  long i = prog_rule(c->p, &r);
  if (i < 0) {
    c->oom = 1;
    return 0;
  }
  *idx = (uint32_t)i + 1;
  return (uint32_t)i;
}

static inline __attribute__((always_inline)) uint32_t rule(struct comp *c, int rk, int clamp)
{
  uint32_t *idx = &c->ruleidx[rk][clamp == 2];
  return *idx ? *idx - 1 : rule_add(c, rk, clamp, idx);
}

/* round(): half away from zero, the zero's sign kept (an inline: the libm
 * call costs more than the rounding of the integers it mostly gets). */
static inline double round_half_away(double v)
{
  if (!(fabs(v) < 4503599627370496.0))   /* 2^52: an integer already; NaN and infinities as they are */
    return v;
  double t = (double)(int64_t)v, f = v - t;   /* f: exact */
  if (f >= 0.5)
    t += 1;
  else if (f <= -0.5)
    t -= 1;
  return copysign(t, v);
}

/* Does e read word slot `slot`? */
static int reads_slot(const struct expr *e, unsigned slot)
{
  switch (e->kind) {
  case EX_SLOT:
    return e->idx == slot;
  case EX_NEG: case EX_FN:
    return reads_slot(e->a, slot);
  case EX_BIN: case EX_CMP: case EX_AND: case EX_OR:
    return reads_slot(e->a, slot) || reads_slot(e->b, slot);
  default:
    return 0;
  }
}

/* A word slot (dest past the registers) stored: given, and constant (k)
 * with the value v or not, for the checks that read it. */
static inline void slot_stored(struct comp *c, unsigned dest, int k, double v)
{
  if (dest < VM_NREG)
    return;
  unsigned s = dest - VM_NREG;
  c->given |= (uint16_t)(1u << s);
  if (k) {
    c->isconst |= (uint16_t)(1u << s);
    c->kval[s] = v;
  } else {
    c->isconst &= (uint16_t)~(1u << s);
  }
}

/* Emit value + SET into dest (register < VM_NREG, or VM_NREG + slot) by
 * the rule of kind rk; check a constant value now, as `s42 check` must. */
static void store(struct comp *c, struct expr *e, unsigned dest, int rk, unsigned col)
{
  double v;
  int failed = 0;
  if (!e || c->b->bad)
    return;   /* a block that did not parse is not compiled: it cannot run */
  if (e->need > c->need)
    c->need = e->need;
  const struct wrule *w = &wrules[rk];
  int clamp = w->clamp;
  int k = fold(c, e, &v, &failed);
  /* a refused word is reported once: the checks that need its value (the
   * arc's radius) skip it rather than report a second, false error */
  uint16_t bit = dest >= VM_NREG ? (uint16_t)(1u << (dest - VM_NREG)) : 0;
  if (failed) {
    c->badslot |= bit;
    return;
  }
  if (k) {
    if (w->round && !(e->kind == EX_NUM && e->idx <= INS_AMAX))   /* (the parser's integers are whole) */
      v = round_half_away(v);
    if (!(v >= w->lo && v <= w->hi)) {
      if (clamp && v > w->hi) {
        warn(c, col, "%s%.10g is over %.0f: clamped to %.0f", w->name, v, w->hi, w->hi);
        clamp = 2;   /* said once, here: not again when it runs */
      } else {
        char rn[8];   /* a parameter's rule has no name of its own: R12 */
        if (!w->name)
          snprintf(rn, sizeof rn, "R%u", dest % 1000);
        err(c, S42_E_RANGE, col, "%s = %.10g is outside %.10g..%.10g", w->name ? w->name : rn, v, w->lo, w->hi);
        c->badslot |= bit;
        return;
      }
    }
  }
  slot_stored(c, dest, k, !k ? 0 : clamp && v > w->hi ? w->hi : v);   /* rounded above when the rule rounds */
  /* failed returned above: the folds hold, unless the expression reads
   * the slot just stored (only X Y Z A are operands; the parser says
   * whether the block has any) */
  gen_in(c, e, !(c->b->slotrd && dest >= VM_NREG && dest - VM_NREG <= SL_A && reads_slot(e, dest - VM_NREG)));
  if (rk == RK_PARAM) {
    emit(c, OP_SETP, dest, col);   /* a parameter: its rule is implied */
    peep_end(c);
    return;
  }
  uint32_t r = rule(c, rk, clamp);
  emit(c, OP_SET, dest | r << 10, col);
}

/* store() of a word, inline for its most common value: a whole literal,
 * signed or not (X+1000, Y-500, F2000), within its rule's range -- what
 * store() would do, without the call and the general fold and gen.
 * Anything else (an expression, a value out of range, a parameter's SETP,
 * a block that did not parse) goes to store(). */
static inline __attribute__((always_inline)) void store_word(struct comp *c, struct expr *e, unsigned dest, int rk,
                                                             unsigned col)
{
  struct expr *n = e && e->kind == EX_NEG ? e->a : e;
  if (n && n->kind == EX_NUM && n->idx <= INS_AMAX && rk != RK_PARAM && !c->b->bad) {
    /* the parser's integer, so whole: a rule's rounding keeps it */
    double v = n == e ? n->v : -n->v;
    const struct wrule *w = &wrules[rk];
    if (v >= w->lo && v <= w->hi) {
      if (e->need > c->need)
        c->need = e->need;
      n->fk = 1;   /* fold's marks */
      if (n != e) {
        e->fk = 1;
        e->v = v;
      }
      slot_stored(c, dest, 1, v);
      if (n == e)
        emit(c, OP_INT, n->idx, n->col);
      else
        emit_num(c, v, e->col);
      emit(c, OP_SET, dest | rule(c, rk, w->clamp) << 10, col);
      return;
    }
  }
  store(c, e, dest, rk, col);
}

/* ---- static checks of one block ---- */

#define G(n) ((b->g >> (n)) & 1)
#define M(n) ((b->m >> (n)) & 1)

/* Is there a word for slot (its column in *col)?  The parser indexes the
 * words as it reads them (struct block: wslots, wkinds, wfirst, wF). */
static int slot_word(const struct comp *c, int slot, unsigned *col)
{
  if (!(c->b->wslots & (1u << slot)))
    return 0;
  if (col)
    *col = c->b->slotcol[slot];
  return 1;
}

/* The first word of a kind, or NULL. */
static const struct word *find_word(const struct comp *c, int kind)
{
  const struct block *b = c->b;
  return b->wkinds & (1u << kind) ? &b->w[b->wfirst[kind]] : NULL;
}

/* The block's motion (words.h): the first G in number order that is a
 * motion of its own; else a plugin's G (check_block knows its group); an M
 * that is a motion of its own (M19) overrides either; with none of them a
 * dialog G makes it a dialog.  The caller makes a block with axis words
 * and nothing else a G01. */
/* The lowest function number in a block's g (or m) bits, taken out of
 * them: a loop visits the block's few functions in number order. */
static int take_low(uint64_t *bits)
{
  int n = __builtin_ctzll(*bits);
  *bits &= *bits - 1;
  return n;
}

static int motion_of(const struct comp *c, const struct block *b)
{
  uint64_t own = b->g & c->g_own;
  int mo = own ? kp_g(__builtin_ctzll(own))->motion : MO_NONE;
  if (mo == MO_NONE && (b->g & ~c->g_table))
    mo = MO_PLUGIN;
  uint32_t mown = b->m & c->m_own;
  if (mown)
    return kp_m(__builtin_ctz(mown))->motion;
  return mo == MO_NONE && (b->g & c->g_dialog) ? MO_DIALOG : mo;
}

/* The first G of the block in `mask` (comp's g_arc, g_sep, g_nodir), or -1. */
static inline int first_g(const struct block *b, uint64_t mask)
{
  uint64_t g = b->g & mask;
  return g ? __builtin_ctzll(g) : -1;
}

/* The plane the block selects: its G17, G18 or G19 (the first), or 0. */
static inline int plane_of(const struct comp *c, const struct block *b)
{
  uint64_t g = b->g & c->g_plane;
  return g ? kp_g(__builtin_ctzll(g))->plane : 0;
}

static int is_sep(const struct kp_word *w) { return w->kind == 'G' && (w->flags & KP_SEP); }
static int is_arc(const struct kp_word *w) { return w->kind == 'G' && (w->flags & KP_ARC); }

/* In-plane axes of G17 (XY), G18 (YZ), G19 (XZ): slot indices (the slots
 * of X Y Z are the axes' indices). */
static void plane_axes(int plane, int *p, int *q)
{
  geom_plane_axes(kp_plane(plane), p, q);
}

static const char *slot_name(int s)
{
  static const char *const n[] = {"X", "Y", "Z", "A", "I", "J", "K", "H"};
  return s < 8 ? n[s] : "?";
}

/* Check the arc geometry when every in-plane word is a literal. */
static void check_arc_const(struct comp *c, int plane, unsigned col)
{
  int p, q;
  plane_axes(plane, &p, &q);
  int cp = p + SL_I, cq = q + SL_I;   /* centre slot of each axis: X->I, Y->J, Z->K */
  int need[4] = {p, q, cp, cq};
  double v[4];
  for (int i = 0; i < 4; i++) {
    int s = need[i];
    if (c->badslot & (1u << s))
      return;   /* refused already, with its own error */
    if (!(c->given & (1u << s)))
      v[i] = 0;
    else if (c->isconst & (1u << s))
      v[i] = c->kval[s];
    else
      return;
  }
  struct geom_arc a = {v[0], v[1], v[2], v[3], 0};   /* the sense does not change the radii */
  char msg[200];
  if (geom_arc_check(&a, MACH_ARC_RMAX, MACH_ARC_TOL, msg, sizeof msg))
    err(c, S42_E_ARC, col, "%s", msg);
}

static int text_len_check(struct comp *c, const struct text *t, const char *fn, unsigned max)
{
  if (!t->s)
    return 0;   /* the text did not parse: already reported */
  if (t->nchars > max) {
    err(c, S42_E_TEXT, t->col, "%s: text of %u characters, at most %u", fn, t->nchars, max);
    return 0;
  }
  return 1;
}

/* The ((Rn reference at p, read as the screen draws it (display/screen.c):
 * spaces before and after R (or Cyrillic Р), then the number up to the
 * first non-digit.  Its end, or NULL when p starts none. */
static const char *ref_end(const char *p)
{
  if (strncmp(p, "((", 2) != 0)
    return NULL;
  const char *q = p + 2;
  while (*q == ' ') q++;
  if (*q == 'R') q++;
  else if (strncmp(q, "\xD0\xA0", 2) == 0) q += 2;
  else return NULL;
  while (*q == ' ') q++;
  if (*q < '0' || *q > '9')
    return NULL;
  while (*q >= '0' && *q <= '9') q++;
  return q;
}

/* Characters of a display text outside its ((Rn references. */
static unsigned text_chars_outside_ref(const char *s)
{
  unsigned n = 0;
  for (const char *p = s; p && *p;) {
    const char *e = ref_end(p);
    if (e) {
      p = e;
      continue;
    }
    if (((unsigned char)*p & 0xC0) != 0x80)
      n++;
    p++;
  }
  return n;
}

/* Check the ((Rn references in a display text; returns how many. */
static int text_refs(struct comp *c, const struct text *t, const char *fn, int g29)
{
  int n = 0;
  if (!t->s)
    return 0;
  for (const char *s = t->s; (s = strstr(s, "((")) != NULL;) {
    const char *q = s + 2;
    while (*q == ' ') q++;
    if (*q != 'R' && strncmp(q, "\xD0\xA0", 2) != 0) {   /* R or Cyrillic Р */
      s += 2;
      continue;
    }
    q += *q == 'R' ? 1 : 2;
    while (*q == ' ') q++;
    if (*q < '0' || *q > '9') {
      err(c, S42_E_TEXT, t->col, "%s: ((R must be followed by a parameter number", fn);
      return n;
    }
    long r = strtol(q, NULL, 10);
    if (r > 113)
      err(c, S42_E_TEXT, t->col, "%s: parameter R%ld does not exist (R0..R113)", fn, r);
    else if (g29 && (r < 100 || r > 113))
      warn(c, t->col, "%s: current data are R100..R113 by convention; R%ld is shown anyway", fn, r);
    n++;
    s = q;
  }
  return n;
}

/* The group of Gn: the language's, or the one its plugin declares. */
static inline int group_of(const struct comp *c, int n)
{
  const struct kp_word *w = kp_g(n);
  const struct s42_function *fn;
  if (w)
    return w->group;
  if (plug_find(c->plugins, 'G', n, &fn) >= 0)
    return fn->group;
  return kp_g_group(n);
}

/* A function of the block that lives in a plugin: E-PLUGIN when the plugin
 * is missing; for a function the language does not name, the rules its
 * descriptor declares (the words it takes, a separate block, a plane). */
static void plugin_function(struct comp *c, char kind, int n, unsigned col, int nwords, int plane)
{
  const struct block *b = c->b;
  const struct s42_function *fn = NULL;
  const struct kp_word *kw = kp_word(kind, n);
  if (kw && !kw->owner)
    return;   /* the core's own: no plugin has it (plug_find says -1) */
  int i = plug_find(c->plugins, kind, n, &fn);
  if (i < 0) {
    if (kw && kw->owner) {
      char msg[600];
      plug_why_missing(c->plugins, kind, n, msg, sizeof msg);
      err(c, S42_E_PLUGIN, col, "%s", msg);
    }
    return;
  }
  c->plugmask |= 1u << i;
  if (kw)
    return;   /* the language's own rules were checked above */
  if (kind == 'G' && fn->group == 1)
    c->plug_g = n;
  if ((fn->flags & S42_FN_SEPARATE) && nwords && !fn->operands)
    err(c, S42_E_BLOCK, col, "%c%02d stands in a separate block: no axis or centre words beside it", kind, n);
  if ((fn->flags & S42_FN_PLANE) && !plane)
    err(c, S42_E_PLANE, col, "%c%02d needs a plane in the same block: G17 (XY), G18 (YZ) or G19 (XZ)", kind, n);
  if (!fn->operands)
    return;
  static const char letters[] = "XYZAIJK";
  for (size_t w = 0; w < b->nw; w++) {
    char l = 0;
    if (b->w[w].kind == WK_SLOT && b->w[w].idx < 7)
      l = letters[b->w[w].idx];
    else if (b->w[w].kind == WK_REG && (b->w[w].letter == 'F' || b->w[w].letter == 'D'))
      l = (char)b->w[w].letter;
    if (l && !strchr(fn->operands, l))
      err(c, S42_E_BLOCK, b->w[w].col, "%c%02d takes no %c word (it takes %s)", kind, n, l,
          *fn->operands ? fn->operands : "none");
  }
}

/* The G and M functions that are the core's own (a row with no owner):
 * bit n set, from the table. */
static void core_masks(struct comp *c)
{
  for (int n = 0; n < 64; n++) {
    const struct kp_word *w = kp_g(n);
    if (!w)
      continue;
    uint64_t bit = 1ull << n;
    c->g_table |= bit;
    if (!w->owner)
      c->core_g |= bit;
    if (w->motion == MO_DIALOG)
      c->g_dialog |= bit;
    else if (w->motion != MO_NONE)
      c->g_own |= bit;
    if (w->plane)
      c->g_plane |= bit;
    if (w->flags & KP_ARC)
      c->g_arc |= bit;
    if (w->flags & KP_SEP)
      c->g_sep |= bit;
    if (w->flags & KP_NODIR)
      c->g_nodir |= bit;
  }
  for (int n = 0; n < 32; n++) {
    if (kp_m(n) && !kp_m(n)->owner)
      c->core_m |= 1u << n;
    if (kp_m(n) && kp_m(n)->motion != MO_NONE)
      c->m_own |= 1u << n;
  }
}

static void check_dialog(struct comp *c);

/* The word slots of the axes X Y Z A (struct block's wslots). */
#define AXIS_SLOTS (1u << SL_X | 1u << SL_Y | 1u << SL_Z | 1u << SL_A)

static inline __attribute__((always_inline)) void check_block(struct comp *c, const struct word *L, const struct word *P, const struct word *PC,
                        const struct word *PP)
{
  struct block *b = c->b;
  unsigned col;
  int plane = 0;
  char list[80];
  /* the axis and centre words, and the column of the first of each in
   * slot order (X Y Z A, I J K) */
  unsigned axes = b->wslots & AXIS_SLOTS;
  unsigned centres = b->wslots & (1u << SL_I | 1u << SL_J | 1u << SL_K);
  static const uint8_t nbits[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};   /* (no popcnt call) */
  int naxis = nbits[axes], ncentre = nbits[centres >> SL_I];
  unsigned cecol = centres ? b->slotcol[__builtin_ctz(centres)] : 0;
  if (!(b->g | b->m) && !b->ngw) {
    /* no G or M function: of the checks below only the centre words',
     * H's, the calls' and jumps' and the length apply */
    c->arc = -1;
    c->plane = 0;
    if (ncentre)
      err(c, S42_E_BLOCK, cecol, "centre words I J K belong to an arc (%s)", kp_codes(list, sizeof list, is_arc));
    goto words;
  }
  /* The checks of the block's functions from here to `words` depend on its
   * G and M functions and which words it has, no more (the key below):
   * a block that has those of one that passed them passes them too, with
   * the same arc and plane.  (The G words' order only orders the errors;
   * the plugins' groups are the session's.) */
  uint32_t fk = (b->wslots & (AXIS_SLOTS | 1u << SL_I | 1u << SL_J | 1u << SL_K)) | (uint32_t)(b->wF >= 0) << 8 |
                (uint32_t)(P || PC) << 9 | (uint32_t)(PP != NULL) << 10;
  struct fcache *fe = &c->fc[(b->g * 0x9E3779B97F4A7C15ull ^ (b->m ^ (uint64_t)fk << 32) * 0xBF58476D1CE4E5B9ull) >> 58];
  if (fe->g == b->g && fe->m == b->m && fe->k == fk) {   /* (an empty entry: no G and no M, not here) */
    c->arc = fe->arc;
    plane = c->plane = fe->plane;
    goto words;
  }
  size_t ndiag = c->d->nerr + c->d->nwarn;
  /* groups, the G words in text order */
  int seen[5] = {0};
  for (int i = 0; i < b->ngw; i++) {
    const struct word *w = &b->w[b->gw[i]];
    int grp = group_of(c, w->num);
    if (seen[grp])
      err(c, S42_E_GROUP, w->col, "G%02d and G%02d are both group %d functions", seen[grp], w->num, grp);
    else
      seen[grp] = w->num;
  }
  unsigned axcol = axes ? b->slotcol[__builtin_ctz(axes)] : 0;
  /* a dialog or display function (group 4) stands with no function of
   * groups 1-3 and no axis or centre word: only assignments, array
   * operations and M functions beside it (language.md sec. 8) */
  int g4_words = 0;   /* said: the block's axis or centre words do not belong */
  if (seen[4]) {
    int other = 0;   /* one error a block: the first thing that does not belong */
    for (int i = 0; i < b->ngw && !other; i++) {
      const struct word *w = &b->w[b->gw[i]];
      int grp = group_of(c, w->num);
      if (grp >= 1 && grp <= 3) {
        err(c, S42_E_GROUP, w->col, "G%02d (dialog and display, group 4) stands without functions of groups 1-3: "
            "G%02d belongs in another block", seen[4], w->num);
        other = 1;
      }
    }
    if ((naxis || ncentre) && !other) {
      g4_words = 1;
      err(c, S42_E_GROUP, axcol && (!cecol || axcol < cecol) ? axcol : cecol,
          "G%02d (dialog and display, group 4) stands without axis or centre words", seen[4]);
    }
  }
  const struct word *F = b->wF >= 0 ? &b->w[b->wF] : NULL;
  int arc = c->arc = first_g(b, c->g_arc);   /* its G, or -1 */

  /* functions that stand in a separate block */
  for (uint64_t bits = b->g & c->g_sep; bits;) {
    int g = take_low(&bits);
    if (g == 7) {
      if (naxis != 1 || ncentre)
        err(c, S42_E_OSC, b->gcol[7], "G07 takes exactly one axis word (the stroke) and F (the speed)");
      else if (!F)
        err(c, S42_E_OSC, b->gcol[7], "G07 needs F, the oscillation speed");
    } else if (g == 4) {
      if (!slot_word(c, SL_X, NULL))
        err(c, S42_E_BLOCK, b->gcol[4], "G04 needs X, the dwell in 0.1 s (G04 X+20 = 2 s)");
      if (naxis > 1 || ncentre)
        err(c, S42_E_BLOCK, b->gcol[4], "G04 stands in a separate block: only X (the dwell) beside it");
    } else if (naxis || ncentre) {
      err(c, S42_E_BLOCK, axcol ? axcol : cecol, "G%02d stands in a separate block: no axis or centre words beside it", g);
    }
  }
  if (M(19)) {
    if (first_g(b, c->g_sep) >= 0)
      err(c, S42_E_BLOCK, b->mcol[19], "M19 gives the direction of a move: not with %s",
          kp_codes(list, sizeof list, is_sep));
    if (!naxis)
      err(c, S42_E_BLOCK, b->mcol[19], "M19 needs the increments that give the direction of the move");
  }

  /* arcs and planes */
  plane = c->plane = plane_of(c, b);
  if (arc >= 0) {
    int g = arc;
    int helix = (kp_g(g)->flags & KP_HELIX) != 0;
    if (!plane) {
      err(c, S42_E_PLANE, b->gcol[g], "G%02d needs a plane in the same block: G17 (XY), G18 (YZ) or G19 (XZ)", g);
    } else {
      int p, q;
      plane_axes(plane, &p, &q);
      int outside = 0;
      for (int s = SL_X; s <= SL_A; s++) {
        if (s == p || s == q || !slot_word(c, s, &col))
          continue;
        outside++;
        if (!helix)
          err(c, S42_E_PLANE, col, "%s is not in the G%d plane of this arc (%s%s)", slot_name(s), plane,
              slot_name(p), slot_name(q));
      }
      if (helix && outside > 1)
        err(c, S42_E_PLANE, b->gcol[g], "G%d: only one axis outside the G%d plane may move along the helix", g, plane);
      for (int s = SL_I; s <= SL_K; s++)
        if (s - SL_I != p && s - SL_I != q && slot_word(c, s, &col))
          err(c, S42_E_PLANE, col, "centre word %s is not in the G%d plane (%s%s)", slot_name(s), plane,
              slot_name(p), slot_name(q));
    }
  } else {
    if (ncentre && !g4_words)
      err(c, S42_E_BLOCK, cecol, "centre words I J K belong to an arc (%s)", kp_codes(list, sizeof list, is_arc));
    if (plane && !M(19))
      warn(c, b->gcol[plane], "G%d has no effect without an arc (%s)", plane, kp_codes(list, sizeof list, is_arc));
  }

  /* auxiliary functions (none of these is said without two M words) */
  if (b->m & (b->m - 1)) {
    int wheel = M(3) + M(4) + M(5);
    if (wheel > 1)
      err(c, S42_E_BLOCK, b->mcol[M(3) ? (M(4) ? 4 : 5) : 5], "only one of M3 M4 M5 in a block");
    if (M(22) && M(23))
      err(c, S42_E_BLOCK, b->mcol[23], "M22 and M23 contradict each other");
    if (M(25) && M(26))
      err(c, S42_E_BLOCK, b->mcol[26], "M25 and M26 contradict each other");
    if (M(27) + M(28) + M(29) > 1)
      err(c, S42_E_BLOCK, b->mcol[29] ? b->mcol[29] : b->mcol[28], "only one of M27 M28 M29 in a block");
    if (M(18) && M(21))
      err(c, S42_E_BLOCK, b->mcol[21], "M18 shows a directive and M21 erases it: not both in a block");
    if (M(17) && M(2))
      err(c, S42_E_BLOCK, b->mcol[17], "M17 and M2 in one block");
  }
  if ((P || PC) && (M(17) || M(2)))
    err(c, S42_E_BLOCK, (P ? P : PC)->col, "a block may not hold both a jump and M%d", M(17) ? 17 : 2);
  int dg = b->g ? first_g(b, c->g_nodir) : -1, dlg = dg >= 0;
  if (dlg && PP)
    err(c, S42_E_BLOCK, PP->col, "PP is not allowed in a block with G%02d", dg);
  if (dlg && M(18))
    err(c, S42_E_BLOCK, b->mcol[18], "M18 is not allowed in a block with G%02d", dg);
  if (dlg && M(21))
    err(c, S42_E_BLOCK, b->mcol[21], "M21 is not allowed in a block with G%02d", dg);
  if ((M(10) || M(12)) && !(G(10) || G(11)))
    err(c, S42_E_BLOCK, b->mcol[M(10) ? 10 : 12], "M%d belongs to a tooth-step search (G10 or G11)", M(10) ? 10 : 12);
  if (c->d->nerr + c->d->nwarn == ndiag)
    *fe = (struct fcache){.g = b->g, .m = b->m, .k = fk, .arc = (int8_t)c->arc, .plane = (uint8_t)plane};
words:
  if (slot_word(c, SL_H, &col) && !L)
    err(c, S42_E_BLOCK, col, "H (repeat count) without L (sub call)");
  if (L || P || PC || PP) {
    if (L && (L->num < 2 || L->num > 999))
      err(c, S42_E_RANGE, L->col, "L%d: a sub's first block is 2..999", L->num);
    if (!b->bad && ((P && P->num < 1) || (PC && PC->num < 1)))
      err(c, S42_E_RANGE, (P ? P : PC)->col, "jump target 0: block numbers are 1..999");
    if (!b->bad && PP && PP->num < 1)
      err(c, S42_E_RANGE, PP->col, "PP target 0: block numbers are 1..999");
  }

  /* group 4: dialog and display */
  if (b->g & (1ull << 27 | 1ull << 28 | 1ull << 33 | 1ull << 37) || M(18) || b->ng29)
    check_dialog(c);
  if (b->len > 320)
    err(c, S42_E_BLOCKLEN, b->col, "block of %u characters; at most 320 (ten display lines)", b->len);

  /* functions that plugins implement (the core's own have no plugin:
   * plugin_function returns at once for them, so they are not visited) */
  c->plugmask = 0;
  c->plug_g = 0;
  for (uint64_t bits = b->g & ~c->core_g; bits;) {
    int n = take_low(&bits);
    plugin_function(c, 'G', n, b->gcol[n], naxis + ncentre, plane);
  }
  for (uint64_t bits = b->m & ~c->core_m; bits;) {
    int n = take_low(&bits);
    plugin_function(c, 'M', n, b->mcol[n], naxis + ncentre, plane);
  }
}

/* The checks of group 4, dialog and display: G27 G28 G33 G37, and the
 * texts of M18 and G29. */
static void check_dialog(struct comp *c)
{
  struct block *b = c->b;
  if (G(28) && !c->prev_g27)
    err(c, S42_E_ORDER, b->gcol[28], "G28 must follow a G27 block (it stores the number G27 took)");
  if (G(27) && c->seen_g34)
    err(c, S42_E_ORDER, b->gcol[27], "G27 after G34: input has ended");
  if (G(27)) {
    text_len_check(c, &b->g27, "G27", b->g27form == '-' ? 56 : 24);
    if (strstr(b->g27.s ? b->g27.s : "", "(("))
      err(c, S42_E_TEXT, b->g27.col, "G27: ((Rn is for G29 and M18 texts");
  }
  if (G(33)) {
    text_len_check(c, &b->g33, "G33", 32);
    text_refs(c, &b->g33, "G33", 0);
  }
  if (M(18) && text_len_check(c, &b->m18, "M18", 32)) {
    int refs = text_refs(c, &b->m18, "M18", 0);
    /* each ((Rn shows as an 8-column field: the line can be wider than
     * its text, and the screen cuts it at 32 columns (language.md sec. 9) */
    unsigned shown = text_chars_outside_ref(b->m18.s) + 8u * (unsigned)refs;
    if (refs && shown > 32)
      warn(c, b->m18.col, "M18: with its %d value field%s of 8 columns the directive can be %u columns wide; "
           "the screen shows the first 32", refs, refs > 1 ? "s" : "", shown);
  }
  for (int i = 0; i < b->ng29; i++) {
    int refs = text_refs(c, &b->g29[i], "G29", 1);
    if (refs > 1) {
      err(c, S42_E_TEXT, b->g29[i].col, "G29: one ((Rn value per line");
    } else if (refs == 1) {
      /* the value takes the last 8 columns: the text beside it is <= 24 */
      struct text t = b->g29[i];
      t.nchars = text_chars_outside_ref(t.s);
      if (t.nchars > 24)
        err(c, S42_E_TEXT, t.col, "G29: %u characters of text beside a value, at most 24", t.nchars);
    } else {
      text_len_check(c, &b->g29[i], "G29", 32);
    }
  }
  if (G(37) && b->g37axis != 'Y')
    err(c, S42_E_AXIS, b->g37col ? b->g37col : b->gcol[37],
        "G37 returns only Y to its home position: G37 /Y/");
}

/* ---- one block ---- */

static uint32_t add_str(struct comp *c, const struct text *t)
{
  size_t n = strlen(t->s) + 1;
  c->x->str = grow(c->x->str, &c->x->capstr, c->x->nstr + n, 1, &c->oom);
  if (c->oom)
    return 0;
  memcpy(c->x->str + c->x->nstr, t->s, n);
  c->x->nstr += n;
  return (uint32_t)(c->x->nstr - n + 1);
}

static int keep_more(struct comp *c, const struct block *b, struct kp_attr *at);

/* The attributes kept lately, by a hash of their bits (2^AH_BITS slots, 64
 * KiB: in cache): a block whose attributes are in its slot takes that
 * index, another is kept anew and takes the slot.  A program has few
 * different attributes, which stay; one whose every block differs (texts)
 * costs a look into this table a block, not into kp_ext.a. */
#define AH_BITS 13
struct aslot { uint32_t fp, e; };   /* the hash's low bits; 1 + the index in kp_ext.a, 0 none */

static inline uint64_t attr_hash(const struct kp_attr *at)
{
  uint64_t w[4];
  memcpy(w, at, sizeof w);
  return (w[0] ^ (w[1] << 23 | w[1] >> 41)) * 0x9E3779B97F4A7C15ull +
         (w[2] ^ (w[3] << 37 | w[3] >> 27)) * 0xBF58476D1CE4E5B9ull;
}

/* The block's attributes: its index into kp_ext.a, where an equal record
 * is kept once (mostly: see struct aslot). */
static void keep_attr(struct comp *c, const struct kp_attr *at)
{
  struct kp_ext *x = c->x;
  if (!c->ah && !(c->ah = calloc((size_t)1 << AH_BITS, sizeof *c->ah))) {
    c->oom = 1;
    return;
  }
  uint64_t h = attr_hash(at);
  struct aslot *sl = &c->ah[h >> (64 - AH_BITS)];
  uint32_t e = sl->e;
  if (!e || sl->fp != (uint32_t)h || memcmp(&x->a[e - 1], at, sizeof *at) != 0) {
    x->a = grow(x->a, &x->cap, x->n + 1, sizeof *x->a, &c->oom);
    if (c->oom)
      return;
    x->a[x->n++] = *at;
    e = (uint32_t)x->n;
    sl->fp = (uint32_t)h;
    sl->e = e;
  }
  if (!x->ai32 && e > 0x10000) {   /* past 16 bits: 32 from here on */
    uint32_t *w = malloc((x->capai ? x->capai : 1) * sizeof *w);
    if (!w) {
      c->oom = 1;
      return;
    }
    for (size_t k = 0; k < x->nai; k++)
      w[k] = x->ai16[k];
    free(x->ai16);
    x->ai16 = NULL;
    x->ai32 = w;
  }
  if (x->nai >= x->capai) {
    size_t cap = x->capai;
    if (x->ai32)
      x->ai32 = grow(x->ai32, &cap, x->nai + 1, sizeof *x->ai32, &c->oom);
    else
      x->ai16 = grow(x->ai16, &cap, x->nai + 1, sizeof *x->ai16, &c->oom);
    if (c->oom)
      return;
    x->capai = cap;
  }
  if (x->ai32)
    x->ai32[x->nai++] = e - 1;
  else
    x->ai16[x->nai++] = (uint16_t)(e - 1);
}

static inline __attribute__((always_inline)) void compile_block(struct comp *c)
{
  struct block *b = c->b;
  const struct word *L = NULL, *P = NULL, *PC = NULL, *PP = NULL;
  int jumps = (b->wkinds & (1u << WK_L | 1u << WK_P | 1u << WK_PCOND | 1u << WK_PP)) != 0;
  if (jumps) {
    L = find_word(c, WK_L);
    P = find_word(c, WK_P);
    PC = find_word(c, WK_PCOND);
    PP = find_word(c, WK_PP);
  }
  check_block(c, L, P, PC, PP);

  struct prog_block pb = {.code = (uint32_t)c->p->ncode, .line = b->line,
                          .number = (uint32_t)(b->number < 0 ? 0 : b->number), .col = col16(b->col)};
  long bi = prog_block_push(c->p, &pb);
  if (bi < 0) {
    c->oom = 1;
    return;
  }
  c->sf = grow(c->sf, &c->capsf, c->ns + 1, sizeof *c->sf, &c->oom);
  if (c->oom)
    return;
  struct kp_attr attr, *at = &attr;   /* kept (keep_attr) once the block is compiled */
  uint8_t *flags = &c->sf[c->ns];
  struct summ summ, *sm = &summ;   /* the block's calls and jumps: made when it has some */
  if (jumps)
    summ = (struct summ){.i = (uint32_t)c->ns, .L = -1, .P = -1, .PP = -1, .callpc = NOPC, .jpc = NOPC, .pppc = NOPC};
  *flags = (uint8_t)((b->bad ? SF_BAD : 0) | (b->badnum ? SF_NONUM : 0));
  c->anyf |= *flags;
  if (b->number > 0 && b->number < 1000) {
    if (!c->first1[b->number])
      c->first1[b->number] = (uint32_t)c->ns + 1;
    c->count[b->number]++;
  }
  c->ns++;
  c->bstart = pb.code;
  *at = (struct kp_attr){.g = b->g, .m = b->m, .plugins = c->plugmask, .plug_g = (uint8_t)c->plug_g,
                         .plane = (uint8_t)c->plane};
  int mo = motion_of(c, b);
  c->given = c->isconst = c->badslot = 0;
  c->need = 0;
  emit(c, OP_BLOCK, (uint32_t)bi, b->col);

  /* the words that store, in text order (the G and M words, the calls and
   * the jumps are the checks' and the end's) */
  for (const struct word *w = b->w, *end = b->w + b->nw; w < end; w++) {
    if (w->kind == WK_SLOT) {   /* the most: X Y Z A I J K H */
      store_word(c, w->e, VM_NREG + w->idx, slot_rule(b, (int)w->idx), w->col);
      at->slots |= (uint16_t)(1u << w->idx);
      if (w->idx <= SL_A) {
        /* M19 teach-in: a bare parameter (+Rn / -Rn) receives the move */
        const struct expr *e = w->e;
        int sign = 1;
        if (e->kind == EX_NEG) { sign = -1; e = e->a; }
        if (e->kind == EX_REG && e->idx <= 113)
          at->bare[w->idx] = (int8_t)(sign * ((int)e->idx + 1));
      }
      continue;
    }
    switch (w->kind) {
    case WK_REG: {
      int g07 = G(7), srch = (G(10) || G(11)) && M(12);
      if (w->letter == 'F' && (g07 || srch)) {
        store_word(c, w->e, VM_NREG + (g07 ? SL_OSCF : SL_SRCHF), g07 ? RK_OSCF : RK_SRCHF, w->col);
        at->slots |= (uint16_t)(1u << (g07 ? SL_OSCF : SL_SRCHF));
      } else if (w->letter == 'F') {
        store_word(c, w->e, REG_F, RK_F, w->col);
        at->has_f = 1;
      } else if (w->letter == 'D') {
        store(c, w->e, REG_D1, RK_D1, w->col);
      } else {
        /* a parameter: SETP, whose rule is implied; the name (R12) only
         * when store() reports its value */
        store(c, w->e, w->idx, RK_PARAM, w->col);
      }
      break;
    }
    case WK_AWR:
      if (b->bad || !w->e)
        break;
      if (w->e->need > c->need)
        c->need = w->e->need;
      gen(c, w->e, 0);
      emit(c, OP_AWR, w->idx, w->col);
      break;
    case WK_AOP:
      emit(c, w->op, w->idx, w->col);
      break;
    default:
      break;
    }
  }
  if (mo == MO_NONE && (b->wslots & AXIS_SLOTS))
    mo = MO_G01;   /* axis words and nothing else that moves */
  at->motion = (uint8_t)mo;
  if (G(28) && b->g28min && b->g28max) {
    store(c, b->g28min, VM_NREG + SL_MIN, RK_MIN, b->g28col);
    store(c, b->g28max, VM_NREG + SL_MAX, RK_MAX, b->g28col);
    /* |answer| must lie in min..max: bounds the wrong way round refuse
     * every answer, and the operator could never leave the field */
    const uint16_t both = 1u << SL_MIN | 1u << SL_MAX;
    if ((c->given & both) == both && (c->isconst & both) == both && c->kval[SL_MIN] > c->kval[SL_MAX])
      err(c, S42_E_RANGE, b->g28col, "G28 /%.10g:%.10g/: the minimum is over the maximum, so no number can pass",
          c->kval[SL_MIN], c->kval[SL_MAX]);
  }
  if (c->arc >= 0 && at->plane)
    check_arc_const(c, at->plane, b->gcol[c->arc]);
  if (b->cond && PC && !b->bad) {
    if (b->cond->need > c->need)
      c->need = b->cond->need;
    gen(c, b->cond, 0);
    size_t last = c->p->ncode - 1;
    if (b->cond->kind == EX_CMP && c->p->ncode > 0 && INS_OP(c->p->code[last]) == OP_CMP) {
      c->p->code[last] = INS(OP_CMPC, INS_A(c->p->code[last]));   /* CMP; COND */
      fuse_compare(c);
    } else
      emit(c, OP_COND, 0, PC->col);
  }
  /* Blocks with anything for the machine or the display always yield;
   * the rest only when the host watches every block (trace, operator).
   * M17 and M20 are the VM's alone (RET, the counter's TRUNC): a block
   * with no other word is nothing to the machine. */
  int machine = mo != MO_NONE || (b->m & ~(1u << 17 | 1u << 20)) || at->has_f || b->g;
  /* A block whose other M words only set the machine's switches (M22 M23
   * M25 M26), and that has no other word for the machine or the display,
   * is nothing to the host when they already stand so: MACHS lets the VM
   * see that from the switches the session publishes (vm.sw). */
  const uint32_t sws = 1u << 22 | 1u << 23 | 1u << 25 | 1u << 26;
  int switches = mo == MO_NONE && !at->has_f && !b->g && !at->slots && !at->plugins &&
                 (b->m & sws) && !(b->m & ~(sws | 1u << 17 | 1u << 20));
  if (switches) {
    uint32_t swmask = (b->m & (1u << 22 | 1u << 23) ? KP_SW_CORR : 0) | (b->m & (1u << 25 | 1u << 26) ? KP_SW_OVERRIDE : 0);
    uint32_t swon = (M(22) ? KP_SW_CORR : 0) | (M(26) ? KP_SW_OVERRIDE : 0);
    emit(c, OP_MACHS, swmask | swon << 12, b->col);
  } else
    emit(c, machine ? OP_MACH : OP_SYNC, 0, b->col);
  for (int i = 0; i < b->nm20; i++)
    emit(c, OP_TRUNC, b->m20[i], b->m20col[i]);
  emit(c, OP_COMMIT, 0, b->col);
  if (L) {
    int h = (c->given & (1u << SL_H)) != 0;
    sm->L = (int16_t)L->num;
    if (!h && INS_OP(c->p->code[c->p->ncode - 1]) == OP_COMMIT) {
      /* COMMIT; INT 1; CALL in one instruction */
      c->p->code[c->p->ncode - 1] = INS(OP_CCALL, 0);
      if (prog_col_set(c->p, c->p->ncode - 1, L->col))
        c->oom = 1;
      sm->callpc = boff(c, (long)c->p->ncode - 1);
    } else {
      emit(c, h ? OP_WORD : OP_INT, h ? SL_H : 1, L->col);   /* the count: H's value, or once */
      sm->callpc = boff(c, emit(c, OP_CALL, 0, L->col));
    }
  }
  if (PP) {
    sm->PP = (int16_t)PP->num;
    sm->pppc = boff(c, emit(c, OP_PPJ, 0, PP->col));
  }
  if (P || PC) {
    const struct word *j = P ? P : PC;
    sm->P = (int16_t)j->num;
    double v;
    int failed = 0;
    int always = P || (b->cond && fold(c, b->cond, &v, &failed) && v != 0);
    if (always)
      *flags |= SF_UNCOND;
    if (!L && !PP && INS_OP(c->p->code[c->p->ncode - 1]) == OP_COMMIT) {
      /* COMMIT; JMP / JCOND in one instruction */
      c->p->code[c->p->ncode - 1] = INS(P ? OP_CJMP : OP_CJCOND, 0);
      if (prog_col_set(c->p, c->p->ncode - 1, j->col))
        c->oom = 1;
      sm->jpc = boff(c, (long)c->p->ncode - 1);
    } else {
      sm->jpc = boff(c, emit(c, P ? OP_JMP : OP_JCOND, 0, j->col));
    }
  }
  if (M(17)) {
    *flags |= SF_M17;
    emit(c, OP_RET, 0, b->mcol[17]);
  }
  if (M(2)) {
    *flags |= SF_M2;
    emit(c, OP_END, 0, b->mcol[2]);
  }
  if (jumps) {
    c->s = grow(c->s, &c->capj, c->nj + 1, sizeof *c->s, &c->oom);
    if (c->oom)
      return;
    c->s[c->nj++] = summ;
    *flags |= SF_JUMPS;
  }
  /* a sub's lone M17: BLOCK; SYNC; COMMIT; RET, which BLOCKR runs at once */
  const uint32_t *code = c->p->code + c->bstart;
  if (M(17) && !c->oom && c->p->ncode == c->bstart + 4 && code[1] == INS(OP_SYNC, 0) &&
      code[2] == INS(OP_COMMIT, 0) && code[3] == INS(OP_RET, 0))
    c->p->code[c->bstart] = INS(OP_BLOCKR, (uint32_t)bi);
  if (L && !c->need)
    c->need = 1;   /* the count of a call */
  if (c->need > c->p->max_stack || c->need > 500) {
    uint32_t need = block_stack(c);
    if (need > c->p->max_stack)
      c->p->max_stack = need;
    if (need > 500)
      err(c, S42_E_SYNTAX, b->col, "expression too complex");
  }

  /* keep the texts and what else few blocks have (struct kp_more) */
  if (b->slashed && !keep_more(c, b, at))   /* (the parser's: a word with a slash argument) */
    return;
  if (M(10) && (G(10) || G(11)))
    c->x->has_m10 = 1;
  c->prev_g27 = G(27);
  if (G(34))
    c->seen_g34 = 1;
  keep_attr(c, at);
}

/* The block's texts, dialog forms and M16 list, kept in kp_ext.more; 0
 * when out of memory. */
static int keep_more(struct comp *c, const struct block *b, struct kp_attr *at)
{
  struct kp_more more = {.g28reg = (int16_t)b->g28reg, .g27form = b->g27form, .g37axis = b->g37axis};
  if (G(27) && b->g27.s) more.g27 = add_str(c, &b->g27);
  if (G(33) && b->g33.s) more.g33 = add_str(c, &b->g33);
  if (M(18) && b->m18.s) more.m18 = add_str(c, &b->m18);
  if (b->ng29) {
    more.g29 = (uint32_t)c->x->nlines;
    more.ng29 = (uint32_t)b->ng29;
    for (int i = 0; i < b->ng29; i++) {
      if (!b->g29[i].s)
        continue;
      c->x->lines = grow(c->x->lines, &c->x->caplines, c->x->nlines + 1, sizeof *c->x->lines, &c->oom);
      if (c->oom)
        return 0;
      c->x->lines[c->x->nlines++] = add_str(c, &b->g29[i]);
    }
  }
  if (b->nm16) {
    more.m16 = (uint32_t)c->x->nm16;
    more.nm16 = (uint32_t)b->nm16;
    c->x->m16 = grow(c->x->m16, &c->x->capm16, c->x->nm16 + (size_t)b->nm16, sizeof *c->x->m16, &c->oom);
    if (c->oom)
      return 0;
    memcpy(c->x->m16 + c->x->nm16, b->m16, (size_t)b->nm16 * sizeof *b->m16);
    c->x->nm16 += (size_t)b->nm16;
  }
  if (b->g28reg != -1 || b->g27form || b->g37axis || more.g27 || more.g33 || more.m18 || more.ng29 || more.nm16) {
    c->x->more = grow(c->x->more, &c->x->capmore, c->x->nmore + 1, sizeof *c->x->more, &c->oom);
    if (c->oom)
      return 0;
    c->x->more[c->x->nmore++] = more;
    at->more = (uint32_t)c->x->nmore;
  }
  return 1;
}

/* ---- program structure ---- */

/* The column of a call's or jump's word: its instruction's (struct summ). */
static unsigned summ_col(const struct comp *c, const struct summ *s, uint16_t pc)
{
  return prog_col(c->p, c->p->blocks[s->i].code + (size_t)pc);
}

static void serr(struct comp *c, size_t i, unsigned col, int code, const char *fmt, ...)
  __attribute__((format(printf, 5, 6)));
static void serr(struct comp *c, size_t i, unsigned col, int code, const char *fmt, ...)
{
  char msg[240];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  const struct prog_block *s = &c->p->blocks[i];
  diag_add(c->d, code ? DIAG_ERROR : DIAG_WARNING, code, s->line, col ? col : s->col, s->number ? (int)s->number : -1,
           "%s", msg);
}

static void ext_free(void *v)
{
  struct kp_ext *x = v;
  if (!x)
    return;
  free(x->a);
  free(x->ai16);
  free(x->ai32);
  free(x->more);
  free(x->str);
  free(x->lines);
  free(x->m16);
  free(x);
}

/* The unit of block i as structure() numbers them (program.blocks' unit,
 * -1 for a block before the first unit): read from the block table rather
 * than kept in an array of its own beside it. */
static inline int unit_of(const struct prog_block *B, size_t i)
{
  return B[i].unit == 0xffff ? -1 : (int)B[i].unit;
}

/* A block's flags in structure(): it starts a unit; a call lands in the
 * middle of a unit there; it can run. */
enum { FL_START = 1, FL_INTO = 2, FL_REACH = 4 };

/* Is call s an edge of the call graph: to a sub that exists, from a block
 * of a unit that can run? */
static inline int graph_call(const struct summ *s, const int *first, const struct prog_block *B, const uint8_t *fl)
{
  return s->L >= 2 && s->L < 1000 && first[s->L] >= 0 && unit_of(B, s->i) >= 0 && (fl[s->i] & FL_REACH);
}

/* The units that can call themselves, directly or through others: those
 * on a cycle of the call graph (the calls of reachable blocks), found as
 * its strongly connected components (Tarjan's, without recursion): linear
 * in units and calls.  cyc[u] is 1 for such a unit; NULL when out of memory. */
static char *calls_itself(const struct summ *S, size_t nj, const int *first, const struct prog_block *B, const uint8_t *fl,
                          int nu)
{
  size_t ne = 0;
  for (size_t k = 0; k < nj; k++)
    if (graph_call(&S[k], first, B, fl))
      ne++;
  size_t *off = calloc((size_t)nu + 1, sizeof *off);
  int *dst = malloc((ne ? ne : 1) * sizeof *dst);
  int *idx = malloc((size_t)nu * sizeof *idx), *low = malloc((size_t)nu * sizeof *low);
  int *stk = malloc((size_t)nu * sizeof *stk), *path = malloc((size_t)nu * sizeof *path);
  size_t *it = malloc((size_t)nu * sizeof *it);
  char *on = calloc((size_t)nu, 1), *cyc = calloc((size_t)nu, 1);
  if (!off || !dst || !idx || !low || !stk || !path || !it || !on || !cyc) {
    free(cyc);
    cyc = NULL;
    goto out;
  }
  /* the calls by caller (counting sort) */
  for (size_t k = 0; k < nj; k++)
    if (graph_call(&S[k], first, B, fl))
      off[unit_of(B, S[k].i) + 1]++;
  for (int u = 0; u < nu; u++)
    off[u + 1] += off[u];
  for (int u = 0; u < nu; u++)
    it[u] = off[u];
  for (size_t k = 0; k < nj; k++)
    if (graph_call(&S[k], first, B, fl)) {
      int from = unit_of(B, S[k].i), to = unit_of(B, first[S[k].L]);
      dst[it[from]++] = to;
      if (from == to)
        cyc[from] = 1;   /* calls itself directly */
    }
  for (int u = 0; u < nu; u++)
    idx[u] = -1;
  int next = 0, nstk = 0;
  for (int r = 0; r < nu; r++) {
    if (idx[r] >= 0)
      continue;
    int depth = 0;
    path[depth++] = r;
    idx[r] = low[r] = next++;
    it[r] = off[r];
    stk[nstk++] = r;
    on[r] = 1;
    while (depth) {
      int u = path[depth - 1];
      if (it[u] < off[u + 1]) {
        int v = dst[it[u]++];
        if (idx[v] < 0) {
          idx[v] = low[v] = next++;
          it[v] = off[v];
          stk[nstk++] = v;
          on[v] = 1;
          path[depth++] = v;
        } else if (on[v] && idx[v] < low[u]) {
          low[u] = idx[v];
        }
        continue;
      }
      depth--;
      if (depth && low[u] < low[path[depth - 1]])
        low[path[depth - 1]] = low[u];
      if (low[u] == idx[u]) {   /* u roots a component: pop it */
        int size = 0, top = nstk;
        do {
          on[stk[--nstk]] = 0;
          size++;
        } while (stk[nstk] != u);
        if (size > 1)
          for (int k = nstk; k < top; k++)
            cyc[stk[k]] = 1;
      }
    }
  }
out:
  free(off);
  free(dst);
  free(idx);
  free(low);
  free(stk);
  free(path);
  free(it);
  free(on);
  return cyc;
}

/* Push block v on reach_all's stack, doubling it when full: -1 when out
 * of memory (the stack freed). */
static int reach_push(uint32_t **stk, size_t *top, size_t *cap, uint32_t v)
{
  if (*top == *cap) {
    uint32_t *t = realloc(*stk, 2 * *cap * sizeof **stk);
    if (!t) {
      free(*stk);
      return -1;
    }
    *stk = t;
    *cap *= 2;
  }
  (*stk)[(*top)++] = v;
  return 0;
}

/* FL_REACH on every block that can run: from each unit's start, on
 * through the blocks that run on into the next and to the targets of
 * jumps (the calls' and jumps' list is in block order: walking on, the
 * next block's are the next in it).  0 when out of memory. */
static int reach_all(struct comp *c, uint8_t *fl, const int *first)
{
  size_t n = c->ns, nj = c->nj, cap = 256, top = 0;
  const uint8_t *F = c->sf;
  const struct summ *S = c->s;
  uint32_t *stk = malloc(cap * sizeof *stk);   /* blocks reached, not yet walked from */
  if (!stk)
    return 0;
  for (size_t i = 0; i < n; i++)
    if (fl[i] & FL_START) {
      fl[i] |= FL_REACH;
      if (reach_push(&stk, &top, &cap, (uint32_t)i))
        return 0;
    }
  while (top) {
    size_t i = stk[--top], k = 0, hi = nj;
    while (k < hi) {   /* the first calls and jumps at or after block i */
      size_t mid = (k + hi) / 2;
      if (S[mid].i < i)
        k = mid + 1;
      else
        hi = mid;
    }
    for (;;) {
      if (F[i] & SF_JUMPS) {
        while (S[k].i < i)
          k++;
        int tg[2] = {S[k].P, S[k].PP};
        for (int t = 0; t < 2; t++) {
          if (tg[t] <= 0 || tg[t] >= 1000 || first[tg[t]] < 0 || (fl[first[tg[t]]] & FL_REACH))
            continue;
          fl[first[tg[t]]] |= FL_REACH;
          if (reach_push(&stk, &top, &cap, (uint32_t)first[tg[t]]))
            return 0;
        }
      }
      if ((F[i] & (SF_M2 | SF_M17 | SF_UNCOND)) || i + 1 >= n || (fl[i + 1] & (FL_START | FL_REACH)))
        break;
      fl[++i] |= FL_REACH;   /* runs on into the next */
    }
  }
  free(stk);
  return 1;
}

static void structure(struct comp *c)
{
  size_t n = c->ns, nj = c->nj;
  const uint8_t *F = c->sf;
  const struct summ *S = c->s;
  const struct prog_block *B = c->p->blocks;
  if (n == 0) {
    diag_add(c->d, DIAG_ERROR, S42_E_SUB, 1, 1, -1, "the program is empty: it needs block 1 and M2");
    return;
  }
  /* index: number -> first block, count (compile_block's) */
  int first[1000], count[1000];
  for (int i = 0; i < 1000; i++) {
    first[i] = (int)c->first1[i] - 1;
    count[i] = (int)c->count[i];
  }
  /* and what a block that did not parse may have held: a number, an M2 */
  unsigned anyf = c->anyf;
  int nonum = (anyf & SF_NONUM) != 0, anybad = (anyf & SF_BAD) != 0;
  /* each block's FL_ flags: unit starts (block 1 and every L target) first */
  uint8_t *fl = calloc(n, 1);
  if (!fl) {
    c->oom = 1;
    return;
  }
  int mp = first[1];
  if (mp < 0 && nonum)
    ;   /* block 1 may be the one whose number is wrong: that error says it */
  else if (mp < 0)
    diag_add(c->d, DIAG_ERROR, S42_E_SUB, B[0].line, B[0].col, B[0].number ? (int)B[0].number : -1,
             "no block 1: the main program starts at block 1");
  else if (count[1] > 1)
    for (size_t i = 0; i < n; i++)
      if (B[i].number == 1 && (int)i != mp)
        serr(c, i, 0, S42_E_SUB, "block 1 appears twice: the main program starts at block 1");
  if (mp >= 0)
    fl[mp] = FL_START;
  for (size_t k = 0; k < nj; k++) {
    size_t i = S[k].i;
    if (S[k].L < 0 || S[k].L < 2 || S[k].L > 999)
      continue;
    int t = S[k].L;
    if (count[t] == 0) {
      if (!nonum)
        serr(c, i, summ_col(c, &S[k], S[k].callpc), S42_E_TARGET, "L%d: there is no block %d to call", t, t);
    }
    else if (count[t] > 1)
      serr(c, i, summ_col(c, &S[k], S[k].callpc), S42_E_SUB, "L%d: block %d appears %d times; a sub's first block must be unique",
           t, t, count[t]);
    else {
      size_t f = (size_t)first[t];
      if (mp >= 0 && first[t] > mp && !(fl[f] & FL_START))   /* once a sub, however many call it */
        serr(c, f, 0, S42_E_SUB, "sub %d starts after block 1: subs come before the main program", t);
      else if (f > 0 && !(fl[f] & (FL_START | FL_INTO)) && (int)f != mp &&
               !(F[f - 1] & (SF_M2 | SF_M17 | SF_UNCOND | SF_BAD))) {
        /* a call into the middle of a sub: the block before runs on into
         * it, so the call is the mistake (not that sub's "end") */
        fl[f] |= FL_INTO;
        serr(c, i, summ_col(c, &S[k], S[k].callpc), S42_E_SUB, "L%d: block %d is in the middle of a sub (block %d before it runs on into "
             "it); a sub starts after the end (M17, M2 or a jump) of the one before", t, t, B[f - 1].number);
      }
      fl[f] |= FL_START;
    }
  }
  /* units in text order: 0 = the MP, subs numbered from 1; whether a unit
   * has an M2 */
  int u = -1, nsub = 0, anym2 = 0;
  for (size_t i = 0; i < n; i++) {
    if (fl[i] & FL_START)
      u = ((int)i == mp) ? 0 : ++nsub;
    c->p->blocks[i].unit = (uint16_t)(u < 0 ? 0xffff : u);
    anym2 |= (F[i] & SF_M2) && u >= 0;
  }
  /* jumps */
  for (size_t j = 0; j < nj; j++) {
    size_t i = S[j].i;
    int tg[2] = {S[j].P, S[j].PP};
    uint16_t tpc[2] = {S[j].jpc, S[j].pppc};
    for (int k = 0; k < 2; k++) {
      int t = tg[k];
      if (t < 1)
        continue;
      if (t > 999 || count[t] == 0) {
        if (!nonum)
          serr(c, i, summ_col(c, &S[j], tpc[k]), S42_E_TARGET, "%s%d: there is no block %d", k ? "PP" : "P", t, t);
      }
      else if (count[t] > 1)
        serr(c, i, summ_col(c, &S[j], tpc[k]), S42_E_TARGET, "%s%d: block %d appears %d times; a jump target must be unique",
             k ? "PP" : "P", t, t, count[t]);
      else if (unit_of(B, first[t]) != unit_of(B, i))
        serr(c, i, summ_col(c, &S[j], tpc[k]), S42_E_SCOPE, "%s%d: block %d is in another %s", k ? "PP" : "P", t, t,
             unit_of(B, i) == 0 ? "unit (a sub)" : "unit");
    }
  }
  /* M17 in the MP, running off the end of a unit */
  for (size_t i = 0; i < n; i++) {
    if ((F[i] & SF_M17) && unit_of(B, i) == 0)
      serr(c, i, 0, S42_E_SUB, "M17 (end of sub) in the main program");
    int last = i + 1 == n || (fl[i + 1] & FL_START);
    if (!last || unit_of(B, i) < 0 || (F[i] & SF_BAD) || (i + 1 < n && (fl[i + 1] & FL_INTO)))
      continue;
    if (unit_of(B, i) == 0 && !anym2)
      continue;   /* the program has no M2 at all: that one error says it */
    int ok = (F[i] & (SF_M2 | SF_UNCOND)) || (unit_of(B, i) > 0 && (F[i] & SF_M17));
    if (!ok) {
      if (unit_of(B, i) == 0)
        serr(c, i, 0, S42_E_SUB, "the main program can run off its end here: its last block needs M2 or an unconditional jump");
      else
        serr(c, i, 0, S42_E_SUB, "this sub can run off its end here: its last block needs M17, M2 or an unconditional jump");
    }
  }
  if (!anym2 && mp >= 0 && !anybad)
    diag_add(c->d, DIAG_ERROR, S42_E_SUB, B[n - 1].line, B[n - 1].col, B[n - 1].number ? (int)B[n - 1].number : -1,
             "no M2: the program never ends (its last block needs M2 or an unconditional jump)");

  /* reachability, per unit, for the dead-code warning */
  if (!c->d->nerr && reach_all(c, fl, first)) {
    for (size_t i = 0; i < n; i++)
      if (!(fl[i] & FL_REACH)) {
        size_t j = i;
        while (j + 1 < n && !(fl[j + 1] & FL_REACH))
          j++;
        serr(c, i, 0, 0, "%s never run%s", unit_of(B, i) < 0 ? "blocks before the first unit are" : "this code is",
             j > i ? " (up to the next reachable block)" : "");
        i = j;
      }
    /* recursion: a sub that can call itself, directly or through others */
    char *cyc = calls_itself(S, nj, first, B, fl, nsub + 1);
    if (cyc) {
      for (size_t i = 0; i < n; i++)
        if ((fl[i] & FL_START) && unit_of(B, i) > 0 && cyc[unit_of(B, i)])
          serr(c, i, 0, 0, "sub %d can call itself: more than 8 nested calls stop the run with E-NEST",
               B[i].number);
      free(cyc);
    }
  }

  /* patch targets */
  if (!c->d->nerr) {
    for (size_t k = 0; k < nj; k++) {
      const struct summ *J = &S[k];
      uint32_t *code = c->p->code + B[J->i].code;
      if (J->callpc != NOPC)
        code[J->callpc] = INS(INS_OP(code[J->callpc]), (uint32_t)first[J->L]);   /* CALL or CCALL */
      if (J->jpc != NOPC)
        code[J->jpc] = INS(INS_OP(code[J->jpc]), (uint32_t)first[J->P]);
      if (J->pppc != NOPC)
        code[J->pppc] = INS(OP_PPJ, (uint32_t)first[J->PP]);
    }
    c->p->entry = c->p->blocks[mp].code;
  }
  free(fl);
}

void comp_setup(struct program *p)
{
  p->saved_reg = REG_F;
  p->lim = (struct prog_limits){
    .depth = KP_DEPTH, .arrays = KP_ARRAYS, .cells = KP_CELLS,
    .param_lo = -9999999, .param_hi = 9999999, .cell_lo = -9999999, .cell_hi = 9999999,
    .angle = 0.001, .trig_max = 2304000, .atan_max = 9999999, .log_max = 9999999,
  };
  p->msgs = &kp_msgs;
}

/* parse_all's each: a block parsed, compile it; nonzero to stop. */
static int compile_one(void *v, struct block *b)
{
  struct comp *c = v;
  if (c->ns >= COMP_MAX_BLOCKS) {
    diag_add(c->d, DIAG_ERROR, S42_E_LIMIT, b->line, b->col, b->number,
             "more than %zu blocks: the program is too long", COMP_MAX_BLOCKS);
    c->toomany = 1;   /* its structure is not checked: it cannot run */
    return 1;
  }
  compile_block(c);
  return c->oom;
}

int comp_program(const char *src, size_t n, struct diag_list *d, struct program *p)
{
  return comp_program_with(src, n, d, p, NULL);
}

int comp_program_with(const char *src, size_t n, struct diag_list *d, struct program *p,
                      const struct plug_set *plugins)
{
  struct comp c;
  memset(&c, 0, sizeof c);
  c.p = p;
  c.d = d;
  c.x = calloc(1, sizeof *c.x);
  c.b = malloc(sizeof *c.b);
  if (!c.x || !c.b) {
    free(c.x);
    free(c.b);
    diag_add(d, DIAG_ERROR, S42_E_SYNTAX, 1, 1, -1, "out of memory");
    return -1;
  }
  p->ext = c.x;
  p->ext_free = ext_free;
  p->runtime = &kp_mrun_runtime;   /* the runner runs a 2С42 block through src/dialect/2c42/kprun.c */
  c.x->plugins = (struct plug_set *)plugins;   /* the set is the caller's; its runtime starts them */
  d->src = src;   /* the source lines under the diagnostics */
  d->nsrc = n;
  comp_setup(p);
  core_masks(&c);
  p->file = d->file;
  /* a file in another encoding is one error, not one a block */
  unsigned bl, bc, bb;
  const char *enc;
  if (lex_find_bad_utf8(src, n, &bl, &bc, &bb, &enc)) {
    const char *name = d->file ? d->file : "FILE";
    if (enc)
      diag_add(d, DIAG_ERROR, S42_E_SYNTAX, bl, bc, -1,
               "not UTF-8 (it reads as %s%s): convert it with `iconv -f %s -t utf-8 %s > NEW.kp`", enc,
               strcmp(enc, "cp1251") == 0 ? ", Windows Cyrillic" : strcmp(enc, "cp866") == 0 ? ", DOS Cyrillic" : "",
               enc, name);
    else
      diag_add(d, DIAG_ERROR, S42_E_SYNTAX, bl, bc, -1,
               "not UTF-8: the byte 0x%02X here is no character; a program is UTF-8 text", bb);
    d->src = NULL;   /* its lines cannot be shown as they are */
    d->nsrc = 0;
    free(c.x);
    p->ext = NULL;
    p->ext_free = NULL;
    free(c.b);
    return -1;
  }
  struct parser ps;
  parse_init(&ps, src, n, d);
  ps.plugins = plugins;
  c.plugins = plugins;
  parse_all(&ps, c.b, compile_one, &c);
  /* a last instruction so that nothing runs off the code */
  emit(&c, OP_END, 0, 0);
  parse_free(&ps);
  if (!c.oom && !c.toomany)
    structure(&c);
  if (c.x->uses_tk && !c.x->has_m10)
    diag_add(d, DIAG_WARNING, 0, c.x->tk_line, c.x->tk_col, c.x->tk_number,
             "TK and UG are set only by a tooth-step search with M10, and this program has none: they read 0");
  if (c.oom && !c.toolong)
    diag_add(d, DIAG_ERROR, S42_E_LIMIT, 1, 1, -1, "out of memory");
  free(c.sf);
  free(c.s);
  free(c.ah);
  free(c.b);
  diag_sort(d);
  return d->nerr ? -1 : 0;
}
