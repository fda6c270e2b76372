/* The machine as a Modbus TCP device (contracts.md section 6): a server
 * that lives in its host's single-threaded loop (poll() between machine
 * steps, nothing blocks), the register map over a session, and our own
 * big-endian encoders for 32/64-bit values. */
#ifndef S42_MODBUS_H
#define S42_MODBUS_H

#include <poll.h>
#include <stddef.h>
#include <stdint.h>

struct session;

#define MB_MAP_VERSION 0x0100
#define MB_DEFAULT_ADDR "127.0.0.1:1502"
#define MB_MAX_CLIENTS 8      /* more are accepted and closed at once */
#define MB_FRAME_MAX 260      /* MBAP header (7) + the largest PDU (253) */

/* Panel keys a client presses: coils 0-4 and the command word's values. */
enum mb_key { MB_KEY_NONE, MB_KEY_PUSK, MB_KEY_STOP, MB_KEY_PS, MB_KEY_EXIT, MB_KEY_RESET };

/* Run states of input register 2. */
enum mb_run { MB_IDLE, MB_RUN, MB_STOPPED, MB_WAITING, MB_ERROR, MB_END };

/* What the host shows the server.  The host owns it and keeps it current;
 * the server reads positions, state and registers through it and writes
 * R0-R113 and the feed override into the session. */
struct mb_machine {
  struct session *s;     /* the session served; NULL: nothing loaded yet (idle, zeros) */
  int idle;              /* no cycle started yet, or reset: run state 0 */
  double feed;           /* contour speed of the last block, mm/min (shown while running) */
  /* --realtime: the block whose motion is under way on the wall clock.  The
   * session's position is already at its end; the server shows the position
   * in between (start..end are CLOCK_MONOTONIC seconds, see mb_now). */
  struct {
    int active;          /* 0: no block in motion */
    int held;            /* feed hold (Стоп): frozen at held_frac */
    double start, end, held_frac;
    int64_t d[4];        /* its contour increments */
    double feed;         /* its effective speed, mm/min */
    int block;           /* its block number, -1 none */
  } motion;
  /* A host that keeps the feed override switch itself (the terminal): the
   * server sets it through this (0 taken, -1 refused) and reads it back
   * from override_pct; NULL: the server sets it in the session. */
  int (*set_override)(void *host, int pct);
  void *host;
  int override_pct;
};

/* ---- the server: the host's loop calls these ----
 *
 *   char err[200]; int usage;
 *   struct mb_server *mb = mb_open("127.0.0.1:1502", err, sizeof err, &usage);
 *   if (!mb) { fprintf(stderr, "s42: %s\n", err); exit(usage ? 2 : 4); }
 *   for (;;) {
 *     mb_poll(mb, &machine, busy ? 0 : 100);     // or mb_fds + own poll + mb_serve
 *     for (int k; (k = mb_key(mb)) != MB_KEY_NONE; ) press(k);
 *     step the machine a little;
 *   }
 *   mb_close(mb);
 */
struct mb_server;

/* Listen on "HOST:PORT", "[V6]:PORT", ":PORT" or "PORT" (host 127.0.0.1);
 * NULL or "" is MB_DEFAULT_ADDR.  Ignores SIGPIPE.  On failure returns NULL
 * with a message in err and *usage set when the address itself is bad
 * (exit 2) rather than a system error such as a port in use (exit 4). */
struct mb_server *mb_open(const char *addr, char *err, size_t n, int *usage);
void mb_close(struct mb_server *mb);
/* "HOST:PORT" as listened on, for messages. */
const char *mb_address(const struct mb_server *mb);

/* mb_fds + poll(timeout_ms) + mb_serve.  Returns 0, or -1 when poll()
 * failed (errno; EINTR is not a failure: a signal returns 0 early). */
int mb_poll(struct mb_server *mb, struct mb_machine *m, int timeout_ms);
/* For a host that polls its own descriptors too (the terminal): the ones
 * the server needs, at most 1 + MB_MAX_CLIENTS; returns how many were set. */
int mb_fds(const struct mb_server *mb, struct pollfd *fds, int max);
/* After that poll(): accept, read, answer, write, and drop connections past
 * their timeouts.  fds/n as filled by mb_fds (revents set by poll). */
void mb_serve(struct mb_server *mb, struct mb_machine *m, const struct pollfd *fds, int n);
/* The poll timeout to use instead of want_ms so a client's deadline (a
 * truncated frame, a stuck reply) is not overslept. */
int mb_timeout(const struct mb_server *mb, int want_ms);
/* The next key pressed by a client, in order; MB_KEY_NONE when none.  A
 * press stays visible in its coil / the command word until taken here. */
int mb_key(struct mb_server *mb);
/* Connections open now. */
int mb_clients(const struct mb_server *mb);

/* ---- the device without sockets (the server's core; fuzzed) ---- */

#define MB_KEYQ 16

struct mb_dev {
  struct mb_machine *m;
  uint16_t ir[828];      /* the input register image of the last update */
  uint8_t di[16];        /* the discrete inputs */
  uint16_t counter;      /* snapshot counter (input register 1) */
  double last_update;    /* mb_now() of the last update (heartbeat) */
  uint8_t keys[MB_KEYQ]; /* pressed, not yet taken */
  unsigned khead, nkeys;
};

void mb_dev_init(struct mb_dev *d, struct mb_machine *m);
/* Rebuild the image from the machine; an update (counter +1, alive
 * toggled) when anything changed or 250 ms passed since the last one. */
void mb_dev_refresh(struct mb_dev *d, double now);
/* The length of the complete MBAP frame at the head of buf: >0 its length,
 * 0 when more bytes are needed, -1 malformed (non-zero protocol id, a
 * length field out of 2..254): close the connection. */
long mb_frame(const uint8_t *buf, size_t have);
/* Answer one complete frame (len from mb_frame) at wall time `now`: the
 * reply (at most MB_FRAME_MAX bytes) goes to rsp and its length is
 * returned. */
int mb_dev_request(struct mb_dev *d, const uint8_t *req, size_t len, uint8_t *rsp, double now);
int mb_dev_key(struct mb_dev *d);
/* A block's motion goes on the wall clock from `start` for `dur` seconds
 * (not held): what the host shows the map while it plays a block out. */
void mb_motion_start(struct mb_machine *m, double start, double dur, const int64_t d[4], double feed, int block);
/* The run state (enum mb_run) the map shows now. */
int mb_run_state(const struct mb_machine *m, double now);
/* CLOCK_MONOTONIC in seconds. */
double mb_now(void);

/* ---- multi-register values, high word first (ABCD) ---- */
void mb_put_u32(uint16_t w[2], uint32_t v);
uint32_t mb_get_u32(const uint16_t w[2]);
void mb_put_i32(uint16_t w[2], int32_t v);
int32_t mb_get_i32(const uint16_t w[2]);
void mb_put_f32(uint16_t w[2], float v);
float mb_get_f32(const uint16_t w[2]);
void mb_put_f64(uint16_t w[4], double v);
double mb_get_f64(const uint16_t w[4]);

#endif
