/* A minimal s42 plugin: M11 writes the block number into R0 and logs a
 * line.  Build it against the installed header alone:
 *   cc -shared -fPIC -o hello.so hello.c        (s42_plugin.h on the path)
 * and run a program that uses M11 with `s42 run PROGRAM.kp --plugins DIR`. */
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
  host->set_param(b, 0, host->number(b));
  host->log(b, "hello from block %d", host->number(b));
  return S42_OK;
}

static const struct s42_function functions[] = {
  S42_M_FUNCTION(11, "", 0, "R0 = this block's number"),
};

/* the descriptor and s42_plugin_entry(): the ABI version, sizes and
 * fingerprint come from the header */
S42_PLUGIN_DECLARE("hello", "1.0", "M11 says hello", functions, .init = init, .run = run);
