/* Fixture: a good plugin.  G50 moves X by its X word at the contour speed
 * (a motion function a plugin adds to the language); M30 writes R1 = R1+1
 * and logs a line. */
#include <s42_plugin.h>
#include <math.h>
#include <string.h>

static const struct s42_host *host;

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)dir;
  S42_PLUGIN_INIT(h, host);
  *self = NULL;
  return S42_OK;
}

static int check(void *self, struct s42_block *b)
{
  (void)self;
  if (host->has_g(b, 50) && host->word(b, 'X') == 13) {
    host->error(b, "E-RANGE", "G50: X+13 is unlucky");
    return S42_FAIL;
  }
  return S42_OK;
}

static int run(void *self, struct s42_block *b)
{
  (void)self;
  if (host->has_m(b, 30)) {
    host->set_param(b, 1, host->param(b, 1) + 1);
    host->log(b, "M30 in block %d", host->number(b));
  }
  if (host->has_g(b, 50)) {
    struct s42_move m;
    memset(&m, 0, sizeof m);
    m.size = sizeof m;
    m.d[S42_X] = host->word(b, 'X');
    m.length = fabs(m.d[S42_X]) / 1000.0;
    m.limit = host->axis_speed(S42_X);
    return host->move(b, &m) ? S42_FAIL : S42_OK;
  }
  return S42_OK;
}

static const struct s42_function fns[] = {
  S42_G_FUNCTION(50, 1, "XF", S42_FN_MOTION, "move X (fixture)"),
  S42_M_FUNCTION(30, NULL, 0, "count in R1 (fixture)"),
};

S42_PLUGIN_DECLARE("good", "0.1", "fixture: works", fns, .init = init, .check = check, .run = run);
