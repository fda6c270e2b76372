/* A minimal s42 plugin: M11 writes the block number into R0 and logs a
 * line.  Build it against the installed header alone:
 *   cc -shared -fPIC -o hello.so hello.c        (s42_plugin.h on the path)
 * and run a program that uses M11 with `s42 run PROGRAM.kp --plugins DIR`. */
#include <s42_plugin.h>

static const struct s42_host *host;

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)dir;
  host = h;
  *self = NULL;
  return S42_OK;
}

static int run(void *self, struct s42_block *b)
{
  (void)self;
  host->set_param(b, 0, host->number(b));
  host->log(b, "hello from block %d", host->number(b));
  return S42_OK;
}

static const struct s42_function functions[] = {
  {sizeof(struct s42_function), 'M', 11, 0, "", 0, "R0 = this block's number"},
};

static const struct s42_plugin descriptor = {
  .size = sizeof descriptor,
  .abi_major = S42_ABI_MAJOR,
  .abi_minor = S42_ABI_MINOR,
  .fingerprint = S42_ABI_FINGERPRINT,
  .name = "hello",
  .version = "1.0",
  .summary = "M11 says hello",
  .functions = functions,
  .nfunctions = 1,
  .init = init,
  .run = run,
};

S42_EXPORT const struct s42_plugin *s42_plugin_entry(void);
S42_EXPORT const struct s42_plugin *s42_plugin_entry(void)
{
  return &descriptor;
}
