/* Writing a file so that a crash never leaves it half written: the bytes go
 * to a temporary file beside it, which is synced, renamed over the old file,
 * and the directory synced.  Used by the M15 state and the TUI's editor. */
#ifndef S42_ATOMIC_H
#define S42_ATOMIC_H

#include <stddef.h>
#include <sys/types.h>
#include <sys/uio.h>

/* Write the nv buffers of v, in order, to path with permissions mode.
 * Messages name `shown` (the name the user gave).  0, or -1 with err. */
int atomic_write(const char *path, const char *shown, mode_t mode, const struct iovec *v, int nv, char *err,
                 size_t n);

#endif
