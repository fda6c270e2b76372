/* The restart snapshot, for every dialect (src/core/mrun.h: mrun_save,
 * mrun_restore): the VM's state at a block's start and the runtime's own
 * blob (its machine and modal state), saved atomically (temporary file,
 * fsync, rename, fsync of the directory for a new name) with a checksum
 * and a hash of the program text, so a restart either goes on from a
 * consistent state or is refused -- never trusts a damaged or stale file.
 * The checksum only finds damage: a hand-edited file with a recomputed
 * sum passes it, so every field is checked against the program and its
 * range before anything of it is used, the VM's here and the runtime's by
 * its restore() with the same checker.  Here rather than in mrun.c for
 * the tests that forge snapshots (tests/restart/forge.c). */
#ifndef S42_SNAPSHOT_H
#define S42_SNAPSHOT_H

#include "vm.h"
#include <stddef.h>
#include <stdint.h>

#define SNAP_MAGIC "S42STATE"
/* 2: code addresses of the superinstructions; plugin states; 3: CMPCK/CMPCR;
 * 4: frames and arrays at the VM's upper bounds; 5: the VM's part and the
 * runtime's blob, of any dialect */
#define SNAP_VERSION 5u
#define SNAP_BLOB_MAX ((size_t)1 << 20)
/* Positions and the block count stay within 2^53, where a double (a JSON
 * number) is still exact and no later move can overflow an int64_t; time
 * within 10^15 s. */
#define SNAP_POS_MAX 9007199254740992LL
#define SNAP_BLOCKS_MAX 9007199254740992ULL
#define SNAP_TIME_MAX 1e15

/* The file: the header, the VM's part, then blob_len bytes of the
 * runtime's blob (each record zeroed before filling, so the checksum
 * covers no stray padding bytes). */
struct snap_header {
  char magic[8];
  uint32_t version, size;   /* size: of everything after the header */
  uint64_t sum;             /* mrun_hash of everything after the header */
};

struct snap_vm {
  uint64_t prog_hash;
  uint32_t block, pc;
  uint64_t blocks;
  double reg[VM_NREG];
  struct vm_array arr[VM_ARRAYS_MAX];   /* the program's lim.arrays and lim.cells used, the rest 0 */
  int32_t depth;
  struct vm_frame frames[VM_DEPTH_MAX]; /* depth of them (at most the program's lim.depth) */
  uint32_t blob_len;
};

/* Checking a loaded record field by field: the first bad field is the one
 * named, as "the state's WHAT (FILE)". */
struct snap_chk {
  const struct program *p;
  const char *shown;
  char *err;
  size_t n;
  int bad;
};
void snap_refuse(struct snap_chk *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* v finite and in lo..hi (and whole, when asked); otherwise refused. */
void snap_range(struct snap_chk *c, const char *what, double v, double lo, double hi, int whole);
void snap_ints(struct snap_chk *c, const char *what, long long v, long long lo, long long hi);
/* UTF-8, perhaps cut short at its end. */
int snap_utf8_ok(const char *s);

#endif
