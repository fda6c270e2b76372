/* The M15 restart point: the machine state saved when a block with M15
 * starts, atomically (temporary file, fsync, rename, fsync of the
 * directory), with a checksum and a hash of the program text, so a restart
 * either continues from a consistent state or is refused -- never trusts a
 * damaged or stale file.  The checksum only finds damage: a hand-edited file
 * with a recomputed sum passes it, so every field is checked against this
 * program and its range before anything of it is used (README "Restart
 * from M15" lists the bounds). */
#ifndef S42_STATE_H
#define S42_STATE_H

#include "session.h"
#include <stddef.h>
#include <stdint.h>

#define STATE_MAGIC "S42STATE"
#define STATE_VERSION 4u  /* 2: code addresses of the superinstructions; plugin states; 3: CMPCK/CMPCR;
                             4: frames and arrays at the VM's upper bounds (the program's limits) */
#define STATE_PLUGS 8
#define STATE_PLUG_MAX 512
/* Positions and the block count stay within 2^53, where a double (a JSON
 * number) is still exact and no later move can overflow an int64_t; time
 * within 10^15 s. */
#define STATE_POS_MAX 9007199254740992LL
#define STATE_BLOCKS_MAX 9007199254740992ULL
#define STATE_TIME_MAX 1e15

/* The file: a header, then one fixed record (zeroed before filling, so
 * the checksum covers no stray padding bytes).  Here rather than in
 * state.c for the tests that forge states (tests/unit/test_state.c). */
struct state_header {
  char magic[8];
  uint32_t version, size;
  uint64_t sum;             /* state_hash of the payload */
};

struct state_payload {
  uint64_t prog_hash;
  uint32_t block, pc;
  uint64_t blocks;
  double reg[VM_NREG];
  struct vm_array arr[VM_ARRAYS_MAX];   /* the program's lim.arrays and lim.cells used, the rest 0 */
  int32_t depth;
  struct vm_frame frames[VM_DEPTH_MAX]; /* depth of them (at most the program's lim.depth) */
  int64_t pos[4];
  double t;
  int32_t wheel, override_pct, override_allowed, corr_allowed;
  uint32_t nplug;           /* the plugins' own states (oscillation) */
  struct {
    char name[48];
    uint32_t len;
    unsigned char data[STATE_PLUG_MAX];
  } plug[STATE_PLUGS];
  int32_t p3, np3;
  struct screen_p3 p3l[SCR_WORK];
  uint32_t directive;
  char dirtext[SCR_COLS * 4 + 1];
};

uint64_t state_hash(const void *data, size_t n);
/* Save the state at the start of the current block.  An existing file at
 * path is replaced only when it is a restart state (or empty): anything
 * else is refused.  0, or -1 with err. */
int state_save(const struct session *s, const char *path, uint64_t prog_hash, char *err, size_t n);
/* Load into a fresh session of the same program: the VM resumes at the M15
 * block.  0, or -1 with err (missing, damaged, another program text, or a
 * field that does not fit this program: err names it). */
int state_load(struct session *s, const char *path, uint64_t prog_hash, char *err, size_t n);
/* The same from the bytes of a state file; `shown` names it in messages. */
int state_restore(struct session *s, const void *data, size_t len, const char *shown, uint64_t prog_hash,
                  char *err, size_t n);

#endif
