/* The session (src/session.h): turns the VM's block events into machine
 * work, waits and trace rows. */
#include "session.h"
#include "errors.h"
#include "messages.h"
#include <math.h>
#include <stdlib.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define BIT(x, n) (((x) >> (n)) & 1)

void sess_init(struct session *s, const struct program *p)
{
  memset(s, 0, sizeof *s);
  s->p = p;
  vm_init(&s->vm, p);
  mach_init(&s->m);
  scr_init(&s->scr);
  s->state = SE_START;
}

int sess_block_number(const struct session *s)
{
  int n = s->p->blocks[s->vm.cur].number;
  return n ? n : -1;
}

static void warn(struct session *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void warn(struct session *s, const char *fmt, ...)
{
  char msg[240];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  if (s->sink.warn)
    s->sink.warn(s->sink.ctx, s, msg);
}

static void emit_row(struct session *s)
{
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  struct sess_row r;
  memset(&r, 0, sizeof r);
  r.seq = ++s->seq;
  r.n = sess_block_number(s);
  r.line = s->p->blocks[s->vm.cur].line;
  r.depth = s->vm.depth;
  r.motion = kp_motion_name[at->motion];
  memcpy(r.d, s->mo.d, sizeof r.d);
  r.f = s->vm.reg[REG_F];
  r.feed = s->mo.feed;
  r.t = s->m.t;
  r.v = s->mo.v;
  r.has_v = s->mo.has_v;
  r.osc = s->m.osc.active;
  r.override_pct = s->m.override_allowed ? s->m.override_pct : 100;
  memcpy(r.jogs, s->jogs, sizeof r.jogs);
  r.has_jogs = s->has_jogs;
  memcpy(r.start, s->start, sizeof r.start);
  r.blk = &s->mb;
  if (s->sink.row)
    s->sink.row(s->sink.ctx, s, &r);
}

/* What of the block this build cannot do yet: a clear error, never a no-op. */
/* The rest of a block after its machine work and waits: M16, the row. */
static void finish_block(struct session *s)
{
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  const struct kp_ext *x = s->p->ext;
  for (uint32_t i = 0; i < at->nm16; i++) {
    const struct m16_item *it = &x->m16[at->m16 + i];
    int axis = it->axis == 'X' ? 0 : it->axis == 'Y' ? 1 : it->axis == 'Z' ? 2 : 3;
    vm_set_reg(&s->vm, it->reg, (double)(it->sign * s->m.corr[axis]));
  }
  emit_row(s);
  s->wait = W_NONE;
  s->state = SE_START;
  s->scr.mode = SCR_AUTO;
}

/* G28: check the number the G27 took against |min|..|max| and store it, or
 * show why not and ask again.  Returns the session event or -1. */
static int g28_check(struct session *s)
{
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  double v = fabs(s->answer);
  int msg = -1;
  if (v < s->vm.w[SL_MIN])
    msg = MSG_BELOW;
  else if (v > s->vm.w[SL_MAX])
    msg = MSG_ABOVE;
  if (msg >= 0) {
    scr_message(&s->scr, scr_msg_text(msg, s->en));
    scr_field_reopen(&s->scr);
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
  if (BIT(at->m, 29))
    s->scr.fixed = -1;
  if (BIT(at->m, 28))
    s->scr.at_fixed = 1;
  if (BIT(at->g, 33))
    scr_center(&s->scr, kp_str(s->p, at->g33));
  if (BIT(at->g, 29)) {
    const struct kp_ext *x = s->p->ext;
    if (!s->m15_seen)
      scr_p3_clear(&s->scr);
    for (uint32_t i = 0; i < at->ng29; i++)
      scr_p3_add(&s->scr, kp_str(s->p, x->lines[at->g29 + i]));
    s->scr.p3 = 1;
  }
  if (BIT(at->g, 27)) {
    scr_prompt(&s->scr, kp_str(s->p, at->g27), at->g27form == '-');
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
    scr_message(&s->scr, scr_msg_text(MSG_DONE, s->en));
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
  if (BIT(at->g, 2) || BIT(at->g, 3)) {
    struct mach_block ab = s->mb;
    char msg[200];
    double len, ys;
    ab.motion = BIT(at->g, 2) ? MO_G02 : MO_G03;
    int e = mach_arc(&ab, &len, &ys, msg, sizeof msg);
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
  for (int a = 0; a < 4; a++) {
    if (step[a] == 0)
      continue;
    s->teach.exact[a] += step[a];
    int64_t want = (int64_t)llround(s->teach.exact[a]);
    int64_t dd = want - s->teach.moved[a];
    s->teach.moved[a] = want;
    mach_jog(&s->m, a, dd, s->m.corr_allowed);
    s->jogs[a] += dd;
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
  mach_exec(&s->m, &s->mb, &s->mo);
  if (s->mo.warn[0])
    warn(s, "%s", s->mo.warn);
  if (BIT(at->m, 15))
    s->m15_seen = 1;
  if (BIT(at->m, 21)) {
    s->directive = 0;
    scr_clear_directive(&s->scr);
  }
  if (at->m18) {
    s->directive = at->m18;
    scr_set_directive(&s->scr, kp_str(s->p, at->m18));
  }
  if (at->motion == MO_G20) {
    memset(s->m.corr, 0, sizeof s->m.corr);   /* M16 counts from here */
    s->scr.mode = SCR_MANUAL;
    s->wait = at->m18 ? W_PS : W_PUSK;
    return SE_WAIT;
  }
  if (at->motion == MO_M19) {
    memset(s->m.corr, 0, sizeof s->m.corr);
    if (teach_start(s, at) == SE_ERROR)
      return SE_ERROR;
    s->scr.mode = SCR_MANUAL;
    s->wait = W_TEACH;
    return SE_WAIT;
  }
  if (at->motion == MO_DIALOG || BIT(at->m, 27) || BIT(at->m, 28) || BIT(at->m, 29)) {
    memset(s->m.corr, 0, sizeof s->m.corr);   /* M16 counts from a dialog block */
    int r = dialog(s, at);
    if (r >= 0)
      return r;
  }
  finish_block(s);
  return -1;
}

/* A VM_EV_BLOCK: do the block's machine work.  Returns the session event
 * when the host must act, or -1 to keep running. */
static int do_block(struct session *s)
{
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  char msg[200];
  s->scr.block = sess_block_number(s);
  if (s->vm.clamped) {
    const struct prog_rule *ru = &s->p->rules[s->vm.clamped - 1];
    warn(s, "%s%.10g is over %.0f: clamped to %.0f", ru->name, s->vm.clamped_from, ru->hi, ru->hi);
    s->vm.clamped = 0;
  }
  if (s->vm.pp_jumps != s->pp_seen) {        /* M16 counts from the last PP jump */
    s->pp_seen = s->vm.pp_jumps;
    memset(s->m.corr, 0, sizeof s->m.corr);
  }
  struct mach_block *b = &s->mb;
  b->motion = at->motion;
  b->plane = at->plane;
  b->g = at->g;
  b->m = at->m;
  b->given = at->slots;
  for (int i = 0; i < SL__COUNT; i++)
    b->w[i] = BIT(at->slots, i) ? s->vm.w[i] : 0.0;
  b->f = s->vm.reg[REG_F];
  b->d1 = s->vm.reg[REG_D1];
  int e = mach_check(&s->m, b, msg, sizeof msg);
  if (e) {
    vm_fail(&s->vm, e, "%s", msg);
    return SE_ERROR;
  }
  memset(s->jogs, 0, sizeof s->jogs);
  s->has_jogs = 0;
  memcpy(s->start, s->m.pos, sizeof s->start);
  if (mach_held(&s->m, b)) {           /* feed override at 0 %: the move waits */
    s->wait = W_FEED;
    return SE_WAIT;
  }
  return exec_block(s);
}

enum sess_ev sess_run(struct session *s)
{
  if (s->state == SE_WAIT || s->state == SE_END || s->state == SE_ERROR || s->state == SE_STOPPED)
    return (enum sess_ev)s->state;
  for (;;) {
    enum vm_event ev = vm_run(&s->vm);
    int r;
    switch (ev) {
    case VM_EV_START:
      return (enum sess_ev)(s->state = SE_START);
    case VM_EV_BLOCK:
      r = do_block(s);
      if (r >= 0)
        return (enum sess_ev)(s->state = r);
      break;
    case VM_EV_END:
      return (enum sess_ev)(s->state = SE_END);
    default:
      return (enum sess_ev)(s->state = SE_ERROR);
    }
  }
}

int sess_key_pusk(struct session *s)
{
  if (s->state != SE_WAIT || s->wait != W_PUSK)
    return -1;
  s->scr.has_message = 0;
  finish_block(s);
  return 0;
}

int sess_answer(struct session *s, long long v)
{
  if (s->state != SE_WAIT || s->wait != W_ANSWER)
    return -1;
  s->scr.has_message = 0;
  scr_field_type(&s->scr, v);
  scr_field_close(&s->scr);
  s->answer = (double)v;
  s->have_answer = 1;
  const struct kp_attr *at = kp_attr(s->p, s->vm.cur);
  if (BIT(at->g, 28)) {
    int r = g28_check(s);
    if (r >= 0)
      return 0;   /* refused: it waits for the number again */
  }
  finish_block(s);
  return 0;
}

void sess_screen(const struct session *s, uint32_t grid[SCR_ROWS][SCR_COLS])
{
  scr_render(&s->scr, s->vm.reg, s->en, grid);
}

int sess_key_ps(struct session *s)
{
  if (s->state != SE_WAIT || (s->wait != W_PS && s->wait != W_TEACH))
    return -1;
  if (s->wait == W_TEACH)
    teach_end(s);
  s->scr.has_message = 0;   /* a message stays until the next key */
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

int sess_jog(struct session *s, int axis, int64_t d)
{
  if (s->state != SE_WAIT || axis < 0 || axis > 3)
    return -1;
  if (s->wait == W_TEACH) {
    teach_jog(s, axis, d);
    return 0;
  }
  if (s->wait != W_PUSK && s->wait != W_PS)
    return -1;   /* jogs belong to manual mode */
  mach_jog(&s->m, axis, d, s->m.corr_allowed);
  s->jogs[axis] += d;
  s->has_jogs = 1;
  return 0;
}

int sess_correct(struct session *s, int axis, int64_t d)
{
  if (!s->m.corr_allowed) {
    warn(s, "correction refused: operational corrections are forbidden (M23)");
    scr_message(&s->scr, scr_msg_text(MSG_NOCORR, s->en));
    return -1;
  }
  mach_jog(&s->m, axis, d, 1);
  return 0;
}

int sess_override(struct session *s, int pct)
{
  if (!s->m.override_allowed) {
    warn(s, "feed override refused: forbidden by M25");
    scr_message(&s->scr, scr_msg_text(MSG_NOOVR, s->en));
    return -1;
  }
  s->m.override_pct = pct;
  if (s->state == SE_WAIT && s->wait == W_FEED && !mach_held(&s->m, &s->mb)) {
    int r = exec_block(s);
    s->state = r >= 0 ? r : SE_START;
  }
  return 0;
}

const char *sess_wait_text(const struct session *s)
{
  /* for stderr, which speaks English like the rest of the diagnostics */
  switch (s->wait) {
  case W_PUSK: return "Пуск (key PUSK)";
  case W_PS: return "ПС, then Пуск (key PS, key PUSK)";
  case W_TEACH: return "teach-in jogs ended by ПС (jog, key PS)";
  case W_ANSWER: return "a number in the input field (answer N)";
  case W_FEED: return "a feed override above 0 % (override N)";
  default: return "nothing";
  }
}
