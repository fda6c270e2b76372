/* A libmodbus client that runs tests/modbus/loop.kp through Modbus alone
 * (s42 run loop.kp --realtime --modbus 127.0.0.1:PORT must be listening):
 * Пуск, positions and state while it runs, parameters, a refused write,
 * cycle exit for the PP jump, an error, reset, and the standard exceptions.
 *   client PORT  -> "modbus-client: N passed, 0 failed", status 0 */
#include "errors.h"
#include <errno.h>
#include <math.h>
#include <modbus.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int passed, failed;
static double worst_ms;

static void check(int ok, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void check(int ok, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  if (ok) {
    passed++;
  } else {
    failed++;
    fputs("FAIL modbus-client: ", stdout);
    vprintf(fmt, ap);
    fputc('\n', stdout);
  }
  va_end(ap);
}

static double now_ms(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

static void sleep_ms(int ms)
{
  struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
  nanosleep(&ts, NULL);
}

static modbus_t *mb;

/* Timed wrappers: every request's round trip counts in worst_ms. */
static int rd_ir(int a, int n, uint16_t *v)
{
  double t = now_ms();
  int r = modbus_read_input_registers(mb, a, n, v);
  t = now_ms() - t;
  if (t > worst_ms)
    worst_ms = t;
  return r;
}

static int rd_di(int a, int n, uint8_t *v)
{
  return modbus_read_input_bits(mb, a, n, v);
}

static int32_t i32(const uint16_t *w)
{
  return (int32_t)((uint32_t)w[0] << 16 | w[1]);
}

static double f64(const uint16_t *w)
{
  uint64_t u = (uint64_t)w[0] << 48 | (uint64_t)w[1] << 32 | (uint64_t)w[2] << 16 | w[3];
  double d;
  memcpy(&d, &u, sizeof d);
  return d;
}

static float f32(const uint16_t *w)
{
  uint32_t u = (uint32_t)w[0] << 16 | w[1];
  float f;
  memcpy(&f, &u, sizeof f);
  return f;
}

static void put_f64(uint16_t *w, double d)
{
  uint64_t u;
  memcpy(&u, &d, sizeof u);
  for (int i = 0; i < 4; i++)
    w[i] = (uint16_t)(u >> (48 - 16 * i));
}

static int state(void)
{
  uint16_t v[3];
  return rd_ir(0, 3, v) == 3 ? v[2] : -1;
}

/* Wait up to ms for run state st. */
static int wait_state(int st, int ms)
{
  double end = now_ms() + ms;
  int s;
  while ((s = state()) != st && now_ms() < end)
    sleep_ms(10);
  return s;
}

static int press(int coil)
{
  return modbus_write_bit(mb, coil, 1);
}

/* A raw request (unit id 1); the reply's exception code, 0 for a normal
 * reply, -1 when none came. */
static int raw_exception(const uint8_t *pdu, int len)
{
  uint8_t req[300], rsp[MODBUS_TCP_MAX_ADU_LENGTH];
  req[0] = 1;
  memcpy(req + 1, pdu, (size_t)len);
  if (modbus_send_raw_request(mb, req, len + 1) < 0)
    return -1;
  int n = modbus_receive_confirmation(mb, rsp);
  if (n < 0)
    return errno >= MODBUS_ENOBASE && errno < EMBXGTAR + 1 ? (int)(errno - MODBUS_ENOBASE) : -1;
  return rsp[7] & 0x80 ? rsp[8] : 0;
}

int main(int argc, char **argv)
{
  if (argc != 2) {
    fprintf(stderr, "usage: client PORT\n");
    return 2;
  }
  mb = modbus_new_tcp("127.0.0.1", atoi(argv[1]));
  if (!mb || modbus_connect(mb) < 0) {
    printf("FAIL modbus-client: cannot connect to port %s: %s\n", argv[1], modbus_strerror(errno));
    return 1;
  }
  modbus_set_response_timeout(mb, 2, 0);
  uint16_t v[125];
  uint8_t bits[16];

  /* idle before Пуск */
  check(rd_ir(0, 22, v) == 22, "read input registers 0-21: %s", modbus_strerror(errno));
  check(v[0] == 0x0100, "map version %04x", v[0]);
  check(v[2] == 0, "run state before Пуск %d, expected 0 (idle)", v[2]);
  uint16_t c0 = v[1];
  sleep_ms(300);
  check(rd_ir(1, 1, v) == 1 && v[0] != c0, "snapshot counter did not move in 300 ms while idle (heartbeat)");
  uint16_t w[4];
  put_f64(w, 0);
  check(modbus_write_registers(mb, 104, 4, w) == 4, "write R1 = 0 while idle: %s", modbus_strerror(errno));

  /* Пуск: the loop runs; positions and state while it runs */
  check(press(0) == 1, "press Пуск: %s", modbus_strerror(errno));
  check(wait_state(1, 1000) == 1, "run state after Пуск is not 1");
  sleep_ms(250);
  check(rd_ir(0, 22, v) == 22, "read while running");
  int32_t x1 = i32(&v[10]);
  uint16_t cnt1 = v[1];
  check(v[2] == 1 && v[3] >= 1 && v[3] <= 3, "running: state %d block %d", v[2], v[3]);
  check(x1 > 0, "X while running %d, expected > 0", x1);
  check(i32(&v[18]) == 600000, "contour speed %d, expected 600000 (600 mm/min)", i32(&v[18]));
  int moving = 0;
  for (int i = 0; i < 20 && !moving; i++) {
    if (rd_di(0, 16, bits) == 16 && bits[0] && bits[7])
      moving = 1;
    sleep_ms(10);
  }
  check(moving, "discrete inputs never showed running + X moving");
  sleep_ms(200);
  check(rd_ir(0, 22, v) == 22 && i32(&v[10]) > x1, "X did not advance: %d then %d", x1, i32(&v[10]));
  check(v[1] != cnt1, "snapshot counter did not change while running");
  check(i32(&v[20]) > 0, "simulated time %u ms", (unsigned)i32(&v[20]));

  /* parameters: refused while running (06), override allowed */
  put_f64(w, 4);
  errno = 0;
  check(modbus_write_registers(mb, 104, 4, w) == -1 && errno == EMBXSBUSY,
        "write R1 while running: expected exception 06, got %s", modbus_strerror(errno));
  check(modbus_write_register(mb, 0, 50) == 1, "write feed override 50: %s", modbus_strerror(errno));
  check(rd_ir(5, 1, v) == 1 && v[0] == 50, "override in effect %d, expected 50", v[0]);
  check(modbus_read_registers(mb, 0, 1, v) == 1 && v[0] == 50, "holding register 0 reads %d", v[0]);
  modbus_write_register(mb, 0, 100);

  /* cycle exit: PP5 is taken, then R5 = 100/R1 fails with E-DIV0 at N5 */
  check(press(3) == 1, "press cycle exit");
  check(wait_state(4, 2000) == 4, "no error state after cycle exit");
  check(rd_ir(0, 22, v) == 22 && v[3] == 5 && v[4] == S42_E_DIV0, "error: block %d code %d, expected N5 and %d",
        v[3], v[4], S42_E_DIV0);
  check(rd_di(0, 16, bits) == 16 && bits[3] && !bits[0], "discrete inputs: error %d running %d", bits[3], bits[0]);

  /* parameters while not running: float64 written, read as float64 and float32 */
  check(modbus_write_registers(mb, 104, 4, w) == 4, "write R1 = 4 after the error: %s", modbus_strerror(errno));
  check(rd_ir(104, 4, v) == 4 && f64(v) == 4.0, "R1 as float64 %g", f64(v));
  check(modbus_read_registers(mb, 602, 2, v) == 2 && f32(v) == 4.0f, "R1 as float32 %g", (double)f32(v));

  /* reset: idle, R kept; Пуск by the command word; cycle exit; M2 */
  check(press(4) == 1, "press reset");
  check(wait_state(0, 1000) == 0, "reset did not return to idle");
  check(rd_ir(104, 4, v) == 4 && f64(v) == 4.0, "R1 after reset %g", f64(v));
  check(modbus_write_register(mb, 1, 1) == 1, "command word 1 (Пуск): %s", modbus_strerror(errno));
  check(wait_state(1, 1000) == 1, "not running after command word Пуск");
  sleep_ms(150);
  check(modbus_write_register(mb, 1, 4) == 1, "command word 4 (cycle exit)");
  check(wait_state(5, 2000) == 5, "no end (M2) after the second cycle exit");
  check(rd_ir(120, 4, v) == 4 && f64(v) == 25.0, "R5 = 100/R1 as float64: %g", f64(v));
  check(rd_ir(610, 2, v) == 2 && f32(v) == 25.0f, "R5 as float32: %g", (double)f32(v));
  check(rd_di(4, 1, bits) == 1 && bits[0], "discrete input 4 (M2) not set");

  /* exceptions */
  errno = 0;
  check(rd_ir(22, 1, v) == -1 && errno == EMBXILADD, "read input register 22: %s", modbus_strerror(errno));
  errno = 0;
  check(modbus_write_register(mb, 100, 1) == -1 && errno == EMBXILADD, "single register into a float64: %s",
        modbus_strerror(errno));
  errno = 0;
  check(modbus_write_registers(mb, 601, 2, w) == -1 && errno == EMBXILADD, "float32 at an odd address: %s",
        modbus_strerror(errno));
  errno = 0;
  check(modbus_write_registers(mb, 100, 2, w) == -1 && errno == EMBXILADD, "half a float64: %s",
        modbus_strerror(errno));
  errno = 0;
  check(modbus_write_register(mb, 0, 151) == -1 && errno == EMBXILVAL, "override 151: %s", modbus_strerror(errno));
  errno = 0;
  check(modbus_write_register(mb, 1, 6) == -1 && errno == EMBXILVAL, "command word 6: %s", modbus_strerror(errno));
  put_f64(w, NAN);
  errno = 0;
  check(modbus_write_registers(mb, 104, 4, w) == -1 && errno == EMBXILVAL, "R1 = NaN: %s", modbus_strerror(errno));
  put_f64(w, 1e8);
  errno = 0;
  check(modbus_write_registers(mb, 104, 4, w) == -1 && errno == EMBXILVAL, "R1 = 1e8: %s", modbus_strerror(errno));
  errno = 0;
  check(modbus_write_bit(mb, 6, 1) == -1 && errno == EMBXILADD, "coil 6: %s", modbus_strerror(errno));
  static const uint8_t unknown[] = {0x2B, 0x0E, 0x01, 0x00};
  check(raw_exception(unknown, sizeof unknown) == 1, "function 0x2B: expected exception 01");
  static const uint8_t qty0[] = {0x04, 0x00, 0x00, 0x00, 0x00};
  check(raw_exception(qty0, sizeof qty0) == 3, "quantity 0: expected exception 03");
  static const uint8_t qty126[] = {0x03, 0x00, 0x64, 0x00, 0x7E};
  check(raw_exception(qty126, sizeof qty126) == 3, "quantity 126: expected exception 03");
  check(rd_ir(0, 1, v) == 1, "the connection survives the exceptions");

  modbus_close(mb);
  modbus_free(mb);
  printf("modbus-client: worst round trip %.1f ms\n", worst_ms);
  printf("modbus-client: %d passed, %d failed\n", passed, failed);
  return failed != 0;
}
