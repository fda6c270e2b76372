/* libFuzzer harness for the compiler alone: lex, parse, static checks and
 * code generation of any text, then the verifier and the disassembler over
 * the result.  No input may crash, hang, leak or trip a sanitizer;
 * diagnostics are fine; a program that compiles must verify, with the
 * maximum stack the verifier finds recorded exactly. */
#include "compile.h"
#include "disasm.h"
#include "verify.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  static FILE *devnull;
  if (!devnull && !(devnull = fopen("/dev/null", "w")))
    return 0;
  struct program p;
  struct diag_list d;
  prog_init(&p);
  diag_init(&d, "fuzz.kp");
  if (comp_program((const char *)data, size, &d, &p) == 0) {
    char msg[300];
    uint32_t need;
    if (prog_verify_need(&p, &need, msg, sizeof msg)) {
      fprintf(stderr, "fuzz_compile: the program compiles but does not verify: %s\n", msg);
      abort();
    }
    if (need != p.max_stack) {
      fprintf(stderr, "fuzz_compile: the compiler records a stack of %u, the verifier finds %u\n", p.max_stack, need);
      abort();
    }
    vm_disasm(devnull, &p, (const char *)data, size);
  }
  diag_print(devnull, &d);
  prog_free(&p);
  diag_free(&d);
  return 0;
}
