/* The M15 restart state file (src/state.h). */
#include "state.h"
#include "atomic.h"
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAGIC "S42STATE"
#define VERSION 3u   /* 2: code addresses of the superinstructions; plugin states; 3: CMPCK/CMPCR */
#define PLUG_STATES 8
#define PLUG_STATE_MAX 512

/* Everything a restart needs, in one fixed record (zeroed before filling,
 * so the checksum covers no stray padding bytes). */
struct payload {
  uint64_t prog_hash;
  uint32_t block, pc;
  uint64_t blocks;
  double reg[VM_NREG];
  struct vm_array arr[2];
  int32_t depth;
  struct vm_frame frames[VM_MAXDEPTH];
  int64_t pos[4];
  double t;
  int32_t wheel, override_pct, override_allowed, corr_allowed;
  uint32_t nplug;       /* the plugins' own states (oscillation) */
  struct {
    char name[48];
    uint32_t len;
    unsigned char data[PLUG_STATE_MAX];
  } plug[PLUG_STATES];
  int32_t p3, np3;
  struct scr_p3 p3l[SCR_WORK];
  uint32_t directive;
  char dirtext[SCR_COLS * 4 + 1];
};

struct header {
  char magic[8];
  uint32_t version, size;
  uint64_t sum;
};

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
  else if (st.st_size < 8 || read(fd, magic, 8) != 8 || memcmp(magic, MAGIC, 8) != 0)
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
  struct payload *pl = calloc(1, sizeof *pl);
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
    int r = pl->nplug < PLUG_STATES
              ? sess_plugin_state(s, k, pl->plug[pl->nplug].name, sizeof pl->plug[0].name,
                                  pl->plug[pl->nplug].data, PLUG_STATE_MAX, &len)
              : 1;
    if (r == 1)
      break;
    if (r < 0 || pl->nplug == PLUG_STATES) {
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

  struct header h;
  memset(&h, 0, sizeof h);
  memcpy(h.magic, MAGIC, 8);
  h.version = VERSION;
  h.size = (uint32_t)sizeof *pl;
  h.sum = state_hash(pl, sizeof *pl);

  struct iovec v[2] = {{&h, sizeof h}, {pl, sizeof *pl}};
  int rc = atomic_write(path, path, 0644, v, 2, err, n);
  free(pl);
  return rc;
}

static int frames_fit(const struct program *p, const struct payload *pl)
{
  for (int i = 0; i < pl->depth; i++)
    if (pl->frames[i].ret >= p->ncode || pl->frames[i].start >= p->ncode || pl->frames[i].block >= p->nblocks)
      return 0;
  return 1;
}

int state_load(struct session *s, const char *path, uint64_t prog_hash, char *err, size_t n)
{
  /* a regular file only: a FIFO is refused, not waited on; one byte more
   * than a state holds is read, so a longer file is damaged, not cut */
  char *data;
  size_t len;
  int r = file_read_all(path, FILE_REGULAR, sizeof(struct header) + sizeof(struct payload) + 1, &data, &len, err, n);
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
  struct header h;
  struct payload *pl = malloc(sizeof *pl);
  int rc = -1;
  if (!pl) {
    snprintf(err, n, "out of memory");
  } else if (len < sizeof h || (memcpy(&h, data, sizeof h), memcmp(h.magic, MAGIC, 8) != 0)) {
    snprintf(err, n, "%s is not an s42 restart state", path);
  } else if (h.version != VERSION || h.size != sizeof *pl) {
    snprintf(err, n, "%s was written by another version of s42", path);
  } else if (len != sizeof h + sizeof *pl || (memcpy(pl, data + sizeof h, sizeof *pl),
                                          state_hash(pl, sizeof *pl) != h.sum)) {
    snprintf(err, n, "%s is damaged (checksum)", path);
  } else if (pl->prog_hash != prog_hash) {
    snprintf(err, n, "the program text changed since the restart point was saved in %s", path);
  } else if (pl->block >= s->p->nblocks || pl->pc != s->p->blocks[pl->block].code || pl->depth < 0 ||
             pl->depth > VM_MAXDEPTH || pl->nplug > PLUG_STATES || pl->np3 < 0 || pl->np3 > SCR_WORK || pl->wheel < 0 || pl->wheel > 2 ||
             !frames_fit(s->p, pl)) {
    snprintf(err, n, "%s does not fit this program", path);
  } else {
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
    pl->dirtext[sizeof pl->dirtext - 1] = 0;
    if (pl->dirtext[0])
      scr_set_directive(&s->scr, pl->dirtext);
    s->m15_seen = 1;
    rc = 0;
    for (uint32_t k = 0; k < pl->nplug && rc == 0; k++) {
      pl->plug[k].name[sizeof pl->plug[k].name - 1] = 0;
      rc = sess_plugin_restore(s, pl->plug[k].name, pl->plug[k].data, pl->plug[k].len, err, n);
    }
  }
  free(data);
  free(pl);
  return rc;
}
