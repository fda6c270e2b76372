/* libFuzzer harness for the Modbus server's connection code (src/host/modbus.c:
 * accept, read buffering, framing, pipelining, replies that wait for the
 * host, time-outs, the slot limit and where a newcomer goes, close)
 * through real loopback sockets.  The input is a script of operations:
 * connect a client (from 127.0.0.1 or 127.0.0.2: one address holds at
 * most 2 of the 3 places, so both the cap and full slots happen), send it bytes,
 * half-close or close it, step the server loop, move the server's clock,
 * let the host take keys and writes.  The server runs without its thread
 * (mb_step) on a clock this harness moves, so time-outs come when the input
 * says.  Every reply must be a well-formed frame answering, in order, a
 * complete request its client sent. */
#include "compile.h"
#include "modbus.h"
#include "mrun.h"
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char prog_src[] =
  "№1 G01 X+1000 F600 ^\n№2 G20 ^\n№3 PP5 ^\n№4 P1 ^\n№5 R5+100/R1 ^\n№6 G04 X+1 M02 ^\n";

#define NCL 4                    /* clients of one input; the server takes 3 */
#define SENT_MAX 16384

static double clock_now;

static double fake_clock(void)
{
  return clock_now;
}

struct client {
  int fd;                        /* -1 closed */
  uint8_t sent[SENT_MAX];        /* what it sent */
  size_t nsent, parsed;          /* sent[0..parsed) cut into frames */
  uint16_t tid[SENT_MAX / 8];    /* transaction ids of its complete requests, in order */
  uint8_t fc[SENT_MAX / 8];
  size_t nreq, nrep;             /* requests complete, replies seen */
  int bad;                       /* it sent a malformed header: nothing after it is answered */
  uint8_t in[4096];
  size_t nin;
};

static void cut(struct client *c)
{
  while (!c->bad) {
    long n = mb_frame(c->sent + c->parsed, c->nsent - c->parsed);
    if (n < 0)
      c->bad = 1;
    if (n <= 0)
      return;
    c->tid[c->nreq] = (uint16_t)(c->sent[c->parsed] << 8 | c->sent[c->parsed + 1]);
    c->fc[c->nreq++] = c->sent[c->parsed + 7];
    c->parsed += (size_t)n;
  }
}

/* Take what the server sent c and check every reply in it. */
static void take(struct client *c)
{
  if (c->fd < 0)
    return;
  for (;;) {
    ssize_t r = recv(c->fd, c->in + c->nin, sizeof c->in - c->nin, MSG_DONTWAIT);
    if (r <= 0)
      break;
    c->nin += (size_t)r;
    while (c->nin >= 6 && c->nin >= 6u + (unsigned)(c->in[4] << 8 | c->in[5])) {
      size_t n = 6u + (unsigned)(c->in[4] << 8 | c->in[5]);
      if (n < 9 || n > MB_FRAME_MAX || c->in[2] || c->in[3])
        abort();                 /* not a well-formed reply */
      if (c->nrep >= c->nreq)
        abort();                 /* a reply to no request */
      uint16_t tid = (uint16_t)(c->in[0] << 8 | c->in[1]);
      if (tid != c->tid[c->nrep] || (c->in[7] & 0x7F) != (c->fc[c->nrep] & 0x7F))
        abort();                 /* out of order, or another request's */
      if ((c->in[7] & 0x80) && n != 9)
        abort();
      c->nrep++;
      memmove(c->in, c->in + n, c->nin - n);
      c->nin -= n;
    }
  }
}

static void press(struct mrun *r, struct mb_machine *m, int k)
{
  struct mrun_input in = {.kind = MRI_PS, .axis2 = -1};
  switch (k) {
  case MB_KEY_PUSK:
    if (m->idle)
      m->idle = 0;
    else if (mrun_resume(r) && mrun_pusk(r) && r->state == MR_END)
      mrun_renew(r);
    break;
  case MB_KEY_STOP: mrun_stop(r); break;
  case MB_KEY_PS: mrun_input(r, &in, NULL, 0); break;
  case MB_KEY_EXIT:
    in.kind = MRI_EXIT;
    mrun_input(r, &in, NULL, 0);
    break;
  case MB_KEY_RESET:
    mrun_renew(r);
    m->idle = 1;
    break;
  default: break;
  }
}

/* A runner of p that comes back at every block's start. */
static struct mrun *runner_of(const struct program *p)
{
  struct mrun *r = malloc(sizeof *r);
  if (!r)
    return NULL;
  struct mrun_config c;
  memset(&c, 0, sizeof c);
  c.max_blocks = 2000;
  c.starts = 1;
  if (mrun_init(r, p, &c)) {
    mrun_free(r);
    free(r);
    return NULL;
  }
  return r;
}

static void runner_free(struct mrun *r)
{
  if (r)
    mrun_free(r);
  free(r);
}

/* A connection from 127.0.0.(1 + from) that is there at once, or none:
 * when the server's backlog is full a blocking connect would wait for SYN
 * retries (seconds). */
static int dial(int port, int from)
{
  int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0)
    return -1;
  struct sockaddr_in sa, src;
  memset(&sa, 0, sizeof sa);
  sa.sin_family = AF_INET;
  src = sa;
  sa.sin_port = htons((uint16_t)port);
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  src.sin_addr.s_addr = htonl(INADDR_LOOPBACK + (uint32_t)from);
  int one = 1, e = 0;
  socklen_t el = sizeof e;
  struct pollfd p = {.fd = fd, .events = POLLOUT, .revents = 0};
  if (bind(fd, (struct sockaddr *)&src, sizeof src) ||
      (connect(fd, (struct sockaddr *)&sa, sizeof sa) && errno != EINPROGRESS) || poll(&p, 1, 0) != 1 ||
      getsockopt(fd, SOL_SOCKET, SO_ERROR, &e, &el) || e) {
    struct linger l = {1, 0};
    setsockopt(fd, SOL_SOCKET, SO_LINGER, &l, sizeof l);
    close(fd);
    return -1;
  }
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  return fd;
}

/* Close without TIME_WAIT (a reset): thousands of inputs a second would
 * otherwise use up the ports. */
static void hang_up(struct client *c)
{
  if (c->fd < 0)
    return;
  struct linger l = {1, 0};
  setsockopt(c->fd, SOL_SOCKET, SO_LINGER, &l, sizeof l);
  close(c->fd);
  c->fd = -1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  static struct program p;
  static int compiled;
  if (!compiled) {
    struct diag_list d;
    prog_init(&p);
    diag_init(&d, "fuzz.kp");
    if (comp_program(prog_src, sizeof prog_src - 1, &d, &p))
      abort();
    diag_free(&d);
    compiled = 1;
  }
  if (size < 1)
    return 0;
  clock_now = 1000;
  struct mb_opts o;
  mb_opts_init(&o);
  o.addr = "127.0.0.1:0";
  o.max_clients = 3;
  o.idle = 2;
  o.read_only = data[0] & 1;
  o.no_thread = 1;
  o.clock = fake_clock;
  char err[300];
  int usage;
  struct mb_server *mb = mb_open(&o, err, sizeof err, &usage);
  if (!mb)
    return 0;                    /* no socket to be had (fd limit): not the code's fault */
  int port = atoi(strrchr(mb_address(mb), ':') + 1);
  struct mrun *r = runner_of(&p);
  struct client *cl = calloc(NCL, sizeof *cl);
  if (!r || !cl)
    abort();
  for (int i = 0; i < NCL; i++)
    cl[i].fd = -1;
  struct mb_machine m;
  memset(&m, 0, sizeof m);
  m.r = r;
  m.idle = (data[0] >> 1) & 1;
  mb_publish(mb, &m);
  size_t i = 1;
  int ops = 0;
  while (i < size && ops++ < 400) {
    uint8_t op = data[i++], arg = op & 0x1F;
    struct client *c = &cl[arg % NCL];
    switch (op >> 5) {
    case 0:                      /* a new client on the first free place */
      mb_step(mb, 0);            /* as the server thread would: take what waits to be accepted */
      for (int k = 0; k < NCL; k++)
        if (cl[k].fd < 0) {
          memset(&cl[k], 0, sizeof cl[k]);
          cl[k].fd = dial(port, arg & 1);
          break;
        }
      break;
    case 1: {                    /* send it the next n bytes */
      size_t n = i < size ? data[i++] : 0;
      if (n > size - i)
        n = size - i;
      if (c->fd >= 0 && n && c->nsent + n <= SENT_MAX) {
        ssize_t w = send(c->fd, data + i, n, MSG_DONTWAIT | MSG_NOSIGNAL);
        if (w > 0) {
          memcpy(c->sent + c->nsent, data + i, (size_t)w);
          c->nsent += (size_t)w;
          cut(c);
        }
      }
      i += n;
      break;
    }
    case 2:                      /* the server loop turns */
      for (int k = 0; k <= arg; k++)
        mb_step(mb, 0);
      break;
    case 3:                      /* time passes: 10 ms steps */
      clock_now += (arg + 1) * 0.01;
      mb_step(mb, 0);
      break;
    case 4:                      /* the host takes what waits for it */
      mb_sync(mb, &m);
      for (int k; (k = mb_key(mb)) != MB_KEY_NONE;)
        press(r, &m, k);
      for (int k = 0; k < (arg & 7) && !m.idle &&
                      (r->state == MR_ROW || r->state == MR_START || (r->state == MR_WAIT && r->resume)); k++)
        mrun_run(r);
      mb_publish(mb, &m);
      break;
    case 5:                      /* the client hangs up */
      take(c);
      if (arg & 0x10)
        hang_up(c);
      else if (c->fd >= 0) {
        close(c->fd);
        c->fd = -1;
      }
      break;
    case 6:                      /* it sends no more (half close) */
      if (c->fd >= 0)
        shutdown(c->fd, SHUT_WR);
      break;
    default:                     /* it reads its replies */
      mb_step(mb, 0);
      take(c);
      break;
    }
    if (mb_clients(mb) > o.max_clients)
      abort();                   /* more connections than places */
  }
  /* the end: the host and the server finish what is in flight */
  for (int k = 0; k < 4; k++) {
    mb_sync(mb, &m);
    mb_step(mb, 0);
    for (int j = 0; j < NCL; j++)
      take(&cl[j]);
  }
  for (int j = 0; j < NCL; j++)
    hang_up(&cl[j]);
  mb_close(mb);
  free(cl);
  runner_free(r);
  return 0;
}
