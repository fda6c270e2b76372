/* The Modbus device without sockets (src/host/modbus.h): golden words of our
 * big-endian encoders, MBAP framing, and requests against a runner of a
 * 2С42 program (and of a 2У22 one: its map) --
 * reads, key presses, parameter writes, the exceptions, the counter; allow
 * lists; where a newcomer goes when the slots are taken (mb_admit); and
 * the threaded server over loopback, its host played here: a
 * write waits for the host's thread and is decided with the machine's real
 * state, a read after it sees the value. */
#include "suites.h"
#include "errors.h"
#include "kprun.h"
#include "modbus.h"
#include "mrun.h"
#include "../../src/dialect/2u22/u22c.h"
#include <arpa/inet.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>

static struct tprog t;
static struct mrun *mr;
static struct mb_machine mm;
static struct mb_dev dev;
static uint8_t rsp[MB_FRAME_MAX];

static void setup(void)
{
  memset(&t, 0, sizeof t);
  prog_init(&t.p);
  diag_init(&t.d, "t.kp");
  mr = calloc(1, sizeof *mr);
  tp_compile(&t, "№1 G01 X+1000 F600 ^\n№2 R5+100/R1 ^\n№3 M02 ^\n");
  ck_assert_msg(t.rc == 0, "%s", tp_diags(&t.d));
  struct mrun_config c;
  memset(&c, 0, sizeof c);
  c.rows = 1;
  ck_assert_int_eq(mrun_init(mr, &t.p, &c), 0);
  memset(&mm, 0, sizeof mm);
  mm.r = mr;
  mb_dev_init(&dev);
}

static void teardown(void)
{
  mrun_free(mr);
  tp_free(&t);
  free(mr);
}

/* The 2С42's grinder under the runner. */
static struct machine *grinder(void)
{
  return &kp_st(mr)->m;
}

/* One frame as the server answers it: from the view of the machine now; a
 * write the host decides is applied to it, as mb_sync does, then replied. */
static int serve(const uint8_t *f, size_t n, double now)
{
  mb_view_of(&dev.v, &mm);
  int r = mb_dev_request(&dev, f, n, rsp, now);
  if (r == 0) {
    int ex = mb_dev_apply(&dev, &mm, &dev.w, now);
    mb_view_of(&dev.v, &mm);
    r = mb_dev_reply(f, ex, rsp);
  }
  return r;
}

/* Send a PDU (unit 1); returns the reply's PDU length, the PDU at rsp+7. */
static int req(const uint8_t *pdu, size_t n, double now)
{
  uint8_t f[MB_FRAME_MAX];
  f[0] = 0x12;
  f[1] = 0x34;
  f[2] = f[3] = 0;
  f[4] = (uint8_t)((n + 1) >> 8);
  f[5] = (uint8_t)(n + 1);
  f[6] = 1;
  memcpy(f + 7, pdu, n);
  ck_assert_int_eq(mb_frame(f, 7 + n), (long)(7 + n));
  int r = serve(f, 7 + n, now);
  ck_assert_int_ge(r, 9);
  ck_assert_int_eq(rsp[0], 0x12);   /* the transaction id comes back */
  ck_assert_int_eq(rsp[1], 0x34);
  ck_assert_int_eq((rsp[4] << 8 | rsp[5]) + 6, r);
  return r - 7;
}

static int exception(const uint8_t *pdu, size_t n)
{
  int l = req(pdu, n, 1.0);
  if (l != 2 || !(rsp[7] & 0x80))
    return 0;
  ck_assert_int_eq(rsp[7], pdu[0] | 0x80);
  return rsp[8];
}

static uint16_t reg(int i)
{
  return (uint16_t)(rsp[9 + 2 * i] << 8 | rsp[10 + 2 * i]);
}

START_TEST(golden_words)
{
  uint16_t w[4];
  mb_put_f32(w, 1234.567f);
  ck_assert_uint_eq(w[0], 0x449A);
  ck_assert_uint_eq(w[1], 0x5225);
  ck_assert(mb_get_f32(w) == 1234.567f);
  mb_put_i32(w, 123456);
  ck_assert_uint_eq(w[0], 0x0001);
  ck_assert_uint_eq(w[1], 0xE240);
  mb_put_u32(w, 123456);
  ck_assert_uint_eq(w[0], 0x0001);
  ck_assert_uint_eq(w[1], 0xE240);
  mb_put_i32(w, -2);
  ck_assert_uint_eq(w[0], 0xFFFF);
  ck_assert_uint_eq(w[1], 0xFFFE);
  ck_assert_int_eq(mb_get_i32(w), -2);
  mb_put_i32(w, INT32_MIN);
  ck_assert_int_eq(mb_get_i32(w), INT32_MIN);
  mb_put_f64(w, 1234.567);
  ck_assert_uint_eq(w[0], 0x4093);
  ck_assert_uint_eq(w[1], 0x4A44);
  ck_assert_uint_eq(w[2], 0x9BA5);
  ck_assert_uint_eq(w[3], 0xE354);
  ck_assert(mb_get_f64(w) == 1234.567);
  mb_put_f64(w, -0.5);
  ck_assert_uint_eq(w[0], 0xBFE0);
  ck_assert_uint_eq(w[1] | w[2] | w[3], 0);
}
END_TEST

START_TEST(framing)
{
  uint8_t f[12] = {0, 1, 0, 0, 0, 6, 1, 4, 0, 0, 0, 1};
  ck_assert_int_eq(mb_frame(f, 0), 0);
  ck_assert_int_eq(mb_frame(f, 5), 0);
  ck_assert_int_eq(mb_frame(f, 11), 0);
  ck_assert_int_eq(mb_frame(f, 12), 12);
  f[3] = 1;                               /* protocol id */
  ck_assert_int_eq(mb_frame(f, 4), -1);
  f[3] = 0;
  f[5] = 1;                               /* length below unit id + function */
  ck_assert_int_eq(mb_frame(f, 6), -1);
  f[4] = 1;
  f[5] = 0;                               /* 256: above the largest PDU */
  ck_assert_int_eq(mb_frame(f, 6), -1);
  f[4] = 0;
  f[5] = 254;
  ck_assert_int_eq(mb_frame(f, 12), 0);   /* the largest: wait for it */
}
END_TEST

START_TEST(idle_image)
{
  static const uint8_t rd[] = {4, 0, 0, 0, 22};
  ck_assert_int_eq(req(rd, sizeof rd, 1.0), 2 + 44);
  ck_assert_uint_eq(reg(0), MB_MAP_VERSION);
  ck_assert_uint_eq(reg(2), MB_RUN);      /* a machine not marked idle runs */
  mm.idle = 1;
  req(rd, sizeof rd, 1.0);
  ck_assert_uint_eq(reg(2), MB_IDLE);
  ck_assert_uint_eq(reg(5), 100);
}
END_TEST

START_TEST(counter_and_alive)
{
  static const uint8_t rd[] = {4, 0, 1, 0, 1};
  static const uint8_t di[] = {2, 0, 15, 0, 1};
  mm.idle = 1;
  req(rd, sizeof rd, 1.0);
  uint16_t c = reg(0);
  req(rd, sizeof rd, 1.1);                /* nothing changed, no heartbeat yet */
  ck_assert_uint_eq(reg(0), c);
  req(di, sizeof di, 1.1);
  int alive = rsp[9] & 1;
  req(rd, sizeof rd, 1.4);                /* the heartbeat */
  ck_assert_uint_eq(reg(0), (uint16_t)(c + 1));
  req(di, sizeof di, 1.4);
  ck_assert_int_eq(rsp[9] & 1, !alive);
  mr->vm.reg[3] = 7;                       /* a change: an update at once */
  req(rd, sizeof rd, 1.45);
  ck_assert_uint_eq(reg(0), (uint16_t)(c + 2));
  /* no request for 1.05 s: the four heartbeats went by all the same */
  req(rd, sizeof rd, 2.5);
  ck_assert_uint_eq(reg(0), (uint16_t)(c + 6));
  req(rd, sizeof rd, 2.6);
  ck_assert_uint_eq(reg(0), (uint16_t)(c + 6));
}
END_TEST

static int keeps_override(void *host, int pct)
{
  (void)host;
  mm.override_pct = pct;
  return 0;
}

/* Coil 5 is the single-block switch and holding register 2 the breakpoint:
 * both go to the runner (or a host that keeps them), and read back. */
START_TEST(single_block_and_breakpoint)
{
  mm.idle = 1;
  static const uint8_t on[] = {5, 0, 5, 0xFF, 0}, off[] = {5, 0, 5, 0, 0}, rdc[] = {1, 0, 0, 0, 6},
                       brk[] = {6, 0, 2, 0, 2}, rdh[] = {3, 0, 0, 0, 3}, both[] = {15, 0, 4, 0, 2, 1, 0x02},
                       hr3[] = {6, 0, 3, 0, 1}, coil6[] = {5, 0, 6, 0xFF, 0};
  ck_assert_int_eq(req(on, sizeof on, 1.0), 5);
  ck_assert_int_eq(rsp[8], 0);            /* the echo of the request */
  ck_assert_int_eq(rsp[9], 5);
  ck_assert_int_eq(mm.single, 1);
  ck_assert_int_eq(mr->single, 1);
  req(rdc, sizeof rdc, 1.0);
  ck_assert_int_eq(rsp[9], 0x20);         /* coil 5 reads the switch; no key waits */
  ck_assert_int_eq(req(brk, sizeof brk, 1.0), 5);
  ck_assert_int_eq(mr->brk, 2);
  req(rdh, sizeof rdh, 1.0);
  ck_assert_uint_eq(reg(0), 100);
  ck_assert_uint_eq(reg(2), 2);
  ck_assert_int_eq(req(off, sizeof off, 1.0), 5);
  ck_assert_int_eq(mr->single, 0);
  /* FC 15 over coils 4 and 5: reset pressed, single block set from the same write */
  ck_assert_int_eq(req(both, sizeof both, 1.0), 5);
  ck_assert_int_eq(mr->single, 1);
  ck_assert_int_eq(mb_dev_key(&dev), MB_KEY_NONE);   /* bit 0 (coil 4) was 0 */
  ck_assert_int_eq(exception(hr3, sizeof hr3), 2);
  ck_assert_int_eq(exception(coil6, sizeof coil6), 2);
  /* the breakpoint waits: block 2 waits for Пуск before it starts */
  enum mrun_ev ev;
  struct mrun_input auto_mode = {.kind = MRI_MODE, .axis = MRM_SINGLE, .n = 0};
  ck_assert_int_eq(mrun_input(mr, &auto_mode, NULL, 0), 0);
  while ((ev = mrun_run(mr)) == MR_START || ev == MR_ROW)
    ;
  ck_assert_int_eq(ev, MR_WAIT);
  ck_assert_int_eq(mr->wait, MRW_BLOCK);
  ck_assert_int_eq(mrun_block_number(mr), 2);
  /* a terminal that is idle (nothing loaded yet): the override in effect
   * is its switch's position */
  mm.r = NULL;
  mm.override_pct = 70;
  mm.set_override = keeps_override;
  static const uint8_t rd5[] = {4, 0, 5, 0, 1};
  req(rd5, sizeof rd5, 1.0);
  ck_assert_uint_eq(reg(0), 70);
}
END_TEST

START_TEST(parameters)
{
  mm.idle = 1;
  uint8_t wr[6 + 8] = {16, 0, 104, 0, 4, 8};
  uint16_t w[4];
  mb_put_f64(w, 4.25);
  for (int i = 0; i < 4; i++) {
    wr[6 + 2 * i] = (uint8_t)(w[i] >> 8);
    wr[7 + 2 * i] = (uint8_t)w[i];
  }
  ck_assert_int_eq(req(wr, sizeof wr, 1.0), 5);
  ck_assert(mr->vm.reg[1] == 4.25);
  static const uint8_t rd64[] = {4, 0, 104, 0, 4}, rd32[] = {3, 2, 0x5A, 0, 2};   /* IR 104, HR 602 */
  req(rd64, sizeof rd64, 1.0);
  uint16_t g[4] = {reg(0), reg(1), reg(2), reg(3)};
  ck_assert(mb_get_f64(g) == 4.25);
  req(rd32, sizeof rd32, 1.0);
  uint16_t h[2] = {reg(0), reg(1)};
  ck_assert(mb_get_f32(h) == 4.25f);
  /* a float32 write keeps the decimal the client meant */
  uint8_t wr32[6 + 4] = {16, 2, 0x5A, 0, 2, 4};
  mb_put_f32(w, 1234.567f);
  wr32[6] = (uint8_t)(w[0] >> 8);
  wr32[7] = (uint8_t)w[0];
  wr32[8] = (uint8_t)(w[1] >> 8);
  wr32[9] = (uint8_t)w[1];
  ck_assert_int_eq(req(wr32, sizeof wr32, 1.0), 5);
  ck_assert(mr->vm.reg[1] == 1234.567);
  /* refused while the cycle runs */
  mm.idle = 0;
  ck_assert_int_eq(exception(wr, sizeof wr), 6);
  ck_assert(mr->vm.reg[1] == 1234.567);
}
END_TEST

START_TEST(exceptions)
{
  mm.idle = 1;
  static const uint8_t unknown[] = {0x2B, 0x0E, 1, 0}, qty0[] = {4, 0, 0, 0, 0}, qty126[] = {3, 0, 0, 0, 126},
                       gap[] = {4, 0, 22, 0, 1}, across[] = {4, 0, 20, 0, 90}, coil5[] = {5, 0, 6, 0xFF, 0},
                       coilval[] = {5, 0, 0, 0x12, 0x34}, single_r[] = {6, 0, 100, 0, 1},
                       ovr[] = {6, 0, 0, 0, 151}, cmd[] = {6, 0, 1, 0, 6}, shortpdu[] = {4, 0},
                       half[] = {16, 0, 100, 0, 2, 4, 0, 0, 0, 0}, odd32[] = {16, 2, 0x59, 0, 2, 4, 0, 0, 0, 0},
                       bc[] = {16, 0, 0, 0, 1, 4, 0, 5}, nan64[] = {16, 0, 100, 0, 4, 8, 0x7F, 0xF8, 0, 0, 0, 0, 0, 0},
                       big64[] = {16, 0, 100, 0, 4, 8, 0x41, 0xA0, 0, 0, 0, 0, 0, 0};   /* 1.34e8 */
  ck_assert_int_eq(exception(unknown, sizeof unknown), 1);
  ck_assert_int_eq(exception(qty0, sizeof qty0), 3);
  ck_assert_int_eq(exception(qty126, sizeof qty126), 3);
  ck_assert_int_eq(exception(gap, sizeof gap), 2);
  ck_assert_int_eq(exception(across, sizeof across), 2);
  ck_assert_int_eq(exception(coil5, sizeof coil5), 2);
  ck_assert_int_eq(exception(coilval, sizeof coilval), 3);
  ck_assert_int_eq(exception(single_r, sizeof single_r), 2);
  ck_assert_int_eq(exception(ovr, sizeof ovr), 3);
  ck_assert_int_eq(exception(cmd, sizeof cmd), 3);
  ck_assert_int_eq(exception(shortpdu, sizeof shortpdu), 3);
  ck_assert_int_eq(exception(half, sizeof half), 2);
  ck_assert_int_eq(exception(odd32, sizeof odd32), 2);
  ck_assert_int_eq(exception(bc, sizeof bc), 3);
  ck_assert_int_eq(exception(nan64, sizeof nan64), 3);
  ck_assert_int_eq(exception(big64, sizeof big64), 3);
  grinder()->override_allowed = 0;        /* M25 */
  static const uint8_t ovr50[] = {6, 0, 0, 0, 50};
  ck_assert_int_eq(exception(ovr50, sizeof ovr50), 6);
  /* another unit id: gateway target failed */
  uint8_t f[12] = {0, 1, 0, 0, 0, 6, 7, 4, 0, 0, 0, 1};
  ck_assert_int_eq(serve(f, sizeof f, 1.0), 9);
  ck_assert_int_eq(rsp[8], 0x0B);
}
END_TEST

START_TEST(keys_in_order)
{
  static const uint8_t pusk[] = {5, 0, 0, 0xFF, 0}, rdc[] = {1, 0, 0, 0, 5}, multi[] = {15, 0, 1, 0, 4, 1, 0x0A},
                       cmd5[] = {6, 0, 1, 0, 5}, rdcmd[] = {3, 0, 1, 0, 1};
  ck_assert_int_eq(req(pusk, sizeof pusk, 1.0), 5);
  req(rdc, sizeof rdc, 1.0);
  ck_assert_int_eq(rsp[9], 0x01);         /* Пуск shows until taken */
  req(multi, sizeof multi, 1.0);          /* coils 1..4 = 0,1,0,1: ПС and reset */
  req(cmd5, sizeof cmd5, 1.0);
  req(rdcmd, sizeof rdcmd, 1.0);
  ck_assert_uint_eq(reg(0), MB_KEY_PUSK); /* the oldest key not taken */
  ck_assert_int_eq(mb_dev_key(&dev), MB_KEY_PUSK);
  ck_assert_int_eq(mb_dev_key(&dev), MB_KEY_PS);
  ck_assert_int_eq(mb_dev_key(&dev), MB_KEY_RESET);
  ck_assert_int_eq(mb_dev_key(&dev), MB_KEY_RESET);
  ck_assert_int_eq(mb_dev_key(&dev), MB_KEY_NONE);
  req(rdc, sizeof rdc, 1.0);
  ck_assert_int_eq(rsp[9], 0);
  for (int i = 0; i < MB_KEYQ; i++)
    ck_assert_int_eq(req(pusk, sizeof pusk, 1.0), 5);
  ck_assert_int_eq(exception(pusk, sizeof pusk), 6);   /* full: busy */
}
END_TEST

START_TEST(positions_between_blocks)
{
  mm.idle = 0;
  grinder()->pos[0] = 1000;               /* the block has ended in the model */
  mm.motion.active = 1;
  mm.motion.start = 10;
  mm.motion.end = 11;
  mm.motion.d[0] = 1000;
  mm.motion.feed = 600;
  mm.motion.block = 1;
  static const uint8_t rd[] = {4, 0, 0, 0, 22}, di[] = {2, 0, 0, 0, 11};
  req(rd, sizeof rd, 10.25);
  uint16_t x[2] = {reg(10), reg(11)}, v[2] = {reg(18), reg(19)};
  ck_assert_int_eq(mb_get_i32(x), 250);
  ck_assert_int_eq(mb_get_i32(v), 600000);
  ck_assert_uint_eq(reg(2), MB_RUN);
  ck_assert_uint_eq(reg(3), 1);
  req(di, sizeof di, 10.5);
  ck_assert_int_eq(rsp[9] & 0x81, 0x81);  /* running, X moving */
  mm.motion.held = 1;                     /* feed hold */
  mm.motion.held_frac = 0.5;
  req(rd, sizeof rd, 10.9);
  uint16_t y[2] = {reg(10), reg(11)};
  ck_assert_int_eq(mb_get_i32(y), 500);
  ck_assert_uint_eq(reg(2), MB_STOPPED);
}
END_TEST

/* Block numbers are 32 bits (2У22 5 digits, FMS-3000 7): input register 3
 * shows one that fits in 16 bits and 0 for one above 65535. */
START_TEST(block_number_above_16_bits)
{
  static const uint8_t rd[] = {4, 0, 0, 0, 22};
  mm.idle = 0;
  t.p.blocks[mr->vm.cur].number = 65535;
  req(rd, sizeof rd, 1.0);
  ck_assert_uint_eq(reg(3), 65535);
  t.p.blocks[mr->vm.cur].number = 65536;
  req(rd, sizeof rd, 1.0);
  ck_assert_uint_eq(reg(3), 0);
  t.p.blocks[mr->vm.cur].number = 9999999;
  req(rd, sizeof rd, 1.0);
  ck_assert_uint_eq(reg(3), 0);
  mm.motion.active = 1;                   /* a move of that block, under way */
  mm.motion.start = 1;
  mm.motion.end = 2;
  mm.motion.block = mrun_block_number(mr);
  req(rd, sizeof rd, 1.5);
  ck_assert_uint_eq(reg(3), 0);
}
END_TEST

START_TEST(read_only_device)
{
  mm.idle = 1;
  dev.read_only = 1;
  static const uint8_t coil[] = {5, 0, 0, 0xFF, 0}, ovr[] = {6, 0, 0, 0, 50}, coils[] = {15, 0, 0, 0, 1, 1, 1},
                       r1[] = {16, 0, 104, 0, 4, 8, 0x40, 0x10, 0, 0, 0, 0, 0, 0}, bad[] = {5, 0, 9, 0x12, 0x34},
                       rd[] = {4, 0, 0, 0, 1};
  ck_assert_int_eq(exception(coil, sizeof coil), 1);
  ck_assert_int_eq(exception(ovr, sizeof ovr), 1);
  ck_assert_int_eq(exception(coils, sizeof coils), 1);
  ck_assert_int_eq(exception(r1, sizeof r1), 1);
  ck_assert_int_eq(exception(bad, sizeof bad), 1);   /* any write, even a malformed one */
  ck_assert(mr->vm.reg[1] == 0);
  ck_assert_int_eq(mb_dev_key(&dev), MB_KEY_NONE);
  ck_assert_int_eq(req(rd, sizeof rd, 1.0), 4);
  ck_assert_uint_eq(reg(0), MB_MAP_VERSION);
}
END_TEST

/* The override written while a block's move plays out on the wall clock
 * (--realtime): the runtime re-times the rest of the move once, from the
 * simulated time the motion has reached, and the motion follows from where
 * it is; 0 % holds it, 100 % goes on from there. */
START_TEST(override_within_a_paced_move)
{
  ck_assert_int_eq(mrun_run(mr), MR_ROW);   /* N1: 1 mm at F600, 0.1 s */
  ck_assert(fabs(mrun_time(mr) - 0.1) < 1e-9);
  mm.feed = 600;
  const int64_t d[4] = {1000, 0, 0, 0};
  mb_motion_start(&mm, 10, 0.1, d, 600, 1);
  static const uint8_t o50[] = {6, 0, 0, 0, 50}, o0[] = {6, 0, 0, 0, 0}, o100[] = {6, 0, 0, 0, 100},
                       rd[] = {4, 0, 0, 0, 22};
  ck_assert_int_eq(req(o50, sizeof o50, 10.05), 5);   /* half way: the rest at half the speed */
  ck_assert(fabs(mrun_time(mr) - 0.15) < 1e-9);
  ck_assert(fabs(mm.motion.start - 9.95) < 1e-9 && fabs(mm.motion.end - 10.15) < 1e-9);
  ck_assert(mm.motion.feed == 300 && mm.feed == 300);
  req(rd, sizeof rd, 10.05);
  uint16_t x[2] = {reg(10), reg(11)}, v[2] = {reg(18), reg(19)}, tm[2] = {reg(20), reg(21)};
  ck_assert_int_eq(mb_get_i32(x), 500);    /* from where it was */
  ck_assert_int_eq(mb_get_i32(v), 300000);
  ck_assert_uint_eq(mb_get_u32(tm), 50);   /* 0.05 s simulated */
  ck_assert_int_eq(req(o0, sizeof o0, 10.10), 5);     /* 0 %: it stands */
  ck_assert_int_eq(mm.motion.held, 1);
  ck_assert_int_eq(mm.ovr_held, 1);
  req(rd, sizeof rd, 10.5);
  ck_assert_uint_eq(reg(2), MB_STOPPED);
  uint16_t x0[2] = {reg(10), reg(11)}, v0[2] = {reg(18), reg(19)};
  ck_assert_int_eq(mb_get_i32(x0), 750);
  ck_assert_int_eq(mb_get_i32(v0), 0);
  ck_assert(fabs(mrun_time(mr) - 0.15) < 1e-9);
  ck_assert_int_eq(req(o100, sizeof o100, 11.0), 5);  /* 100 %: on from there */
  ck_assert_int_eq(mm.motion.held, 0);
  ck_assert_int_eq(mm.ovr_held, 0);
  ck_assert(fabs(mrun_time(mr) - 0.125) < 1e-9);
  ck_assert(fabs(mm.motion.end - 11.025) < 1e-9);
  req(rd, sizeof rd, 11.0);
  uint16_t x1[2] = {reg(10), reg(11)}, v1[2] = {reg(18), reg(19)};
  ck_assert_uint_eq(reg(2), MB_RUN);
  ck_assert_int_eq(mb_get_i32(x1), 750);
  ck_assert_int_eq(mb_get_i32(v1), 600000);
  ck_assert_uint_eq(reg(5), 100);
}
END_TEST

/* The 2У22's map: X (a diameter) and Z in µm at 10-13, R0-R9 and nothing
 * beyond (02), the spindle and coolant at discrete inputs 5 and 6, F% in
 * effect under G20 only. */
START_TEST(lathe_map)
{
  struct program p;
  struct diag_list d;
  prog_init(&p);
  diag_init(&d, "t.u22");
  const char *src = "%\nN1 T1 G01 G90 G94 G97 S500 M03 M39 M08 R3+250\nN2 F1000 X4000 Z-1000\nN3 G20 F100 Z-2000\n"
                    "N4 M02\n";
  ck_assert_int_eq(u22_compile(src, strlen(src), &d, &p), 0);
  struct mrun lr;
  struct mrun_config c;
  memset(&c, 0, sizeof c);
  c.rows = 1;
  ck_assert_int_eq(mrun_init(&lr, &p, &c), 0);
  mm.r = &lr;
  mm.idle = 0;
  ck_assert_int_eq(mrun_run(&lr), MR_ROW);   /* N1 */
  ck_assert_int_eq(mrun_run(&lr), MR_ROW);   /* N2 */
  static const uint8_t rd[] = {4, 0, 0, 0, 22}, di[] = {2, 0, 0, 0, 16}, r3[] = {4, 0, 112, 0, 4},
                       r10[] = {4, 0, 140, 0, 4}, r10_32[] = {4, 2, 0x6C, 0, 2}, o50[] = {6, 0, 0, 0, 50};
  req(rd, sizeof rd, 1.0);
  uint16_t x[2] = {reg(10), reg(11)}, z[2] = {reg(12), reg(13)};
  ck_assert_int_eq(mb_get_i32(x), 40000);    /* Ø 40 mm */
  ck_assert_int_eq(mb_get_i32(z), -10000);
  ck_assert_uint_eq(reg(14) | reg(15) | reg(16) | reg(17), 0);
  ck_assert_uint_eq(reg(3), 2);
  ck_assert_uint_eq(reg(5), 100);            /* G23: F% does not act */
  req(di, sizeof di, 1.0);
  ck_assert_int_eq(rsp[9] & 0x60, 0x60);     /* spindle, coolant */
  req(r3, sizeof r3, 1.0);
  uint16_t g[4] = {reg(0), reg(1), reg(2), reg(3)};
  ck_assert(mb_get_f64(g) == 250);
  ck_assert_int_eq(exception(r10, sizeof r10), 2);      /* R10: the lathe has none */
  ck_assert_int_eq(exception(r10_32, sizeof r10_32), 2);
  uint8_t wr[6 + 8] = {16, 0, 140, 0, 4, 8};
  ck_assert_int_eq(exception(wr, sizeof wr), 2);
  ck_assert_int_eq(exception(o50, sizeof o50), 0);      /* the switch is kept under G23 */
  ck_assert_int_eq(lr.override, 50);
  req(rd, sizeof rd, 1.0);
  ck_assert_uint_eq(reg(5), 100);
  ck_assert_int_eq(mrun_run(&lr), MR_ROW);   /* N3 under G20: at 50 % */
  req(rd, sizeof rd, 1.0);
  ck_assert_uint_eq(reg(5), 50);
  mrun_free(&lr);
  prog_free(&p);
  diag_free(&d);
}
END_TEST

static struct sockaddr_in v4(const char *a)
{
  struct sockaddr_in sa;
  memset(&sa, 0, sizeof sa);
  sa.sin_family = AF_INET;
  ck_assert_int_eq(inet_pton(AF_INET, a, &sa.sin_addr), 1);
  return sa;
}

static struct sockaddr_in6 v6(const char *a)
{
  struct sockaddr_in6 sa;
  memset(&sa, 0, sizeof sa);
  sa.sin6_family = AF_INET6;
  ck_assert_int_eq(inet_pton(AF_INET6, a, &sa.sin6_addr), 1);
  return sa;
}

START_TEST(allow_lists)
{
  struct mb_net v[8];
  char err[200];
  int n = mb_allow_parse("192.168.10.0/24,10.0.0.7,fd00::/8,::1", v, 8, err, sizeof err);
  ck_assert_int_eq(n, 4);
  struct sockaddr_in a;
  struct sockaddr_in6 b;
  a = v4("192.168.10.77"), ck_assert(mb_allow_match(v, n, &a));
  a = v4("192.168.11.1"), ck_assert(!mb_allow_match(v, n, &a));
  a = v4("10.0.0.7"), ck_assert(mb_allow_match(v, n, &a));
  a = v4("10.0.0.8"), ck_assert(!mb_allow_match(v, n, &a));
  b = v6("fd12:3456::1"), ck_assert(mb_allow_match(v, n, &b));
  b = v6("fe80::1"), ck_assert(!mb_allow_match(v, n, &b));
  b = v6("::1"), ck_assert(mb_allow_match(v, n, &b));
  b = v6("::ffff:192.168.10.5"), ck_assert(mb_allow_match(v, n, &b));   /* IPv4 on a dual-stack socket */
  b = v6("::ffff:127.0.0.1"), ck_assert(!mb_allow_match(v, n, &b));
  ck_assert_int_eq(mb_allow_parse("10.1.2.3/12", v, 8, err, sizeof err), 1);   /* host bits are ignored */
  a = v4("10.15.0.1"), ck_assert(mb_allow_match(v, 1, &a));
  a = v4("10.16.0.1"), ck_assert(!mb_allow_match(v, 1, &a));
  ck_assert_int_eq(mb_allow_parse("0.0.0.0/0", v, 8, err, sizeof err), 1);
  a = v4("203.0.113.9"), ck_assert(mb_allow_match(v, 1, &a));
  static const char *const bad[] = {"", ",", "10.0.0.1,", "10.0.0.0/33", "::/129", "10.0.0.0/", "10.0.0.0/x",
                                    "300.1.1.1", "host.example", "10.0.0.1 ,10.0.0.2", "1.2.3.4/-1"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    err[0] = 0;
    ck_assert_msg(mb_allow_parse(bad[i], v, 8, err, sizeof err) < 0, "'%s' was taken", bad[i]);
    ck_assert_msg(strstr(err, "--modbus-allow") != NULL, "'%s': %s", bad[i], err);
  }
  ck_assert_int_eq(mb_allow_parse("1.1.1.1,2.2.2.2,3.3.3.3", v, 2, err, sizeof err), -1);
}
END_TEST

/* ---- the slots (mb_admit) ---- */

/* A connection from 10.0.0.h accepted at `at`, that last asked at `asked`
 * (< 0: never). */
static struct mb_slot slot(int h, double at, double asked)
{
  struct mb_slot c;
  memset(&c, 0, sizeof c);
  struct sockaddr_in a = v4("10.0.0.1");
  ((uint8_t *)&a.sin_addr)[3] = (uint8_t)h;
  ck_assert_int_eq(mb_host_key(&a, c.host), 0);
  c.serial = (unsigned long)(at * 1000);
  c.talked = asked >= 0;
  c.active = c.last = c.talked ? asked : at;
  return c;
}

static const uint8_t *host(int h)
{
  static struct mb_slot c;
  c = slot(h, 0, -1);
  return c.host;
}

START_TEST(host_cap)
{
  ck_assert_int_eq(mb_host_cap(1), 1);
  ck_assert_int_eq(mb_host_cap(2), 1);
  ck_assert_int_eq(mb_host_cap(8), 7);
  ck_assert_int_eq(mb_host_cap(MB_CLIENTS_LIMIT), MB_CLIENTS_LIMIT - 1);
}
END_TEST

START_TEST(host_keys)
{
  uint8_t a[16], b[16];
  struct sockaddr_in x = v4("192.168.10.5");
  struct sockaddr_in6 y = v6("::ffff:192.168.10.5"), z = v6("fd00::5");
  ck_assert_int_eq(mb_host_key(&x, a), 0);
  ck_assert_int_eq(mb_host_key(&y, b), 0);
  ck_assert(memcmp(a, b, 16) == 0);          /* IPv4 on a dual-stack socket: the same host */
  ck_assert_int_eq(mb_host_key(&z, b), 0);
  ck_assert(memcmp(a, b, 16) != 0);
  x.sin_port = htons(1234);                   /* the port is not the host */
  ck_assert_int_eq(mb_host_key(&x, b), 0);
  ck_assert(memcmp(a, b, 16) == 0);
  struct sockaddr u = {.sa_family = AF_UNIX};
  ck_assert_int_eq(mb_host_key(&u, a), -1);
}
END_TEST

START_TEST(admit_free_slots)
{
  struct mb_slot s8[8];
  ck_assert_int_eq(mb_admit(s8, 0, 8, host(1), 100), MB_ADMIT);
  for (int i = 0; i < 7; i++)
    s8[i] = slot(2 + i, 99.9, 99.95);         /* seven hosts, all active */
  ck_assert_int_eq(mb_admit(s8, 7, 8, host(9), 100), MB_ADMIT);
  ck_assert_int_eq(mb_admit(s8, 7, 8, host(2), 100), MB_ADMIT);
  ck_assert_int_eq(mb_admit(s8, 1, 1, host(3), 100), MB_REFUSE);   /* one slot, active */
  ck_assert_int_eq(mb_admit(s8, 1, 1, host(2), 100), MB_REFUSE);   /* its own host alike */
  ck_assert_int_eq(mb_admit(s8, 1, 1, host(2), 101), 0);           /* idle: it makes room */
}
END_TEST

START_TEST(admit_never_closes_an_active_client)
{
  /* issue 30: seven busy clients (one host) and a panel polling every
   * 100 ms: a newcomer is refused, whoever was silent longest */
  struct mb_slot s8[8];
  for (int i = 0; i < 7; i++)
    s8[i] = slot(1, 10 + i, 100 - 0.001 * i);
  s8[7] = slot(2, 50, 99.9);
  ck_assert_int_eq(mb_admit(s8, 8, 8, host(3), 100), MB_REFUSE);
  ck_assert_int_eq(mb_admit(s8, 8, 8, host(2), 100), MB_REFUSE);
  /* active is within MB_GRACE: of the last request, or of the accept */
  s8[7] = slot(2, 50, 100 - MB_GRACE + 0.01);
  ck_assert_int_eq(mb_admit(s8, 8, 8, host(3), 100), MB_REFUSE);
  s8[7] = slot(2, 100 - MB_GRACE + 0.01, -1);   /* accepted just now, not asked yet */
  ck_assert_int_eq(mb_admit(s8, 8, 8, host(3), 100), MB_REFUSE);
  s8[7] = slot(2, 50, 100 - MB_GRACE);          /* a second silent: idle */
  ck_assert_int_eq(mb_admit(s8, 8, 8, host(3), 100), 7);
  s8[7] = slot(2, 100 - MB_GRACE, -1);
  ck_assert_int_eq(mb_admit(s8, 8, 8, host(3), 100), 7);
}
END_TEST

START_TEST(admit_the_oldest_idle)
{
  struct mb_slot s4[4];
  s4[0] = slot(1, 10, 90);     /* asked, silent 10 s */
  s4[1] = slot(2, 20, -1);     /* never asked, accepted second */
  s4[2] = slot(3, 15, -1);     /* never asked, accepted first */
  s4[3] = slot(4, 30, 99.5);   /* active */
  /* one that never asked goes first, the oldest of them */
  ck_assert_int_eq(mb_admit(s4, 4, 4, host(5), 100), 2);
  s4[2] = slot(3, 15, 95);
  ck_assert_int_eq(mb_admit(s4, 4, 4, host(5), 100), 1);
  /* all asked: the one silent longest */
  s4[1] = slot(2, 20, 80);
  ck_assert_int_eq(mb_admit(s4, 4, 4, host(5), 100), 1);
  s4[1] = slot(2, 20, 92);
  ck_assert_int_eq(mb_admit(s4, 4, 4, host(5), 100), 0);
  /* silent alike: the older */
  s4[2] = slot(3, 5, 90);
  ck_assert_int_eq(mb_admit(s4, 4, 4, host(5), 100), 2);
  /* a newcomer from the host of an idle one, under its cap: still the longest silent */
  ck_assert_int_eq(mb_admit(s4, 4, 4, host(2), 100), 2);
}
END_TEST

START_TEST(admit_per_host_cap)
{
  /* 8 slots: one host holds at most 7, even with a slot free */
  struct mb_slot s8[8];
  for (int i = 0; i < 7; i++)
    s8[i] = slot(1, 10 + i, 99.5);
  ck_assert_int_eq(mb_admit(s8, 7, 8, host(1), 100), MB_REFUSE);
  ck_assert_int_eq(mb_admit(s8, 7, 8, host(2), 100), MB_ADMIT);
  /* at its cap, its own idle connection makes room (a panel reconnecting
   * after its old connection died), the oldest silent of its own */
  s8[3] = slot(1, 13, 90);
  s8[5] = slot(1, 15, 80);
  ck_assert_int_eq(mb_admit(s8, 7, 8, host(1), 100), 5);
  /* ... and never another host's, however idle */
  s8[3] = slot(1, 13, 99.5);
  s8[5] = slot(1, 15, 99.5);
  s8[7] = slot(2, 1, 2);
  ck_assert_int_eq(mb_admit(s8, 8, 8, host(1), 100), MB_REFUSE);
  ck_assert_int_eq(mb_admit(s8, 8, 8, host(3), 100), 7);
  /* two slots: one each; IPv4 and IPv4-mapped IPv6 are one host */
  struct mb_slot s2[2] = {slot(1, 10, 99.5)};
  struct sockaddr_in6 m = v6("::ffff:10.0.0.1");
  uint8_t h[16];
  ck_assert_int_eq(mb_host_key(&m, h), 0);
  ck_assert_int_eq(mb_admit(s2, 1, 2, h, 100), MB_REFUSE);
  ck_assert_int_eq(mb_admit(s2, 1, 2, host(2), 100), MB_ADMIT);
}
END_TEST

/* ---- the threaded server over loopback; this test is its host ---- */

static struct mb_server *srv;
static int cfd = -1;

static void srv_setup(void)
{
  setup();
  struct mb_opts o;
  mb_opts_init(&o);
  o.addr = "127.0.0.1:0";
  char err[300];
  int usage;
  srv = mb_open(&o, err, sizeof err, &usage);
  ck_assert_msg(srv != NULL, "%s", err);
  ck_assert_str_eq(mb_warning(srv), "");
  const char *port = strrchr(mb_address(srv), ':');
  ck_assert(port != NULL);
  struct sockaddr_in sa = v4("127.0.0.1");
  sa.sin_port = htons((uint16_t)atoi(port + 1));
  cfd = socket(AF_INET, SOCK_STREAM, 0);
  ck_assert_int_ge(cfd, 0);
  ck_assert_int_eq(connect(cfd, (struct sockaddr *)&sa, sizeof sa), 0);
  mm.idle = 1;
  mb_publish(srv, &mm);
}

static void srv_teardown(void)
{
  close(cfd);
  mb_close(srv);
  teardown();
}

static double now_s(void)
{
  return mb_now();
}

static void send_pdu(const uint8_t *pdu, size_t n)
{
  uint8_t f[MB_FRAME_MAX] = {0x55, 0x66, 0, 0, (uint8_t)((n + 1) >> 8), (uint8_t)(n + 1), 1};
  memcpy(f + 7, pdu, n);
  ck_assert_int_eq(send(cfd, f, 7 + n, 0), (ssize_t)(7 + n));
}

/* The reply within ms milliseconds: its length, 0 when none came. */
static int recv_reply(int ms)
{
  struct timeval tv = {ms / 1000, (ms % 1000) * 1000};
  setsockopt(cfd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  size_t have = 0;
  while (have < 6 || have < 6u + (unsigned)(rsp[4] << 8 | rsp[5])) {
    ssize_t r = recv(cfd, rsp + have, sizeof rsp - have, 0);
    if (r <= 0)
      return 0;
    have += (size_t)r;
  }
  return (int)have;
}

static void sleep_ms(int ms)
{
  struct timespec ts = {0, ms * 1000000L};
  nanosleep(&ts, NULL);
}

/* A write of R1 = 2.5 (FC 16, float64). */
static const uint8_t wr_r1[] = {16, 0, 104, 0, 4, 8, 0x40, 0x04, 0, 0, 0, 0, 0, 0};

START_TEST(server_write_waits_for_the_host)
{
  send_pdu(wr_r1, sizeof wr_r1);
  ck_assert_int_eq(recv_reply(20), 0);       /* not before the host took it */
  ck_assert(mr->vm.reg[1] == 0);
  /* the host comes to it (as its loop would, woken by mb_fd) */
  struct pollfd p = {.fd = mb_fd(srv), .events = POLLIN, .revents = 0};
  ck_assert_int_eq(poll(&p, 1, 1000), 1);
  mb_sync(srv, &mm);
  ck_assert(mr->vm.reg[1] == 2.5);
  ck_assert_int_eq(recv_reply(1000), 12);
  ck_assert_int_eq(rsp[7], 16);
  /* a read right after it sees the value */
  static const uint8_t rd[] = {4, 0, 104, 0, 4};
  send_pdu(rd, sizeof rd);
  ck_assert_int_eq(recv_reply(1000), 9 + 8);
  uint16_t w[4] = {(uint16_t)(rsp[9] << 8 | rsp[10]), (uint16_t)(rsp[11] << 8 | rsp[12]),
                   (uint16_t)(rsp[13] << 8 | rsp[14]), (uint16_t)(rsp[15] << 8 | rsp[16])};
  ck_assert(mb_get_f64(w) == 2.5);
}
END_TEST

START_TEST(server_write_decided_with_the_real_state)
{
  /* the view says idle, but the cycle has started since: refused, not applied */
  mm.idle = 0;
  send_pdu(wr_r1, sizeof wr_r1);
  sleep_ms(5);
  mb_sync(srv, &mm);
  ck_assert_int_eq(recv_reply(1000), 9);
  ck_assert_int_eq(rsp[7], 0x90);
  ck_assert_int_eq(rsp[8], 6);
  ck_assert(mr->vm.reg[1] == 0);
  /* the view says it runs: refused at once, without the host */
  double t0 = now_s();
  send_pdu(wr_r1, sizeof wr_r1);
  ck_assert_int_eq(recv_reply(1000), 9);
  ck_assert_int_eq(rsp[8], 6);
  ck_assert(now_s() - t0 < 0.02);
  /* M25 at the moment the host takes the override: refused */
  mm.idle = 1;
  mb_publish(srv, &mm);
  grinder()->override_allowed = 0;
  static const uint8_t ovr[] = {6, 0, 0, 0, 50};
  send_pdu(ovr, sizeof ovr);
  sleep_ms(5);
  mb_sync(srv, &mm);
  ck_assert_int_eq(recv_reply(1000), 9);
  ck_assert_int_eq(rsp[8], 6);
  ck_assert_int_eq(grinder()->override_pct, 100);
  grinder()->override_allowed = 1;
  send_pdu(ovr, sizeof ovr);
  sleep_ms(5);
  mb_sync(srv, &mm);
  ck_assert_int_eq(recv_reply(1000), 12);
  ck_assert_int_eq(grinder()->override_pct, 50);
}
END_TEST

START_TEST(server_busy_host)
{
  /* the host does not come (computing): 06 in time, and never applied */
  double t0 = now_s();
  send_pdu(wr_r1, sizeof wr_r1);
  ck_assert_int_eq(recv_reply(1000), 9);
  ck_assert_int_eq(rsp[8], 6);
  double took = now_s() - t0;
  ck_assert_msg(took >= MB_WRITE_WAIT - 0.005 && took < MB_WRITE_WAIT + 0.1, "%.3f s", took);
  mb_sync(srv, &mm);
  ck_assert(mr->vm.reg[1] == 0);
  /* a key is acknowledged at once and waits in its coil */
  static const uint8_t stop[] = {5, 0, 1, 0xFF, 0}, coils[] = {1, 0, 0, 0, 5};
  send_pdu(stop, sizeof stop);
  ck_assert_int_eq(recv_reply(1000), 12);
  send_pdu(coils, sizeof coils);
  ck_assert_int_eq(recv_reply(1000), 10);
  ck_assert_int_eq(rsp[9], 0x02);
  ck_assert_int_eq(mb_key(srv), MB_KEY_STOP);
  ck_assert_int_eq(mb_key(srv), MB_KEY_NONE);
  send_pdu(coils, sizeof coils);
  ck_assert_int_eq(recv_reply(1000), 10);
  ck_assert_int_eq(rsp[9], 0);
  ck_assert_int_eq(mb_clients(srv), 1);
}
END_TEST

Suite *suite_modbus(void)
{
  Suite *su = suite_create("modbus");
  TCase *tc = tcase_create("device");
  tcase_add_checked_fixture(tc, setup, teardown);
  tcase_add_test(tc, golden_words);
  tcase_add_test(tc, framing);
  tcase_add_test(tc, idle_image);
  tcase_add_test(tc, counter_and_alive);
  tcase_add_test(tc, single_block_and_breakpoint);
  tcase_add_test(tc, parameters);
  tcase_add_test(tc, exceptions);
  tcase_add_test(tc, keys_in_order);
  tcase_add_test(tc, positions_between_blocks);
  tcase_add_test(tc, block_number_above_16_bits);
  tcase_add_test(tc, read_only_device);
  tcase_add_test(tc, override_within_a_paced_move);
  tcase_add_test(tc, lathe_map);
  tcase_add_test(tc, allow_lists);
  tcase_add_test(tc, host_cap);
  tcase_add_test(tc, host_keys);
  tcase_add_test(tc, admit_free_slots);
  tcase_add_test(tc, admit_never_closes_an_active_client);
  tcase_add_test(tc, admit_the_oldest_idle);
  tcase_add_test(tc, admit_per_host_cap);
  suite_add_tcase(su, tc);
  TCase *ts = tcase_create("server");
  tcase_add_checked_fixture(ts, srv_setup, srv_teardown);
  tcase_add_test(ts, server_write_waits_for_the_host);
  tcase_add_test(ts, server_write_decided_with_the_real_state);
  tcase_add_test(ts, server_busy_host);
  suite_add_tcase(su, ts);
  return su;
}
