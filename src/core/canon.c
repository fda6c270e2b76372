/* The trace sink of the canonical calls (src/core/canon.h). */
#include "canon.h"
#include "geom.h"
#include <stdarg.h>
#include <stdio.h>

static double mm_of(const struct canon_call *c, int axis, int64_t v)
{
  return (double)v * (c->mm ? c->mm[axis] : 0.001);
}

static void out(struct canon_trace *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void out(struct canon_trace *t, const char *fmt, ...)
{
  char line[256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(line, sizeof line, fmt, ap);
  va_end(ap);
  t->line(t->ctx, line);
}

void canon_trace_init(struct canon_trace *t, void (*line)(void *ctx, const char *text), void *ctx)
{
  t->line = line;
  t->ctx = ctx;
  t->f = -1;
  t->plane = -1;
}

static void feed_rate(struct canon_trace *t, double f)
{
  if (f != t->f) {
    out(t, "SET_FEED_RATE(%.4f)", f);
    t->f = f;
  }
}

static void point(struct canon_trace *t, const char *call, const struct canon_call *c)
{
  out(t, "%s(%.4f, %.4f, %.4f, %.4f, 0.0000, 0.0000)", call, mm_of(c, 0, c->pos[0]), mm_of(c, 1, c->pos[1]),
      mm_of(c, 2, c->pos[2]), mm_of(c, 3, c->pos[3]));
}

/* LinuxCNC's planes: XY (X, Y; axis Z), YZ (Y, Z; axis X), XZ (Z, X; axis
 * Y): the first and second axes in its order, and its turning sense the
 * reverse of ours in XZ (ours turns from X to Z). */
static void arc(struct canon_trace *t, const struct canon_call *c)
{
  static const char *const name[] = {"CANON_PLANE_XY", "CANON_PLANE_YZ", "CANON_PLANE_XZ"};
  static const int first[] = {0, 1, 2}, second[] = {1, 2, 0}, axis[] = {2, 0, 1};
  int pl = c->plane >= 0 && c->plane <= 2 ? c->plane : GEOM_XZ;
  if (t->plane != pl) {
    out(t, "SELECT_PLANE(%s)", name[pl]);
    t->plane = pl;
  }
  int p, q;
  geom_plane_axes(pl, &p, &q);
  int64_t ctr[4] = {0, 0, 0, 0};
  ctr[p] = c->centre[0];
  ctr[q] = c->centre[1];
  int rot = c->ccw ? 1 : -1;
  if (pl == GEOM_XZ)
    rot = -rot;
  int f = first[pl], g = second[pl], h = axis[pl];
  out(t, "ARC_FEED(%.4f, %.4f, %.4f, %.4f, %d, %.4f, %.4f, 0.0000, 0.0000)", mm_of(c, f, c->pos[f]),
      mm_of(c, g, c->pos[g]), mm_of(c, f, ctr[f]), mm_of(c, g, ctr[g]), rot, mm_of(c, h, c->pos[h]),
      mm_of(c, 3, c->pos[3]));
}

void canon_trace_call(void *ctx, const struct canon_call *c)
{
  struct canon_trace *t = ctx;
  switch (c->kind) {
  case CANON_FEED_LINE:
    feed_rate(t, c->f);
    point(t, "STRAIGHT_FEED", c);
    break;
  case CANON_FEED_ARC:
    feed_rate(t, c->f);
    arc(t, c);
    break;
  case CANON_TRAVERSE:
    point(t, "STRAIGHT_TRAVERSE", c);
    break;
  case CANON_DWELL:
    out(t, "DWELL(%.4f)", c->v);
    break;
  case CANON_SPINDLE:
    out(t, "%s(0)", c->dir > 0 ? "START_SPINDLE_CLOCKWISE" : c->dir < 0 ? "START_SPINDLE_COUNTERCLOCKWISE"
                                                                      : "STOP_SPINDLE_TURNING");
    break;
  case CANON_OVERRIDE:
    out(t, "%s", c->on ? "ENABLE_FEED_OVERRIDE()" : "DISABLE_FEED_OVERRIDE()");
    break;
  case CANON_END:
    out(t, "PROGRAM_END()");
    break;
  case CANON_SPINDLE_SPEED:
    out(t, "SET_SPINDLE_SPEED(0, %.4f)", c->v);
    break;
  case CANON_FEED_MODE:
    out(t, "SET_FEED_MODE(0, %d)", c->on != 0);
    out(t, "SET_FEED_RATE(0.0000)");   /* a switch cancels F (LinuxCNC prints it so too) */
    t->f = 0;
    break;
  case CANON_SYNCH_START:
    out(t, "START_SPEED_FEED_SYNC(%.6f,0)", c->v);
    break;
  case CANON_SYNCH_STOP:
    out(t, "STOP_SPEED_FEED_SYNCH()");
    break;
  case CANON_COOLANT:
    if (c->on)
      out(t, "FLOOD_ON()");
    else {
      out(t, "MIST_OFF()");
      out(t, "FLOOD_OFF()");
    }
    break;
  case CANON_TOOL:
    out(t, "SELECT_TOOL(%d)", c->dir);
    break;
  default:
    break;
  }
}
