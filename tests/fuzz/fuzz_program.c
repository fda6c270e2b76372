/* libFuzzer harness: compile any text as a 2С42 program and, when it
 * compiles, run it headless with a block budget.  Nothing may crash, hang,
 * leak or trip a sanitizer. */
#include "compile.h"
#include "session.h"
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  struct program p;
  struct diag_list d;
  prog_init(&p);
  diag_init(&d, "fuzz.kp");
  if (comp_program((const char *)data, size, &d, &p) == 0) {
    struct session *s = malloc(sizeof *s);
    if (s) {
      sess_init(s, &p);
      s->vm.max_blocks = 5000;
      s->vm.yield_all = 1;
      for (int i = 0; i < 100000; i++) {
        enum sess_ev ev = sess_run(s);
        if (ev == SE_WAIT) {
          if (sess_key_ps(s) && sess_key_pusk(s))
            break;
        } else if (ev != SE_START) {
          break;
        }
      }
      free(s);
    }
  }
  prog_free(&p);
  diag_free(&d);
  return 0;
}
