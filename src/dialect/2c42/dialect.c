/* The 2С42-65 as a dialect of the registry (src/core/dialect.h). */
#include "dialect.h"
#include "compile.h"

static int compile(const char *src, size_t n, struct diag_list *d, struct program *p, const struct plug_set *plugins)
{
  return comp_program_with(src, n, d, p, plugins);
}

const struct dialect dialect_2c42 = {
  .name = "2c42",
  .ext = ".kp",
  .controller = "2С42-65 (ВЗ-208Ф3 tool-grinding semi-automatic)",
  .machine = "grinder",
  .compile = compile,
  .run = DIALECT_RUN_SESSION,
};
