/* Fixture: callbacks that crash.  The file loads, its probe passes and
 * init() starts it; then each function crashes its own way:
 *   G54  run() writes through a null pointer (SIGSEGV)
 *   G55  run() divides by zero (SIGFPE)
 *   G56  run() calls abort() (SIGABRT)
 *   G57  run() recurses until the stack overflows (SIGSEGV, on the
 *        alternate signal stack)
 *   G58  check() writes through a null pointer
 *   G59  run() is fine, but advance() crashes from then on: in the next
 *        block's move
 *   G60  run() is fine, but describe() crashes from then on: as the
 *        block's trace row is made
 *   G61  run() is fine, but fini() crashes: as s42 exits
 * It is built without make asan's sanitizers (plugins/module.mk): it is
 * there to crash for real, not to be reported by them first. */
#include <s42_plugin.h>
#include <stdlib.h>

static const struct s42_host *host;
static int *volatile nowhere;   /* NULL, where the compiler cannot see it */
static volatile int zero;
static volatile int bottom = -1;  /* never reached: the stack ends first */
static int advance_crashes, describe_crashes, fini_crashes;

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)dir;
  S42_PLUGIN_INIT(h, host);
  *self = NULL;
  return S42_OK;
}

static int deeper(int n)
{
  volatile char pad[4096];
  pad[0] = (char)n;
  if (n == bottom)
    return 0;
  return deeper(n + 1) + pad[0];   /* not a tail call: every frame stays */
}

static int check(void *self, struct s42_block *b)
{
  (void)self;
  if (host->has_g(b, 58))
    *nowhere = 58;
  return S42_OK;
}

static int run(void *self, struct s42_block *b)
{
  (void)self;
  if (host->has_g(b, 54))
    *nowhere = 54;
  if (host->has_g(b, 55))
    return 55 / zero;
  if (host->has_g(b, 56))
    abort();
  if (host->has_g(b, 57))
    return deeper(0);
  if (host->has_g(b, 59))
    advance_crashes = 1;
  if (host->has_g(b, 60))
    describe_crashes = 1;
  if (host->has_g(b, 61))
    fini_crashes = 1;
  return S42_OK;
}

static void advance(void *self, struct s42_block *b, double dt)
{
  (void)self;
  (void)b;
  (void)dt;
  if (advance_crashes)
    *nowhere = 59;
}

static void fini(void *self)
{
  (void)self;
  if (fini_crashes)
    *nowhere = 61;
}

static size_t describe(void *self, int what, char *buf, size_t cap)
{
  (void)self;
  (void)what;
  (void)buf;
  (void)cap;
  if (describe_crashes)
    *nowhere = 60;
  return 0;
}

static const struct s42_function fns[] = {
  S42_G_FUNCTION(54, 1, "", S42_FN_SEPARATE, "writes through NULL in run (fixture)"),
  S42_G_FUNCTION(55, 1, "", S42_FN_SEPARATE, "divides by zero in run (fixture)"),
  S42_G_FUNCTION(56, 1, "", S42_FN_SEPARATE, "aborts in run (fixture)"),
  S42_G_FUNCTION(57, 1, "", S42_FN_SEPARATE, "overflows the stack in run (fixture)"),
  S42_G_FUNCTION(58, 1, "", S42_FN_SEPARATE, "writes through NULL in check (fixture)"),
  S42_G_FUNCTION(59, 1, "", S42_FN_SEPARATE, "advance crashes from then on (fixture)"),
  S42_G_FUNCTION(60, 1, "", S42_FN_SEPARATE, "describe crashes from then on (fixture)"),
  S42_G_FUNCTION(61, 1, "", S42_FN_SEPARATE, "fini crashes (fixture)"),
};

S42_PLUGIN_DECLARE("cbcrash", "0.1", "fixture: callbacks crash", fns, .init = init, .fini = fini, .check = check,
                   .run = run, .advance = advance, .describe = describe, .trace_key = "cbcrash");
