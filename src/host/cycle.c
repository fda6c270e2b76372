/* One run setup for every host (src/host/cycle.h). */
#include "cycle.h"
#include "errors.h"
#include "state.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BIT(x, n) (((x) >> (n)) & 1)

int cycle_setup(struct cycle *c, struct session *s, const struct program *p, const char *src, size_t n,
                const struct sess_config *cfg, const char *program, const char *state_opt, int restart, char *why,
                size_t nwhy, size_t *block)
{
  memset(c, 0, sizeof *c);
  c->s = s;
  c->hash = state_hash(src, n);
  sess_init(s, p);
  sess_configure(s, cfg);
  why[0] = 0;
  if (sess_start_plugins(s, why, nwhy, block))
    return CYCLE_PLUGIN;
  for (size_t b = 0; b < p->nblocks && !c->has_m15; b++)
    c->has_m15 = BIT(kp_attr(p, b)->m, 15);
  if (!c->has_m15 && !restart)
    return CYCLE_OK;
  if (state_opt) {
    c->state_path = strdup(state_opt);
  } else if (program) {
    if ((c->state_path = malloc(strlen(program) + 7)) != NULL)
      sprintf(c->state_path, "%s.state", program);
  } else {
    snprintf(why, nwhy, "the text has no file name yet, so the restart point is not saved (save it first)");
    return CYCLE_NO_NAME;
  }
  if (!c->state_path) {
    snprintf(why, nwhy, "out of memory");
    return CYCLE_OOM;
  }
  return CYCLE_OK;
}

int cycle_restart(struct cycle *c, char *why, size_t n)
{
  if (!c->state_path)
    snprintf(why, n, "no state file (the text has no file name)");
  if (!c->state_path || state_load(c->s, c->state_path, c->hash, why, n)) {
    sess_refuse(c->s, S42_E_STATE, "restart refused: %s", why);
    return -1;
  }
  return 0;
}

int cycle_m15(struct cycle *c)
{
  struct session *s = c->s;
  if (!c->state_path || !BIT(kp_attr(s->p, sess_cur(s))->m, 15))
    return 0;
  char err[512];
  if (state_save(s, c->state_path, c->hash, err, sizeof err)) {
    sess_fail(s, S42_E_STATE, "cannot save the M15 restart state: %s", err);
    return -1;
  }
  c->saves++;
  return 1;
}

void cycle_free(struct cycle *c)
{
  free(c->state_path);
  c->state_path = NULL;
}
