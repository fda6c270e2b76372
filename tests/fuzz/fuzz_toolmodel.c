/* libFuzzer harness: parse any bytes as a tool model (contracts.md sec. 5).
 * Nothing may crash or trip a sanitizer; a parsed model must pass tm_check,
 * a refusal must leave a message naming the file and fitting the buffer. */
#include "toolmodel.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  struct tm_model m;
  char err[96];
  memset(err, 'x', sizeof err);
  if (tm_parse(&m, (const char *)data, size, "f.tool", err, sizeof err) == 0) {
    char e2[256];
    if (tm_check(&m, e2, sizeof e2) != 0)
      abort();
    double sum = 0;
    for (int i = 0; i < m.teeth; i++)
      sum += m.steps[i];
    if (sum < 359.99 || sum > 360.01)
      abort();
  } else if (memchr(err, 0, sizeof err) == NULL || strncmp(err, "f.tool", 6) != 0) {
    abort();
  }
  return 0;
}
