/* The machine as a Modbus TCP device (src/modbus.h, contracts.md sec. 6).
 * libmodbus listens and accepts; framing, validation and replies are ours,
 * because libmodbus 3.1.6 blocks on a truncated frame and sleeps 500 ms on
 * several error paths of modbus_reply -- nothing here may block the loop. */
#include "modbus.h"
#include "session.h"
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <modbus/modbus.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define NREG_R 114
#define R_MAX 9999999.0        /* |Rn| beyond this is E-RANGE (language.md sec. 6) */
#define IR_R64 100
#define IR_R32 600
#define HEARTBEAT 0.25         /* s: an update at least this often (alive toggles) */
#define FRAME_TIMEOUT 0.25     /* s: a frame once begun must be complete by then */
#define SEND_TIMEOUT 2.0       /* s: a reply the client does not take */
#define IDLE_TIMEOUT 60.0      /* s: a connection that sends nothing */

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

/* ---- the map over the machine ---- */

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
static double motion_frac(const struct mb_machine *m, double now)
{
  if (!m->motion.active)
    return 1;
  if (m->motion.held)
    return m->motion.held_frac;
  double len = m->motion.end - m->motion.start;
  if (len <= 0 || now >= m->motion.end)
    return 1;
  double f = (now - m->motion.start) / len;
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

int mb_run_state(const struct mb_machine *m, double now)
{
  const struct session *s = m->s;
  if (!s || m->idle)
    return MB_IDLE;
  if (s->state == SE_STOPPED || (m->motion.active && m->motion.held))
    return MB_STOPPED;
  if (motion_frac(m, now) < 1)
    return MB_RUN;
  switch (s->state) {
  case SE_WAIT: return MB_WAITING;
  case SE_ERROR: return MB_ERROR;
  case SE_END: return MB_END;
  default: return MB_RUN;
  }
}

static void build(const struct mb_machine *m, double now, uint16_t ir[828], uint8_t di[16])
{
  memset(ir, 0, 828 * sizeof *ir);
  memset(di, 0, 16);
  ir[0] = MB_MAP_VERSION;
  int st = mb_run_state(m, now);
  ir[2] = (uint16_t)st;
  const struct session *s = m->s;
  if (!s)
    return;
  double frac = motion_frac(m, now);
  int moving = m->motion.active && frac < 1;
  int block = st == MB_IDLE ? 0 : moving ? m->motion.block : sess_block_number(s);
  ir[3] = (uint16_t)(block > 0 && block < 65536 ? block : 0);
  ir[4] = (uint16_t)(s->state == SE_ERROR && st == MB_ERROR ? s->vm.err.code : 0);
  ir[5] = (uint16_t)(s->m.override_allowed ? s->m.override_pct : 100);
  for (int a = 0; a < 4; a++) {
    double p = (double)s->m.pos[a];
    if (moving)
      p -= (double)m->motion.d[a] * (1 - frac);
    mb_put_i32(&ir[10 + 2 * a], sat32(p));
    di[7 + a] = (uint8_t)(moving && !m->motion.held && m->motion.d[a] != 0);
  }
  double feed = st != MB_RUN ? 0 : moving ? m->motion.feed : m->feed;
  mb_put_i32(&ir[18], sat32(feed * 1000));
  double t = s->m.t;
  if (moving)
    t -= (m->motion.end - m->motion.start) * (1 - frac);
  mb_put_u32(&ir[20], t > 0 ? (uint32_t)(uint64_t)llround(t * 1000) : 0);  /* wraps after 49 days */
  for (int n = 0; n < NREG_R; n++) {
    mb_put_f64(&ir[IR_R64 + 4 * n], s->vm.reg[n]);
    mb_put_f32(&ir[IR_R32 + 2 * n], (float)s->vm.reg[n]);
  }
  di[0] = st == MB_RUN;
  di[1] = st == MB_STOPPED || (st == MB_WAITING && s->wait == W_FEED);
  di[2] = st == MB_WAITING;
  di[3] = st == MB_ERROR;
  di[4] = st == MB_END;
  di[5] = s->m.wheel != WHEEL_OFF;
  di[6] = (uint8_t)sess_oscillating(s);
}

void mb_dev_init(struct mb_dev *d, struct mb_machine *m)
{
  memset(d, 0, sizeof *d);
  d->m = m;
  build(m, 0, d->ir, d->di);
}

void mb_dev_refresh(struct mb_dev *d, double now)
{
  uint16_t ir[828];
  uint8_t di[16];
  build(d->m, now, ir, di);
  ir[1] = d->counter;
  di[15] = d->di[15];
  if (memcmp(ir, d->ir, sizeof ir) || memcmp(di, d->di, sizeof di) || now - d->last_update >= HEARTBEAT ||
      now < d->last_update) {
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
 * size of the values in them (1 word, 4 = float64, 2 = float32). */
struct span { unsigned lo, hi, width; };
static const struct span hr_map[] = {{0, 2, 1}, {IR_R64, IR_R64 + 4 * NREG_R, 4}, {IR_R32, IR_R32 + 2 * NREG_R, 2}};
static const struct span ir_map[] = {{0, 22, 1}, {IR_R64, IR_R64 + 4 * NREG_R, 4}, {IR_R32, IR_R32 + 2 * NREG_R, 2}};

/* The block holding all of [a, a+q), or NULL. */
static const struct span *span_of(const struct span *map, unsigned a, unsigned q)
{
  for (int i = 0; i < 3; i++)
    if (a >= map[i].lo && a + q <= map[i].hi)
      return &map[i];
  return NULL;
}

static uint16_t hr_value(const struct mb_dev *d, unsigned a)
{
  if (a == 0)
    return (uint16_t)(d->m->set_override ? d->m->override_pct : d->m->s ? d->m->s->m.override_pct : 100);
  if (a == 1)
    return (uint16_t)(d->nkeys ? d->keys[d->khead] : 0);
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

/* FC 16 on holding registers: checked whole before anything is applied. */
static int write_regs(struct mb_dev *d, unsigned a, unsigned q, const uint8_t *v, double now)
{
  const struct span *sp = span_of(hr_map, a, q);
  if (!sp || (a - sp->lo) % sp->width || q % sp->width)
    return EX_ADDR;              /* outside the map, or part of a value */
  struct session *s = d->m->s;
  if (sp->width == 1) {
    int ovr = -1, cmd = -1;
    for (unsigned i = 0; i < q; i++) {
      unsigned x = be16(v + 2 * i);
      if (a + i == 0) {
        if (x > 150)
          return EX_VALUE;
        ovr = (int)x;
      } else {
        if (x > MB_KEY_RESET)
          return EX_VALUE;
        cmd = (int)x;
      }
    }
    if (ovr >= 0 && !d->m->set_override && (!s || !s->m.override_allowed))
      return EX_BUSY;            /* M25 forbids the override */
    if (cmd > 0 && d->nkeys >= MB_KEYQ)
      return EX_BUSY;
    if (ovr >= 0 && (d->m->set_override ? d->m->set_override(d->m->host, ovr) : sess_override(s, ovr)))
      return EX_BUSY;
    if (cmd > 0)
      push_key(d, cmd);
    return 0;
  }
  double val[NREG_R];
  unsigned n = q / sp->width, r0 = (a - sp->lo) / sp->width;
  for (unsigned i = 0; i < n; i++) {
    uint16_t w[4];
    for (unsigned k = 0; k < sp->width; k++)
      w[k] = (uint16_t)be16(v + 2 * (i * sp->width + k));
    val[i] = sp->width == 4 ? mb_get_f64(w) : from_f32(mb_get_f32(w));
    if (!isfinite(val[i]) || fabs(val[i]) > R_MAX)
      return EX_VALUE;
  }
  if (!s || mb_run_state(d->m, now) == MB_RUN)
    return EX_BUSY;              /* R only while the cycle does not run */
  for (unsigned i = 0; i < n; i++)
    s->vm.reg[r0 + i] = val[i];
  return 0;
}

/* One request's PDU; the reply PDU goes to out.  Returns 0 or an exception. */
static int handle(struct mb_dev *d, const uint8_t *pdu, size_t pl, uint8_t *out, size_t *ol, double now)
{
  unsigned fc = pdu[0];
  unsigned a = pl >= 5 ? be16(pdu + 1) : 0, q = pl >= 5 ? be16(pdu + 3) : 0;
  mb_dev_refresh(d, now);        /* every read of this request sees one image */
  switch (fc) {
  case MODBUS_FC_READ_COILS:
  case MODBUS_FC_READ_DISCRETE_INPUTS: {
    if (pl != 5 || q < 1 || q > MODBUS_MAX_READ_BITS)
      return EX_VALUE;
    if (a + q > (fc == MODBUS_FC_READ_COILS ? 5u : 16u))
      return EX_ADDR;
    out[0] = (uint8_t)fc;
    out[1] = (uint8_t)((q + 7) / 8);
    memset(out + 2, 0, out[1]);
    for (unsigned i = 0; i < q; i++) {
      int bit = fc == MODBUS_FC_READ_COILS ? key_pending(d, (int)(a + i) + 1) : d->di[a + i];
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
    if (!span_of(fc == MODBUS_FC_READ_INPUT_REGISTERS ? ir_map : hr_map, a, q))
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
    if (a >= 5)
      return EX_ADDR;
    if (q && push_key(d, (int)a + 1))
      return EX_BUSY;
    memcpy(out, pdu, 5);
    *ol = 5;
    return 0;
  case MODBUS_FC_WRITE_SINGLE_REGISTER: {
    if (pl != 5)
      return EX_VALUE;
    if (a > 1)
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
    if (a + q > 5)
      return EX_ADDR;
    unsigned presses = 0;
    for (unsigned i = 0; i < q; i++)
      presses += (pdu[6 + i / 8] >> (i % 8)) & 1;
    if (d->nkeys + presses > MB_KEYQ)
      return EX_BUSY;
    for (unsigned i = 0; i < q; i++)
      if ((pdu[6 + i / 8] >> (i % 8)) & 1)
        push_key(d, (int)(a + i) + 1);
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

int mb_dev_request(struct mb_dev *d, const uint8_t *req, size_t len, uint8_t *rsp, double now)
{
  /* len >= 8 and <= MB_FRAME_MAX: mb_frame checked the length field */
  const uint8_t *pdu = req + 7;
  size_t pl = len - 7, ol = 0;
  uint8_t *out = rsp + 7;
  memcpy(rsp, req, 7);           /* transaction id, protocol id, unit id */
  int ex = req[6] == 1 || req[6] == 255 ? handle(d, pdu, pl, out, &ol, now) : EX_GATEWAY;
  if (ex) {
    out[0] = (uint8_t)(pdu[0] | 0x80);
    out[1] = (uint8_t)ex;
    ol = 2;
  }
  rsp[4] = (uint8_t)((ol + 1) >> 8);
  rsp[5] = (uint8_t)(ol + 1);
  return (int)(7 + ol);
}

/* ---- the server ---- */

struct mb_client {
  int fd;
  size_t nin, nout;
  double since_in;     /* when the unfinished frame in `in` began */
  double since_out;    /* when the unsent reply in `out` was queued */
  double last;         /* last bytes received */
  uint8_t in[2 * MB_FRAME_MAX];
  uint8_t out[4 * MB_FRAME_MAX];
};

struct mb_server {
  modbus_t *ctx;
  int lfd;
  int ncl;
  struct mb_client cl[MB_MAX_CLIENTS];
  struct mb_dev dev;
  struct mb_machine none;   /* served until the host's first mb_poll */
  char addr[96];
};

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

struct mb_server *mb_open(const char *addr, char *err, size_t n, int *usage)
{
  char host[256], port[8];
  *usage = 1;
  if (!addr || !*addr)
    addr = MB_DEFAULT_ADDR;
  if (split_addr(addr, host, sizeof host, port, sizeof port, err, n))
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
  signal(SIGPIPE, SIG_IGN);      /* a client that went away is not our death */
  struct mb_server *mb = calloc(1, sizeof *mb);
  if (!mb) {
    snprintf(err, n, "out of memory");
    return NULL;
  }
  mb->lfd = -1;
  mb->ctx = modbus_new_tcp_pi(host, port);
  if (!mb->ctx) {
    snprintf(err, n, "Modbus on %s: %s", addr, modbus_strerror(errno));
    free(mb);
    return NULL;
  }
  errno = 0;
  mb->lfd = modbus_tcp_pi_listen(mb->ctx, 16);
  if (mb->lfd < 0) {
    int e = errno ? errno : EADDRNOTAVAIL;
    snprintf(err, n, "Modbus on %s:%s: %s", host, port, e == EADDRINUSE ? "the port is in use" : strerror(e));
    modbus_free(mb->ctx);
    free(mb);
    return NULL;
  }
  fcntl(mb->lfd, F_SETFL, fcntl(mb->lfd, F_GETFL) | O_NONBLOCK);
  fcntl(mb->lfd, F_SETFD, FD_CLOEXEC);
  struct sockaddr_storage ss;
  socklen_t sl = sizeof ss;
  char h[80], sv[8];
  if (getsockname(mb->lfd, (struct sockaddr *)&ss, &sl) == 0 &&
      getnameinfo((struct sockaddr *)&ss, sl, h, sizeof h, sv, sizeof sv, NI_NUMERICHOST | NI_NUMERICSERV) == 0)
    snprintf(mb->addr, sizeof mb->addr, ss.ss_family == AF_INET6 ? "[%s]:%s" : "%s:%s", h, sv);
  else
    snprintf(mb->addr, sizeof mb->addr, "%s:%s", host, port);
  mb_dev_init(&mb->dev, &mb->none);
  return mb;
}

static void drop(struct mb_server *mb, int i)
{
  close(mb->cl[i].fd);
  mb->cl[i] = mb->cl[--mb->ncl];
}

void mb_close(struct mb_server *mb)
{
  if (!mb)
    return;
  while (mb->ncl)
    drop(mb, mb->ncl - 1);
  if (mb->lfd >= 0)
    close(mb->lfd);
  modbus_set_socket(mb->ctx, -1);
  modbus_free(mb->ctx);
  free(mb);
}

const char *mb_address(const struct mb_server *mb)
{
  return mb->addr;
}

int mb_clients(const struct mb_server *mb)
{
  return mb->ncl;
}

int mb_key(struct mb_server *mb)
{
  return mb_dev_key(&mb->dev);
}

static int room(const struct mb_client *c)
{
  return sizeof c->out - c->nout >= MB_FRAME_MAX;
}

int mb_fds(const struct mb_server *mb, struct pollfd *fds, int max)
{
  int n = 0;
  if (max < 1)
    return 0;
  fds[n].fd = mb->lfd;
  fds[n].events = POLLIN;
  fds[n++].revents = 0;
  for (int i = 0; i < mb->ncl && n < max; i++) {
    const struct mb_client *c = &mb->cl[i];
    fds[n].fd = c->fd;
    fds[n].events = (short)((c->nout ? POLLOUT : 0) | (room(c) && c->nin < sizeof c->in ? POLLIN : 0));
    fds[n++].revents = 0;
  }
  return n;
}

/* 0 kept, -1 dropped (the caller must not touch c again). */
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

/* Answer the complete frames in the input buffer while replies fit. */
static int pump(struct mb_server *mb, int i, double now)
{
  struct mb_client *c = &mb->cl[i];
  for (;;) {
    long fl = mb_frame(c->in, c->nin);
    if (fl < 0) {                /* not Modbus TCP: this connection ends */
      drop(mb, i);
      return -1;
    }
    if (fl == 0 || !room(c))
      break;
    if (!c->nout)
      c->since_out = now;
    c->nout += (size_t)mb_dev_request(&mb->dev, c->in, (size_t)fl, c->out + c->nout, now);
    c->nin -= (size_t)fl;
    memmove(c->in, c->in + fl, c->nin);
    c->since_in = now;
  }
  return flush_out(mb, i, now);
}

static void accept_all(struct mb_server *mb, double now)
{
  for (int k = 0; k < 16; k++) {
    int fd = modbus_tcp_pi_accept(mb->ctx, &mb->lfd);
    modbus_set_socket(mb->ctx, -1);   /* the connection is ours, not the context's */
    if (fd < 0)
      return;                    /* EAGAIN: none left (or it went away) */
    if (mb->ncl >= MB_MAX_CLIENTS) {
      close(fd);                 /* over the limit: refused at once */
      continue;
    }
    int one = 1;
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    struct mb_client *c = &mb->cl[mb->ncl++];
    memset(c, 0, offsetof(struct mb_client, in));
    c->fd = fd;
    c->last = c->since_in = c->since_out = now;
  }
}

static void read_in(struct mb_server *mb, int i, double now)
{
  struct mb_client *c = &mb->cl[i];
  if (c->nin >= sizeof c->in || !room(c))
    return;
  ssize_t r = recv(c->fd, c->in + c->nin, sizeof c->in - c->nin, MSG_DONTWAIT);
  if (r == 0 || (r < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
    drop(mb, i);
    return;
  }
  if (r < 0)
    return;
  if (!c->nin)
    c->since_in = now;
  c->nin += (size_t)r;
  c->last = now;
  pump(mb, i, now);
}

static int find(const struct mb_server *mb, int fd)
{
  for (int i = 0; i < mb->ncl; i++)
    if (mb->cl[i].fd == fd)
      return i;
  return -1;
}

/* The earliest deadline of client c, or 0 when it has none. */
static double deadline(const struct mb_client *c)
{
  double t = c->last + IDLE_TIMEOUT;
  if (c->nin && mb_frame(c->in, c->nin) == 0 && c->since_in + FRAME_TIMEOUT < t)
    t = c->since_in + FRAME_TIMEOUT;
  if (c->nout && c->since_out + SEND_TIMEOUT < t)
    t = c->since_out + SEND_TIMEOUT;
  return t;
}

void mb_serve(struct mb_server *mb, struct mb_machine *m, const struct pollfd *fds, int n)
{
  double now = mb_now();
  mb->dev.m = m ? m : &mb->none;
  for (int k = 0; k < n; k++) {
    short re = fds[k].revents;
    if (!re)
      continue;
    if (fds[k].fd == mb->lfd) {
      accept_all(mb, now);
      continue;
    }
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
    if (now >= deadline(&mb->cl[i]))
      drop(mb, i);               /* a truncated frame, a stuck reply, silence */
}

int mb_timeout(const struct mb_server *mb, int want_ms)
{
  double now = mb_now();
  for (int i = 0; i < mb->ncl; i++) {
    double left = (deadline(&mb->cl[i]) - now) * 1000;
    int ms = left <= 0 ? 0 : left > 1e6 ? 1000000 : (int)ceil(left);
    if (want_ms < 0 || ms < want_ms)
      want_ms = ms;
  }
  return want_ms;
}

int mb_poll(struct mb_server *mb, struct mb_machine *m, int timeout_ms)
{
  struct pollfd fds[1 + MB_MAX_CLIENTS];
  int n = mb_fds(mb, fds, 1 + MB_MAX_CLIENTS);
  int r = poll(fds, (nfds_t)n, mb_timeout(mb, timeout_ms));
  if (r < 0) {
    if (errno == EINTR)
      return 0;
    return -1;
  }
  mb_serve(mb, m, fds, n);
  return 0;
}
