/* Atomic file writes (src/atomic.h). */
#include "atomic.h"
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

int atomic_write(const char *path, const char *shown, mode_t mode, const struct iovec *v, int nv, char *err,
                 size_t n)
{
  size_t tl = strlen(path) + 16;
  char *tmp = malloc(tl), *dir = strdup(path);
  if (!tmp || !dir) {
    free(tmp);
    free(dir);
    snprintf(err, n, "out of memory");
    return -1;
  }
  snprintf(tmp, tl, "%s.tmpXXXXXX", path);
  int fd = mkstemp(tmp), rc = -1, bad = 0;
  if (fd < 0) {
    snprintf(err, n, "%s: cannot create a temporary file beside it: %s", shown, strerror(errno));
    free(tmp);
    free(dir);
    return -1;
  }
  bad = fchmod(fd, mode) != 0;
  for (int i = 0; i < nv && !bad; i++)
    bad = write_all(fd, v[i].iov_base, v[i].iov_len) != 0;
  if (bad || fsync(fd)) {
    snprintf(err, n, "%s: %s", tmp, strerror(errno));
    close(fd);
    unlink(tmp);
  } else if (close(fd)) {
    snprintf(err, n, "%s: %s", tmp, strerror(errno));
    unlink(tmp);
  } else if (rename(tmp, path)) {
    snprintf(err, n, "%s: %s", shown, strerror(errno));
    unlink(tmp);
  } else {
    /* the rename itself must reach the disk */
    int dfd = open(dirname(dir), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
      fsync(dfd);
      close(dfd);
    }
    rc = 0;
  }
  free(tmp);
  free(dir);
  return rc;
}
