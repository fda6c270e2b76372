/* cairo loaded on demand (src/host/cairo_dl.h). */
#define S42_CAIRO_DL_IMPL
#include "cairo_dl.h"
#include <dlfcn.h>
#include <stdio.h>

struct s42_cairo s42_cairo;

int s42_cairo_load(char *err, size_t n)
{
  static void *lib;
  if (lib)
    return 0;
  /* kept open for the life of the process: cairo's font caches live there */
  void *h = dlopen("libcairo.so.2", RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    snprintf(err, n, "cannot load cairo: %s", dlerror());
    return -1;
  }
  void *sym;
#define S42_CAIRO_SYM(name) \
  if (!(sym = dlsym(h, #name))) { \
    snprintf(err, n, "cairo has no %s: %s", #name, dlerror()); \
    dlclose(h); \
    return -1; \
  } \
  *(void **)&s42_cairo.name = sym;
  S42_CAIRO_FNS(S42_CAIRO_SYM)
#undef S42_CAIRO_SYM
  lib = h;
  return 0;
}
