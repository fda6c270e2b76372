/* What a compiled 2У22 block means to the lathe: the front end's per-block
 * record (program.ext, indexed like program.blocks), read by the runtime
 * (runtime.c) when the VM yields the block (VM_EV_BLOCK).  The VM never
 * reads it.
 *
 * The bytecode of a block: BLOCK; the R assignments left to right (SETP
 * into registers 0..9); each other word's value into its slot (SET with the
 * word's range rule: E-RANGE); MACH (every block yields: the runtime does
 * its machine work and its row); COMMIT; then the block's structure -- an
 * L call (CALL, the count rr), an H repeat's counter and M20's jump back,
 * M17 (RET), M02/M30 (END).  Registers: R0..R9 are the parameters (10, 11:
 * the H counters of the main program's two levels; a sub with an H repeat
 * has a pair of its own from 12 up, so that a sub called inside a repeat
 * cannot disturb its caller's count: u22_attr.hreg); nothing is saved
 * across calls. */
#ifndef S42_U22_H
#define S42_U22_H

#include "program.h"
#include <stdint.h>

/* Word slots (vm.w[]): the value as written, an integer in the word's unit
 * (X Z I K: 0.01 mm, X and I as a diameter -- K and I under G33: µm; F as
 * written; S rpm or m/min; T the tool; E 0.1 s). */
enum u22_slot { U22_X, U22_Z, U22_I, U22_K, U22_F, U22_S, U22_T, U22_E, U22_NSLOT };

/* The G and M functions of Tables 1.2 and 1.3 as bit indices. */
enum u22_g { UG01, UG02, UG03, UG04, UG09, UG20, UG21, UG23, UG25, UG33, UG90, UG91, UG94, UG95, UG96, UG97, UG_N };
enum u22_m { UM00, UM01, UM02, UM03, UM04, UM05, UM08, UM09, UM17, UM20, UM30, UM38, UM39, UM_N };

#define U22_REG_H0 10      /* the H counter of repeat level 1; level 2 is 11 */

struct u22_attr {
  uint16_t g;        /* bit UGnn: the block has Gnn */
  uint16_t m;        /* bit UMnn: the block has Mnn */
  uint16_t words;    /* bit U22_x: the word is given; its value is vm.w[U22_x] at VM_EV_BLOCK */
  uint8_t skip;      /* written with '/': passed over while block skip (U/) is on */
  uint8_t home;      /* G25: bit LX (1) X named, bit LZ (2) Z named */
  uint8_t sub;       /* L ss: the sub it calls after its own words (0 none) */
  uint8_t runs;      /* L ss rr: rr (1 when written L ss) */
  uint16_t h;        /* H n given: 1 + n (0: no H) */
  uint8_t hreg;      /* H or M20: the register of that repeat's counter (0: neither) */
};

struct u22_ext {
  struct u22_attr *a;            /* one per program block */
  size_t n, cap;
  double unit;                   /* mm per count of X Z I K: 0.01 (--resolution 0.001: 0.001) */
};

static inline const struct u22_attr *u22_attr(const struct program *p, size_t b)
{
  return &((const struct u22_ext *)p->ext)->a[b];
}

/* The 2У22's names of its functions: "G01", "M38" (tables, words.c). */
extern const int u22_g_number[UG_N];
extern const int u22_m_number[UM_N];

/* The runtime on the neutral runner (runtime.c, src/core/mrun.h). */
struct mrun_rt;
extern const struct mrun_rt u22_runtime;

#endif
