/* The dialect registry (src/core/dialect.h).  dialect_list is generated
 * by the build ($(BUILD)/gen/dialects.c). */
#include "dialect.h"
#include <stdio.h>
#include <string.h>
#include <strings.h>

const struct dialect *dialect_by_name(const char *name)
{
  for (size_t i = 0; dialect_list[i]; i++)
    if (strcmp(dialect_list[i]->name, name) == 0)
      return dialect_list[i];
  return NULL;
}

const struct dialect *dialect_by_file(const char *path)
{
  const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
  const char *dot = strrchr(base, '.');
  if (dot)
    for (size_t i = 0; dialect_list[i]; i++)
      if (strcasecmp(dialect_list[i]->ext, dot) == 0)
        return dialect_list[i];
  return dialect_by_name("2c42");
}

void dialect_names(char *buf, size_t n)
{
  size_t k = 0;
  buf[0] = 0;
  for (size_t i = 0; dialect_list[i] && k < n; i++)
    k += (size_t)snprintf(buf + k, n - k, "%s%s", i ? ", " : "", dialect_list[i]->name);
}
