/* libFuzzer harness for the operator-script parser. */
#include "operator.h"
#include <stdint.h>
#include <stdio.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  struct opscript s;
  FILE *devnull = fopen("/dev/null", "w");
  if (!devnull)
    return 0;
  if (ops_parse((const char *)data, size, "fuzz.op", &s, devnull) == 0)
    ops_free(&s);
  fclose(devnull);
  return 0;
}
