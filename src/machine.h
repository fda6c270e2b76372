/* The simulated ВЗ-208Ф3: positions of X, Y, Z, A in discretes, simulated
 * time, the wheel, oscillation, the feed override and the contour-speed
 * limits of language.md section 16.  It knows nothing of bytecode: the
 * session hands it one block's meaning (struct mach_block) at a time. */
#ifndef S42_MACHINE_H
#define S42_MACHINE_H

#include <stddef.h>
#include <stdint.h>

enum { AX_X, AX_Y, AX_Z, AX_A };
enum { WHEEL_OFF, WHEEL_CW, WHEEL_CCW };

#define MACH_AXIS_MAX 6000.0          /* mm/min (deg/min for A) */
#define MACH_Y_MAX (6000.0 / 36.0)
#define MACH_WHEEL_RUNDOWN 3.0        /* s, the wheel's run-down after M5 */

struct mach_block {
  int motion;          /* enum motion (src/kp.h) */
  int plane;           /* 0, 17, 18, 19 */
  uint64_t g;
  uint32_t m;
  uint16_t given;      /* word slots given (src/ast.h SL_*) */
  double w[16];        /* their values, rounded as the language says */
  double f;            /* contour speed in force for this block */
  double d1;
};

struct mach_out {
  int64_t d[4];        /* contour increments made */
  double feed;         /* effective contour speed, mm/min */
  double v;            /* surface speed with A (when has_v) */
  int has_v;
  char warn[160];      /* a warning to show (clamped oscillation speed) */
};

struct mach_osc {
  int defined, active, axis;
  double stroke;       /* discretes, signed: the first direction */
  double speed;        /* mm/min (deg/min) after clamping */
  double travel;       /* discretes travelled since it started */
  int64_t base;        /* the axis position where it started */
};

struct machine {
  int64_t pos[4];      /* relative to the start, discretes */
  double t;            /* simulated seconds */
  int wheel;
  int override_pct;    /* feed override switch, 0..150 */
  int override_allowed;/* M26 (default) / M25 */
  int corr_allowed;    /* M22 / M23 (default) */
  int64_t corr[4];     /* corrections since the last mark (G20, M19, dialog, PP) */
  struct mach_osc osc;
};

void mach_init(struct machine *m);
/* Check a block against the machine's state; nothing changes.  Returns 0 or
 * an error code (vm/errors.h) with the message in msg. */
int mach_check(const struct machine *m, const struct mach_block *b, char *msg, size_t n);
/* Carry the block out (it passed mach_check): modal changes, the motion or
 * dwell, then M14 and M2's end of oscillation. */
void mach_exec(struct machine *m, const struct mach_block *b, struct mach_out *o);
/* Is the block's contour move held by a feed override of 0 %? */
int mach_held(const struct machine *m, const struct mach_block *b);
/* Effective speed of a linear move (increments in discretes) at speed f. */
double mach_linear_limit(const double d[4]);
/* Arc of a G02/G03 block: length in mm, the largest Y share of the tangent
 * along it (0..1).  Returns 0, or an error code with a message. */
int mach_arc(const struct mach_block *b, double *len_mm, double *yshare, char *msg, size_t n);
/* Move an axis by hand (jog, correction); counts in the position. */
void mach_jog(struct machine *m, int axis, int64_t d, int correction);
/* Advance simulated time by dt seconds (oscillation runs meanwhile). */
void mach_advance(struct machine *m, double dt);
/* The oscillating axis's current offset from where it started. */
int64_t mach_osc_offset(const struct machine *m);

#endif
