/* Plugins (include/s42_plugin.h): finding them, reading their descriptors,
 * and starting them when a program first needs one.  The compiler asks
 * which functions exist; the session calls the block phases. */
#ifndef S42_PLUGIN_LOADER_H
#define S42_PLUGIN_LOADER_H

#include "s42_plugin.h"
#include <stddef.h>
#include <stdio.h>

#define PLUG_MAX 32          /* plugins a session can use (a bit mask) */

enum plug_state { PLUG_FOUND, PLUG_READY, PLUG_FAILED };

struct plug {
  char *path;                /* the shared object */
  char *dir;                 /* its directory */
  void *handle;
  const struct s42_plugin *d;
  int state;                 /* enum plug_state */
  void *self;
  char err[300];             /* why init failed */
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

struct plug_set {
  struct plug v[PLUG_MAX];
  size_t n;
  struct plug_refused *bad;
  size_t nbad;
  char **dirs;               /* the directories searched, in order */
  size_t ndirs;
};

/* Search `opt_dir` (--plugins, may be NULL), S42_PLUGIN_PATH (':'-separated),
 * the build tree beside the executable and the installed directory.  A
 * plugin found earlier shadows a later one of the same name.  Never fails:
 * what cannot be loaded lands in ps->bad. */
void plug_scan(struct plug_set *ps, const char *opt_dir);
void plug_free(struct plug_set *ps);

/* The plugin implementing function kind ('G'/'M') number, or -1. */
int plug_find(const struct plug_set *ps, char kind, int number, const struct s42_function **fn);

/* The plugin a language function belongs to ("helix" for G12), or NULL
 * when the language leaves it to the core. */
const char *plug_owner(char kind, int number, const char **what);

/* Why a function is unavailable: fills msg (for E-PLUGIN). */
void plug_why_missing(const struct plug_set *ps, char kind, int number, char *msg, size_t n);

/* Start plugin i (init) if it is not yet; 0, or -1 with ps->v[i].err. */
int plug_use(struct plug_set *ps, int i, const struct s42_host *host);

/* Options given to plugins (host->option, ABI 1.1): "tool", "dump-images",
 * "lang".  The value is kept by reference (argv); NULL unsets. */
void plug_set_option(const char *name, const char *value);
const char *plug_option(const char *name);
/* The reason init() gives with host->error(NULL, ...), for plug_use. */
void plug_init_reason(const char *msg);

/* `s42 plugins`: what was found, refused and where it looked. */
void plug_list(const struct plug_set *ps, FILE *f);

#endif
