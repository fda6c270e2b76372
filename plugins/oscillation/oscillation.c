/* The oscillation plugin: G07 (stroke and speed of one axis), M13 (on from
 * the start of its block), M14 (off at the end of its block; M2 includes
 * it).  While on, the axis runs back and forth over its stroke at its own
 * speed, independently of the contour, through blocks and sub calls; when
 * it stops, the axis returns to where it started oscillating, at the
 * oscillation speed (language.md sections 7-9). */
#include <s42_plugin.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const struct s42_host *host;

struct osc {
  int defined, active, axis;
  double stroke;       /* discretes, signed: its sign is the first direction */
  double speed;        /* mm/min (deg/min), after clamping */
  double travel;       /* discretes travelled since it started */
  double off;          /* the displacement now applied to the axis */
};

static const char axis_names[] = "XYZA";

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)dir;
  S42_PLUGIN_INIT(h, host);
  struct osc *o = h->alloc(sizeof *o);
  if (!o)
    return S42_FAIL;
  memset(o, 0, sizeof *o);
  *self = o;
  return S42_OK;
}

static void fini(void *self)
{
  host->free(self);
}

static void reset(void *self)
{
  memset(self, 0, sizeof(struct osc));
}

/* The one axis word of a G07 block. */
static int g07_axis(struct s42_block *b)
{
  for (int a = S42_X; a <= S42_A; a++)
    if (host->has_word(b, axis_names[a]))
      return a;
  return -1;
}

/* The displacement after `travel` discretes along a stroke s: 0 -> s -> 0. */
static double offset_at(double travel, double s)
{
  double as = fabs(s);
  if (as == 0)
    return 0;
  double p = fmod(travel, 2 * as);
  double off = p <= as ? p : 2 * as - p;
  return s < 0 ? -off : off;
}

static int check(void *self, struct s42_block *b)
{
  struct osc *o = self;
  int axis = o->axis, defined = o->defined;
  if (host->has_g(b, 7)) {
    axis = g07_axis(b);
    if (axis < 0) {
      host->error(b, "E-OSC", "G07 takes exactly one axis word (the stroke)");
      return S42_FAIL;
    }
    if (host->word(b, axis_names[axis]) == 0) {
      host->error(b, "E-OSC", "G07: oscillation stroke 0");
      return S42_FAIL;
    }
    if (!(host->word(b, 'F') > 0)) {
      host->error(b, "E-OSC", "G07: oscillation speed F must be above 0");
      return S42_FAIL;
    }
    if (o->active && axis != o->axis) {
      host->error(b, "E-OSC", "G07 changes the oscillating axis while it oscillates: M14 first");
      return S42_FAIL;
    }
    defined = 1;
  }
  if (host->has_m(b, 13) && !defined) {
    host->error(b, "E-OSC", "M13 before any G07: the oscillation is not defined");
    return S42_FAIL;
  }
  if ((o->active || host->has_m(b, 13)) && host->moves_axis(b, axis)) {
    host->error(b, "E-OSC", "%c oscillates and may not move in the contour", axis_names[axis]);
    return S42_FAIL;
  }
  return S42_OK;
}

static int start(void *self, struct s42_block *b)
{
  struct osc *o = self;
  if (host->has_g(b, 7)) {
    int axis = g07_axis(b);
    double sp = host->word(b, 'F'), max = host->axis_speed(axis);
    if (sp > max) {
      host->warn(b, "G07: oscillation speed %.0f is over the %c axis's %.2f: clamped", sp, axis_names[axis], max);
      sp = max;
    }
    o->defined = 1;
    o->axis = axis;
    o->stroke = host->word(b, axis_names[axis]);
    o->speed = sp;
  }
  if (host->has_m(b, 13) && !o->active) {
    o->active = 1;
    o->travel = 0;
    o->off = 0;
    host->displace(b, o->axis, 0);   /* marks where it starts, for plots */
  }
  return S42_OK;
}

/* Move the axis to the displacement `off` (whole discretes reach the axis). */
static void apply(struct osc *o, struct s42_block *b, double off)
{
  int64_t have = (int64_t)llround(o->off), want = (int64_t)llround(off);
  o->off = off;
  if (want != have)
    host->displace(b, o->axis, want - have);
}

static void advance(void *self, struct s42_block *b, double dt)
{
  struct osc *o = self;
  if (!o->active || !(dt > 0))
    return;
  double s = fabs(o->stroke), dist = dt * o->speed * 1000.0 / 60.0;
  /* report the turning points (for plots), a bounded number of them */
  for (int turns = 0; s > 0 && turns < 256; turns++) {
    double to_turn = s - fmod(o->travel, s);
    if (to_turn >= dist)
      break;
    o->travel += to_turn;
    dist -= to_turn;
    apply(o, b, offset_at(o->travel, o->stroke));
  }
  o->travel += dist;
  apply(o, b, offset_at(o->travel, o->stroke));
}

static int finish(void *self, struct s42_block *b)
{
  struct osc *o = self;
  if (!o->active || !(host->has_m(b, 14) || host->has_m(b, 2)))
    return S42_OK;
  o->active = 0;
  double back = fabs((double)llround(o->off));
  if (back > 0 && o->speed > 0)
    host->dwell(b, back / 1000.0 / o->speed * 60.0);   /* the return stroke */
  apply(o, b, 0);
  o->travel = 0;
  return S42_OK;
}

static size_t save(void *self, void *buf, size_t cap)
{
  if (cap >= sizeof(struct osc))
    memcpy(buf, self, sizeof(struct osc));
  return sizeof(struct osc);
}

static int load(void *self, const void *buf, size_t len)
{
  struct osc o;
  if (len != sizeof o)
    return S42_FAIL;
  memcpy(&o, buf, sizeof o);
  /* a restart state edited by hand must not get past here: what G07 and
   * M13 could have left, nothing else (the travel stays where a double
   * still counts whole discretes) */
  if ((o.defined != 0 && o.defined != 1) || (o.active != 0 && o.active != 1) || (o.active && !o.defined) ||
      o.axis < 0 || o.axis > 3 || !(fabs(o.stroke) <= 9999999) || !(o.speed >= 0 && o.speed <= 6000) ||
      !(o.travel >= 0 && o.travel <= 9007199254740992.0) || !(fabs(o.off) <= fabs(o.stroke)) ||
      (o.defined && (o.stroke == 0 || !(o.speed > 0))))
    return S42_FAIL;
  memcpy(self, &o, sizeof o);
  return S42_OK;
}

static size_t describe(void *self, int what, char *buf, size_t cap)
{
  const struct osc *o = self;
  int n = 0;
  if (what == S42_DESCRIBE_TRACE && o->active)
    n = snprintf(buf, cap, "\"on\"");
  else if (what == S42_DESCRIBE_DUMP && o->defined)
    n = snprintf(buf, cap, "{\"axis\":\"%c\",\"stroke\":%.0f,\"speed\":%.3f,\"on\":%s}", "xyza"[o->axis],
                 o->stroke, o->speed, o->active ? "true" : "false");
  return n > 0 ? (size_t)n : 0;
}

static const struct s42_function functions[] = {
  S42_G_FUNCTION(7, 1, "XYZAF", S42_FN_SEPARATE,
                 "oscillation parameters: one axis word (stroke, first direction) and F (speed)"),
  S42_M_FUNCTION(13, NULL, 0, "oscillation on, from the start of this block"),
  S42_M_FUNCTION(14, NULL, 0, "oscillation off at the end of this block; the axis returns"),
};

S42_PLUGIN_DECLARE("oscillation", "1.0", "oscillation of one axis through blocks and subs (G07 M13 M14)", functions,
                   .flags = S42_PL_EVERY_BLOCK, .init = init, .fini = fini, .check = check, .start = start,
                   .finish = finish, .advance = advance, .save = save, .load = load, .describe = describe,
                   .trace_key = "osc", .reset = reset);
