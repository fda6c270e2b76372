/* libFuzzer harness for the Modbus request handler (src/host/modbus.h) without
 * sockets: the input is a byte stream as a client would send it, cut into
 * frames by mb_frame and answered by mb_dev_request from the view of a live
 * runner of a 2С42 program (a write it leaves to the host applied as
 * mb_sync would); the keys pressed are taken and the machine steps between
 * frames.  The
 * connection code itself is fuzz_modbus_conn.c's. */
#include "compile.h"
#include "modbus.h"
#include "mrun.h"
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char prog_src[] =
  "№1 G01 X+1000 F600 ^\n№2 G20 ^\n№3 PP5 ^\n№4 P1 ^\n№5 R5+100/R1 ^\n№6 G04 X+1 M02 ^\n";

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
  struct mrun *mr = runner_of(&p);
  struct mb_dev *dev = malloc(sizeof *dev);
  if (!mr || !dev) {
    runner_free(mr);
    free(dev);
    return 0;
  }
  struct mb_machine m;
  memset(&m, 0, sizeof m);
  m.r = mr;
  m.idle = data[0] & 1;
  if (data[0] & 2) {           /* a paced block under way */
    m.motion.active = 1;
    m.motion.held = (data[0] >> 2) & 1;
    m.motion.held_frac = 0.5;
    m.motion.start = 0;
    m.motion.end = 2;
    m.motion.d[0] = 1000;
    m.motion.feed = 600;
    m.motion.block = 1;
  }
  mb_dev_init(dev);
  dev->read_only = (data[0] >> 3) & 1;
  data++;
  size--;
  uint8_t rsp[MB_FRAME_MAX];
  double now = 0.5;
  while (size) {
    long n = mb_frame(data, size);
    if (n <= 0)
      break;                   /* malformed (closed) or truncated (times out) */
    mb_view_of(&dev->v, &m);
    int r = mb_dev_request(dev, data, (size_t)n, rsp, now);
    if (r == 0) {              /* a write for the host: its header must be there */
      if (n < 12)
        abort();
      int ex = mb_dev_apply(dev, &m, &dev->w, now);
      if (ex != 0 && ex != 6)
        abort();
      r = mb_dev_reply(data, ex, rsp);
    }
    if (r < 9 || r > MB_FRAME_MAX || memcmp(rsp, data, 4) != 0 || (rsp[4] << 8 | rsp[5]) + 6 != r)
      abort();                 /* a reply must be a well-formed frame */
    data += n;
    size -= (size_t)n;
    now += 0.1;
    for (int k; (k = mb_dev_key(dev)) != MB_KEY_NONE;)
      press(mr, &m, k);
    if (!m.idle && (mr->state == MR_ROW || mr->state == MR_START || (mr->state == MR_WAIT && mr->resume)))
      mrun_run(mr);
  }
  free(dev);
  runner_free(mr);
  return 0;
}
