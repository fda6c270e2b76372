/* Atomic file writes and careful reads (src/core/atomic.h). */
#include "atomic.h"
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

static int write_all(int fd, const char *p, size_t n)
{
  while (n) {
    ssize_t w = write(fd, p, n);
    if (w < 0) {
      if (errno == EINTR)
        continue;
      return -1;
    }
    p += w;
    n -= (size_t)w;
  }
  return 0;
}

/* The temporary files.  A write killed between creating its temporary
 * file and the rename leaves BASE.tmpXXXXXX behind, and the next write's
 * sweep (remove_stale) removes it.  Two runs may save one file at the same
 * time (`s42 tui c.kp` beside `s42 run c.kp`, both on c.kp.state), each
 * sweeping while the other writes, so the sweep must never remove a live
 * writer's file.  One rule makes that impossible rather than unlikely: a
 * temporary name is unlinked only by a process that holds the flock of the
 * file the name points to, after it has seen, holding it, that the name
 * still points to that file.
 *
 * - The writer (tmp_create) holds the flock of its temporary file from
 *   before its first byte until after the rename: it writes nothing until
 *   it holds the lock and has seen its name still point to its file (the
 *   device and inode of what it holds open).  From then on no sweep can
 *   take the lock, so none unlinks the name; and nothing else removes or
 *   replaces such a name (mkstemp makes it with O_EXCL, a rename only
 *   moves it away), so it stays the writer's until its own rename.
 * - The sweep takes the lock without waiting (a live writer's fails), then
 *   checks that the name still points to the file it locked -- a name
 *   removed meanwhile by another sweep may have been made again by a new
 *   writer -- and only then unlinks it.  Between that check and the unlink
 *   no one else can remove or replace the name: it would need the lock.
 * - So the one file a sweep can take from a live writer is one that writer
 *   has just made and not yet locked: empty, nothing written yet.  The
 *   writer finds out at once -- its lock fails (the sweep holds it, and
 *   unlinks the name) or its name points to no file of its own (the sweep
 *   did) -- and makes another.  A save never loses what it wrote, whatever
 *   the timing.  (Before, the writer ignored a lock it did not get and
 *   wrote on into a file the other run's sweep had unlinked; its rename
 *   failed, "No such file or directory", every few hundred saves.)
 *
 * Only that exact pattern (mkstemp's six letters and digits), only regular
 * files of this user.  On a file system without flock a writer writes
 * without the guard, and the sweep, which cannot lock either, removes
 * nothing. */

/* a and b are the same file */
static int same_file(const struct stat *a, const struct stat *b)
{
  return a->st_dev == b->st_dev && a->st_ino == b->st_ino;
}

static void remove_stale(const char *dir, const char *base)
{
  DIR *d = opendir(dir);
  if (!d)
    return;
  size_t bl = strlen(base);
  struct dirent *e;
  while ((e = readdir(d)) != NULL) {
    const char *nm = e->d_name, *x = nm + bl + 4;
    if (strncmp(nm, base, bl) != 0 || strncmp(nm + bl, ".tmp", 4) != 0 || strlen(x) != 6)
      continue;
    int ok = 1;
    for (int i = 0; i < 6; i++)
      ok &= isalnum((unsigned char)x[i]) != 0;
    if (!ok)
      continue;
    int fd = openat(dirfd(d), nm, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0)
      continue;
    struct stat st, again;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_uid == geteuid() && flock(fd, LOCK_EX | LOCK_NB) == 0 &&
        fstatat(dirfd(d), nm, &again, AT_SYMLINK_NOFOLLOW) == 0 && same_file(&st, &again))
      unlinkat(dirfd(d), nm, 0);
    close(fd);   /* drops the lock: after the unlink */
  }
  closedir(d);
}

/* How many fresh temporary files in a row a writer lets other writers'
 * sweeps take before it gives up (each is a sweep that came in the
 * microseconds between a mkstemp and its flock). */
enum { TMP_TRIES = 100 };

/* Make the temporary file PATH.tmpXXXXXX in tmp (tl bytes) and lock it
 * (above): its descriptor; -1 with errno; -2 when other saves' sweeps
 * took TMP_TRIES in a row.  tmp holds the last name tried. */
static int tmp_create(const char *path, char *tmp, size_t tl)
{
  for (int i = 0; i < TMP_TRIES; i++) {
    snprintf(tmp, tl, "%s.tmpXXXXXX", path);
    int fd = mkstemp(tmp);
    if (fd < 0)
      return -1;
    int lk;
    while ((lk = flock(fd, LOCK_EX | LOCK_NB)) != 0 && errno == EINTR)
      ;
    if (lk != 0 && errno == EWOULDBLOCK) {
      close(fd);   /* a sweep holds it, and unlinks the name */
      continue;
    }
    /* (locked, or no locks on this file system: then no sweep takes it) */
    struct stat mine, named;
    if (fstat(fd, &mine) != 0) {
      int e = errno;
      if (lk == 0)
        unlink(tmp);   /* ours: no sweep can take it while we hold the lock */
      close(fd);
      errno = e;
      return -1;
    }
    if (lstat(tmp, &named) == 0 && same_file(&mine, &named))
      return fd;
    close(fd);   /* a sweep took it before the lock: nothing was written */
  }
  return -2;
}

int atomic_write(const char *path, const char *shown, mode_t mode, const struct iovec *v, int nv, char *err,
                 size_t n)
{
  return atomic_write_flags(path, shown, mode, v, nv, 0, err, n);
}

int atomic_write_flags(const char *path, const char *shown, mode_t mode, const struct iovec *v, int nv, int flags,
                       char *err, size_t n)
{
  size_t tl = strlen(path) + 16;
  char *tmp = malloc(tl), *dir = strdup(path), *base = strdup(path);
  if (!tmp || !dir || !base) {
    free(tmp);
    free(dir);
    free(base);
    snprintf(err, n, "out of memory");
    return -1;
  }
  const char *dname = dirname(dir);
  remove_stale(dname, basename(base));
  int fd = tmp_create(path, tmp, tl), rc = -1, bad = 0;
  if (fd < 0) {
    if (fd == -2)
      snprintf(err, n, "%s: cannot keep a temporary file beside it: the last of %d in a row, %s, was taken by "
               "another save of the same file", shown, TMP_TRIES, tmp);
    else
      snprintf(err, n, "%s: cannot create the temporary file %s beside it: %s", shown, tmp, strerror(errno));
    free(tmp);
    free(dir);
    free(base);
    return -1;
  }
  /* the lock is held until the rename (tmp_create) */
  bad = fchmod(fd, mode) != 0;
  for (int i = 0; i < nv && !bad; i++)
    bad = write_all(fd, v[i].iov_base, v[i].iov_len) != 0;
  struct stat old;
  /* ATOMIC_DIRSYNC_NEW: is there a name to replace?  (lstat: a symbolic
   * link is replaced by the rename, not followed) */
  int is_new = !(flags & ATOMIC_DIRSYNC_NEW) || lstat(path, &old) != 0;
  if (bad || fsync(fd)) {
    snprintf(err, n, "%s: %s", tmp, strerror(errno));
    unlink(tmp);
  } else if (rename(tmp, path)) {
    snprintf(err, n, "%s: cannot rename the temporary file %s over it: %s", shown, tmp, strerror(errno));
    unlink(tmp);
  } else {
    /* the rename itself must reach the disk -- unless the caller settles
     * for the old whole file after a power cut when a name is replaced */
    if (is_new) {
      int dfd = open(dname, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (dfd >= 0) {
        fsync(dfd);
        close(dfd);
      }
    }
    rc = 0;
  }
  /* after fsync the bytes are on the disk: close only drops the lock */
  close(fd);
  free(tmp);
  free(dir);
  free(base);
  return rc;
}

/* ---- reading ---- */

const char *file_kind(mode_t mode)
{
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISREG(mode)) return "a regular file";
  return "not a regular file";
}

/* st (of the file opened) is allowed; otherwise err says why. */
static int allowed(const char *path, const struct stat *st, int allow, char *err, size_t n)
{
  if (S_ISREG(st->st_mode))
    return 1;
  struct stat in;
  if (allow == FILE_OR_STDIN && S_ISFIFO(st->st_mode) && fstat(STDIN_FILENO, &in) == 0 && S_ISFIFO(in.st_mode) &&
      in.st_dev == st->st_dev && in.st_ino == st->st_ino)
    return 1;
  if (S_ISDIR(st->st_mode))
    snprintf(err, n, "%s: is a directory, not a file", path);
  else
    snprintf(err, n, "%s: is %s, not a regular file%s", path, file_kind(st->st_mode),
             allow == FILE_OR_STDIN && S_ISFIFO(st->st_mode) ? " (a pipe is read only as standard input)" : "");
  return 0;
}

int file_open_read(const char *path, int allow, char *err, size_t n)
{
  /* O_NONBLOCK: opening a FIFO without a writer would wait for one */
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    snprintf(err, n, "%s: %s", path, strerror(errno));
    return -1;
  }
  struct stat st;
  if (fstat(fd, &st) != 0) {
    snprintf(err, n, "%s: %s", path, strerror(errno));
    close(fd);
    return -1;
  }
  if (!allowed(path, &st, allow, err, n)) {
    close(fd);
    return -1;
  }
  /* a pipe on standard input is read as it comes (this descriptor is a
   * file description of its own: fd 0's flags stay as they were) */
  int fl = fcntl(fd, F_GETFL);
  if (fl >= 0)
    fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
  return fd;
}

/* Read what fd holds (then close it): file_read_all without the open. */
static int read_fd(int fd, const char *path, size_t max, char **buf, size_t *len, char *err, size_t n)
{
  struct stat st;
  /* a regular file is read in one piece of its size; a pipe grows */
  size_t cap = fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && (uint64_t)st.st_size <= max ? (size_t)st.st_size + 1
                                                                                          : 65536;
  size_t got = 0;
  char *b = malloc(cap);
  int rc = 0;
  while (b) {
    if (got == cap) {
      size_t nc = cap > max / 2 ? max + 2 : cap * 2;
      char *nb = nc > cap ? realloc(b, nc) : NULL;
      if (!nb) {
        free(b);
        b = NULL;
        break;
      }
      b = nb;
      cap = nc;
    }
    ssize_t r = read(fd, b + got, cap - got);
    if (r < 0 && errno == EINTR)
      continue;
    if (r < 0) {
      snprintf(err, n, "%s: %s", path, strerror(errno));
      rc = -1;
      break;
    }
    if (r == 0)
      break;
    got += (size_t)r;
    if (got > max) {
      snprintf(err, n, "%s: too large: at most %zu bytes are read", path, max);
      rc = -2;
      break;
    }
  }
  close(fd);
  if (!b) {
    snprintf(err, n, "%s: out of memory", path);
    return -1;
  }
  if (rc) {
    free(b);
    return rc;
  }
  if (got == cap) {   /* room for the NUL */
    char *nb = realloc(b, cap + 1);
    if (!nb) {
      free(b);
      snprintf(err, n, "%s: out of memory", path);
      return -1;
    }
    b = nb;
  }
  b[got] = 0;
  *buf = b;
  *len = got;
  return 0;
}

int file_same_as(const char *a, const char *b)
{
  struct stat sa, sb;
  return a && b && stat(a, &sa) == 0 && stat(b, &sb) == 0 && same_file(&sa, &sb);
}

int file_check_read(const char *path, int allow, char *err, size_t n)
{
  struct stat st;
  if (stat(path, &st) != 0)
    return 0;   /* missing: whoever opens it says so in its own words */
  return allowed(path, &st, allow, err, n) ? 0 : -1;
}

int file_read_all(const char *path, int allow, size_t max, char **buf, size_t *len, char *err, size_t n)
{
  int fd = file_open_read(path, allow, err, n);
  return fd < 0 ? -1 : read_fd(fd, path, max, buf, len, err, n);
}

/* ---- A large program mapped rather than read ----
 * Reading copies every byte from the page cache into fresh pages, which
 * the kernel first clears: for a 25 MB program that is most of the time
 * the compile spends in the kernel.  A private mapping shares the page
 * cache's pages instead.  The mapping is the file's pages and then one
 * page of zeros, so the text is NUL-terminated even when its size is a
 * multiple of the page size, or when the file grows meanwhile.
 *
 * A file cut short while mapped makes its pages past the new end raise
 * SIGBUS when touched.  The handler puts a page of zeros in place of the
 * one touched and marks the mapping cut (file_cut): the reader sees the
 * text end there, and the caller says the file changed under it instead
 * of crashing.  A SIGBUS anywhere else goes to the disposition there was
 * before. */
static struct fmap {
  char *base;                  /* NULL: a free slot */
  size_t span;                 /* bytes mapped, the page of zeros included */
  volatile sig_atomic_t cut;   /* a page was replaced by zeros */
} fmaps[4];
static size_t fmap_page;
static struct sigaction fmap_prev;

static struct fmap *fmap_of(const char *a, int within)
{
  for (size_t i = 0; i < sizeof fmaps / sizeof *fmaps; i++) {
    struct fmap *m = &fmaps[i];
    if (m->base && (within ? a >= m->base && a < m->base + m->span : a == m->base))
      return m;
  }
  return NULL;
}

static void fmap_bus(int sig, siginfo_t *si, void *uc)
{
  (void)sig;
  (void)uc;
  const char *a = si->si_addr;
  struct fmap *m = si->si_code > 0 ? fmap_of(a, 1) : NULL;   /* (> 0: a fault, not kill(2)) */
  if (m) {
    char *page = m->base + ((size_t)(a - m->base) & ~(fmap_page - 1));
    if (mmap(page, fmap_page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0) != MAP_FAILED) {
      m->cut = 1;
      return;   /* the access is made again, and reads zeros */
    }
  }
  sigaction(SIGBUS, &fmap_prev, NULL);   /* not ours: delivered again, as before */
  raise(SIGBUS);
}

/* Map fd's size bytes with a page of zeros after them: 0, or -1 (then
 * the caller reads the file instead). */
static int fmap_add(int fd, size_t size, char **buf)
{
  struct fmap *m = fmaps;   /* a free slot */
  while (m < fmaps + sizeof fmaps / sizeof *fmaps && m->base)
    m++;
  if (m == fmaps + sizeof fmaps / sizeof *fmaps)
    return -1;
  if (!fmap_page) {
    long pg = sysconf(_SC_PAGESIZE);
    struct sigaction sa = {.sa_sigaction = fmap_bus, .sa_flags = SA_SIGINFO};
    sigemptyset(&sa.sa_mask);
    if (pg <= 0 || (pg & (pg - 1)) || sigaction(SIGBUS, &sa, &fmap_prev) != 0)
      return -1;
    fmap_page = (size_t)pg;
  }
  size_t span = (size + fmap_page - 1) / fmap_page * fmap_page + fmap_page;
  char *b = mmap(NULL, span, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (b == MAP_FAILED)
    return -1;
  if (mmap(b, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_FIXED, fd, 0) == MAP_FAILED) {
    munmap(b, span);
    return -1;
  }
  *m = (struct fmap){.base = b, .span = span};
  *buf = b;
  return 0;
}

int file_load(const char *path, int allow, size_t max, char **buf, size_t *len, char *err, size_t n)
{
  int fd = file_open_read(path, allow, err, n);
  if (fd < 0)
    return -1;
  struct stat st;
  if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && (uint64_t)st.st_size >= FILE_MAP_MIN &&
      (uint64_t)st.st_size <= max && fmap_add(fd, (size_t)st.st_size, buf) == 0) {
    close(fd);
    *len = (size_t)st.st_size;
    return 0;
  }
  return read_fd(fd, path, max, buf, len, err, n);
}

int file_cut(const char *buf)
{
  const struct fmap *m = buf ? fmap_of(buf, 0) : NULL;
  return m && m->cut;
}

void file_unload(char *buf)
{
  struct fmap *m = buf ? fmap_of(buf, 0) : NULL;
  if (!m) {
    free(buf);
    return;
  }
  munmap(m->base, m->span);
  *m = (struct fmap){0};
}
