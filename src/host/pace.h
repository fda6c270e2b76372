/* Machine-speed pacing (--realtime): ties simulated seconds to the wall
 * clock.  The headless runner sleeps until a block's end is due; the
 * terminal asks how far ahead the simulation is and polls for keys that
 * long instead, so nothing blocks.  A hold freezes the clock (feed hold). */
#ifndef S42_PACE_H
#define S42_PACE_H

#include <signal.h>
#include <time.h>

struct pace {
  struct timespec t0;    /* wall clock when the simulated time was sim0 */
  double sim0;
  int held;
  double held_at;        /* simulated time reached when the hold began */
  const volatile sig_atomic_t *stop;   /* a signal set it: stop sleeping (may be NULL) */
};

/* From now on the wall clock runs from simulated time sim. */
void pace_start(struct pace *p, double sim);
/* The simulated time the wall clock has reached. */
double pace_now(const struct pace *p);
/* How many seconds simulated time sim lies ahead of the wall clock (<= 0:
 * it is due). */
double pace_ahead(const struct pace *p, double sim);
/* Sleep until sim is due (the headless runner), or until a signal sets
 * *p->stop. */
void pace_sleep_until(const struct pace *p, double sim);
/* Feed hold on / off: the clock stops, then goes on from where it stopped. */
void pace_hold(struct pace *p, int on);

#endif
