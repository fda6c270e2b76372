/* Fixture: built for plugin ABI 2.0, which this s42 does not have. */
#include <s42_plugin.h>

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)h; (void)dir; (void)self;
  return S42_OK;
}

static const struct s42_function fns[] = {
  {sizeof(struct s42_function), 'G', 51, 1, NULL, 0, "never offered"},
};

static const struct s42_plugin desc = {
  .size = sizeof desc, .abi_major = S42_ABI_MAJOR + 1, .abi_minor = 0,
  .fingerprint = S42_ABI_FINGERPRINT, .name = "wrongabi", .version = "9", .summary = "fixture: ABI 2.0",
  .functions = fns, .nfunctions = 1, .init = init,
};

S42_EXPORT const struct s42_plugin *s42_plugin_entry(void);
S42_EXPORT const struct s42_plugin *s42_plugin_entry(void) { return &desc; }
