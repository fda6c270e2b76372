/* Fixture: a plugin whose constructor does what a broken library does when
 * it is loaded, chosen by the name it is installed under: crash*.so dies of
 * SIGSEGV, exit*.so calls _exit(0) (a library that thinks it is a
 * program), hang*.so never returns, marker*.so appends a line to the file
 * $S42_MARKER (proof that it was loaded at all, even by a probe); any
 * other name is harmless.  $S42_BADCTOR, when set, chooses instead (a
 * crashing helix.so).  Its plugin name is its file name's stem, and it
 * would provide G53 -- so a program that uses G53 makes s42 look for it. */
#define _GNU_SOURCE
#include <s42_plugin.h>
#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char name[48] = "badctor";

__attribute__((constructor)) static void loaded(void)
{
  Dl_info info;
  if (!dladdr((void *)loaded, &info) || !info.dli_fname)
    return;
  const char *b = strrchr(info.dli_fname, '/');
  b = b ? b + 1 : info.dli_fname;
  size_t k = strcspn(b, ".");
  if (k > 0 && k < sizeof name) {
    memcpy(name, b, k);
    name[k] = 0;
  }
  const char *how = getenv("S42_BADCTOR") ? getenv("S42_BADCTOR") : name;
  if (strncmp(how, "crash", 5) == 0) {
    raise(SIGSEGV);
  } else if (strncmp(how, "exit", 4) == 0) {
    _exit(0);
  } else if (strncmp(how, "hang", 4) == 0) {
    for (;;)
      pause();
  } else if (strncmp(how, "marker", 6) == 0) {
    const char *f = getenv("S42_MARKER");
    int fd = f ? open(f, O_WRONLY | O_CREAT | O_APPEND, 0644) : -1;
    if (fd >= 0) {
      char line[sizeof name + 1];
      size_t n = strlen(name);
      memcpy(line, name, n);
      line[n] = '\n';
      ssize_t w = write(fd, line, n + 1);   /* a short write: the test sees the line missing */
      (void)w;
      close(fd);
    }
  }
}

static int init(const struct s42_host *h, const char *dir, void **self)
{
  (void)h;
  (void)dir;
  *self = NULL;
  return S42_OK;
}

static const struct s42_function fns[] = {
  S42_G_FUNCTION(53, 1, "", S42_FN_SEPARATE, "does nothing (fixture)"),
};

S42_PLUGIN_DECLARE(name, "0.1", "fixture: its constructor", fns, .init = init);
