/* forge: hand-edit fields of an M15 restart state and recompute its
 * checksum, as someone editing the file on purpose would -- for
 * tests/restart/run.sh, which checks that every such field is refused.
 *   forge STATE FIELD VALUE [FIELD VALUE ...]
 * FIELD: block pc blocks depth t wheel override override_allowed
 * corr_allowed nplug p3 np3 directive dirtext prog_hash, r.N, arr.K.ptr
 * arr.K.len arr.K.cell.I (K 1-2), frame.I.ret|start|left|block|saved|jflag
 * (I from 1), pos.X|Y|Z|A, plug.K.name|len|byte.I, p3l.I.reg|ch.J.
 * VALUE: a number (nan and inf too) or, for names and texts, a string. */
#include "state.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static struct state_payload pl;

static int fail(const char *what, const char *f)
{
  fprintf(stderr, "forge: %s: %s\n", what, f);
  return 2;
}

/* Set one field; 0, or -1 when FIELD is not known. */
static int set(const char *f, const char *v)
{
  double d = strtod(v, NULL);
  long long i = strtoll(v, NULL, 0);
  int a, b, c;
  char sub[16], ax;
#define INT(name, lv) if (strcmp(f, name) == 0) { lv = i; return 0; }
  INT("block", pl.block)
  INT("pc", pl.pc)
  INT("blocks", pl.blocks)
  INT("depth", pl.depth)
  INT("wheel", pl.wheel)
  INT("override", pl.override_pct)
  INT("override_allowed", pl.override_allowed)
  INT("corr_allowed", pl.corr_allowed)
  INT("nplug", pl.nplug)
  INT("p3", pl.p3)
  INT("np3", pl.np3)
  INT("directive", pl.directive)
  INT("prog_hash", pl.prog_hash)
#undef INT
  if (strcmp(f, "t") == 0) { pl.t = d; return 0; }
  if (strcmp(f, "dirtext") == 0) { snprintf(pl.dirtext, sizeof pl.dirtext, "%s", v); return 0; }
  if (sscanf(f, "r.%d", &a) == 1 && a >= 0 && a < VM_NREG) { pl.reg[a] = d; return 0; }
  if (sscanf(f, "arr.%d.cell.%d", &a, &b) == 2 && a >= 1 && a <= 2 && b >= 0 && b < VM_CELLS_MAX) {
    pl.arr[a - 1].cell[b] = d;
    return 0;
  }
  if (sscanf(f, "arr.%d.%15s", &a, sub) == 2 && a >= 1 && a <= 2) {
    if (strcmp(sub, "ptr") == 0) { pl.arr[a - 1].ptr = (int)i; return 0; }
    if (strcmp(sub, "len") == 0) { pl.arr[a - 1].len = (int)i; return 0; }
    return -1;
  }
  if (sscanf(f, "frame.%d.%15s", &a, sub) == 2 && a >= 1 && a <= VM_DEPTH_MAX) {
    struct vm_frame *fr = &pl.frames[a - 1];
    if (strcmp(sub, "ret") == 0) { fr->ret = (uint32_t)i; return 0; }
    if (strcmp(sub, "start") == 0) { fr->start = (uint32_t)i; return 0; }
    if (strcmp(sub, "left") == 0) { fr->left = (uint32_t)i; return 0; }
    if (strcmp(sub, "block") == 0) { fr->block = (uint32_t)i; return 0; }
    if (strcmp(sub, "saved") == 0) { fr->saved = d; return 0; }
    if (strcmp(sub, "jflag") == 0) { fr->jflag = (uint8_t)i; return 0; }
    return -1;
  }
  if (sscanf(f, "pos.%c", &ax) == 1 && strchr("XYZA", ax) && ax) {
    pl.pos[strchr("XYZA", ax) - "XYZA"] = i;
    return 0;
  }
  if (sscanf(f, "plug.%d.byte.%d", &a, &b) == 2 && a >= 1 && a <= STATE_PLUGS && b >= 0 && b < STATE_PLUG_MAX) {
    pl.plug[a - 1].data[b] = (unsigned char)i;
    return 0;
  }
  if (sscanf(f, "plug.%d.%15s", &a, sub) == 2 && a >= 1 && a <= STATE_PLUGS) {
    if (strcmp(sub, "len") == 0) { pl.plug[a - 1].len = (uint32_t)i; return 0; }
    if (strcmp(sub, "name") == 0) {
      /* all 48 bytes when the value is that long: no terminating NUL */
      memset(pl.plug[a - 1].name, 0, sizeof pl.plug[a - 1].name);
      memcpy(pl.plug[a - 1].name, v, strnlen(v, sizeof pl.plug[a - 1].name));
      return 0;
    }
    return -1;
  }
  if (sscanf(f, "p3l.%d.ch.%d", &a, &c) == 2 && a >= 1 && a <= SCR_WORK && c >= 0 && c < SCR_COLS) {
    pl.p3l[a - 1].ch[c] = (uint32_t)i;
    return 0;
  }
  if (sscanf(f, "p3l.%d.reg", &a) == 1 && a >= 1 && a <= SCR_WORK) {
    pl.p3l[a - 1].reg = (int)i;
    return 0;
  }
  return -1;
}

int main(int argc, char **argv)
{
  if (argc < 4 || argc % 2) {
    fprintf(stderr, "usage: forge STATE FIELD VALUE [FIELD VALUE ...]\n");
    return 2;
  }
  FILE *f = fopen(argv[1], "rb");
  struct state_header h;
  if (!f)
    return fail("cannot open", argv[1]);
  int ok = fread(&h, sizeof h, 1, f) == 1 && fread(&pl, sizeof pl, 1, f) == 1;
  fclose(f);
  if (!ok || memcmp(h.magic, STATE_MAGIC, 8) != 0 || h.size != sizeof pl)
    return fail("not a restart state of this layout", argv[1]);
  for (int i = 2; i < argc; i += 2)
    if (set(argv[i], argv[i + 1]))
      return fail("unknown field", argv[i]);
  h.sum = state_hash(&pl, sizeof pl);
  f = fopen(argv[1], "wb");
  if (!f || fwrite(&h, sizeof h, 1, f) != 1 || fwrite(&pl, sizeof pl, 1, f) != 1 || fclose(f) != 0)
    return fail("cannot write", argv[1]);
  return 0;
}
