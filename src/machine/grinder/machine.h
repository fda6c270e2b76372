/* The simulated ВЗ-208Ф3: positions of X, Y, Z, A in discretes, simulated
 * time, the wheel, the feed override, the contour-speed limits of
 * language.md section 16 and the travel.  It knows no language: what a
 * program makes it do comes through the canonical table (grinder_ops,
 * src/core/canon.h: a line, an arc or a helix, a dwell, the wheel, a
 * traverse, the panel's switches, the end) in machine coordinates -- the
 * start position is 0 -- and it reports each call it carries out to its
 * sink (the runner's journal; --trace=canon prints them as LinuxCNC does).
 * What the operator does by hand (jogs, corrections) and what passes time
 * without a call of the program (a plugin's) are its own functions below.
 * Passing time reaches the tick hook (oscillation). */
#ifndef S42_MACHINE_H
#define S42_MACHINE_H

#include "canon.h"
#include <stddef.h>
#include <stdint.h>

enum { AX_X, AX_Y, AX_Z, AX_A };
enum { WHEEL_OFF, WHEEL_CW, WHEEL_CCW };

#define MACH_AXIS_MAX 6000.0          /* mm/min (deg/min for A) */
#define MACH_Y_MAX (6000.0 / 36.0)
#define MACH_WHEEL_RUNDOWN 3.0        /* s, the wheel's run-down after M5 */

#define MACH_ARC_RMAX 4000000.0       /* discretes: the largest arc radius */
#define MACH_ARC_TOL 2.0              /* discretes: start and end radius may differ this much */

/* A contour move: a line to `to`, or an arc in a plane round a centre (the
 * axes off the plane stay).  to: absolute, discretes. */
struct mach_path {
  int arc;
  int64_t to[4];
  int plane;           /* enum geom_plane (src/core/geom.h) */
  double cp, cq;       /* the centre, relative to the start, in the plane's axes */
  int ccw;
};

/* The panel's interlock the program sets by CANON_SWITCH (M22/M23; the
 * override's M25/M26 is CANON_OVERRIDE). */
enum { MACH_SW_CORR };

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
  /* where it reports each canonical call it carries out (the runner's
   * journal); none: nothing is reported */
  struct canon_sink out;
  /* what the last motion call made: its increments, its effective speed */
  struct mach_out last;
};

/* The table the runtimes call (src/core/canon.h): FEED_LINE, FEED_ARC (a
 * helix with the axes off the plane; len and limit: a plugin's own curve),
 * TRAVERSE, DWELL, SPINDLE (the check refuses a reversal without a stop
 * first, E-WHEEL; a turning wheel runs down MACH_WHEEL_RUNDOWN s after a
 * stop), OVERRIDE (M25/M26), SWITCH (n MACH_SW_CORR: M22/M23), END.  A feed
 * move checks its geometry (E-ARC), speed (E-FEED) and travel (E-TRAVEL)
 * first; F and the override apply, then the limits.  Each motion leaves
 * what it made in m->last. */
extern const struct canon_ops grinder_ops;
static inline struct canon_dev grinder_dev(struct machine *m)
{
  struct canon_dev d = {&grinder_ops, m};
  return d;
}

/* The machine's axes as the canonical interface describes them: name,
 * unit, rotary or not, the fastest it moves. */
struct mach_axis {
  char name;           /* 'X' */
  const char *unit;    /* "mm", "deg" */
  int rotary;
  double max_speed;    /* mm/min or deg/min */
};
#define MACH_NAXES 4
extern const struct mach_axis mach_axes[MACH_NAXES];

void mach_init(struct machine *m);
/* Check a contour move at speed f before anything moves: its geometry
 * (E-ARC), its speed (E-FEED), its travel (E-TRAVEL).  0, or the error code
 * (vm/errors.h) with the message in msg. */
int mach_check_path(const struct machine *m, const struct mach_path *pa, double f, char *msg, size_t n);
/* Only the travel (a plugin's curve through the same points: the helix). */
int mach_check_travel(const struct machine *m, const struct mach_path *pa, char *msg, size_t n);
/* Would the wheel turning dir (1 M3, -1 M4) be a reversal without a stop
 * first?  0, or E-WHEEL with msg. */
int mach_check_spindle(const struct machine *m, int dir, char *msg, size_t n);
/* The override switch was turned (m->override_pct is the new position)
 * at simulated time `now`, within the last contour move: the rest of it
 * goes at the new speed.  The move's end and the machine's time move by
 * the difference, which is returned (seconds; 0 when `now` is not within a
 * move that takes the override).  At 0 % nothing changes: the host holds
 * the move (its clock stops) and calls this again when the switch leaves 0. */
double mach_override_at(struct machine *m, double now);
/* Is simulated time `now` within the last contour move, one that takes the
 * override (M26)?  What mach_override_at acts on, and where a 0 % holds. */
int mach_in_move(const struct machine *m, double now);
/* Would a feed override of 0 % hold a contour move that moves an axis? */
int mach_held(const struct machine *m, int moves);
/* Effective speed limit of a linear move (increments in discretes). */
double mach_linear_limit(const double d[4]);
/* An arc's length in mm and the largest Y share of its tangent (0..1): the
 * speed limit of language.md sec. 16.3. */
struct geom_arc;
void mach_arc_shape(int plane, const struct geom_arc *a, double *len_mm, double *yshare);
/* Move an axis by hand (jog, correction); counts in the position.  The
 * axis stops at its travel limit: returns the move made (d, or less). */
int64_t mach_jog(struct machine *m, int axis, int64_t d, int correction);
/* Would these moves of the axes, from where they are, stay in their travel? */
int mach_in_travel(const struct machine *m, const int64_t d[4]);
/* Advance simulated time by dt seconds (the tick hook runs): time a
 * plugin takes that is no call of the program (no record). */
void mach_advance(struct machine *m, double dt);
/* A plugin moves an axis outside the contour (oscillation) by d discretes:
 * no record; the caller reports it as a manual move. */
void mach_displace(struct machine *m, int axis, int64_t d);
/* The maximum speed of an axis, mm/min (deg/min). */
double mach_axis_max(int axis);

#endif
