/* Finding and loading plugins (src/core/plugin.h).  Scanning lists files and
 * opens none: a file is opened when a program asks for a function it may
 * provide, and only after a child process has loaded it once (plug_probe),
 * so a constructor that crashes, hangs or calls exit() costs a refusal, not
 * the command.  Every other failure -- a file that is not a shared object, a
 * missing entry symbol, another ABI version, an init that fails -- is caught
 * here too, reported with the file and the reason, and the handle closed;
 * a *.so that is no regular file (a FIFO, a directory, a link that loops)
 * is refused as the scan finds it.  A callback that crashes later costs the
 * plugin, not the command: the crash guard (plugin.h) catches the signal. */
#include "plugin.h"
#include "words.h"   /* the dialect's G/M table: which functions are a plugin's */
#include <dirent.h>
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <setjmp.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#ifndef S42_PLUGINDIR
#define S42_PLUGINDIR "/usr/local/lib/s42/plugins"
#endif

static void release_thunk(struct plug_set *ps);   /* options and starting a plugin, below */

/* The functions the language names whose work lives in plugins: the
 * owner column of the dialect's word table (words.h). */
static const char *plug_owner(char kind, int number, const char **what)
{
  const struct kp_word *w = kp_word(kind, number);
  if (!w || !w->owner)
    return NULL;
  if (what)
    *what = w->name;
  return w->owner;
}

static char *dupstr(const char *s)
{
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d)
    memcpy(d, s, n);
  return d;
}

static void add_dir(struct plug_set *ps, const char *dir)
{
  if (!dir || !*dir)
    return;
  for (size_t i = 0; i < ps->ndirs; i++)
    if (strcmp(ps->dirs[i], dir) == 0)
      return;
  char **v = realloc(ps->dirs, (ps->ndirs + 1) * sizeof *v);
  if (!v)
    return;
  ps->dirs = v;
  if ((v[ps->ndirs] = dupstr(dir)))
    ps->ndirs++;
}

/* "helix.so" -> "helix" */
static void stem(const char *path, char *out, size_t n)
{
  const char *b = strrchr(path, '/');
  b = b ? b + 1 : path;
  size_t k = strcspn(b, ".");
  if (k >= n)
    k = n - 1;
  memcpy(out, b, k);
  out[k] = 0;
}

static void refuse(struct plug_set *ps, const char *path, const char *name, const char *fmt, ...)
  __attribute__((format(printf, 4, 5)));
static void refuse(struct plug_set *ps, const char *path, const char *name, const char *fmt, ...)
{
  struct plug_refused *v = realloc(ps->bad, (ps->nbad + 1) * sizeof *v);
  if (!v)
    return;
  ps->bad = v;
  struct plug_refused *r = &v[ps->nbad];
  r->path = dupstr(path);
  char st[64];
  stem(path, st, sizeof st);
  r->name = dupstr(name ? name : st);
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(r->msg, sizeof r->msg, fmt, ap);
  va_end(ap);
  if (r->path && r->name)
    ps->nbad++;
  else {
    free(r->path);
    free(r->name);
  }
}

static int has_name(const struct plug_set *ps, const char *name)
{
  for (size_t i = 0; i < ps->n; i++)
    if (strcmp(ps->v[i].d->name, name) == 0)
      return 1;
  return 0;
}

/* Is a descriptor sane enough to be used at all?  NULL when it is. */
static const char *bad_descriptor(const struct s42_plugin *d)
{
  if (!d->name || !*d->name || strlen(d->name) > 40)
    return "has no usable name";
  if (!d->version)
    return "has no version";
  if (d->nfunctions > 64 || (d->nfunctions && !d->functions))
    return "has a malformed function table";
  if (!d->init)
    return "has no init callback";
  for (uint32_t i = 0; i < d->nfunctions; i++) {
    const struct s42_function *f = &d->functions[i];
    if (f->size < sizeof(struct s42_function) || (f->kind != 'G' && f->kind != 'M') || f->number < 0 ||
        f->number > (f->kind == 'G' ? 63 : 31) || (f->kind == 'G' && (f->group < 1 || f->group > 4)))
      return "has a malformed function table";
  }
  return NULL;
}

/* The descriptor of a loaded file, or NULL with why.  phase >= 0 (the probe
 * child): a byte before each step, so the parent knows which one died. */
static const struct s42_plugin *read_descriptor(void *h, int phase, char *why, size_t n);

/* ---- the probe: load a file once in a child process ---- */

static void send_all(int fd, const char *p, size_t k)
{
  while (k > 0) {
    ssize_t w = write(fd, p, k);
    if (w < 0 && errno == EINTR)
      continue;
    if (w <= 0)
      _exit(127);
    p += w;
    k -= (size_t)w;
  }
}

static size_t touch(const char *s)
{
  return s ? strlen(s) : 0;
}

/* The child: load, read the descriptor, report over fd.  Records: one byte
 * per step ('L' loading, 'E' the entry function, 'C' reading the
 * descriptor), then 'K' (usable) or 'R' and the reason with its NUL. */
static _Noreturn void probe_child(const char *path, int fd)
{
  /* a crash must end the child with its signal, not in a handler the
   * parent installed (the sanitizers') */
  static const int crash[] = {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT, SIGTRAP, SIGSYS};
  for (size_t i = 0; i < sizeof crash / sizeof crash[0]; i++)
    signal(crash[i], SIG_DFL);
  int null = open("/dev/null", O_WRONLY);   /* what the plugin prints is not ours */
  if (null >= 0) {
    dup2(null, STDOUT_FILENO);
    dup2(null, STDERR_FILENO);
  }
  char why[300];
  send_all(fd, "L", 1);
  dlerror();
  void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  const struct s42_plugin *d = NULL;
  if (!h) {
    const char *e = dlerror();
    snprintf(why, sizeof why, "cannot be loaded: %s", e ? e : "unknown reason");
  } else if ((d = read_descriptor(h, fd, why, sizeof why)) != NULL) {
    /* every string `s42 plugins` and the session will read */
    size_t k = touch(d->version) + touch(d->summary) + touch(d->trace_key);
    for (uint32_t i = 0; i < d->nfunctions; i++)
      k += touch(d->functions[i].operands) + touch(d->functions[i].summary);
    (void)k;
    send_all(fd, "K", 1);
    _exit(0);
  }
  send_all(fd, "R", 1);
  send_all(fd, why, strlen(why) + 1);
  _exit(0);
}

/* What the child sent: 1 usable, -1 refused (*reason), 0 no final record
 * yet; *step is the last step it reached. */
static int record(const char *buf, size_t k, char *step, const char **reason)
{
  size_t i = 0;
  while (i < k && (buf[i] == 'L' || buf[i] == 'E' || buf[i] == 'C'))
    i++;
  if (step)
    *step = i ? buf[i - 1] : 0;
  if (i < k && buf[i] == 'K')
    return 1;
  if (i < k && buf[i] == 'R' && memchr(buf + i, 0, k - i)) {
    if (reason)
      *reason = buf + i + 1;
    return -1;
  }
  return 0;
}

static const char *signame(int sig)
{
  switch (sig) {
  case SIGSEGV: return " (SIGSEGV)";
  case SIGBUS: return " (SIGBUS)";
  case SIGILL: return " (SIGILL)";
  case SIGFPE: return " (SIGFPE)";
  case SIGABRT: return " (SIGABRT)";
  case SIGKILL: return " (SIGKILL)";
  case SIGTRAP: return " (SIGTRAP)";
  case SIGSYS: return " (SIGSYS)";
  default: return "";
  }
}

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + t.tv_nsec / 1e9;
}

/* The probe; with `later`, a child that reported a usable file is left to
 * exit on its own while the parent goes on (its pid in *later, for
 * plug_free to reap): waiting for its exit would double the cost. */
static int probe(const char *path, char *why, size_t n, pid_t *later)
{
  int fd[2];
  if (pipe2(fd, O_CLOEXEC)) {
    snprintf(why, n, "cannot be probed: pipe: %s", strerror(errno));
    return -1;
  }
  pid_t pid = fork();
  if (pid < 0) {
    snprintf(why, n, "cannot be probed: fork: %s", strerror(errno));
    close(fd[0]);
    close(fd[1]);
    return -1;
  }
  if (pid == 0) {
    close(fd[0]);
    probe_child(path, fd[1]);
  }
  close(fd[1]);
  char buf[400];
  size_t k = 0;
  int late = 0, done = 0;
  double end = now() + PLUG_PROBE_SECONDS;
  while (!done && k < sizeof buf - 1) {
    int ms = (int)((end - now()) * 1000);
    if (ms <= 0) {
      late = 1;
      break;
    }
    struct pollfd pf = {fd[0], POLLIN, 0};
    int r = poll(&pf, 1, ms);
    if (r < 0 && errno == EINTR)
      continue;
    if (r == 0) {
      late = 1;
      break;
    }
    ssize_t got = r > 0 ? read(fd[0], buf + k, sizeof buf - 1 - k) : -1;
    if (got < 0 && errno == EINTR)
      continue;
    if (got <= 0)
      break;                      /* the child is gone */
    k += (size_t)got;
    done = record(buf, k, NULL, NULL) != 0;
  }
  close(fd[0]);
  char step;
  const char *reason;
  int r = record(buf, k, &step, &reason);
  if (r > 0 && later) {
    *later = pid;
    return 0;
  }
  if (late)
    kill(pid, SIGKILL);
  int st = 0;
  while (waitpid(pid, &st, 0) < 0 && errno == EINTR)
    ;
  if (r > 0)
    return 0;
  if (r < 0) {
    snprintf(why, n, "%s", reason);
    return -1;
  }
  /* no record: the last step reached says what died */
  const char *what = step == 'E' ? "its entry function" : step == 'C' ? "reading its descriptor" : "loading it";
  if (late)
    snprintf(why, n, "cannot be used: %s did not end within %d s", what, PLUG_PROBE_SECONDS);
  else if (WIFSIGNALED(st) && step == 'L')
    snprintf(why, n, "cannot be used: its constructor crashed: signal %d%s", WTERMSIG(st), signame(WTERMSIG(st)));
  else if (WIFSIGNALED(st))
    snprintf(why, n, "cannot be used: %s crashed: signal %d%s", what, WTERMSIG(st), signame(WTERMSIG(st)));
  else
    snprintf(why, n, "cannot be used: %s ended the process: exit %d", what, WIFEXITED(st) ? WEXITSTATUS(st) : -1);
  return -1;
}

int plug_probe(const char *path, char *why, size_t n)
{
  return probe(path, why, n, NULL);
}

/* ---- the crash guard (plugin.h) ---- */

#define GUARD_NSIG 5
static const int guard_sigs[GUARD_NSIG] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
/* What each signal went to before the guard's handler: where a signal that
 * is not a plugin's goes on to. */
static struct sigaction guard_prev[GUARD_NSIG];
/* Sets that started a plugin (their `armed`): the handlers stay while > 0. */
static int guard_sets;
/* A guarded call in progress. */
struct guard {
  sigjmp_buf jb;
  struct guard *outer;       /* the call this one runs inside (a plugin's
                                move() runs the others' advance()), or NULL */
  volatile sig_atomic_t sig; /* the signal that came back */
};
/* The innermost call running on this thread, and its alternate stack. */
static _Thread_local struct guard *guard_top;
static _Thread_local void *guard_stack;
static _Thread_local size_t guard_stack_size;
static _Thread_local int guard_stack_checked;

static void guard_handler(int sig, siginfo_t *si, void *uc);

static int guard_index(int sig)
{
  for (int k = 0; k < GUARD_NSIG; k++)
    if (guard_sigs[k] == sig)
      return k;
  return -1;
}

static int guard_ours(const struct sigaction *sa)
{
  return (sa->sa_flags & SA_SIGINFO) && sa->sa_sigaction == guard_handler;
}

/* A signal that is no plugin's goes where it went before the handler was
 * put in: to that handler, called as the kernel would have called it, or
 * to the default action (or none), as if the guard had never been there. */
static void guard_chain(int sig, siginfo_t *si, void *uc)
{
  int k = guard_index(sig);
  struct sigaction p;
  if (k < 0 || guard_ours(&guard_prev[k])) {
    memset(&p, 0, sizeof p);
    p.sa_handler = SIG_DFL;
  } else {
    p = guard_prev[k];
  }
  if ((p.sa_flags & SA_SIGINFO) && p.sa_sigaction) {
    p.sa_sigaction(sig, si, uc);
    return;
  }
  if (!(p.sa_flags & SA_SIGINFO) && p.sa_handler != SIG_DFL && p.sa_handler != SIG_IGN) {
    p.sa_handler(sig);
    return;
  }
  sigemptyset(&p.sa_mask);
  sigaction(sig, &p, NULL);
  if (si->si_code <= 0)
    raise(sig);   /* sent (kill, abort): again, to that disposition, once this returns */
  /* a fault: the instruction faults again on return */
}

static void guard_handler(int sig, siginfo_t *si, void *uc)
{
  struct guard *g = guard_top;
  /* a fault of this thread's, or a signal it sent itself (abort()); not
   * one from elsewhere (kill -SEGV) */
  if (g && (si->si_code > 0 || si->si_pid == getpid())) {
    g->sig = sig;
    siglongjmp(g->jb, 1);
  }
  guard_chain(sig, si, uc);
}

static void guard_action(struct sigaction *sa)
{
  memset(sa, 0, sizeof *sa);
  sa->sa_sigaction = guard_handler;
  sa->sa_flags = SA_SIGINFO | SA_ONSTACK;
  sigemptyset(&sa->sa_mask);
}

/* This thread's alternate signal stack: one it has (ASan's) or one of the
 * guard's, made once, for a handler to run on when the stack overflowed. */
static void guard_altstack(void)
{
  if (guard_stack_checked)
    return;
  guard_stack_checked = 1;
  stack_t ss;
  if (sigaltstack(NULL, &ss) == 0 && !(ss.ss_flags & SS_DISABLE))
    return;
  size_t n = 64 * 1024;
#ifdef _SC_SIGSTKSZ
  long m = sysconf(_SC_SIGSTKSZ);
  if (m > 0 && (size_t)m * 4 > n)
    n = (size_t)m * 4;
#endif
  void *p = mmap(NULL, n, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED)
    return;   /* no alternate stack: everything but an overflow is still caught */
  ss.ss_sp = p;
  ss.ss_size = n;
  ss.ss_flags = 0;
  if (sigaltstack(&ss, NULL) != 0) {
    munmap(p, n);
    return;
  }
  guard_stack = p;
  guard_stack_size = n;
}

/* The alternate stack back as it was, when no set holds the handlers. */
static void guard_altstack_free(void)
{
  if (!guard_stack || guard_sets || guard_top)
    return;
  stack_t ss, off = {.ss_flags = SS_DISABLE};
  if (sigaltstack(NULL, &ss) == 0 && ss.ss_sp == guard_stack && !(ss.ss_flags & SS_ONSTACK) &&
      sigaltstack(&off, NULL) == 0)
    munmap(guard_stack, guard_stack_size);
  guard_stack = NULL;
  guard_stack_checked = 0;
}

/* A set started a plugin: the handlers in, kept until guard_release. */
static void guard_hold(struct plug_set *ps)
{
  if (ps->armed)
    return;
  ps->armed = 1;
  guard_altstack();   /* this thread's, where the set's plugins run */
  if (guard_sets++)
    return;
  struct sigaction sa, cur;
  guard_action(&sa);
  for (int k = 0; k < GUARD_NSIG; k++)
    if (sigaction(guard_sigs[k], NULL, &cur) == 0 && !guard_ours(&cur)) {
      guard_prev[k] = cur;
      sigaction(guard_sigs[k], &sa, NULL);
    }
}

/* plug_free: the handlers out when no set holds them, unless another has
 * replaced them since (then it decides; the guard's, should it come back,
 * still goes on to what was before it). */
static void guard_release(struct plug_set *ps)
{
  if (!ps->armed)
    return;
  ps->armed = 0;
  if (--guard_sets)
    return;
  struct sigaction cur;
  for (int k = 0; k < GUARD_NSIG; k++)
    if (sigaction(guard_sigs[k], NULL, &cur) == 0 && guard_ours(&cur))
      sigaction(guard_sigs[k], &guard_prev[k], NULL);
}

/* The call, with the jump back: 0 when it returned, or the signal.
 * Nothing of this frame changes between sigsetjmp and the call's end but
 * g.sig, which is volatile: what the jump back finds is what was there. */
static int guard_call(void (*call)(void *), void *ctx)
{
  struct guard g;
  g.sig = 0;
  g.outer = guard_top;
  guard_top = &g;
  if (sigsetjmp(g.jb, 0) == 0) {
    call(ctx);
    guard_top = g.outer;
    return 0;
  }
  guard_top = g.outer;
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, g.sig);
  pthread_sigmask(SIG_UNBLOCK, &set, NULL);   /* the jump left the handler with it blocked */
  return g.sig;
}

/* The same with the handlers in for this call alone (no set holds them),
 * and what was there put back after. */
static __attribute__((noinline)) int guard_call_brief(void (*call)(void *), void *ctx)
{
  struct sigaction sa, was[GUARD_NSIG];
  unsigned mine = 0;
  guard_altstack();
  guard_action(&sa);
  for (int k = 0; k < GUARD_NSIG; k++)
    if (sigaction(guard_sigs[k], NULL, &was[k]) == 0 && !guard_ours(&was[k])) {
      guard_prev[k] = was[k];
      if (sigaction(guard_sigs[k], &sa, NULL) == 0)
        mine |= 1u << k;
    }
  int sig = guard_call(call, ctx);
  for (int k = 0; k < GUARD_NSIG; k++)
    if (mine & (1u << k))
      sigaction(guard_sigs[k], &was[k], NULL);
  return sig;
}

static __attribute__((noinline, cold)) void guard_crashed(struct plug_set *ps, int i, const char *what, int sig)
{
  struct plug *p = &ps->v[i];
  p->state = PLUG_CRASHED;
  snprintf(p->err, sizeof p->err, "the %s plugin crashed%s in %s(): it is not called again", p->d->name,
           signame(sig), what);
  ps->crashes++;
  ps->crashed = i;
}

/* The one place a plugin's code is called from. */
int plug_guarded(struct plug_set *ps, int i, const char *what, void (*call)(void *), void *ctx)
{
  if (ps && i >= 0 && ps->v[i].state == PLUG_CRASHED)
    return -1;
  int sig = ps && ps->armed ? guard_call(call, ctx) : guard_call_brief(call, ctx);
  if (sig && ps && i >= 0)
    guard_crashed(ps, i, what, sig);
  return sig;
}

/* The callbacks through plug_guarded: their arguments and value. */
struct call {
  const struct plug *p;
  struct s42_block *b;
  int (*cb)(void *, struct s42_block *);
  int what, r;
  double x;
  double *d;
  void *buf;
  const void *in;
  size_t n, z;
};

static void call_block(void *c_)
{
  struct call *c = c_;
  c->r = c->cb(c->p->self, c->b);
}

int plug_call(struct plug_set *ps, int i, const char *what, int (*cb)(void *, struct s42_block *),
              struct s42_block *b)
{
  struct call c = {.p = &ps->v[i], .b = b, .cb = cb, .r = S42_FAIL};
  plug_guarded(ps, i, what, call_block, &c);
  return c.r;
}

static void call_advance(void *c_)
{
  struct call *c = c_;
  c->p->d->advance(c->p->self, c->b, c->x);
}

void plug_call_advance(struct plug_set *ps, int i, struct s42_block *b, double dt)
{
  struct call c = {.p = &ps->v[i], .b = b, .x = dt};
  plug_guarded(ps, i, "advance", call_advance, &c);
}

static void call_path(void *c_)
{
  struct call *c = c_;
  c->r = c->p->d->path(c->p->self, c->b, c->x, c->d);
}

int plug_call_path(struct plug_set *ps, int i, struct s42_block *b, double t, double d[4])
{
  struct call c = {.p = &ps->v[i], .b = b, .x = t, .d = d, .r = S42_FAIL};
  plug_guarded(ps, i, "path", call_path, &c);
  return c.r;
}

static void call_save(void *c_)
{
  struct call *c = c_;
  c->z = c->p->d->save(c->p->self, c->buf, c->n);
}

size_t plug_call_save(struct plug_set *ps, int i, void *buf, size_t cap)
{
  struct call c = {.p = &ps->v[i], .buf = buf, .n = cap};
  plug_guarded(ps, i, "save", call_save, &c);
  return c.z;
}

static void call_load(void *c_)
{
  struct call *c = c_;
  c->r = c->p->d->load(c->p->self, c->in, c->n);
}

int plug_call_load(struct plug_set *ps, int i, const void *buf, size_t len)
{
  struct call c = {.p = &ps->v[i], .in = buf, .n = len, .r = S42_FAIL};
  plug_guarded(ps, i, "load", call_load, &c);
  return c.r;
}

static void call_describe(void *c_)
{
  struct call *c = c_;
  c->z = c->p->d->describe(c->p->self, c->what, c->buf, c->n);
}

size_t plug_call_describe(struct plug_set *ps, int i, int what, char *buf, size_t cap)
{
  struct call c = {.p = &ps->v[i], .what = what, .buf = buf, .n = cap};
  plug_guarded(ps, i, "describe", call_describe, &c);
  return c.z;
}

static void call_reset(void *c_)
{
  struct call *c = c_;
  c->p->d->reset(c->p->self);
}

void plug_call_reset(struct plug_set *ps, int i)
{
  struct call c = {.p = &ps->v[i]};
  plug_guarded(ps, i, "reset", call_reset, &c);
}

static void call_fini(void *c_)
{
  struct call *c = c_;
  c->p->d->fini(c->p->self);
}

/* init(host, dir, &self) */
struct call_init {
  const struct s42_plugin *d;
  const struct s42_host *host;
  const char *dir;
  void **self;
  int r;
};

static void call_init(void *c_)
{
  struct call_init *c = c_;
  c->r = c->d->init(c->host, c->dir, c->self);
}

/* the entry function of a file not yet a plugin */
struct call_entry {
  s42_plugin_entry_fn entry;
  const struct s42_plugin *d;
};

static void call_entry(void *c_)
{
  struct call_entry *c = c_;
  c->d = c->entry();
}

static const struct s42_plugin *read_descriptor(void *h, int phase, char *why, size_t n)
{
  char ver[96];
  s42_plugin_entry_fn entry;
  void *sym = dlsym(h, S42_PLUGIN_ENTRY_NAME);
  memcpy(&entry, &sym, sizeof entry);
  if (!sym) {
    snprintf(why, n, "has no entry symbol %s()", S42_PLUGIN_ENTRY_NAME);
    return NULL;
  }
  const struct s42_plugin *d;
  if (phase >= 0) {   /* the probe's child: a crash ends it, and the parent says so */
    send_all(phase, "E", 1);
    d = entry();
    send_all(phase, "C", 1);
  } else {
    struct call_entry c = {.entry = entry};
    int sig = plug_guarded(NULL, -1, S42_PLUGIN_ENTRY_NAME, call_entry, &c);
    if (sig > 0) {
      snprintf(why, n, "cannot be used: its entry function crashed: signal %d%s", sig, signame(sig));
      return NULL;
    }
    d = c.d;
  }
  /* the version, before anything else of the descriptor is trusted */
  if (!d || d->size < offsetof(struct s42_plugin, name) + sizeof d->name ||
      d->fingerprint != S42_ABI_FINGERPRINT) {
    snprintf(why, n, "is not an s42 plugin (no descriptor or a wrong fingerprint)");
    return NULL;
  }
  if (d->abi_major != S42_ABI_MAJOR || d->abi_minor > S42_ABI_MINOR) {
    snprintf(ver, sizeof ver, "%u.%u", (unsigned)d->abi_major, (unsigned)d->abi_minor);
    snprintf(why, n, "was built for plugin ABI %s; this s42 has ABI %d.%d", ver, S42_ABI_MAJOR, S42_ABI_MINOR);
    return NULL;
  }
  const char *bad = d->size < sizeof *d ? "has a descriptor shorter than ABI 1.0's" : bad_descriptor(d);
  if (bad) {
    snprintf(why, n, "%s", bad);
    return NULL;
  }
  return d;
}

/* ---- opening a file when it is needed ---- */

static void open_file(struct plug_set *ps, size_t f)
{
  struct plug_file *pf = &ps->files[f];
  if (pf->state != PF_NEW)
    return;
  pf->state = PF_REFUSED;
  char why[300];
  if (probe(pf->path, why, sizeof why, &pf->probe)) {
    refuse(ps, pf->path, NULL, "%s", why);
    return;
  }
  dlerror();
  void *h = dlopen(pf->path, RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char *e = dlerror();
    refuse(ps, pf->path, NULL, "cannot be loaded: %s", e ? e : "unknown reason");
    return;
  }
  const struct s42_plugin *d = read_descriptor(h, -1, why, sizeof why);
  if (!d) {
    refuse(ps, pf->path, NULL, "%s", why);
    dlclose(h);
    return;
  }
  if (has_name(ps, d->name)) {   /* a file opened earlier has the name */
    pf->state = PF_SHADOWED;
    dlclose(h);
    return;
  }
  if (ps->n == PLUG_MAX) {
    refuse(ps, pf->path, d->name, "is one plugin too many (at most %d)", PLUG_MAX);
    dlclose(h);
    return;
  }
  struct plug *p = &ps->v[ps->n];
  memset(p, 0, sizeof *p);
  p->path = dupstr(pf->path);
  p->dir = dupstr(ps->dirs[pf->dir]);
  if (!p->path || !p->dir) {
    free(p->path);
    free(p->dir);
    dlclose(h);
    return;
  }
  p->handle = h;
  p->d = d;
  p->state = PLUG_FOUND;
  pf->state = PF_OPEN;
  pf->plug = (int)ps->n++;
}

void plug_open_all(struct plug_set *ps)
{
  for (size_t f = 0; f < ps->nfiles; f++)
    open_file(ps, f);
}

/* ---- scanning: names only ---- */

static int by_name(const void *a, const void *b)
{
  return strcmp(*(char *const *)a, *(char *const *)b);
}

static void add_file(struct plug_set *ps, size_t dir, const char *path)
{
  char st[sizeof ps->files->stem];
  stem(path, st, sizeof st);
  struct plug_file *v = realloc(ps->files, (ps->nfiles + 1) * sizeof *v);
  if (!v)
    return;
  ps->files = v;
  struct plug_file *pf = &v[ps->nfiles];
  memset(pf, 0, sizeof *pf);
  if (!(pf->path = dupstr(path)))
    return;
  pf->dir = dir;
  memcpy(pf->stem, st, sizeof st);
  pf->state = PF_NEW;
  ps->nfiles++;
}

/* What a *.so that is no regular file is, for its refusal. */
static const char *not_a_file(mode_t mode)
{
  if (S_ISDIR(mode))
    return "is a directory";
  if (S_ISFIFO(mode))
    return "is a FIFO, not a plugin file";
  if (S_ISSOCK(mode))
    return "is a socket, not a plugin file";
  if (S_ISCHR(mode))
    return "is a character device, not a plugin file";
  if (S_ISBLK(mode))
    return "is a block device, not a plugin file";
  return "is not a regular file";
}

/* A *.so of a plugin directory: a candidate to open when it is needed (a
 * regular file, or a symbolic link to one), or refused now with what it
 * is, so that `s42 plugins` and E-FUNC's notes say why it is not used.
 * Only stat() looks at it: a FIFO is never opened (that would wait for a
 * writer). */
static void consider(struct plug_set *ps, size_t dir, const char *path)
{
  struct stat st;
  if (stat(path, &st) == 0) {
    if (S_ISREG(st.st_mode))
      add_file(ps, dir, path);
    else
      refuse(ps, path, NULL, "%s", not_a_file(st.st_mode));
    return;
  }
  int e = errno;
  char to[PATH_MAX];
  ssize_t k;
  if (e == ELOOP)
    refuse(ps, path, NULL, "is a symbolic link that loops");
  else if (e == ENOENT && (k = readlink(path, to, sizeof to - 1)) >= 0)
    refuse(ps, path, NULL, "is a symbolic link to %.*s, which does not exist", (int)k, to);
  else if (e != ENOENT)   /* (ENOENT: removed since the directory was read) */
    refuse(ps, path, NULL, "cannot be examined: %s", strerror(e));
}

static void scan_dir(struct plug_set *ps, size_t dir)
{
  DIR *dp = opendir(ps->dirs[dir]);
  if (!dp)
    return;
  char **names = NULL;
  size_t n = 0;
  struct dirent *e;
  while ((e = readdir(dp))) {
    size_t k = strlen(e->d_name);
    if (k < 4 || strcmp(e->d_name + k - 3, ".so") != 0 || e->d_name[0] == '.')
      continue;
    char **v = realloc(names, (n + 1) * sizeof *v);
    if (!v)
      break;
    names = v;
    if ((names[n] = dupstr(e->d_name)))
      n++;
  }
  closedir(dp);
  qsort(names, n, sizeof *names, by_name);   /* the same order on every machine */
  for (size_t i = 0; i < n; i++) {
    char path[PATH_MAX];
    if ((size_t)snprintf(path, sizeof path, "%s/%s", ps->dirs[dir], names[i]) < sizeof path)
      consider(ps, dir, path);
    free(names[i]);
  }
  free(names);
}

/* Beside the executable: an installed s42 has its plugins in
 * <exe>/../lib/s42/plugins wherever it was installed or copied to (DESTDIR,
 * a moved tree), so it never depends on the prefix compiled in; the build
 * tree's ./s42 beside a Makefile has them in build/plugins, build-asan/s42
 * in build-asan/plugins. */
static void exe_dirs(struct plug_set *ps)
{
  char exe[PATH_MAX], p[PATH_MAX + 32];
  ssize_t k = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (k <= 0)
    return;
  exe[k] = 0;
  char *slash = strrchr(exe, '/');
  if (!slash)
    return;
  *slash = 0;
  struct stat st;
  char *up = strrchr(exe, '/');
  if (up) {   /* /opt/s42/bin -> /opt/s42/lib/s42/plugins; only if it is there */
    snprintf(p, sizeof p, "%.*s/lib/s42/plugins", (int)(up - exe), exe);
    if (stat(p, &st) == 0 && S_ISDIR(st.st_mode))
      add_dir(ps, p);
  }
  snprintf(p, sizeof p, "%s/Makefile", exe);
  if (access(p, R_OK) == 0) {
    snprintf(p, sizeof p, "%s/build/plugins", exe);
    add_dir(ps, p);
  }
  snprintf(p, sizeof p, "%s/../Makefile", exe);
  if (access(p, R_OK) == 0) {
    snprintf(p, sizeof p, "%s/plugins", exe);
    add_dir(ps, p);
  }
}

void plug_scan(struct plug_set *ps, const char *opt_dir)
{
  memset(ps, 0, sizeof *ps);
  add_dir(ps, opt_dir);
  const char *env = getenv("S42_PLUGIN_PATH");
  if (env) {
    char *copy = dupstr(env), *save = NULL;
    for (char *t = copy ? strtok_r(copy, ":", &save) : NULL; t; t = strtok_r(NULL, ":", &save))
      add_dir(ps, t);
    free(copy);
  }
  exe_dirs(ps);
  add_dir(ps, S42_PLUGINDIR);
  for (size_t i = 0; i < ps->ndirs; i++)
    scan_dir(ps, i);
}

void plug_free(struct plug_set *ps)
{
  /* the handlers out first: whatever replaced them meanwhile (the
   * terminal's, put back as the terminal closed) is what each fini()
   * finds, and the guard then puts its own in for that call alone */
  guard_release(ps);
  for (size_t i = ps->n; i-- > 0;) {
    struct plug *p = &ps->v[i];
    if (p->state == PLUG_READY && p->d->fini)
      plug_guarded(ps, (int)i, "fini", call_fini, &(struct call){.p = p});
    if (p->state != PLUG_CRASHED)   /* a crashed plugin's destructors are its code too: never run */
      dlclose(p->handle);
    free(p->path);
    free(p->dir);
  }
  for (size_t i = 0; i < ps->nbad; i++) {
    free(ps->bad[i].path);
    free(ps->bad[i].name);
  }
  free(ps->bad);
  for (size_t i = 0; i < ps->ndirs; i++)
    free(ps->dirs[i]);
  free(ps->dirs);
  for (size_t i = 0; i < ps->nfiles; i++) {
    while (ps->files[i].probe > 0 && waitpid(ps->files[i].probe, NULL, 0) < 0 && errno == EINTR)
      ;
    free(ps->files[i].path);
  }
  free(ps->files);
  release_thunk(ps);
  memset(ps, 0, sizeof *ps);
  guard_altstack_free();
}

/* ---- looking functions up ---- */

/* Is kind/number a function of the language that is no plugin's (G01)? */
static int core_function(char kind, int number)
{
  const struct kp_word *w = kp_word(kind, number);
  return w && !w->owner;
}

static const struct s42_function *provides(const struct plug *p, char kind, int number)
{
  for (uint32_t k = 0; k < p->d->nfunctions; k++)
    if (p->d->functions[k].kind == kind && p->d->functions[k].number == number)
      return &p->d->functions[k];
  return NULL;
}

int plug_find(const struct plug_set *cps, char kind, int number, const struct s42_function **fn)
{
  if (!cps || core_function(kind, number))
    return -1;
  /* Opening a file only fills in what the set already stands for (the
   * files it lists); the set itself is never const (plug_scan filled it). */
  struct plug_set *ps = (struct plug_set *)cps;
  const char *owner = plug_owner(kind, number, NULL);
  for (int pass = owner ? 0 : 1; pass < 2; pass++)
    for (size_t f = 0; f < ps->nfiles; f++) {
      if (pass == 0 && strcmp(ps->files[f].stem, owner) != 0)
        continue;
      open_file(ps, f);
      if (ps->files[f].state != PF_OPEN)
        continue;
      const struct s42_function *found = provides(&ps->v[ps->files[f].plug], kind, number);
      if (found) {
        if (fn)
          *fn = found;
        return ps->files[f].plug;
      }
    }
  return -1;
}

int plug_by_name(struct plug_set *ps, const char *name)
{
  if (!ps)
    return -1;
  for (int pass = 0; pass < 3; pass++)
    for (size_t f = 0; f < ps->nfiles; f++) {
      if (pass == 1 && strcmp(ps->files[f].stem, name) == 0)
        open_file(ps, f);
      else if (pass == 2)
        open_file(ps, f);
      if (ps->files[f].state == PF_OPEN && strcmp(ps->v[ps->files[f].plug].d->name, name) == 0)
        return ps->files[f].plug;
    }
  return -1;
}

void plug_why_missing(const struct plug_set *ps, char kind, int number, char *msg, size_t n)
{
  const char *what = NULL, *owner = plug_owner(kind, number, &what);
  char fn[8];
  snprintf(fn, sizeof fn, "%c%02d", kind, number);
  if (!owner) {
    snprintf(msg, n, "%s needs a plugin, and none provides it", fn);
    return;
  }
  for (size_t i = 0; ps && i < ps->nbad; i++)
    if (strcmp(ps->bad[i].name, owner) == 0) {
      snprintf(msg, n, "%s (%s) needs the %s plugin: %s %s", fn, what, owner, ps->bad[i].path, ps->bad[i].msg);
      return;
    }
  if (!ps || !ps->ndirs) {
    snprintf(msg, n, "%s (%s) needs the %s plugin, which was not found", fn, what, owner);
    return;
  }
  size_t k = (size_t)snprintf(msg, n, "%s (%s) needs the %s plugin, which was not found in ", fn, what, owner);
  for (size_t i = 0; i < ps->ndirs && k < n; i++)
    k += (size_t)snprintf(msg + k, n - k, "%s%s", i ? ":" : "", ps->dirs[i]);
  if (k < n)
    snprintf(msg + k, n - k, " (give --plugins DIR or S42_PLUGIN_PATH)");
}

/* ---- options and starting a plugin ---- */

static const char *const option_names[PLUG_NOPT] = {
  [PLUG_OPT_TOOL] = "tool", [PLUG_OPT_DUMP_IMAGES] = "dump-images", [PLUG_OPT_LANG] = "lang",
};

static int option_index(const char *name)
{
  for (int i = 0; name && i < PLUG_NOPT; i++)
    if (strcmp(option_names[i], name) == 0)
      return i;
  return -1;
}

void plug_set_option(struct plug_set *ps, const char *name, const char *value)
{
  int i = option_index(name);
  if (ps && i >= 0)
    ps->opt[i] = value;
}

const char *plug_get_option(const struct plug_set *ps, const char *name)
{
  int i = option_index(name);
  if (i < 0)
    return NULL;
  const char *v = ps ? ps->opt[i] : NULL;
  return v ? v : i == PLUG_OPT_LANG ? "uk" : NULL;
}

/* The plugin being started on this thread, and its set: init() runs here
 * and nowhere else, so what it says about itself (error(NULL, ...)) and
 * asks (option()) belongs to them. */
static _Thread_local struct plug *starting;
static _Thread_local struct plug_set *starting_set;

void plug_init_reason(const char *msg)
{
  if (starting)
    snprintf(starting->reason, sizeof starting->reason, "%s", msg ? msg : "");
}

const char *plug_option(const char *name)
{
  return plug_get_option(starting_set, name);
}

/* host->option() takes no context (ABI 1.1), and a plugin may call it from
 * any callback.  So each set whose plugins start takes one of PLUG_THUNKS
 * option functions, each answering for the set in its slot, for as long as
 * the set lives; it puts that one in the host table its plugins get.  The
 * slots are the only state the loader shares between sets: which set owns
 * which function, never a value. */
static struct plug_set *_Atomic thunk_set[PLUG_THUNKS];
#define THUNK(k) \
  static const char *option_##k(const char *name) { return plug_get_option(atomic_load(&thunk_set[k]), name); }
THUNK(0) THUNK(1) THUNK(2) THUNK(3) THUNK(4) THUNK(5) THUNK(6) THUNK(7)
THUNK(8) THUNK(9) THUNK(10) THUNK(11) THUNK(12) THUNK(13) THUNK(14) THUNK(15)
static const char *(*const thunks[PLUG_THUNKS])(const char *) = {
  option_0, option_1, option_2, option_3, option_4, option_5, option_6, option_7,
  option_8, option_9, option_10, option_11, option_12, option_13, option_14, option_15,
};

static void release_thunk(struct plug_set *ps)
{
  if (ps->thunk)
    atomic_store(&thunk_set[ps->thunk - 1], NULL);
}

/* The set's host table, made once from the caller's. */
static void set_host(struct plug_set *ps, const struct s42_host *host)
{
  if (ps->host.size)
    return;
  ps->host = *host;
  if (host->option != plug_option)
    return;   /* the caller answers option() itself */
  for (int k = 0; k < PLUG_THUNKS && !ps->thunk; k++) {
    struct plug_set *none = NULL;
    if (atomic_compare_exchange_strong(&thunk_set[k], &none, ps))
      ps->thunk = k + 1;
  }
  /* all taken: plug_option answers, exactly in init(), where plugins read
   * their options (the bundled ones do) */
  if (ps->thunk)
    ps->host.option = thunks[ps->thunk - 1];
}

int plug_use(struct plug_set *ps, int i, const struct s42_host *host)
{
  struct plug *p = &ps->v[i];
  if (p->state == PLUG_READY)
    return 0;
  if (p->state == PLUG_FAILED || p->state == PLUG_CRASHED)
    return -1;
  set_host(ps, host);
  guard_hold(ps);
  void *self = NULL;
  p->reason[0] = 0;
  struct plug *was = starting;
  struct plug_set *was_set = starting_set;
  starting = p;
  starting_set = ps;
  struct call_init c = {.d = p->d, .host = &ps->host, .dir = p->dir, .self = &self, .r = S42_FAIL};
  plug_guarded(ps, i, "init", call_init, &c);
  int r = c.r;
  starting = was;
  starting_set = was_set;
  if (p->state == PLUG_CRASHED)
    return -1;   /* err says how */
  if (r != S42_OK) {
    p->usage = r == S42_FAIL_USAGE;
    char why[sizeof p->reason];
    memcpy(why, p->reason, sizeof why);   /* another member of *p: no overlap, but say so */
    if (why[0])
      snprintf(p->err, sizeof p->err, "the %s plugin (%s) failed to start: %s", p->d->name, p->path, why);
    else
      snprintf(p->err, sizeof p->err, "the %s plugin (%s) failed to start", p->d->name, p->path);
    p->state = PLUG_FAILED;
    return -1;
  }
  p->self = self;
  p->state = PLUG_READY;
  return 0;
}

void plug_list(struct plug_set *ps, FILE *f)
{
  plug_open_all(ps);
  fprintf(f, "plugin ABI %d.%d; searched:", S42_ABI_MAJOR, S42_ABI_MINOR);
  for (size_t i = 0; i < ps->ndirs; i++)
    fprintf(f, " %s", ps->dirs[i]);
  fputc('\n', f);
  if (!ps->n && !ps->nbad)
    fputs("no plugins found\n", f);
  for (size_t j = 0; j < ps->nfiles; j++) {
    if (ps->files[j].state != PF_OPEN)
      continue;
    int i = ps->files[j].plug;
    const struct s42_plugin *d = ps->v[i].d;
    fprintf(f, "%s %s (ABI %u.%u) %s\n", d->name, d->version, (unsigned)d->abi_major, (unsigned)d->abi_minor,
            ps->v[i].path);
    if (d->summary)
      fprintf(f, "  %s\n", d->summary);
    for (uint32_t k = 0; k < d->nfunctions; k++) {
      const struct s42_function *fn = &d->functions[k];
      char note[80] = "";
      int w = core_function(fn->kind, fn->number) ? -2 : plug_find(ps, fn->kind, fn->number, NULL);
      if (w == -2)
        snprintf(note, sizeof note, "  (the language's own: not used)");
      else if (w != i && w >= 0)
        snprintf(note, sizeof note, "  (provided by the %s plugin)", ps->v[w].d->name);
      fprintf(f, "  %c%02d  %s%s\n", fn->kind, fn->number, fn->summary ? fn->summary : "", note);
    }
  }
  for (size_t i = 0; i < ps->nbad; i++)
    fprintf(f, "refused: %s %s\n", ps->bad[i].path, ps->bad[i].msg);
}

void plug_list_json(struct plug_set *ps, FILE *f, void (*str)(FILE *, const char *))
{
  plug_open_all(ps);
  fprintf(f, "{\"abi\":\"%d.%d\",\"searched\":[", S42_ABI_MAJOR, S42_ABI_MINOR);
  for (size_t i = 0; i < ps->ndirs; i++) {
    if (i)
      fputc(',', f);
    str(f, ps->dirs[i]);
  }
  fputs("],\"plugins\":[", f);
  int first = 1;
  for (size_t j = 0; j < ps->nfiles; j++) {
    if (ps->files[j].state != PF_OPEN)
      continue;
    int i = ps->files[j].plug;
    const struct s42_plugin *d = ps->v[i].d;
    fputs(first ? "{\"name\":" : ",{\"name\":", f);
    first = 0;
    str(f, d->name);
    fputs(",\"version\":", f);
    str(f, d->version);
    fprintf(f, ",\"abi\":\"%u.%u\",\"path\":", (unsigned)d->abi_major, (unsigned)d->abi_minor);
    str(f, ps->v[i].path);
    fputs(",\"summary\":", f);
    str(f, d->summary ? d->summary : "");
    fputs(",\"functions\":[", f);
    for (uint32_t k = 0; k < d->nfunctions; k++) {
      const struct s42_function *fn = &d->functions[k];
      int w = core_function(fn->kind, fn->number) ? -2 : plug_find(ps, fn->kind, fn->number, NULL);
      fprintf(f, "%s{\"function\":\"%c%02d\",\"summary\":", k ? "," : "", fn->kind, fn->number);
      str(f, fn->summary ? fn->summary : "");
      /* used: this plugin gives the function; otherwise the language or
       * another plugin does */
      fputs(",\"used\":", f);
      fputs(w == i ? "true" : "false", f);
      if (w >= 0 && w != i) {
        fputs(",\"provided_by\":", f);
        str(f, ps->v[w].d->name);
      } else if (w == -2) {
        fputs(",\"provided_by\":\"the language\"", f);
      }
      fputc('}', f);
    }
    fputs("]}", f);
  }
  fputs("],\"refused\":[", f);
  for (size_t i = 0; i < ps->nbad; i++) {
    fputs(i ? ",{\"path\":" : "{\"path\":", f);
    str(f, ps->bad[i].path);
    fputs(",\"reason\":", f);
    str(f, ps->bad[i].msg);
    fputc('}', f);
  }
  fputs("]}\n", f);
}
