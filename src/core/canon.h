/* The canonical machine calls as events, and the trace sink that prints
 * them as LinuxCNC's canonical machining functions (--trace=canon: what
 * `rs274 -g` prints for a twin program, without its N... prefix).  A
 * machine reports each call it carries out (struct canon_call: absolute
 * positions in counts, after the call); the sink keeps what LinuxCNC
 * prints only on a change (the feed rate, the plane). */
#ifndef S42_CANON_H
#define S42_CANON_H

#include <stddef.h>
#include <stdint.h>

enum canon_kind {
  CANON_FEED_LINE,       /* STRAIGHT_FEED to pos at feed f */
  CANON_FEED_ARC,        /* ARC_FEED to pos round centre in plane, ccw or not, at feed f */
  CANON_TRAVERSE,        /* STRAIGHT_TRAVERSE to pos */
  CANON_DWELL,           /* DWELL(v) seconds */
  CANON_SPINDLE,         /* dir 1 START_SPINDLE_CLOCKWISE, -1 COUNTERCLOCKWISE, 0 STOP_SPINDLE_TURNING */
  CANON_OVERRIDE,        /* on: ENABLE_FEED_OVERRIDE, else DISABLE */
  CANON_END,             /* PROGRAM_END */
  CANON_SPINDLE_SPEED,   /* SET_SPINDLE_SPEED(0, v) rpm */
  CANON_FEED_MODE,       /* SET_FEED_MODE(0, on): on 1 per revolution, 0 per minute */
  CANON_SYNCH_START,     /* START_SPEED_FEED_SYNC(v, 0): a thread's pitch v mm per revolution */
  CANON_SYNCH_STOP,      /* STOP_SPEED_FEED_SYNCH() */
  CANON_COOLANT,         /* on: FLOOD_ON(), else MIST_OFF() FLOOD_OFF() as LinuxCNC's M9 */
  CANON_TOOL             /* SELECT_TOOL(dir): the tool number */
};

struct canon_call {
  int kind;
  int64_t pos[4];        /* X Y Z A after the call, discretes (0.001 mm, 0.001 deg) */
  double f;              /* feed moves: the programmed speed, mm/min */
  double v;              /* DWELL: seconds */
  int dir, on;           /* SPINDLE, OVERRIDE */
  int plane;             /* ARC: enum geom_plane (XY, YZ, XZ) */
  int64_t centre[2];     /* ARC: the centre in the plane's two axes (geom_plane_axes order), absolute */
  int ccw;               /* ARC: turning from the plane's first axis towards its second */
  const double *mm;      /* mm (deg) per count of X Y Z A; NULL: 0.001 each (a lathe's X
                            counts its diameter and prints the radius: 0.0005) */
};

/* The sink: prints a line per call to out, SET_FEED_RATE and SELECT_PLANE
 * when they change. */
struct canon_trace {
  void (*line)(void *ctx, const char *text);
  void *ctx;
  double f;              /* the last SET_FEED_RATE printed, -1 none */
  int plane;             /* the last SELECT_PLANE printed, -1 none */
};

void canon_trace_init(struct canon_trace *t, void (*line)(void *ctx, const char *text), void *ctx);
/* The machine's observer hook: ctx is a struct canon_trace. */
void canon_trace_call(void *ctx, const struct canon_call *c);

#endif
