/* An LD_PRELOAD shim for tests/cli/run.sh: every malloc of 16 KiB or more
 * fails, as when the machine is out of memory (the parser's arena asks
 * for 16 KiB chunks); smaller ones go through. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stddef.h>

void *malloc(size_t sz)
{
  static void *(*real)(size_t);
  if (!real)
    real = (void *(*)(size_t))dlsym(RTLD_NEXT, "malloc");
  if (sz >= 16384)
    return NULL;
  return real(sz);
}
