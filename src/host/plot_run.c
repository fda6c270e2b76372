/* The plot engine watching a run (src/host/plot.h's plot_watch): the
 * runner's view of what happened (its machine, the rows, how it ended)
 * turned into the engine's stream.  Apart from plot.c so that the engine
 * links without the runner (the tests drive it directly). */
#include "plot.h"
#include "mrun.h"
#include "run.h"
#include <string.h>

static void position(const struct mrun *r, int64_t pos[CANON_AXES])
{
  memset(pos, 0, CANON_AXES * sizeof *pos);
  if (r->rt && r->rt->position)
    r->rt->position(r, pos);
}

static void w_start(void *ctx, const struct mrun *r)
{
  struct canon_info in;
  int64_t pos[CANON_AXES];
  mrun_info(r, &in);
  position(r, pos);
  plot_begin(ctx, &in, pos);
}

static void w_call(void *ctx, const struct canon_call *c)
{
  plot_call(ctx, c);
}

static void w_moved(void *ctx, const struct mrun *r, const struct mrun_move *m)
{
  (void)r;
  plot_move(ctx, m->kind, m->axis, m->d, m->pos, m->t);
}

static void w_row(void *ctx, const struct mrun *r)
{
  plot_row(ctx, mrun_block_number(r), mrun_time(r));
}

static void w_result(void *ctx, const struct mrun *r, int status, const char *code, int n, unsigned line,
                     int stop)
{
  struct plot *pl = ctx;
  if (!plot_view_name(pl) || !strcmp(plot_view_name(pl), "none"))
    w_start(ctx, r);   /* refused before it started (a restart): the machine as it stands */
  struct plot_result res;
  char wt[300];
  memset(&res, 0, sizeof res);
  res.status = status;
  res.code = code;
  res.n = n;
  res.line = line;
  if (status == 3) {
    /* where it stopped: the block in progress */
    res.n = mrun_block_number(r);
    res.line = r->p && r->vm.cur < r->p->nblocks ? r->p->blocks[r->vm.cur].line : 0;
    res.stop = stop == RUN_STOP_SCRIPT ? PLOT_STOP_SCRIPT : stop == RUN_STOP_KEY ? PLOT_STOP_KEY : PLOT_STOP_OTHER;
    if (stop == RUN_STOP_SCRIPT)
      res.waited = mrun_wait_text(r, wt, sizeof wt);
  }
  res.blocks = r->vm.blocks;
  res.t = mrun_time(r);
  res.has_pos = 1;
  position(r, res.pos);
  plot_end(pl, &res);
}

void plot_watch(struct plot *pl, struct run_watch *w)
{
  memset(w, 0, sizeof *w);
  w->ctx = pl;
  w->start = w_start;
  w->call = w_call;
  w->moved = w_moved;
  w->row = w_row;
  w->result = w_result;
}
