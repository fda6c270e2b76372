/* Fixture: a plugin that changes the VM and then fails the block, to show
 * that a failed block is a transaction (language.md sec. 7).  M06 and M07
 * both write R0 600 times (more than the VM's journal holds), then R1 =
 * R1 + 1, TK, UG, array 1 (block number, 2, 3) and array 2; M06 succeeds,
 * M07 then fails with E-TEETH.  After M07 the registers and arrays must be
 * as after the block before it. */
#include <s42_plugin.h>

static const struct s42_host *host;

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)dir;
  S42_PLUGIN_INIT(h, host);
  *self = NULL;
  return S42_OK;
}

static int run(void *self, struct s42_block *b)
{
  (void)self;
  int n = host->number(b);
  for (int i = 0; i < 600; i++)
    host->set_param(b, 0, i);
  host->set_param(b, 1, host->param(b, 1) + 1);
  host->set_param(b, S42_TK, 1000 + n);
  host->set_param(b, S42_UG, 2000 + n);
  double a1[3] = {n, 2, 3}, a2[5] = {n, n, n, n, n};
  if (host->load_array(b, 1, a1, 3) || host->load_array(b, 2, a2, 5))
    return S42_FAIL;
  if (host->has_m(b, 7)) {
    host->error(b, "E-TEETH", "the fixture fails after writing (block %d)", n);
    return S42_FAIL;
  }
  return S42_OK;
}

static const struct s42_function fns[] = {
  S42_M_FUNCTION(6, "", 0, "writes R0 R1 TK UG and the arrays (fixture)"),
  S42_M_FUNCTION(7, "", 0, "writes as M06, then fails (fixture)"),
};

S42_PLUGIN_DECLARE("txfail", "0.1", "fixture: writes, then fails", fns, .init = init, .run = run);
