/* Fixture: a plugin that reads its options.  init() keeps the "tool" it was
 * given (and fails, with that reason, for the tool "fail"); describe()
 * reports it beside what option("tool") and option("lang") answer now, as
 * {"init":"...","now":"...","lang":"..."}; M01 sets R1 to the length of the
 * tool option now.  Its state is all in *self and its host table too: a
 * second plugin set in the process starts it again in the same shared
 * object. */
#include <s42_plugin.h>
#include <stdio.h>
#include <string.h>

struct opts {
  const struct s42_host *host;
  char init[64];
};

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)dir;
  const struct s42_host *host;
  S42_PLUGIN_INIT(h, host);
  const char *tool = host->option("tool");
  if (tool && strcmp(tool, "fail") == 0) {
    host->error(NULL, NULL, "the tool is %s", tool);
    return S42_FAIL_USAGE;
  }
  struct opts *o = host->alloc(sizeof *o);
  if (!o)
    return S42_FAIL;
  o->host = host;
  snprintf(o->init, sizeof o->init, "%s", tool ? tool : "");
  *self = o;
  return S42_OK;
}

static void fini(void *self)
{
  struct opts *o = self;
  o->host->free(o);
}

static int run(void *self, struct s42_block *b)
{
  struct opts *o = self;
  const char *tool = o->host->option("tool");
  return o->host->set_param(b, 1, tool ? (double)strlen(tool) : -1) ? S42_FAIL : S42_OK;
}

static size_t describe(void *self, int what, char *buf, size_t cap)
{
  struct opts *o = self;
  (void)what;
  const char *now = o->host->option("tool"), *lang = o->host->option("lang");
  int k = snprintf(buf, cap, "{\"init\":\"%s\",\"now\":\"%s\",\"lang\":\"%s\"}", o->init, now ? now : "",
                   lang ? lang : "(null)");
  return k < 0 ? 0 : (size_t)k;
}

static const struct s42_function fns[] = {
  S42_M_FUNCTION(1, NULL, 0, "R1 = length of the tool option (fixture)"),
};

S42_PLUGIN_DECLARE("opts", "0.1", "fixture: reads its options", fns, .init = init, .fini = fini, .run = run,
                   .describe = describe, .trace_key = "opts");
