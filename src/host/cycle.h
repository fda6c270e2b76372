/* One run setup for every host (s42 run, s42 tui, the Modbus cycle): the
 * session made ready for a program, its plugins started, the restart
 * point's file chosen, a restart loaded, and the M15 saves at the blocks'
 * starts.  The hosts report what happened in their own way; what happens
 * is decided here, once. */
#ifndef S42_CYCLE_H
#define S42_CYCLE_H

#include "session.h"
#include <stddef.h>
#include <stdint.h>

struct cycle {
  struct session *s;
  char *state_path;        /* where the restart point is kept, NULL none */
  uint64_t hash;           /* the program text's (a state is of one text) */
  int has_m15;             /* the program has restart points */
  unsigned long saves;     /* restart points saved in this cycle */
};

enum { CYCLE_OK, CYCLE_PLUGIN, CYCLE_NO_NAME, CYCLE_OOM };

/* Set s up for a run of p (text src, n bytes, from the file `program`,
 * NULL when it has no name yet): sess_init, the host's settings, the
 * plugins the program uses started.  The restart point's file is
 * `state_opt` (--state) or PROGRAM.state, when the program has M15 or a
 * restart is asked.  Returns CYCLE_OK; CYCLE_PLUGIN when a plugin refuses
 * because of the command line (why says so, *block is the first block
 * that needs it: the run must not start); CYCLE_NO_NAME when the program
 * has M15 but no file name, so no restart point can be kept (the run may
 * go on); CYCLE_OOM. */
int cycle_setup(struct cycle *c, struct session *s, const struct program *p, const char *src, size_t n,
                const struct sess_config *cfg, const char *program, const char *state_opt, int restart, char *why,
                size_t nwhy, size_t *block);
/* Load the restart point: 0, or -1 with the session ended with E-STATE
 * ("restart refused: why") and why set. */
int cycle_restart(struct cycle *c, char *why, size_t n);
/* At a block's start (SE_START): a block with M15 saves the restart point.
 * 1 saved, 0 nothing to save, -1 the save failed: the session has ended
 * with E-STATE ("cannot save the M15 restart state: ...") -- the file system
 * refused, the program did nothing wrong. */
int cycle_m15(struct cycle *c);
void cycle_free(struct cycle *c);

#endif
