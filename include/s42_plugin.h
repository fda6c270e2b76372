/* s42_plugin.h -- the s42 plugin ABI, version 1.1.  This header is the whole
 * of what a plugin author needs: a plugin includes nothing else of s42.
 *
 * A plugin is a shared object that exports one function,
 *
 *     const struct s42_plugin *s42_plugin_entry(void);
 *
 * returning a constant descriptor: the ABI it was built for, its name and
 * version, the G and M functions it implements and its callbacks.  s42
 * opens a plugin file only when a program uses a function it may provide
 * (one the language leaves to a plugin is looked for first in the file
 * named after that plugin, helix.so for G12), loads it first in a child
 * process -- so a constructor that crashes or exits is reported, not
 * suffered -- then with dlopen(RTLD_NOW | RTLD_LOCAL), checks abi_major,
 * abi_minor and the fingerprint before it calls anything else, and refuses
 * a plugin built for another major version (or a newer minor one) with a
 * message naming both versions.  A constructor therefore runs twice and
 * must have no lasting effect.  Reading the descriptor costs nothing:
 * init() runs only when a program uses one of the plugin's functions, so a
 * plugin with heavy dependencies keeps them in a second library that
 * init() dlopens (see plugins/toothsearch/ in the s42 sources).
 *
 * Host services arrive as a function table (struct s42_host) in init(); the
 * plugin never links against the s42 executable.  Every struct here carries
 * its own size as its first member and grows only by appending members, so
 * a plugin built against an older 1.x header keeps working: the host reads
 * only the members the plugin's `size` covers, and a plugin must check
 * host->size before it calls a host service added after 1.0.  The loader
 * refuses a plugin built for a newer minor version than the host's, so a
 * 1.1 plugin always meets a 1.1 host or a newer one.
 *
 * What 1.1 added (each marked "1.1" below): the run() status
 * S42_WAIT_SECTION, the init() status S42_FAIL_USAGE and error(NULL, ...)
 * as init()'s reason, the machine's own texts (S42_MSG_*), and the host
 * services option(), text(), message() and results() (struct s42_results,
 * display format P5).  A 1.0 plugin never sees any of it.
 *
 * Units are those of the 2С42: lengths in discretes (1 µm; A in 0.001°),
 * speeds in mm/min (deg/min for A), time in seconds.
 *
 * Errors never unwind across the boundary: a callback that fails calls
 * host->error() with an error code of the language ("E-ARC", "E-OSC", ...)
 * and returns S42_FAIL; the block then has not run and the cycle stops with
 * that error.  A plugin written in C++ catches every exception at its edge.
 * A callback that crashes instead (SIGSEGV, SIGBUS, SIGFPE, SIGILL or
 * SIGABRT on s42's thread while it runs) fails the block with E-PLUGIN,
 * and s42 never calls that plugin again; this is a best effort, not
 * isolation: what the plugin broke before it crashed stays broken (the
 * s42 README, "Writing a plugin", says what is guaranteed).
 *
 * A plugin may add G functions 0..63 and M functions 0..31 that the language
 * does not have, or implement those the language leaves to plugins (G07
 * G10-G13, M10 M12-M14); the language's other functions stay its own (a
 * plugin's G01 is never called).  The first plugin found for a function
 * wins; for one the language leaves to a plugin, the files named after
 * that plugin (oscillation.so, toothsearch.so, helix.so) come first.
 *
 * One instance per plugin set: init() runs once, reset() starts every run,
 * fini() ends it.  s42 has one set, so one instance per process; a program
 * that embeds two s42 sessions with a set each (two --tool values) starts
 * a plugin once in each set, in the same shared object.  So keep what a
 * run needs in *self, not in statics the two would share; a static host
 * pointer is fine for the services that take a block, but option()
 * answers for the set whose table it is: read options in init(), or
 * through the table init() got.
 *
 * A minimal plugin is docs/plugin-example/hello.c in the s42 sources:
 * descriptor, init and run, built with `cc -shared -fPIC -o hello.so
 * hello.c`, no other header and no library of s42.
 */
#ifndef S42_PLUGIN_H
#define S42_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define S42_ABI_MAJOR 1
#define S42_ABI_MINOR 1
/* "s42-abi\1": guards against a stray symbol of the same name */
#define S42_ABI_FINGERPRINT 0x7334322d61626901ull
#define S42_PLUGIN_ENTRY_NAME "s42_plugin_entry"

#if defined(__GNUC__)
#define S42_EXPORT __attribute__((visibility("default")))
#else
#define S42_EXPORT
#endif
#ifdef __cplusplus
#define S42_EXTERN_C extern "C"
#else
#define S42_EXTERN_C
#endif

/* What callbacks return. */
enum s42_status {
  S42_OK = 0,
  S42_FAIL = -1,       /* after host->error(); the block has not run */
  S42_WAIT_PUSK = 1,   /* run(): wait for Пуск, then run() is called again */
  S42_WAIT_PS = 2,     /* run(): wait for ПС, then run() is called again */
  /* 1.1: run(): wait for Пуск while the operator brings the tool to the
   * next section of a tooth-step search -- table (X) and spindle (A)
   * moves that count in the position (the operator script's `section`;
   * jogs in the terminal); then run() is called again.  A plain
   * S42_WAIT_PUSK accepts jogs but not section moves. */
  S42_WAIT_SECTION = 3,
  /* 1.1: init(): the plugin cannot start because of what the user gave it
   * on the command line (a missing --tool, a malformed file): s42 reports
   * the reason (error(NULL, ...)) and stops before the run with exit
   * status 2, bad usage.  Any other failure of init() is S42_FAIL. */
  S42_FAIL_USAGE = -2
};

/* 1.1: the machine's own texts, for text(): the directives and messages of
 * a tooth-step search (language.md section 15), in the language the
 * operator chose (--lang).  Numbers are never reused. */
enum s42_msg {
  S42_MSG_PROBE_SECTION1 = 1,   /* "упор в перетин 1": probe into section 1, Пуск */
  S42_MSG_SEARCH_SECTION1 = 2,  /* "пошук в перетині 1": the search runs there */
  S42_MSG_PROBE_SECTION2 = 3,   /* "упорку в переріз 2": move to section 2, Пуск */
  S42_MSG_SEARCH_SECTION2 = 4,  /* "пошук в перетині 2" */
  S42_MSG_RETRACT_PROBE = 5,    /* "відвести упорку": retract, ПС, then Пуск */
  S42_MSG_HAND_LEFT = 6,        /* measured a left-hand helix, G10 said right */
  S42_MSG_HAND_RIGHT = 7        /* measured a right-hand helix, G11 said left */
};

/* 1.1: results of a tooth-step search for results(): the host shows them
 * in display format P5 (service line РЕЗУЛЬТАТИ, tooth count, lead, angle,
 * the circular steps eight at a time, + and - page through them).  It
 * copies what it needs; the plugin's memory is not kept.  Setting TK, UG,
 * the arrays and R99 is the plugin's business (set_param, load_array). */
struct s42_results {
  uint32_t size;          /* sizeof(struct s42_results) */
  int teeth;              /* 1..150 */
  const double *steps;    /* teeth circular steps, 0.001 degree, in the order
                             the probe met the teeth */
  int lead;               /* 1: tk, ug and hand were measured (M10) */
  double tk;              /* lead, µm (0: straight flutes) */
  double ug;              /* helix angle, 0.001 degree */
  int hand;               /* the measured hand: 1 right, -1 left, 0 straight */
};

enum s42_axis { S42_X, S42_Y, S42_Z, S42_A };

/* Parameter numbers for param()/set_param() beyond R0..R113. */
enum s42_param { S42_D1 = 114, S42_TK = 115, S42_UG = 116, S42_F = 117 };

/* Service-line modes for mode(). */
enum s42_mode { S42_MODE_AUTO, S42_MODE_MANUAL, S42_MODE_RESULTS };

/* struct s42_function.flags */
enum {
  S42_FN_SEPARATE = 1,  /* stands in a separate block (language.md sec. 8) */
  S42_FN_PLANE = 2,     /* needs G17, G18 or G19 in the block */
  S42_FN_MOTION = 4     /* moves the axes: run() calls host->move() */
};

/* One G or M function the plugin implements. */
struct s42_function {
  uint32_t size;          /* sizeof(struct s42_function) */
  char kind;              /* 'G' or 'M' */
  int number;             /* 0..99 */
  int group;              /* G: its group, 1..4 (language.md sec. 8); M: 0 */
  const char *operands;   /* letters of the words the block may carry with
                             it besides functions, jumps and parameters
                             ("XYZAIJKF"); NULL: any */
  uint32_t flags;         /* S42_FN_* */
  const char *summary;    /* one line for `s42 plugins` */
};

/* The block being run, as the host sees it: opaque to plugins. */
struct s42_block;

/* A contour move for host->move(): the host applies F, the feed override,
 * the 6000 clamp and the limit, advances simulated time by length / speed,
 * and adds the increments to the position. */
struct s42_move {
  uint32_t size;          /* sizeof(struct s42_move) */
  double d[4];            /* increments of X Y Z A, discretes */
  double length;          /* path length, mm (for A alone: degrees) */
  double limit;           /* the highest contour speed at which no axis
                             exceeds its own speed on this path, mm/min */
};

/* Services of the host.  Calls that take a block are valid only during the
 * callback that received it. */
struct s42_host {
  uint32_t size;
  uint16_t abi_major, abi_minor;

  /* the block */
  int (*number)(struct s42_block *b);            /* its number, -1 none */
  int (*has_g)(struct s42_block *b, int g);
  int (*has_m)(struct s42_block *b, int m);
  int (*plane)(struct s42_block *b);             /* 0, 17, 18 or 19 */
  /* Words of the block, by letter: X Y Z A I J K (discretes) and F (the
   * block's own F: for G07 the oscillation speed, with M12 the search
   * speed; otherwise the contour speed it sets).  has_word is 0 for a word
   * the block does not have; word() then returns 0. */
  int (*has_word)(struct s42_block *b, char letter);
  double (*word)(struct s42_block *b, char letter);
  /* run() of a block that waited: 0 on the first call, then 1, 2, ... */
  int (*resumed)(struct s42_block *b);

  /* parameters (R0..R113, S42_D1, S42_TK, S42_UG, S42_F) and arrays.
   * What set_param and load_array write belongs to the block: a block that
   * fails (any callback returns S42_FAIL, in any phase) leaves every
   * parameter and both arrays as they were after the previous block, as
   * the language's own words do (language.md sec. 7). */
  double (*param)(struct s42_block *b, int n);
  int (*set_param)(struct s42_block *b, int n, double v);   /* 0, -1 out of range */
  /* Load array 1 or 2 with n <= 15 values from the start (the rest 0),
   * pointer at the start.  0, or -1 for a bad array or n, or a value
   * outside -9999999..9999999 (nothing is written). */
  int (*load_array)(struct s42_block *b, int array, const double *v, int n);

  /* the machine */
  int64_t (*position)(struct s42_block *b, int axis);
  double (*time)(struct s42_block *b);
  double (*axis_speed)(int axis);                /* the axis's maximum, mm/min */
  /* Does this block's contour move `axis`: a non-zero increment, or an arc
   * (or helix) in a plane that holds the axis, whatever its end point? */
  int (*moves_axis)(struct s42_block *b, int axis);
  int (*move)(struct s42_block *b, const struct s42_move *m);
  /* Move an axis outside the contour (oscillation): counts in the position,
   * takes no time of its own; the host records it for plots. */
  void (*displace)(struct s42_block *b, int axis, int64_t d);
  /* Let simulated time pass (a search's revolution, a return stroke). */
  void (*dwell)(struct s42_block *b, double seconds);

  /* reports: error() before returning S42_FAIL; code is "E-OSC" etc.
   * (1.1: in init(), with b NULL, error() gives the reason init fails) */
  void (*error)(struct s42_block *b, const char *code, const char *fmt, ...)
#if defined(__GNUC__)
      __attribute__((format(printf, 3, 4)))
#endif
      ;
  void (*warn)(struct s42_block *b, const char *fmt, ...)
#if defined(__GNUC__)
      __attribute__((format(printf, 2, 3)))
#endif
      ;
  void (*log)(struct s42_block *b, const char *fmt, ...)
#if defined(__GNUC__)
      __attribute__((format(printf, 2, 3)))
#endif
      ;
  void *(*alloc)(size_t n);                      /* NULL when out of memory */
  void (*free)(void *p);

  /* the operator's display */
  void (*directive)(struct s42_block *b, const char *text);  /* NULL erases */
  void (*mode)(struct s42_block *b, int mode);               /* S42_MODE_* */

  /* ---- 1.1 (check host->size before use; see the top of this file) ---- */

  /* The value of a command-line option meant for plugins, or NULL when it
   * was not given; valid for the whole run, callable from init() on, and
   * the options of the plugin set whose init() received this table.
   * Names: "tool" (--tool FILE, the tool model of a tooth-step search),
   * "dump-images" (--dump-images DIR: write the images a search took
   * there), "lang" ("uk" or "en", never NULL). */
  const char *(*option)(const char *name);
  /* The machine's own text S42_MSG_* in the operator's language (UTF-8,
   * at most 32 characters), or NULL for an unknown number.  Show it with
   * directive() or message(). */
  const char *(*text)(struct s42_block *b, int msg);
  /* A message on the directive line (line 16) that hides the directive
   * until the operator's next key, as the machine's own messages do. */
  void (*message)(struct s42_block *b, const char *text);
  /* Show search results in display format P5 and the service line
   * РЕЗУЛЬТАТИ; the work area keeps them until a dialog (G27, G33) or a
   * G29 display takes it.  Returns 0, or -1 for results it cannot show. */
  int (*results)(struct s42_block *b, const struct s42_results *r);
};

/* The descriptor.  Callbacks other than init may be NULL. */
struct s42_plugin {
  uint32_t size;              /* sizeof(struct s42_plugin) as built */
  uint16_t abi_major, abi_minor;
  uint64_t fingerprint;       /* S42_ABI_FINGERPRINT */
  const char *name, *version, *summary;
  const struct s42_function *functions;
  uint32_t nfunctions;
  uint32_t flags;             /* S42_PL_* */

  /* Called once, when a program first needs the plugin (s42 run starts the
   * plugins a program uses before its first block); dir is the directory
   * the plugin was loaded from.  Returns S42_OK, or S42_FAIL (then nothing
   * else is called, fini neither) -- 1.1: or S42_FAIL_USAGE.  1.1: before
   * failing, host->error(NULL, code, fmt, ...) says why (code may be NULL);
   * the reason reaches the user in the E-PLUGIN message or, for
   * S42_FAIL_USAGE, on its own before the run. */
  int (*init)(const struct s42_host *host, const char *dir, void **self);
  void (*fini)(void *self);

  /* The phases of one block (language.md sec. 7), called for a block that
   * uses one of the plugin's functions -- or for every block while the
   * program uses the plugin, with S42_PL_EVERY_BLOCK:
   *   check   before anything changes: raise errors here
   *   start   modal changes (M13)
   *   run     the block's own function (motion, search); may wait
   *   finish  after the motion (M14) */
  int (*check)(void *self, struct s42_block *b);
  int (*start)(void *self, struct s42_block *b);
  int (*run)(void *self, struct s42_block *b);
  int (*finish)(void *self, struct s42_block *b);
  /* Simulated time passes by dt seconds (during moves, dwells, run-down). */
  void (*advance)(void *self, struct s42_block *b, double dt);
  /* The point at fraction t (0..1) of the path of a block whose run()
   * moves, as increments from its start; the host uses it for teach-in
   * (M19: t proportional to the path length) and to draw curves. */
  int (*path)(void *self, struct s42_block *b, double t, double d[4]);
  /* The restart state (M15): save returns the bytes needed (and writes
   * them when they fit in cap); load takes them back. */
  size_t (*save)(void *self, void *buf, size_t cap);
  int (*load)(void *self, const void *buf, size_t len);
  /* A JSON value for the trace row (what = S42_DESCRIBE_TRACE) or the dump
   * (S42_DESCRIBE_DUMP) under the key trace_key; returns its length, 0 to
   * leave the key out. */
  size_t (*describe)(void *self, int what, char *buf, size_t cap);
  const char *trace_key;
  /* A new run starts (after init, and before a restart's load). */
  void (*reset)(void *self);
};

enum { S42_PL_EVERY_BLOCK = 1 };
enum { S42_DESCRIBE_TRACE = 1, S42_DESCRIBE_DUMP = 2 };

typedef const struct s42_plugin *(*s42_plugin_entry_fn)(void);

/* ---- declaring a plugin (as SQLite's sqlite3ext.h, Redis modules) ----
 *
 * These fill in what every plugin repeats -- the sizes, the ABI version
 * and fingerprint, the function count, the entry function -- so that a
 * plugin writes only what is its own.  What they build is the descriptor
 * above, byte for byte as a plugin filling it by hand gets (a plugin may
 * still do that: one that declares an older minor version must).
 *
 *   static const struct s42_function functions[] = {
 *     S42_G_FUNCTION(12, 1, "XYZAIJKF", S42_FN_PLANE | S42_FN_MOTION, "helix, clockwise"),
 *     S42_M_FUNCTION(30, NULL, 0, "count in R1"),
 *   };
 *
 *   static int init(const struct s42_host *h, const char *dir, void **self)
 *   {
 *     S42_PLUGIN_INIT(h, host);   (host: the plugin's const struct s42_host *)
 *     ...
 *   }
 *
 *   S42_PLUGIN_DECLARE("helix", "1.0", "helical interpolation (G12 G13)", functions,
 *                      .init = init, .check = check, .run = run, .path = path);
 *
 * S42_G_FUNCTION(number, group, operands, flags, summary) and
 * S42_M_FUNCTION(number, operands, flags, summary): one struct
 * s42_function each (an M has group 0).
 *
 * S42_PLUGIN_DECLARE(name, version, summary, functions, ...): the
 * descriptor, for this header's ABI, with `functions` (an array, counted
 * with sizeof) and the members that follow as designated initializers --
 * the callbacks, .init among them, .flags, .trace_key -- and the exported
 * s42_plugin_entry() returning it.  Once per plugin, at file scope, after
 * the callbacks.  (C++20: name the members in their order here.)
 *
 * S42_PLUGIN_INIT(h, var): the first statement of init(): returns S42_FAIL
 * when h is the table of another major version or shorter than this
 * header's -- the loader never lets that happen, but it is the rule for a
 * plugin before it calls the services of its version -- and keeps h in var. */
#define S42_G_FUNCTION(number, group, operands, flags, summary) \
  {sizeof(struct s42_function), 'G', (number), (group), (operands), (flags), (summary)}
#define S42_M_FUNCTION(number, operands, flags, summary) \
  {sizeof(struct s42_function), 'M', (number), 0, (operands), (flags), (summary)}

#define S42_PLUGIN_DECLARE(name_, version_, summary_, functions_, ...)                                  \
  static const struct s42_plugin s42_plugin_descriptor = {                                             \
    .size = sizeof(struct s42_plugin), .abi_major = S42_ABI_MAJOR, .abi_minor = S42_ABI_MINOR,         \
    .fingerprint = S42_ABI_FINGERPRINT, .name = (name_), .version = (version_), .summary = (summary_), \
    .functions = (functions_), .nfunctions = (uint32_t)(sizeof(functions_) / sizeof((functions_)[0])), \
    __VA_ARGS__};                                                                                      \
  S42_EXTERN_C S42_EXPORT const struct s42_plugin *s42_plugin_entry(void);                             \
  S42_EXTERN_C S42_EXPORT const struct s42_plugin *s42_plugin_entry(void) { return &s42_plugin_descriptor; }

#define S42_PLUGIN_INIT(h, var)                                                       \
  do {                                                                                \
    if ((h)->abi_major != S42_ABI_MAJOR || (h)->size < sizeof(struct s42_host))       \
      return S42_FAIL;                                                                \
    (var) = (h);                                                                      \
  } while (0)

#ifdef __cplusplus
}
#endif

#endif
