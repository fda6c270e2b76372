/* Machine-speed pacing (src/host/pace.h): the wall clock against simulated
 * time, for --realtime runs and the terminal. */
#include "pace.h"
#include <errno.h>

static double since(const struct timespec *t0)
{
  struct timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return (double)(now.tv_sec - t0->tv_sec) + (double)(now.tv_nsec - t0->tv_nsec) / 1e9;
}

void pace_start(struct pace *p, double sim)
{
  /* p->stop is the owner's and stays as it was */
  clock_gettime(CLOCK_MONOTONIC, &p->t0);
  p->sim0 = sim;
  p->held = 0;
  p->held_at = sim;
}

double pace_now(const struct pace *p)
{
  return p->held ? p->held_at : p->sim0 + since(&p->t0);
}

double pace_ahead(const struct pace *p, double sim)
{
  return sim - pace_now(p);
}

void pace_sleep_until(const struct pace *p, double sim)
{
  double wait = pace_ahead(p, sim);
  if (wait <= 0 || p->held)
    return;
  struct timespec ts;
  ts.tv_sec = (time_t)wait;
  ts.tv_nsec = (long)((wait - (double)ts.tv_sec) * 1e9);
  while (nanosleep(&ts, &ts) && errno == EINTR)
    if (p->stop && *p->stop)
      return;
}

void pace_hold(struct pace *p, int on)
{
  if (on && !p->held) {
    p->held_at = pace_now(p);
    p->held = 1;
  } else if (!on && p->held) {
    pace_start(p, p->held_at);
  }
}
