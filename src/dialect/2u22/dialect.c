/* The 2У22 (16Б16Ф3 lathe) as a dialect of the registry (src/core/dialect.h). */
#include "dialect.h"
#include "u22c.h"
#include "u22.h"

static int compile(const char *src, size_t n, struct diag_list *d, struct program *p, const struct plug_set *plugins)
{
  (void)plugins;   /* the 2У22 has no plugin functions */
  return u22_compile(src, n, d, p);
}

const struct dialect dialect_2u22 = {
  .name = "2u22",
  .ext = ".u22",
  .controller = "2У22 (16Б16Ф3 lathe)",
  .machine = "lathe",
  .compile = compile,
  .run = DIALECT_RUN_MACHINE,
  .runtime = &u22_runtime,
};
