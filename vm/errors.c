/* Names and machine messages of the error codes (vm/errors.h). */
#include "errors.h"
#include <string.h>

static const struct { const char *code, *uk, *en; } table[] = {
#define ERR_ROW(e, c, uk, en) {c, uk, en},
  S42_ERRORS(ERR_ROW)
#undef ERR_ROW
};

const char *err_code(int e)
{
  return (e >= 0 && e < S42_E_COUNT) ? table[e].code : "E-?";
}

const char *err_title(int e, int en)
{
  if (e < 0 || e >= S42_E_COUNT)
    return "?";
  return en ? table[e].en : table[e].uk;
}

int err_from_code(const char *code)
{
  for (int i = 1; i < S42_E_COUNT; i++)
    if (strcmp(table[i].code, code) == 0)
      return i;
  return -1;
}
