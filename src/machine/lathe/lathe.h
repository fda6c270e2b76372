/* The simulated 16Б16Ф3 lathe (spec/dialects/2u22.md sec. 1, D-22..D-32):
 * the cross slide X and the carriage Z, the spindle with its two ranges,
 * the turret's tools with their X/Z corrections, coolant, machine zero and
 * the part zero, the travel, the working-feed and traverse limits, and
 * simulated time.  It knows no language: its calls are the canonical
 * machine's (a traverse, a line, an arc, a thread, a dwell, the spindle,
 * the feed mode, a tool, coolant, homing), and a trace observer sees each
 * as LinuxCNC prints it (src/core/canon.h; --trace=canon).
 *
 * Units: positions are counts of 1 µm; X counts the DIAMETER (a diameter
 * change of d moves the slide d/2).  A position given to a call is the
 * tool tip's in the part's coordinates (what the program and the display
 * mean, and what LinuxCNC's canonical calls print: its work coordinates);
 * the machine keeps where the slides are in machine coordinates
 * (slide = tip + part zero - the tool's correction) and checks the travel
 * there.  Feeds are mm/min of the path measured on the slides (D-24). */
#ifndef S42_LATHE_H
#define S42_LATHE_H

#include "canon.h"
#include <stddef.h>
#include <stdint.h>

enum { LX, LZ };                      /* the axes: X (diameter), Z */

#define LATHE_TOOLS 100               /* T0..T99; T0 is no tool (no correction) */
#define LATHE_RANGES 4                /* spindle ranges a model may have, 0 (none selected) included */

/* A lathe model: what differs between the machines the lathe dialects
 * drive (the 16Б16Ф3 of the 2У22 today; the 16К20Ф3 of the 2Р22 next).
 * A machine file (--machine) may change the travel and the limits. */
struct lathe_model {
  const char *name;                   /* "16Б16Ф3" */
  double feed_x, feed_z;              /* working-feed limits, mm/min (X of the slide) */
  double rapid_x, rapid_z;            /* traverse, mm/min (X of the slide) */
  int64_t travel_x, travel_z;         /* µm either side of machine zero, X of the radius (D-23) */
  int64_t arc_tol;                    /* µm of radius: start and end radii may differ this much (D-32) */
  int64_t pitch_max;                  /* µm: the longest thread pitch the machine cuts */
  int nranges;                        /* spindle ranges 1..nranges (M38, M39...) */
  double range_lo[LATHE_RANGES], range_hi[LATHE_RANGES];   /* rpm; [0]: no range selected */
};
/* The 16Б16Ф3 (spec/dialects/2u22.md sec. 1): feeds 1200 / 2400, traverse
 * 5000 / 10000 mm/min, travel 225 mm of radius and 650 mm, arcs within
 * 10 µm, pitch up to 40 mm, ranges M38 45-280 and M39 224-1800 rpm. */
extern const struct lathe_model lathe_16b16f3;

/* A tool's correction (the tool table, --tools FILE): tip = slide + d. */
struct lathe_tool {
  int has;                            /* in the table */
  int64_t d[2];                       /* µm, X as a diameter */
};

struct lathe {
  struct lathe_model model;           /* the machine's constants (a copy: a machine file changes them) */
  int64_t slide[2];                   /* machine coordinates, µm (X diameter); 0 0 = machine zero */
  int64_t zero[2];                    /* the part zero OX OZ: machine coordinates of the part's origin */
  int64_t lo[2], hi[2];               /* the travel of the slides, machine coordinates (D-23 by default) */
  struct lathe_tool tools[LATHE_TOOLS];
  int tool;                           /* in the working position, 0 none */
  double t;                           /* simulated seconds */
  int dir;                            /* spindle: 1 CW (M03), -1 CCW (M04), 0 stopped */
  double s;                           /* the S in force: rpm (G97) or m/min (G96), after clamping */
  int range;                          /* 0, 1, 2 */
  int per_rev;                        /* G95: feeds are mm per revolution */
  int css;                            /* G96: s is the cutting speed, m/min */
  int coolant;
  double feed;                        /* the last feed move's effective speed, mm/min of the path */
  double rpm_now;                     /* the spindle's speed at the end of the last call (css varies it) */
  double f_canon;                     /* the F of the last feed move, the canon's feed rate (0 after a
                                         G94/G95 switch): a thread's STRAIGHT_FEED keeps it (added) */
  int ovr_pct;                        /* the feed override switch, % (100 at power-on) */
  int ovr_on;                         /* it acts (CANON_OVERRIDE: the 2У22's G20, D-6 and D-46) */
  /* the last feed move, for an override turned within it: its start and
   * end (s), the path speed asked at 100 % and the axes' cap (mm/min), the
   * speed it goes at now */
  struct {
    int on;
    double t0, t1, vreq, cap, v;
  } mv;
  /* where it reports each canonical call it carries out and each warning
   * (a feed cut to the axes' limits, an S clamped to the range): the
   * runner's journal; none: nothing is reported */
  struct canon_sink out;
};

/* Power-on (D-7, D-22) of a model: slides at machine zero, part zero 0,
 * the model's travel, no tools in the table, T0, spindle stopped, no
 * range, G94 G97, coolant off, time 0. */
void lathe_init(struct lathe *l, const struct lathe_model *model);

/* The table the runtimes call (src/core/canon.h): TRAVERSE and HOME (the
 * axes X Z of `axes`), FEED_LINE, FEED_ARC (XZ plane: centre in centre[0]
 * X, centre[1] Z; ccw is G02 as below), THREAD, DWELL, SPINDLE,
 * SPINDLE_SPEED, SPINDLE_MODE, SPINDLE_RANGE, FEED_MODE, TOOL, COOLANT,
 * END, each as the function of the same name below; positions are the tool
 * tip's in part coordinates, X (axis 0) a diameter in µm, Z axis 2. */
extern const struct canon_ops lathe_ops;
static inline struct canon_dev lathe_dev(struct lathe *l)
{
  struct canon_dev d = {&lathe_ops, l};
  return d;
}
/* The tool tip's position in the part's coordinates (µm, X diameter). */
int64_t lathe_pos(const struct lathe *l, int axis);
/* The part zero (the operator's V0 entry, `zero X <mm> Z <mm>`): the tip
 * stays where it is in the machine, its part coordinates change. */
void lathe_set_zero(struct lathe *l, int64_t ox, int64_t oz);
/* The spindle's speed now, rpm (0 stopped); under G96 at diameter d (µm). */
double lathe_rpm(const struct lathe *l, int64_t d);
/* The override switch (l->ovr_pct) was turned at simulated time `now`,
 * within the last feed move, one the override acts on: the rest of it
 * goes at the new speed (a G01-G03's; not G25's, not a thread's).  The
 * move's end and the time move by the difference, which is returned (0:
 * not within such a move, or at 0 %, where the host holds the move). */
double lathe_override_at(struct lathe *l, double now);
/* Is simulated time `now` within the last feed move, one the override acts on? */
int lathe_in_move(const struct lathe *l, double now);

/* Each call returns 0, or an error code (vm/errors.h: S42_E_TRAVEL,
 * S42_E_ARC, S42_E_FEED, S42_E_THREAD) with the message in msg, having
 * changed nothing: a call checks before it moves. */

/* STRAIGHT_TRAVERSE of the axes in mask (bit LX, bit LZ) to `to` (part
 * coordinates), each at its traverse speed, together; the time is the
 * longer axis's. */
int lathe_traverse(struct lathe *l, unsigned mask, const int64_t to[2], char *msg, size_t n);
/* G25: the axes in mask to machine zero at traverse speed (D-31). */
int lathe_home(struct lathe *l, unsigned mask, char *msg, size_t n);
/* STRAIGHT_FEED to `to` at f: mm/min (G94), or mm per revolution (G95,
 * times the spindle's speed, which must turn: E-FEED otherwise).  f 0 is
 * E-FEED.  The speed is cut so that neither slide passes its working-feed
 * limit (a warning when it is, D-24). */
int lathe_feed_line(struct lathe *l, const int64_t to[2], double f, char *msg, size_t n);
/* ARC_FEED to `to` round centre c (part coordinates, X diameter); cw:
 * G02, else G03 (as LinuxCNC's G2/G3 in G18).  One quadrant at most and
 * the radii within the model's arc_tol (E-ARC); speed as a line's. */
int lathe_feed_arc(struct lathe *l, const int64_t to[2], const int64_t c[2], int cw, double f, char *msg, size_t n);
/* G33: a thread to `to`, pitch k µm of Z per revolution (taper: X changes
 * with it); the spindle must turn and Z speed = k * rpm must stay within
 * the model's feed_z (E-THREAD).  Also E-THREAD (added): k not in
 * (0, pitch_max], no Z move, a taper whose X slide would pass feed_x.
 * Under G96 the rpm is taken piece by piece along it. */
int lathe_thread(struct lathe *l, const int64_t to[2], double k, char *msg, size_t n);
/* DWELL: sec of simulated time. */
void lathe_dwell(struct lathe *l, double sec);
/* The spindle: dir 1 CW, -1 CCW, 0 stop. */
void lathe_spindle(struct lathe *l, int dir);
/* S: rpm (G97) or m/min (G96), clamped to the range in force with a
 * warning (D-10); M38/M39 (lathe_range) re-clamp it.  S0 is 0 rpm, no
 * warning; under G96 S is not clamped (the rpm it gives is, at each
 * diameter).  A negative or non-finite S, a range not 0..nranges, a T not
 * 0..99 are refused with a warning, changing nothing (added). */
void lathe_speed(struct lathe *l, double s);
void lathe_range(struct lathe *l, int range);
/* G96 on / G97 off; G97 re-clamps the S in force as rpm.  The front end
 * calls it before lathe_speed when a block has both (G96 S...). */
void lathe_css(struct lathe *l, int on);
/* G94 / G95 (SET_FEED_MODE). */
void lathe_feed_mode(struct lathe *l, int per_rev);
/* T: the tool in the working position; its correction applies from now. */
void lathe_tool(struct lathe *l, int t);
void lathe_coolant(struct lathe *l, int on);
/* PROGRAM_END (M02, M30): spindle and coolant stop (D-30). */
void lathe_end(struct lathe *l);

/* The tool table (--tools FILE), in the text format README documents:
 *   ; comment
 *   T1  X -12.50  Z 40.00      the corrections in mm, X as a diameter
 * (the format in full: tools.c's head comment).  The table replaces the
 * one before only when the whole text is good.
 * 0, or -1 with "FILE:LINE:COL: message" in err. */
int lathe_tools_parse(struct lathe *l, const char *text, size_t len, const char *file, char *err, size_t n);

#endif
