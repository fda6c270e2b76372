/* Arithmetic and functions of the VM (vm/vmmath.h). */
#include "vmmath.h"
#include "errors.h"
#include "opcodes.h"
#include <math.h>
#include <stdio.h>

static const char *num(char *buf, size_t n, double v)
{
  snprintf(buf, n, "%.10g", v);
  return buf;
}

static const char *fname(int op)
{
  switch (op) {
  case OP_SIN: return "SI";
  case OP_COS: return "CO";
  case OP_TAN: return "TG";
  case OP_ASIN: return "ASI";
  case OP_ACOS: return "ACO";
  case OP_ATAN: return "ATG";
  case OP_LOG: return "LO";
  default: return vm_ops[op].name;
  }
}

static int fn1(int op, double x, double *out, char *msg, size_t n)
{
  const double deg = M_PI / 180000.0;   /* 0.001 deg to radians, exact pi */
  char b[32];
  switch (op) {
  case OP_SIN: case OP_COS: case OP_TAN:
    if (!(fabs(x) <= 2304000.0)) {
      snprintf(msg, n, "%s(%s): argument outside -2304000..2304000", fname(op), num(b, sizeof b, x));
      return S42_E_DOMAIN;
    }
    if (op == OP_SIN) {
      *out = sin(x * deg);
    } else if (op == OP_COS) {
      *out = cos(x * deg);
    } else {
      double q = x / 90000.0;
      if (q == floor(q) && fmod(fabs(q), 2.0) == 1.0) {
        snprintf(msg, n, "TG(%s): tangent of an odd multiple of 90 degrees", num(b, sizeof b, x));
        return S42_E_DOMAIN;
      }
      *out = tan(x * deg);
    }
    return 0;
  case OP_ASIN: case OP_ACOS:
    if (!(fabs(x) <= 1.0)) {
      snprintf(msg, n, "%s(%s): argument outside -1..1", fname(op), num(b, sizeof b, x));
      return S42_E_DOMAIN;
    }
    *out = (op == OP_ASIN ? asin(x) : acos(x)) / deg;
    return 0;
  case OP_ATAN:
    if (!(fabs(x) <= 9999999.0)) {
      snprintf(msg, n, "ATG(%s): argument outside -9999999..9999999", num(b, sizeof b, x));
      return S42_E_DOMAIN;
    }
    *out = atan(x) / deg;
    return 0;
  default: /* OP_LOG */
    if (!(x > 0.0 && x <= 9999999.0)) {
      snprintf(msg, n, "LO(%s): argument outside 0 (excluded)..9999999", num(b, sizeof b, x));
      return S42_E_DOMAIN;
    }
    *out = log(x);
    return 0;
  }
}

static int arith(int op, double a, double b, double *out, char *msg, size_t n)
{
  char b1[32], b2[32];
  double r;
  switch (op) {
  case OP_ADD: r = a + b; break;
  case OP_SUB: r = a - b; break;
  case OP_MUL: r = a * b; break;
  case OP_DIV:
    if (b == 0.0) {
      snprintf(msg, n, "division of %s by zero", num(b1, sizeof b1, a));
      return S42_E_DIV0;
    }
    r = a / b;
    break;
  default: /* OP_POW */
    if (a < 0.0 && b != floor(b)) {
      snprintf(msg, n, "power: negative base %s with the fractional exponent %s",
               num(b1, sizeof b1, a), num(b2, sizeof b2, b));
      return S42_E_DOMAIN;
    }
    if (a == 0.0 && b < 0.0) {
      snprintf(msg, n, "power: zero to the negative exponent %s", num(b2, sizeof b2, b));
      return S42_E_DIV0;
    }
    r = pow(a, b);
    break;
  }
  if (!isfinite(r)) {
    snprintf(msg, n, "intermediate result too large (%s %s %s)", num(b1, sizeof b1, a),
             fname(op), num(b2, sizeof b2, b));
    return S42_E_RANGE;
  }
  *out = r;
  return 0;
}

int vm_math(int op, double a, double b, double *out, char *msg, size_t n)
{
  switch (op) {
  case OP_NEG: *out = -a; return 0;
  case OP_ADD: case OP_SUB: case OP_MUL: case OP_DIV: case OP_POW:
    return arith(op, a, b, out, msg, n);
  default:
    return fn1(op, a, out, msg, n);
  }
}
