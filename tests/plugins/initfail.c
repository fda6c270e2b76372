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
  {sizeof(struct s42_function), 'M', 31, 0, NULL, 0, "never starts (fixture)"},
};

static const struct s42_plugin desc = {
  .size = sizeof desc, .abi_major = S42_ABI_MAJOR, .abi_minor = S42_ABI_MINOR,
  .fingerprint = S42_ABI_FINGERPRINT, .name = "initfail", .version = "0.1", .summary = "fixture: init fails",
  .functions = fns, .nfunctions = 1, .init = init,
};

S42_EXPORT const struct s42_plugin *s42_plugin_entry(void);
S42_EXPORT const struct s42_plugin *s42_plugin_entry(void) { return &desc; }
