/* Fixture: init fails, saying why (ABI 1.1: error(NULL, ...) in init).
 * The program that uses M31 must stop with E-PLUGIN naming the reason; one
 * that does not use it must not notice. */
#include <s42_plugin.h>

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)dir; (void)self;
  h->error(NULL, "E-PLUGIN", "the fixture's %s is missing", "licence");
  return S42_FAIL;
}

static const struct s42_function fns[] = {
  S42_M_FUNCTION(31, NULL, 0, "never starts (fixture)"),
};

S42_PLUGIN_DECLARE("initfail", "0.1", "fixture: init fails", fns, .init = init);
