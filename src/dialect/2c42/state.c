/* The M15 restart state file (src/core/state.h). */
#include "state.h"
#include "ast.h"
#include "atomic.h"
#include "opcodes.h"
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define R_MAX 9999999.0      /* a parameter, an array cell, TK, UG */
#define D1_MAX 400000.0
#define F_MAX 6000.0
#define H_MAX 30000u         /* the H word: a sub runs at most that many times */

uint64_t state_hash(const void *data, size_t n)
{
  /* FNV-1a, 64 bits */
  const unsigned char *p = data;
  uint64_t h = 1469598103934665603ULL;
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}

/* An existing file at path is replaced only when it is a restart state (any
 * version) or empty: `--state prog.kp` must not turn the program into a
 * state.  A FIFO or a device is not even opened for long (O_NONBLOCK). */
static int check_target(const char *path, char *err, size_t n)
{
  int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT)
      return 0;
    snprintf(err, n, "%s: %s", path, strerror(errno));
    return -1;
  }
  struct stat st;
  char magic[8];
  int rc = -1;
  if (fstat(fd, &st) != 0)
    snprintf(err, n, "%s: %s", path, strerror(errno));
  else if (!S_ISREG(st.st_mode))
    snprintf(err, n, "%s is %s, not a restart state: it is not replaced", path, file_kind(st.st_mode));
  else if (st.st_size == 0)
    rc = 0;
  else if (st.st_size < 8 || read(fd, magic, 8) != 8 || memcmp(magic, STATE_MAGIC, 8) != 0)
    snprintf(err, n, "%s is not an s42 restart state: it is not replaced (remove it, or choose another --state)",
             path);
  else
    rc = 0;
  close(fd);
  return rc;
}

int state_save(const struct session *s, const char *path, uint64_t prog_hash, char *err, size_t n)
{
  if (check_target(path, err, n))
    return -1;
  struct state_payload *pl = calloc(1, sizeof *pl);
  if (!pl) {
    snprintf(err, n, "out of memory");
    return -1;
  }
  const struct vm *vm = &s->vm;
  pl->prog_hash = prog_hash;
  pl->block = vm->cur;
  pl->pc = s->p->blocks[vm->cur].code;
  pl->blocks = vm->blocks;
  memcpy(pl->reg, vm->reg, sizeof pl->reg);
  memcpy(pl->arr, vm->arr, sizeof pl->arr);
  pl->depth = vm->depth;
  for (int i = 0; i < vm->depth; i++)
    pl->frames[i] = vm->frames[i];
  memcpy(pl->pos, s->m.pos, sizeof pl->pos);
  pl->t = s->m.t;
  pl->wheel = s->m.wheel;
  pl->override_pct = s->m.override_pct;
  pl->override_allowed = s->m.override_allowed;
  pl->corr_allowed = s->m.corr_allowed;
  for (int k = 0;; k++) {
    size_t len = 0;
    int r = pl->nplug < STATE_PLUGS
              ? sess_plugin_state(s, k, pl->plug[pl->nplug].name, sizeof pl->plug[0].name,
                                  pl->plug[pl->nplug].data, STATE_PLUG_MAX, &len)
              : 1;
    if (r == 1)
      break;
    if (r == -2) {   /* its save() crashed: no state, rather than one without it */
      snprintf(err, n, "%s", s->plugins->v[s->plugins->crashed].err);
      free(pl);
      return -1;
    }
    if (r < 0 || pl->nplug == STATE_PLUGS) {
      snprintf(err, n, "a plugin's restart state is too large");
      free(pl);
      return -1;
    }
    if (r == 0)
      pl->plug[pl->nplug++].len = (uint32_t)len;
  }
  pl->p3 = s->scr.p3;
  pl->np3 = s->scr.np3;
  memcpy(pl->p3l, s->scr.p3l, sizeof pl->p3l);
  pl->directive = s->directive;
  memcpy(pl->dirtext, s->scr.dirtext, sizeof pl->dirtext);

  struct state_header h;
  memset(&h, 0, sizeof h);
  memcpy(h.magic, STATE_MAGIC, 8);
  h.version = STATE_VERSION;
  h.size = (uint32_t)sizeof *pl;
  h.sum = state_hash(pl, sizeof *pl);

  struct iovec v[2] = {{&h, sizeof h}, {pl, sizeof *pl}};
  /* one fsync a save (the file's); the directory's only when the save
   * makes the name (the first save into a new file): a later save that
   * the power cut takes back leaves the previous save's whole state, the
   * previous restart point (src/core/atomic.h) */
  int rc = atomic_write_flags(path, path, 0644, v, 2, ATOMIC_DIRSYNC_NEW, err, n);
  free(pl);
  return rc;
}

/* ---- checking a loaded record, field by field ---- */

struct chk {
  const struct program *p;
  const char *shown;
  char *err;
  size_t n;
  int bad;
};

static void refuse(struct chk *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void refuse(struct chk *c, const char *fmt, ...)
{
  if (c->bad++)
    return;   /* the first bad field is the one named */
  char what[300];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  snprintf(c->err, c->n, "the state's %s (%s)", what, c->shown);
}

/* A double for a message: nan and inf as such, no exponent below 1e15. */
static const char *num(char *b, size_t n, double v)
{
  snprintf(b, n, "%.15g", v);
  return b;
}

/* v finite and in lo..hi (and whole, when asked); otherwise refused. */
static void range(struct chk *c, const char *what, double v, double lo, double hi, int whole)
{
  char b[40], l[24], h[24];
  if (!(v >= lo && v <= hi))
    refuse(c, "%s is %s, not %s..%s", what, num(b, sizeof b, v), num(l, sizeof l, lo), num(h, sizeof h, hi));
  else if (whole && v != floor(v))
    refuse(c, "%s is %s, not a whole number", what, num(b, sizeof b, v));
}

static void ints(struct chk *c, const char *what, long long v, long long lo, long long hi)
{
  if (v < lo || v > hi)
    refuse(c, lo < 0 ? "%s is %lld, not %lld..%lld" : "%s is %lld, not %lld-%lld", what, v, lo, hi);
}

/* The block whose code starts exactly at pc, or -1. */
static long block_starting(const struct program *p, uint32_t pc)
{
  if (pc >= p->ncode || !p->nblocks)
    return -1;
  size_t b = prog_block_at(p, pc);
  return p->blocks[b].code == pc ? (long)b : -1;
}

/* UTF-8 that screen_set_directive may have cut at its buffer's end. */
static int utf8_ok(const char *s)
{
  const unsigned char *u = (const unsigned char *)s;
  while (*u) {
    int len = *u < 0x80 ? 1 : (*u & 0xE0) == 0xC0 ? 2 : (*u & 0xF0) == 0xE0 ? 3 : (*u & 0xF8) == 0xF0 ? 4 : 0;
    if (!len || (len == 2 && *u < 0xC2))
      return 0;
    for (int i = 1; i < len; i++) {
      if (!u[i])
        return 1;   /* cut short at the end */
      if ((u[i] & 0xC0) != 0x80)
        return 0;
    }
    u += len;
  }
  return 1;
}

/* The sub call stack: each frame returns to just after a CALL of its sub,
 * from a block of the unit that called it, down to the main program; the
 * restart block lies in the innermost sub. */
static void check_frames(struct chk *c, const struct state_payload *pl)
{
  const struct program *p = c->p;
  char what[64];
  unsigned unit = 0;   /* the unit the next call is made from */
  for (int i = 0; i < pl->depth && !c->bad; i++) {
    const struct vm_frame *f = &pl->frames[i];
    long sb = block_starting(p, f->start);
    uint32_t call = f->ret >= 1 && f->ret <= p->ncode ? p->code[f->ret - 1] : 0;
    if (f->ret == 0 || f->ret > p->ncode || (INS_OP(call) != OP_CALL && INS_OP(call) != OP_CCALL) || sb < 0 ||
        INS_A(call) != (uint32_t)sb) {   /* a call's operand is the sub's first block */
      refuse(c, "sub call %d returns to code address %u, which does not follow a call of the sub at %u", i + 1,
             f->ret, f->start);
      break;
    }
    size_t cb = prog_block_at(p, f->ret - 1);
    if (f->block != cb || p->blocks[cb].unit != unit) {
      refuse(c, "sub call %d is made from block index %u, not from a block of the %s", i + 1, f->block,
             unit ? "calling sub" : "main program");
      break;
    }
    snprintf(what, sizeof what, "sub call %d repeats left", i + 1);
    ints(c, what, f->left, 0, H_MAX - 1);
    snprintf(what, sizeof what, "sub call %d saved F", i + 1);
    if (p->saved_reg >= 0)
      range(c, what, f->saved, 0, F_MAX, 1);
    else
      range(c, what, f->saved, 0, 0, 0);
    snprintf(what, sizeof what, "sub call %d jump condition", i + 1);
    ints(c, what, f->jflag, 0, 1);
    unit = p->blocks[sb].unit;
  }
  if (!c->bad && p->blocks[pl->block].unit != unit)
    refuse(c, "restart block N%u is not in the %s the call stack ends in", p->blocks[pl->block].number,
           unit ? "sub" : "main program");
}

static void check_payload(struct chk *c, const struct state_payload *pl)
{
  const struct program *p = c->p;
  char what[64];
  /* where the run goes on: an M15 block of this program */
  if (pl->block >= p->nblocks) {
    refuse(c, "restart block is index %u, but the program has %zu blocks", pl->block, p->nblocks);
    return;
  }
  const struct prog_block *b = &p->blocks[pl->block];
  if (!((kp_attr(p, pl->block)->m >> 15) & 1))
    refuse(c, "restart block (line %u, N%u) has no M15", b->line, b->number);
  if (pl->pc != b->code)
    refuse(c, "code address is %u, not %u where the restart block starts", pl->pc, b->code);
  if (pl->blocks > STATE_BLOCKS_MAX)
    refuse(c, "count of executed blocks is %llu, over 2^53", (unsigned long long)pl->blocks);
  ints(c, "sub call depth", pl->depth, 0, p->lim.depth < VM_DEPTH_MAX ? p->lim.depth : VM_DEPTH_MAX);
  if (!c->bad)
    check_frames(c, pl);
  /* parameters and the machine's registers */
  for (int r = 0; r <= 113; r++) {
    snprintf(what, sizeof what, "R%d", r);
    range(c, what, pl->reg[r], -R_MAX, R_MAX, 0);
  }
  range(c, "D1", pl->reg[REG_D1], 0, D1_MAX, 0);
  range(c, "TK", pl->reg[REG_TK], -R_MAX, R_MAX, 0);
  range(c, "UG", pl->reg[REG_UG], -R_MAX, R_MAX, 0);
  range(c, "F", pl->reg[REG_F], 0, F_MAX, 1);
  for (int r = REG_F + 1; r < VM_NREG; r++) {
    snprintf(what, sizeof what, "unused register %d", r);
    range(c, what, pl->reg[r], 0, 0, 0);
  }
  /* the program's arrays, then what it has not: 0 */
  const int narr = (int)p->lim.arrays, ncell = (int)p->lim.cells;
  for (int a = 0; a < VM_ARRAYS_MAX; a++) {
    const struct vm_array *ar = &pl->arr[a];
    char v[40];
    if (a >= narr) {
      int i = 0;
      while (i < VM_CELLS_MAX && ar->cell[i] == 0)
        i++;
      if (ar->ptr || ar->len || i < VM_CELLS_MAX)
        refuse(c, "array %d is not empty, and the program has %d array%s", a + 1, narr, narr == 1 ? "" : "s");
      continue;
    }
    snprintf(what, sizeof what, "array %d pointer", a + 1);
    ints(c, what, ar->ptr, 0, ncell);
    snprintf(what, sizeof what, "array %d length", a + 1);
    ints(c, what, ar->len, 0, ncell);
    for (int i = 0; i < VM_CELLS_MAX; i++) {
      snprintf(what, sizeof what, "array %d cell %d", a + 1, i);
      if (i >= ncell && ar->cell[i] != 0)
        refuse(c, "%s is %s, past the array's last cell %d", what, num(v, sizeof v, ar->cell[i]), ncell - 1);
      else if (i < ar->len || ar->len < 0)
        range(c, what, ar->cell[i], -R_MAX, R_MAX, 0);
      else if (ar->cell[i] != 0)   /* past the length a cell is always 0 */
        refuse(c, "%s is %s, past the array's length %d", what, num(v, sizeof v, ar->cell[i]), ar->len);
    }
  }
  /* the machine */
  for (int a = 0; a < 4; a++)
    if (pl->pos[a] < -STATE_POS_MAX || pl->pos[a] > STATE_POS_MAX)
      refuse(c, "%c position is %lld discretes, beyond +-%lld", "XYZA"[a], (long long)pl->pos[a], STATE_POS_MAX);
  range(c, "time", pl->t, 0, STATE_TIME_MAX, 0);
  ints(c, "wheel state", pl->wheel, 0, 2);
  ints(c, "feed override", pl->override_pct, 0, 150);
  ints(c, "M25/M26 override switch", pl->override_allowed, 0, 1);
  ints(c, "M22/M23 correction switch", pl->corr_allowed, 0, 1);
  /* the plugins' records: each one named once, within its buffer */
  if (pl->nplug > STATE_PLUGS)
    refuse(c, "plugin count is %u, not 0-%d", pl->nplug, STATE_PLUGS);
  for (uint32_t k = 0; k < pl->nplug && !c->bad; k++) {
    const char *name = pl->plug[k].name;
    size_t nl = strnlen(name, sizeof pl->plug[k].name);
    if (nl == 0 || nl == sizeof pl->plug[k].name)
      refuse(c, "plugin %u's name is %s", k + 1, nl ? "not terminated" : "empty");
    else if (pl->plug[k].len > STATE_PLUG_MAX)
      refuse(c, "%s plugin's record is %u bytes, over its %d-byte buffer", name, pl->plug[k].len, STATE_PLUG_MAX);
    for (uint32_t j = 0; j < k && !c->bad; j++)
      if (strncmp(pl->plug[j].name, name, sizeof pl->plug[k].name) == 0)
        refuse(c, "%s plugin's record comes twice", name);
  }
  /* the display */
  ints(c, "P3 display switch", pl->p3, 0, 1);
  ints(c, "G29 line count", pl->np3, 0, SCR_WORK);
  for (int i = 0; i < pl->np3 && i < SCR_WORK && !c->bad; i++) {
    snprintf(what, sizeof what, "G29 line %d parameter", i + 1);
    ints(c, what, pl->p3l[i].reg, -1, 113);
    for (int k = 0; k < SCR_COLS; k++) {
      uint32_t ch = pl->p3l[i].ch[k];
      if (ch > 0x10FFFF || (ch >= 0xD800 && ch <= 0xDFFF)) {
        refuse(c, "G29 line %d holds U+%X, not a character", i + 1, (unsigned)ch);
        break;
      }
    }
  }
  if (!memchr(pl->dirtext, 0, sizeof pl->dirtext)) {
    refuse(c, "directive text is not terminated");
  } else if (pl->directive) {
    /* an M18 of this program, shown as screen_set_directive keeps it */
    int found = 0;
    for (size_t k = 0; k < p->nblocks && !found; k++)
      found = kp_more(p, kp_attr(p, k))->m18 == pl->directive;
    char want[sizeof pl->dirtext];
    if (found)
      snprintf(want, sizeof want, "%s", kp_str(p, pl->directive));
    if (!found)
      refuse(c, "directive is text %u, which no M18 of this program shows", pl->directive);
    else if (strcmp(want, pl->dirtext) != 0)
      refuse(c, "directive text is not that of its M18");
  } else if (!utf8_ok(pl->dirtext)) {
    refuse(c, "directive text is not UTF-8");
  }
}

int state_restore(struct session *s, const void *data, size_t len, const char *shown, uint64_t prog_hash,
                  char *err, size_t n)
{
  struct state_header h;
  if (len < sizeof h || (memcpy(&h, data, sizeof h), memcmp(h.magic, STATE_MAGIC, 8) != 0)) {
    snprintf(err, n, "%s is not an s42 restart state", shown);
    return -1;
  }
  if (h.version != STATE_VERSION || h.size != sizeof(struct state_payload)) {
    snprintf(err, n, "%s was written by another version of s42", shown);
    return -1;
  }
  struct state_payload *pl = malloc(sizeof *pl);
  if (!pl) {
    snprintf(err, n, "out of memory");
    return -1;
  }
  int rc = -1;
  if (len != sizeof h + sizeof *pl ||
      (memcpy(pl, (const char *)data + sizeof h, sizeof *pl), state_hash(pl, sizeof *pl) != h.sum)) {
    snprintf(err, n, "%s is damaged (checksum)", shown);
    goto out;
  }
  if (pl->prog_hash != prog_hash) {
    snprintf(err, n, "the program text changed since the restart point was saved in %s", shown);
    goto out;
  }
  struct chk c = {s->p, shown, err, n, 0};
  check_payload(&c, pl);
  if (c.bad)
    goto out;
  struct vm *vm = &s->vm;
  vm->pc = pl->pc;
  vm->cur = pl->block;
  vm->blocks = pl->blocks;
  memcpy(vm->reg, pl->reg, sizeof vm->reg);
  memcpy(vm->arr, pl->arr, sizeof vm->arr);
  vm->depth = pl->depth;
  for (int i = 0; i < pl->depth; i++)
    vm->frames[i] = pl->frames[i];
  memcpy(s->m.pos, pl->pos, sizeof s->m.pos);
  s->m.t = pl->t;
  s->m.wheel = pl->wheel;
  s->m.override_pct = pl->override_pct;
  s->m.override_allowed = pl->override_allowed;
  s->m.corr_allowed = pl->corr_allowed;
  s->scr.p3 = pl->p3;
  s->scr.np3 = pl->np3;
  memcpy(s->scr.p3l, pl->p3l, sizeof s->scr.p3l);
  s->directive = pl->directive;
  if (pl->dirtext[0])
    screen_set_directive(&s->scr, pl->dirtext);
  s->m15_seen = 1;
  rc = 0;
  for (uint32_t k = 0; k < pl->nplug && rc == 0; k++)
    rc = sess_plugin_restore(s, pl->plug[k].name, pl->plug[k].data, pl->plug[k].len, err, n);
out:
  free(pl);
  return rc;
}

int state_load(struct session *s, const char *path, uint64_t prog_hash, char *err, size_t n)
{
  char *data;
  size_t len;
  /* one byte more than a state holds: a longer file is damaged, not cut */
  int r = file_read_all(path, FILE_REGULAR, sizeof(struct state_header) + sizeof(struct state_payload) + 1, &data,
                        &len, err, n);
  if (r == -2) {
    snprintf(err, n, "%s is damaged (checksum)", path);
    return -1;
  }
  if (r) {
    char why[400];
    snprintf(why, sizeof why, "%s", err);
    snprintf(err, n, "no restart state: %s", why);
    return -1;
  }
  r = state_restore(s, data, len, path, prog_hash, err, n);
  free(data);
  return r;
}
