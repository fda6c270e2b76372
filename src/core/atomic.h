/* Whole files, written and read safely.  Writing: a crash never leaves a
 * file half written -- the bytes go to a temporary file beside it, which is
 * synced, renamed over the old file, and the directory synced (with
 * ATOMIC_DIRSYNC_NEW only when the name is new); the
 * temporary file a killed writer left is removed by the next write, never
 * one a live writer holds (two runs may save one file at once).  Used
 * by the M15 state and the TUI's editor.  Reading: only a regular file (or,
 * when the caller allows it, a pipe that is s42's own standard input), so a
 * FIFO or a device is a clear error rather than a hang. */
#ifndef S42_ATOMIC_H
#define S42_ATOMIC_H

#include <stddef.h>
#include <sys/types.h>
#include <sys/uio.h>

/* Write the nv buffers of v, in order, to path with permissions mode.
 * Messages name `shown` (the name the user gave).  0, or -1 with err. */
int atomic_write(const char *path, const char *shown, mode_t mode, const struct iovec *v, int nv, char *err,
                 size_t n);
/* The same with flags.  ATOMIC_DIRSYNC_NEW: sync the directory only when
 * the rename makes a new name there; one that replaces an existing file
 * syncs only the file.  The rename is atomic either way: a SIGKILL or a
 * crash of the process leaves the old or the new file, whole (the kernel
 * keeps what was written).  After a power cut the directory may still
 * name the old file -- whole, as its own write synced it -- until the
 * file system commits the rename (ext4: within its commit interval, or at
 * any later fsync, such as the next write's).  For a file rewritten often
 * whose previous version is an acceptable fallback (the M15 restart
 * state: the previous restart point). */
enum { ATOMIC_DIRSYNC_NEW = 1 };
int atomic_write_flags(const char *path, const char *shown, mode_t mode, const struct iovec *v, int nv, int flags,
                       char *err, size_t n);

/* What may be read: a regular file only, or also a pipe that is standard
 * input (`s42 run /dev/stdin`, `--operator /dev/stdin` at the end of a
 * pipeline). */
enum { FILE_REGULAR, FILE_OR_STDIN };

/* "a FIFO", "a character device", ... for messages. */
const char *file_kind(mode_t mode);
/* Open for reading without blocking on a FIFO or a device, and refuse
 * what `allow` does not allow.  The descriptor (blocking again), or -1
 * with err "PATH: REASON". */
int file_open_read(const char *path, int allow, char *err, size_t n);
/* The largest program file s42 reads, compiles or edits (README "Limits"):
 * 16,777,216 blocks (the most a program can have, vm/opcodes.h) of a
 * typical 25 bytes fit; larger is a mistake, not a program. */
#define FILE_MAX_PROGRAM ((size_t)512 << 20)
/* The whole file, NUL-terminated (*buf, malloc'd; *len without the NUL).
 * 0; -1 with err; -2 when it holds more than max bytes (err says so). */
int file_read_all(const char *path, int allow, size_t max, char **buf, size_t *len, char *err, size_t n);
/* file_read_all for a program: a regular file of FILE_MAP_MIN bytes or
 * more is mapped (private, NUL-terminated by a page of zeros), not read.
 * Release *buf with file_unload, never free.  If the file is cut short
 * while mapped, the pages past its new end read as zeros and file_cut
 * says so (no SIGBUS).  At most four are mapped at once; more are read. */
#define FILE_MAP_MIN ((size_t)1 << 20)
int file_load(const char *path, int allow, size_t max, char **buf, size_t *len, char *err, size_t n);
/* 1: the file of buf (from file_load) was cut short while mapped, and
 * what buf holds past its new end is zeros, not the file. */
int file_cut(const char *buf);
/* Release what file_load (or file_read_all) gave; NULL is nothing. */
void file_unload(char *buf);
/* 1 when a and b both name existing files and they are one file (the same
 * device and inode; links followed, so a symbolic or hard link, `./a` or
 * `d/../a` is a), else 0.  For refusing an output that is the input. */
int file_same_as(const char *a, const char *b);
/* The same rules without opening (for a file someone else opens, such as
 * a plugin's --tool): 0, or -1 with err. */
int file_check_read(const char *path, int allow, char *err, size_t n);

#endif
