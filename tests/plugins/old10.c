/* Fixture: a plugin built for ABI 1.0, before 1.1 appended host services.
 * It must still load and run: M8 sets R5 to 10 + its block number.  It
 * reads only the 1.0 part of the host table, whose size it checks as a
 * 1.0 plugin would have (the table then ended with mode). */
#include <s42_plugin.h>
#include <stddef.h>

static const struct s42_host *host;

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)dir;
  if (h->size < offsetof(struct s42_host, mode) + sizeof h->mode || h->abi_major != 1)
    return S42_FAIL;
  host = h;
  *self = NULL;
  return S42_OK;
}

static int run(void *self, struct s42_block *b)
{
  (void)self;
  return host->set_param(b, 5, 10 + host->number(b)) ? S42_FAIL : S42_OK;
}

/* the 1.0 layout of struct s42_function */
static const struct s42_function fns[] = {
  {sizeof(struct s42_function), 'M', 8, 0, "", 0, "R5 = 10 + block number (fixture: ABI 1.0)"},
};

static const struct s42_plugin desc = {
  .size = sizeof desc, .abi_major = 1, .abi_minor = 0,
  .fingerprint = S42_ABI_FINGERPRINT, .name = "old10", .version = "1.0", .summary = "fixture: built for ABI 1.0",
  .functions = fns, .nfunctions = 1, .init = init, .run = run,
};

S42_EXPORT const struct s42_plugin *s42_plugin_entry(void);
S42_EXPORT const struct s42_plugin *s42_plugin_entry(void) { return &desc; }
