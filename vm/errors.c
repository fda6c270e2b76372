/* Names and neutral meanings of the error codes (vm/errors.h). */
#include "errors.h"
#include <string.h>

static const struct { const char *code, *text; } table[] = {
#define ERR_ROW(e, c, text) {c, text},
  S42_ERRORS(ERR_ROW)
#undef ERR_ROW
};

const char *err_code(int e)
{
  return (e >= 0 && e < S42_E_COUNT) ? table[e].code : "E-?";
}

const char *err_meaning(int e)
{
  return (e >= 0 && e < S42_E_COUNT) ? table[e].text : "?";
}

int err_from_code(const char *code)
{
  for (int i = 1; i < S42_E_COUNT; i++)
    if (strcmp(table[i].code, code) == 0)
      return i;
  return -1;
}
