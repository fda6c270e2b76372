/* Fixture: callbacks that fail.  M24 fails in run() with a reason
 * (E-TEETH), G52 in check() without one. */
#include <s42_plugin.h>

static const struct s42_host *host;

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)dir;
  host = h;
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
  {sizeof(struct s42_function), 'M', 24, 0, NULL, 0, "fails in run (fixture)"},
  {sizeof(struct s42_function), 'G', 52, 1, "", S42_FN_SEPARATE, "fails in check (fixture)"},
};

static const struct s42_plugin desc = {
  .size = sizeof desc, .abi_major = S42_ABI_MAJOR, .abi_minor = S42_ABI_MINOR,
  .fingerprint = S42_ABI_FINGERPRINT, .name = "cbfail", .version = "0.1", .summary = "fixture: callbacks fail",
  .functions = fns, .nfunctions = 2, .init = init, .check = check, .run = run,
};

S42_EXPORT const struct s42_plugin *s42_plugin_entry(void);
S42_EXPORT const struct s42_plugin *s42_plugin_entry(void) { return &desc; }
