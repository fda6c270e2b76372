/* The host side of the plugin ABI (include/s42_plugin.h) for a 2С42 run on
 * the runner (kprun.h): what a plugin's callbacks may read and do of the
 * block, the machine and the screen, and the block's phases through the
 * crash guard of plugin.c.  A plugin changes the VM only through the VM's
 * journaled calls. */
#include "kprun.h"
#include "ast.h"
#include "errors.h"
#include "messages.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BIT(x, n) (((x) >> (n)) & 1)

#define ST(b) kp_st((b)->r)
#define PLUG(b) (&ST(b)->plugins->v[(b)->plug])
/* The plugins of mask (bit i: plugin i), in index order: the work is the
 * plugins in use, not PLUG_MAX. */
#define EACH_PLUGIN(mask, i) \
  for (uint32_t each_ = (mask), i = 0; each_ && (i = (uint32_t)__builtin_ctz(each_), 1); each_ &= each_ - 1)

static const struct kp_attr *cur_attr(const struct mrun *r)
{
  return kp_attr(r->p, r->vm.cur);
}

static int h_number(struct s42_block *b) { return mrun_block_number(b->r); }
static int h_has_g(struct s42_block *b, int g) { return g >= 0 && g < 64 && BIT(cur_attr(b->r)->g, g); }
static int h_has_m(struct s42_block *b, int m) { return m >= 0 && m < 32 && BIT(cur_attr(b->r)->m, m); }
static int h_plane(struct s42_block *b) { return cur_attr(b->r)->plane; }

/* The slot of a word letter, or -1; F: the slot its value went to. */
static int word_slot(const struct mrun *r, char l)
{
  const struct kp_attr *at = cur_attr(r);
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
  const struct kp_attr *at = cur_attr(b->r);
  int sl = word_slot(b->r, l);
  if (sl >= 0)
    return BIT(at->slots, sl);
  return l == 'F' && at->has_f;
}

static double h_word(struct s42_block *b, char l)
{
  if (!h_has_word(b, l))
    return 0;
  int sl = word_slot(b->r, l);
  return sl >= 0 ? ST(b)->mb.w[sl] : b->r->vm.reg[REG_F];
}

static int h_resumed(struct s42_block *b) { return ST(b)->resumed; }

static double h_param(struct s42_block *b, int n)
{
  return n >= 0 && n < VM_NREG ? b->r->vm.reg[n] : 0;
}

/* A plugin changes the VM only through the VM's journaled calls, so a block
 * that fails after it wrote leaves the registers and arrays as after the
 * previous block (language.md sec. 7), as the program's own words do. */
static int h_set_param(struct s42_block *b, int n, double v)
{
  if (n < 0 || n > REG_F || !isfinite(v))
    return -1;
  vm_set_reg(&b->r->vm, (unsigned)n, v);
  return 0;
}

static int h_load_array(struct s42_block *b, int array, const double *v, int n)
{
  if (array < 1 || array > (int)b->r->p->lim.arrays || n < 0 || n > (int)b->r->p->lim.cells || (n && !v))
    return -1;
  for (int i = 0; i < n; i++)   /* the cells' range, as array words have it (E-RANGE) */
    if (!(fabs(v[i]) <= 9999999))
      return -1;
  vm_load_array(&b->r->vm, array - 1, v, n);
  return 0;
}

static int64_t h_position(struct s42_block *b, int axis) { return axis >= 0 && axis < 4 ? ST(b)->m.pos[axis] : 0; }
static double h_time(struct s42_block *b) { return ST(b)->m.t; }
static double h_axis_speed(int axis) { return mach_axis_max(axis); }

/* Is the block's motion a contour move (the core's or a plugin's)? */
int kp_contour_block(const struct mrun *r)
{
  const struct kp_state *s = kp_st(r);
  const struct kp_attr *at = cur_attr(r);
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
  const struct kp_state *s = ST(b);
  if (axis < 0 || axis >= 4 || !kp_contour_block(b->r))
    return 0;
  const struct kp_attr *at = cur_attr(b->r);
  int arc = kp_motion_arc(at->motion);
  if (arc && ((at->plane == 17 && (axis == 0 || axis == 1)) || (at->plane == 18 && (axis == 1 || axis == 2)) ||
              (at->plane == 19 && (axis == 0 || axis == 2))))
    return 1;
  return BIT(at->slots, axis) && s->mb.w[axis] != 0;
}

static int h_move(struct s42_block *b, const struct s42_move *mv)
{
  struct kp_state *s = ST(b);
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
  if (kp_mach_path_move(&s->m, along ? &pa : NULL, mv->d, mv->length, lim, s->mb.f, &o, msg, sizeof msg)) {
    snprintf(s->perrmsg, sizeof s->perrmsg, "%s", msg);
    return -1;
  }
  for (int a = 0; a < 4; a++)
    s->mo.d[a] += o.d[a];
  s->mo.feed = o.feed;
  return 0;
}

static void h_displace(struct s42_block *b, int axis, int64_t d)
{
  struct kp_state *s = ST(b);
  if (axis < 0 || axis > 3)
    return;
  mach_displace(&s->m, axis, d);
  mrun_moved(b->r, MRV_DISPLACE, axis, d, (int64_t[CANON_AXES]){s->m.pos[0], s->m.pos[1], s->m.pos[2], s->m.pos[3]},
             s->m.t);
}

static void h_dwell(struct s42_block *b, double sec)
{
  if (isfinite(sec) && sec > 0 && sec < 1e9)
    mach_advance(&ST(b)->m, sec);
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
  struct kp_state *s = ST(b);
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
  kp_warn(b->r, "%s", msg);
}

static void h_log(struct s42_block *b, const char *fmt, ...)
{
  char msg[240];
  int k = snprintf(msg, sizeof msg, "%s: ", PLUG(b)->d->name);
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg + k, sizeof msg - (size_t)k, fmt ? fmt : "", ap);
  va_end(ap);
  mrun_log(b->r, msg);
}

static void *h_alloc(size_t n) { return malloc(n ? n : 1); }
static void h_free(void *p) { free(p); }

static void h_directive(struct s42_block *b, const char *text)
{
  struct kp_state *s = ST(b);
  s->directive = 0;
  if (text)
    screen_set_directive(&s->scr, text);
  else
    screen_clear_directive(&s->scr);
}

static void h_mode(struct s42_block *b, int mode)
{
  ST(b)->scr.mode = mode == S42_MODE_MANUAL ? SCR_MANUAL : mode == S42_MODE_RESULTS ? SCR_RESULTS : SCR_AUTO;
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
  return screen_msg_text(ids[msg], b ? ST(b)->en : 0);
}

static void h_message(struct s42_block *b, const char *text)
{
  if (text)
    screen_message(&ST(b)->scr, text);
}

static int h_results(struct s42_block *b, const struct s42_results *r)
{
  if (!r || r->size < sizeof *r)
    return -1;
  return screen_p5_set(&ST(b)->scr, r->teeth, r->steps, r->lead, r->tk, r->ug, r->hand);
}

const struct s42_host kp_host = {
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
int kp_motion_plugin(const struct mrun *r)
{
  const struct kp_state *s = kp_st(r);
  const struct kp_attr *at = cur_attr(r);
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
 * describe, reset): the block fails with its E-PLUGIN.  0, or K_FAIL
 * with the VM failed. */
int kp_plug_crashed(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  const struct plug_set *ps = s->plugins;
  if (!ps || ps->crashes == s->crashes)
    return 0;
  s->crashes = ps->crashes;
  vm_fail(&r->vm, S42_E_PLUGIN, "%s", ps->v[ps->crashed].err);
  return K_FAIL;
}

/* A callback's status: 0 to go on, or K_FAIL with the VM failed. */
int kp_plug_status(struct mrun *rn, int i, int r, const char *phase)
{
  struct kp_state *s = kp_st(rn);
  if (kp_plug_crashed(rn))
    return K_FAIL;
  if (r == S42_OK || (r > 0 && strcmp(phase, "run") == 0))
    return 0;
  if (r > 0) {
    vm_fail(&rn->vm, S42_E_PLUGIN, "the %s plugin asked for the operator in %s(), which only run() may",
            s->plugins->v[i].d->name, phase);
  } else if (s->perr) {
    vm_fail(&rn->vm, s->perr, "%s", s->perrmsg);
  } else {
    vm_fail(&rn->vm, S42_E_PLUGIN, "the %s plugin failed in %s() without saying why", s->plugins->v[i].d->name,
            phase);
  }
  return K_FAIL;
}

/* Call one phase of the block's plugins; 0, or K_FAIL. */
int kp_plug_phase(struct mrun *r, uint32_t mask, int which)
{
  struct kp_state *s = kp_st(r);
  static const char *const names[] = {"check", "start", "finish"};
  if (kp_plug_crashed(r))   /* in reset() as the plugin started, advance() in a run-down */
    return K_FAIL;
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
    int e = kp_plug_status(r, i, plug_call(s->plugins, i, names[which], cb, &s->blk), names[which]);
    if (e)
      return e;
  }
  return 0;
}

/* The plugin's first block in this run: it starts afresh. */
static void mark_started(struct kp_state *s, int i)
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

/* Start the plugins the block uses (init on first use); 0 or K_FAIL. */
int kp_plug_start_block(struct mrun *r, uint32_t mask)
{
  struct kp_state *s = kp_st(r);
  if (mask && !s->plugins) {
    vm_fail(&r->vm, S42_E_PLUGIN, "this block needs plugins and none are loaded");
    return K_FAIL;
  }
  EACH_PLUGIN(mask, i) {
    if (plug_use(s->plugins, i, &kp_host)) {
      vm_fail(&r->vm, S42_E_PLUGIN, "%s", s->plugins->v[i].err);
      return K_FAIL;
    }
    mark_started(s, i);
  }
  return 0;
}

int kp_plugin_state(const struct mrun *r, int k, char *name, size_t nname, void *buf, size_t cap, size_t *len)
{
  const struct kp_state *s = kp_st(r);
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

int kp_plugin_restore(struct mrun *r, const char *name, const void *buf, size_t len, char *err, size_t n)
{
  struct kp_state *s = kp_st(r);
  int i = plug_by_name(s->plugins, name);   /* opened if this program did not need it yet */
  if (i < 0) {
    snprintf(err, n, "the restart state needs the %s plugin, which is not loaded", name);
    return -1;
  }
  struct plug *pl = &s->plugins->v[i];
  if (plug_use(s->plugins, i, &kp_host)) {
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

void kp_tick(void *ctx, double dt)
{
  struct kp_state *s = kp_st(ctx);
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

void kp_plugin_json(const struct mrun *r, int what, char *buf, size_t n)
{
  const struct kp_state *s = kp_st(r);
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
 * finish(); K_*. */
int kp_run_plugins(struct mrun *rn)
{
  struct kp_state *s = kp_st(rn);
  const struct kp_attr *at = kp_attr(rn->p, rn->vm.cur);
  /* the block's plugins from run_next on, in index order */
  for (uint32_t todo = at->plugins & ~((1u << s->run_next) - 1); todo; todo &= todo - 1) {
    int i = __builtin_ctz(todo);
    struct plug *pl = &s->plugins->v[i];
    if (!pl->d->run || (at->motion == MO_M19 && i == kp_motion_plugin(rn)))
      continue;   /* under M19 the operator's jogs make the move */
    s->blk.plug = i;
    s->perr = 0;
    int r = plug_call(s->plugins, i, "run", pl->d->run, &s->blk);
    if (r == S42_WAIT_PUSK || r == S42_WAIT_PS || r == S42_WAIT_SECTION) {
      if (kp_plug_crashed(rn))
        return K_FAIL;
      s->run_next = i;
      s->plug_wait = 1;
      s->cont = KC_PLUGIN;
      return mrun_wait(rn, r == S42_WAIT_PUSK ? MRW_PUSK : r == S42_WAIT_PS ? MRW_PS : MRW_SECTION);
    }
    if (kp_plug_status(rn, i, r, "run"))
      return K_FAIL;
    s->resumed = 0;
  }
  s->plug_wait = 0;
  s->run_next = 0;
  if ((at->plugins | s->every) && kp_plug_phase(rn, at->plugins | s->every, 2))
    return K_FAIL;
  return kp_after_motion(rn);
}

int kp_start_plugins(struct mrun *r, char *msg, size_t n, uint32_t *block)
{
  struct kp_state *s = kp_st(r);
  if (!s->plugins)
    return 0;
  uint32_t done = 0;
  for (size_t b = 0; b < r->p->nblocks; b++) {
    uint32_t mask = kp_attr(r->p, b)->plugins & ~done;
    done |= mask;
    EACH_PLUGIN(mask, i) {
      struct plug *pl = &s->plugins->v[i];
      int up = plug_use(s->plugins, i, &kp_host);
      s->crashes = s->plugins->crashes;   /* an init() that crashed is told at the plugin's block */
      if (up == 0 || !pl->usage)
        continue;
      snprintf(msg, n, "%s", pl->reason[0] ? pl->reason : pl->err);
      *block = (uint32_t)b;
      return -1;
    }
  }
  return 0;
}
