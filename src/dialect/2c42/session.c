/* The session (src/core/session.h): turns the VM's block events into machine
 * work, waits and trace rows. */
#include "session.h"
#include "sess_rt.h"
#include "error.h"
#include "errors.h"
#include "messages.h"
#include <math.h>
#include <stdlib.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define BIT(x, n) (((x) >> (n)) & 1)

static void tick(void *ctx, double dt);

void sess_init(struct session *s, const struct program *p)
{
  memset(s, 0, sizeof *s);
  s->p = p;
  vm_init(&s->vm, p);
  mach_init(&s->m);
  s->m.tick = tick;
  s->m.tick_ctx = s;
  screen_init(&s->scr);
  s->state = SE_START;
  s->blk.s = s;
  s->go = 1;             /* the cycle's start is its first block's Пуск */
  s->rt = &kp_runtime;   /* the session's own (the program carries the runner's) */
}

void sess_configure(struct session *s, const struct sess_config *c)
{
  s->cfg = *c;
  s->en = c->en;
  s->scr.en = c->en;
  s->vm.max_blocks = c->max_blocks;
  s->m.travel = c->travel;
  s->plugins = c->plugins;
  s->crashes = c->plugins ? c->plugins->crashes : 0;
  s->sink = c->sink;
  s->vm.yield_all = c->yield_all;
  s->vm.start_all = c->start_all || s->single || s->brk;
  s->vm.watch = c->watch;
  s->m.out.call = c->canon;
  s->m.out.ctx = c->canon_ctx;
}

void sess_set_start_all(struct session *s, int on)
{
  s->cfg.start_all = on;
  s->vm.start_all = on || s->single || s->brk;
}

void sess_set_cyrillic(struct session *s, int on)
{
  s->scr.cyr = on != 0;
}

void sess_fail(struct session *s, int code, const char *fmt, ...)
{
  char msg[sizeof s->vm.err.msg];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  vm_fail(&s->vm, code, "%s", msg);
  s->state = SE_ERROR;
}

void sess_refuse(struct session *s, int code, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(s->vm.err.msg, sizeof s->vm.err.msg, fmt, ap);
  va_end(ap);
  s->vm.err.code = code;
  s->vm.err.block = 0;
  s->vm.err.col = 1;
  s->state = SE_ERROR;
}

void sess_renew(struct session *s)
{
  double reg[114];
  memcpy(reg, s->vm.reg, sizeof reg);
  struct sess_config cfg = s->cfg;
  int ovr = s->m.override_pct, single = s->single, brk = s->brk, cyr = s->scr.cyr;
  const struct program *p = s->p;
  sess_init(s, p);
  sess_configure(s, &cfg);
  s->m.override_pct = ovr;
  s->scr.cyr = cyr;
  sess_set_single(s, single);
  sess_set_break(s, brk);
  memcpy(s->vm.reg, reg, sizeof reg);
}

void sess_error(const struct session *s, struct s42_error *e)
{
  const struct vm_error *v = &s->vm.err;
  const struct prog_block *b = v->block < s->p->nblocks ? &s->p->blocks[v->block] : NULL;
  memset(e, 0, sizeof *e);
  e->code = v->code;
  e->number = b && b->number ? (int)b->number : -1;
  e->line = b ? b->line : 1;
  e->col = v->col ? v->col : b ? b->col : 1;
  e->aux = v->aux;
  snprintf(e->msg, sizeof e->msg, "%s", v->msg);
}

void sess_show_error(struct session *s)
{
  struct s42_error e;
  char m[200];
  sess_error(s, &e);
  s42_error_machine(&e, s->p, s->en, m, sizeof m);
  screen_message(&s->scr, m);
}

void sess_show_message(struct session *s, const char *text)
{
  screen_message(&s->scr, text);
}

int sess_panel_edit(struct session *s, int op, int arg)
{
  return screen_edit(&s->scr, op, arg);
}

int sess_block_number(const struct session *s)
{
  int n = s->p->blocks[s->vm.cur].number;
  return n ? n : -1;
}

void sess_warn(struct session *s, const char *fmt, ...)
{
  char msg[240];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (s->sink.warn)
    s->sink.warn(s->sink.ctx, s, msg);
}

void sess_emit_row(struct session *s)
{
  ++s->seq;
  /* the plugins' members: the hosts read them after the block too
   * (sess_oscillating); nothing to do when no plugin has started */
  if (s->started)
    sess_plugin_json(s, S42_DESCRIBE_TRACE, s->extra, sizeof s->extra);
  else
    s->extra[0] = 0;
  if (!s->sink.row)
    return;   /* nothing watches: no row is built */
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  const struct prog_block *pb = &s->p->blocks[s->vm.cur];
  struct sess_row r;   /* every member set below: no memset of the whole */
  r.seq = s->seq;
  r.n = pb->number ? (int)pb->number : -1;
  r.line = pb->line;
  r.depth = s->vm.depth;
  r.motion = kp_motion_name[at->motion];
  memcpy(r.d, s->mo.d, sizeof r.d);
  r.f = s->vm.reg[REG_F];
  r.feed = s->mo.feed;
  r.t = s->m.t;
  r.v = s->mo.v;
  r.has_v = s->mo.has_v;
  r.extra = s->extra;
  if (at->motion == MO_PLUGIN) {
    snprintf(s->gname, sizeof s->gname, "G%02d", at->plug_g % 100);
    r.motion = s->gname;
  }
  r.override_pct = s->m.override_allowed ? s->m.override_pct : 100;
  memcpy(r.jogs, s->jogs, sizeof r.jogs);
  r.has_jogs = s->has_jogs;
  memcpy(r.start, s->start, sizeof r.start);
  r.teach = at->motion == MO_M19;
  if (r.teach && (BIT(at->g, 2) || BIT(at->g, 3))) {
    struct kp_block b = s->mb;
    b.motion = BIT(at->g, 2) ? MO_G02 : MO_G03;   /* teach-in along an arc */
    r.has_path = kp_path(s->start, &b, &r.path);
  } else {
    r.has_path = kp_path(s->start, &s->mb, &r.path);
  }
  if (!r.has_path)
    memset(&r.path, 0, sizeof r.path);
  s->sink.row(s->sink.ctx, s, &r);
}


/* ---- plugins: the host services (include/s42_plugin.h) ---- */

#define PLUG(b) (&(b)->s->plugins->v[(b)->plug])
/* The plugins of mask (bit i: plugin i), in index order: the work is the
 * plugins in use, not PLUG_MAX. */
#define EACH_PLUGIN(mask, i) \
  for (uint32_t each_ = (mask), i = 0; each_ && (i = (uint32_t)__builtin_ctz(each_), 1); each_ &= each_ - 1)

static const struct kp_attr *cur_attr(const struct session *s)
{
  return kp_attr(s->p, s->vm.cur);
}

static int h_number(struct s42_block *b) { return sess_block_number(b->s); }
static int h_has_g(struct s42_block *b, int g) { return g >= 0 && g < 64 && BIT(cur_attr(b->s)->g, g); }
static int h_has_m(struct s42_block *b, int m) { return m >= 0 && m < 32 && BIT(cur_attr(b->s)->m, m); }
static int h_plane(struct s42_block *b) { return cur_attr(b->s)->plane; }

/* The slot of a word letter, or -1; F: the slot its value went to. */
static int word_slot(const struct session *s, char l)
{
  const struct kp_attr *at = cur_attr(s);
  static const char letters[] = "XYZAIJK";
  const char *p = l ? strchr(letters, l) : NULL;
  if (p)
    return (int)(p - letters);
  if (l == 'F' && BIT(at->slots, SL_OSCF))
    return SL_OSCF;
  if (l == 'F' && BIT(at->slots, SL_SRCHF))
    return SL_SRCHF;
  return -1;
}

static int h_has_word(struct s42_block *b, char l)
{
  const struct kp_attr *at = cur_attr(b->s);
  int sl = word_slot(b->s, l);
  if (sl >= 0)
    return BIT(at->slots, sl);
  return l == 'F' && at->has_f;
}

static double h_word(struct s42_block *b, char l)
{
  if (!h_has_word(b, l))
    return 0;
  int sl = word_slot(b->s, l);
  return sl >= 0 ? b->s->mb.w[sl] : b->s->vm.reg[REG_F];
}

static int h_resumed(struct s42_block *b) { return b->s->resumed; }

static double h_param(struct s42_block *b, int n)
{
  return n >= 0 && n < VM_NREG ? b->s->vm.reg[n] : 0;
}

/* A plugin changes the VM only through the VM's journaled calls, so a block
 * that fails after it wrote leaves the registers and arrays as after the
 * previous block (language.md sec. 7), as the program's own words do. */
static int h_set_param(struct s42_block *b, int n, double v)
{
  if (n < 0 || n > REG_F || !isfinite(v))
    return -1;
  vm_set_reg(&b->s->vm, (unsigned)n, v);
  return 0;
}

static int h_load_array(struct s42_block *b, int array, const double *v, int n)
{
  if (array < 1 || array > (int)b->s->p->lim.arrays || n < 0 || n > (int)b->s->p->lim.cells || (n && !v))
    return -1;
  for (int i = 0; i < n; i++)   /* the cells' range, as array words have it (E-RANGE) */
    if (!(fabs(v[i]) <= 9999999))
      return -1;
  vm_load_array(&b->s->vm, array - 1, v, n);
  return 0;
}

static int64_t h_position(struct s42_block *b, int axis) { return axis >= 0 && axis < 4 ? b->s->m.pos[axis] : 0; }
static double h_time(struct s42_block *b) { return b->s->m.t; }
static double h_axis_speed(int axis) { return mach_axis_max(axis); }

/* Is the block's motion a contour move (the core's or a plugin's)? */
int sess_contour_block(const struct session *s)
{
  const struct kp_attr *at = cur_attr(s);
  switch (at->motion) {
  case MO_G01: case MO_G02: case MO_G03: case MO_G12: case MO_G13: return 1;
  case MO_PLUGIN: {
    const struct s42_function *fn;
    return plug_find(s->plugins, 'G', at->plug_g, &fn) >= 0 && (fn->flags & S42_FN_MOTION);
  }
  default: return 0;
  }
}

/* Does the block's contour move the axis?  An arc moves both axes of its
 * plane whatever its end point (a half circle back to the same Z, a full
 * circle): the oscillating axis may not be one of them (language.md sec. 9
 * M13); otherwise a non-zero increment moves it. */
static int h_moves_axis(struct s42_block *b, int axis)
{
  const struct session *s = b->s;
  if (axis < 0 || axis >= 4 || !sess_contour_block(s))
    return 0;
  const struct kp_attr *at = cur_attr(s);
  int arc = kp_motion_arc(at->motion);
  if (arc && ((at->plane == 17 && (axis == 0 || axis == 1)) || (at->plane == 18 && (axis == 1 || axis == 2)) ||
              (at->plane == 19 && (axis == 0 || axis == 2))))
    return 1;
  return BIT(at->slots, axis) && s->mb.w[axis] != 0;
}

static int h_move(struct s42_block *b, const struct s42_move *mv)
{
  struct session *s = b->s;
  if (!mv || mv->size < sizeof *mv)
    return -1;
  for (int a = 0; a < 4; a++)
    if (!isfinite(mv->d[a]) || fabs(mv->d[a]) > 1e12)
      return -1;
  if (!isfinite(mv->length) || mv->length < 0 || !(mv->limit > 0))
    return -1;
  struct mach_out o;
  memset(&o, 0, sizeof o);
  double lim = mv->limit < MACH_AXIS_MAX ? mv->limit : MACH_AXIS_MAX;
  struct kp_block arc = s->mb;   /* a helix follows the block's arc (G12, G13): the trace says so */
  struct mach_path pa;
  int along = (arc.motion == MO_G12 || arc.motion == MO_G13) && kp_path(s->m.pos, &arc, &pa) && pa.arc;
  char msg[200];
  if (kp_mach_path_move(&s->m, along ? &pa : NULL, mv->d, mv->length, lim, s->mb.f, &o, msg, sizeof msg))
    return -1;
  for (int a = 0; a < 4; a++)
    s->mo.d[a] += o.d[a];
  s->mo.feed = o.feed;
  return 0;
}

static void h_displace(struct s42_block *b, int axis, int64_t d)
{
  struct session *s = b->s;
  if (axis < 0 || axis > 3)
    return;
  mach_displace(&s->m, axis, d);
  if (s->sink.moved)
    s->sink.moved(s->sink.ctx, s, axis, d);
}

static void h_dwell(struct s42_block *b, double sec)
{
  if (isfinite(sec) && sec > 0 && sec < 1e9)
    mach_advance(&b->s->m, sec);
}

static void h_error(struct s42_block *b, const char *code, const char *fmt, ...)
{
  if (!b) {   /* init(): why it fails (ABI 1.1) */
    char msg[240];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt ? fmt : "", ap);
    va_end(ap);
    plug_init_reason(msg);
    return;
  }
  struct session *s = b->s;
  int e = code ? err_from_code(code) : -1;
  s->perr = e > 0 ? e : S42_E_PLUGIN;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(s->perrmsg, sizeof s->perrmsg, fmt ? fmt : "", ap);
  va_end(ap);
}

static void h_warn(struct s42_block *b, const char *fmt, ...)
{
  char msg[240];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt ? fmt : "", ap);
  va_end(ap);
  sess_warn(b->s, "%s", msg);
}

static void h_log(struct s42_block *b, const char *fmt, ...)
{
  char msg[240];
  int k = snprintf(msg, sizeof msg, "%s: ", PLUG(b)->d->name);
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg + k, sizeof msg - (size_t)k, fmt ? fmt : "", ap);
  va_end(ap);
  if (b->s->sink.log)
    b->s->sink.log(b->s->sink.ctx, b->s, msg);
}

static void *h_alloc(size_t n) { return malloc(n ? n : 1); }
static void h_free(void *p) { free(p); }

static void h_directive(struct s42_block *b, const char *text)
{
  struct session *s = b->s;
  s->directive = 0;
  if (text)
    screen_set_directive(&s->scr, text);
  else
    screen_clear_directive(&s->scr);
}

static void h_mode(struct s42_block *b, int mode)
{
  b->s->scr.mode = mode == S42_MODE_MANUAL ? SCR_MANUAL : mode == S42_MODE_RESULTS ? SCR_RESULTS : SCR_AUTO;
}

/* ABI 1.1: the machine's own texts, options, messages and results */
static const char *h_text(struct s42_block *b, int msg)
{
  static const int ids[] = {
    [S42_MSG_PROBE_SECTION1] = MSG_PROBE1, [S42_MSG_SEARCH_SECTION1] = MSG_SEARCH1,
    [S42_MSG_PROBE_SECTION2] = MSG_PROBE2, [S42_MSG_SEARCH_SECTION2] = MSG_SEARCH2,
    [S42_MSG_RETRACT_PROBE] = MSG_RETRACT, [S42_MSG_HAND_LEFT] = MSG_HANDL, [S42_MSG_HAND_RIGHT] = MSG_HANDR,
  };
  if (msg < 1 || msg >= (int)(sizeof ids / sizeof ids[0]))
    return NULL;
  return screen_msg_text(ids[msg], b ? b->s->en : 0);
}

static void h_message(struct s42_block *b, const char *text)
{
  if (text)
    screen_message(&b->s->scr, text);
}

static int h_results(struct s42_block *b, const struct s42_results *r)
{
  if (!r || r->size < sizeof *r)
    return -1;
  return screen_p5_set(&b->s->scr, r->teeth, r->steps, r->lead, r->tk, r->ug, r->hand);
}

static const struct s42_host host = {
  .size = sizeof(struct s42_host),
  .abi_major = S42_ABI_MAJOR,
  .abi_minor = S42_ABI_MINOR,
  .number = h_number,
  .has_g = h_has_g,
  .has_m = h_has_m,
  .plane = h_plane,
  .has_word = h_has_word,
  .word = h_word,
  .resumed = h_resumed,
  .param = h_param,
  .set_param = h_set_param,
  .load_array = h_load_array,
  .position = h_position,
  .time = h_time,
  .axis_speed = h_axis_speed,
  .moves_axis = h_moves_axis,
  .move = h_move,
  .displace = h_displace,
  .dwell = h_dwell,
  .error = h_error,
  .warn = h_warn,
  .log = h_log,
  .alloc = h_alloc,
  .free = h_free,
  .directive = h_directive,
  .mode = h_mode,
  .option = plug_option,
  .text = h_text,
  .message = h_message,
  .results = h_results,
};

/* The plugin that owns the block's group-1 G (G12, a plugin's own G), -1. */
int sess_motion_plugin(const struct session *s)
{
  const struct kp_attr *at = cur_attr(s);
  if (!at->plugins)
    return -1;
  for (int g = 0; g < 64; g++)
    if (BIT(at->g, g)) {
      const struct s42_function *fn;
      int i = plug_find(s->plugins, 'G', g, &fn);
      if (i >= 0 && fn->group == 1 && (fn->flags & S42_FN_MOTION))
        return i;
    }
  return -1;
}

/* A plugin crashed since the session last looked (plugin.h, the crash
 * guard) -- in this callback, in one a host service of it ran (another's
 * advance() in its move()), or in one whose value says nothing (advance,
 * describe, reset): the block fails with its E-PLUGIN.  0, or SE_ERROR
 * with the VM failed. */
static int plug_crashed(struct session *s)
{
  const struct plug_set *ps = s->plugins;
  if (!ps || ps->crashes == s->crashes)
    return 0;
  s->crashes = ps->crashes;
  vm_fail(&s->vm, S42_E_PLUGIN, "%s", ps->v[ps->crashed].err);
  return SE_ERROR;
}

/* A callback's status: 0 to go on, or SE_ERROR with the VM failed. */
int sess_plug_status(struct session *s, int i, int r, const char *phase)
{
  if (plug_crashed(s))
    return SE_ERROR;
  if (r == S42_OK || (r > 0 && strcmp(phase, "run") == 0))
    return 0;
  if (r > 0) {
    vm_fail(&s->vm, S42_E_PLUGIN, "the %s plugin asked for the operator in %s(), which only run() may",
            s->plugins->v[i].d->name, phase);
  } else if (s->perr) {
    vm_fail(&s->vm, s->perr, "%s", s->perrmsg);
  } else {
    vm_fail(&s->vm, S42_E_PLUGIN, "the %s plugin failed in %s() without saying why", s->plugins->v[i].d->name,
            phase);
  }
  return SE_ERROR;
}

/* Call one phase of the block's plugins; 0, or SE_ERROR. */
int sess_plug_phase(struct session *s, uint32_t mask, int which)
{
  static const char *const names[] = {"check", "start", "finish"};
  if (plug_crashed(s))   /* in reset() as the plugin started, advance() in a run-down */
    return SE_ERROR;
  EACH_PLUGIN(mask, i) {
    struct plug *pl = &s->plugins->v[i];
    if (pl->state != PLUG_READY)
      continue;
    int (*cb)(void *, struct s42_block *) =
      which == 0 ? pl->d->check : which == 1 ? pl->d->start : pl->d->finish;
    if (!cb)
      continue;
    s->blk.plug = i;
    s->perr = 0;
    int e = sess_plug_status(s, i, plug_call(s->plugins, i, names[which], cb, &s->blk), names[which]);
    if (e)
      return e;
  }
  return 0;
}

/* The plugin's first block in this run: it starts afresh. */
static void mark_started(struct session *s, int i)
{
  if ((s->started >> i) & 1)
    return;
  struct plug *pl = &s->plugins->v[i];
  if (pl->d->reset)
    plug_call_reset(s->plugins, i);
  s->started |= 1u << i;
  if (s->plugins->v[i].d->flags & S42_PL_EVERY_BLOCK)
    s->every |= 1u << i;
}

/* Start the plugins the block uses (init on first use); 0 or SE_ERROR. */
int sess_plug_start_block(struct session *s, uint32_t mask)
{
  if (mask && !s->plugins) {
    vm_fail(&s->vm, S42_E_PLUGIN, "this block needs plugins and none are loaded");
    return SE_ERROR;
  }
  EACH_PLUGIN(mask, i) {
    if (plug_use(s->plugins, i, &host)) {
      vm_fail(&s->vm, S42_E_PLUGIN, "%s", s->plugins->v[i].err);
      return SE_ERROR;
    }
    mark_started(s, i);
  }
  return 0;
}

int sess_plugin_state(const struct session *s, int k, char *name, size_t nname, void *buf, size_t cap,
                      size_t *len)
{
  if (!s->plugins || k < 0 || k >= PLUG_MAX)
    return 1;
  int seen = 0;
  EACH_PLUGIN(s->started, i) {
    if (seen++ < k)
      continue;
    struct plug *pl = &s->plugins->v[i];
    if (pl->state != PLUG_READY || !pl->d->save)
      return 2;
    *len = plug_call_save(s->plugins, i, buf, cap);
    if (pl->state == PLUG_CRASHED)
      return -2;
    if (*len > cap)
      return -1;
    snprintf(name, nname, "%s", pl->d->name);
    return 0;
  }
  return 1;
}

int sess_plugin_restore(struct session *s, const char *name, const void *buf, size_t len, char *err, size_t n)
{
  int i = plug_by_name(s->plugins, name);   /* opened if this program did not need it yet */
  if (i < 0) {
    snprintf(err, n, "the restart state needs the %s plugin, which is not loaded", name);
    return -1;
  }
  struct plug *pl = &s->plugins->v[i];
  if (plug_use(s->plugins, i, &host)) {
    snprintf(err, n, "%s", pl->err);
    return -1;
  }
  mark_started(s, i);
  if (!pl->d->load || plug_call_load(s->plugins, i, buf, len) != S42_OK) {
    if (pl->state == PLUG_CRASHED)
      snprintf(err, n, "%s", pl->err);
    else
      snprintf(err, n, "the %s plugin cannot take back its saved state", name);
    return -1;
  }
  return 0;
}

static void tick(void *ctx, double dt)
{
  struct session *s = ctx;
  if (!s->plugins)
    return;
  EACH_PLUGIN(s->started, i) {
    struct plug *pl = &s->plugins->v[i];
    if (pl->state == PLUG_READY && pl->d->advance) {
      s->blk.plug = i;
      plug_call_advance(s->plugins, i, &s->blk, dt);
    }
  }
}

int sess_oscillating(const struct session *s)
{
  return strstr(s->extra, "\"osc\":\"on\"") != NULL;
}

void sess_plugin_json(const struct session *s, int what, char *buf, size_t n)
{
  size_t k = 0;
  buf[0] = 0;
  if (!s->plugins)
    return;
  EACH_PLUGIN(s->started, i) {
    struct plug *pl = &s->plugins->v[i];
    if (pl->state != PLUG_READY || !pl->d->describe || !pl->d->trace_key)
      continue;
    char v[200];
    size_t len = plug_call_describe(s->plugins, i, what, v, sizeof v);
    if (len == 0 || len >= sizeof v)
      continue;
    v[len] = 0;
    int w = snprintf(buf + k, n - k, ",\"%s\":%s", pl->d->trace_key, v);
    if (w < 0 || (size_t)w >= n - k) {
      buf[k] = 0;
      return;
    }
    k += (size_t)w;
  }
}

/* The block's plugins' run() from the one that waited (or the first), then
 * finish(); returns the session event or -1. */
int sess_run_plugins(struct session *s)
{
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  /* the block's plugins from run_next on, in index order */
  for (uint32_t todo = at->plugins & ~((1u << s->run_next) - 1); todo; todo &= todo - 1) {
    int i = __builtin_ctz(todo);
    struct plug *pl = &s->plugins->v[i];
    if (!pl->d->run || (at->motion == MO_M19 && i == sess_motion_plugin(s)))
      continue;   /* under M19 the operator's jogs make the move */
    s->blk.plug = i;
    s->perr = 0;
    int r = plug_call(s->plugins, i, "run", pl->d->run, &s->blk);
    if (r == S42_WAIT_PUSK || r == S42_WAIT_PS || r == S42_WAIT_SECTION) {
      if (plug_crashed(s))
        return SE_ERROR;
      s->run_next = i;
      s->plug_wait = 1;
      s->wait = r == S42_WAIT_PUSK ? W_PUSK : r == S42_WAIT_PS ? W_PS : W_SECTION;
      return SE_WAIT;
    }
    if (sess_plug_status(s, i, r, "run"))
      return SE_ERROR;
    s->resumed = 0;
  }
  s->plug_wait = 0;
  s->run_next = 0;
  if ((at->plugins | s->every) && sess_plug_phase(s, at->plugins | s->every, 2))
    return SE_ERROR;
  return s->rt->after(s);
}

/* The switches a MACHS block looks at (vm.h), published before every
 * vm_run: the operator, a Modbus client or a plugin may have changed them
 * since.  Only when such a block would be nothing but the switch: no row is
 * read (a trace, a plot, the pace, Modbus show every block that comes to
 * the host), no plugin runs on every block or has started (its trace
 * members are taken at each block). */
static uint32_t published_switches(const struct session *s)
{
  if (s->sink.row || s->every || s->started)
    return 0;
  return VM_SW_HELD | (s->m.corr_allowed ? KP_SW_CORR : 0) | (s->m.override_allowed ? KP_SW_OVERRIDE : 0);
}

enum sess_ev sess_run(struct session *s)
{
  if (s->state == SE_WAIT || s->state == SE_END || s->state == SE_ERROR || s->state == SE_STOPPED)
    return (enum sess_ev)s->state;
  if (!s->rt) {          /* a front end that has no runtime on the session */
    sess_refuse(s, S42_E_SUB, "this program's dialect has no runtime on the session");
    return SE_ERROR;
  }
  if (plug_crashed(s))   /* since the host last ran it: a key's work, a jog's path */
    return (enum sess_ev)(s->state = SE_ERROR);
  if (s->gate) {         /* a block starts: after the host's actions there (`at N5 mode single`) */
    s->gate = 0;
    int wait = !s->go && (s->single || (s->brk && sess_block_number(s) == s->brk));
    s->go = 0;
    if (wait) {          /* single block or the breakpoint: Пуск first */
      s->wait = W_BLOCK;
      return (enum sess_ev)(s->state = SE_WAIT);
    }
  }
  for (;;) {
    s->vm.sw = published_switches(s);
    enum vm_event ev = vm_run(&s->vm);
    int r;
    switch (ev) {
    case VM_EV_START:
      s->gate = 1;       /* single block and the breakpoint are looked at when the host comes back */
      s->rt->start(s);
      return (enum sess_ev)(s->state = SE_START);
    case VM_EV_BLOCK:
      r = s->rt->block(s);
      if (r != SE_ERROR && plug_crashed(s))   /* in advance() of a move, describe() of the row */
        r = SE_ERROR;
      if (r >= 0)
        return (enum sess_ev)(s->state = r);
      break;
    case VM_EV_END: {
      struct canon_dev d = grinder_dev(&s->m);
      struct canon_call c = canon_of(CANON_END);
      char msg[80];
      canon_do(&d, &c, msg, sizeof msg);
    }
      return (enum sess_ev)(s->state = SE_END);
    default:
      s->scr.block = sess_block_number(s);   /* the screen names the block that failed */
      return (enum sess_ev)(s->state = SE_ERROR);
    }
  }
}

/* The operator did what a plugin's run() waited for: run it again. */
static void resume_plugin(struct session *s)
{
  s->resumed++;
  s->wait = W_NONE;
  int r = sess_run_plugins(s);
  if (r >= 0)
    s->state = r;
}

int sess_key_pusk(struct session *s)
{
  if (s->state == SE_WAIT && s->wait == W_BLOCK) {
    s->wait = W_NONE;    /* the block starts; the next one waits again */
    s->state = SE_START;
    return 0;
  }
  if (s->state != SE_WAIT || (s->wait != W_PUSK && s->wait != W_SECTION))
    return -1;
  s->scr.has_message = 0;
  if (s->plug_wait) {
    resume_plugin(s);
    return 0;
  }
  s->rt->finish(s);
  return 0;
}

int sess_answer(struct session *s, long long v)
{
  if (s->state != SE_WAIT || s->wait != W_ANSWER)
    return -1;
  s->scr.has_message = 0;
  screen_field_type(&s->scr, v);
  screen_field_close(&s->scr);
  s->answer = (double)v;
  s->have_answer = 1;
  if (s->rt->answer(s))
    return 0;   /* refused: it waits for the number again */
  s->rt->finish(s);
  return 0;
}

void sess_screen(const struct session *s, uint32_t grid[SCR_ROWS][SCR_COLS])
{
  screen_render(&s->scr, s->vm.reg, s->en, grid);
}

int sess_key_ps(struct session *s)
{
  if (s->state != SE_WAIT || (s->wait != W_PS && s->wait != W_TEACH))
    return -1;
  if (s->wait == W_TEACH)
    s->rt->teach_end(s);
  s->scr.has_message = 0;   /* a message stays until the next key */
  if (s->plug_wait && s->wait == W_PS) {
    resume_plugin(s);
    return 0;
  }
  s->wait = W_PUSK;
  return 0;
}

void sess_key_exit(struct session *s)
{
  s->vm.exit_latch = 1;
}

void sess_key_stop(struct session *s)
{
  if (s->state == SE_END || s->state == SE_ERROR)
    return;
  s->state = SE_STOPPED;
}

int sess_resume(struct session *s)
{
  if (s->state != SE_STOPPED)
    return -1;
  s->state = s->wait != W_NONE ? SE_WAIT : SE_START;
  return 0;
}

/* A hand move of one axis: it stops at the travel limit, and says so. */
static int64_t stopped_jog(struct session *s, int axis, int64_t d, int correction)
{
  int64_t made = mach_jog(&s->m, axis, d, correction);
  if (made != d)
    sess_warn(s, "%c stopped at its travel limit %.3f %s (--machine): %.3f of %.3f made", mach_axes[axis].name,
         (double)s->m.pos[axis] / 1000, mach_axes[axis].unit, (double)made / 1000, (double)d / 1000);
  return made;
}

void sess_set_travel(struct session *s, const struct mach_travel *t)
{
  if (t)
    s->m.travel = s->cfg.travel = *t;
}

int sess_jog(struct session *s, int axis, int64_t d)
{
  if (s->state != SE_WAIT || axis < 0 || axis > 3)
    return -1;
  if (s->wait == W_TEACH) {
    s->rt->teach_jog(s, axis, d);
    return 0;
  }
  if (s->wait != W_PUSK && s->wait != W_PS && s->wait != W_SECTION)
    return -1;   /* jogs belong to manual mode */
  s->jogs[axis] += stopped_jog(s, axis, d, s->m.corr_allowed);
  s->has_jogs = 1;
  return 0;
}

int sess_section(struct session *s, int axis, int64_t d)
{
  if (s->state != SE_WAIT || s->wait != W_SECTION || axis < 0 || axis > 3)
    return -1;
  /* the probe's placement, not a correction of the work: M16 does not see it */
  s->jogs[axis] += stopped_jog(s, axis, d, 0);
  s->has_jogs = 1;
  return 0;
}

int sess_start_plugins(struct session *s, char *msg, size_t n, size_t *block)
{
  if (!s->plugins)
    return 0;
  uint32_t done = 0;
  for (size_t b = 0; b < s->p->nblocks; b++) {
    uint32_t mask = kp_attr(s->p, b)->plugins & ~done;
    done |= mask;
    EACH_PLUGIN(mask, i) {
      struct plug *pl = &s->plugins->v[i];
      int up = plug_use(s->plugins, i, &host);
      s->crashes = s->plugins->crashes;   /* an init() that crashed is told at the plugin's block */
      if (up == 0 || !pl->usage)
        continue;
      snprintf(msg, n, "%s", pl->reason[0] ? pl->reason : pl->err);
      *block = b;
      return -1;
    }
  }
  return 0;
}

int sess_correct(struct session *s, int axis, int64_t d)
{
  if (!s->m.corr_allowed) {
    sess_warn(s, "correction refused: operational corrections are forbidden (M23)");
    screen_message(&s->scr, screen_msg_text(MSG_NOCORR, s->en));
    return -1;
  }
  stopped_jog(s, axis, d, 1);
  return 0;
}

int sess_set_param(struct session *s, int reg, double v, char *why, size_t n)
{
  if (s->state != SE_WAIT && s->state != SE_START) {
    snprintf(why, n, "the cycle is over");
    return -1;
  }
  if (reg < 0 || reg > REG_D1) {
    snprintf(why, n, "only R0-R113 and D1 are set from the panel (TK and UG come from a tooth search, F from the program)");
    return -1;
  }
  if (reg == REG_D1 && !(v >= 0 && v <= 400000)) {
    snprintf(why, n, "D1 is 0..400000 µm, not %.10g", v);
    return -1;
  }
  if (!(fabs(v) <= 9999999)) {
    snprintf(why, n, "%.10g is beyond -9999999..9999999", v);
    return -1;
  }
  vm_set_reg(&s->vm, (unsigned)reg, v);
  return 0;
}

void sess_load_params(struct session *s, unsigned r0, unsigned n, const double *v)
{
  if (r0 < VM_NREG && n <= VM_NREG - r0)
    memcpy(&s->vm.reg[r0], v, n * sizeof *v);
}

int sess_override(struct session *s, int pct)
{
  if (!s->m.override_allowed) {
    sess_warn(s, "feed override refused: forbidden by M25");
    screen_message(&s->scr, screen_msg_text(MSG_NOOVR, s->en));
    return -1;
  }
  s->m.override_pct = pct;
  if (s->state == SE_WAIT && s->wait == W_FEED) {
    int r = s->rt->released(s);
    if (r != -2)
      s->state = r >= 0 ? r : SE_START;
  }
  return 0;
}

double sess_override_at(struct session *s, double now)
{
  return mach_override_at(&s->m, now);
}

void sess_set_single(struct session *s, int on)
{
  s->single = on != 0;
  s->vm.start_all = s->cfg.start_all || s->single || s->brk;
}

void sess_set_break(struct session *s, int n)
{
  s->brk = n > 0 ? n : 0;
  s->vm.start_all = s->cfg.start_all || s->single || s->brk;
}

const char *sess_wait_text(const struct session *s)
{
  /* for stderr, which speaks English like the rest of the diagnostics */
  const char *w;
  switch (s->wait) {
  case W_PUSK: w = "Пуск (key PUSK)"; break;
  case W_PS: w = "ПС, then Пуск (key PS, key PUSK)"; break;
  case W_TEACH: return "teach-in jogs ended by ПС (jog, key PS)";
  case W_ANSWER: return "a number in the input field (answer N)";
  case W_FEED: return "a feed override above 0 % (override N)";
  case W_BLOCK: return s->single ? "Пуск to start the block (single block; key PUSK)"
                                 : "Пуск to start the block (breakpoint; key PUSK)";
  case W_SECTION: w = "Пуск in the next section of the tooth search (section X|A moves, then key PUSK)"; break;
  default: return "nothing";
  }
  if (!s->plug_wait || !s->scr.dirtext[0])
    return w;
  /* a plugin's wait: its directive says what it is */
  static _Thread_local char buf[sizeof s->scr.dirtext + 160];
  snprintf(buf, sizeof buf, "%s with the directive \"%s\"", w, s->scr.dirtext);
  return buf;
}
