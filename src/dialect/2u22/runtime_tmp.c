/* TEMPORARY: a stand-in for the runtime (runtime.c, written elsewhere) so
 * that the front end links and can be tested.  Delete when runtime.c lands. */
#include "mrun.h"
#include "u22.h"

const struct mrun_rt u22_runtime = {.size = 1};
