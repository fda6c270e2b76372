/* Finding and loading plugins (src/plugin.h).  Every failure -- a file that
 * is not a shared object, a missing entry symbol, another ABI version, an
 * init that fails -- is caught here, reported with the file and the reason,
 * and the handle closed: a broken plugin never takes s42 down. */
#include "plugin.h"
#include <dirent.h>
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef S42_PLUGINDIR
#define S42_PLUGINDIR "/usr/local/lib/s42/plugins"
#endif

/* The functions the language names whose work lives in plugins. */
static const struct owner {
  char kind;
  int number;
  const char *plugin, *what;
} owners[] = {
  {'G', 7, "oscillation", "oscillation parameters"},
  {'M', 13, "oscillation", "oscillation on"},
  {'M', 14, "oscillation", "oscillation off"},
  {'G', 10, "toothsearch", "tooth-step search"},
  {'G', 11, "toothsearch", "tooth-step search"},
  {'M', 10, "toothsearch", "lead and helix angle"},
  {'M', 12, "toothsearch", "search speed from F"},
  {'G', 12, "helix", "helical interpolation"},
  {'G', 13, "helix", "helical interpolation"},
};

const char *plug_owner(char kind, int number, const char **what)
{
  for (size_t i = 0; i < sizeof owners / sizeof owners[0]; i++)
    if (owners[i].kind == kind && owners[i].number == number) {
      if (what)
        *what = owners[i].what;
      return owners[i].plugin;
    }
  return NULL;
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
    return "it has no usable name";
  if (!d->version)
    return "it has no version";
  if (d->nfunctions > 64 || (d->nfunctions && !d->functions))
    return "its function table is malformed";
  if (!d->init)
    return "it has no init callback";
  for (uint32_t i = 0; i < d->nfunctions; i++) {
    const struct s42_function *f = &d->functions[i];
    if (f->size < sizeof(struct s42_function) || (f->kind != 'G' && f->kind != 'M') || f->number < 0 ||
        f->number > (f->kind == 'G' ? 63 : 31) || (f->kind == 'G' && (f->group < 1 || f->group > 4)))
      return "its function table is malformed";
  }
  return NULL;
}

static void load_one(struct plug_set *ps, const char *dir, const char *path)
{
  char ver[96];
  dlerror();
  void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char *e = dlerror();
    refuse(ps, path, NULL, "cannot be loaded: %s", e ? e : "unknown reason");
    return;
  }
  s42_plugin_entry_fn entry;
  void *sym = dlsym(h, S42_PLUGIN_ENTRY_NAME);
  memcpy(&entry, &sym, sizeof entry);
  if (!sym) {
    refuse(ps, path, NULL, "has no entry symbol %s()", S42_PLUGIN_ENTRY_NAME);
    dlclose(h);
    return;
  }
  const struct s42_plugin *d = entry();
  /* the version, before anything else of the descriptor is trusted */
  if (!d || d->size < offsetof(struct s42_plugin, name) + sizeof d->name ||
      d->fingerprint != S42_ABI_FINGERPRINT) {
    refuse(ps, path, NULL, "is not an s42 plugin (no descriptor or a wrong fingerprint)");
    dlclose(h);
    return;
  }
  if (d->abi_major != S42_ABI_MAJOR || d->abi_minor > S42_ABI_MINOR) {
    char mine[32];
    snprintf(ver, sizeof ver, "%u.%u", (unsigned)d->abi_major, (unsigned)d->abi_minor);
    snprintf(mine, sizeof mine, "%d.%d", S42_ABI_MAJOR, S42_ABI_MINOR);
    refuse(ps, path, NULL, "was built for plugin ABI %s; this s42 has ABI %s", ver, mine);
    dlclose(h);
    return;
  }
  const char *why = d->size < sizeof *d ? "its descriptor is shorter than ABI 1.0's" : bad_descriptor(d);
  if (why) {
    refuse(ps, path, NULL, "%s", why);
    dlclose(h);
    return;
  }
  if (has_name(ps, d->name)) {   /* an earlier directory wins */
    dlclose(h);
    return;
  }
  if (ps->n == PLUG_MAX) {
    refuse(ps, path, d->name, "is one plugin too many (at most %d)", PLUG_MAX);
    dlclose(h);
    return;
  }
  struct plug *p = &ps->v[ps->n];
  memset(p, 0, sizeof *p);
  p->path = dupstr(path);
  p->dir = dupstr(dir);
  if (!p->path || !p->dir) {
    free(p->path);
    free(p->dir);
    dlclose(h);
    return;
  }
  p->handle = h;
  p->d = d;
  p->state = PLUG_FOUND;
  ps->n++;
}

static int by_name(const void *a, const void *b)
{
  return strcmp(*(char *const *)a, *(char *const *)b);
}

static void scan_dir(struct plug_set *ps, const char *dir)
{
  DIR *dp = opendir(dir);
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
    struct stat st;
    if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, names[i]) < sizeof path && stat(path, &st) == 0 &&
        S_ISREG(st.st_mode))
      load_one(ps, dir, path);
    free(names[i]);
  }
  free(names);
}

/* The build tree: ./s42 beside a Makefile has its plugins in build/plugins;
 * build-asan/s42 in build-asan/plugins. */
static void build_dirs(struct plug_set *ps)
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
  build_dirs(ps);
  add_dir(ps, S42_PLUGINDIR);
  for (size_t i = 0; i < ps->ndirs; i++)
    scan_dir(ps, ps->dirs[i]);
}

void plug_free(struct plug_set *ps)
{
  for (size_t i = ps->n; i-- > 0;) {
    struct plug *p = &ps->v[i];
    if (p->state == PLUG_READY && p->d->fini)
      p->d->fini(p->self);
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
  memset(ps, 0, sizeof *ps);
}

int plug_find(const struct plug_set *ps, char kind, int number, const struct s42_function **fn)
{
  if (!ps)
    return -1;
  for (size_t i = 0; i < ps->n; i++) {
    const struct s42_plugin *d = ps->v[i].d;
    for (uint32_t k = 0; k < d->nfunctions; k++)
      if (d->functions[k].kind == kind && d->functions[k].number == number) {
        if (fn)
          *fn = &d->functions[k];
        return (int)i;
      }
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

/* The options plugins may ask for, by name. */
static struct {
  const char *name, *value;
} options[] = {{"tool", NULL}, {"dump-images", NULL}, {"lang", NULL}};

void plug_set_option(const char *name, const char *value)
{
  for (size_t i = 0; i < sizeof options / sizeof options[0]; i++)
    if (strcmp(options[i].name, name) == 0)
      options[i].value = value;
}

const char *plug_option(const char *name)
{
  if (!name)
    return NULL;
  for (size_t i = 0; i < sizeof options / sizeof options[0]; i++)
    if (strcmp(options[i].name, name) == 0)
      return options[i].value ? options[i].value : strcmp(name, "lang") == 0 ? "uk" : NULL;
  return NULL;
}

/* What the plugin being started said about its failure. */
static char init_reason[240];

void plug_init_reason(const char *msg)
{
  snprintf(init_reason, sizeof init_reason, "%s", msg ? msg : "");
}

int plug_use(struct plug_set *ps, int i, const struct s42_host *host)
{
  struct plug *p = &ps->v[i];
  if (p->state == PLUG_READY)
    return 0;
  if (p->state == PLUG_FAILED)
    return -1;
  void *self = NULL;
  init_reason[0] = 0;
  int r = p->d->init(host, p->dir, &self);
  if (r != S42_OK) {
    snprintf(p->reason, sizeof p->reason, "%s", init_reason);
    p->usage = r == S42_FAIL_USAGE;
    if (init_reason[0])
      snprintf(p->err, sizeof p->err, "the %s plugin (%s) failed to start: %s", p->d->name, p->path, init_reason);
    else
      snprintf(p->err, sizeof p->err, "the %s plugin (%s) failed to start", p->d->name, p->path);
    p->state = PLUG_FAILED;
    return -1;
  }
  p->self = self;
  p->state = PLUG_READY;
  return 0;
}

void plug_list(const struct plug_set *ps, FILE *f)
{
  fprintf(f, "plugin ABI %d.%d; searched:", S42_ABI_MAJOR, S42_ABI_MINOR);
  for (size_t i = 0; i < ps->ndirs; i++)
    fprintf(f, " %s", ps->dirs[i]);
  fputc('\n', f);
  if (!ps->n && !ps->nbad)
    fputs("no plugins found\n", f);
  for (size_t i = 0; i < ps->n; i++) {
    const struct s42_plugin *d = ps->v[i].d;
    fprintf(f, "%s %s (ABI %u.%u) %s\n", d->name, d->version, (unsigned)d->abi_major, (unsigned)d->abi_minor,
            ps->v[i].path);
    if (d->summary)
      fprintf(f, "  %s\n", d->summary);
    for (uint32_t k = 0; k < d->nfunctions; k++) {
      const struct s42_function *fn = &d->functions[k];
      int shadow = plug_find(ps, fn->kind, fn->number, NULL);
      fprintf(f, "  %c%02d  %s%s\n", fn->kind, fn->number, fn->summary ? fn->summary : "",
              shadow != (int)i ? "  (provided by an earlier plugin)" : "");
    }
  }
  for (size_t i = 0; i < ps->nbad; i++)
    fprintf(f, "refused: %s %s\n", ps->bad[i].path, ps->bad[i].msg);
}
