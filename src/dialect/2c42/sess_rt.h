/* What a dialect's runtime does with a session, and what of the session it
 * may use.  The session steps the VM, keeps the waits, the sinks and the
 * plugins; the runtime decides what a block of its language means -- its
 * machine work, its waits, the rest of the block when a wait ends.  The
 * front end puts its runtime into the program (program.runtime). */
#ifndef S42_SESS_RT_H
#define S42_SESS_RT_H

#include "session.h"

struct sess_runtime {
  /* a block's start came back from the VM (before the host acts there) */
  void (*start)(struct session *s);
  /* VM_EV_BLOCK: the block's machine work; the session event, or -1 to go on */
  int (*block)(struct session *s);
  /* the block's plugins have run: its waits and the rest; event or -1 */
  int (*after)(struct session *s);
  /* a wait the block had is over: the rest of it (the row; s->state SE_START) */
  void (*finish)(struct session *s);
  /* a number was typed into the field (s->answer): 1 refused (it asks
   * again), 0 taken */
  int (*answer)(struct session *s);
  /* M19-style teach-in: a jog, and its end (ПС) */
  void (*teach_jog)(struct session *s, int axis, int64_t d);
  void (*teach_end)(struct session *s);
  /* the override moved while the block waited for it (W_FEED): -2 it still
   * waits, else the event or -1 */
  int (*released)(struct session *s);
};

/* The session's services for a runtime. */
void sess_warn(struct session *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The block's trace row, to the sink. */
void sess_emit_row(struct session *s);
/* The plugins of the block (mask): start those not started yet; their
 * phase `which` (0 check, 1 before the motion, 2 after); then run() each in
 * turn (a wait stops there; the rest goes on at the next key), ending with
 * the runtime's after().  0 / an event, or SE_ERROR. */
int sess_plug_start_block(struct session *s, uint32_t mask);
int sess_plug_phase(struct session *s, uint32_t mask, int which);
int sess_run_plugins(struct session *s);
/* The plugin whose G is the block's motion, or -1. */
int sess_motion_plugin(const struct session *s);
/* A plugin callback's status: 0 fine, or the run ends (E-PLUGIN or its code). */
int sess_plug_status(struct session *s, int i, int r, const char *phase);
/* Is the block's motion a contour move (the core's or a plugin's)? */
int sess_contour_block(const struct session *s);

#endif
