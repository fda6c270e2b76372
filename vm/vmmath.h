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

/* Relation mask (1 <, 2 =, 4 >) holds between a and b, equal within 1e-9.
 * Inline: the VM's conditional jumps run it at every pass of a loop. */
static inline int vm_rel(double a, double b, unsigned mask)
{
  double m = fabs(a) > fabs(b) ? fabs(a) : fabs(b);
  if (m < 1.0)
    m = 1.0;
  unsigned got = fabs(a - b) <= 1e-9 * m ? 2u : (a < b ? 1u : 4u);
  return (mask & got) != 0;
}

#endif
