/* The 2С42 runtime on the runner (src/dialect/2c42/kprun.h): a block's
 * machine work on the grinder through the canonical table, its waits --
 * G20 manual mode, M19 teach-in, the dialog G27-G34, a plugin's -- M16's
 * correction window, M18's directive, M15's restart points, and what the
 * operator's input does in each wait.  The runner steps the VM; what a 2С42
 * block means is decided here. */
#include "kprun.h"
#include "ast.h"
#include "errors.h"
#include "messages.h"
#include "machfile.h"
#include "snapshot.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BIT(x, n) (((x) >> (n)) & 1)

void kp_warn(struct mrun *r, const char *fmt, ...)
{
  char msg[240];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  mrun_warn(r, "%s", msg);
}

static int fail(struct mrun *r, int code, const char *msg)
{
  mrun_fail(r, code, "%s", msg);
  return K_FAIL;
}

/* ---- power-on, a new cycle ---- */

static void power_on(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  mach_init(&s->m);
  s->m.tick = kp_tick;
  s->m.tick_ctx = r;
  s->m.out = mrun_sink(r);
  s->m.travel = s->travel;
  s->m.override_pct = r->override;
  screen_init(&s->scr);
  s->en = s->scr.en = r->cfg.en;
  s->blk.r = r;
  s->plugins = r->p ? ((const struct kp_ext *)r->p->ext)->plugins : NULL;
}

static void reset(struct mrun *r)
{
  power_on(r);
}

/* A new cycle of the same program (reset; Пуск after M2): a fresh machine
 * at block 1, with R0-R113 as they were (the 2С42 keeps its parameters),
 * the travel, the override, Рус kept. */
static void renew(struct mrun *r, const double *reg)
{
  struct kp_state *s = kp_st(r);
  struct mach_travel travel = s->travel;
  int cyr = s->scr.cyr;
  memset(s, 0, sizeof *s);
  s->travel = travel;
  power_on(r);
  s->scr.cyr = cyr;
  memcpy(r->vm.reg, reg, 114 * sizeof *reg);
}

/* ---- the block ---- */

/* The blocks that open M16's correction window when they start: G20, M19
 * and the dialog (language.md sec. 14). */
static int window_block(const struct kp_attr *at)
{
  return at->motion == MO_G20 || at->motion == MO_M19 || at->motion == MO_DIALOG || BIT(at->m, 27) ||
         BIT(at->m, 28) || BIT(at->m, 29);
}

void kp_emit_row(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  /* the plugins' members: the hosts read them after the block too (the
   * view's oscillation); nothing to do when no plugin has started */
  if (s->started)
    kp_plugin_json(r, S42_DESCRIBE_TRACE, s->extra, sizeof s->extra);
  else
    s->extra[0] = 0;
  if (!r->cfg.rows && !r->cfg.every)
    return;   /* nothing reads it: no row is built */
  const struct kp_attr *at = kp_attr(r->p, r->vm.cur);
  struct kp_row *w = &s->row;
  w->motion = kp_motion_name[at->motion];
  if (at->motion == MO_PLUGIN) {
    snprintf(s->gname, sizeof s->gname, "G%02d", at->plug_g % 100);
    w->motion = s->gname;
  }
  memcpy(w->d, s->mo.d, sizeof w->d);
  w->f = r->vm.reg[REG_F];
  w->feed = s->mo.feed;
  w->t = s->m.t;
  w->v = s->mo.v;
  w->has_v = s->mo.has_v;
  w->override_pct = s->m.override_allowed ? s->m.override_pct : 100;
  memcpy(w->jogs, s->jogs, sizeof w->jogs);
  w->has_jogs = s->has_jogs;
}

/* The rest of a block after its machine work and waits: M16, the row. */
static int finish_block(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  const struct kp_more *at = kp_more(r->p, kp_attr(r->p, r->vm.cur));
  const struct kp_ext *x = r->p->ext;
  for (uint32_t i = 0; i < at->nm16; i++) {
    const struct m16_item *it = &x->m16[at->m16 + i];
    int axis = it->axis == 'X' ? 0 : it->axis == 'Y' ? 1 : it->axis == 'Z' ? 2 : 3;
    vm_set_reg(&r->vm, it->reg, (double)(it->sign * s->m.corr[axis]));
  }
  if (at->nm16)
    memset(s->m.corr, 0, sizeof s->m.corr);   /* a correction is recorded once: a new window */
  kp_emit_row(r);
  s->scr.mode = SCR_AUTO;
  return K_DONE;
}

/* G28: check the number the G27 took against |min|..|max| and store it, or
 * show why not and ask again.  K_WAIT, or -1 when stored. */
static int g28_check(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  const struct kp_more *at = kp_more(r->p, kp_attr(r->p, r->vm.cur));
  double v = fabs(s->answer);
  int msg = -1;
  if (v < r->vm.w[SL_MIN])
    msg = MSG_BELOW;
  else if (v > r->vm.w[SL_MAX])
    msg = MSG_ABOVE;
  if (msg >= 0) {
    screen_message(&s->scr, screen_msg_text(msg, s->en));
    screen_field_reopen(&s->scr);
    return mrun_wait(r, MRW_ANSWER);
  }
  vm_set_reg(&r->vm, (unsigned)at->g28reg, s->answer);
  s->have_answer = 0;
  return -1;
}

/* The dialog and display functions of the block (language.md sec. 13):
 * K_WAIT, K_FAIL, or -1 to finish the block. */
static int dialog(struct mrun *r, const struct kp_attr *at)
{
  struct kp_state *s = kp_st(r);
  const struct kp_more *mo = kp_more(r->p, at);
  if (BIT(at->m, 29))
    s->scr.fixed = -1;
  if (BIT(at->m, 28))
    s->scr.at_fixed = 1;
  if (BIT(at->g, 33))
    screen_center(&s->scr, kp_str(r->p, mo->g33));
  if (BIT(at->g, 29)) {
    const struct kp_ext *x = r->p->ext;
    if (!s->m15_seen)
      screen_p3_clear(&s->scr);
    for (uint32_t i = 0; i < mo->ng29; i++)
      screen_p3_add(&s->scr, kp_str(r->p, x->lines[mo->g29 + i]));
    s->scr.p3 = 1;
  }
  if (BIT(at->g, 27)) {
    screen_prompt(&s->scr, kp_str(r->p, mo->g27), mo->g27form == '-');
    if (BIT(at->m, 27))
      s->scr.fixed = s->scr.last;
    return mrun_wait(r, MRW_ANSWER);
  }
  if (BIT(at->m, 27))
    s->scr.fixed = s->scr.last >= 0 ? s->scr.last : s->scr.nbuf;
  if (BIT(at->g, 28)) {
    if (!s->have_answer)
      return fail(r, S42_E_ORDER, "G28: no number was taken by a G27 before it");
    return g28_check(r);
  }
  if (BIT(at->g, 34)) {
    screen_message(&s->scr, screen_msg_text(MSG_DONE, s->en));
    return mrun_wait(r, MRW_PUSK);
  }
  return -1;
}

/* M19: set up the teach-in of the block's line or arc.  0, or K_FAIL when
 * the arc is impossible. */
static int teach_start(struct mrun *r, const struct kp_attr *at)
{
  struct kp_state *s = kp_st(r);
  memset(&s->teach, 0, sizeof s->teach);
  s->teach.junior = -1;
  for (int a = 0; a < 4; a++) {
    s->teach.given[a] = BIT(at->slots, a);
    s->teach.inc[a] = s->teach.given[a] ? s->mb.w[a] : 0;
    if (s->teach.junior < 0 && s->teach.inc[a] != 0)
      s->teach.junior = a;
  }
  int mp = kp_motion_plugin(r);
  if (mp >= 0 && s->plugins->v[mp].state == PLUG_READY && s->plugins->v[mp].d->path) {
    /* a plugin's curve (a helix): follow its path, measured along it */
    double prev[4] = {0, 0, 0, 0}, pt[4];
    s->blk.plug = mp;
    s->perr = 0;
    for (int k = 1; k <= 4096; k++) {
      if (plug_call_path(s->plugins, mp, &s->blk, k / 4096.0, pt) != S42_OK)
        return kp_plug_status(r, mp, S42_FAIL, "path");
      s->teach.len += sqrt((pt[0] - prev[0]) * (pt[0] - prev[0]) + (pt[1] - prev[1]) * (pt[1] - prev[1]) +
                           (pt[2] - prev[2]) * (pt[2] - prev[2]) + (pt[3] - prev[3]) * (pt[3] - prev[3]));
      memcpy(prev, pt, sizeof prev);
    }
    s->teach.plug = mp + 1;
    if (s->teach.junior < 0)   /* a closed path: the plane's first axis drives it */
      s->teach.junior = at->plane == 18 ? AX_Y : AX_X;
    return 0;
  }
  if (BIT(at->g, 2) || BIT(at->g, 3)) {
    struct kp_block ab = s->mb;
    char msg[200];
    double len, ys;
    ab.motion = BIT(at->g, 2) ? MO_G02 : MO_G03;
    int e = kp_mach_arc(&ab, &len, &ys, msg, sizeof msg);
    if (e)
      return fail(r, e, msg);
    int p = at->plane == 18 ? AX_Y : AX_X, q = at->plane == 17 ? AX_Y : AX_Z;
    s->teach.arc = 1;
    s->teach.p = p;
    s->teach.q = q;
    s->teach.cp = s->mb.w[SL_I + p];
    s->teach.cq = s->mb.w[SL_I + q];
    s->teach.r = hypot(s->teach.cp, s->teach.cq);
    s->teach.th0 = s->teach.th = atan2(-s->teach.cq, -s->teach.cp);
    s->teach.ccw = BIT(at->g, 3);
    if (s->teach.junior < 0)   /* a full circle: the plane's first axis drives it */
      s->teach.junior = s->teach.given[p] ? p : q;
  }
  return 0;
}

/* A hand move of one axis: it stops at the travel limit, and says so. */
static int64_t stopped_jog(struct mrun *r, int axis, int64_t d, int correction, int kind)
{
  struct kp_state *s = kp_st(r);
  int64_t made = mach_jog(&s->m, axis, d, correction);
  if (made != d)
    kp_warn(r, "%c stopped at its travel limit %.3f %s (--machine): %.3f of %.3f made", mach_axes[axis].name,
            (double)s->m.pos[axis] / 1000, mach_axes[axis].unit, (double)made / 1000, (double)d / 1000);
  if (made)
    mrun_moved(r, kind, axis, made, (int64_t[CANON_AXES]){s->m.pos[0], s->m.pos[1], s->m.pos[2], s->m.pos[3]},
               s->m.t);
  return made;
}

/* M19: a jog of `axis` by d.  The junior axis drives the programmed move
 * (in its direction when the signs agree, backwards otherwise); another axis
 * of the block moves nothing; an axis not in the block moves alone. */
static void teach_jog(struct mrun *r, int axis, int64_t d)
{
  struct kp_state *s = kp_st(r);
  double step[4] = {0, 0, 0, 0};
  if (!s->teach.given[axis] || s->teach.junior < 0) {
    step[axis] = (double)d;
  } else if (axis != s->teach.junior) {
    return;
  } else if (s->teach.plug && s->teach.len > 0) {
    /* the jog is the path length along the plugin's curve */
    double inc = s->teach.inc[axis], from[4], to[4];
    int forward = inc == 0 || (d > 0) == (inc > 0);
    double u1 = s->teach.u + fabs((double)d) / s->teach.len * (forward ? 1 : -1);
    s->blk.plug = s->teach.plug - 1;
    if (plug_call_path(s->plugins, s->teach.plug - 1, &s->blk, s->teach.u, from) != S42_OK ||
        plug_call_path(s->plugins, s->teach.plug - 1, &s->blk, u1, to) != S42_OK)
      return;
    s->teach.u = u1;
    for (int a = 0; a < 4; a++)
      step[a] = to[a] - from[a];
  } else if (!s->teach.arc) {
    for (int a = 0; a < 4; a++)
      step[a] = s->teach.inc[a] * (double)d / s->teach.inc[axis];
  } else {
    /* the jog is the path length along the arc */
    double inc = s->teach.inc[axis];
    int forward = inc == 0 || (d > 0) == (inc > 0);
    double dth = fabs((double)d) / s->teach.r * (forward ? 1 : -1) * (s->teach.ccw ? 1 : -1);
    double th1 = s->teach.th + dth;
    double rr = s->teach.r;
    step[s->teach.p] = rr * (cos(th1) - cos(s->teach.th));
    step[s->teach.q] = rr * (sin(th1) - sin(s->teach.th));
    s->teach.th = th1;
  }
  /* the axes move together: a step that would take one past its travel
   * is not made at all (the others would leave the programmed path) */
  int64_t dd[4];
  for (int a = 0; a < 4; a++)
    dd[a] = step[a] == 0 ? 0 : (int64_t)llround(s->teach.exact[a] + step[a]) - s->teach.moved[a];
  if (!mach_in_travel(&s->m, dd)) {
    kp_warn(r, "the jog would take an axis past its travel limit (--machine): not made");
    return;
  }
  for (int a = 0; a < 4; a++) {
    if (step[a] == 0)
      continue;
    s->teach.exact[a] += step[a];
    s->teach.moved[a] += dd[a];
    mach_jog(&s->m, a, dd[a], s->m.corr_allowed);
    s->jogs[a] += dd[a];
    if (dd[a])
      mrun_moved(r, MRV_TEACH, a, dd[a], (int64_t[CANON_AXES]){s->m.pos[0], s->m.pos[1], s->m.pos[2], s->m.pos[3]},
                 s->m.t);
  }
  s->has_jogs = 1;
}

/* M19 ended with ПС: the bare-parameter axis words take the moves made. */
static void teach_end(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  const struct kp_attr *at = kp_attr(r->p, r->vm.cur);
  for (int a = 0; a < 4; a++)
    if (at->bare[a]) {
      int reg = abs(at->bare[a]) - 1;
      vm_set_reg(&r->vm, (unsigned)reg, at->bare[a] > 0 ? (double)s->teach.moved[a] : -(double)s->teach.moved[a]);
    }
}

int kp_after_motion(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  const struct kp_attr *at = kp_attr(r->p, r->vm.cur);
  s->cont = KC_FINISH;
  if (BIT(at->m, 15))
    s->m15_seen = 1;
  if (BIT(at->m, 21)) {
    s->directive = 0;
    screen_clear_directive(&s->scr);
  }
  const uint32_t m18 = kp_more(r->p, at)->m18;
  if (m18) {
    s->directive = m18;
    screen_set_directive(&s->scr, kp_str(r->p, m18));
  }
  if (at->motion == MO_G20) {
    s->scr.mode = SCR_MANUAL;
    return mrun_wait(r, m18 ? MRW_PS : MRW_PUSK);
  }
  if (at->motion == MO_M19) {
    if (teach_start(r, at) == K_FAIL)
      return K_FAIL;
    s->scr.mode = SCR_MANUAL;
    return mrun_wait(r, MRW_TEACH);
  }
  if (window_block(at)) {
    int e = dialog(r, at);
    if (e != -1)
      return e;
  }
  return finish_block(r);
}

/* The block's machine work proper, once nothing holds it. */
static int exec_block(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  const struct kp_attr *at = kp_attr(r->p, r->vm.cur);
  kp_mach_modal(&s->m, &s->mb);
  if (kp_plug_phase(r, at->plugins | s->every, 1))
    return K_FAIL;
  char msg[200];
  int e = kp_mach_motion(&s->m, &s->mb, &s->mo, msg, sizeof msg);
  if (e)
    return fail(r, e, msg);
  s->run_next = 0;
  s->resumed = 0;
  if (!(at->plugins | s->every)) {   /* what kp_run_plugins does without plugins */
    s->plug_wait = 0;
    return kp_after_motion(r);
  }
  return kp_run_plugins(r);
}

/* A contour move, the core's or a plugin's, waits at a feed override of 0 %. */
static int held(const struct mrun *r)
{
  const struct kp_state *s = kp_st(r);
  int mo = s->mb.motion;   /* a block without a motion is no contour move: no call */
  if (mo != MO_G01 && mo != MO_G02 && mo != MO_G03 && mo != MO_G12 && mo != MO_G13 && mo != MO_PLUGIN)
    return 0;
  return kp_contour_block(r) && mach_held(&s->m, kp_mach_moves(&s->mb));
}

/* The M words whose machine work is a switch (kp_mach_modal), a mark or
 * the VM's alone (M2, M17, M20's TRUNC). */
#define LEAN_M (1u << 2 | 1u << 3 | 1u << 4 | 1u << 5 | 1u << 15 | 1u << 17 | 1u << 20 | 1u << 22 | 1u << 23 | \
                1u << 25 | 1u << 26)

/* A block with no motion, no plugin, no wait, no window, no M16, M18 or
 * M21: what is left of exec_block, after_motion and finish_block for it is
 * lean_rest, so that such a block (an M word, a sub's M17) costs a few
 * stores more than one that does not come to the runtime (issue 18). */
static inline int lean_block(const struct kp_state *s, const struct program *p, const struct kp_attr *at)
{
  return at->motion == MO_NONE && !(at->m & ~LEAN_M) && !(at->plugins | s->every) &&
         (!at->more || (!kp_more(p, at)->nm16 && !kp_more(p, at)->m18));
}

static int lean_rest(struct mrun *r, const struct kp_attr *at)
{
  struct kp_state *s = kp_st(r);
  memset(s->jogs, 0, sizeof s->jogs);
  s->has_jogs = 0;
  memcpy(s->start, s->m.pos, sizeof s->start);
  kp_mach_modal(&s->m, &s->mb);
  memset(&s->mo, 0, sizeof s->mo);   /* kp_mach_motion without a motion */
  s->run_next = 0;
  s->resumed = 0;
  s->plug_wait = 0;
  if (BIT(at->m, 15))
    s->m15_seen = 1;
  kp_emit_row(r);                    /* finish_block without M16 */
  s->scr.mode = SCR_AUTO;
  return K_DONE;
}

/* VM_EV_BLOCK: do the block's machine work. */
static int block_work(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  const struct kp_attr *at = kp_attr(r->p, r->vm.cur);
  char msg[200];
  uint32_t number = r->p->blocks[r->vm.cur].number;
  s->scr.block = number ? (int)number : -1;
  if (r->vm.clamped) {
    const struct prog_rule *ru = &r->p->rules[r->vm.clamped - 1];
    kp_warn(r, "%s%.10g is over %.0f: clamped to %.0f", ru->name, r->vm.clamped_from, ru->hi, ru->hi);
    r->vm.clamped = 0;
  }
  /* a G20, M19 or dialog block opens M16's correction window as it starts:
   * at its VM_EV_START when the host acted there (an `at` correction is
   * in the window), else here; a PP jump opens none (language.md sec. 14) */
  int lean = lean_block(s, r->p, at);   /* no window_block among them */
  if (!lean && window_block(at) && !s->window_opened)
    memset(s->m.corr, 0, sizeof s->m.corr);
  s->window_opened = 0;
  struct kp_block *b = &s->mb;
  b->motion = at->motion;
  b->plane = at->plane;
  b->g = at->g;
  b->m = at->m;
  /* the words the block has, 0 the rest: only the previous block's words
   * can be non-zero there (this is the only place mb is written) */
  for (uint32_t sl = b->given & ~at->slots; sl; sl &= sl - 1)
    b->w[__builtin_ctz(sl)] = 0.0;
  for (uint32_t sl = at->slots; sl; sl &= sl - 1)
    b->w[__builtin_ctz(sl)] = r->vm.w[__builtin_ctz(sl)];
  b->given = at->slots;
  b->f = r->vm.reg[REG_F];
  b->d1 = r->vm.reg[REG_D1];
  int e = kp_mach_check(&s->m, b, msg, sizeof msg);
  if (e)
    return fail(r, e, msg);
  if (lean)
    return lean_rest(r, at);
  if (at->plugins | s->every) {
    if (kp_plug_start_block(r, at->plugins) || kp_plug_phase(r, at->plugins | s->every, 0))
      return K_FAIL;
  }
  memset(s->jogs, 0, sizeof s->jogs);
  s->has_jogs = 0;
  memcpy(s->start, s->m.pos, sizeof s->start);
  if (held(r)) {           /* feed override at 0 %: the move waits */
    s->cont = KC_EXEC;
    return mrun_wait(r, MRW_FEED);
  }
  return exec_block(r);
}

/* The block, with the crash guard's word on its plugins: one that crashed
 * since the runtime last looked (a key's work, a jog's path) or in it
 * (advance() of a move, describe() of the row) fails it. */
static int do_block(struct mrun *r)
{
  if (kp_plug_crashed(r))
    return K_FAIL;
  int e = block_work(r);
  return e != K_FAIL && kp_plug_crashed(r) ? K_FAIL : e;
}

static int resume_work(struct mrun *r);

static int resume(struct mrun *r)
{
  if (kp_plug_crashed(r))
    return K_FAIL;
  int e = resume_work(r);
  return e != K_FAIL && kp_plug_crashed(r) ? K_FAIL : e;
}

/* The wait is over: the rest of the block. */
static int resume_work(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  switch (s->cont) {
  case KC_EXEC:
    return exec_block(r);
  case KC_PLUGIN:
    s->resumed++;
    return kp_run_plugins(r);
  default:
    return finish_block(r);
  }
}

static void on_start(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  s->window_opened = window_block(kp_attr(r->p, r->vm.cur));
  if (s->window_opened)
    memset(s->m.corr, 0, sizeof s->m.corr);
}

static void on_end(struct mrun *r)
{
  struct kp_state *s = kp_st(r);
  struct canon_dev d = grinder_dev(&s->m);
  struct canon_call c = canon_of(CANON_END);
  char msg[80];
  canon_do(&d, &c, msg, sizeof msg);
}

static void on_failed(struct mrun *r)
{
  kp_st(r)->scr.block = mrun_block_number(r);   /* the screen names the block that failed */
}

/* ---- the operator ---- */

/* What the 2С42-65 and the ВЗ-208Ф3 have not. */
static const char *refuses(const struct mrun *r, const struct mrun_input *in)
{
  (void)r;
  if (in->kind == MRI_ZERO)
    return "the ВЗ-208Ф3 has no part zero to set (that is the lathe's)";
  if (in->kind == MRI_MODE && in->axis == MRM_SKIP)
    return "the 2С42-65 has no block skip";
  if (in->kind == MRI_MODE && in->axis == MRM_OPTSTOP)
    return "the 2С42-65 has no M01";
  return NULL;
}

static int input(struct mrun *r, const struct mrun_input *in, char *why, size_t n)
{
  struct kp_state *s = kp_st(r);
  int waiting = r->state == MR_WAIT;
  int w = waiting ? r->wait : MRW_NONE;
  switch (in->kind) {
  case MRI_PUSK:
    if (w != MRW_PUSK && w != MRW_SECTION)
      break;
    s->scr.has_message = 0;
    s->cont = s->plug_wait ? KC_PLUGIN : KC_FINISH;
    return 1;
  case MRI_PS:
    if (w == MRW_ANSWER) {   /* the number typed into the field (the panel) */
      struct mrun_input a = {.kind = MRI_ANSWER, .n = (int64_t)llround(screen_field_value(&s->scr))};
      return input(r, &a, why, n);
    }
    if (w != MRW_PS && w != MRW_TEACH)
      break;
    if (w == MRW_TEACH)
      teach_end(r);
    s->scr.has_message = 0;   /* a message stays until the next key */
    if (s->plug_wait && w == MRW_PS) {
      s->cont = KC_PLUGIN;
      return 1;
    }
    r->wait = MRW_PUSK;
    return 0;
  case MRI_ANSWER:
    if (w != MRW_ANSWER)
      break;
    s->scr.has_message = 0;
    screen_field_type(&s->scr, (long long)in->n);
    screen_field_close(&s->scr);
    s->answer = (double)in->n;
    s->have_answer = 1;
    if (BIT(kp_attr(r->p, r->vm.cur)->g, 28) && g28_check(r) == K_WAIT)
      return 0;   /* refused: it waits for the number again */
    s->cont = KC_FINISH;
    return 1;
  case MRI_JOG:
    if (in->axis < 0 || in->axis > 3)
      break;
    if (w == MRW_TEACH) {
      teach_jog(r, in->axis, in->n);
      return 0;
    }
    if (w != MRW_PUSK && w != MRW_PS && w != MRW_SECTION) {
      snprintf(why, n, "jogs belong to manual mode (G20), M19 teach-in and a tooth search's sections");
      return -1;
    }
    s->jogs[in->axis] += stopped_jog(r, in->axis, in->n, s->m.corr_allowed, MRV_JOG);
    s->has_jogs = 1;
    return 0;
  case MRI_SECTION:
    if (w != MRW_SECTION || in->axis < 0 || in->axis > 3)
      break;
    /* the probe's placement, not a correction of the work: M16 does not see it */
    s->jogs[in->axis] += stopped_jog(r, in->axis, in->n, 0, MRV_SECTION);
    if (in->axis2 >= 0 && in->axis2 <= 3)
      s->jogs[in->axis2] += stopped_jog(r, in->axis2, in->n2, 0, MRV_SECTION);
    s->has_jogs = 1;
    return 0;
  case MRI_CORRECT:
    if (in->axis < 0 || in->axis > 3)
      break;
    if (!s->m.corr_allowed) {
      kp_warn(r, "correction refused: operational corrections are forbidden (M23)");
      screen_message(&s->scr, screen_msg_text(MSG_NOCORR, s->en));
      snprintf(why, n, "operational corrections are forbidden (M23)");
      return -1;
    }
    stopped_jog(r, in->axis, in->n, 1, MRV_CORRECT);
    return 0;
  case MRI_KEY:
    /* the panel's edit keys on the screen: the field's digits, minus, ЗБ,
     * cursor, the buffer's scroll, P5's pages; and Рус (-1) */
    if (in->axis == -1) {
      s->scr.cyr = in->n != 0;
      return 0;
    }
    return screen_edit(&s->scr, in->axis, (int)in->n) ? -1 : 0;
  default:
    break;
  }
  snprintf(why, n, "the machine does not wait for it");
  return -1;
}

/* The override switch (M25 forbids it: a warning and the screen say so). */
static int override(struct mrun *r, int pct, double now, double *shift)
{
  struct kp_state *s = kp_st(r);
  *shift = 0;
  if (!s->m.override_allowed) {
    kp_warn(r, "feed override refused: forbidden by M25");
    screen_message(&s->scr, screen_msg_text(MSG_NOOVR, s->en));
    return -1;
  }
  s->m.override_pct = pct;
  if (r->state == MR_WAIT && r->wait == MRW_FEED)
    return held(r) ? 0 : 1;
  if (pct == 0)
    return mach_in_move(&s->m, now) ? 2 : 0;
  *shift = mach_override_at(&s->m, now);
  return 0;
}

/* The switches a MACHS block looks at (vm.h), published before every
 * vm_run: the operator, a Modbus client or a plugin may have changed them
 * since.  Only when such a block would be nothing but the switch: no row is
 * read (the runner asks only then), no plugin runs on every block or has
 * started (its trace members are taken at each block). */
static uint32_t switches(const struct mrun *r)
{
  const struct kp_state *s = kp_st(r);
  if (s->every || s->started)
    return 0;
  return VM_SW_HELD | (s->m.corr_allowed ? KP_SW_CORR : 0) | (s->m.override_allowed ? KP_SW_OVERRIDE : 0);
}

static int restart_point(const struct mrun *r, uint32_t b)
{
  return BIT(kp_attr(r->p, b)->m, 15);
}

static const char *wait_text(const struct mrun *r, char *buf, size_t n)
{
  /* for stderr, which speaks English like the rest of the diagnostics */
  const struct kp_state *s = kp_st(r);
  const char *w;
  switch (r->wait) {
  case MRW_PUSK: w = "Пуск (key PUSK)"; break;
  case MRW_PS: w = "ПС, then Пуск (key PS, key PUSK)"; break;
  case MRW_SECTION: w = "Пуск in the next section of the tooth search (section X|A moves, then key PUSK)"; break;
  case MRW_TEACH: return "teach-in jogs ended by ПС (jog, key PS)";
  case MRW_ANSWER: return "a number in the input field (answer N)";
  case MRW_FEED: return "a feed override above 0 % (override N)";
  default: return NULL;   /* the runner's words */
  }
  if (!s->plug_wait || !s->scr.dirtext[0])
    return w;
  /* a plugin's wait: its directive says what it is */
  snprintf(buf, n, "%s with the directive \"%s\"", w, s->scr.dirtext);
  return buf;
}

static int prepare(struct mrun *r, char *why, size_t n, uint32_t *block)
{
  return kp_start_plugins(r, why, n, block);
}

static double time_of(const struct mrun *r)
{
  return kp_st(r)->m.t;
}

static void position(const struct mrun *r, int64_t pos[CANON_AXES])
{
  memset(pos, 0, CANON_AXES * sizeof *pos);
  memcpy(pos, kp_st(r)->m.pos, 4 * sizeof *pos);
}

static void info(const struct mrun *r, struct canon_info *in)
{
  grinder_ops.info(r->st ? &kp_st(r)->m : NULL, in);
}

static void show(struct mrun *r, const char *text)
{
  screen_message(&kp_st(r)->scr, text);
}

int kp_set_param(struct mrun *r, int reg, double v, char *why, size_t n);

int kp_set_param(struct mrun *r, int reg, double v, char *why, size_t n)
{
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
  vm_set_reg(&r->vm, (unsigned)reg, v);
  return 0;
}

/* A file the grinder reads: --machine (the travel); --tools is a lathe's. */
static int load(struct mrun *r, const char *what, const char *text, size_t len, const char *file, char *err,
                size_t nerr)
{
  struct kp_state *s = kp_st(r);
  if (strcmp(what, "tools") == 0) {
    snprintf(err, nerr, "--tools is a lathe's tool table; the 2С42's tooth-search tool model is --tool");
    return -2;
  }
  if (strcmp(what, "machine") != 0) {
    snprintf(err, nerr, "the grinder reads no %s file", what);
    return -2;
  }
  char *buf = NULL;
  size_t blen = 0;
  FILE *f = open_memstream(&buf, &blen);
  if (!f) {
    snprintf(err, nerr, "out of memory");
    return -1;
  }
  int bad = machfile_parse(text, len, file, &s->travel, f);
  fclose(f);
  if (blen && buf[blen - 1] == '\n')
    buf[--blen] = 0;
  snprintf(err, nerr, "%s", buf ? buf : "");
  free(buf);
  if (bad)
    return -1;
  s->m.travel = s->travel;
  return 0;
}

static const char *const pages[] = {"screen", NULL};

const struct mrun_rt kp_mrun_runtime = {
  .size = sizeof(struct kp_state),
  .machine = "ВЗ-208Ф3",
  .reset = reset,
  .renew = renew,
  .prepare = prepare,
  .start = on_start,
  .block = do_block,
  .input = input,
  .resume = resume,
  .refuses = refuses,
  .override = override,
  .switches = switches,
  .restart_point = restart_point,
  .restart_word = "M15",
  .reg_range = kp_reg_range,
  .repeat_max = 30000,
  .save = kp_save,
  .restore = kp_restore,
  .row_json = kp_row_json,
  .row_text = kp_row_text,
  .dump_json = kp_dump_json,
  .error_machine = 1,
  .note_uk = "на екрані: ",
  .note_en = "the machine shows: ",
  .end = on_end,
  .failed = on_failed,
  .time = time_of,
  .load = load,
  .pages = pages,
  .page = kp_page,
  .screen = kp_screen,
  .position = position,
  .info = info,
  .wait_text = wait_text,
  .view = kp_view,
  .show = show,
  .set_param = kp_set_param,
};
