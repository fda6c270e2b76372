/* Fixture: callbacks that fail.  M24 fails in run() with a reason
 * (E-TEETH), G52 in check() without one. */
#include <s42_plugin.h>

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
  return host->has_g(b, 52) ? S42_FAIL : S42_OK;
}

static int run(void *self, struct s42_block *b)
{
  (void)self;
  if (host->has_m(b, 24)) {
    host->error(b, "E-TEETH", "no teeth found (fixture)");
    return S42_FAIL;
  }
  return S42_OK;
}

static const struct s42_function fns[] = {
  S42_M_FUNCTION(24, NULL, 0, "fails in run (fixture)"),
  S42_G_FUNCTION(52, 1, "", S42_FN_SEPARATE, "fails in check (fixture)"),
};

S42_PLUGIN_DECLARE("cbfail", "0.1", "fixture: callbacks fail", fns, .init = init, .check = check, .run = run);
