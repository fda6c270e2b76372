/* ncursesw loaded on demand (src/host/curses_dl.h). */
#define S42_CURSES_DL_IMPL
#include <curses.h>
#include "curses_dl.h"
#include <dlfcn.h>
#include <stdio.h>

struct s42_curses s42_curses;

int s42_curses_load(char *err, size_t n)
{
  static void *lib;
  if (lib)
    return 0;
  /* its dependency libtinfo comes with it; dlsym looks there too */
  void *h = dlopen(S42_CURSES_SONAME, RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char *e = dlerror();
    snprintf(err, n, "cannot load %s (the terminal draws with ncursesw): %s", S42_CURSES_SONAME,
             e ? e : "dlopen failed");
    return -1;
  }
  void *sym;
#define S42_CURSES_SYM(name) \
  if (!(sym = dlsym(h, #name))) { \
    snprintf(err, n, "%s has no %s", S42_CURSES_SONAME, #name); \
    dlclose(h); \
    return -1; \
  } \
  *(void **)&s42_curses.name = sym;
  S42_CURSES_SYMS(S42_CURSES_SYM)
#undef S42_CURSES_SYM
  lib = h;
  return 0;
}
