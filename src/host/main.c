/* s42: the command line (contracts.md section 1) and the headless runner. */
#include "atomic.h"
#include "compile.h"
#include "disasm.h"
#include "errors.h"
#include "machfile.h"
#include "canon.h"
#include "cycle.h"
#include "dialect.h"
#include "error.h"
#include "modbus.h"
#include "nearest.h"
#include "operator.h"
#include "run.h"
#include "mrun.h"
#include "pace.h"
#include "plot.h"
#include "plugin.h"
#include "kpreport.h"
#include "session.h"
#include "state.h"
#include "tui.h"
#include "tui_modbus.h"
#include "curses_dl.h"
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#ifndef S42_VERSION
#define S42_VERSION "0.1.0"
#endif

enum { EXIT_END = 0, EXIT_PROGRAM = 1, EXIT_USAGE = 2, EXIT_STOPPED = 3, EXIT_IO = 4 };


/* Every option, the commands that take it and its line of help: the
 * per-command help (`s42 run --help`) and "did you mean" come from here. */
enum { C_RUN = 1, C_TUI = 2, C_PLOT = 4, C_CHECK = 8, C_DISASM = 16, C_PLUGINS = 32, C_DIALECTS = 64 };
static const struct optinfo {
  const char *name, *arg;
  unsigned cmds;
  const char *help;
} optinfo[] = {
  {"--operator", "FILE", C_RUN | C_PLOT, "operator actions for a headless run"},
  {"--tool", "FILE", C_RUN | C_TUI | C_PLOT, "tool model for tooth-step search (G10/G11)"},
  {"--tools", "FILE", C_RUN | C_TUI | C_PLOT, "a lathe's tool table: each tool's X and Z corrections (2У22; --tool too)"},
  {"--dump-images", "DIR", C_RUN | C_TUI | C_PLOT, "write the probe images of each search there, plain and annotated"},
  {"--trace", NULL, C_RUN | C_PLOT, "one line per executed block on stdout"},
  {"--trace=json", NULL, C_RUN | C_PLOT, "the same as JSON Lines (--trace=text: as --trace)"},
  {"--trace=canon", NULL, C_RUN, "each call on the machine, as LinuxCNC's canonical calls (rs274 -g)"},
  {"--dump", NULL, C_RUN | C_PLOT, "the final machine state as one JSON object on stdout"},
  {"--screen", NULL, C_RUN | C_PLOT, "the final 16x32 screen on stdout"},
  {"--state", "FILE", C_RUN | C_TUI | C_PLOT, "where the M15 restart state is kept (default PROGRAM.kp.state)"},
  {"--restart", NULL, C_RUN | C_TUI | C_PLOT, "start from the saved M15 restart point"},
  {"--max-blocks", "N", C_RUN | C_TUI | C_PLOT, "stop with E-LIMIT after N executed blocks (default 100000000)"},
  {"--modbus", "[=HOST:PORT]", C_RUN | C_TUI, "serve the machine over Modbus TCP (default 127.0.0.1:1502)"},
  {"--modbus-allow", "ADDR[/BITS],...", C_RUN | C_TUI, "serve only these clients (IPv4 or IPv6)"},
  {"--modbus-read-only", NULL, C_RUN | C_TUI, "refuse every write (exception 01): clients only watch"},
  {"--modbus-max-clients", "N", C_RUN | C_TUI, "connections at once (default 8; N-1 from one address)"},
  {"--modbus-idle", "SECONDS", C_RUN | C_TUI, "close a connection silent that long (default 60; 0 never)"},
  {"--machine", "FILE", C_RUN | C_TUI | C_PLOT, "the machine as installed: each axis's travel (README: Travel limits)"},
  {"--realtime", NULL, C_RUN | C_PLOT, "pace the run at machine speed (Ctrl-C stops it with the dump)"},
  {"--lang", "uk|en", C_RUN | C_TUI | C_PLOT, "language of machine messages (default uk)"},
  {"-o", "FILE", C_PLOT, "the picture to write: .png, .svg or .pdf"},
  {"--stock", "DxL", C_PLOT, "a lathe's bar: diameter x length in mm, its face at Z 0 (2У22)"},
  {"--json", NULL, C_CHECK | C_PLUGINS, "the output as JSON (check: one object a diagnostic, a line)"},
  {"--plugins", "DIR", C_RUN | C_TUI | C_PLOT | C_CHECK | C_DISASM | C_PLUGINS,
   "where plugins are looked for first (also S42_PLUGIN_PATH)"},
};

static const struct cmdinfo {
  const char *name, *args, *what;
  unsigned bit;
} cmdinfo[] = {
  {"run", "PROGRAM.kp [options]", "run headless: the batch emulator", C_RUN},
  {"tui", "[PROGRAM.kp] [options]", "the 2С42-65 panel in the terminal", C_TUI},
  {"check", "[--json] PROGRAM.kp...", "compile only, print diagnostics", C_CHECK},
  {"disasm", "PROGRAM.kp", "print the bytecode, block by block", C_DISASM},
  {"plot", "PROGRAM.kp -o FILE [options]", "run headless and draw the tool path (.png .svg .pdf)", C_PLOT},
  {"plugins", "[--json]", "list the plugins found and their functions", C_PLUGINS},
  {"dialects", "", "list the controllers' languages s42 reads, their files and machines", C_DIALECTS},
};

/* An option that is not one: say so, with the nearest one the command takes. */
static void unknown_option(const char *a, unsigned cmd)
{
  const char *names[sizeof optinfo / sizeof optinfo[0]];
  size_t n = 0;
  char word[64];
  snprintf(word, sizeof word, "%.*s", (int)strcspn(a, "="), a);   /* --modbuss=... as --modbuss */
  for (size_t i = 0; i < sizeof optinfo / sizeof optinfo[0]; i++)
    if (optinfo[i].cmds & cmd)
      names[n++] = optinfo[i].name;
  const char *m = nearest_word(word, names, n);
  if (m)
    fprintf(stderr, "s42: unknown option '%s': did you mean %s? (see s42 %s --help)\n", a, m,
            cmd == C_TUI ? "tui" : cmd == C_PLOT ? "plot" : "run");
  else
    fprintf(stderr, "s42: unknown option '%s' (see s42 %s --help)\n", a,
            cmd == C_TUI ? "tui" : cmd == C_PLOT ? "plot" : "run");
}

/* s42 --help: the commands, and the options of run, tui and plot. */
static void usage_to(FILE *f)
{
  for (size_t i = 0; i < sizeof cmdinfo / sizeof cmdinfo[0]; i++) {
    char left[64];
    snprintf(left, sizeof left, "%s %s", cmdinfo[i].name, cmdinfo[i].args);
    fprintf(f, "%s s42 %-36s %s\n", i ? "      " : "usage:", left, cmdinfo[i].what);
  }
  fprintf(f, "       s42 --help | --version | COMMAND --help\n\noptions of run, tui and plot (s42 COMMAND --help: which):\n");
  for (size_t i = 0; i < sizeof optinfo / sizeof optinfo[0]; i++) {
    const struct optinfo *o = &optinfo[i];
    if (!(o->cmds & (C_RUN | C_TUI | C_PLOT)) || !o->help)
      continue;
    char left[64];
    snprintf(left, sizeof left, "%s%s%s", o->name, o->arg && o->arg[0] != '[' ? " " : "", o->arg ? o->arg : "");
    fprintf(f, "  %-31s %s\n", left, o->help);
  }
  fprintf(f, "\nexit status: 0 the program reached M2; 1 an error in the program; 2 bad usage;\n"
          "3 the operator script had no fitting action, or the cycle was stopped; 4 I/O error\n");
}

/* s42 CMD --help: the command's usage and the options it takes. */
static int cmd_help(const struct cmdinfo *c)
{
  printf("usage: s42 %s %s\n  %s\n", c->name, c->args, c->what);
  int any = 0;
  for (size_t i = 0; i < sizeof optinfo / sizeof optinfo[0]; i++) {
    const struct optinfo *o = &optinfo[i];
    if (!(o->cmds & c->bit) || !o->help)
      continue;
    if (!any++)
      printf("\noptions:\n");
    char left[64];
    snprintf(left, sizeof left, "%s%s%s", o->name, o->arg && o->arg[0] != '[' ? " " : "", o->arg ? o->arg : "");
    printf("  %-31s %s\n", left, o->help);
  }
  printf("\nexit status: 0 %s; 1 an error in the program; 2 bad usage;\n"
         "3 the operator script had no fitting action, or the cycle was stopped; 4 I/O error\n"
         "(man s42 for the whole story)\n",
         c->bit & (C_CHECK | C_DISASM) ? "no error" : c->bit == C_PLUGINS ? "listed" : "the program reached M2");
  return 0;
}

struct opts {
  unsigned cmd;              /* C_RUN, C_TUI or C_PLOT: for "did you mean" */
  const char *program, *operator_file, *tool, *tools, *dump_images, *state, *plugins, *modbus, *out, *machine;
  const char *stock;         /* --stock DxL (a lathe's plot) */
  struct mach_travel travel; /* from --machine FILE (none without it) */
  int trace, json, canon, dump, screen, restart, realtime, en;
  unsigned long long max_blocks;
  struct mb_opts mb;         /* --modbus-*: mb.addr is o->modbus */
  const char *mb_opt;        /* the first --modbus-* option given (they need --modbus) */
};

/* Limits of the files s42 reads (README "Limits"). */
#define MAX_PROGRAM_BYTES FILE_MAX_PROGRAM
#define MAX_OPERATOR_BYTES ((size_t)1 << 20)

/* Read a whole regular file of at most `max` bytes, NUL-terminated: a
 * FIFO, a device or a socket is refused at once (src/core/atomic.h), a pipe
 * only as standard input (`s42 run /dev/stdin`). */
static int read_file_as(int map, const char *path, size_t max, char **buf, size_t *len)
{
  char err[600];
  int r = (map ? file_load : file_read_all)(path, FILE_OR_STDIN, max, buf, len, err, sizeof err);
  if (r)
    fprintf(stderr, "s42: %s%s\n", err, r == -2 ? " [E-LIMIT]" : "");
  return r ? -1 : 0;
}

static int read_file(const char *path, size_t max, char **buf, size_t *len)
{
  return read_file_as(0, path, max, buf, len);
}

static int parse_opts(int argc, char **argv, int i, struct opts *o, int multi)
{
  memset(o, 0, sizeof *o);
  o->cmd = strcmp(argv[1], "tui") == 0 ? C_TUI : strcmp(argv[1], "plot") == 0 ? C_PLOT : C_RUN;
  o->max_blocks = 100000000ULL;
  mb_opts_init(&o->mb);
  for (; i < argc; i++) {
    const char *a = argv[i];
    const char **val = NULL;
    if (strcmp(a, "--trace") == 0) { o->trace = 1; continue; }
    if (strcmp(a, "--trace=json") == 0) { o->trace = 1; o->json = 1; continue; }
    if (strcmp(a, "--trace=text") == 0) { o->trace = 1; o->json = 0; o->canon = 0; continue; }
    if (strcmp(a, "--trace=canon") == 0) { o->canon = 1; o->trace = 0; continue; }
    if (strcmp(a, "--dump") == 0) { o->dump = 1; continue; }
    if (strcmp(a, "--screen") == 0) { o->screen = 1; continue; }
    if (strcmp(a, "--restart") == 0) { o->restart = 1; continue; }
    if (strcmp(a, "--realtime") == 0) { o->realtime = 1; continue; }
    if (strcmp(a, "--modbus-read-only") == 0) {
      o->mb.read_only = 1;
      o->mb_opt = o->mb_opt ? o->mb_opt : a;
      continue;
    }
    if (strcmp(a, "--modbus-allow") == 0 || strcmp(a, "--modbus-max-clients") == 0 ||
        strcmp(a, "--modbus-idle") == 0) {
      if (i + 1 >= argc) {
        fprintf(stderr, "s42: %s needs a value\n", a);
        return -1;
      }
      const char *v = argv[++i];
      o->mb_opt = o->mb_opt ? o->mb_opt : a;
      char *end;
      errno = 0;
      if (a[9] == 'a') {
        o->mb.allow = v;       /* checked when the server opens */
      } else if (a[9] == 'm') {
        long n = strtol(v, &end, 10);
        if (errno || *end || !*v || n < 1 || n > MB_CLIENTS_LIMIT) {
          fprintf(stderr, "s42: --modbus-max-clients takes a whole number 1-%d, not '%s'\n", MB_CLIENTS_LIMIT, v);
          return -1;
        }
        o->mb.max_clients = (int)n;
      } else {
        double d = strtod(v, &end);
        if (errno || *end || !*v || !(d >= 0) || d > 1e6) {
          fprintf(stderr, "s42: --modbus-idle takes seconds (0 for never), not '%s'\n", v);
          return -1;
        }
        o->mb.idle = d;
      }
      continue;
    }
    if (strncmp(a, "--modbus", 8) == 0 && (a[8] == 0 || a[8] == '=')) {
      /* --modbus=ADDR, --modbus ADDR (a word with ':' or a bare port), or alone */
      const char *v = i + 1 < argc ? argv[i + 1] : "";
      if (a[8] == '=')
        o->modbus = a + 9;
      else if (v[0] && v[0] != '-' && (strchr(v, ':') || strspn(v, "0123456789") == strlen(v)))
        o->modbus = argv[++i];
      else
        o->modbus = MB_DEFAULT_ADDR;
      continue;
    }
    if (strcmp(a, "--operator") == 0) val = &o->operator_file;
    else if (strcmp(a, "--tool") == 0) val = &o->tool;
    else if (strcmp(a, "--tools") == 0) val = &o->tools;
    else if (strcmp(a, "--stock") == 0) val = &o->stock;
    else if (strcmp(a, "--dump-images") == 0) val = &o->dump_images;
    else if (strcmp(a, "--state") == 0) val = &o->state;
    else if (strcmp(a, "--machine") == 0) val = &o->machine;
    else if (strcmp(a, "--plugins") == 0) val = &o->plugins;
    else if (strcmp(a, "-o") == 0) val = &o->out;
    else if (strcmp(a, "--lang") == 0 || strcmp(a, "--max-blocks") == 0) {
      if (i + 1 >= argc) {
        fprintf(stderr, "s42: %s needs a value\n", a);
        return -1;
      }
      const char *v = argv[++i];
      if (a[2] == 'l') {
        if (strcmp(v, "uk") == 0) o->en = 0;
        else if (strcmp(v, "en") == 0) o->en = 1;
        else {
          fprintf(stderr, "s42: --lang takes uk or en, not '%s'\n", v);
          return -1;
        }
      } else {
        char *end;
        errno = 0;
        unsigned long long n = strtoull(v, &end, 10);
        if (errno || *end || !*v || v[0] == '-' || n == 0) {
          fprintf(stderr, "s42: --max-blocks takes a positive whole number, not '%s'\n", v);
          return -1;
        }
        o->max_blocks = n;
      }
      continue;
    } else if (a[0] == '-' && a[1]) {
      unknown_option(a, o->cmd);
      return -1;
    } else {
      if (o->program && !multi) {
        fprintf(stderr, "s42: one program at a time ('%s' and '%s')\n", o->program, a);
        return -1;
      }
      if (!o->program)
        o->program = a;
      continue;
    }
    if (i + 1 >= argc) {
      fprintf(stderr, "s42: %s needs a value\n", a);
      return -1;
    }
    *val = argv[++i];
  }
  if (o->machine) {
    char *text;
    size_t n;
    if (read_file(o->machine, MAX_OPERATOR_BYTES, &text, &n))
      return -1;
    int bad = machfile_parse(text, n, o->machine, &o->travel, stderr);
    free(text);
    if (bad)
      return -1;
  }
  /* the tooth search's plugin opens --tool itself: a FIFO or a device
   * would hang it, so it is refused here (a pipe only as standard input) */
  char err[600];
  if (o->tool && file_check_read(o->tool, FILE_OR_STDIN, err, sizeof err)) {
    fprintf(stderr, "s42: --tool %s\n", err);
    return -1;
  }
  if (o->mb_opt && !o->modbus) {
    fprintf(stderr, "s42: %s is an option of the Modbus server: it needs --modbus\n", o->mb_opt);
    return -1;
  }
  o->mb.addr = o->modbus;
  return 0;
}

/* The plugins of this process: scanned once, on first need, from --plugins
 * (the first command-line option that gave it), S42_PLUGIN_PATH, the build
 * tree and the installed directory. */
static struct plug_set plugins;
static int plugins_scanned;

static void plugins_free(void)
{
  plug_free(&plugins);
}

static struct plug_set *plugins_init(const char *dir)
{
  if (!plugins_scanned) {
    plugins_scanned = 1;
    struct stat st;
    if (dir && (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)))
      fprintf(stderr, "s42: warning: --plugins %s: not a directory\n", dir);
    plug_scan(&plugins, dir);
    atexit(plugins_free);
  }
  return &plugins;
}

/* The plugins of a run, plot or tui command, with what they may ask for
 * (host->option): its --tool, --dump-images and --lang. */
static struct plug_set *plugins_for(const struct opts *o)
{
  struct plug_set *ps = plugins_init(o->plugins);
  plug_set_option(ps, "tool", o->tool);
  plug_set_option(ps, "dump-images", o->dump_images);
  plug_set_option(ps, "lang", o->en ? "en" : "uk");
  return ps;
}

/* A function no plugin found (E-FUNC) may belong to a file that was
 * refused: say which files were, at the first such error. */
static void refused_notes(struct diag_list *d, const struct plug_set *ps)
{
  for (size_t i = 0; i < d->n && ps->nbad; i++) {
    const struct diag g = d->v[i];
    if (g.sev != DIAG_ERROR || g.code != S42_E_FUNC)
      continue;
    for (size_t k = 0; k < ps->nbad; k++)
      diag_add(d, DIAG_NOTE, 0, g.line, g.col, g.number, "the plugin file %s %s", ps->bad[k].path,
               ps->bad[k].msg);
    diag_sort(d);
    return;
  }
}

static int load_as(const char *path, struct program *p, struct diag_list *d, char **src, size_t *n, int print);

/* Compile a file; diagnostics to stderr.  Returns 0 ok, 1 program errors,
 * 4 I/O.  On success *src stays allocated for the caller. */
static int load(const char *path, struct program *p, struct diag_list *d, char **src, size_t *n)
{
  return load_as(path, p, d, src, n, 1);
}

/* The same, printing no diagnostics (check --json prints them itself). */
static int load_quiet(const char *path, struct program *p, struct diag_list *d, char **src, size_t *n)
{
  return load_as(path, p, d, src, n, 0);
}

/* --dialect NAME, any command's: the language of its files (NULL: each
 * file's extension says). */
static const struct dialect *cli_dialect;

static const struct dialect *dialect_of(const char *path)
{
  return cli_dialect ? cli_dialect : dialect_by_file(path);
}

/* `--dialect NAME` (or `--dialect=NAME`) among a command's arguments:
 * taken out of argv.  0, or -1 after saying what is wrong. */
static int take_dialect_opt(int *argc, char **argv)
{
  for (int i = 2; i < *argc; i++) {
    const char *name;
    int words;
    if (strcmp(argv[i], "--dialect") == 0) {
      if (i + 1 >= *argc) {
        fprintf(stderr, "s42: --dialect needs a name (s42 dialects lists them)\n");
        return -1;
      }
      name = argv[i + 1];
      words = 2;
    } else if (strncmp(argv[i], "--dialect=", 10) == 0) {
      name = argv[i] + 10;
      words = 1;
    } else {
      continue;
    }
    const struct dialect *dl = dialect_by_name(name);
    if (!dl) {
      char all[400];
      dialect_names(all, sizeof all);
      const char *names[64];
      size_t k = 0;
      for (; dialect_list[k] && k < 64; k++)
        names[k] = dialect_list[k]->name;
      const char *m = nearest_word(name, names, k);
      if (m)
        fprintf(stderr, "s42: --dialect: no dialect '%s': did you mean %s? (%s)\n", name, m, all);
      else
        fprintf(stderr, "s42: --dialect: no dialect '%s' (%s)\n", name, all);
      return -1;
    }
    cli_dialect = dl;
    for (int k = i; k + words <= *argc; k++)
      argv[k] = argv[k + words];
    *argc -= words;
    i--;
  }
  return 0;
}

static int load_as(const char *path, struct program *p, struct diag_list *d, char **src, size_t *n, int print)
{
  prog_init(p);
  diag_init(d, path);
  d->color = diag_want_color(stderr);
  /* (mapped when large: release with file_unload) */
  if (read_file_as(1, path, MAX_PROGRAM_BYTES, src, n))
    return EXIT_IO;
  struct plug_set *ps = plugins_init(NULL);
  int r = dialect_of(path)->compile(*src, *n, d, p, ps);
  if (file_cut(*src)) {
    fprintf(stderr, "s42: %s: the file was cut short while it was read (is something writing it?)\n", path);
    return EXIT_IO;
  }
  if (r && d->oom) {
    refused_notes(d, ps);
    if (print)
      diag_print(stderr, d);
    return EXIT_IO;
  }
  refused_notes(d, ps);
  if (print)
    diag_print(stderr, d);
  return r ? EXIT_PROGRAM : 0;
}

/* `--plugins DIR` among a command's arguments: taken out of argv. */
static int take_plugins_opt(int *argc, char **argv)
{
  for (int i = 2; i < *argc; i++) {
    if (strcmp(argv[i], "--plugins") != 0)
      continue;
    if (i + 1 >= *argc) {
      fprintf(stderr, "s42: --plugins needs a directory\n");
      return -1;
    }
    plugins_init(argv[i + 1]);
    for (int k = i; k + 2 <= *argc; k++)
      argv[k] = argv[k + 2];
    *argc -= 2;
    i--;
  }
  return 0;
}

static int cmd_plugins(int argc, char **argv)
{
  if (take_plugins_opt(&argc, argv))
    return EXIT_USAGE;
  int json = argc == 3 && strcmp(argv[2], "--json") == 0;
  if (argc != 2 && !json) {
    fprintf(stderr, "usage: s42 plugins [--json] [--plugins DIR]\n");
    return EXIT_USAGE;
  }
  if (json)
    plug_list_json(plugins_init(NULL), stdout, json_string);
  else
    plug_list(plugins_init(NULL), stdout);
  return 0;
}

/* `s42 check --json`: one JSON object a diagnostic, one a line. */
static void check_json(const struct diag_list *d, const char *file)
{
  static const char *const sev[] = {"error", "warning", "note"};
  for (size_t i = 0; i < d->n; i++) {
    const struct diag *g = &d->v[i];
    fputs("{\"file\":", stdout);
    json_string(stdout, file);
    printf(",\"line\":%u,\"col\":%u,\"block\":", g->line, g->col);
    if (g->number >= 0)
      printf("%d", g->number);
    else
      fputs("null", stdout);
    printf(",\"severity\":\"%s\",\"code\":", sev[g->sev >= 0 && g->sev <= 2 ? g->sev : 0]);
    if (g->code)
      printf("\"%s\"", err_code(g->code));
    else
      fputs("null", stdout);
    fputs(",\"message\":", stdout);
    json_string(stdout, g->msg);
    fputs("}\n", stdout);
  }
}

/* s42 check FILE...: the status is 1 when any program has errors, even when
 * another file could not be read (4 then only when none has errors): the
 * programs' verdict is what a script checking them asks for. */
/* s42 dialects: the registry, a line each. */
static int cmd_dialects(int argc, char **argv)
{
  (void)argv;
  if (argc > 2) {
    fprintf(stderr, "usage: s42 dialects\n");
    return EXIT_USAGE;
  }
  printf("%-10s %-6s %-10s %s\n", "dialect", "file", "machine", "controller");
  for (size_t i = 0; dialect_list[i]; i++) {
    const struct dialect *d = dialect_list[i];
    printf("%-10s %-6s %-10s %s%s\n", d->name, d->ext, d->machine, d->controller,
           d->run == DIALECT_RUN_VM ? " (blocks run on the VM alone)" : "");
  }
  return 0;
}

static int cmd_check(int argc, char **argv)
{
  int errors = 0, io = 0, any = 0, json = 0;
  if (take_plugins_opt(&argc, argv))
    return EXIT_USAGE;
  for (int i = 2; i < argc; i++) {
    if (strcmp(argv[i], "--json") == 0) {
      json = 1;
      for (int k = i; k + 1 < argc; k++)
        argv[k] = argv[k + 1];
      argc--;
      i--;
    } else if (argv[i][0] == '-' && argv[i][1]) {
      fprintf(stderr, "s42: check takes only program files, --json and --plugins DIR ('%s')\n", argv[i]);
      return EXIT_USAGE;
    }
  }
  for (int i = 2; i < argc; i++) {
    struct program p;
    struct diag_list d;
    char *src = NULL;
    size_t n = 0;
    any = 1;
    int r = json ? load_quiet(argv[i], &p, &d, &src, &n) : load(argv[i], &p, &d, &src, &n);
    if (json) {
      if (r == EXIT_IO) {
        fputs("{\"file\":", stdout);
        json_string(stdout, argv[i]);
        fputs(",\"line\":null,\"col\":null,\"block\":null,\"severity\":\"error\",\"code\":null,\"message\":", stdout);
        json_string(stdout, "the file cannot be read (the reason is on stderr)");
        fputs("}\n", stdout);
      } else {
        check_json(&d, argv[i]);
      }
    }
    errors |= r == EXIT_PROGRAM;
    io |= r == EXIT_IO;
    prog_free(&p);
    diag_free(&d);
    file_unload(src);
  }
  if (!any) {
    fprintf(stderr, "s42: check needs a program file\n");
    usage_to(stderr);
    return EXIT_USAGE;
  }
  return errors ? EXIT_PROGRAM : io ? EXIT_IO : 0;
}

static int cmd_disasm(int argc, char **argv)
{
  if (take_plugins_opt(&argc, argv))
    return EXIT_USAGE;
  if (argc != 3 || argv[2][0] == '-') {
    fprintf(stderr, "usage: s42 disasm PROGRAM.kp\n");
    return EXIT_USAGE;
  }
  struct program p;
  struct diag_list d;
  char *src = NULL;
  size_t n = 0;
  int r = load(argv[2], &p, &d, &src, &n);
  if (r == 0)
    vm_disasm(stdout, &p, src, n);
  prog_free(&p);
  diag_free(&d);
  file_unload(src);
  return r;
}

/* ---- the headless run ---- */

/* "N12", or "N-" for a block without a number. */
static const char *bname(int n, char *buf)
{
  return diag_block(n, buf);
}

struct runner {
  struct session s;
  struct cycle cyc;          /* the run setup: the restart point's file, the M15 saves */
  struct opscript ops;
  size_t next;               /* next ordered action */
  const char *file;
  unsigned *runs;            /* runs per block number, for `at` */
  uint8_t *watch;
  size_t unfit;              /* 1 + the action reported as not fitting a wait, 0 none */
};

static void warn_sink(void *ctx, const struct session *s, const char *msg)
{
  struct runner *r = ctx;
  const struct prog_block *b = &s->p->blocks[sess_cur(s)];
  fprintf(stderr, "%s:%u:%u: warning: N", r->file, b->line, b->col);
  if (b->number)
    fprintf(stderr, "%u", b->number);
  else
    fputc('-', stderr);
  fprintf(stderr, ": %s\n", msg);
}

struct both_sink {
  struct trace_ctx tr;
  struct runner *r;
  int realtime;            /* --realtime: wait until the wall clock reaches the simulated time */
  struct pace pace;
};

static void row_sink(void *ctx, const struct session *s, const struct sess_row *row)
{
  struct both_sink *b = ctx;
  if (b->realtime)
    pace_sleep_until(&b->pace, row->t);
  if (b->tr.out) {
    report_row(&b->tr, s, row);
    if (b->realtime)
      fflush(b->tr.out);
  }
}

/* --trace=canon: a canonical call on stdout, a line each. */
static void canon_line(void *ctx, const char *call)
{
  fprintf(ctx, "%s\n", call);
}

static void sink_warn(void *ctx, const struct session *s, const char *msg)
{
  struct both_sink *b = ctx;
  warn_sink(b->r, s, msg);
}

static void sink_log(void *ctx, const struct session *s, const char *msg)
{
  (void)ctx;
  (void)s;
  fprintf(stderr, "s42: note: %s\n", msg);
}

static void apply_immediate(struct runner *r, const struct op_action *a)
{
  switch (a->kind) {
  case OA_KEY:
    if (a->key == OPKEY_EXIT)
      sess_key_exit(&r->s);
    else if (a->key == OPKEY_STOP)
      sess_key_stop(&r->s);
    break;
  case OA_CORRECT:
    sess_correct(&r->s, a->axis, a->n);
    break;
  case OA_OVERRIDE:
    sess_override(&r->s, (int)a->n);
    break;
  case OA_MODE:   /* the 2С42's scripts have only single block (refused_for_2c42) */
    sess_set_single(&r->s, (int)a->n);
    break;
  case OA_BREAK:
    sess_set_break(&r->s, (int)a->n);
    break;
  default:
    break;
  }
}

/* The block boundary: immediate actions at the head of the script, then
 * the `at` actions for this run of this block. */
static void at_boundary(struct runner *r)
{
  while (r->next < r->ops.n && !ops_is_waiting(&r->ops.v[r->next]) && r->s.state != SE_STOPPED)
    apply_immediate(r, &r->ops.v[r->next++]);
  int num = sess_block_number(&r->s);
  if (num > 0 && r->watch[sess_cur(&r->s)]) {
    unsigned run = ++r->runs[num];
    for (size_t i = 0; i < r->ops.nat; i++) {
      struct op_action *a = &r->ops.at[i];
      if (a->at_number == num && a->at_run == run && !a->fired) {
        a->fired = 1;
        apply_immediate(r, a);
      }
    }
  }
}

/* The machine waits: take the script's fitting actions.  0 when the wait is
 * over, -1 when the script has nothing that fits (stop, status 3). */
static int serve_wait(struct runner *r)
{
  char what[96], nb[16];
  while (r->s.state == SE_WAIT) {
    if (r->next >= r->ops.n) {
      const struct prog_block *b = &r->s.p->blocks[sess_cur(&r->s)];
      fprintf(stderr, "%s:%u:%u: error: %s: the machine waits for %s and the operator script has no more actions\n",
              r->file, b->line, b->col, bname(sess_block_number(&r->s), nb), sess_wait_text(&r->s));
      return -1;
    }
    const struct op_action *a = &r->ops.v[r->next];
    int ok = -1;
    if (!ops_is_waiting(a)) {
      apply_immediate(r, a);
      ok = 0;
    } else if (a->kind == OA_KEY && a->key == OPKEY_PUSK) {
      ok = sess_key_pusk(&r->s);
    } else if (a->kind == OA_KEY && a->key == OPKEY_PS) {
      ok = sess_key_ps(&r->s);
    } else if (a->kind == OA_JOG) {
      ok = sess_jog(&r->s, a->axis, a->n);
    } else if (a->kind == OA_ANSWER) {
      ok = sess_answer(&r->s, a->n);
    } else if (a->kind == OA_SECTION) {
      ok = sess_section(&r->s, a->axis, a->n);
      if (!ok && a->axis2 >= 0)
        ok = sess_section(&r->s, a->axis2, a->n2);
    }
    if (ok) {
      r->unfit = r->next + 1;
      const struct prog_block *b = &r->s.p->blocks[sess_cur(&r->s)];
      fprintf(stderr, "%s:%u:%u: error: %s: the machine waits for %s; the operator script's next action "
              "(line %u: %s) does not fit\n", r->file, b->line, b->col, bname(sess_block_number(&r->s), nb),
              sess_wait_text(&r->s), a->line, ops_describe(a, what, sizeof what));
      return -1;
    }
    r->next++;
  }
  return 0;
}

/* A block with M15 starts: save the restart point (src/host/cycle.c).  A
 * save that fails (the disk, the directory, a --state that is not a state)
 * ends the run there with E-STATE: the dump names it, and the status is 4
 * -- the file system refused, the program did nothing wrong. */
static int save_m15(struct runner *r)
{
  return cycle_m15(&r->cyc) < 0 ? -1 : 0;
}

static volatile sig_atomic_t quit_signal;

static void on_quit(int sig)
{
  quit_signal = sig;
}

static void headless_free(struct runner *r, struct program *p, struct diag_list *d, char *src)
{
  cycle_free(&r->cyc);
  free(r->watch);
  free(r->runs);
  ops_free(&r->ops);
  prog_free(p);
  diag_free(d);
  file_unload(src);
}

/* Operator actions of other machines in a 2С42 script: refused before the run. */
static int refused_for_2c42(const struct opscript *ops, const char *file)
{
  int bad = 0;
  for (int pass = 0; pass < 2; pass++)
    for (size_t i = 0; i < (pass ? ops->nat : ops->n); i++) {
      const struct op_action *a = pass ? &ops->at[i] : &ops->v[i];
      const char *why = a->kind == OA_ZERO ? "zero: the ВЗ-208Ф3 has no part zero to set (that is the lathe's)"
                        : a->kind == OA_MODE && a->n2 == OPMODE_SKIP ? "mode skip: the 2С42-65 has no block skip"
                        : a->kind == OA_MODE && a->n2 == OPMODE_OPTSTOP ? "mode optstop: the 2С42-65 has no M01"
                                                                        : NULL;
      if (why) {
        fprintf(stderr, "%s:%u:%u: error: %s\n", file, a->line, a->col, why);
        bad = 1;
      }
    }
  return bad;
}

/* A dialect on the one runner (src/host/run.c); pl: s42 plot's picture. */
static int run_machine(const struct opts *o, struct program *p, struct diag_list *d, const char *src, size_t n,
                       struct plot *pl)
{
  const struct mrun_rt *rt = p->runtime;
  int table = rt && rt->tool_table;
  const char *no = table && o->tool && o->tools ? "--tool with --tools"
                   : table && o->dump_images ? "--dump-images" : NULL;
  if (no) {
    fprintf(stderr, "s42: %s: %s is not there yet for the %s dialect (%s)\n", o->program, no,
            dialect_of(o->program)->name, dialect_of(o->program)->machine);
    return EXIT_USAGE;
  }
  struct run_opts r;
  memset(&r, 0, sizeof r);
  r.program = o->program;
  r.operator_file = o->operator_file;
  r.tools = o->tools ? o->tools : table ? o->tool : NULL;   /* a lathe's tool is its table (the runner's tool.txt) */
  r.machine = o->machine;
  r.state = o->state;
  r.trace = o->trace;
  r.json = o->json;
  r.canon = o->canon;
  r.dump = o->dump;
  r.screen = o->screen;
  r.restart = o->restart;
  r.realtime = o->realtime;
  r.en = o->en;
  r.max_blocks = o->max_blocks;
  r.mb = o->modbus ? &o->mb : NULL;
  struct run_watch w;
  if (pl)
    plot_watch(pl, &w);
  r.watch = pl ? &w : NULL;
  return run_headless(&r, p, d, src, n);
}

/* --dump of a program that did not compile: the machine at power-on, in
 * its dialect's format. */
static void dump_refused(const struct opts *o, const struct program *p, const struct diag_list *d)
{
  const struct diag *g = diag_first_error(d);
  struct s42_error de;
  s42_error_of_diag(&de, g);
  const struct dialect *dl = dialect_of(o->program);
  if (dl->run != DIALECT_RUN_SESSION)
    run_dump_refused(dl->runtime, p, &de, o->en);
  else
    report_dump(stdout, "error", &de, p, o->en, NULL);
}

static int headless(const struct opts *opt)
{
  struct opts o = *opt;
  struct runner r;
  memset(&r, 0, sizeof r);
  r.file = o.program;
  if (o.operator_file) {
    char *text;
    size_t n;
    if (read_file(o.operator_file, MAX_OPERATOR_BYTES, &text, &n))
      return EXIT_IO;
    int bad = ops_parse(text, n, o.operator_file, &r.ops, stderr);
    free(text);
    if (bad)
      return EXIT_USAGE;
  }
  struct program p;
  struct diag_list d;
  char *src = NULL;
  size_t n = 0;
  int rc = load(o.program, &p, &d, &src, &n);
  /* the dialects on the runner, and every run served over Modbus (the one
   * server loop is run.c's) */
  if (rc == 0 && (dialect_of(o.program)->run != DIALECT_RUN_SESSION || o.modbus)) {
    rc = run_machine(&o, &p, &d, src, n, NULL);
    prog_free(&p);
    diag_free(&d);
    file_unload(src);
    ops_free(&r.ops);
    return rc;
  }
  if (o.tools) {
    fprintf(stderr, "s42: %s: --tools is a lathe's tool table; the 2С42's tooth-search tool model is --tool\n",
            o.program);
    rc = rc ? rc : EXIT_USAGE;
  }
  if (rc == 0 && dialect_of(o.program)->run == DIALECT_RUN_SESSION && refused_for_2c42(&r.ops, o.operator_file))
    rc = EXIT_USAGE;
  if (rc) {
    if (o.dump && rc == EXIT_PROGRAM)
      dump_refused(&o, &p, &d);
    prog_free(&p);
    diag_free(&d);
    file_unload(src);
    ops_free(&r.ops);
    return rc;
  }

  /* an `at` or `break` for a block the program does not have would never fire */
  if (r.ops.nat || r.ops.n) {
    unsigned char have[1000] = {0};
    for (size_t b = 0; b < p.nblocks; b++)
      if (p.blocks[b].number < 1000)
        have[p.blocks[b].number] = 1;
    if (ops_check_at(&r.ops, have, o.operator_file, stderr)) {
      fprintf(stderr, "%s: note: the operator script %s is refused: the run does not start\n", o.program,
              o.operator_file);
      prog_free(&p);
      diag_free(&d);
      file_unload(src);
      ops_free(&r.ops);
      return EXIT_USAGE;
    }
  }

  struct both_sink bs;
  bs.tr.out = o.trace ? stdout : NULL;
  bs.tr.json = o.json;
  bs.r = &r;
  bs.realtime = o.realtime;
  r.watch = calloc(p.nblocks ? p.nblocks : 1, 1);
  r.runs = calloc(1000, sizeof *r.runs);
  if (!r.watch || !r.runs) {
    fprintf(stderr, "s42: out of memory\n");
    headless_free(&r, &p, &d, src);
    return EXIT_IO;
  }
  for (size_t i = 0; i < r.ops.nat; i++)
    for (size_t b = 0; b < p.nblocks; b++)
      if ((int)p.blocks[b].number == r.ops.at[i].at_number)
        r.watch[b] = 1;
  for (size_t b = 0; b < p.nblocks; b++)   /* M15 blocks save the restart state when they start */
    if ((kp_attr(&p, b)->m >> 15) & 1)
      r.watch[b] = 1;
  struct sess_config cfg;
  memset(&cfg, 0, sizeof cfg);
  cfg.en = o.en;
  cfg.max_blocks = o.max_blocks;
  cfg.travel = o.travel;
  cfg.plugins = plugins_init(NULL);
  cfg.sink.ctx = &bs;
  /* rows only for what reads them: a run with none builds none */
  cfg.sink.row = o.trace || o.realtime ? row_sink : NULL;
  cfg.sink.warn = sink_warn;
  cfg.sink.log = sink_log;
  cfg.yield_all = o.trace;
  cfg.watch = r.watch;
  struct canon_trace ct;
  if (o.canon) {
    canon_trace_init(&ct, canon_line, stdout);
    cfg.canon = canon_trace_call;
    cfg.canon_ctx = &ct;
  }
  /* the plugins the program uses start now: one that cannot because of
   * the command line (no --tool for G10) stops the run before it begins */
  {
    char why[300], nbuf[16];
    size_t fb = 0;
    int setup = cycle_setup(&r.cyc, &r.s, &p, src, n, &cfg, o.program, o.state, o.restart, why, sizeof why, &fb);
    if (setup == CYCLE_PLUGIN) {
      const struct prog_block *b = &p.blocks[fb];
      fprintf(stderr, "s42: %s\n", why);
      fprintf(stderr, "%s:%u:%u: note: %s: the first block that needs it\n", o.program, b->line, b->col,
              bname(b->number ? (int)b->number : -1, nbuf));
      headless_free(&r, &p, &d, src);
      return EXIT_USAGE;
    }
    if (setup == CYCLE_OOM) {
      fprintf(stderr, "s42: out of memory\n");
      headless_free(&r, &p, &d, src);
      return EXIT_IO;
    }
  }
  int status = EXIT_END;
  const char *st = "end";
  struct s42_error de, *dep = NULL;
  char serr[512];
  int ran = 1;                       /* the cycle started (not refused before its first block) */
  if (o.restart && cycle_restart(&r.cyc, serr, sizeof serr)) {
    ran = 0;
    fprintf(stderr, "%s:1:1: error: N-: restart refused: %s [E-STATE]\n", o.program, serr);
    sess_error(&r.s, &de);
    snprintf(de.msg, sizeof de.msg, "%s", serr);   /* the dump says why; stderr said "restart refused" */
    de.number = -1;
    dep = &de;
    status = EXIT_PROGRAM;
    st = "error";
  }
  bs.pace.stop = NULL;
  int interruptible = o.realtime;
  if (interruptible) {
    /* --realtime takes as long as the machine would: Ctrl-C (or SIGTERM)
     * stops it at the next block boundary with the dump of that moment,
     * as under --modbus */
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_quit;      /* no SA_RESTART: the pacing sleep returns at once */
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    bs.pace.stop = &quit_signal;
  }
  pace_start(&bs.pace, sess_time(&r.s));     /* a restart goes on from the saved time */

  while (status == EXIT_END) {
    sess_set_start_all(&r.s, interruptible || (r.next < r.ops.n && !ops_is_waiting(&r.ops.v[r.next])));
    if (interruptible && quit_signal) {
      const struct prog_block *b = &p.blocks[sess_cur(&r.s)];
      char qb[16];
      fprintf(stderr, "%s:%u:%u: note: %s: stopped by %s before this block\n", o.program, b->line, b->col,
              bname(sess_block_number(&r.s), qb), quit_signal == SIGINT ? "Ctrl-C (SIGINT)" : "SIGTERM");
      status = EXIT_STOPPED;
      st = "stopped";
      break;
    }
    enum sess_ev ev = sess_run(&r.s);
    if (ev == SE_START) {
      if (save_m15(&r)) {
        status = EXIT_IO;
        st = "error";
        break;
      }
      at_boundary(&r);
      if (r.s.state == SE_STOPPED) {
        status = EXIT_STOPPED;
        st = "stopped";
        break;
      }
      continue;
    }
    if (ev == SE_WAIT) {
      if (serve_wait(&r) == 0 && r.s.state != SE_STOPPED)
        continue;
      status = EXIT_STOPPED;
      st = "stopped";
      break;
    }
    if (ev == SE_END) {
      break;
    }
    if (ev == SE_STOPPED) {
      status = EXIT_STOPPED;
      st = "stopped";
      break;
    }
    status = EXIT_PROGRAM;
    st = "error";
    break;
  }
  char nb[16];
  if (r.s.state == SE_STOPPED && status == EXIT_STOPPED) {
    const struct prog_block *b = &p.blocks[sess_cur(&r.s)];
    if (r.next <= r.ops.n && r.s.wait == W_NONE)
      fprintf(stderr, "%s:%u:%u: note: %s: the cycle was stopped (key STOP)\n", o.program, b->line, b->col,
              bname(sess_block_number(&r.s), nb));
  }
  /* the program's error, or a failed M15 save's (status 4) */
  if ((status == EXIT_PROGRAM || (status == EXIT_IO && r.s.state == SE_ERROR)) && !dep) {
    sess_error(&r.s, &de);
    struct diag g;
    s42_error_diag(&de, &g);
    diag_print_in(stderr, &d, &g);
    char machine[200];
    s42_error_machine(&de, &p, o.en, machine, sizeof machine);
    fprintf(stderr, "%s:%u:%u: note: %s: %s\n", o.program, de.line, de.col,
            o.en ? "the machine shows" : "на екрані", machine);
    dep = &de;
  }
  /* what the script held that the run did not use (a run that started) */
  if (o.operator_file && ran)
    ops_warn_unused(&r.ops, r.next, r.unfit, r.runs, o.operator_file, stderr);
  if (o.dump)
    report_dump(stdout, st, dep, &p, o.en, &r.s);
  if (o.screen) {
    uint32_t grid[SCR_ROWS][SCR_COLS];
    if (dep) {
      char machine[200];
      s42_error_machine(dep, &p, o.en, machine, sizeof machine);
      sess_show_message(&r.s, machine);
    }
    sess_screen(&r.s, grid);
    screen_print(stdout, grid);
  }
  if (fflush(stdout) || ferror(stdout)) {
    fprintf(stderr, "s42: error writing the output\n");
    status = EXIT_IO;
  }
  headless_free(&r, &p, &d, src);
  return status;
}

static int cmd_run(int argc, char **argv)
{
  struct opts o;
  if (parse_opts(argc, argv, 2, &o, 0))
    return EXIT_USAGE;
  plugins_for(&o);
  if (!o.program) {
    fprintf(stderr, "s42: run needs a program file\n");
    usage_to(stderr);
    return EXIT_USAGE;
  }
  if (o.out) {
    fprintf(stderr, "s42: run writes no file (-o is for plot)\n");
    return EXIT_USAGE;
  }
  return headless(&o);
}

/* s42 plot: one path for every dialect -- compile, run headless on the
 * runner (src/host/run.c) with the plot engine watching (src/host/plot.h),
 * which draws it in the view of the machine's kind. */
static int cmd_plot(int argc, char **argv)
{
  struct opts o;
  if (parse_opts(argc, argv, 2, &o, 0))
    return EXIT_USAGE;
  plugins_for(&o);
  if (!o.program || !o.out) {
    fprintf(stderr, "usage: s42 plot PROGRAM.kp -o FILE.png|.svg|.pdf [--operator FILE] [options]\n");
    return EXIT_USAGE;
  }
  const struct dialect *dl = dialect_of(o.program);
  if (dl->run == DIALECT_RUN_VM) {
    fprintf(stderr, "s42: %s: this dialect runs its blocks on the VM alone: plot, --modbus, --operator, "
            "--state, --restart, --tool and --machine need a machine\n", o.program);
    return EXIT_USAGE;
  }
  if (o.modbus) {
    fprintf(stderr, "s42: plot does not serve Modbus (--modbus is for run and tui)\n");
    return EXIT_USAGE;
  }
  char err[300];
  struct plot_stock stock = {0, 0, 0};
  if (o.stock && strcmp(dl->machine, "lathe") != 0) {
    /* the controller's short name: "2С42" of "2С42-65 (...)" */
    int len = (int)strcspn(dl->controller, "- (");
    fprintf(stderr, "s42: --stock is a lathe's bar; the %.*s's plot has none\n", len, dl->controller);
    return EXIT_USAGE;
  }
  if (o.stock && plot_parse_stock(o.stock, &stock, err, sizeof err)) {
    fprintf(stderr, "s42: --stock %s: %s\n", o.stock, err);
    return EXIT_USAGE;
  }
  if (plot_check_path(o.out, o.program, err, sizeof err)) {
    fprintf(stderr, "s42: %s\n", err);
    return EXIT_USAGE;
  }
  struct plot *pl = plot_new(&stock);
  if (!pl) {
    fprintf(stderr, "s42: out of memory\n");
    return EXIT_IO;
  }
  struct program p;
  struct diag_list d;
  char *src = NULL;
  size_t n = 0;
  int rc = load(o.program, &p, &d, &src, &n);
  if (rc == 0) {
    rc = run_machine(&o, &p, &d, src, n, pl);
  } else if (rc == EXIT_PROGRAM) {
    /* not run: the picture of its machine says why */
    const struct diag *g = diag_first_error(&d);
    const struct mrun_rt *rt = p.runtime ? p.runtime : dl->runtime;
    struct canon_info in;
    memset(&in, 0, sizeof in);
    if (rt && rt->info)
      rt->info(&(struct mrun){.rt = rt}, &in);
    plot_refused(pl, in.kind ? in.kind : dl->machine, g ? err_code(g->code) : "E-SYNTAX", g ? g->number : -1,
                 g ? g->line : 0);
    if (o.dump)
      dump_refused(&o, &p, &d);
  }
  if (rc != EXIT_USAGE && rc != EXIT_IO && plot_write(pl, o.program, o.out, err, sizeof err)) {
    fprintf(stderr, "s42: %s: %s\n", o.out, err);
    rc = EXIT_IO;
  }
  plot_free(pl);
  prog_free(&p);
  diag_free(&d);
  file_unload(src);
  return rc;
}

/* s42 tui: the terminal front end (src/host/tui.c), at machine speed. */
static int cmd_tui(int argc, char **argv)
{
  struct opts o;
  if (parse_opts(argc, argv, 2, &o, 0))
    return EXIT_USAGE;
  const char *bad = o.operator_file ? "--operator (operator scripts are for s42 run)"
                    : o.trace ? "--trace" : o.dump ? "--dump" : o.screen ? "--screen" : o.out ? "-o" : NULL;
  if (bad) {
    fprintf(stderr, "s42: tui does not take %s\n", bad);
    return EXIT_USAGE;
  }
  const struct dialect *dl = o.program ? dialect_of(o.program) : cli_dialect;
  if (dl && dl->run == DIALECT_RUN_VM) {
    fprintf(stderr, "s42: tui: the %s dialect has no panel yet (s42 run and s42 check take it)\n", dl->name);
    return EXIT_USAGE;
  }
  if (o.restart && !o.program) {
    fprintf(stderr, "s42: --restart needs the program file\n");
    return EXIT_USAGE;
  }
  struct tui_opts t;
  memset(&t, 0, sizeof t);
  t.plugins = plugins_for(&o);
  t.program = o.program;
  t.state = o.state;
  t.restart = o.restart;
  t.realtime = 1;          /* the operator watches: machine speed (F9 / f toggles) */
  t.en = o.en;
  t.max_blocks = o.max_blocks;
  t.travel = o.travel;
  t.dialect = cli_dialect;
  t.tools = o.tools ? o.tools : dl && dl->run == DIALECT_RUN_MACHINE ? o.tool : NULL;
  if (dl && dl->run == DIALECT_RUN_MACHINE) {
    const char *no = o.modbus ? "--modbus" : o.state ? "--state" : o.restart ? "--restart"
                     : o.machine ? "--machine" : o.tool && o.tools ? "--tool with --tools" : NULL;
    if (no) {
      fprintf(stderr, "s42: tui: %s is not there yet for the %s dialect (%s)\n", no, dl->name, dl->machine);
      return EXIT_USAGE;
    }
  } else if (o.tools) {
    fprintf(stderr, "s42: tui: --tools is a lathe's tool table; the 2С42's tooth-search tool model is --tool\n");
    return EXIT_USAGE;
  }
  /* ncursesw is loaded for the terminal alone (curses_dl.h) */
  char lerr[300];
  if (s42_curses_load(lerr, sizeof lerr)) {
    fprintf(stderr, "s42 tui: %s\n", lerr);
    return EXIT_IO;
  }
  struct tui_source mb;
  if (o.modbus) {
    char err[300];
    int addr_bad;
    if (tui_modbus_open(&o.mb, &mb, err, sizeof err, &addr_bad)) {
      fprintf(stderr, "s42: %s\n", err);
      return addr_bad ? EXIT_USAGE : EXIT_IO;
    }
  }
  int rc = tui_main(&t, o.modbus ? &mb : NULL, o.modbus ? 1 : 0);
  if (o.modbus)
    tui_modbus_close(&mb);
  return rc;
}

static int command(int argc, char **argv);

/* Every command's output is checked once more at the end: a full disk or a
 * closed pipe is status 4 with the reason, never a silent success. */
int main(int argc, char **argv)
{
  int rc = command(argc, argv);
  if (fflush(stdout) != 0 || ferror(stdout)) {
    if (rc != EXIT_IO)   /* the headless run said so already */
      fprintf(stderr, "s42: error writing the output: %s\n", strerror(errno ? errno : EIO));
    rc = EXIT_IO;
  }
  return rc;
}

static int command(int argc, char **argv)
{
  if (argc < 2) {
    usage_to(stderr);
    return EXIT_USAGE;
  }
  if (take_dialect_opt(&argc, argv))
    return EXIT_USAGE;
  const char *cmd = argv[1];
  /* s42 CMD --help (or -h anywhere among its words), s42 help CMD */
  for (size_t i = 0; i < sizeof cmdinfo / sizeof cmdinfo[0]; i++) {
    int mine = strcmp(cmd, cmdinfo[i].name) == 0;
    if (strcmp(cmd, "help") == 0 && argc == 3 && strcmp(argv[2], cmdinfo[i].name) == 0)
      return cmd_help(&cmdinfo[i]);
    for (int k = 2; mine && k < argc; k++)
      if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0)
        return cmd_help(&cmdinfo[i]);
  }
  if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
    usage_to(stdout);
    return 0;
  }
  if (strcmp(cmd, "--version") == 0) {
    printf("s42 %s\n", S42_VERSION);
    return 0;
  }
  if (strcmp(cmd, "run") == 0)
    return cmd_run(argc, argv);
  if (strcmp(cmd, "check") == 0)
    return cmd_check(argc, argv);
  if (strcmp(cmd, "disasm") == 0)
    return cmd_disasm(argc, argv);
  if (strcmp(cmd, "--opcodes-md") == 0) {
    vm_opcodes_md(stdout);
    return 0;
  }
  if (strcmp(cmd, "plot") == 0)
    return cmd_plot(argc, argv);
  if (strcmp(cmd, "plugins") == 0)
    return cmd_plugins(argc, argv);
  if (strcmp(cmd, "dialects") == 0)
    return cmd_dialects(argc, argv);
  if (strcmp(cmd, "tui") == 0)
    return cmd_tui(argc, argv);
  const char *names[sizeof cmdinfo / sizeof cmdinfo[0]];
  for (size_t i = 0; i < sizeof cmdinfo / sizeof cmdinfo[0]; i++)
    names[i] = cmdinfo[i].name;
  const char *m = nearest_word(cmd, names, sizeof names / sizeof names[0]);
  if (m)
    fprintf(stderr, "s42: unknown command '%s': did you mean %s?\n", cmd, m);
  else
    fprintf(stderr, "s42: unknown command '%s'\n", cmd);
  usage_to(stderr);
  return EXIT_USAGE;
}
