/* libFuzzer harness for the operator-script parser, and for what the
 * headless run asks of a parsed script: the `at` check against the
 * program's block numbers before the run and the warnings after it (which
 * blocks exist, how far the run got and how often each block started are
 * taken from the input's own bytes). */
#include "operator.h"
#include <stdint.h>
#include <stdio.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  struct opscript s;
  FILE *devnull = fopen("/dev/null", "w");
  if (!devnull)
    return 0;
  if (ops_parse((const char *)data, size, "fuzz.op", &s, devnull) == 0) {
    unsigned char have[1000];
    static unsigned runs[1000];
    unsigned h = 2166136261u;
    for (size_t i = 0; i < size; i++)
      h = (h ^ data[i]) * 16777619u;
    for (int n = 0; n < 1000; n++) {
      h = h * 1103515245u + 12345u;
      have[n] = (h >> 16) & 1;
      runs[n] = (h >> 8) % 5;
    }
    ops_check_at(&s, have, "fuzz.op", devnull);
    for (size_t i = 0; i < s.nat; i++)
      s.at[i].fired = (h >> (i % 32)) & 1;
    ops_warn_unused(&s, s.n ? h % (s.n + 1) : 0, s.n ? h % (s.n + 2) : 0, (h & 1) ? runs : NULL, "fuzz.op",
                    devnull);
    ops_free(&s);
  }
  fclose(devnull);
  return 0;
}
