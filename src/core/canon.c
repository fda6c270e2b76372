/* The canonical interface's dispatch and its trace sink (src/core/canon.h). */
#include "canon.h"
#include "errors.h"
#include "geom.h"
#include <stdarg.h>
#include <stdio.h>

static const char *const names[CANON_NKIND] = {
  [CANON_FEED_LINE] = "STRAIGHT_FEED", [CANON_FEED_ARC] = "ARC_FEED", [CANON_TRAVERSE] = "STRAIGHT_TRAVERSE",
  [CANON_DWELL] = "DWELL", [CANON_SPINDLE] = "START_SPINDLE", [CANON_OVERRIDE] = "ENABLE_FEED_OVERRIDE",
  [CANON_END] = "PROGRAM_END", [CANON_SPINDLE_SPEED] = "SET_SPINDLE_SPEED", [CANON_FEED_MODE] = "SET_FEED_MODE",
  [CANON_SYNCH_START] = "START_SPEED_FEED_SYNC", [CANON_SYNCH_STOP] = "STOP_SPEED_FEED_SYNCH",
  [CANON_COOLANT] = "FLOOD_ON", [CANON_TOOL] = "SELECT_TOOL", [CANON_THREAD] = "THREAD",
  [CANON_HOME] = "HOME", [CANON_SPINDLE_MODE] = "SET_SPINDLE_MODE", [CANON_SPINDLE_RANGE] = "SET_SPINDLE_RANGE",
  [CANON_TOOL_CHANGE] = "CHANGE_TOOL", [CANON_TOOL_OFFSET] = "USE_TOOL_LENGTH_OFFSET",
  [CANON_CUTTER_RADIUS] = "START_CUTTER_RADIUS_COMPENSATION", [CANON_ORIGIN] = "SET_G5X_OFFSET",
  [CANON_AUX] = "SET_AUX_OUTPUT_BIT", [CANON_WAIT_INPUT] = "WAIT", [CANON_STOP] = "PROGRAM_STOP",
  [CANON_OPTIONAL_STOP] = "OPTIONAL_PROGRAM_STOP", [CANON_SWITCH] = "SET_PANEL_SWITCH",
  [CANON_UNITS] = "USE_LENGTH_UNITS",
};

const char *canon_name(int kind)
{
  return kind >= 0 && kind < CANON_NKIND && names[kind] ? names[kind] : "UNKNOWN";
}

int canon_do(const struct canon_dev *d, struct canon_call *c, char *msg, size_t n)
{
  if (c->kind < 0 || c->kind >= CANON_NKIND || !d->ops->fn[c->kind]) {
    struct canon_info in = {0};
    if (d->ops->info)
      d->ops->info(d->m, &in);
    snprintf(msg, n, "the %s has no call %s", in.name ? in.name : "machine", canon_name(c->kind));
    return S42_E_FUNC;
  }
  return d->ops->fn[c->kind](d->m, c, msg, n);
}

void canon_report(const struct canon_sink *s, const struct canon_call *c)
{
  if (s && s->call)
    s->call(s->ctx, c);
}

void canon_warn(const struct canon_sink *s, const char *msg)
{
  if (s && s->warn && msg[0])
    s->warn(s->ctx, msg);
}

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
  out(t, "%s(%.4f, %.4f, %.4f, %.4f, %.4f, %.4f)", call, mm_of(c, 0, c->pos[0]), mm_of(c, 1, c->pos[1]),
      mm_of(c, 2, c->pos[2]), mm_of(c, 3, c->pos[3]), mm_of(c, 4, c->pos[4]), mm_of(c, 5, c->pos[5]));
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
  int64_t ctr[CANON_AXES] = {0};
  ctr[p] = c->centre[0];
  ctr[q] = c->centre[1];
  int rot = c->ccw ? 1 : -1;
  if (pl == GEOM_XZ)
    rot = -rot;
  int f = first[pl], g = second[pl], h = axis[pl];
  /* a helix of several turns: LinuxCNC's rotation counts them */
  rot *= 1 + (c->turns > 0 ? c->turns : 0);
  out(t, "ARC_FEED(%.4f, %.4f, %.4f, %.4f, %d, %.4f, %.4f, %.4f, %.4f)", mm_of(c, f, c->pos[f]),
      mm_of(c, g, c->pos[g]), mm_of(c, f, ctr[f]), mm_of(c, g, ctr[g]), rot, mm_of(c, h, c->pos[h]),
      mm_of(c, 3, c->pos[3]), mm_of(c, 4, c->pos[4]), mm_of(c, 5, c->pos[5]));
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
    out(t, "SELECT_TOOL(%d)", c->n);
    break;
  case CANON_TOOL_CHANGE:
    out(t, "CHANGE_TOOL(%d)", c->n);
    break;
  case CANON_TOOL_OFFSET:
    out(t, "USE_TOOL_LENGTH_OFFSET(%.4f, %.4f, %.4f, %.4f, %.4f, %.4f, 0.0000, 0.0000, 0.0000)",
        mm_of(c, 0, c->pos[0]), mm_of(c, 1, c->pos[1]), mm_of(c, 2, c->pos[2]), mm_of(c, 3, c->pos[3]),
        mm_of(c, 4, c->pos[4]), mm_of(c, 5, c->pos[5]));
    break;
  case CANON_CUTTER_RADIUS:
    if (c->dir)
      out(t, "START_CUTTER_RADIUS_COMPENSATION(%.4f, %s)", c->v, c->dir > 0 ? "LEFT" : "RIGHT");
    else
      out(t, "STOP_CUTTER_RADIUS_COMPENSATION()");
    break;
  case CANON_ORIGIN:
    out(t, "SET_G5X_OFFSET(%d, %.4f, %.4f, %.4f, %.4f, %.4f, %.4f)", c->n, mm_of(c, 0, c->pos[0]),
        mm_of(c, 1, c->pos[1]), mm_of(c, 2, c->pos[2]), mm_of(c, 3, c->pos[3]), mm_of(c, 4, c->pos[4]),
        mm_of(c, 5, c->pos[5]));
    break;
  case CANON_AUX:
    out(t, "%s(%d)", c->on ? "SET_AUX_OUTPUT_BIT" : "CLEAR_AUX_OUTPUT_BIT", c->n);
    break;
  case CANON_WAIT_INPUT:
    out(t, "WAIT(%d, 0, %d, %.4f)", c->n, c->on ? 1 : 0, c->v);
    break;
  case CANON_STOP:
    out(t, "PROGRAM_STOP()");
    break;
  case CANON_OPTIONAL_STOP:
    out(t, "OPTIONAL_PROGRAM_STOP()");
    break;
  case CANON_UNITS:
    out(t, "USE_LENGTH_UNITS(%s)", c->on ? "CANON_UNITS_MM" : "CANON_UNITS_INCHES");
    break;
  default:
    /* CANON_SPINDLE_MODE, CANON_SPINDLE_RANGE, CANON_SWITCH: no line of
     * LinuxCNC's to print (THREAD and HOME come as the records they make) */
    break;
  }
}
