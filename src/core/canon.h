/* The canonical machine interface, in both directions, in LinuxCNC's terms
 * (its canon.hh in spirit): one table of calls that every machine
 * implements and every runtime and cycle generator (src/cycles/) calls
 * without knowing which machine is behind it, and one record,
 * struct canon_call, for a call asked and for a call carried out.
 *
 * A runtime fills a record (its kind and arguments: an absolute target in
 * the machine's counts, a feed, a spindle direction...) and hands it to the
 * machine with canon_do(); the machine checks it, carries it out in
 * simulated time and reports what it did -- one or more records with where
 * the axes were and are, and when -- to the sink the runner gave it (the
 * open block's journal, src/core/mrun.h).  The trace sink below prints
 * those records as LinuxCNC's canonical calls (--trace=canon: what
 * `rs274 -g` prints for a twin program, without its N... prefix); the plot
 * and the terminal read the same records.
 *
 * Positions are counts of each axis (X Y Z A B C); a machine says how many
 * mm (degrees) a count is (canon_info, and canon_call.mm), so a lathe's X
 * may count its diameter and print its radius. */
#ifndef S42_CANON_H
#define S42_CANON_H

#include <stddef.h>
#include <stdint.h>

#define CANON_AXES 6           /* X Y Z A B C, LinuxCNC's order */

enum canon_kind {
  /* motion */
  CANON_FEED_LINE,       /* STRAIGHT_FEED to pos at feed f */
  CANON_FEED_ARC,        /* ARC_FEED to pos round centre in plane, ccw or not, at f; the axes off
                            the plane move along with it (a helix), `turns` full turns more */
  CANON_TRAVERSE,        /* STRAIGHT_TRAVERSE to pos (the axes of `axes`; 0: all) */
  CANON_DWELL,           /* DWELL(v) seconds */
  CANON_SPINDLE,         /* dir 1 START_SPINDLE_CLOCKWISE, -1 COUNTERCLOCKWISE, 0 STOP_SPINDLE_TURNING */
  CANON_OVERRIDE,        /* on: ENABLE_FEED_OVERRIDE, else DISABLE */
  CANON_END,             /* PROGRAM_END */
  CANON_SPINDLE_SPEED,   /* SET_SPINDLE_SPEED(0, v) rpm (or m/min under CSS) */
  CANON_FEED_MODE,       /* SET_FEED_MODE(0, on): on 1 per revolution, 0 per minute */
  CANON_SYNCH_START,     /* START_SPEED_FEED_SYNC(v, 0): a thread's pitch v mm per revolution */
  CANON_SYNCH_STOP,      /* STOP_SPEED_FEED_SYNCH() */
  CANON_COOLANT,         /* on: FLOOD_ON(), else MIST_OFF() FLOOD_OFF() as LinuxCNC's M9 */
  CANON_TOOL,            /* SELECT_TOOL(n): the tool into the working position (a turret) */
  /* calls whose records a machine reports as the ones above, or as their own */
  CANON_THREAD,          /* a thread to pos, pitch v counts of the thread's axis per revolution, the
                            feed synchronised with the spindle: reported as SYNCH_START,
                            FEED_LINE, SYNCH_STOP */
  CANON_HOME,            /* the axes of `axes` to machine zero at traverse speed: a TRAVERSE */
  CANON_SPINDLE_MODE,    /* on: constant surface speed (v the highest rpm, 0 none), else rpm */
  CANON_SPINDLE_RANGE,   /* the gear range n (a machine's own; LinuxCNC has none: no line) */
  CANON_TOOL_CHANGE,     /* CHANGE_TOOL(n): the selected tool into the spindle */
  CANON_TOOL_OFFSET,     /* USE_TOOL_LENGTH_OFFSET: the offsets in pos (counts of each axis) */
  CANON_CUTTER_RADIUS,   /* v the radius in mm, dir 1 left (G41), -1 right (G42), 0 off (G40) */
  CANON_ORIGIN,          /* SET_G5X_OFFSET: the work offset n (1 G54...) at pos */
  CANON_AUX,             /* SET_AUX_OUTPUT_BIT(n) (on) / CLEAR_AUX_OUTPUT_BIT(n) */
  CANON_WAIT_INPUT,      /* WAIT(n, 0, on, v): input n to level `on`, timeout v s (0: none) */
  CANON_STOP,            /* PROGRAM_STOP (M00) */
  CANON_OPTIONAL_STOP,   /* OPTIONAL_PROGRAM_STOP (M01) */
  CANON_SWITCH,          /* a panel interlock the program sets, n which, on: a machine's own
                            (the ВЗ-208Ф3's operational corrections, M22/M23): no line */
  CANON_UNITS,           /* USE_LENGTH_UNITS: on 1 mm, 0 inch */
  CANON_NKIND
};

struct canon_call {
  int kind;
  unsigned axes;         /* TRAVERSE, HOME: bit k for axis k (0: every axis) */
  int64_t pos[CANON_AXES];   /* the target (asked); where the axes are after it (reported) */
  int64_t from[CANON_AXES];  /* reported: where they were before it */
  double t0, t1;         /* reported: the simulated seconds it began and ended */
  double f;              /* feed moves: the programmed speed (mm/min, or mm/rev) */
  double feed;           /* reported, feed moves: the effective path speed, mm/min */
  double len, limit;     /* feed moves, asked: a path whose length (mm) and speed limit (mm/min)
                            the caller computed (a plugin's curve); 0: the machine's own */
  double v;              /* DWELL seconds; SPINDLE_SPEED; THREAD, SYNCH_START pitch; see above */
  int dir, on, n;        /* SPINDLE; switches; TOOL, AUX, ORIGIN numbers */
  int plane;             /* ARC: enum geom_plane (XY, YZ, XZ) */
  int64_t centre[2];     /* ARC: the centre in the plane's two axes (geom_plane_axes order), absolute */
  double cp, cq;         /* ARC, asked: the centre relative to the start, exactly (centre is
                            its rounding) */
  int ccw;               /* ARC: turning from the plane's first axis towards its second */
  int turns;             /* ARC: full turns beyond the first (a helix of several turns) */
  const double *mm;      /* mm (deg) per count of each axis; NULL: 0.001 each */
};

/* Where a machine reports what it did: the open block's journal. */
struct canon_sink {
  void (*call)(void *ctx, const struct canon_call *c);
  /* a warning of the machine's (a feed cut to the axes' limits), for the
   * host, at the block that raised it */
  void (*warn)(void *ctx, const char *msg);
  void *ctx;
};
void canon_report(const struct canon_sink *s, const struct canon_call *c);
void canon_warn(const struct canon_sink *s, const char *msg);

/* An axis as the machine describes it. */
struct canon_axis {
  char name;             /* 'X' */
  const char *unit;      /* "mm", "deg" */
  int rotary;
  double mm;             /* mm (deg) per count */
  double max_speed;      /* mm/min (deg/min) */
  int has_travel;        /* the travel below holds (else it is unlimited) */
  int64_t lo, hi;        /* counts, machine coordinates */
};

/* What a machine is: its kind (the plot's view and the panel's: "grinder",
 * "lathe", "mill", "robot"), its name and its axes in canonical order (an
 * axis the machine lacks has name 0). */
struct canon_info {
  const char *kind;
  const char *name;
  int naxes;             /* the axes it has */
  struct canon_axis axis[CANON_AXES];
};

/* A machine's side of the table: a function per kind it carries out (NULL:
 * it has no such call).  Each checks before it changes anything: 0 done, or
 * an error code (vm/errors.h) with the message in msg, the machine as it
 * was.  c is the asked record; the machine may write its reported members
 * into it. */
typedef int canon_fn(void *m, struct canon_call *c, char *msg, size_t n);
struct canon_ops {
  canon_fn *fn[CANON_NKIND];
  void (*info)(const void *m, struct canon_info *out);
};

/* A machine behind the table. */
struct canon_dev {
  const struct canon_ops *ops;
  void *m;
};

/* Carry out c on the machine: 0, or its error code and message; a call the
 * machine does not have is E-FUNC naming it and the machine. */
int canon_do(const struct canon_dev *d, struct canon_call *c, char *msg, size_t n);
/* A record of kind k, every member 0 (pos: call canon_here first for a
 * move that keeps some axes where they are). */
static inline struct canon_call canon_of(int k)
{
  struct canon_call c = {0};
  c.kind = k;
  return c;
}
/* The name LinuxCNC gives a kind ("STRAIGHT_FEED"), or ours in its style
 * where it has none ("THREAD", "HOME", "SET_SPINDLE_RANGE"). */
const char *canon_name(int kind);

/* The trace sink: prints a line per record to out, SET_FEED_RATE and
 * SELECT_PLANE when they change. */
struct canon_trace {
  void (*line)(void *ctx, const char *text);
  void *ctx;
  double f;              /* the last SET_FEED_RATE printed, -1 none */
  int plane;             /* the last SELECT_PLANE printed, -1 none */
};

void canon_trace_init(struct canon_trace *t, void (*line)(void *ctx, const char *text), void *ctx);
/* A record carried out: ctx is a struct canon_trace. */
void canon_trace_call(void *ctx, const struct canon_call *c);

#endif
