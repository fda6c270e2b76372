/* libFuzzer harness for the 2У22 front end (src/dialect/2u22): any text
 * through its lexer, parser, checks and emitter, then the verifier and the
 * disassembler over the result and, when it compiled, the VM alone for at
 * most 5,000 blocks (each block's machine turn, VM_EV_BLOCK, does nothing).
 * No input may crash, hang, leak or trip a sanitizer; diagnostics are
 * fine; a program that compiles must verify with the stack it records,
 * carry one record per block, and run to its end or to a clean error. */
#include "../../src/dialect/2u22/u22.h"
#include "../../src/dialect/2u22/u22c.h"
#include "disasm.h"
#include "verify.h"
#include "vm.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  static FILE *devnull;
  static struct vm vm;   /* large: not on the stack */
  if (!devnull && !(devnull = fopen("/dev/null", "w")))
    return 0;
  struct program p;
  struct diag_list d;
  prog_init(&p);
  diag_init(&d, "fuzz.u22");
  if (u22_compile((const char *)data, size, &d, &p) == 0) {
    char msg[300];
    uint32_t need;
    if (prog_verify_need(&p, &need, msg, sizeof msg)) {
      fprintf(stderr, "fuzz_u22: the program compiles but does not verify: %s\n", msg);
      abort();
    }
    if (need != p.max_stack) {
      fprintf(stderr, "fuzz_u22: the compiler records a stack of %u, the verifier finds %u\n", p.max_stack, need);
      abort();
    }
    const struct u22_ext *x = p.ext;
    if (!x || x->n != p.nblocks || p.runtime != &u22_runtime || p.lim.depth != 2 || p.saved_reg != -1) {
      fprintf(stderr, "fuzz_u22: the program's record, runtime or limits are wrong\n");
      abort();
    }
    vm_disasm(devnull, &p, (const char *)data, size);
    if (vm_init(&vm, &p) == 0) {
      vm.max_blocks = 5000;
      for (int i = 0; i < 20000; i++) {
        enum vm_event ev = vm_run(&vm);
        if (ev == VM_EV_END || ev == VM_EV_ERROR)
          break;
        if (ev == VM_EV_BLOCK && vm.depth > 2) {
          fprintf(stderr, "fuzz_u22: a block runs %d calls deep\n", vm.depth);
          abort();
        }
      }
      if (vm.err.code && vm.err.code != S42_E_RANGE && vm.err.code != S42_E_LIMIT && vm.err.code != S42_E_NEST) {
        fprintf(stderr, "fuzz_u22: the VM alone failed with %s: %s\n", err_code(vm.err.code), vm.err.msg);
        abort();
      }
    }
  }
  diag_print(devnull, &d);
  prog_free(&p);
  diag_free(&d);
  return 0;
}
