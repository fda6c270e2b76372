/* Plugins (include/s42_plugin.h): finding them, opening a file only when a
 * program needs a function it may provide, reading its descriptor, and
 * starting a plugin when a program first uses it.  The compiler asks which
 * functions exist; the session calls the block phases. */
#ifndef S42_PLUGIN_LOADER_H
#define S42_PLUGIN_LOADER_H

#include "s42_plugin.h"
#include <stddef.h>
#include <stdio.h>
#include <sys/types.h>

#define PLUG_MAX 32          /* plugins a session can use (a bit mask) */

/* PLUG_CRASHED: a callback died of a signal (the crash guard, below); the
 * plugin is never called again in this process. */
enum plug_state { PLUG_FOUND, PLUG_READY, PLUG_FAILED, PLUG_CRASHED };

struct plug {
  char *path;                /* the shared object */
  char *dir;                 /* its directory */
  void *handle;
  const struct s42_plugin *d;
  int state;                 /* enum plug_state */
  void *self;
  char err[300];             /* why init failed, or how it crashed */
  char reason[240];          /* the plugin's own words for it (1.1), or "" */
  int usage;                 /* init said S42_FAIL_USAGE: the command line's fault */
};

/* A plugin file that was refused, with the reason (for `s42 plugins` and
 * for E-PLUGIN messages naming a language function's plugin). */
struct plug_refused {
  char *path;
  char *name;                /* the plugin name the file suggests */
  char msg[300];
};

/* A *.so of a plugin directory.  Scanning only lists files; one is opened
 * (probed in a child first, then dlopened) when a function it may provide
 * is asked for. */
enum plug_file_state { PF_NEW, PF_OPEN, PF_REFUSED, PF_SHADOWED };

struct plug_file {
  char *path;
  size_t dir;                /* index in plug_set.dirs */
  char stem[48];             /* "helix" of helix.so: the plugin it should be */
  int state;                 /* enum plug_file_state */
  int plug;                  /* PF_OPEN: its index in plug_set.v */
  pid_t probe;               /* the probe's child, not yet reaped, or 0 */
};

/* The options a set gives its plugins (host->option, ABI 1.1). */
enum plug_opt { PLUG_OPT_TOOL, PLUG_OPT_DUMP_IMAGES, PLUG_OPT_LANG, PLUG_NOPT };

/* Everything the loader keeps is here, none of it in globals: two sets in
 * one process (two sessions) have their own plugins, options and host
 * table.  A set does not move once a plugin of it started (its plugins
 * hold a pointer to its host table). */
struct plug_set {
  struct plug v[PLUG_MAX];   /* the plugins opened, in the order they were */
  size_t n;
  struct plug_refused *bad;
  size_t nbad;
  char **dirs;               /* the directories searched, in order */
  size_t ndirs;
  struct plug_file *files;   /* every candidate, in search order */
  size_t nfiles;
  const char *opt[PLUG_NOPT];  /* by reference (argv); NULL: not given */
  struct s42_host host;      /* what its plugins' init() get: the caller's
                                table, with option() answering for this set */
  int thunk;                 /* which option() answers for it, + 1; 0 none yet */
  int armed;                 /* a plugin of it started: the guard's handlers
                                stay in place until plug_free */
  unsigned crashes;          /* callbacks that crashed (the guard) */
  int crashed;               /* the plugin the last one was of */
};

/* List the plugin files of `opt_dir` (--plugins, may be NULL), then
 * S42_PLUGIN_PATH (':'-separated), then <exe>/../lib/s42/plugins, the build
 * tree beside the executable and the compiled-in directory.  Opens nothing.
 * Of two files whose plugins have the same name, the one found earlier
 * wins.  Never fails: a *.so that is no regular file or link to one (a
 * FIFO, a directory, a link that loops or leads nowhere) lands in ps->bad
 * now, what cannot be loaded later. */
void plug_scan(struct plug_set *ps, const char *opt_dir);
void plug_free(struct plug_set *ps);

/* The plugin implementing function kind ('G'/'M') number, or -1.  A
 * function of the language that is not a plugin's (G01, M03) is never
 * looked for.  One the language leaves to a plugin (G12) is looked for
 * first in the files named after that plugin (helix.so), then, like a
 * function the language does not have, in every file in search order; the
 * first that provides it wins.  Files are opened as the search reaches
 * them: the set is const to callers that only ask (the compiler), but it
 * remembers what it opened. */
int plug_find(const struct plug_set *ps, char kind, int number, const struct s42_function **fn);

/* The plugin called `name` (a restart state names it), opened if needed; -1. */
int plug_by_name(struct plug_set *ps, const char *name);

/* Open every file (for `s42 plugins`). */
void plug_open_all(struct plug_set *ps);

/* Why a function is unavailable: fills msg (for E-PLUGIN). */
void plug_why_missing(const struct plug_set *ps, char kind, int number, char *msg, size_t n);

/* Start plugin i (init) if it is not yet; 0, or -1 with ps->v[i].err.  Its
 * init() gets the set's copy of `host` (the first plug_use's), whose
 * option() -- when host's is plug_option -- answers with this set's
 * options for the whole run. */
int plug_use(struct plug_set *ps, int i, const struct s42_host *host);

/* The options a set gives its plugins (host->option, ABI 1.1): "tool",
 * "dump-images", "lang"; set after plug_scan, before a plugin starts.  The
 * value is kept by reference (argv); NULL unsets; other names are ignored.
 * plug_get_option answers as host->option() does: NULL when not given,
 * "lang" "uk" then. */
void plug_set_option(struct plug_set *ps, const char *name, const char *value);
const char *plug_get_option(const struct plug_set *ps, const char *name);
/* Two services of a host table (the session's) that come with no block:
 * option() -- plug_option answers with the options of the set whose plugin
 * is starting on this thread, and plug_use gives each set's plugins an
 * option() of their own instead, which answers for that set at any time
 * (for PLUG_THUNKS sets at once; a set beyond keeps plug_option: right in
 * init(), NULL -- "uk" for lang -- outside it); and error(NULL, ...) in
 * init() -- plug_init_reason keeps the reason of the plugin that is
 * starting on this thread (none: ignored) for its E-PLUGIN message. */
#define PLUG_THUNKS 16
const char *plug_option(const char *name);
void plug_init_reason(const char *msg);

/* `s42 plugins --json`: the same as one JSON object (str writes a JSON
 * string: the caller's encoder). */
void plug_list_json(struct plug_set *ps, FILE *f, void (*str)(FILE *, const char *));
/* `s42 plugins`: what was found, refused and where it looked (opens all). */
void plug_list(struct plug_set *ps, FILE *f);

/* Load a file in a child process (fork, dlopen, the descriptor checked),
 * so that a constructor that crashes, hangs or ends the process harms only
 * the child.  0 when the parent may dlopen it; -1 with why ("its
 * constructor crashed: signal 11").  The probe gives up after
 * PLUG_PROBE_SECONDS. */
#define PLUG_PROBE_SECONDS 5
int plug_probe(const char *path, char *why, size_t n);

/* ---- the crash guard ----
 * Every call into a plugin's code is made through plug_guarded(), in a
 * frame of its own: the plug_call_* below wrap each callback for the
 * session, one line a call site,
 *
 *     int r = plug_call(ps, i, "run", pl->d->run, &s->blk);
 *
 * SIGSEGV, SIGBUS, SIGFPE, SIGILL or SIGABRT raised on this thread while
 * the call runs -- a fault, or a signal the thread sent itself (abort()) --
 * comes back there: plugin i of ps is PLUG_CRASHED with its err saying so
 * ("the helix plugin crashed (SIGSEGV) in run(): it is not called again"),
 * ps->crashes counts it, ps->crashed names it, and the call's value is
 * that of a failure (S42_FAIL, 0 bytes).  A crashed plugin is never called
 * again: a plug_call_* of it fails at once, plug_use refuses it, plug_free
 * neither calls its fini nor closes it (a destructor is its code too).  A
 * crash in a host service the plugin called counts as the plugin's; a
 * signal outside the call, or on another thread, goes where it went before
 * (the default action, the terminal's handler, ASan's).  The handlers run
 * on an alternate signal stack, so a plugin that overflows the stack is
 * caught too.  What this guarantees and what it does not: README.md,
 * "Writing a plugin".
 *
 * The handlers go in when a plugin of a set first starts (plug_use) and
 * stay until plug_free, so that a call costs no system call; a call before
 * that (a file's entry function, read when a program's compile opens the
 * file) puts them in for itself alone, and then puts back what was there. */

/* call(ctx), guarded, as a call of plugin i of ps (ps NULL, i -1: of no
 * plugin yet, a file's entry function).  0 when it returned; the signal
 * when it crashed; -1 when plugin i crashed before (nothing is called). */
int plug_guarded(struct plug_set *ps, int i, const char *what, void (*call)(void *), void *ctx);

/* The callbacks, guarded: what the callback returned, or S42_FAIL (0 for
 * save and describe; advance and reset nothing) when it crashed or had. */
int plug_call(struct plug_set *ps, int i, const char *what, int (*cb)(void *, struct s42_block *),
              struct s42_block *b);   /* check, start, run, finish */
void plug_call_advance(struct plug_set *ps, int i, struct s42_block *b, double dt);
int plug_call_path(struct plug_set *ps, int i, struct s42_block *b, double t, double d[4]);
size_t plug_call_save(struct plug_set *ps, int i, void *buf, size_t cap);
int plug_call_load(struct plug_set *ps, int i, const void *buf, size_t len);
size_t plug_call_describe(struct plug_set *ps, int i, int what, char *buf, size_t cap);
void plug_call_reset(struct plug_set *ps, int i);

#endif
