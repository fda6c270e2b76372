/* The 2С42 runtime on the session (src/core/sess_rt.h): a block's machine
 * work on the grinder, its waits -- G20 manual mode, M19 teach-in, the
 * dialog G27-G34 -- M16's correction window, M18's directive, M15's mark,
 * and the rest of the block when a wait ends.  The session steps the VM and
 * hosts the plugins; what a 2С42 block means is decided here. */
#include "sess_rt.h"
#include "ast.h"
#include "errors.h"
#include "kp.h"
#include "messages.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BIT(x, n) (((x) >> (n)) & 1)

static int after_motion(struct session *s);

/* The blocks that open M16's correction window when they start: G20, M19
 * and the dialog (language.md sec. 14). */
static int window_block(const struct kp_attr *at)
{
  return at->motion == MO_G20 || at->motion == MO_M19 || at->motion == MO_DIALOG || BIT(at->m, 27) ||
         BIT(at->m, 28) || BIT(at->m, 29);
}

/* The rest of a block after its machine work and waits: M16, the row. */
static void finish_block(struct session *s)
{
  const struct kp_more *at = kp_more(s->p, kp_attr(s->p, s->vm.cur));
  const struct kp_ext *x = s->p->ext;
  for (uint32_t i = 0; i < at->nm16; i++) {
    const struct m16_item *it = &x->m16[at->m16 + i];
    int axis = it->axis == 'X' ? 0 : it->axis == 'Y' ? 1 : it->axis == 'Z' ? 2 : 3;
    vm_set_reg(&s->vm, it->reg, (double)(it->sign * s->m.corr[axis]));
  }
  if (at->nm16)
    memset(s->m.corr, 0, sizeof s->m.corr);   /* a correction is recorded once: a new window */
  sess_emit_row(s);
  s->wait = W_NONE;
  s->state = SE_START;
  s->scr.mode = SCR_AUTO;
}

/* G28: check the number the G27 took against |min|..|max| and store it, or
 * show why not and ask again.  Returns the session event or -1. */
static int g28_check(struct session *s)
{
  const struct kp_more *at = kp_more(s->p, kp_attr(s->p, s->vm.cur));
  double v = fabs(s->answer);
  int msg = -1;
  if (v < s->vm.w[SL_MIN])
    msg = MSG_BELOW;
  else if (v > s->vm.w[SL_MAX])
    msg = MSG_ABOVE;
  if (msg >= 0) {
    screen_message(&s->scr, screen_msg_text(msg, s->en));
    screen_field_reopen(&s->scr);
    s->wait = W_ANSWER;
    return SE_WAIT;
  }
  vm_set_reg(&s->vm, (unsigned)at->g28reg, s->answer);
  s->have_answer = 0;
  return -1;
}

/* The dialog and display functions of the block (language.md sec. 13). */
static int dialog(struct session *s, const struct kp_attr *at)
{
  const struct kp_more *mo = kp_more(s->p, at);
  if (BIT(at->m, 29))
    s->scr.fixed = -1;
  if (BIT(at->m, 28))
    s->scr.at_fixed = 1;
  if (BIT(at->g, 33))
    screen_center(&s->scr, kp_str(s->p, mo->g33));
  if (BIT(at->g, 29)) {
    const struct kp_ext *x = s->p->ext;
    if (!s->m15_seen)
      screen_p3_clear(&s->scr);
    for (uint32_t i = 0; i < mo->ng29; i++)
      screen_p3_add(&s->scr, kp_str(s->p, x->lines[mo->g29 + i]));
    s->scr.p3 = 1;
  }
  if (BIT(at->g, 27)) {
    screen_prompt(&s->scr, kp_str(s->p, mo->g27), mo->g27form == '-');
    if (BIT(at->m, 27))
      s->scr.fixed = s->scr.last;
    s->wait = W_ANSWER;
    return SE_WAIT;
  }
  if (BIT(at->m, 27))
    s->scr.fixed = s->scr.last >= 0 ? s->scr.last : s->scr.nbuf;
  if (BIT(at->g, 28)) {
    if (!s->have_answer) {
      vm_fail(&s->vm, S42_E_ORDER, "G28: no number was taken by a G27 before it");
      return SE_ERROR;
    }
    return g28_check(s);
  }
  if (BIT(at->g, 34)) {
    screen_message(&s->scr, screen_msg_text(MSG_DONE, s->en));
    s->wait = W_PUSK;
    return SE_WAIT;
  }
  return -1;
}

/* M19: set up the teach-in of the block's line or arc.  Returns -1, or
 * SE_ERROR when the arc is impossible. */
static int teach_start(struct session *s, const struct kp_attr *at)
{
  memset(&s->teach, 0, sizeof s->teach);
  s->teach.junior = -1;
  for (int a = 0; a < 4; a++) {
    s->teach.given[a] = BIT(at->slots, a);
    s->teach.inc[a] = s->teach.given[a] ? s->mb.w[a] : 0;
    if (s->teach.junior < 0 && s->teach.inc[a] != 0)
      s->teach.junior = a;
  }
  int mp = sess_motion_plugin(s);
  if (mp >= 0 && s->plugins->v[mp].state == PLUG_READY && s->plugins->v[mp].d->path) {
    /* a plugin's curve (a helix): follow its path, measured along it */
    double prev[4] = {0, 0, 0, 0}, pt[4];
    s->blk.plug = mp;
    s->perr = 0;
    for (int k = 1; k <= 4096; k++) {
      if (plug_call_path(s->plugins, mp, &s->blk, k / 4096.0, pt) != S42_OK)
        return sess_plug_status(s, mp, S42_FAIL, "path");
      s->teach.len += sqrt((pt[0] - prev[0]) * (pt[0] - prev[0]) + (pt[1] - prev[1]) * (pt[1] - prev[1]) +
                           (pt[2] - prev[2]) * (pt[2] - prev[2]) + (pt[3] - prev[3]) * (pt[3] - prev[3]));
      memcpy(prev, pt, sizeof prev);
    }
    s->teach.plug = mp + 1;
    if (s->teach.junior < 0)   /* a closed path: the plane's first axis drives it */
      s->teach.junior = at->plane == 18 ? AX_Y : AX_X;
    return -1;
  }
  if (BIT(at->g, 2) || BIT(at->g, 3)) {
    struct kp_block ab = s->mb;
    char msg[200];
    double len, ys;
    ab.motion = BIT(at->g, 2) ? MO_G02 : MO_G03;
    int e = kp_mach_arc(&ab, &len, &ys, msg, sizeof msg);
    if (e) {
      vm_fail(&s->vm, e, "%s", msg);
      return SE_ERROR;
    }
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
  return -1;
}

/* M19: a jog of `axis` by d.  The junior axis drives the programmed move
 * (in its direction when the signs agree, backwards otherwise); another axis
 * of the block moves nothing; an axis not in the block moves alone. */
static void teach_jog(struct session *s, int axis, int64_t d)
{
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
    double r = s->teach.r;
    step[s->teach.p] = r * (cos(th1) - cos(s->teach.th));
    step[s->teach.q] = r * (sin(th1) - sin(s->teach.th));
    s->teach.th = th1;
  }
  /* the axes move together: a step that would take one past its travel
   * is not made at all (the others would leave the programmed path) */
  int64_t dd[4];
  for (int a = 0; a < 4; a++)
    dd[a] = step[a] == 0 ? 0 : (int64_t)llround(s->teach.exact[a] + step[a]) - s->teach.moved[a];
  if (!mach_in_travel(&s->m, dd)) {
    sess_warn(s, "the jog would take an axis past its travel limit (--machine): not made");
    return;
  }
  for (int a = 0; a < 4; a++) {
    if (step[a] == 0)
      continue;
    s->teach.exact[a] += step[a];
    s->teach.moved[a] += dd[a];
    mach_jog(&s->m, a, dd[a], s->m.corr_allowed);
    s->jogs[a] += dd[a];
  }
  s->has_jogs = 1;
}

/* M19 ended with ПС: the bare-parameter axis words take the moves made. */
static void teach_end(struct session *s)
{
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  for (int a = 0; a < 4; a++)
    if (at->bare[a]) {
      int reg = abs(at->bare[a]) - 1;
      vm_set_reg(&s->vm, (unsigned)reg, at->bare[a] > 0 ? (double)s->teach.moved[a] : -(double)s->teach.moved[a]);
    }
}

/* The block's machine work proper, once nothing holds it. */
static int exec_block(struct session *s)
{
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  kp_mach_modal(&s->m, &s->mb);
  if (sess_plug_phase(s, at->plugins | s->every, 1))
    return SE_ERROR;
  char msg[200];
  int e = kp_mach_motion(&s->m, &s->mb, &s->mo, msg, sizeof msg);
  if (e) {
    vm_fail(&s->vm, e, "%s", msg);
    return SE_ERROR;
  }
  s->run_next = 0;
  s->resumed = 0;
  if (!(at->plugins | s->every)) {   /* what sess_run_plugins does without plugins */
    s->plug_wait = 0;
    return after_motion(s);
  }
  return sess_run_plugins(s);
}

static int after_motion(struct session *s)
{
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  if (BIT(at->m, 15))
    s->m15_seen = 1;
  if (BIT(at->m, 21)) {
    s->directive = 0;
    screen_clear_directive(&s->scr);
  }
  const uint32_t m18 = kp_more(s->p, at)->m18;
  if (m18) {
    s->directive = m18;
    screen_set_directive(&s->scr, kp_str(s->p, m18));
  }
  if (at->motion == MO_G20) {
    s->scr.mode = SCR_MANUAL;
    s->wait = m18 ? W_PS : W_PUSK;
    return SE_WAIT;
  }
  if (at->motion == MO_M19) {
    if (teach_start(s, at) == SE_ERROR)
      return SE_ERROR;
    s->scr.mode = SCR_MANUAL;
    s->wait = W_TEACH;
    return SE_WAIT;
  }
  if (window_block(at)) {
    int r = dialog(s, at);
    if (r >= 0)
      return r;
  }
  finish_block(s);
  return -1;
}

/* A contour move, the core's or a plugin's, waits at a feed override of 0 %. */
static int held(const struct session *s)
{
  int mo = s->mb.motion;   /* a block without a motion is no contour move: no call */
  if (mo != MO_G01 && mo != MO_G02 && mo != MO_G03 && mo != MO_G12 && mo != MO_G13 && mo != MO_PLUGIN)
    return 0;
  return sess_contour_block(s) && mach_held(&s->m, kp_mach_moves(&s->mb));
}

/* The M words whose machine work is a switch (kp_mach_modal), a mark or
 * the VM's alone (M2, M17, M20's TRUNC). */
#define LEAN_M (1u << 2 | 1u << 3 | 1u << 4 | 1u << 5 | 1u << 15 | 1u << 17 | 1u << 20 | 1u << 22 | 1u << 23 | \
                1u << 25 | 1u << 26)

/* A block with no motion, no plugin, no wait, no window, no M16, M18 or
 * M21: what is left of exec_block, after_motion and finish_block for it is
 * lean_rest, so that such a block (an M word, a sub's M17) costs a few
 * stores more than one that does not come to the host (issue 18). */
static inline int lean_block(const struct session *s, const struct kp_attr *at)
{
  return at->motion == MO_NONE && !(at->m & ~LEAN_M) && !(at->plugins | s->every) &&
         (!at->more || (!kp_more(s->p, at)->nm16 && !kp_more(s->p, at)->m18));
}

static int lean_rest(struct session *s, const struct kp_attr *at)
{
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
  sess_emit_row(s);                  /* finish_block without M16 */
  s->wait = W_NONE;
  s->state = SE_START;
  s->scr.mode = SCR_AUTO;
  return -1;
}

/* A VM_EV_BLOCK: do the block's machine work.  Returns the session event
 * when the host must act, or -1 to keep running. */
static int do_block(struct session *s)
{
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  char msg[200];
  uint32_t number = s->p->blocks[s->vm.cur].number;
  s->scr.block = number ? (int)number : -1;   /* sess_block_number */
  if (s->vm.clamped) {
    const struct prog_rule *ru = &s->p->rules[s->vm.clamped - 1];
    sess_warn(s, "%s%.10g is over %.0f: clamped to %.0f", ru->name, s->vm.clamped_from, ru->hi, ru->hi);
    s->vm.clamped = 0;
  }
  /* a G20, M19 or dialog block opens M16's correction window as it starts:
   * at its VM_EV_START when the host acted there (an `at` correction is
   * in the window), else here; a PP jump opens none (language.md sec. 14) */
  int lean = lean_block(s, at);   /* no window_block among them */
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
    b->w[__builtin_ctz(sl)] = s->vm.w[__builtin_ctz(sl)];
  b->given = at->slots;
  b->f = s->vm.reg[REG_F];
  b->d1 = s->vm.reg[REG_D1];
  int e = kp_mach_check(&s->m, b, msg, sizeof msg);
  if (e) {
    vm_fail(&s->vm, e, "%s", msg);
    return SE_ERROR;
  }
  if (lean)
    return lean_rest(s, at);
  if (at->plugins | s->every) {
    if (sess_plug_start_block(s, at->plugins) || sess_plug_phase(s, at->plugins | s->every, 0))
      return SE_ERROR;
  }
  memset(s->jogs, 0, sizeof s->jogs);
  s->has_jogs = 0;
  memcpy(s->start, s->m.pos, sizeof s->start);
  if (held(s)) {           /* feed override at 0 %: the move waits */
    s->wait = W_FEED;
    return SE_WAIT;
  }
  return exec_block(s);
}

/* After a restart: the dialog area as the program's dialog left it before
 * the restart point (the G33 headings, each G27 line with the number its
 * G28 stored, now in the restored parameters).  The state keeps no screen
 * buffer: the program text and the parameters say what it held. */
void kp_restore_dialog(struct session *s)
{
  const struct program *p = s->p;
  struct screen *sc = &s->scr;
  /* the main program's blocks before the restart block, or before the
   * call that leads to it */
  size_t upto = s->vm.cur;
  if (s->vm.depth > 0)
    upto = prog_block_at(p, s->vm.frames[0].ret);
  int p3 = sc->p3, open = 0;
  if (sc->nbuf)
    upto = 0;   /* the state brought the buffer itself */
  for (size_t b = 0; b < upto && b < p->nblocks; b++) {
    const struct kp_attr *at = kp_attr(p, b);
    const struct kp_more *mo = kp_more(p, at);
    if (p->blocks[b].unit != 0)
      continue;
    if (BIT(at->m, 29))
      sc->fixed = -1;
    if (BIT(at->m, 28))
      sc->at_fixed = 1;
    if (BIT(at->g, 33))
      screen_center(sc, kp_str(p, mo->g33));
    if (BIT(at->g, 27)) {
      sc->editing = 0;   /* a G27 without its G28: the number it took is not known */
      screen_prompt(sc, kp_str(p, mo->g27), mo->g27form == '-');
      if (BIT(at->m, 27))
        sc->fixed = sc->last;
      open = 1;
    } else if (BIT(at->m, 27)) {
      sc->fixed = sc->last >= 0 ? sc->last : sc->nbuf;
    }
    if (BIT(at->g, 28) && open && mo->g28reg >= 0) {
      screen_field_type(sc, llround(s->vm.reg[mo->g28reg]));
      screen_field_close(sc);
      open = 0;
    }
  }
  sc->editing = 0;
  sc->at_fixed = 0;
  sc->p3 = p3;
}

/* Hooks the session calls (struct sess_runtime). */
static void on_start(struct session *s)
{
  s->window_opened = window_block(kp_attr(s->p, s->vm.cur));
  if (s->window_opened)
    memset(s->m.corr, 0, sizeof s->m.corr);
}

static int on_answer(struct session *s)
{
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  return BIT(at->g, 28) && g28_check(s) >= 0;
}

static int on_released(struct session *s)
{
  return held(s) ? -2 : exec_block(s);
}

const struct sess_runtime kp_runtime = {
  .start = on_start,
  .block = do_block,
  .after = after_motion,
  .finish = finish_block,
  .answer = on_answer,
  .teach_jog = teach_jog,
  .teach_end = teach_end,
  .released = on_released,
};
