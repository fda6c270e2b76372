/* The machine as a Modbus TCP device (src/host/modbus.h, contracts.md sec. 6).
 *
 * Two threads.  The server thread owns every socket: it accepts, reads,
 * frames, answers and writes, and it never touches the machine.  It answers
 * from a view of the map (struct mb_view) that the host's thread publishes
 * between blocks; a paced block's positions move on the wall clock from it.
 * So a trace into a pipe nobody reads, or a tooth search that computes for
 * ten seconds, stops the machine but not the server: a client still gets
 * its reply within milliseconds.  What a client changes goes the other way:
 * key presses wait in a queue (acknowledged at once, as the coil reads 1
 * until the machine takes the press); a write of the override or of R waits
 * for the host's thread, which applies it with the machine's real state in
 * hand (R only while the cycle does not run) and publishes the new view
 * before the reply is sent -- so an acknowledged write has been applied
 * before the cycle goes on, and a read after it sees the value.  The
 * alternative, accepting R writes from the view and applying them later,
 * would acknowledge a write the cycle had already outrun.  One mutex guards
 * the view, the key queue and the waiting writes; two pipes wake each side.
 *
 * libmodbus listens and accepts; framing, validation and replies are ours,
 * because libmodbus 3.1.6 blocks on a truncated frame and sleeps 500 ms on
 * several error paths of modbus_reply. */
#include "modbus.h"
#include "mrun.h"
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <modbus/modbus.h>
#include "modbus_dl.h"   /* libmodbus through dlopen, loaded by mb_open */
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define R_MAX 9999999.0        /* |Rn| beyond this is E-RANGE (language.md sec. 6; a program's own limits when loaded) */
#define IR_R64 100
#define IR_R32 600
#define HEARTBEAT 0.25         /* s: an update at least this often (alive toggles) */
#define FRAME_TIMEOUT 0.25     /* s: a frame once begun must be complete by then */
#define SEND_TIMEOUT 2.0       /* s: a reply the client does not take */
#define MAX_ALLOW 64           /* entries of --modbus-allow */
#define DEFER (-1)             /* write_regs: the host decides */

enum { EX_FUNC = 1, EX_ADDR = 2, EX_VALUE = 3, EX_BUSY = 6, EX_GATEWAY = 0x0B };

double mb_now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + (double)ts.tv_nsec / 1e9;
}

/* ---- encoders: high word first, each word big-endian on the wire ---- */

void mb_put_u32(uint16_t w[2], uint32_t v)
{
  w[0] = (uint16_t)(v >> 16);
  w[1] = (uint16_t)v;
}

uint32_t mb_get_u32(const uint16_t w[2])
{
  return (uint32_t)w[0] << 16 | w[1];
}

void mb_put_i32(uint16_t w[2], int32_t v)
{
  mb_put_u32(w, (uint32_t)v);
}

int32_t mb_get_i32(const uint16_t w[2])
{
  uint32_t u = mb_get_u32(w);
  return u <= INT32_MAX ? (int32_t)u : -(int32_t)(~u) - 1;
}

void mb_put_f32(uint16_t w[2], float v)
{
  uint32_t u;
  memcpy(&u, &v, sizeof u);
  mb_put_u32(w, u);
}

float mb_get_f32(const uint16_t w[2])
{
  uint32_t u = mb_get_u32(w);
  float v;
  memcpy(&v, &u, sizeof v);
  return v;
}

void mb_put_f64(uint16_t w[4], double v)
{
  uint64_t u;
  memcpy(&u, &v, sizeof u);
  for (int i = 0; i < 4; i++)
    w[i] = (uint16_t)(u >> (48 - 16 * i));
}

double mb_get_f64(const uint16_t w[4])
{
  uint64_t u = 0;
  for (int i = 0; i < 4; i++)
    u = u << 16 | w[i];
  double v;
  memcpy(&v, &u, sizeof v);
  return v;
}

/* ---- the map over the view ---- */

static int32_t sat32(double v)
{
  if (!(v == v))
    return 0;
  if (v >= 2147483647.0)
    return INT32_MAX;
  if (v <= -2147483648.0)
    return INT32_MIN;
  return (int32_t)llround(v);
}

/* Part of the paced block's motion done at `now`, 1 when none is under way. */
static double motion_frac(const struct mb_motion *mo, double now)
{
  if (!mo->active)
    return 1;
  if (mo->held)
    return mo->held_frac;
  double len = mo->end - mo->start;
  if (len <= 0 || now >= mo->end)
    return 1;
  double f = (now - mo->start) / len;
  return f < 0 ? 0 : f;
}

void mb_motion_start(struct mb_machine *m, double start, double dur, const int64_t d[4], double feed, int block)
{
  m->motion.active = 1;
  m->motion.held = 0;
  m->motion.held_frac = 0;
  m->motion.start = start;
  m->motion.end = start + dur;
  memcpy(m->motion.d, d, sizeof m->motion.d);
  m->motion.feed = feed;
  m->motion.block = block;
}

static int run_state(int loaded, int idle, int state, const struct mb_motion *mo, double now)
{
  if (!loaded || idle)
    return MB_IDLE;
  if (state == MR_STOPPED || (mo->active && mo->held))
    return MB_STOPPED;
  if (motion_frac(mo, now) < 1)
    return MB_RUN;
  switch (state) {
  case MR_WAIT: return MB_WAITING;
  case MR_ERROR: return MB_ERROR;
  case MR_END: return MB_END;
  default: return MB_RUN;        /* MR_ROW, MR_START: the cycle goes on */
  }
}

static int machine_state(const struct mb_machine *m)
{
  return m->r ? m->r->state : m->s ? mb_sess_state(m->s) : MR_ROW;
}

int mb_run_state(const struct mb_machine *m, double now)
{
  return run_state(m->r || m->s, m->idle, machine_state(m), &m->motion, now);
}

/* The runtime's view of the runner (zeros and the override switch when it has none). */
static void rt_view(const struct mrun *r, struct mrun_view *mv)
{
  if (r->rt && r->rt->view) {
    r->rt->view(r, mv);
  } else {
    memset(mv, 0, sizeof *mv);
    mv->override_eff = r->override;
  }
}

/* Every field set, none cleared first: the host's thread does this at
 * every block boundary, so it costs no more than the copy itself. */
void mb_view_of(struct mb_view *v, const struct mb_machine *m)
{
  const struct mrun *r = m->r;
  v->idle = m->idle;
  v->feed = m->feed;
  v->motion = m->motion;
  v->override_hr = m->set_override ? m->override_pct : r ? r->override : 100;
  v->single = m->single;
  v->brk = m->brk;
  v->loaded = r != NULL || m->s != NULL;
  v->nregs = MB_NREG;            /* nothing loaded: room for R0-R113, all 0 */
  v->r_lo = -R_MAX;
  v->r_hi = R_MAX;
  if (m->s && !r) {
    mb_sess_view(v, m->s);       /* the terminal's session (mb_sess.c) */
    if (m->set_override)
      v->override_hr = m->override_pct;
    return;
  }
  v->override_eff = v->override_hr;   /* idle: the switch as it stands */
  if (!r)
    return;                      /* build() shows nothing more */
  if (!m->set_single)
    v->single = r->single;       /* the runner's switches, whoever set them (a script's mode too) */
  if (!m->set_break)
    v->brk = r->brk;
  v->state = r->state;
  v->wait_feed = r->wait == MRW_FEED;
  v->err_code = r->state == MR_ERROR ? (int)r->vm.err.code : 0;
  v->block = mrun_block_number(r);
  struct mrun_view mv;
  rt_view(r, &mv);
  v->override_eff = mv.override_eff;
  v->wheel = (mv.bits & MRUN_BIT_SPINDLE) != 0;
  v->osc = (mv.bits & MRUN_BIT_AUX) != 0;
  memcpy(v->pos, mv.pos, sizeof v->pos);
  v->t = mrun_time(r);
  v->nregs = mv.nregs < 0 ? 0 : mv.nregs > MB_NREG ? MB_NREG : mv.nregs;
  if (r->p) {
    v->r_lo = r->p->lim.param_lo;
    v->r_hi = r->p->lim.param_hi;
  }
  memcpy(v->reg, mv.reg, (size_t)v->nregs * sizeof *v->reg);
  memset(v->reg + v->nregs, 0, (size_t)(MB_NREG - v->nregs) * sizeof *v->reg);
}

static void build(const struct mb_view *v, double now, uint16_t ir[828], uint8_t di[16])
{
  memset(ir, 0, 828 * sizeof *ir);
  memset(di, 0, 16);
  ir[0] = MB_MAP_VERSION;
  int st = run_state(v->loaded, v->idle, v->state, &v->motion, now);
  ir[2] = (uint16_t)st;
  ir[5] = (uint16_t)v->override_eff;
  if (!v->loaded)
    return;
  double frac = motion_frac(&v->motion, now);
  int moving = v->motion.active && frac < 1;
  int block = st == MB_IDLE ? 0 : moving ? v->motion.block : v->block;
  ir[3] = (uint16_t)(block > 0 && block < 65536 ? block : 0);
  ir[4] = (uint16_t)(v->state == MR_ERROR && st == MB_ERROR ? v->err_code : 0);
  for (int a = 0; a < 4; a++) {
    double p = (double)v->pos[a];
    if (moving)
      p -= (double)v->motion.d[a] * (1 - frac);
    mb_put_i32(&ir[10 + 2 * a], sat32(p));
    di[7 + a] = (uint8_t)(moving && !v->motion.held && v->motion.d[a] != 0);
  }
  double feed = st != MB_RUN ? 0 : moving ? v->motion.feed : v->feed;
  mb_put_i32(&ir[18], sat32(feed * 1000));
  double t = v->t;
  if (moving)
    t -= (v->motion.end - v->motion.start) * (1 - frac);
  mb_put_u32(&ir[20], t > 0 ? (uint32_t)(uint64_t)llround(t * 1000) : 0);  /* wraps after 49 days */
  for (int n = 0; n < v->nregs; n++) {
    mb_put_f64(&ir[IR_R64 + 4 * n], v->reg[n]);
    mb_put_f32(&ir[IR_R32 + 2 * n], (float)v->reg[n]);
  }
  di[0] = st == MB_RUN;
  di[1] = st == MB_STOPPED || (st == MB_WAITING && v->wait_feed);
  di[2] = st == MB_WAITING;
  di[3] = st == MB_ERROR;
  di[4] = st == MB_END;
  di[5] = (uint8_t)v->wheel;
  di[6] = (uint8_t)v->osc;
}

void mb_dev_init(struct mb_dev *d)
{
  memset(d, 0, sizeof *d);
  d->v.idle = 1;
  d->v.override_hr = d->v.override_eff = 100;
  d->v.nregs = MB_NREG;
  d->v.r_lo = -R_MAX;
  d->v.r_hi = R_MAX;
  d->last_update = -1;           /* no update yet */
  build(&d->v, 0, d->ir, d->di);
}

void mb_dev_refresh(struct mb_dev *d, double now)
{
  uint16_t ir[828];
  uint8_t di[16];
  build(&d->v, now, ir, di);
  ir[1] = d->counter;
  di[15] = d->di[15];
  if (d->last_update < 0 || now < d->last_update) {
    d->last_update = now;        /* the clock went back (or a first read): start from here */
    ir[1] = ++d->counter;
    di[15] ^= 1;
  } else if (now - d->last_update >= HEARTBEAT) {
    /* the heartbeats no request saw went by all the same: one per 250 ms */
    unsigned beats = (unsigned)((now - d->last_update) / HEARTBEAT);
    d->counter = (uint16_t)(d->counter + beats);
    if (beats & 1)
      di[15] ^= 1;
    d->last_update += beats * HEARTBEAT;
    ir[1] = d->counter;
  } else if (memcmp(ir, d->ir, sizeof ir) || memcmp(di, d->di, sizeof di)) {
    ir[1] = ++d->counter;
    di[15] ^= 1;
    d->last_update = now;
  }
  memcpy(d->ir, ir, sizeof ir);
  memcpy(d->di, di, sizeof di);
}

static int push_key(struct mb_dev *d, int key)
{
  if (d->nkeys >= MB_KEYQ)
    return -1;
  d->keys[(d->khead + d->nkeys++) % MB_KEYQ] = (uint8_t)key;
  return 0;
}

int mb_dev_key(struct mb_dev *d)
{
  if (!d->nkeys)
    return MB_KEY_NONE;
  int k = d->keys[d->khead];
  d->khead = (d->khead + 1) % MB_KEYQ;
  d->nkeys--;
  return k;
}

static int key_pending(const struct mb_dev *d, int key)
{
  for (unsigned i = 0; i < d->nkeys; i++)
    if (d->keys[(d->khead + i) % MB_KEYQ] == key)
      return 1;
  return 0;
}

long mb_frame(const uint8_t *buf, size_t have)
{
  if (have >= 4 && (buf[2] | buf[3]))
    return -1;                    /* protocol id: Modbus is 0 */
  if (have < 6)
    return 0;
  unsigned len = (unsigned)buf[4] << 8 | buf[5];
  if (len < 2 || len > 254)       /* unit id + function code .. + the largest PDU */
    return -1;
  return have >= 6 + (size_t)len ? (long)(6 + len) : 0;
}

static unsigned be16(const uint8_t *p)
{
  return (unsigned)p[0] << 8 | p[1];
}

/* The holding-register blocks and input-register blocks: [lo, hi) with the
 * size of the values in them (1 word, 4 = float64, 2 = float32); the
 * parameters' blocks hold as many as the machine publishes (nregs). */
struct span { unsigned lo, hi, width; };

/* The block holding all of [a, a+q), or NULL; its bounds in *sp. */
static const struct span *span_of(struct span *sp, int input, int nregs, unsigned a, unsigned q)
{
  const struct span map[3] = {{0, input ? 22u : 3u, 1},
                              {IR_R64, IR_R64 + 4 * (unsigned)nregs, 4},
                              {IR_R32, IR_R32 + 2 * (unsigned)nregs, 2}};
  for (int i = 0; i < 3; i++)
    if (a >= map[i].lo && a + q <= map[i].hi) {
      *sp = map[i];
      return sp;
    }
  return NULL;
}

static uint16_t hr_value(const struct mb_dev *d, unsigned a)
{
  if (a == 0)
    return (uint16_t)d->v.override_hr;
  if (a == 1)
    return (uint16_t)(d->nkeys ? d->keys[d->khead] : 0);
  if (a == 2)
    return (uint16_t)d->v.brk;
  return d->ir[a];
}

/* A float32 write stores the shortest decimal that gives that float back,
 * so 1234.567 arrives as 1234.567 and not 1234.5670166015625. */
static double from_f32(float f)
{
  char buf[40];
  for (int p = 6; p <= 9; p++) {
    snprintf(buf, sizeof buf, "%.*g", p, (double)f);
    if (strtof(buf, NULL) == f)
      return strtod(buf, NULL);
  }
  return (double)f;
}

/* FC 6 / FC 16 on holding registers: checked whole before anything is
 * applied.  0 done, an exception, or DEFER with the write in d->w (the
 * override and R are the host's to apply, on its thread). */
static int write_regs(struct mb_dev *d, unsigned a, unsigned q, const uint8_t *v, double now)
{
  struct span spb;
  const struct span *sp = span_of(&spb, 0, d->v.nregs, a, q);
  if (!sp || (a - sp->lo) % sp->width || q % sp->width)
    return EX_ADDR;              /* outside the map, or part of a value */
  struct mb_write *w = &d->w;
  if (sp->width == 1) {
    int ovr = -1, cmd = -1, brk = -1;
    for (unsigned i = 0; i < q; i++) {
      unsigned x = be16(v + 2 * i);
      if (a + i == 0) {
        if (x > 150)
          return EX_VALUE;
        ovr = (int)x;
      } else if (a + i == 1) {
        if (x > MB_KEY_RESET)
          return EX_VALUE;
        cmd = (int)x;
      } else {
        brk = (int)x;            /* the breakpoint: a block number, 0 none */
      }
    }
    if (ovr < 0 && brk < 0) {    /* the command word alone: a key press */
      if (cmd > 0 && push_key(d, cmd))
        return EX_BUSY;
      return 0;
    }
    w->ovr = ovr;
    w->brk = brk;
    w->single = -1;
    w->cmd = cmd > 0 ? cmd : 0;
    w->r0 = w->n = 0;
    return DEFER;
  }
  unsigned n = q / sp->width, r0 = (a - sp->lo) / sp->width;
  for (unsigned i = 0; i < n; i++) {
    uint16_t x[4];
    for (unsigned k = 0; k < sp->width; k++)
      x[k] = (uint16_t)be16(v + 2 * (i * sp->width + k));
    w->val[i] = sp->width == 4 ? mb_get_f64(x) : from_f32(mb_get_f32(x));
    if (!isfinite(w->val[i]) || !(w->val[i] >= d->v.r_lo && w->val[i] <= d->v.r_hi))
      return EX_VALUE;
  }
  /* R only while the cycle does not run: refused at once when the view
   * says it runs (a refusal is never wrong: nothing was applied); the host
   * decides the rest with the machine's real state */
  if (!d->v.loaded || run_state(1, d->v.idle, d->v.state, &d->v.motion, now) == MB_RUN)
    return EX_BUSY;
  w->ovr = w->single = w->brk = -1;
  w->cmd = 0;
  w->r0 = r0;
  w->n = n;
  return DEFER;
}

static int is_write(unsigned fc)
{
  return fc == MODBUS_FC_WRITE_SINGLE_COIL || fc == MODBUS_FC_WRITE_SINGLE_REGISTER ||
         fc == MODBUS_FC_WRITE_MULTIPLE_COILS || fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS;
}

/* One request's PDU; the reply PDU goes to out.  Returns 0, an exception
 * or DEFER. */
static int handle(struct mb_dev *d, const uint8_t *pdu, size_t pl, uint8_t *out, size_t *ol, double now)
{
  unsigned fc = pdu[0];
  unsigned a = pl >= 5 ? be16(pdu + 1) : 0, q = pl >= 5 ? be16(pdu + 3) : 0;
  if (d->read_only && is_write(fc))
    return EX_FUNC;              /* --modbus-read-only: no writes at all */
  mb_dev_refresh(d, now);        /* every read of this request sees one image */
  switch (fc) {
  case MODBUS_FC_READ_COILS:
  case MODBUS_FC_READ_DISCRETE_INPUTS: {
    if (pl != 5 || q < 1 || q > MODBUS_MAX_READ_BITS)
      return EX_VALUE;
    if (a + q > (fc == MODBUS_FC_READ_COILS ? 6u : 16u))
      return EX_ADDR;
    out[0] = (uint8_t)fc;
    out[1] = (uint8_t)((q + 7) / 8);
    memset(out + 2, 0, out[1]);
    for (unsigned i = 0; i < q; i++) {
      int bit = fc != MODBUS_FC_READ_COILS ? d->di[a + i] : a + i == 5 ? d->v.single : key_pending(d, (int)(a + i) + 1);
      if (bit)
        out[2 + i / 8] |= (uint8_t)(1u << (i % 8));
    }
    *ol = 2u + out[1];
    return 0;
  }
  case MODBUS_FC_READ_HOLDING_REGISTERS:
  case MODBUS_FC_READ_INPUT_REGISTERS: {
    if (pl != 5 || q < 1 || q > MODBUS_MAX_READ_REGISTERS)
      return EX_VALUE;
    struct span spb;
    if (!span_of(&spb, fc == MODBUS_FC_READ_INPUT_REGISTERS, d->v.nregs, a, q))
      return EX_ADDR;
    out[0] = (uint8_t)fc;
    out[1] = (uint8_t)(2 * q);
    for (unsigned i = 0; i < q; i++) {
      uint16_t w = fc == MODBUS_FC_READ_INPUT_REGISTERS ? d->ir[a + i] : hr_value(d, a + i);
      out[2 + 2 * i] = (uint8_t)(w >> 8);
      out[3 + 2 * i] = (uint8_t)w;
    }
    *ol = 2 + 2 * q;
    return 0;
  }
  case MODBUS_FC_WRITE_SINGLE_COIL:
    if (pl != 5 || (q != 0xFF00 && q != 0))
      return EX_VALUE;
    if (a >= 6)
      return EX_ADDR;
    if (a == 5) {                /* single block: a switch, the host's to set */
      d->w.ovr = d->w.brk = -1;
      d->w.single = q != 0;
      d->w.cmd = 0;
      d->w.r0 = d->w.n = 0;
      return DEFER;
    }
    if (q && push_key(d, (int)a + 1))
      return EX_BUSY;
    memcpy(out, pdu, 5);
    *ol = 5;
    return 0;
  case MODBUS_FC_WRITE_SINGLE_REGISTER: {
    if (pl != 5)
      return EX_VALUE;
    if (a > 2)
      return EX_ADDR;            /* R values take 2 or 4 registers: FC 16 */
    uint8_t v[2] = {pdu[3], pdu[4]};
    int e = write_regs(d, a, 1, v, now);
    if (e)
      return e;
    memcpy(out, pdu, 5);
    *ol = 5;
    return 0;
  }
  case MODBUS_FC_WRITE_MULTIPLE_COILS: {
    if (pl < 6 || q < 1 || q > MODBUS_MAX_WRITE_BITS || pdu[5] != (q + 7) / 8 || pl != 6u + pdu[5])
      return EX_VALUE;
    if (a + q > 6)
      return EX_ADDR;
    unsigned presses = 0;
    for (unsigned i = 0; i < q && a + i < 5; i++)
      presses += (pdu[6 + i / 8] >> (i % 8)) & 1;
    if (d->nkeys + presses > MB_KEYQ)
      return EX_BUSY;
    for (unsigned i = 0; i < q && a + i < 5; i++)
      if ((pdu[6 + i / 8] >> (i % 8)) & 1)
        push_key(d, (int)(a + i) + 1);
    if (a + q == 6) {            /* coil 5 among them: the switch is deferred to the host */
      unsigned i = 5 - a;
      d->w.ovr = d->w.brk = -1;
      d->w.single = (pdu[6 + i / 8] >> (i % 8)) & 1;
      d->w.cmd = 0;
      d->w.r0 = d->w.n = 0;
      return DEFER;
    }
    memcpy(out, pdu, 5);
    *ol = 5;
    return 0;
  }
  case MODBUS_FC_WRITE_MULTIPLE_REGISTERS: {
    if (pl < 6 || q < 1 || q > MODBUS_MAX_WRITE_REGISTERS || pdu[5] != 2 * q || pl != 6u + pdu[5])
      return EX_VALUE;
    int e = write_regs(d, a, q, pdu + 6, now);
    if (e)
      return e;
    memcpy(out, pdu, 5);
    *ol = 5;
    return 0;
  }
  default:
    return EX_FUNC;
  }
}

/* The reply frame: the request's header, then the PDU in rsp+7 (ol bytes)
 * or the exception ex. */
static int reply(const uint8_t *req, int ex, uint8_t *rsp, size_t ol)
{
  memcpy(rsp, req, 7);           /* transaction id, protocol id, unit id */
  if (ex) {
    rsp[7] = (uint8_t)(req[7] | 0x80);
    rsp[8] = (uint8_t)ex;
    ol = 2;
  }
  rsp[4] = (uint8_t)((ol + 1) >> 8);
  rsp[5] = (uint8_t)(ol + 1);
  return (int)(7 + ol);
}

int mb_dev_request(struct mb_dev *d, const uint8_t *req, size_t len, uint8_t *rsp, double now)
{
  /* len >= 8 and <= MB_FRAME_MAX: mb_frame checked the length field */
  size_t ol = 0;
  int ex = req[6] == 1 || req[6] == 255 ? handle(d, req + 7, len - 7, rsp + 7, &ol, now) : EX_GATEWAY;
  if (ex == DEFER)
    return 0;
  return reply(req, ex, rsp, ol);
}

int mb_dev_reply(const uint8_t *req, int ex, uint8_t *rsp)
{
  if (!ex)
    memcpy(rsp + 7, req + 7, 5);   /* FC 6 and FC 16 echo function, address, value / quantity */
  return reply(req, ex, rsp, 5);
}

/* The override switch moves to pct on the runner while a paced block's
 * motion may be under way on the wall clock: the runtime re-times the rest
 * of its move from the simulated time the motion has reached (mrun_override,
 * once), and the motion here follows -- the rest at the new speed, from
 * where it is; at 0 % it stands (run state 2) until the switch leaves 0.
 * 0, or -1 when the machine refuses (M25). */
static int override_on_runner(struct mb_machine *m, int pct, double now)
{
  struct mrun *r = m->r;
  struct mb_motion *mo = &m->motion;
  double len = mo->end - mo->start;
  int in = mo->active && len > 0 && (mo->held || now < mo->end);
  double frac = !in ? 1 : mo->held ? mo->held_frac : (now - mo->start) / len;
  if (frac < 0)
    frac = 0;
  double sim = mrun_time(r) - (in ? (1 - frac) * len : 0), d = 0;
  int e = mrun_override(r, pct, sim, &d);
  if (e < 0)
    return -1;
  if (!in)
    return 0;                    /* no motion on the wall clock: the runtime did all there is */
  if (pct == 0) {
    if (!mo->held && e == 2) {   /* the move stands where it is */
      mo->held_frac = frac;
      mo->held = 1;
      m->ovr_held = 1;
      mo->feed = 0;
    }
    return 0;
  }
  int was_held = m->ovr_held;
  if (m->ovr_held) {
    m->ovr_held = 0;
    mo->held = r->state == MR_STOPPED;   /* a Стоп meanwhile still holds it */
  }
  if (d == 0 && !was_held)
    return 0;                    /* not within a move that takes the override: nothing changes */
  double rest = (1 - frac) * len + d;
  len = frac < 1 ? rest / (1 - frac) : len;
  mo->start = now - frac * len;
  mo->end = mo->start + len;
  struct mrun_view mv;
  rt_view(r, &mv);
  mo->feed = m->feed = mv.feed;  /* the move's speed as the runtime re-timed it */
  return 0;
}

int mb_dev_apply(struct mb_dev *d, struct mb_machine *m, const struct mb_write *w, double now)
{
  struct mrun *r = m->r;
  struct session *s = r ? NULL : m->s;
  if (w->cmd && d->nkeys >= MB_KEYQ)
    return EX_BUSY;
  if (w->n) {
    if ((!r && !s) || mb_run_state(m, now) == MB_RUN)
      return EX_BUSY;            /* the cycle went on since the view was published */
    if (w->r0 + w->n > (unsigned)d->v.nregs)
      return EX_ADDR;            /* the machine has no such parameter */
    if (r)
      mrun_load_params(r, w->r0, w->n, w->val);
    else
      mb_sess_load(s, w->r0, w->n, w->val);
  }
  if (w->ovr >= 0) {
    if (m->set_override) {
      if (m->set_override(m->host, w->ovr))
        return EX_BUSY;
    } else if (r ? override_on_runner(m, w->ovr, now) : !s || mb_sess_override(s, w->ovr)) {
      return EX_BUSY;            /* M25 forbids the override */
    }
  }
  if (w->single >= 0) {
    if (m->set_single) {
      m->set_single(m->host, w->single);
    } else {
      m->single = w->single;
      if (r) {
        struct mrun_input in = {.kind = MRI_MODE, .axis = MRM_SINGLE, .n = w->single};
        mrun_input(r, &in, NULL, 0);
      } else if (s) {
        mb_sess_single(s, w->single);
      }
    }
  }
  if (w->brk >= 0) {
    if (m->set_break) {
      m->set_break(m->host, w->brk);
    } else {
      m->brk = w->brk;
      if (r) {
        struct mrun_input in = {.kind = MRI_BREAK, .n = w->brk};
        mrun_input(r, &in, NULL, 0);
      } else if (s) {
        mb_sess_break(s, w->brk);
      }
    }
  }
  if (w->cmd)
    push_key(d, w->cmd);
  return 0;
}

/* ---- allow lists ---- */

int mb_allow_parse(const char *s, struct mb_net *v, int max, char *err, size_t n)
{
  int nv = 0;
  const char *p = s;
  for (;;) {
    size_t l = strcspn(p, ",");
    char item[80], *slash;
    if (!l || l >= sizeof item) {
      snprintf(err, n, "--modbus-allow: '%.*s' in '%s' is not ADDRESS[/BITS]", (int)(l < 60 ? l : 60), p, s);
      return -1;
    }
    if (nv >= max) {
      snprintf(err, n, "--modbus-allow: more than %d entries", max);
      return -1;
    }
    memcpy(item, p, l);
    item[l] = 0;
    struct mb_net *e = &v[nv];
    memset(e, 0, sizeof *e);
    int maxbits = 32;
    if ((slash = strchr(item, '/')) != NULL)
      *slash = 0;
    if (inet_pton(AF_INET, item, e->a) == 1) {
      e->family = AF_INET;
    } else if (inet_pton(AF_INET6, item, e->a) == 1) {
      e->family = AF_INET6;
      maxbits = 128;
    } else {
      snprintf(err, n, "--modbus-allow: '%s' is not an IPv4 or IPv6 address", item);
      return -1;
    }
    e->bits = maxbits;
    if (slash) {
      const char *b = slash + 1;
      size_t bl = strlen(b);
      if (!bl || bl > 3 || strspn(b, "0123456789") != bl || atoi(b) > maxbits) {
        snprintf(err, n, "--modbus-allow: '/%s' after %s is not a prefix length 0-%d", b, item, maxbits);
        return -1;
      }
      e->bits = atoi(b);
    }
    nv++;
    p += l;
    if (!*p)
      return nv;
    p++;
  }
}

static int prefix_eq(const uint8_t *a, const uint8_t *b, int bits)
{
  int full = bits / 8, rest = bits % 8;
  if (memcmp(a, b, (size_t)full))
    return 0;
  if (!rest)
    return 1;
  uint8_t mask = (uint8_t)(0xFF << (8 - rest));
  return (a[full] & mask) == (b[full] & mask);
}

int mb_allow_match(const struct mb_net *v, int nv, const void *sa)
{
  const struct sockaddr *s = sa;
  const uint8_t *a;
  int fam = s->sa_family;
  if (fam == AF_INET) {
    a = (const uint8_t *)&((const struct sockaddr_in *)sa)->sin_addr;
  } else if (fam == AF_INET6) {
    const struct in6_addr *a6 = &((const struct sockaddr_in6 *)sa)->sin6_addr;
    a = (const uint8_t *)a6;
    if (IN6_IS_ADDR_V4MAPPED(a6)) {
      fam = AF_INET;               /* an IPv4 client of a dual-stack socket */
      a += 12;
    }
  } else {
    return 0;
  }
  for (int i = 0; i < nv; i++)
    if (v[i].family == fam && prefix_eq(a, v[i].a, v[i].bits))
      return 1;
  return 0;
}

int mb_host_key(const void *sa, uint8_t host[16])
{
  const struct sockaddr *s = sa;
  if (s->sa_family == AF_INET) {
    memset(host, 0, 10);
    host[10] = host[11] = 0xFF;
    memcpy(host + 12, &((const struct sockaddr_in *)sa)->sin_addr, 4);
    return 0;
  }
  if (s->sa_family == AF_INET6) {
    memcpy(host, &((const struct sockaddr_in6 *)sa)->sin6_addr, 16);
    return 0;
  }
  return -1;
}

/* ---- the slots ---- */

int mb_host_cap(int max)
{
  return max > 1 ? max - 1 : 1;
}

/* Whether a is to be closed before b (b NULL: a is the first seen): one
 * that never asked before one that did (the older first), else the one
 * silent longer. */
static int sooner(const struct mb_slot *a, const struct mb_slot *b)
{
  if (!b)
    return 1;
  if (a->talked != b->talked)
    return !a->talked;
  if (a->talked && a->last != b->last)
    return a->last < b->last;
  return a->serial < b->serial;
}

int mb_admit(const struct mb_slot *s, int n, int max, const uint8_t host[16], double now)
{
  int mine = 0;
  for (int i = 0; i < n; i++)
    mine += !memcmp(s[i].host, host, 16);
  int capped = mine >= mb_host_cap(max);
  if (!capped && n < max)
    return MB_ADMIT;
  int v = -1;
  for (int i = 0; i < n; i++) {
    if (capped && memcmp(s[i].host, host, 16))
      continue;                  /* its address's own make room, not another's */
    if (now - s[i].active < MB_GRACE)
      continue;                  /* active: never closed for a newcomer */
    if (sooner(&s[i], v >= 0 ? &s[v] : NULL))
      v = i;
  }
  return v >= 0 ? v : MB_REFUSE;
}

/* A loopback address (127/8, ::1, ::ffff:127/104). */
static int loopback(const struct sockaddr *s)
{
  if (s->sa_family == AF_INET)
    return ((const uint8_t *)&((const struct sockaddr_in *)s)->sin_addr)[0] == 127;
  if (s->sa_family == AF_INET6) {
    const struct in6_addr *a6 = &((const struct sockaddr_in6 *)s)->sin6_addr;
    return IN6_IS_ADDR_LOOPBACK(a6) || (IN6_IS_ADDR_V4MAPPED(a6) && a6->s6_addr[12] == 127);
  }
  return 0;
}

/* Split "HOST:PORT" / "[V6]:PORT" / ":PORT" / "PORT". */
static int split_addr(const char *s, char *host, size_t hn, char *port, size_t pn, char *err, size_t en)
{
  const char *p;
  size_t hl;
  if (s[0] == '[') {
    const char *e = strchr(s, ']');
    if (!e || e[1] != ':') {
      snprintf(err, en, "--modbus: '%s' is not [ADDRESS]:PORT", s);
      return -1;
    }
    hl = (size_t)(e - s - 1);
    memcpy(host, s + 1, hl < hn ? hl : 0);
    p = e + 2;
  } else if ((p = strrchr(s, ':')) != NULL) {
    hl = (size_t)(p - s);
    if (memchr(s, ':', hl)) {
      snprintf(err, en, "--modbus: write an IPv6 address in brackets: [%.*s]:PORT", (int)hl, s);
      return -1;
    }
    if (hl < hn)
      memcpy(host, s, hl);
    p++;
  } else {
    hl = 0;
    p = s;
  }
  if (hl >= hn) {
    snprintf(err, en, "--modbus: host name too long in '%s'", s);
    return -1;
  }
  host[hl] = 0;
  if (!hl)
    snprintf(host, hn, "127.0.0.1");
  size_t pl = strlen(p);
  if (!pl || pl > 5 || strspn(p, "0123456789") != pl || atol(p) > 65535) {
    snprintf(err, en, "--modbus: '%s' is not HOST:PORT with a port 0-65535", s);
    return -1;
  }
  snprintf(port, pn, "%ld", atol(p));
  return 0;
}

/* ---- the server ---- */

enum { P_FREE, P_QUEUED, P_DONE };

/* A write waiting for the host's thread (one per connection at most: the
 * connection reads no further request until it is answered). */
struct mb_pend {
  int state;
  int ex;                /* P_DONE: its outcome */
  struct mb_write w;
};

struct mb_client {
  int fd;
  size_t nin, nout;
  double since_in;     /* when the unfinished frame in `in` began */
  double since_out;    /* when the unsent reply in `out` was queued */
  struct mb_slot s;    /* its address, when it last asked or sent anything, its age */
  int eof;             /* it sent no more: answer what came, then close */
  int pend;            /* its write in mb->pend, -1 none */
  double pend_until;   /* answered 06 then, if the host has not taken it */
  uint8_t head[12];    /* the waiting write's MBAP header and first PDU bytes, for its reply */
  uint8_t in[2 * MB_FRAME_MAX];
  uint8_t out[4 * MB_FRAME_MAX];
};

struct mb_server {
  /* set by mb_open, then read-only */
  modbus_t *ctx;
  int lfd;
  int max;
  double idle;
  struct mb_net allow[MAX_ALLOW];
  int nallow;
  double (*clock)(void);
  char addr[96];
  char warning[300];
  int to_host[2];           /* server -> host: a key or a write waits */
  int to_srv[2];            /* host -> server: a write was applied; stop */
  pthread_t thread;
  int threaded;
  /* the server thread's (or mb_step's caller's) alone */
  struct mb_client *cl;
  int ncl;
  struct mb_slot *slots;    /* max: the clients' for mb_admit */
  unsigned long accepted;   /* connections so far */
  struct pollfd *pfd;
  /* under lock */
  pthread_mutex_t lock;
  struct mb_dev dev;
  struct mb_pend *pend;     /* max entries */
  int nclients;
  int stop;
};

static void wake(int fd)
{
  char b = 1;
  ssize_t r = write(fd, &b, 1);   /* full (EAGAIN): a wake-up is already there */
  (void)r;
}

static void drain(int fd)
{
  char b[64];
  while (read(fd, b, sizeof b) > 0)
    ;
}

static int pipe_nb(int p[2])
{
  if (pipe(p))
    return -1;
  for (int i = 0; i < 2; i++) {
    fcntl(p[i], F_SETFL, fcntl(p[i], F_GETFL) | O_NONBLOCK);
    fcntl(p[i], F_SETFD, FD_CLOEXEC);
  }
  return 0;
}

void mb_opts_init(struct mb_opts *o)
{
  memset(o, 0, sizeof *o);
  o->max_clients = MB_DEFAULT_CLIENTS;
  o->idle = MB_DEFAULT_IDLE;
}

static void *server_main(void *arg);

static void free_server(struct mb_server *mb)
{
  for (int i = 0; i < 2; i++) {
    if (mb->to_host[i] >= 0)
      close(mb->to_host[i]);
    if (mb->to_srv[i] >= 0)
      close(mb->to_srv[i]);
  }
  if (mb->lfd >= 0)
    close(mb->lfd);
  if (mb->ctx) {
    modbus_set_socket(mb->ctx, -1);
    modbus_free(mb->ctx);
  }
  pthread_mutex_destroy(&mb->lock);
  free(mb->cl);
  free(mb->slots);
  free(mb->pfd);
  free(mb->pend);
  free(mb);
}

struct mb_server *mb_open(const struct mb_opts *o, char *err, size_t n, int *usage)
{
  char host[256], port[8];
  const char *addr = o->addr && *o->addr ? o->addr : MB_DEFAULT_ADDR;
  *usage = 1;
  if (split_addr(addr, host, sizeof host, port, sizeof port, err, n))
    return NULL;
  if (o->max_clients < 1 || o->max_clients > MB_CLIENTS_LIMIT) {
    snprintf(err, n, "--modbus-max-clients: %d is not 1-%d", o->max_clients, MB_CLIENTS_LIMIT);
    return NULL;
  }
  if (!(o->idle >= 0)) {
    snprintf(err, n, "--modbus-idle: %g is not a number of seconds", o->idle);
    return NULL;
  }
  struct mb_net allow[MAX_ALLOW];
  int nallow = 0;
  if (o->allow && (nallow = mb_allow_parse(o->allow, allow, MAX_ALLOW, err, n)) < 0)
    return NULL;
  struct addrinfo hints, *ai = NULL;
  memset(&hints, 0, sizeof hints);
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  int g = getaddrinfo(host, port, &hints, &ai);
  if (g) {
    snprintf(err, n, "--modbus: cannot resolve '%s': %s", host, gai_strerror(g));
    return NULL;
  }
  freeaddrinfo(ai);
  *usage = 0;
  /* libmodbus now, not at every start of s42 */
  if (s42_modbus_load(err, n))
    return NULL;
  signal(SIGPIPE, SIG_IGN);      /* a client that went away is not our death */
  struct mb_server *mb = calloc(1, sizeof *mb);
  if (!mb) {
    snprintf(err, n, "out of memory");
    return NULL;
  }
  mb->lfd = mb->to_host[0] = mb->to_host[1] = mb->to_srv[0] = mb->to_srv[1] = -1;
  pthread_mutex_init(&mb->lock, NULL);
  mb->max = o->max_clients;
  mb->idle = o->idle;
  memcpy(mb->allow, allow, sizeof allow);
  mb->nallow = nallow;
  mb->clock = o->clock ? o->clock : mb_now;
  mb->cl = calloc((size_t)mb->max, sizeof *mb->cl);
  mb->slots = calloc((size_t)mb->max, sizeof *mb->slots);
  mb->pfd = calloc((size_t)mb->max + 2, sizeof *mb->pfd);
  mb->pend = calloc((size_t)mb->max, sizeof *mb->pend);
  if (!mb->cl || !mb->slots || !mb->pfd || !mb->pend || pipe_nb(mb->to_host) || pipe_nb(mb->to_srv)) {
    snprintf(err, n, "Modbus: %s", errno ? strerror(errno) : "out of memory");
    free_server(mb);
    return NULL;
  }
  mb->ctx = modbus_new_tcp_pi(host, port);
  if (!mb->ctx) {
    snprintf(err, n, "Modbus on %s: %s", addr, modbus_strerror(errno));
    free_server(mb);
    return NULL;
  }
  errno = 0;
  mb->lfd = modbus_tcp_pi_listen(mb->ctx, 16);
  if (mb->lfd < 0) {
    int e = errno ? errno : EADDRNOTAVAIL;
    snprintf(err, n, "Modbus on %s:%s: %s", host, port, e == EADDRINUSE ? "the port is in use" : strerror(e));
    free_server(mb);
    return NULL;
  }
  fcntl(mb->lfd, F_SETFL, fcntl(mb->lfd, F_GETFL) | O_NONBLOCK);
  fcntl(mb->lfd, F_SETFD, FD_CLOEXEC);
  struct sockaddr_storage ss;
  socklen_t sl = sizeof ss;
  char h[80], sv[8];
  if (getsockname(mb->lfd, (struct sockaddr *)&ss, &sl) == 0 &&
      getnameinfo((struct sockaddr *)&ss, sl, h, sizeof h, sv, sizeof sv, NI_NUMERICHOST | NI_NUMERICSERV) == 0) {
    snprintf(mb->addr, sizeof mb->addr, ss.ss_family == AF_INET6 ? "[%s]:%s" : "%s:%s", h, sv);
    if (!nallow && !loopback((struct sockaddr *)&ss))
      snprintf(mb->warning, sizeof mb->warning,
               "Modbus on %s: not a loopback address, and no --modbus-allow: any host that reaches it can %s",
               mb->addr, o->read_only ? "read the machine's state" :
               "start and stop the cycle, set the feed override and write the parameters");
  } else {
    snprintf(mb->addr, sizeof mb->addr, "%s:%s", host, port);
  }
  mb_dev_init(&mb->dev);
  mb->dev.read_only = o->read_only;
  if (!o->no_thread) {
    /* the thread takes no signals: SIGINT, SIGTERM, SIGWINCH stay the host's */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    int e = pthread_create(&mb->thread, NULL, server_main, mb);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (e) {
      snprintf(err, n, "Modbus: cannot start the server thread: %s", strerror(e));
      free_server(mb);
      return NULL;
    }
    mb->threaded = 1;
  }
  return mb;
}

/* Close connection i (the caller must not touch it again). */
static void drop(struct mb_server *mb, int i)
{
  struct mb_client *c = &mb->cl[i];
  pthread_mutex_lock(&mb->lock);
  if (c->pend >= 0)
    mb->pend[c->pend].state = P_FREE;   /* not yet taken: never applied; taken: never acknowledged */
  mb->nclients = mb->ncl - 1;
  pthread_mutex_unlock(&mb->lock);
  close(c->fd);
  *c = mb->cl[--mb->ncl];
}

void mb_close(struct mb_server *mb)
{
  if (!mb)
    return;
  if (mb->threaded) {
    pthread_mutex_lock(&mb->lock);
    mb->stop = 1;
    pthread_mutex_unlock(&mb->lock);
    wake(mb->to_srv[1]);
    pthread_join(mb->thread, NULL);
  }
  while (mb->ncl)
    drop(mb, mb->ncl - 1);
  free_server(mb);
}

const char *mb_address(const struct mb_server *mb)
{
  return mb->addr;
}

const char *mb_warning(const struct mb_server *mb)
{
  return mb->warning;
}

int mb_clients(struct mb_server *mb)
{
  pthread_mutex_lock(&mb->lock);
  int n = mb->nclients;
  pthread_mutex_unlock(&mb->lock);
  return n;
}

static int room(const struct mb_client *c)
{
  return sizeof c->out - c->nout >= MB_FRAME_MAX;
}

/* 0 kept, -1 dropped. */
static int flush_out(struct mb_server *mb, int i, double now)
{
  struct mb_client *c = &mb->cl[i];
  while (c->nout) {
    ssize_t w = send(c->fd, c->out, c->nout, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (w < 0) {
      if (errno == EINTR)
        continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK)
        return 0;
      drop(mb, i);
      return -1;
    }
    memmove(c->out, c->out + w, c->nout - (size_t)w);
    c->nout -= (size_t)w;
    c->since_out = now;
  }
  return 0;
}

/* Queue a reply of n bytes already at c->out + c->nout. */
static void queued(struct mb_client *c, int n, double now)
{
  if (!c->nout)
    c->since_out = now;
  c->nout += (size_t)n;
}

/* Answer the complete frames in the input buffer, in order, sending as it
 * goes: a pipelined burst is answered whole, not only as far as the output
 * buffer reaches (the rest would wait for bytes that never come).  Stops at
 * a write that waits for the host, or when the client does not take its
 * replies (POLLOUT brings us back).  0 kept, -1 dropped. */
static int pump(struct mb_server *mb, int i, double now)
{
  struct mb_client *c = &mb->cl[i];
  int woke = 0;
  while (c->pend < 0) {
    long fl = mb_frame(c->in, c->nin);
    if (fl < 0) {                /* not Modbus TCP: this connection ends */
      if (!flush_out(mb, i, now))  /* after the replies to what came before, if it takes them */
        drop(mb, i);
      return -1;
    }
    if (fl == 0)
      break;
    if (!room(c)) {
      if (flush_out(mb, i, now))
        return -1;
      if (!room(c))
        break;
    }
    pthread_mutex_lock(&mb->lock);
    unsigned keys = mb->dev.nkeys;
    int r = mb_dev_request(&mb->dev, c->in, (size_t)fl, c->out + c->nout, now);
    if (r == 0) {                /* a write for the host: a slot of its own */
      int k = 0;
      while (k < mb->max && mb->pend[k].state != P_FREE)
        k++;
      if (k < mb->max) {         /* always: there are as many slots as connections */
        mb->pend[k].state = P_QUEUED;
        mb->pend[k].w = mb->dev.w;
        c->pend = k;
        c->pend_until = now + MB_WRITE_WAIT;
        memcpy(c->head, c->in, sizeof c->head);
        woke = 1;
      } else {
        r = mb_dev_reply(c->in, EX_BUSY, c->out + c->nout);
      }
    }
    woke |= mb->dev.nkeys > keys;
    pthread_mutex_unlock(&mb->lock);
    if (r > 0)
      queued(c, r, now);
    c->s.talked = 1;
    c->s.active = now;
    c->nin -= (size_t)fl;
    memmove(c->in, c->in + fl, c->nin);
    c->since_in = now;
  }
  if (woke)
    wake(mb->to_host[1]);
  return flush_out(mb, i, now);
}

/* The reply of client i's waiting write once the host applied it, or 06
 * when it has not taken it by its time.  0 kept, -1 dropped. */
static int settle(struct mb_server *mb, int i, double now)
{
  struct mb_client *c = &mb->cl[i];
  if (c->pend < 0)
    return 0;
  pthread_mutex_lock(&mb->lock);
  struct mb_pend *p = &mb->pend[c->pend];
  int ex = -1;
  if (p->state == P_DONE)
    ex = p->ex;
  else if (now >= c->pend_until)
    ex = EX_BUSY;                /* still queued: withdrawn, never applied */
  if (ex >= 0)
    p->state = P_FREE;
  pthread_mutex_unlock(&mb->lock);
  if (ex < 0)
    return 0;
  c->pend = -1;
  queued(c, mb_dev_reply(c->head, ex, c->out + c->nout), now);   /* room was kept for it */
  return pump(mb, i, now);       /* the requests behind it */
}

/* Newcomers: each gets a slot, or an idle connection's, or is closed at
 * once (mb_admit): an active client is never closed for one, and a loop of
 * connections, all refused, holds up no one. */
static void accept_all(struct mb_server *mb, double now)
{
  for (int k = 0; k < 16; k++) {
    int fd = modbus_tcp_pi_accept(mb->ctx, &mb->lfd);
    modbus_set_socket(mb->ctx, -1);   /* the connection is ours, not the context's */
    if (fd < 0)
      return;                    /* EAGAIN: none left (or it went away) */
    struct sockaddr_storage ss;
    socklen_t sl = sizeof ss;
    uint8_t host[16];
    if (getpeername(fd, (struct sockaddr *)&ss, &sl) || mb_host_key(&ss, host) ||
        (mb->nallow && !mb_allow_match(mb->allow, mb->nallow, &ss))) {
      close(fd);                 /* gone already, or not on --modbus-allow */
      continue;
    }
    for (int i = 0; i < mb->ncl; i++)
      mb->slots[i] = mb->cl[i].s;
    int v = mb_admit(mb->slots, mb->ncl, mb->max, host, now);
    if (v == MB_REFUSE) {
      close(fd);                 /* no room it may take: it finds the connection closed, and may retry */
      continue;
    }
    if (v >= 0)
      drop(mb, v);
    int one = 1;
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    struct mb_client *c = &mb->cl[mb->ncl++];
    memset(c, 0, offsetof(struct mb_client, in));
    c->fd = fd;
    c->pend = -1;
    memcpy(c->s.host, host, sizeof host);
    c->s.active = c->s.last = c->since_in = c->since_out = now;
    c->s.serial = ++mb->accepted;
    pthread_mutex_lock(&mb->lock);
    mb->nclients = mb->ncl;
    pthread_mutex_unlock(&mb->lock);
  }
}

static void read_in(struct mb_server *mb, int i, double now)
{
  struct mb_client *c = &mb->cl[i];
  if (c->nin >= sizeof c->in)
    return;
  ssize_t r = recv(c->fd, c->in + c->nin, sizeof c->in - c->nin, MSG_DONTWAIT);
  if (r < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
    drop(mb, i);
    return;
  }
  if (r < 0)
    return;
  if (r == 0) {                  /* a half close: the requests before it are still answered */
    c->eof = 1;
    pump(mb, i, now);
    return;
  }
  if (!c->nin)
    c->since_in = now;
  c->nin += (size_t)r;
  c->s.last = now;
  pump(mb, i, now);
}

static int find(const struct mb_server *mb, int fd)
{
  for (int i = 0; i < mb->ncl; i++)
    if (mb->cl[i].fd == fd)
      return i;
  return -1;
}

/* The earliest deadline of client c. */
static double deadline(const struct mb_server *mb, const struct mb_client *c)
{
  double t = mb->idle > 0 ? c->s.last + mb->idle : 1e300;
  if (c->nin && mb_frame(c->in, c->nin) == 0 && c->since_in + FRAME_TIMEOUT < t)
    t = c->since_in + FRAME_TIMEOUT;
  if (c->nout && c->since_out + SEND_TIMEOUT < t)
    t = c->since_out + SEND_TIMEOUT;
  if (c->pend >= 0 && c->pend_until < t)
    t = c->pend_until;
  return t;
}

void mb_step(struct mb_server *mb, int timeout_ms)
{
  int n = 0;
  struct pollfd *fds = mb->pfd;
  fds[n].fd = mb->lfd;
  fds[n++].events = POLLIN;
  fds[n].fd = mb->to_srv[0];
  fds[n++].events = POLLIN;
  double now = mb->clock();
  for (int i = 0; i < mb->ncl; i++) {
    const struct mb_client *c = &mb->cl[i];
    fds[n].fd = c->fd;
    fds[n++].events = (short)((c->nout ? POLLOUT : 0) | (c->nin < sizeof c->in && !c->eof ? POLLIN : 0));
    double left = (deadline(mb, c) - now) * 1000;
    int ms = left <= 0 ? 0 : left > 1e6 ? 1000000 : (int)ceil(left);
    if (timeout_ms < 0 || ms < timeout_ms)
      timeout_ms = ms;
  }
  for (int k = 0; k < n; k++)
    fds[k].revents = 0;
  if (poll(fds, (nfds_t)n, timeout_ms) < 0)
    return;                      /* EINTR (no signal reaches the thread; a harness's may) */
  now = mb->clock();
  if (fds[1].revents)
    drain(mb->to_srv[0]);
  for (int k = 2; k < n; k++) {
    short re = fds[k].revents;
    if (!re)
      continue;
    int i = find(mb, fds[k].fd);
    if (i < 0)
      continue;
    if (re & (POLLERR | POLLNVAL)) {
      drop(mb, i);
      continue;
    }
    if ((re & POLLOUT) && (flush_out(mb, i, now) || pump(mb, i, now)))
      continue;
    if (re & (POLLIN | POLLHUP))
      read_in(mb, i, now);
  }
  for (int i = mb->ncl - 1; i >= 0; i--)
    if (mb->cl[i].pend >= 0)
      settle(mb, i, now);        /* applied by the host, or out of time */
  for (int i = mb->ncl - 1; i >= 0; i--) {
    const struct mb_client *c = &mb->cl[i];
    if (i < mb->ncl && (now >= deadline(mb, c) || (c->eof && c->pend < 0 && !c->nout && mb_frame(c->in, c->nin) <= 0)))
      drop(mb, i);               /* a truncated frame, a stuck reply, silence; all answered after a close */
  }
  if (fds[0].revents)
    accept_all(mb, now);         /* last: a newcomer may close an idle one */
}

static void *server_main(void *arg)
{
  struct mb_server *mb = arg;
  for (;;) {
    pthread_mutex_lock(&mb->lock);
    int stop = mb->stop;
    pthread_mutex_unlock(&mb->lock);
    if (stop)
      return NULL;
    mb_step(mb, 1000);
  }
}

/* ---- the host's side ---- */

int mb_fd(const struct mb_server *mb)
{
  return mb->to_host[0];
}

void mb_sync(struct mb_server *mb, struct mb_machine *m)
{
  drain(mb->to_host[0]);
  double now = mb->clock();
  int any = 0;
  pthread_mutex_lock(&mb->lock);
  for (int k = 0; k < mb->max; k++) {
    struct mb_pend *p = &mb->pend[k];
    if (p->state != P_QUEUED)
      continue;
    p->ex = mb_dev_apply(&mb->dev, m, &p->w, now);
    p->state = P_DONE;
    any = 1;
  }
  mb_view_of(&mb->dev.v, m);     /* before the reply: a read after it sees the value */
  pthread_mutex_unlock(&mb->lock);
  if (any)
    wake(mb->to_srv[1]);
}

void mb_publish(struct mb_server *mb, const struct mb_machine *m)
{
  pthread_mutex_lock(&mb->lock);   /* in place: the host is the machine's only reader here */
  mb_view_of(&mb->dev.v, m);
  pthread_mutex_unlock(&mb->lock);
}

void mb_publish_running(struct mb_server *mb, const struct mb_machine *m)
{
  pthread_mutex_lock(&mb->lock);
  mb_view_of(&mb->dev.v, m);
  if (mb->dev.v.state == MR_WAIT || mb->dev.v.state == MR_STOPPED)
    mb->dev.v.state = MR_START;
  pthread_mutex_unlock(&mb->lock);
}

int mb_key(struct mb_server *mb)
{
  pthread_mutex_lock(&mb->lock);
  int k = mb_dev_key(&mb->dev);
  pthread_mutex_unlock(&mb->lock);
  return k;
}

int mb_poll(struct mb_server *mb, struct mb_machine *m, int timeout_ms)
{
  struct pollfd p = {.fd = mb->to_host[0], .events = POLLIN, .revents = 0};
  if (poll(&p, 1, timeout_ms) < 0) {
    if (errno == EINTR)
      return 0;
    return -1;
  }
  mb_sync(mb, m);
  return 0;
}
