/* libFuzzer harness for the VM and the machine: compile any text as a 2С42
 * program and, when it compiles, verify it and run it headless with a
 * block budget, watched block by block or not at all, answering every
 * wait the way an operator might (a number, ПС, Пуск, a jog), with cycle
 * exit and corrections pressed now and then.
 * Nothing may crash, hang, leak or trip a sanitizer; a program that
 * compiles must verify before it runs. */
#include "compile.h"
#include "session.h"
#include "verify.h"
#include <stdint.h>
#include <stdio.h>
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
    char msg[300];
    if (prog_verify(&p, msg, sizeof msg)) {
      fprintf(stderr, "fuzz_vm: the program compiles but does not verify: %s\n", msg);
      abort();
    }
    struct session *s = malloc(sizeof *s);
    if (s) {
      sess_init(s, &p);
      s->vm.max_blocks = 5000;
      /* operator answers from the input's own bytes: deterministic */
      unsigned h = 2166136261u;
      for (size_t i = 0; i < size; i++)
        h = (h ^ data[i]) * 16777619u;
      /* watched (every block yields: the VM's checking dispatch table) or,
       * for one input in four, not (its plain table, as a batch run) */
      s->vm.yield_all = (h & 3) != 0;
      s->vm.start_all = (h & 3) != 0;
      for (int i = 0; i < 20000; i++) {
        enum sess_ev ev = sess_run(s);
        h = h * 1103515245u + 12345u;
        if (ev == SE_START) {
          if ((h >> 16) % 97 == 0)
            sess_key_exit(s);
          if ((h >> 16) % 89 == 1)
            sess_correct(s, (int)(h >> 8) & 3, (int64_t)(h % 2001) - 1000);
          if ((h >> 16) % 83 == 2)
            sess_override(s, (int)((h >> 4) % 151));
          continue;
        }
        if (ev != SE_WAIT)
          break;
        int ok;
        switch (s->wait) {
        case W_ANSWER:
          ok = sess_answer(s, (long long)(h % 200001) - 100000);
          break;
        case W_TEACH:
          sess_jog(s, (int)(h >> 8) & 3, (int64_t)(h % 20001) - 10000);
          ok = sess_key_ps(s);
          break;
        case W_FEED:
          ok = sess_override(s, 100);
          if (ok == 0 && s->state == SE_WAIT)
            ok = -1;
          break;
        default:
          if ((h >> 20) & 1)
            sess_jog(s, (int)(h >> 8) & 3, (int64_t)(h % 2001) - 1000);
          ok = sess_key_ps(s);
          if (sess_key_pusk(s) == 0)
            ok = 0;
          break;
        }
        if (ok)
          break;
        uint32_t grid[SCR_ROWS][SCR_COLS];
        if ((h >> 12) % 7 == 0)
          sess_screen(s, grid);
      }
      uint32_t grid[SCR_ROWS][SCR_COLS];
      sess_screen(s, grid);
      free(s);
    }
  }
  prog_free(&p);
  diag_free(&d);
  return 0;
}
