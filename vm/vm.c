/* The VM's dispatch loop, in the style of Lua's lvm.c: vmcase/vmbreak are a
 * switch by default and computed goto under GCC; cases are short and the pc
 * is saved before anything that can raise, so every error knows its block
 * and column.  A block is a transaction: register writes are journaled and
 * the arrays snapshotted at their first change, so an error rolls back. */
#include "vm.h"
#include "errors.h"
#include "msgs.h"
#include "opcodes.h"
#include "vmmath.h"
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

const struct vm_opinfo vm_ops[OP__COUNT] = {
#define OP_INFO(name, opd, ext, pop, push, doc) {#name, OPD_##opd, OPD_##ext, pop, push, doc},
  S42_OPCODES(OP_INFO)
#undef OP_INFO
};

/* vm_init's refusal: before anything runs, naming the entry block. */
static int refuse(struct vm *vm, enum vm_detail id, ...)
{
  const struct program *p = vm->p;
  va_list ap;
  vm->cur = p->nblocks && p->entry < p->ncode ? (uint32_t)prog_block_at(p, p->entry) : 0;
  vm->err.code = S42_E_LIMIT;
  vm->err.block = vm->cur;
  va_start(ap, id);
  vm_msg_vformat(vm->err.msg, sizeof vm->err.msg, p->msgs, id, ap);
  va_end(ap);
  vm->done = 1;
  return -1;
}

int vm_init(struct vm *vm, const struct program *p)
{
  memset(vm, 0, sizeof *vm);
  vm->p = p;
  vm->pc = p->entry;
  vm->max_blocks = 100000000;
  if (p->max_stack > VM_STACK)
    return refuse(vm, VMSG_STACK, p->max_stack, VM_STACK);
  if (p->lim.depth > VM_DEPTH_MAX)
    return refuse(vm, VMSG_DEPTH, p->lim.depth, VM_DEPTH_MAX);
  if (p->lim.arrays > VM_ARRAYS_MAX || p->lim.cells > VM_CELLS_MAX)
    return refuse(vm, VMSG_ARRAYS, p->lim.arrays, p->lim.cells, VM_ARRAYS_MAX, VM_CELLS_MAX);
  /* one angle unit in radians, as vm_math computes it (to the bit) */
  vm->rad = M_PI / (180.0 / p->lim.angle);
  return 0;
}

/* The part of an array the program uses: the pointer, the length and its
 * lim.cells cells (a snapshot copies no more than the 2С42's 2 x 15 did). */
static inline size_t used_bytes(const struct vm *vm)
{
  return offsetof(struct vm_array, cell) + vm->p->lim.cells * sizeof(double);
}

static void rollback(struct vm *vm)
{
  while (vm->nundo > 0) {
    vm->nundo--;
    vm->reg[vm->undo[vm->nundo].reg] = vm->undo[vm->nundo].old;
  }
  for (uint32_t k = 0; vm->arr_saved; k++, vm->arr_saved >>= 1)
    if (vm->arr_saved & 1)
      memcpy(&vm->arr[k], &vm->arr_old[k], used_bytes(vm));
}

static void verr(struct vm *vm, int code, unsigned col, const char *fmt, va_list ap)
{
  vm->err.code = code;
  vm->err.block = vm->cur;
  vm->err.col = col;
  vsnprintf(vm->err.msg, sizeof vm->err.msg, fmt, ap);
  rollback(vm);
  vm->done = 1;
}

static void raise_at(struct vm *vm, uint32_t pc, int code, const char *fmt, ...)
  __attribute__((format(printf, 4, 5)));
static void raise_at(struct vm *vm, uint32_t pc, int code, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  verr(vm, code, pc < vm->p->ncode ? prog_col(vm->p, pc) : 0, fmt, ap);
  va_end(ap);
}

/* Raise code with the program's detail message id (vm/msgs.h: the
 * arguments that id declares, in order). */
static void raise_msg(struct vm *vm, uint32_t pc, int code, enum vm_detail id, ...)
{
  char msg[sizeof vm->err.msg];
  va_list ap;
  va_start(ap, id);
  vm_msg_vformat(msg, sizeof msg, vm->p->msgs, id, ap);
  va_end(ap);
  raise_at(vm, pc, code, "%s", msg);
}

void vm_fail(struct vm *vm, int code, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  verr(vm, code, 0, fmt, ap);
  va_end(ap);
}

static inline void journal(struct vm *vm, unsigned reg)
{
  /* A register written twice in a block needs only its first old value,
   * but a second entry is harmless and the check would cost more. */
  if (vm->nundo < VM_JOURNAL) {
    vm->undo[vm->nundo].reg = reg;
    vm->undo[vm->nundo].old = vm->reg[reg];
    vm->nundo++;
  }
}

void vm_set_reg(struct vm *vm, unsigned reg, double v)
{
  if (reg >= VM_NREG)
    return;
  /* A host may write one register many times in a block (a plugin's loop):
   * its first old value is all the rollback needs, and keeping one entry
   * per register keeps the journal from filling up and dropping a later
   * register's old value. */
  unsigned i = 0;
  while (i < vm->nundo && vm->undo[i].reg != reg)
    i++;
  if (i == vm->nundo)
    journal(vm, reg);
  vm->reg[reg] = v;
}

/* An array's first change in a block snapshots it (the part in use): a
 * block that touches one array copies one. */
static inline void save_array(struct vm *vm, uint32_t k)
{
  if (!(vm->arr_saved & 1u << k)) {
    memcpy(&vm->arr_old[k], &vm->arr[k], used_bytes(vm));
    vm->arr_saved |= 1u << k;
  }
}

/* The arrays of mask (bit k: array k) that the program has. */
static inline void save_arrays(struct vm *vm, uint32_t mask)
{
  for (uint32_t k = 0; k < vm->p->lim.arrays; k++)
    if (mask & 1u << k)
      save_array(vm, k);
}

void vm_load_array(struct vm *vm, int k, const double *v, int n)
{
  if (k < 0 || (uint32_t)k >= vm->p->lim.arrays || n < 0 || (uint32_t)n > vm->p->lim.cells)
    return;
  save_array(vm, (uint32_t)k);
  struct vm_array *a = &vm->arr[k];
  memset(a, 0, sizeof *a);
  for (int i = 0; i < n; i++)
    a->cell[i] = v[i];
  a->len = n;
}

static const char *num(char *buf, size_t n, double v)
{
  snprintf(buf, n, "%.10g", v);
  return buf;
}

/* SET: convert by the rule and store; 0 or an error code (message in vm). */
static int do_set(struct vm *vm, uint32_t pc, uint32_t a, double v)
{
  const struct prog_rule *r = &vm->p->rules[a >> 10];
  unsigned dest = a & 0x3ff;
  char b1[32], b2[32], b3[32];
  if (r->round)
    v = round(v);
  if (!(v >= r->lo && v <= r->hi)) {
    if (r->clamp_hi && v > r->hi) {
      if (r->clamp_hi == 1) {
        vm->clamped = (a >> 10) + 1;   /* the host warns */
        vm->clamped_from = v;
      }
      v = r->hi;
    } else {
      raise_msg(vm, pc, r->err, VMSG_RULE, r->name, num(b1, sizeof b1, v), num(b2, sizeof b2, r->lo),
                num(b3, sizeof b3, r->hi));
      return r->err;
    }
  }
  if (dest < VM_NREG) {
    journal(vm, dest);
    vm->reg[dest] = v;
  } else {
    vm->w[dest - VM_NREG] = v;
  }
  return 0;
}

/* An array bound broken: out of line, so that arr_pos stays a leaf. */
static __attribute__((noinline, cold)) int arr_fail(struct vm *vm, uint32_t pc, int code, int n)
{
  if (code == S42_E_ARRAYM)
    raise_msg(vm, pc, code, VMSG_ARRAYM, n);
  else
    raise_msg(vm, pc, code, VMSG_ARRAYP, n, vm->arr[n - 1].ptr, (int)vm->p->lim.cells - 1);
  vm->err.aux = n;
  return code;
}

/* Array access; mode 1 (T1x: then advance), 2 (T2x: stay), 3 (T3x: back
 * first).  The caller has snapshotted the array (save_array). */
static int arr_pos(struct vm *vm, uint32_t pc, uint32_t a, int *idx)
{
  struct vm_array *ar = &vm->arr[a & 3];
  int mode = (int)(a >> 2), n = (int)(a & 3) + 1;
  if (mode == 3) {
    if (ar->ptr == 0)
      return arr_fail(vm, pc, S42_E_ARRAYM, n);
    ar->ptr--;
  }
  if ((uint32_t)ar->ptr >= vm->p->lim.cells)
    return arr_fail(vm, pc, S42_E_ARRAYP, n);
  *idx = ar->ptr;
  if (mode == 1)
    ar->ptr++;
  return 0;
}

/* SETP's range error (and the fused forms' SETP part), raised at pc. */
static __attribute__((noinline, cold)) void param_fail(struct vm *vm, uint32_t pc, uint32_t reg, double v)
{
  char b1[32], b2[32], b3[32];
  const struct program *p = vm->p;
  raise_msg(vm, pc, S42_E_RANGE, VMSG_PARAM, reg, num(b1, sizeof b1, v), num(b2, sizeof b2, p->lim.param_lo),
            num(b3, sizeof b3, p->lim.param_hi));
}

/* Arithmetic that failed (or may fail): take the message from vm_math. */
static int math_at(struct vm *vm, uint32_t pc, int op, double a, double b, double *out)
{
  char msg[sizeof vm->err.msg];
  int e = vm_math(vm->p, op, a, b, out, msg, sizeof msg);
  if (e)
    raise_at(vm, pc, e, "%s", msg);
  return e;
}

#if defined(__GNUC__) && !defined(S42_SWITCH_DISPATCH)
#define VM_GOTO 1
#define vmdispatch(o) goto *disp[o];
#define vmcase(l) L_##l:
#define vmbreak do { ins = code[pc++]; goto *disp[INS_OP(ins)]; } while (0)
#else
#define vmdispatch(o) switch (o)
#define vmcase(l) case OP_##l:
#define vmbreak continue
#endif

#define RAISED goto fail
#define LEAVE(ev)                                    \
  do {                                               \
    vm->pc = pc;                                     \
    vm->depth = (int)depth;                          \
    vm->blocks = blocks0 + (uint64_t)(left0 - left); \
    vm->jflag = (uint8_t)jflag;                      \
    return (ev);                                     \
  } while (0)
/* BLOCK's part in every form of it: the block is current, and counted
 * against the budget (E-LIMIT past it) */
#define BLOCK_ENTER()                                                              \
  do {                                                                             \
    vm->cur = INS_A(ins);                                                          \
    if (left <= 0) {                                                               \
      raise_msg(vm, pc - 1, S42_E_LIMIT, VMSG_BUDGET, (unsigned long long)vm->max_blocks); \
      RAISED;                                                                      \
    }                                                                              \
  } while (0)
/* COMMIT's part in every form of it: the block's journal and array
 * snapshots are let go, and the block is counted as run */
#define BLOCK_COMMIT()     \
  do {                     \
    vm->nundo = 0;         \
    vm->arr_saved = 0;     \
    left--;                \
  } while (0)
/* An opcode whose plain-table entry is its one handler. */
#ifdef VM_GOTO
#define vmcase1(l) L_##l: LP_##l:
#else
#define vmcase1(l) vmcase(l)
#endif
/* The top of the stack lives in a local (tos), the rest in st[]: most
 * instructions then never touch memory for their operands.  st[0] is a
 * scratch cell that takes the undefined tos of an empty stack. */
#define POP() (popped = tos, tos = st[--sp], popped)
#define PUSH(v) (st[sp++] = tos, tos = (v))

/* Any of the n flags set: a watch array that flags no block watches nothing. */
static int any_set(const uint8_t *f, size_t n)
{
  for (size_t i = 0; i < n; i++)
    if (f[i])
      return 1;
  return 0;
}

int vm_skip(struct vm *vm)
{
  const struct program *p = vm->p;
  if (vm->done || vm->cur + 1 >= p->nblocks || vm->pc != p->blocks[vm->cur].code + 1 || vm->nundo)
    return -1;
  if (p->blocks[vm->cur + 1].unit != p->blocks[vm->cur].unit)
    return -1;
  vm->pc = p->blocks[vm->cur + 1].code;
  return 0;
}

enum vm_event vm_run(struct vm *vm)
{
  const struct program *p = vm->p;
  const uint32_t *code = p->code;
  const double *k = p->k;
  const struct prog_block *blk = p->blocks;   /* a jump's operand is a block (OPD_PC) */
  double st[VM_STACK + 1];   /* program.max_stack <= VM_STACK (vm_init) */
  double tos = 0.0, popped, out;
  int sp = 0;
  uint32_t pc = vm->pc;
  uint32_t ins, times;
  double a, b, r;
  /* the host sets these only between calls */
  const uint64_t limit = vm->max_blocks ? vm->max_blocks : UINT64_MAX;
  if (vm->watch != vm->watch_seen) {
    vm->watch_seen = vm->watch;
    vm->watch_any = vm->watch && any_set(vm->watch, p->nblocks);
  }
  const int watching = vm->start_all || vm->watch_any;
  const int yield_all = vm->yield_all;
  /* the program's parameter range, in locals: a store to a register could
   * alias p->lim for the compiler, and SETP runs in nearly every block */
  const double param_lo = p->lim.param_lo, param_hi = p->lim.param_hi;
  /* the same range within the finite numbers: a value inside is finite,
   * so a fused arithmetic-and-store needs one test for both of its checks */
  const double plo = param_lo < -DBL_MAX ? -DBL_MAX : param_lo, phi = param_hi > DBL_MAX ? DBL_MAX : param_hi;
  const double rad = vm->rad, trig_max = p->lim.trig_max;
  /* a call's two program constants, read once: the deepest nesting, and
   * the register a call saves and its return restores (a program with none
   * saves and restores a scratch cell, so CALL and RET need no test) */
  const uint32_t depth_max = p->lim.depth;
  double no_saved = 0.0;
  double *const saved = p->saved_reg >= 0 ? &vm->reg[p->saved_reg] : &no_saved;
  /* The call depth, the budget and the jump condition live in locals
   * while the VM runs: a call, a return and a block then keep them in
   * registers, not in a store and a load through vm.  LEAVE writes them
   * back (with the pc) at every return to the host. */
  uint32_t depth = (uint32_t)vm->depth;
  /* The blocks the budget has left: a block counts down and tests for 0,
   * not against a limit in another register.  Signed, so that a block the
   * host began before it lowered the budget still counts (below 0). */
  const uint64_t blocks0 = vm->blocks;
  const int64_t left0 = blocks0 >= limit ? 0
                        : limit - blocks0 > (uint64_t)INT64_MAX ? INT64_MAX : (int64_t)(limit - blocks0);
  int64_t left = left0;
  unsigned jflag = vm->jflag;

  if (vm->done)
    return vm->err.code ? VM_EV_ERROR : VM_EV_END;

#ifdef VM_GOTO
  /* Two dispatch tables (Lua's hook trick, decided once a call): when the
   * host watches nothing, BLOCK and SYNC go to forms that test no switch. */
  static const void *const disp_watch[OP__COUNT] = {
#define OP_LABEL(name, opd, ext, pop, push, doc) &&L_##name,
    S42_OPCODES(OP_LABEL)
#undef OP_LABEL
  };
  static const void *const disp_plain[OP__COUNT] = {
#define OP_LABEL(name, opd, ext, pop, push, doc) &&LP_##name,
    S42_OPCODES(OP_LABEL)
#undef OP_LABEL
  };
  const void *const *const disp = watching || yield_all ? disp_watch : disp_plain;
  vmbreak;
#else
  for (;;) {
    ins = code[pc++];
#endif
    vmdispatch(INS_OP(ins)) {
      vmcase(BLOCK) {
        BLOCK_ENTER();
        if (watching && (vm->start_all || vm->watch[vm->cur])) {
          LEAVE(VM_EV_START);
        }
        vmbreak;
      }
#ifdef VM_GOTO
      LP_BLOCK: {
        BLOCK_ENTER();
        vmbreak;
      }
      LP_SYNC: vmbreak;
      LP_BLOCKR: {
        BLOCK_ENTER();
        goto blockr;
      }
#endif
      /* a block of SYNC; COMMIT; RET alone: when neither it nor every
       * block is watched, its SYNC, COMMIT and RET at once (verify.c
       * checks that those three follow) */
      vmcase(BLOCKR) {
        BLOCK_ENTER();
        if (watching && (vm->start_all || vm->watch[vm->cur])) {
          LEAVE(VM_EV_START);
        }
        if (yield_all)
          vmbreak;   /* its SYNC yields: the three run one by one */
#ifdef VM_GOTO
      blockr:
#endif
        BLOCK_COMMIT();
        pc += 3;   /* past SYNC, COMMIT, RET: RET's own return, its pc at pc - 1 */
        goto ret;
      }
      vmcase1(CONST) { PUSH(k[INS_A(ins)]); vmbreak; }
      vmcase1(INT) { PUSH((double)INS_A(ins)); vmbreak; }
      vmcase1(REG) { PUSH(vm->reg[INS_A(ins)]); vmbreak; }
      vmcase1(WORD) { PUSH(vm->w[INS_A(ins)]); vmbreak; }
      vmcase1(NEG) { tos = -tos; vmbreak; }
      /* a non-finite result or a zero divisor is always an error: vm_math
       * then says which, exactly as constant folding does */
#define BINARY(L, BASE, OPER, OPERAND) \
      vmcase1(L) { \
        b = (OPERAND); a = tos; r = a OPER b; \
        if (!isfinite(r) || (BASE == OP_DIV && b == 0.0)) { \
          math_at(vm, pc - 1, BASE, a, b, &out); \
          RAISED; \
        } \
        tos = r; \
        vmbreak; \
      }
      BINARY(ADD, OP_ADD, +, POP())
      BINARY(SUB, OP_SUB, -, POP())
      BINARY(MUL, OP_MUL, *, POP())
      BINARY(DIV, OP_DIV, /, POP())
      vmcase1(POW) {
        b = POP(); a = tos;
        if (math_at(vm, pc - 1, OP_POW, a, b, &out)) RAISED;
        tos = out;
        vmbreak;
      }
#define FUNCTION(L) \
      vmcase1(L) { if (math_at(vm, pc - 1, OP_##L, tos, 0, &out)) RAISED; tos = out; vmbreak; }
      /* SIN COS ASIN ACOS ATAN inline, computed as vm_math does (to the
       * bit); outside its domain vm_math says why */
#define TRIG(L, DOMAIN, VALUE) \
      vmcase1(L) { \
        if (!(DOMAIN)) { \
          math_at(vm, pc - 1, OP_##L, tos, 0, &out); \
          RAISED; \
        } \
        tos = (VALUE); \
        vmbreak; \
      }
      TRIG(SIN, fabs(tos) <= trig_max, sin(tos * rad))
      TRIG(COS, fabs(tos) <= trig_max, cos(tos * rad))
      TRIG(ASIN, fabs(tos) <= 1.0, asin(tos) / rad)
      TRIG(ACOS, fabs(tos) <= 1.0, acos(tos) / rad)
      TRIG(ATAN, fabs(tos) <= p->lim.atan_max, atan(tos) / rad)
#undef TRIG
      /* REG; SIN and REG; COS: the register read, then exactly SIN or COS */
#define RTRIG(L, BASE, FN) \
      vmcase1(L) { \
        a = vm->reg[INS_A(ins)]; \
        if (!(fabs(a) <= trig_max)) { \
          math_at(vm, pc - 1, BASE, a, 0, &out); \
          RAISED; \
        } \
        PUSH(FN(a * rad)); \
        vmbreak; \
      }
      RTRIG(RSIN, OP_SIN, sin)
      RTRIG(RCOS, OP_COS, cos)
#undef RTRIG
      /* REG a; SIN; REG a; COS (or COS first): one domain test (the two
       * share it, so the first part is the one that would raise), one
       * sincos, which gives sin's and cos's results to the bit (glibc
       * computes the three alike; the unit tests compare them) */
#define RSINCOS(L, BASE, FIRST, SECOND) \
      vmcase1(L) { \
        double s_, c_; \
        a = vm->reg[INS_A(ins)]; \
        if (!(fabs(a) <= trig_max)) { \
          math_at(vm, pc - 1, BASE, a, 0, &out); \
          RAISED; \
        } \
        sincos(a * rad, &s_, &c_); \
        PUSH(FIRST); \
        PUSH(SECOND); \
        vmbreak; \
      }
      RSINCOS(RSINCOS, OP_SIN, s_, c_)
      RSINCOS(RCOSSIN, OP_COS, c_, s_)
#undef RSINCOS
      /* SIN; SETP and the like: the function exactly, then SETP exactly
       * (its error at the EXT word's column) */
#define TRIGP(L, BASE, DOMAIN, VALUE) \
      vmcase1(L) { \
        if (!(DOMAIN)) { \
          math_at(vm, pc - 1, BASE, tos, 0, &out); \
          RAISED; \
        } \
        r = (VALUE); \
        uint32_t d = INS_A(code[pc]); \
        if (!(r >= param_lo && r <= param_hi)) { \
          param_fail(vm, pc, d, r); \
          RAISED; \
        } \
        tos = st[--sp]; \
        journal(vm, d); \
        vm->reg[d] = r; \
        pc++; \
        vmbreak; \
      }
      TRIGP(SINP, OP_SIN, fabs(tos) <= trig_max, sin(tos * rad))
      TRIGP(COSP, OP_COS, fabs(tos) <= trig_max, cos(tos * rad))
      TRIGP(ASINP, OP_ASIN, fabs(tos) <= 1.0, asin(tos) / rad)
      TRIGP(ACOSP, OP_ACOS, fabs(tos) <= 1.0, acos(tos) / rad)
      TRIGP(ATANP, OP_ATAN, fabs(tos) <= p->lim.atan_max, atan(tos) / rad)
#undef TRIGP
      FUNCTION(TAN)
      FUNCTION(LOG)
#undef FUNCTION
      vmcase1(SET) {
        if (do_set(vm, pc - 1, INS_A(ins), POP())) RAISED;
        vmbreak;
      }
      vmcase1(ARD) {
        int i;
        save_array(vm, INS_A(ins) & 3);
        if (arr_pos(vm, pc - 1, INS_A(ins), &i)) RAISED;
        PUSH(vm->arr[INS_A(ins) & 3].cell[i]);
        vmbreak;
      }
      vmcase1(AWR) {
        int i;
        char bv[32], b1[32], b2[32];
        a = POP();
        if (!(a >= p->lim.cell_lo && a <= p->lim.cell_hi)) {
          raise_msg(vm, pc - 1, S42_E_RANGE, VMSG_CELL, (INS_A(ins) & 3) + 1, num(bv, sizeof bv, a),
                    num(b1, sizeof b1, p->lim.cell_lo), num(b2, sizeof b2, p->lim.cell_hi));
          RAISED;
        }
        save_array(vm, INS_A(ins) & 3);
        if (arr_pos(vm, pc - 1, INS_A(ins), &i)) RAISED;
        struct vm_array *ar = &vm->arr[INS_A(ins) & 3];
        ar->cell[i] = a;
        if (ar->len < i + 1)
          ar->len = i + 1;
        vmbreak;
      }
      vmcase1(AZERO) {
        save_arrays(vm, INS_A(ins));
        for (uint32_t n = 0; n < p->lim.arrays; n++)
          if (INS_A(ins) & (1u << n))
            memset(&vm->arr[n], 0, used_bytes(vm));
        vmbreak;
      }
      vmcase1(APTR0) {
        save_arrays(vm, INS_A(ins));
        for (uint32_t n = 0; n < p->lim.arrays; n++)
          if (INS_A(ins) & (1u << n))
            vm->arr[n].ptr = 0;
        vmbreak;
      }
      vmcase1(APTREND) {
        save_arrays(vm, INS_A(ins));
        for (uint32_t n = 0; n < p->lim.arrays; n++)
          if (INS_A(ins) & (1u << n))
            vm->arr[n].ptr = vm->arr[n].len;
        vmbreak;
      }
      vmcase1(CMP) {
        b = POP(); a = tos;
        tos = vm_rel(a, b, INS_A(ins)) ? 1.0 : 0.0;
        vmbreak;
      }
      vmcase1(AND) { b = POP(); tos = (tos != 0.0 && b != 0.0); vmbreak; }
      vmcase1(OR) { b = POP(); tos = (tos != 0.0 || b != 0.0); vmbreak; }
      vmcase1(COND) { jflag = POP() != 0.0; vmbreak; }
      vmcase1(MACH) {
        LEAVE(VM_EV_BLOCK);
      }
      vmcase1(MACHS) {
        uint32_t sw = INS_A(ins);
        if (!yield_all && (vm->sw & ((sw & 0xfffu) | VM_SW_HELD)) == ((sw >> 12) | VM_SW_HELD))
          vmbreak;   /* the switches stand so already: nothing for the host */
        LEAVE(VM_EV_BLOCK);
      }
      vmcase(SYNC) {   /* the plain table's SYNC is above, after BLOCK */
        if (yield_all) {
          LEAVE(VM_EV_BLOCK);
        }
        vmbreak;
      }
      vmcase1(TRUNC) {
        vm->reg[INS_A(ins)] = trunc(vm->reg[INS_A(ins)]);
        vmbreak;
      }
      vmcase1(COMMIT) {
        BLOCK_COMMIT();
        vmbreak;
      }
      vmcase1(CCALL) {   /* COMMIT, then CALL once */
        BLOCK_COMMIT();
        times = 1;
        goto call;
      }
      vmcase1(CALL) {
        times = (uint32_t)POP();
        if (times == 0)
          vmbreak;
      call:
        if (depth >= depth_max) {
          raise_msg(vm, pc - 1, S42_E_NEST, VMSG_NEST, (int)depth + 1, (int)depth_max);
          RAISED;
        }
        struct vm_frame *f = &vm->frames[depth++];
        f->ret = pc;
        f->start = blk[INS_A(ins)].code;
        f->left = times - 1;
        f->block = vm->cur;
        f->saved = *saved;
        f->jflag = jflag;
        pc = f->start;
        vmbreak;
      }
      vmcase1(PPJ) {
        if (vm->exit_latch) {
          vm->exit_latch = 0;
          vm->pp_jumps++;
          pc = blk[INS_A(ins)].code;
        }
        vmbreak;
      }
      vmcase1(JMP) { pc = blk[INS_A(ins)].code; vmbreak; }
      vmcase1(JCOND) {
        if (jflag)
          pc = blk[INS_A(ins)].code;
        vmbreak;
      }
      vmcase1(RET) {
      ret:   /* BLOCKR's RET and RETEND in a called sub come here: the same return */
        if (depth == 0) {
          raise_msg(vm, pc - 1, S42_E_SUB, VMSG_RETMAIN);
          RAISED;
        }
        struct vm_frame *f = &vm->frames[depth - 1];
        *saved = f->saved;
        if (f->left > 0) {
          f->left--;
          pc = f->start;
        } else {
          depth--;
          jflag = f->jflag;
          pc = f->ret;
          /* the calling block's jump, when one follows the call (L10
           * P(...)2): taken here, exactly as JCOND takes it, a dispatch
           * sooner */
          ins = code[pc];
          if (INS_OP(ins) == OP_JCOND)
            pc = jflag ? blk[INS_A(ins)].code : pc + 1;
        }
        vmbreak;
      }
      vmcase1(END) {
        vm->exit_latch = 0;
        vm->done = 1;
        LEAVE(VM_EV_END);
      }
      /* return when called, end otherwise (Bosch M2, FMS-3000 M99) */
      vmcase1(RETEND) {
        if (depth > 0)
          goto ret;
        vm->exit_latch = 0;
        vm->done = 1;
        LEAVE(VM_EV_END);
      }
      /* superinstructions: exactly what their two instructions did */
      BINARY(ADDI, OP_ADD, +, (double)INS_A(ins))
      BINARY(SUBI, OP_SUB, -, (double)INS_A(ins))
      BINARY(MULI, OP_MUL, *, (double)INS_A(ins))
      BINARY(DIVI, OP_DIV, /, (double)INS_A(ins))
      BINARY(ADDK, OP_ADD, +, k[INS_A(ins)])
      BINARY(SUBK, OP_SUB, -, k[INS_A(ins)])
      BINARY(MULK, OP_MUL, *, k[INS_A(ins)])
      BINARY(DIVK, OP_DIV, /, k[INS_A(ins)])
      BINARY(ADDR, OP_ADD, +, vm->reg[INS_A(ins)])
      BINARY(SUBR, OP_SUB, -, vm->reg[INS_A(ins)])
      BINARY(MULR, OP_MUL, *, vm->reg[INS_A(ins)])
      BINARY(DIVR, OP_DIV, /, vm->reg[INS_A(ins)])
#undef BINARY
      vmcase1(SETP) {
        a = POP();
        if (!(a >= param_lo && a <= param_hi)) {
          char b1[32], b2[32], b3[32];
          raise_msg(vm, pc - 1, S42_E_RANGE, VMSG_PARAM, INS_A(ins), num(b1, sizeof b1, a),
                    num(b2, sizeof b2, param_lo), num(b3, sizeof b3, param_hi));
          RAISED;
        }
        journal(vm, INS_A(ins));
        vm->reg[INS_A(ins)] = a;
        vmbreak;
      }
      vmcase1(CMPC) {
        b = POP(); a = POP();
        jflag = (uint8_t)vm_rel(a, b, INS_A(ins));
        vmbreak;
      }
      vmcase1(CMPCK) {
        a = POP();
        jflag = (uint8_t)vm_rel(a, k[INS_A(ins) >> 3], INS_A(ins) & 7);
        vmbreak;
      }
      vmcase1(CMPCR) {
        a = POP();
        jflag = (uint8_t)vm_rel(a, vm->reg[INS_A(ins) >> 3], INS_A(ins) & 7);
        vmbreak;
      }
      vmcase1(CJMP) {
        BLOCK_COMMIT();
        pc = blk[INS_A(ins)].code;
        vmbreak;
      }
      vmcase1(CJCOND) {
        BLOCK_COMMIT();
        if (jflag)
          pc = blk[INS_A(ins)].code;
        vmbreak;
      }
      /* Register forms (src/dialect/2c42/peep.c): exactly what their two or
       * three instructions did, each error at the pc -- so the column -- of
       * the part that raised it: the arithmetic at the instruction's own,
       * the store at its EXT word's.  A result inside plo..phi is finite, so
       * one test stands for the arithmetic's check and SETP's. */
      vmcase1(EXT) vmbreak;   /* never reached: the instruction before it steps over it */
#define RPUSH(L, BASE, OPER, OPERAND) \
      vmcase1(L) { \
        a = vm->reg[INS_A(ins) & 127]; b = (OPERAND); r = a OPER b; \
        if (!isfinite(r) || (BASE == OP_DIV && b == 0.0)) { \
          math_at(vm, pc - 1, BASE, a, b, &out); \
          RAISED; \
        } \
        PUSH(r); \
        vmbreak; \
      }
#define STOREP(L, BASE, OPER, LEFT, RIGHT) \
      vmcase1(L) { \
        RIGHT; LEFT; r = a OPER b; \
        uint32_t d = INS_A(code[pc]); \
        if (!(r >= plo && r <= phi)) { \
          if (!isfinite(r)) \
            math_at(vm, pc - 1, BASE, a, b, &out); \
          else \
            param_fail(vm, pc, d, r); \
          RAISED; \
        } \
        journal(vm, d); \
        vm->reg[d] = r; \
        pc++; \
        vmbreak; \
      }
#define RFORMS(OP, OPER) \
      RPUSH(R##OP##I, OP_##OP, OPER, (double)(INS_A(ins) >> 7)) \
      RPUSH(R##OP##K, OP_##OP, OPER, k[INS_A(ins) >> 7]) \
      RPUSH(R##OP##R, OP_##OP, OPER, vm->reg[INS_A(ins) >> 7]) \
      STOREP(OP##P, OP_##OP, OPER, a = POP(), b = POP()) \
      STOREP(OP##IP, OP_##OP, OPER, a = POP(), b = (double)INS_A(ins)) \
      STOREP(OP##KP, OP_##OP, OPER, a = POP(), b = k[INS_A(ins)]) \
      STOREP(OP##RP, OP_##OP, OPER, a = POP(), b = vm->reg[INS_A(ins)]) \
      STOREP(R##OP##IP, OP_##OP, OPER, a = vm->reg[INS_A(ins) & 127], b = (double)(INS_A(ins) >> 7)) \
      STOREP(R##OP##KP, OP_##OP, OPER, a = vm->reg[INS_A(ins) & 127], b = k[INS_A(ins) >> 7]) \
      STOREP(R##OP##RP, OP_##OP, OPER, a = vm->reg[INS_A(ins) & 127], b = vm->reg[INS_A(ins) >> 7])
      RFORMS(ADD, +)
      RFORMS(SUB, -)
      RFORMS(MUL, *)
      RFORMS(DIV, /)
#undef RFORMS
#undef STOREP
#undef RPUSH
      /* a register against a constant: plainly below or above its bounds
       * (vm_rel_bounds), the relation is < or >; near it, or an infinite
       * register, the tolerant compare decides */
      vmcase1(CMPRK) {
        double x = vm->reg[INS_A(ins) >> 3];
        const double *kb = &k[INS_A(code[pc])];
        unsigned got;
        if (x < kb[1] && x > -HUGE_VAL)
          got = 1;
        else if (x > kb[2] && x < HUGE_VAL)
          got = 4;
        else
          got = vm_rel_got(x, kb[0]);
        jflag = (INS_A(ins) & got) != 0;
        pc++;
        vmbreak;
      }
    }
#if !(defined(__GNUC__) && !defined(S42_SWITCH_DISPATCH))
  }
#endif
fail:
  LEAVE(VM_EV_ERROR);
}
