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
  const char *tool = h->option("tool");
  if (tool && strcmp(tool, "fail") == 0) {
    h->error(NULL, NULL, "the tool is %s", tool);
    return S42_FAIL_USAGE;
  }
  struct opts *o = h->alloc(sizeof *o);
  if (!o)
    return S42_FAIL;
  o->host = h;
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
  {sizeof(struct s42_function), 'M', 1, 0, NULL, 0, "R1 = length of the tool option (fixture)"},
};

static const struct s42_plugin desc = {
  .size = sizeof desc, .abi_major = S42_ABI_MAJOR, .abi_minor = S42_ABI_MINOR,
  .fingerprint = S42_ABI_FINGERPRINT, .name = "opts", .version = "0.1", .summary = "fixture: reads its options",
  .functions = fns, .nfunctions = 1, .init = init, .fini = fini, .run = run, .describe = describe,
  .trace_key = "opts",
};

S42_EXPORT const struct s42_plugin *s42_plugin_entry(void);
S42_EXPORT const struct s42_plugin *s42_plugin_entry(void) { return &desc; }
