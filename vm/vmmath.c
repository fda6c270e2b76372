/* Arithmetic and functions of the VM (vm/vmmath.h). */
#include "vmmath.h"
#include "errors.h"
#include "msgs.h"
#include "opcodes.h"
#include <math.h>
#include <stdio.h>

static const char *num(char *buf, size_t n, double v)
{
  snprintf(buf, n, "%.10g", v);
  return buf;
}

/* x outside -max..max: the function's message with the domain's ends. */
static int outside(const struct program *p, enum vm_detail id, double x, double max, char *msg, size_t n)
{
  char b[32], lo[32], hi[32];
  vm_msg_format(msg, n, p->msgs, id, num(b, sizeof b, x), num(lo, sizeof lo, -max), num(hi, sizeof hi, max));
  return S42_E_DOMAIN;
}

static int fn1(const struct program *p, int op, double x, double *out, char *msg, size_t n)
{
  /* units in a half turn (180000 for 0.001 deg: 180/0.001 is exactly that
   * double), and one unit in radians with the exact pi */
  const double half = 180.0 / p->lim.angle, rad = M_PI / half;
  char b[32], hi[32];
  switch (op) {
  case OP_SIN: case OP_COS: case OP_TAN:
    if (!(fabs(x) <= p->lim.trig_max))
      return outside(p, op == OP_SIN ? VMSG_SIN : op == OP_COS ? VMSG_COS : VMSG_TAN, x, p->lim.trig_max, msg, n);
    if (op == OP_SIN) {
      *out = sin(x * rad);
    } else if (op == OP_COS) {
      *out = cos(x * rad);
    } else {
      double q = x / (half / 2);
      if (q == floor(q) && fmod(fabs(q), 2.0) == 1.0) {
        vm_msg_format(msg, n, p->msgs, VMSG_TANPOLE, num(b, sizeof b, x));
        return S42_E_DOMAIN;
      }
      *out = tan(x * rad);
    }
    return 0;
  case OP_ASIN: case OP_ACOS:
    if (!(fabs(x) <= 1.0)) {
      vm_msg_format(msg, n, p->msgs, op == OP_ASIN ? VMSG_ASIN : VMSG_ACOS, num(b, sizeof b, x));
      return S42_E_DOMAIN;
    }
    *out = (op == OP_ASIN ? asin(x) : acos(x)) / rad;
    return 0;
  case OP_ATAN:
    if (!(fabs(x) <= p->lim.atan_max))
      return outside(p, VMSG_ATAN, x, p->lim.atan_max, msg, n);
    *out = atan(x) / rad;
    return 0;
  default: /* OP_LOG */
    if (!(x > 0.0 && x <= p->lim.log_max)) {
      vm_msg_format(msg, n, p->msgs, VMSG_LOG, num(b, sizeof b, x), num(hi, sizeof hi, p->lim.log_max));
      return S42_E_DOMAIN;
    }
    *out = log(x);
    return 0;
  }
}

static int arith(const struct program *p, int op, double a, double b, double *out, char *msg, size_t n)
{
  char b1[32], b2[32];
  double r;
  switch (op) {
  case OP_ADD: r = a + b; break;
  case OP_SUB: r = a - b; break;
  case OP_MUL: r = a * b; break;
  case OP_DIV:
    if (b == 0.0) {
      vm_msg_format(msg, n, p->msgs, VMSG_DIV0, num(b1, sizeof b1, a));
      return S42_E_DIV0;
    }
    r = a / b;
    break;
  default: /* OP_POW */
    if (a < 0.0 && b != floor(b)) {
      vm_msg_format(msg, n, p->msgs, VMSG_POWNEG, num(b1, sizeof b1, a), num(b2, sizeof b2, b));
      return S42_E_DOMAIN;
    }
    if (a == 0.0 && b < 0.0) {
      vm_msg_format(msg, n, p->msgs, VMSG_POWZERO, num(b2, sizeof b2, b));
      return S42_E_DIV0;
    }
    r = pow(a, b);
    break;
  }
  if (!isfinite(r)) {
    vm_msg_format(msg, n, p->msgs, VMSG_OVERFLOW, num(b1, sizeof b1, a), vm_ops[op].name, num(b2, sizeof b2, b));
    return S42_E_RANGE;
  }
  *out = r;
  return 0;
}

int vm_math(const struct program *p, int op, double a, double b, double *out, char *msg, size_t n)
{
  switch (op) {
  case OP_NEG: *out = -a; return 0;
  case OP_ADD: case OP_SUB: case OP_MUL: case OP_DIV: case OP_POW:
    return arith(p, op, a, b, out, msg, n);
  default:
    return fn1(p, op, a, out, msg, n);
  }
}
