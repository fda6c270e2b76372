/* The VM: a stepper over a compiled program.  vm_run executes until the host
 * must act -- a block's machine work, a watched block's start, the end, an
 * error -- and returns that event; the host acts and calls vm_run again.
 * No global state: any number of VMs may live in one process. */
#ifndef S42_VM_H
#define S42_VM_H

#include "program.h"
#include <stdint.h>

/* The call depth, the arrays and their cells, the ranges and the angle unit
 * are the program's (program.lim); the frames and arrays below hold up to
 * the VM's upper bounds of vm/program.h. */
#define VM_JOURNAL 512    /* register writes one block can make (a block is <= 320 chars) */
#define VM_STACK 512      /* values on the evaluation stack (program.max_stack at most) */

/* vm.sw: the host has published its switches (without it MACHS is MACH). */
#define VM_SW_HELD (1u << 31)

enum vm_event {
  VM_EV_BLOCK,   /* the current block's words are evaluated: do its machine work */
  VM_EV_START,   /* a watched block (vm.watch) is about to run */
  VM_EV_END,     /* the program ended (M2) */
  VM_EV_ERROR    /* vm.err says what; the block was rolled back */
};

/* An array: the program's lim.cells of cell[] are used, the rest stay 0. */
struct vm_array { int ptr, len; double cell[VM_CELLS_MAX]; };

struct vm_frame {
  uint32_t ret, start, left, block;
  double saved;
  uint8_t jflag;
};

struct vm_error {
  int code;         /* vm/errors.h */
  uint32_t block;   /* block index */
  unsigned col;     /* column of the word that raised it (0 unknown) */
  int aux;          /* code-specific: the array number for E-ARRAY± */
  char msg[200];
};

struct vm_undo { uint32_t reg; double old; };

struct vm {
  const struct program *p;
  uint32_t pc;
  uint32_t cur;                /* index of the block being run */
  double reg[VM_NREG];
  double w[VM_NSLOT];          /* the pending block's word values */
  struct vm_array arr[VM_ARRAYS_MAX];   /* the program's lim.arrays are used */
  uint8_t jflag;               /* the block's jump condition */
  int depth;
  struct vm_frame frames[VM_DEPTH_MAX];  /* lim.depth of them at most */
  uint64_t blocks;             /* blocks executed (committed) */
  uint64_t max_blocks;         /* E-LIMIT when reached; 0 = no limit */
  int yield_all;               /* SYNC yields too: the host watches every block */
  int start_all;               /* yield VM_EV_START before every block */
  const uint8_t *watch;        /* per block: yield VM_EV_START before it runs; read as
                                  a whole when the VM first sees the pointer (a host
                                  that changes the flags in place hands it over anew:
                                  NULL for one vm_run, or another array) */
  const uint8_t *watch_seen;   /* the watch array last scanned, and whether it flags any */
  int watch_any;
  uint32_t sw;                 /* the host's switches, as it published them before this
                                  vm_run: VM_SW_HELD and a bit each (their meaning the
                                  dialect's); a MACHS block whose switches already stand
                                  so is no work for the host.  0: every MACHS yields */
  int exit_latch;              /* cycle-exit key, taken by the next PP block */
  uint32_t pp_jumps;           /* operational jumps taken */
  int done;                    /* ended or failed: vm_run returns at once */
  unsigned clamped;            /* rule index + 1 of a value clamped in this block, 0 none */
  double clamped_from;         /* the value before clamping */
  struct vm_error err;
  double rad;                  /* the program's angle unit in radians (vm_init) */
  /* the open block's transaction */
  unsigned nundo;
  unsigned arr_saved;           /* bit k: array k is snapshotted in arr_old[k] */
  struct vm_undo undo[VM_JOURNAL];
  struct vm_array arr_old[VM_ARRAYS_MAX];
};

/* 0, or -1 when the program needs more than this VM holds -- a deeper stack
 * than VM_STACK, a call depth, arrays or cells above VM_DEPTH_MAX,
 * VM_ARRAYS_MAX, VM_CELLS_MAX: the VM is then ended with that error
 * (E-LIMIT), which the first vm_run returns. */
int vm_init(struct vm *vm, const struct program *p);
enum vm_event vm_run(struct vm *vm);
/* The host's machine work for the current block failed: roll the block back
 * and end the run with that error.  vm_run then returns VM_EV_ERROR. */
void vm_fail(struct vm *vm, int code, const char *fmt, ...)
  __attribute__((format(printf, 3, 4)));
/* Set a register from the host (dialog input, teach-in, M16, a plugin),
 * journaled as part of the open block however often the host writes. */
void vm_set_reg(struct vm *vm, unsigned reg, double v);
/* Load array k (0 .. lim.arrays - 1) from the host (a plugin's results):
 * n <= lim.cells values from the start, the rest 0, the pointer at the
 * start; snapshotted as part of the open block, as the program's own array
 * words are. */
void vm_load_array(struct vm *vm, int k, const double *v, int n);

/* Right after VM_EV_START: do not run the block that was about to start
 * (block skip, `/`); vm_run goes on with the next block in the program's
 * text, which must exist in the same unit (the front end refuses a
 * skippable block that ends a unit or a repeat).  0, or -1 when not at a
 * block's start or there is no next block (nothing changes). */
int vm_skip(struct vm *vm);

/* Block number of block index b (0 when it has none). */
static inline uint32_t vm_block_number(const struct vm *vm, uint32_t b)
{
  return vm->p->blocks[b].number;
}

#endif
