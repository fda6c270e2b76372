/* s42 tui --modbus: the Modbus TCP server (src/host/modbus.c) as one more
 * source of the terminal's poll() loop.  The server's own thread answers
 * the clients from the view this file publishes after every step of the
 * terminal (so a slow terminal or a plugin computing never holds a client
 * up); what clients change wakes the loop through mb_fd.  A client's keys
 * are the panel's keys (tui_press), its feed override the panel's switch
 * (tui_override), and the map shows what the terminal shows, positions
 * mid-block included. */
#include "tui_modbus.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct tui_mb {
  struct mb_server *mb;
  struct mb_machine mm;
  struct tui *t;
  int told;                        /* the address is in the messages */
};

static int set_override(void *host, int pct)
{
  struct tui_mb *x = host;
  return x->t ? tui_override(x->t, pct) : -1;
}

static void set_single(void *host, int on)
{
  struct tui_mb *x = host;
  if (x->t)
    tui_set_single(x->t, on);
}

static void set_break(void *host, int n)
{
  struct tui_mb *x = host;
  if (x->t)
    tui_set_break(x->t, n);
}

/* Mirror the terminal's machine into what the server's view is made of. */
static void mirror(struct tui_mb *x, struct tui *t)
{
  x->t = t;
  if (!x->told) {
    char m[400];
    snprintf(m, sizeof m, "Modbus TCP on %s: a client's Пуск, Стоп, ПС, cycle exit and reset are the panel's",
             mb_address(x->mb));
    tui_say(t, m);
    if (*mb_warning(x->mb)) {
      snprintf(m, sizeof m, "warning: %s", mb_warning(x->mb));
      tui_say(t, m);
    }
    x->told = 1;
  }
  const struct session *s = tui_session(t);
  x->mm.s = (struct session *)s;   /* mb_sync writes R0-R113 only while the cycle does not run */
  x->mm.idle = s == NULL;
  x->mm.override_pct = tui_override_pct(t);
  x->mm.single = tui_single(t);
  x->mm.brk = tui_break(t);
  struct tui_motion m;
  tui_motion(t, &m);
  x->mm.feed = m.feed;
  memset(&x->mm.motion, 0, sizeof x->mm.motion);
  if (!m.active)
    return;
  mb_motion_start(&x->mm, mb_now() - m.frac * m.dur, m.dur, m.d, m.feed, m.block);
  x->mm.motion.held = m.held;
  x->mm.motion.held_frac = m.frac;
}

static void update(void *ctx, struct tui *t)
{
  struct tui_mb *x = ctx;
  mirror(x, t);
  mb_publish(x->mb, &x->mm);
}

static void busy(void *ctx, struct tui *t)
{
  struct tui_mb *x = ctx;
  mirror(x, t);
  mb_publish_running(x->mb, &x->mm);
}

static int fds(void *ctx, struct pollfd *pfd, int max)
{
  struct tui_mb *x = ctx;
  if (max < 1)
    return 0;
  pfd[0].fd = mb_fd(x->mb);
  pfd[0].events = POLLIN;
  pfd[0].revents = 0;
  return 1;
}

/* A client pressed a key or wrote the override or R. */
static void ready(void *ctx, struct tui *t, const struct pollfd *pfd, int n)
{
  struct tui_mb *x = ctx;
  (void)pfd;
  (void)n;
  mirror(x, t);
  mb_sync(x->mb, &x->mm);
  static const enum tui_key keys[] = {
    [MB_KEY_PUSK] = TUI_PUSK, [MB_KEY_STOP] = TUI_STOP, [MB_KEY_PS] = TUI_PS,
    [MB_KEY_EXIT] = TUI_EXIT, [MB_KEY_RESET] = TUI_RESET,
  };
  for (int k; (k = mb_key(x->mb)) != MB_KEY_NONE;) {
    tui_press(t, keys[k]);
    mirror(x, t);
  }
  mb_publish(x->mb, &x->mm);
}

int tui_modbus_open(const struct mb_opts *o, struct tui_source *src, char *err, size_t n, int *usage)
{
  struct tui_mb *x = calloc(1, sizeof *x);
  if (!x) {
    snprintf(err, n, "out of memory");
    *usage = 0;
    return -1;
  }
  if (!(x->mb = mb_open(o, err, n, usage))) {
    free(x);
    return -1;
  }
  if (*mb_warning(x->mb))
    fprintf(stderr, "s42: warning: %s\n", mb_warning(x->mb));
  x->mm.set_override = set_override;
  x->mm.set_single = set_single;
  x->mm.set_break = set_break;
  x->mm.host = x;
  x->mm.idle = 1;
  x->mm.override_pct = 100;
  mb_publish(x->mb, &x->mm);
  memset(src, 0, sizeof *src);
  src->ctx = x;
  src->fds = fds;
  src->ready = ready;
  src->update = update;
  src->busy = busy;
  return 0;
}

void tui_modbus_close(struct tui_source *src)
{
  struct tui_mb *x = src->ctx;
  if (!x)
    return;
  mb_close(x->mb);
  free(x);
  src->ctx = NULL;
}
