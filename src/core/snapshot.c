/* The restart snapshot (src/core/snapshot.h, mrun.h). */
#include "snapshot.h"
#include "atomic.h"
#include "mrun.h"
#include "opcodes.h"
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

uint64_t mrun_hash(const void *data, size_t n)
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
  else if (st.st_size < 8 || read(fd, magic, 8) != 8 || memcmp(magic, SNAP_MAGIC, 8) != 0)
    snprintf(err, n, "%s is not an s42 restart state: it is not replaced (remove it, or choose another --state)",
             path);
  else
    rc = 0;
  close(fd);
  return rc;
}

/* A run that stopped between blocks goes on to the next block's start
 * (the committed block's jumps run, nothing of the machine moves), where a
 * snapshot can be taken.  0, or -1 when the program ended or failed first. */
static int to_block_start(struct mrun *r)
{
  if (r->at_start)
    return 0;
  int all = r->vm.start_all;
  r->vm.start_all = 1;
  enum vm_event ev = vm_run(&r->vm);
  r->vm.start_all = all;
  if (ev != VM_EV_START)
    return -1;
  r->at_start = 1;   /* the next mrun_run goes on at this block's start */
  return 0;
}

int mrun_save(struct mrun *r, const char *path, char *err, size_t n)
{
  if (!r->rt->save) {
    snprintf(err, n, "the %s keeps no restart state", r->rt->machine ? r->rt->machine : "machine");
    return -1;
  }
  if (r->state == MR_WAIT && r->wait != MRW_BLOCK && r->wait != MRW_STOP && !r->at_start) {
    snprintf(err, n, "the run stopped inside a block, which a restart cannot go on from");
    return -1;
  }
  if (check_target(path, err, n))
    return -1;
  if (to_block_start(r)) {
    snprintf(err, n, "the program ended: there is nothing to go on from");
    return -1;
  }
  struct snap_vm *v = calloc(1, sizeof *v);
  unsigned char *blob = malloc(SNAP_BLOB_MAX);
  if (!v || !blob) {
    free(v);
    free(blob);
    snprintf(err, n, "out of memory");
    return -1;
  }
  const struct vm *vm = &r->vm;
  v->prog_hash = r->cfg.prog_hash;
  v->block = vm->cur;
  v->pc = r->p->blocks[vm->cur].code;
  v->blocks = vm->blocks;
  memcpy(v->reg, vm->reg, sizeof v->reg);
  memcpy(v->arr, vm->arr, sizeof v->arr);
  v->depth = vm->depth;
  for (int i = 0; i < vm->depth; i++)
    v->frames[i] = vm->frames[i];
  memset(blob, 0, SNAP_BLOB_MAX);
  err[0] = 0;
  size_t len = r->rt->save(r, blob, SNAP_BLOB_MAX, err, n);
  if (len == 0 && err[0]) {
    free(v);
    free(blob);
    return -1;
  }
  if (len > SNAP_BLOB_MAX) {
    snprintf(err, n, "the machine's restart state is too large");
    free(v);
    free(blob);
    return -1;
  }
  v->blob_len = (uint32_t)len;
  struct snap_header h;
  memset(&h, 0, sizeof h);
  memcpy(h.magic, SNAP_MAGIC, 8);
  h.version = SNAP_VERSION;
  h.size = (uint32_t)(sizeof *v + len);
  /* the sum over both parts, as they lie in the file */
  uint64_t sum = 1469598103934665603ULL;
  const unsigned char *parts[2] = {(const unsigned char *)v, blob};
  size_t lens[2] = {sizeof *v, len};
  for (int k = 0; k < 2; k++)
    for (size_t i = 0; i < lens[k]; i++) {
      sum ^= parts[k][i];
      sum *= 1099511628211ULL;
    }
  h.sum = sum;
  struct iovec io[3] = {{&h, sizeof h}, {v, sizeof *v}, {blob, len}};
  /* one fsync a save (the file's); the directory's only when the save
   * makes the name (the first save into a new file): a later save that
   * the power cut takes back leaves the previous save's whole state, the
   * previous restart point (src/core/atomic.h) */
  int rc = atomic_write_flags(path, path, 0644, io, 3, ATOMIC_DIRSYNC_NEW, err, n);
  free(v);
  free(blob);
  return rc;
}

/* ---- checking a loaded record, field by field ---- */

void snap_refuse(struct snap_chk *c, const char *fmt, ...)
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

void snap_range(struct snap_chk *c, const char *what, double v, double lo, double hi, int whole)
{
  char b[40], l[24], h[24];
  if (!(v >= lo && v <= hi))
    snap_refuse(c, "%s is %s, not %s..%s", what, num(b, sizeof b, v), num(l, sizeof l, lo), num(h, sizeof h, hi));
  else if (whole && v != floor(v))
    snap_refuse(c, "%s is %s, not a whole number", what, num(b, sizeof b, v));
}

void snap_ints(struct snap_chk *c, const char *what, long long v, long long lo, long long hi)
{
  if (v < lo || v > hi)
    snap_refuse(c, lo < 0 ? "%s is %lld, not %lld..%lld" : "%s is %lld, not %lld-%lld", what, v, lo, hi);
}

int snap_utf8_ok(const char *s)
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

/* The block whose code starts exactly at pc, or -1. */
static long block_starting(const struct program *p, uint32_t pc)
{
  if (pc >= p->ncode || !p->nblocks)
    return -1;
  size_t b = prog_block_at(p, pc);
  return p->blocks[b].code == pc ? (long)b : -1;
}

/* Register k's name and range as the runtime gives them: 1 used, 0 unused. */
static int reg_of(const struct mrun *r, int k, char *name, size_t n, double *lo, double *hi, int *whole)
{
  *whole = 0;
  if (r->rt->reg_range)
    return r->rt->reg_range(r, k, name, n, lo, hi, whole);
  snprintf(name, n, "R%d", k);
  *lo = r->p->lim.param_lo;
  *hi = r->p->lim.param_hi;
  return 1;
}

/* The sub call stack: each frame returns to just after a CALL of its sub,
 * from a block of the unit that called it, down to the main program; the
 * restart block lies in the innermost sub. */
static void check_frames(struct snap_chk *c, const struct mrun *r, const struct snap_vm *v)
{
  const struct program *p = c->p;
  char what[64], name[24];
  unsigned unit = 0;   /* the unit the next call is made from */
  for (int i = 0; i < v->depth && !c->bad; i++) {
    const struct vm_frame *f = &v->frames[i];
    long sb = block_starting(p, f->start);
    uint32_t call = f->ret >= 1 && f->ret <= p->ncode ? p->code[f->ret - 1] : 0;
    if (f->ret == 0 || f->ret > p->ncode || (INS_OP(call) != OP_CALL && INS_OP(call) != OP_CCALL) || sb < 0 ||
        INS_A(call) != (uint32_t)sb) {   /* a call's operand is the sub's first block */
      snap_refuse(c, "sub call %d returns to code address %u, which does not follow a call of the sub at %u", i + 1,
                  f->ret, f->start);
      break;
    }
    size_t cb = prog_block_at(p, f->ret - 1);
    if (f->block != cb || p->blocks[cb].unit != unit) {
      snap_refuse(c, "sub call %d is made from block index %u, not from a block of the %s", i + 1, f->block,
                  unit ? "calling sub" : "main program");
      break;
    }
    snprintf(what, sizeof what, "sub call %d repeats left", i + 1);
    snap_ints(c, what, f->left, 0, r->rt->repeat_max ? (long long)r->rt->repeat_max - 1 : INT32_MAX);
    double lo = 0, hi = 0;
    int whole = 0;
    if (p->saved_reg >= 0 && reg_of(r, p->saved_reg, name, sizeof name, &lo, &hi, &whole)) {
      snprintf(what, sizeof what, "sub call %d saved %s", i + 1, name);
      snap_range(c, what, f->saved, lo, hi, whole);
    } else {
      snprintf(what, sizeof what, "sub call %d saved value", i + 1);
      snap_range(c, what, f->saved, 0, 0, 0);
    }
    snprintf(what, sizeof what, "sub call %d jump condition", i + 1);
    snap_ints(c, what, f->jflag, 0, 1);
    unit = p->blocks[sb].unit;
  }
  if (!c->bad && p->blocks[v->block].unit != unit)
    snap_refuse(c, "restart block N%u is not in the %s the call stack ends in", p->blocks[v->block].number,
                unit ? "sub" : "main program");
}

static void check_vm(struct snap_chk *c, const struct mrun *r, const struct snap_vm *v)
{
  const struct program *p = c->p;
  char what[64];
  /* where the run goes on: a block start of this program (a restart point) */
  if (v->block >= p->nblocks) {
    snap_refuse(c, "restart block is index %u, but the program has %zu blocks", v->block, p->nblocks);
    return;
  }
  const struct prog_block *b = &p->blocks[v->block];
  if (r->rt->restart_word && !(r->rt->restart_point && r->rt->restart_point(r, v->block)))
    snap_refuse(c, "restart block (line %u, N%u) has no %s", b->line, b->number, r->rt->restart_word);
  if (v->pc != b->code)
    snap_refuse(c, "code address is %u, not %u where the restart block starts", v->pc, b->code);
  if (v->blocks > SNAP_BLOCKS_MAX)
    snap_refuse(c, "count of executed blocks is %llu, over 2^53", (unsigned long long)v->blocks);
  snap_ints(c, "sub call depth", v->depth, 0, p->lim.depth < VM_DEPTH_MAX ? p->lim.depth : VM_DEPTH_MAX);
  if (!c->bad)
    check_frames(c, r, v);
  /* the registers, by the runtime's names and ranges; unused ones 0 */
  for (int k = 0; k < VM_NREG; k++) {
    char name[24];
    double lo, hi;
    int whole;
    if (reg_of(r, k, name, sizeof name, &lo, &hi, &whole)) {
      snap_range(c, name, v->reg[k], lo, hi, whole);
    } else {
      snprintf(what, sizeof what, "unused register %d", k);
      snap_range(c, what, v->reg[k], 0, 0, 0);
    }
  }
  /* the program's arrays, then what it has not: 0 */
  const int narr = (int)p->lim.arrays, ncell = (int)p->lim.cells;
  for (int a = 0; a < VM_ARRAYS_MAX; a++) {
    const struct vm_array *ar = &v->arr[a];
    char w[40];
    if (a >= narr) {
      int i = 0;
      while (i < VM_CELLS_MAX && ar->cell[i] == 0)
        i++;
      if (ar->ptr || ar->len || i < VM_CELLS_MAX)
        snap_refuse(c, "array %d is not empty, and the program has %d array%s", a + 1, narr, narr == 1 ? "" : "s");
      continue;
    }
    snprintf(what, sizeof what, "array %d pointer", a + 1);
    snap_ints(c, what, ar->ptr, 0, ncell);
    snprintf(what, sizeof what, "array %d length", a + 1);
    snap_ints(c, what, ar->len, 0, ncell);
    for (int i = 0; i < VM_CELLS_MAX; i++) {
      snprintf(what, sizeof what, "array %d cell %d", a + 1, i);
      if (i >= ncell && ar->cell[i] != 0)
        snap_refuse(c, "%s is %s, past the array's last cell %d", what, num(w, sizeof w, ar->cell[i]), ncell - 1);
      else if (i < ar->len || ar->len < 0)
        snap_range(c, what, ar->cell[i], p->lim.cell_lo, p->lim.cell_hi, 0);
      else if (ar->cell[i] != 0)   /* past the length a cell is always 0 */
        snap_refuse(c, "%s is %s, past the array's length %d", what, num(w, sizeof w, ar->cell[i]), ar->len);
    }
  }
}

int mrun_restore_bytes(struct mrun *r, const void *data, size_t len, const char *shown, char *err, size_t n)
{
  struct snap_header h;
  if (len < sizeof h || (memcpy(&h, data, sizeof h), memcmp(h.magic, SNAP_MAGIC, 8) != 0)) {
    snprintf(err, n, "%s is not an s42 restart state", shown);
    return -1;
  }
  if (h.version != SNAP_VERSION || h.size < sizeof(struct snap_vm) ||
      h.size - sizeof(struct snap_vm) > SNAP_BLOB_MAX) {
    snprintf(err, n, "%s was written by another version of s42", shown);
    return -1;
  }
  if (len != sizeof h + h.size || mrun_hash((const char *)data + sizeof h, h.size) != h.sum) {
    snprintf(err, n, "%s is damaged (checksum)", shown);
    return -1;
  }
  struct snap_vm v;
  memcpy(&v, (const char *)data + sizeof h, sizeof v);
  if (v.blob_len != h.size - sizeof v) {
    snprintf(err, n, "%s is damaged (checksum)", shown);
    return -1;
  }
  if (v.prog_hash != r->cfg.prog_hash) {
    snprintf(err, n, "the program text changed since the restart point was saved in %s", shown);
    return -1;
  }
  if (!r->rt->restore) {
    snprintf(err, n, "the %s keeps no restart state", r->rt->machine ? r->rt->machine : "machine");
    return -1;
  }
  struct snap_chk c = {r->p, shown, err, n, 0};
  check_vm(&c, r, &v);
  if (c.bad)
    return -1;
  struct vm *vm = &r->vm;
  vm->pc = v.pc;
  vm->cur = v.block;
  vm->blocks = v.blocks;
  memcpy(vm->reg, v.reg, sizeof vm->reg);
  memcpy(vm->arr, v.arr, sizeof vm->arr);
  vm->depth = v.depth;
  for (int i = 0; i < v.depth; i++)
    vm->frames[i] = v.frames[i];
  if (r->rt->restore(r, (const char *)data + sizeof h + sizeof v, v.blob_len, shown, err, n))
    return -1;
  r->go = 1;   /* the restart's Пуск starts its block */
  return 0;
}

int mrun_restore(struct mrun *r, const char *path, char *err, size_t n)
{
  char *data;
  size_t len;
  /* one byte more than a snapshot holds: a longer file is damaged, not cut */
  int rc = file_read_all(path, FILE_REGULAR, sizeof(struct snap_header) + sizeof(struct snap_vm) + SNAP_BLOB_MAX + 1,
                         &data, &len, err, n);
  if (rc == -2) {
    snprintf(err, n, "%s is damaged (checksum)", path);
    return -1;
  }
  if (rc) {
    char why[400];
    snprintf(why, sizeof why, "%s", err);
    snprintf(err, n, "no restart state: %s", why);
    return -1;
  }
  rc = mrun_restore_bytes(r, data, len, path, err, n);
  free(data);
  return rc;
}
