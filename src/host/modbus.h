/* The machine as a Modbus TCP device (contracts.md section 6), for every
 * dialect on the runner: a server thread that owns the sockets and answers
 * from a snapshot of the map (the view) that the host's thread publishes,
 * so neither output that blocks nor a plugin that computes for seconds
 * stalls a client; what clients change (keys, the feed override, the
 * parameters) waits for the host's thread, which takes it between blocks.
 * What the map shows comes from the runner (struct mrun: its state, its
 * wait, its switches) and the runtime's view hook (positions, parameters,
 * the spindle and aux bits, the override in effect): the map is one, what
 * each dialect puts in it is the runtime's.  Also our own big-endian
 * encoders for 32/64-bit values. */
#ifndef S42_MODBUS_H
#define S42_MODBUS_H

#include <stddef.h>
#include <stdint.h>

struct mrun;
struct session;

#define MB_MAP_VERSION 0x0100
#define MB_DEFAULT_ADDR "127.0.0.1:1502"
#define MB_DEFAULT_CLIENTS 8  /* connections at once (--modbus-max-clients) */
#define MB_CLIENTS_LIMIT 256  /* the most --modbus-max-clients takes */
#define MB_DEFAULT_IDLE 60.0  /* s without a request before a connection is closed (--modbus-idle) */
#define MB_FRAME_MAX 260      /* MBAP header (7) + the largest PDU (253) */
#define MB_NREG 114           /* the most parameters the map has room for: R0-R113 (the 2С42's) */

/* Panel keys a client presses: coils 0-4 and the command word's values. */
enum mb_key { MB_KEY_NONE, MB_KEY_PUSK, MB_KEY_STOP, MB_KEY_PS, MB_KEY_EXIT, MB_KEY_RESET };

/* Run states of input register 2. */
enum mb_run { MB_IDLE, MB_RUN, MB_STOPPED, MB_WAITING, MB_ERROR, MB_END };

/* --realtime: the block whose motion is under way on the wall clock.  The
 * machine's position is already at its end; the map shows the position in
 * between (start..end are CLOCK_MONOTONIC seconds, see mb_now). */
struct mb_motion {
  int active;            /* 0: no block in motion */
  int held;              /* feed hold (Стоп): frozen at held_frac */
  double start, end, held_frac;
  int64_t d[4];          /* its contour increments */
  double feed;           /* its effective speed, mm/min */
  int block;             /* its block number, -1 none */
};

/* The host's machine as the map sees it.  The host owns it, keeps it
 * current and only its own thread reads it (mb_publish, mb_sync): the
 * server thread never touches the machine. */
struct mb_machine {
  struct mrun *r;        /* the runner served; NULL (and s NULL): nothing loaded yet (idle, zeros) */
  /* The terminal's 2С42 session, until the terminal runs on the runner
   * (src/host/mb_sess.c reads it; r is NULL then).  Goes with it. */
  struct session *s;
  int idle;              /* no cycle started yet, or reset: run state 0 */
  double feed;           /* contour speed of the last block, mm/min (shown while running) */
  struct mb_motion motion;
  /* A host that keeps the feed override switch itself (the terminal): the
   * server sets it through this (0 taken, -1 refused) and reads it back
   * from override_pct; NULL: the server sets it on the runner
   * (mrun_override at the simulated time a paced motion has reached: the
   * rest of the move re-timed, 0 % holding it).  Called on the host's
   * thread with the server's lock held: it must not block. */
  int (*set_override)(void *host, int pct);
  void *host;
  int override_pct;
  /* Single block (coil 5) and the breakpoint (holding register 2): the
   * host's switches.  A host that keeps them itself (the terminal) sets
   * these hooks and keeps single/brk current; otherwise the server sets
   * them on the runner (mrun_input: MRI_MODE, MRI_BREAK), and the map reads
   * the runner's. */
  void (*set_single)(void *host, int on);
  void (*set_break)(void *host, int n);
  int single, brk;
  /* the override went to 0 % within a block's motion: it holds (run
   * state 2) until the override leaves 0 (the host's, not the server's) */
  int ovr_held;
};

/* ---- the server ----
 *
 *   struct mb_opts o;
 *   mb_opts_init(&o);
 *   o.addr = "127.0.0.1:1502";
 *   char err[300]; int usage;
 *   struct mb_server *mb = mb_open(&o, err, sizeof err, &usage);
 *   if (!mb) { fprintf(stderr, "s42: %s\n", err); exit(usage ? 2 : 4); }
 *   if (*mb_warning(mb)) fprintf(stderr, "s42: warning: %s\n", mb_warning(mb));
 *   for (;;) {
 *     mb_poll(mb, &machine, busy ? 0 : 100);   // or poll mb_fd yourself, then mb_sync
 *     for (int k; (k = mb_key(mb)) != MB_KEY_NONE; ) press(k);
 *     step the machine a little;
 *     mb_publish(mb, &machine);                // at every block boundary and state change
 *   }
 *   mb_close(mb);
 *
 * Reads are answered by the server thread from the last view published
 * (positions of a paced block move on the wall clock from it).  A coil or
 * command-word press is acknowledged at once and waits in the key queue
 * (its coil reads 1) until mb_key takes it.  A write of the override or of
 * R waits until the host's next mb_sync applies it -- the reply says what
 * the machine did, and a read after it sees the value -- or gets exception
 * 06 when the host has not come to it within MB_WRITE_WAIT; an R write
 * while the view shows the cycle running gets 06 at once. */
#define MB_WRITE_WAIT 0.05    /* s */

struct mb_opts {
  const char *addr;      /* "HOST:PORT", "[V6]:PORT", ":PORT" or "PORT" (host 127.0.0.1); NULL or "": MB_DEFAULT_ADDR */
  int max_clients;       /* 1..MB_CLIENTS_LIMIT, of them mb_host_cap from one address (see mb_admit) */
  double idle;           /* s without a request before a connection is closed; 0: never */
  int read_only;         /* every write (coils, holding registers) gets exception 01 */
  const char *allow;     /* "ADDR[/BITS],..." IPv4 or IPv6: only these clients; NULL: any */
  /* for test harnesses */
  int no_thread;         /* no server thread: the caller runs mb_step */
  double (*clock)(void); /* NULL: mb_now */
};

void mb_opts_init(struct mb_opts *o);

struct mb_server;

/* Listen and start the server thread.  Ignores SIGPIPE.  On failure returns
 * NULL with a message in err and *usage set when the address or the allow
 * list is bad (exit 2) rather than a system error such as a port in use
 * (exit 4). */
struct mb_server *mb_open(const struct mb_opts *o, char *err, size_t n, int *usage);
/* Stop the thread, close every connection. */
void mb_close(struct mb_server *mb);
/* "HOST:PORT" as listened on, for messages. */
const char *mb_address(const struct mb_server *mb);
/* "" or why the address is exposed (a non-loopback address and no allow list). */
const char *mb_warning(const struct mb_server *mb);

/* The host's side, all on one thread. */
/* Readable when a key or a write waits for the host (then mb_sync). */
int mb_fd(const struct mb_server *mb);
/* Apply the writes that wait (override, R) to m, then publish its view. */
void mb_sync(struct mb_server *mb, struct mb_machine *m);
/* Publish the view of m: what reads see from now on. */
void mb_publish(struct mb_server *mb, const struct mb_machine *m);
/* Before a key that may compute for long (Пуск or ПС answering a wait: a
 * tooth search goes on inside it): publish m as running at its block, so
 * reads meanwhile show the cycle running, not the wait the key ends.  The
 * host publishes the real state right after the key. */
void mb_publish_running(struct mb_server *mb, const struct mb_machine *m);
/* poll(mb_fd, timeout_ms) + mb_sync.  Returns 0, or -1 when poll() failed
 * (errno; EINTR is not a failure: a signal returns 0 early). */
int mb_poll(struct mb_server *mb, struct mb_machine *m, int timeout_ms);
/* The next key pressed by a client, in order; MB_KEY_NONE when none. */
int mb_key(struct mb_server *mb);
/* Connections open now. */
int mb_clients(struct mb_server *mb);

/* With no_thread: one turn of the server loop (poll the sockets up to
 * timeout_ms, accept, read, answer, write, time out). */
void mb_step(struct mb_server *mb, int timeout_ms);

/* ---- the device without sockets (the server's core; fuzzed) ---- */

#define MB_KEYQ 16

/* The map's source: what mb_view_of takes from the machine. */
struct mb_view {
  int loaded;            /* a machine is served */
  int idle;
  int state;             /* enum mrun_ev */
  int wait_feed;         /* waits for a feed override above 0 % (MRW_FEED) */
  int nregs;             /* the parameters the machine publishes, R0..R<nregs-1> (<= MB_NREG) */
  double r_lo, r_hi;     /* the values a parameter takes (the program's; outside: exception 03) */
  int err_code;
  int block;             /* its block number */
  int override_eff;      /* the override in effect, % */
  int override_hr;       /* holding register 0 */
  int single, brk;       /* coil 5, holding register 2 */
  int wheel, osc;        /* discrete inputs 5 and 6: MRUN_BIT_SPINDLE, MRUN_BIT_AUX */
  int64_t pos[4];
  double t, feed;
  double reg[MB_NREG];
  struct mb_motion motion;
};

/* A write the host must decide (mb_dev_request returned 0). */
struct mb_write {
  int ovr;               /* the override to set, -1 none */
  int single, brk;       /* single block (coil 5) 0/1, the breakpoint (HR 2); -1 none */
  int cmd;               /* a command word pressed with it, 0 none */
  unsigned r0, n;        /* R r0 .. r0+n-1 to set (n 0: none) */
  double val[MB_NREG];
};

struct mb_dev {
  struct mb_view v;      /* what the map shows */
  uint16_t ir[828];      /* the input register image of the last update */
  uint8_t di[16];        /* the discrete inputs */
  uint16_t counter;      /* snapshot counter (input register 1) */
  double last_update;    /* time of the last update (heartbeat) */
  uint8_t keys[MB_KEYQ]; /* pressed, not yet taken */
  unsigned khead, nkeys;
  int read_only;
  struct mb_write w;     /* the write mb_dev_request left to the host */
};

void mb_view_of(struct mb_view *v, const struct mb_machine *m);
void mb_dev_init(struct mb_dev *d);
/* Rebuild the image from the view; an update (counter +1, alive toggled)
 * when anything changed or 250 ms passed since the last one. */
void mb_dev_refresh(struct mb_dev *d, double now);
/* The length of the complete MBAP frame at the head of buf: >0 its length,
 * 0 when more bytes are needed, -1 malformed (non-zero protocol id, a
 * length field out of 2..254): close the connection. */
long mb_frame(const uint8_t *buf, size_t have);
/* Answer one complete frame (len from mb_frame) at wall time `now`: the
 * reply (at most MB_FRAME_MAX bytes) goes to rsp and its length is
 * returned; 0 when the request is a write the host decides (in d->w):
 * mb_dev_apply on the host's thread, then mb_dev_reply. */
int mb_dev_request(struct mb_dev *d, const uint8_t *req, size_t len, uint8_t *rsp, double now);
/* Apply w to the machine: 0, or the exception that refuses it (06; 02 for
 * R beyond the machine's parameters). */
int mb_dev_apply(struct mb_dev *d, struct mb_machine *m, const struct mb_write *w, double now);
/* The reply to a deferred write: its request's first 12 bytes, the outcome. */
int mb_dev_reply(const uint8_t *req, int ex, uint8_t *rsp);
int mb_dev_key(struct mb_dev *d);
/* A block's motion goes on the wall clock from `start` for `dur` seconds
 * (not held): what the host shows the map while it plays a block out. */
void mb_motion_start(struct mb_machine *m, double start, double dur, const int64_t d[4], double feed, int block);
/* The run state (enum mb_run) the map shows now. */
int mb_run_state(const struct mb_machine *m, double now);
/* CLOCK_MONOTONIC in seconds. */
double mb_now(void);

/* ---- the slots: where a newcomer goes (no sockets; unit-tested) ---- */

#define MB_GRACE 1.0          /* s: a connection accepted or asking this recently is active */

/* What mb_admit knows of one connection. */
struct mb_slot {
  uint8_t host[16];      /* the peer's address (mb_host_key) */
  double active;         /* when it was accepted or made its last whole request */
  double last;           /* when it last sent anything */
  unsigned long serial;  /* accepted as the serial-th: the older, the smaller */
  int talked;            /* has made a whole request */
};

enum { MB_ADMIT = -1, MB_REFUSE = -2 };

/* The most connections one address may hold of max: max - 1 (at least 1),
 * so that one host never takes every slot. */
int mb_host_cap(int max);
/* A newcomer from `host` finds the n connections s (of max slots):
 * MB_ADMIT, a free slot is its; i >= 0, connection i is closed to make
 * room; MB_REFUSE, it is closed.  An active connection (one accepted or
 * asking within MB_GRACE of now) is never closed for it.  Room is made,
 * when every slot is taken, by closing an idle connection: one that never
 * made a request first (the oldest), else the one silent longest; and
 * when its address holds mb_host_cap connections already, only one of
 * those can make room, even if a slot is free. */
int mb_admit(const struct mb_slot *s, int n, int max, const uint8_t host[16], double now);
/* The key of an IPv4 or IPv6 socket address in host (IPv4 and IPv4-mapped
 * IPv6 alike as ::ffff:a.b.c.d): 0, or -1 for another family. */
int mb_host_key(const void *sockaddr, uint8_t host[16]);

/* ---- allow lists ---- */
struct mb_net { int family; uint8_t a[16]; int bits; };
/* Parse "ADDR[/BITS],..." into at most max entries: the count, or -1 with
 * a message in err. */
int mb_allow_parse(const char *s, struct mb_net *v, int max, char *err, size_t n);
/* Whether the socket address (IPv4, IPv6, IPv4-mapped IPv6) is on the list. */
int mb_allow_match(const struct mb_net *v, int nv, const void *sockaddr);

/* ---- the terminal's 2С42 session (src/host/mb_sess.c) ----
 * Until the terminal runs on the runner, a mb_machine may serve a session
 * (m->s, m->r NULL): these read and write it for modbus.c, which knows no
 * session.  They go when the terminal moves. */
void mb_sess_view(struct mb_view *v, const struct session *s);
/* The session's state as an enum mrun_ev (SE_START: MR_START, ...). */
int mb_sess_state(const struct session *s);
void mb_sess_load(struct session *s, unsigned r0, unsigned n, const double *v);
/* The session's own override switch (a host without set_override): 0, or -1 refused (M25). */
int mb_sess_override(struct session *s, int pct);
void mb_sess_single(struct session *s, int on);
void mb_sess_break(struct session *s, int n);

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
