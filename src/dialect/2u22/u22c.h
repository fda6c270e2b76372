/* The 2У22 front end's own declarations (the runtime needs only u22.h):
 * the compiler and the message table.  Named u22c.h, not compile.h: the
 * 2С42's compile.h is on the include path of the tests and the fuzzers. */
#ifndef S42_U22C_H
#define S42_U22C_H

#include "diag.h"
#include "msgs.h"
#include "program.h"
#include <stddef.h>

/* Compile a 2У22 program (spec/dialects/2u22.md) into p, diagnostics in d:
 * 0 when it can run, -1 when it has errors (d->oom: out of memory). */
int u22_compile(const char *src, size_t n, struct diag_list *d, struct program *p);

/* What the 2У22 says for the VM's errors (vm/msgs.h), Ukrainian and English. */
extern const struct vm_msgs u22_msgs;

/* The digits Table 1.1 allows after each address (G33's I and K: 5). */
enum { U22_DIG_XZIK = 7, U22_DIG_IK33 = 5, U22_DIG_F = 5, U22_DIG_S = 4, U22_DIG_T = 3, U22_DIG_E = 7,
       U22_DIG_N = 5, U22_DIG_G = 2, U22_DIG_M = 2, U22_DIG_H = 4, U22_DIG_R = 7 };

/* The longest block: 80 characters without the end mark, comments and
 * spaces (L502, D-2, D-26). */
#define U22_BLOCK_MAX 80

#endif
