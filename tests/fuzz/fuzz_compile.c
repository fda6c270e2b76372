/* libFuzzer harness for the compiler alone: lex, parse, static checks and
 * code generation of any text, then the disassembler over the result.  No
 * input may crash, hang, leak or trip a sanitizer; diagnostics are fine. */
#include "compile.h"
#include "disasm.h"
#include <stdint.h>
#include <stdio.h>

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
  if (comp_program((const char *)data, size, &d, &p) == 0)
    vm_disasm(devnull, &p, (const char *)data, size);
  diag_print(devnull, &d);
  prog_free(&p);
  diag_free(&d);
  return 0;
}
