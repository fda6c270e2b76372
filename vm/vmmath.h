/* Arithmetic and functions of the VM, shared with the compiler's constant
 * folding so that `s42 check` and a run agree to the bit. */
#ifndef S42_VMMATH_H
#define S42_VMMATH_H

#include <stddef.h>

/* Apply binary or unary opcode `op` (vm/opcodes.h) to a (and b).  Returns 0
 * and sets *out, or an error code (vm/errors.h) with a message in msg. */
int vm_math(int op, double a, double b, double *out, char *msg, size_t n);
/* Relation mask (1 <, 2 =, 4 >) holds between a and b, equal within 1e-9. */
int vm_rel(double a, double b, unsigned mask);

#endif
