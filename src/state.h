/* The M15 restart point: the machine state saved when a block with M15
 * starts, atomically (temporary file, fsync, rename, fsync of the
 * directory), with a checksum and a hash of the program text, so a restart
 * either continues from a consistent state or is refused -- never trusts a
 * damaged or stale file. */
#ifndef S42_STATE_H
#define S42_STATE_H

#include "session.h"
#include <stddef.h>
#include <stdint.h>

uint64_t state_hash(const void *data, size_t n);
/* Save the state at the start of the current block.  0, or -1 with err. */
int state_save(const struct session *s, const char *path, uint64_t prog_hash, char *err, size_t n);
/* Load into a fresh session of the same program: the VM resumes at the M15
 * block.  0, or -1 with err (missing, damaged, or another program text). */
int state_load(struct session *s, const char *path, uint64_t prog_hash, char *err, size_t n);

#endif
