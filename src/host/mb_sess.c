/* The Modbus map over the terminal's 2С42 session (src/host/modbus.h,
 * "the terminal's 2С42 session"): what modbus.c reads from a runner, read
 * from a session instead, so that modbus.c knows no session.  The
 * terminal's loop still runs the 2С42 on src/dialect/2c42/session.c; when
 * it runs on the runner this file goes. */
#include "modbus.h"
#include "mrun.h"
#include "session.h"
#include <string.h>

int mb_sess_state(const struct session *s)
{
  switch (s->state) {
  case SE_WAIT: return MR_WAIT;
  case SE_END: return MR_END;
  case SE_ERROR: return MR_ERROR;
  case SE_STOPPED: return MR_STOPPED;
  default: return MR_START;
  }
}

void mb_sess_view(struct mb_view *v, const struct session *s)
{
  v->state = mb_sess_state(s);
  v->wait_feed = s->wait == W_FEED;
  v->err_code = (int)sess_vm_error(s)->code;
  v->block = sess_block_number(s);
  v->override_hr = sess_override_pct(s);   /* a host that keeps the switch puts its own back */
  v->override_eff = sess_override_allowed(s) ? sess_override_pct(s) : 100;
  v->wheel = sess_wheel(s) != WHEEL_OFF;
  v->osc = s->extra[0] && sess_oscillating(s);
  memcpy(v->pos, sess_positions(s), sizeof v->pos);
  v->t = sess_time(s);
  v->nregs = MB_NREG;
  memcpy(v->reg, sess_regs(s), sizeof v->reg);
}

void mb_sess_load(struct session *s, unsigned r0, unsigned n, const double *v)
{
  sess_load_params(s, r0, n, v);
}

int mb_sess_override(struct session *s, int pct)
{
  if (!sess_override_allowed(s))
    return -1;   /* M25 (checked first: no warning printed) */
  return sess_override(s, pct) ? -1 : 0;
}

void mb_sess_single(struct session *s, int on)
{
  sess_set_single(s, on);
}

void mb_sess_break(struct session *s, int n)
{
  sess_set_break(s, n);
}
