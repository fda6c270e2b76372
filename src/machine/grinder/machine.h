/* The simulated ВЗ-208Ф3: positions of X, Y, Z, A in discretes, simulated
 * time, the wheel, the feed override and the contour-speed limits of
 * language.md section 16.  It knows nothing of bytecode or plugins: the
 * session hands it one block's meaning (struct mach_block) at a time, and
 * hears of passing time through the tick hook (oscillation runs there). */
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
  int motion;          /* enum motion (src/dialect/2c42/kp.h) */
  int plane;           /* 0, 17, 18, 19 */
  uint64_t g;
  uint32_t m;
  uint16_t given;      /* word slots given (src/dialect/2c42/ast.h SL_*) */
  double w[16];        /* their values, rounded as the language says */
  double f;            /* contour speed in force for this block */
  double d1;
};

struct mach_out {
  int64_t d[4];        /* contour increments made */
  double feed;         /* effective contour speed, mm/min */
  double v;            /* surface speed with A (when has_v) */
  int has_v;
};

/* The travel of each axis (--machine FILE), discretes relative to the
 * program's start position; an axis without `has` is unlimited. */
struct mach_travel {
  uint8_t has[4];
  int64_t lo[4], hi[4];
};

struct machine {
  int64_t pos[4];      /* relative to the start, discretes */
  struct mach_travel travel;   /* none by default: the seed gives none */
  double t;            /* simulated seconds */
  int wheel;
  int override_pct;    /* feed override switch, 0..150 */
  int override_allowed;/* M26 (default) / M25 */
  int corr_allowed;    /* M22 / M23 (default) */
  int64_t corr[4];     /* corrections since the last mark (G20, M19, dialog, PP) */
  /* the last contour move (mach_move), for an override turned within it */
  struct {
    int on;            /* it took the override (M26) */
    double len;        /* mm */
    double limit, f;   /* its speed limit, its programmed speed, mm/min */
    double feed;       /* the speed it goes at now, mm/min */
    double t0, t1;     /* simulated seconds: its start, its end */
  } mv;
  /* called whenever simulated time passes, with the seconds */
  void (*tick)(void *ctx, double dt);
  void *tick_ctx;
};

void mach_init(struct machine *m);
/* Check a block against the machine's state; nothing changes.  Returns 0 or
 * an error code (vm/errors.h) with the message in msg. */
int mach_check(const struct machine *m, const struct mach_block *b, char *msg, size_t n);
/* Carry the block out (it passed mach_check), in two steps: the modal
 * changes (the wheel first, M22/M23, M25/M26), then the core's motion or
 * dwell (G01 G02 G03 G04 G37). */
void mach_modal(struct machine *m, const struct mach_block *b);
void mach_motion(struct machine *m, const struct mach_block *b, struct mach_out *o);
/* A contour move a plugin computed: increments d (discretes), its length
 * (mm) and speed limit (mm/min); F and the override apply as for G01. */
void mach_move(struct machine *m, const double d[4], double len, double limit, double f, struct mach_out *o);
/* The override switch was turned (m->override_pct is the new position)
 * at simulated time `now`, within the last contour move: the rest of it
 * goes at the new speed.  The move's end and the machine's time move by
 * the difference, which is returned (seconds; 0 when `now` is not within a
 * move that takes the override).  At 0 % nothing changes: the host holds
 * the move (its clock stops) and calls this again when the switch leaves 0. */
double mach_override_at(struct machine *m, double now);
/* Would a feed override of 0 % hold this block's contour move (the caller
 * knows whether the block is one: the core's G01-G03 or a plugin's)? */
int mach_held(const struct machine *m, const struct mach_block *b);
/* Effective speed of a linear move (increments in discretes) at speed f. */
double mach_linear_limit(const double d[4]);
/* Arc of a G02/G03 block: length in mm, the largest Y share of the tangent
 * along it (0..1).  Returns 0, or an error code with a message. */
int mach_arc(const struct mach_block *b, double *len_mm, double *yshare, char *msg, size_t n);
/* Move an axis by hand (jog, correction); counts in the position.  The
 * axis stops at its travel limit: returns the move made (d, or less). */
int64_t mach_jog(struct machine *m, int axis, int64_t d, int correction);
/* Would these moves of the axes, from where they are, stay in their travel? */
int mach_in_travel(const struct machine *m, const int64_t d[4]);
/* Advance simulated time by dt seconds (the tick hook runs). */
void mach_advance(struct machine *m, double dt);
/* The maximum speed of an axis, mm/min (deg/min). */
double mach_axis_max(int axis);

#endif
