/* tests/restart/killsave.so: an LD_PRELOAD shim that kills the process
 * (SIGKILL, raised on itself) inside its Nth save of a restart state, so
 * that tests/restart/run.sh can put a kill exactly where a chance kill
 * only sometimes lands.  Nothing in s42 knows of it: it wraps the libc
 * calls that src/atomic.c makes for a save (mkstemp for the temporary file
 * BASE.tmpXXXXXX, write into it, rename it over BASE).
 *
 *   S42_KILLSAVE=N:write[:K]  the Nth save whose temporary file's name has
 *                           ".state.tmp" in it: its Kth write() (the
 *                           first unless K is given) writes half of its
 *                           bytes, then SIGKILL (a kill in the middle of
 *                           writing the new state)
 *   S42_KILLSAVE=N:rename   the Nth save: all of it is written (and
 *                           fsynced), then SIGKILL instead of the rename
 *   S42_KILLSAVE_LOG=FILE   where it says what it did, one line, just before
 *                           the kill: "killed save N in write K: 62 of 124
 *                           bytes of PATH" or "killed save N before the
 *                           rename of PATH" (the test checks that line)
 *
 * Without S42_KILLSAVE it only passes every call on.  Built without
 * sanitizers (under make asan the test sets verify_asan_link_order=0). */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int want_n = -1;      /* the save to kill (1 = the first), -1 none */
static int at_rename;        /* 0: in its Kth write; 1: before its rename */
static int want_k = 1;       /* that K */
static int writes;           /* writes into the target so far */
static int saves;            /* saves begun so far */
static int target_fd = -1;   /* the Nth save's temporary file */
static char target_path[4096];

static void setup(void)
{
  static int done;
  if (done)
    return;
  done = 1;
  const char *e = getenv("S42_KILLSAVE");
  if (!e)
    return;
  char *end;
  long n = strtol(e, &end, 10);
  if (n < 1 || *end != ':')
    return;
  if (strncmp(end + 1, "write", 5) == 0 && (end[6] == 0 || end[6] == ':')) {
    at_rename = 0;
    if (end[6] == ':') {
      want_k = atoi(end + 7);
      if (want_k < 1)
        return;
    }
  } else if (strcmp(end + 1, "rename") == 0)
    at_rename = 1;
  else
    return;
  want_n = (int)n;
}

static void die(const char *what)
{
  const char *log = getenv("S42_KILLSAVE_LOG");
  if (log) {
    int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd >= 0) {
      ssize_t r = write(fd, what, strlen(what));
      (void)r;
      close(fd);
    }
  }
  raise(SIGKILL);
  _exit(137); /* not reached */
}

static int note_tmp(int fd, const char *tmpl)
{
  setup();
  if (fd >= 0 && want_n > 0 && strstr(tmpl, ".state.tmp") && ++saves == want_n) {
    target_fd = fd;
    snprintf(target_path, sizeof target_path, "%s", tmpl);
  }
  return fd;
}

int mkstemp(char *tmpl)
{
  static int (*real)(char *);
  if (!real)
    real = (int (*)(char *))dlsym(RTLD_NEXT, "mkstemp");
  return note_tmp(real(tmpl), tmpl);
}

int mkstemp64(char *tmpl)
{
  static int (*real)(char *);
  if (!real)
    real = (int (*)(char *))dlsym(RTLD_NEXT, "mkstemp64");
  return note_tmp(real(tmpl), tmpl);
}

ssize_t write(int fd, const void *buf, size_t n)
{
  static ssize_t (*real)(int, const void *, size_t);
  if (!real)
    real = (ssize_t (*)(int, const void *, size_t))dlsym(RTLD_NEXT, "write");
  if (fd >= 0 && fd == target_fd && !at_rename && n > 1 && ++writes == want_k) {
    size_t half = n / 2, done = 0;
    while (done < half) {
      ssize_t w = real(fd, (const char *)buf + done, half - done);
      if (w <= 0)
        break;
      done += (size_t)w;
    }
    char msg[4200];
    snprintf(msg, sizeof msg, "killed save %d in write %d: %zu of %zu bytes of %s\n", want_n, want_k, done, n,
             target_path);
    die(msg);
  }
  return real(fd, buf, n);
}

int rename(const char *from, const char *to)
{
  static int (*real)(const char *, const char *);
  if (!real)
    real = (int (*)(const char *, const char *))dlsym(RTLD_NEXT, "rename");
  if (at_rename && target_fd >= 0 && strcmp(from, target_path) == 0) {
    char msg[4200];
    snprintf(msg, sizeof msg, "killed save %d before the rename of %s\n", want_n, target_path);
    die(msg);
  }
  return real(from, to);
}
