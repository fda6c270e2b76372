/* Arithmetic and functions of the VM, shared with the compiler's constant
 * folding so that `s42 check` and a run agree to the bit: both take the
 * angle unit, the functions' domains and the message texts from the
 * program (program.lim, program.msgs). */
#ifndef S42_VMMATH_H
#define S42_VMMATH_H

#include "program.h"
#include <math.h>
#include <stddef.h>

/* Apply binary or unary opcode `op` (vm/opcodes.h) to a (and b) under p's
 * limits.  Returns 0 and sets *out, or an error code (vm/errors.h) with
 * p's message in msg. */
int vm_math(const struct program *p, int op, double a, double b, double *out, char *msg, size_t n);

/* Which relation holds between a and b: 1 <, 2 = (equal within 1e-9 of
 * the larger magnitude, at least 1), 4 >. */
static inline unsigned vm_rel_got(double a, double b)
{
  double m = fabs(a) > fabs(b) ? fabs(a) : fabs(b);
  if (m < 1.0)
    m = 1.0;
  return fabs(a - b) <= 1e-9 * m ? 2u : (a < b ? 1u : 4u);
}

/* Relation mask (1 <, 2 =, 4 >) holds between a and b.  Inline: the VM's
 * conditional jumps run it at every pass of a loop. */
static inline int vm_rel(double a, double b, unsigned mask)
{
  return (mask & vm_rel_got(a, b)) != 0;
}

/* Bounds for a constant b (finite): every finite a < *lo has
 * vm_rel_got(a, b) == 1, every finite a > *hi has 4 -- four tolerances away,
 * twice what the tolerance can grow to with |a| up to 2 max(|b|, 1), and
 * beyond that |a - b| > |a| / 2 dwarfs 1e-9 |a|.  (Near +-DBL_MAX a bound
 * overflows to an infinity, past which no finite a lies.  An infinite a is
 * "equal" to every b: vm_rel_got's tolerance is infinite too; the fast
 * path leaves it to vm_rel_got.)  CMPRK carries them with b (K[j+1],
 * K[j+2]); the verifier recomputes them. */
static inline void vm_rel_bounds(double b, double *lo, double *hi)
{
  double t = 4e-9 * (fabs(b) > 1.0 ? fabs(b) : 1.0);
  *lo = b - t;
  *hi = b + t;
}

#endif
