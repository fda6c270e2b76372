/* libmodbus loaded on demand (src/host/modbus_dl.h). */
#define S42_MODBUS_DL_IMPL
#include "modbus_dl.h"
#include <dlfcn.h>
#include <stdio.h>

struct s42_modbus s42_modbus;

int s42_modbus_load(char *err, size_t n)
{
  static void *lib;
  if (lib)
    return 0;
  void *h = dlopen(S42_MODBUS_SONAME, RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char *e = dlerror();
    snprintf(err, n, "--modbus: cannot load %s (the Modbus server needs libmodbus): %s", S42_MODBUS_SONAME,
             e ? e : "dlopen failed");
    return -1;
  }
  void *sym;
#define S42_MODBUS_SYM(name) \
  if (!(sym = dlsym(h, #name))) { \
    snprintf(err, n, "--modbus: %s has no %s", S42_MODBUS_SONAME, #name); \
    dlclose(h); \
    return -1; \
  } \
  *(void **)&s42_modbus.name = sym;
  S42_MODBUS_FNS(S42_MODBUS_SYM)
#undef S42_MODBUS_SYM
  lib = h;
  return 0;
}
