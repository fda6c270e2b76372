/* The 2С42's part of the restart snapshot (kprun.h; core keeps the VM's,
 * src/core/snapshot.h): the grinder at the M15 block's start, the plugins'
 * own states and what the screen shows that the program text does not say.
 * Every field is checked against the program and its range on the way
 * back (README "Restart from M15" lists the bounds). */
#include "kprun.h"
#include "ast.h"
#include "snapshot.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#define R_MAX 9999999.0      /* a parameter, an array cell, TK, UG */
#define D1_MAX 400000.0
#define F_MAX 6000.0
#define KP_PLUGS 8
#define KP_PLUG_MAX 512

struct kp_blob {
  int64_t pos[4];
  double t;
  int32_t wheel, override_pct, override_allowed, corr_allowed;
  uint32_t nplug;           /* the plugins' own states (oscillation) */
  struct {
    char name[48];
    uint32_t len;
    unsigned char data[KP_PLUG_MAX];
  } plug[KP_PLUGS];
  int32_t p3, np3;
  struct screen_p3 p3l[SCR_WORK];
  uint32_t directive;
  char dirtext[SCR_COLS * 4 + 1];
};

int kp_reg_range(const struct mrun *r, int k, char *name, size_t n, double *lo, double *hi, int *whole)
{
  (void)r;
  *whole = 0;
  if (k <= 113) {
    snprintf(name, n, "R%d", k);
    *lo = -R_MAX;
    *hi = R_MAX;
    return 1;
  }
  switch (k) {
  case REG_D1: snprintf(name, n, "D1"); *lo = 0; *hi = D1_MAX; return 1;
  case REG_TK: snprintf(name, n, "TK"); *lo = -R_MAX; *hi = R_MAX; return 1;
  case REG_UG: snprintf(name, n, "UG"); *lo = -R_MAX; *hi = R_MAX; return 1;
  case REG_F: snprintf(name, n, "F"); *lo = 0; *hi = F_MAX; *whole = 1; return 1;
  default: return 0;
  }
}

size_t kp_save(const struct mrun *r, void *buf, size_t cap, char *err, size_t n)
{
  const struct kp_state *s = kp_st(r);
  struct kp_blob *b = buf;
  if (cap < sizeof *b)
    return sizeof *b;
  memset(b, 0, sizeof *b);
  memcpy(b->pos, s->m.pos, sizeof b->pos);
  b->t = s->m.t;
  b->wheel = s->m.wheel;
  b->override_pct = s->m.override_pct;
  b->override_allowed = s->m.override_allowed;
  b->corr_allowed = s->m.corr_allowed;
  for (int k = 0;; k++) {
    size_t len = 0;
    int e = b->nplug < KP_PLUGS
              ? kp_plugin_state(r, k, b->plug[b->nplug].name, sizeof b->plug[0].name, b->plug[b->nplug].data,
                                KP_PLUG_MAX, &len)
              : 1;
    if (e == 1)
      break;
    if (e == -2) {   /* its save() crashed: no state, rather than one without it */
      const struct plug_set *ps = kp_st(r)->plugins;
      snprintf(err, n, "%s", ps->v[ps->crashed].err);
      return 0;
    }
    if (e < 0 || b->nplug == KP_PLUGS) {
      snprintf(err, n, "a plugin's restart state is too large");
      return 0;
    }
    if (e == 0)
      b->plug[b->nplug++].len = (uint32_t)len;
  }
  b->p3 = s->scr.p3;
  b->np3 = s->scr.np3;
  memcpy(b->p3l, s->scr.p3l, sizeof b->p3l);
  b->directive = s->directive;
  memcpy(b->dirtext, s->scr.dirtext, sizeof b->dirtext);
  return sizeof *b;
}

static void check(struct snap_chk *c, const struct kp_blob *b)
{
  const struct program *p = c->p;
  char what[64];
  for (int a = 0; a < 4; a++)
    if (b->pos[a] < -SNAP_POS_MAX || b->pos[a] > SNAP_POS_MAX)
      snap_refuse(c, "%c position is %lld discretes, beyond +-%lld", "XYZA"[a], (long long)b->pos[a], SNAP_POS_MAX);
  snap_range(c, "time", b->t, 0, SNAP_TIME_MAX, 0);
  snap_ints(c, "wheel state", b->wheel, 0, 2);
  snap_ints(c, "feed override", b->override_pct, 0, 150);
  snap_ints(c, "M25/M26 override switch", b->override_allowed, 0, 1);
  snap_ints(c, "M22/M23 correction switch", b->corr_allowed, 0, 1);
  /* the plugins' records: each one named once, within its buffer */
  if (b->nplug > KP_PLUGS)
    snap_refuse(c, "plugin count is %u, not 0-%d", b->nplug, KP_PLUGS);
  for (uint32_t k = 0; k < b->nplug && !c->bad; k++) {
    const char *name = b->plug[k].name;
    size_t nl = strnlen(name, sizeof b->plug[k].name);
    if (nl == 0 || nl == sizeof b->plug[k].name)
      snap_refuse(c, "plugin %u's name is %s", k + 1, nl ? "not terminated" : "empty");
    else if (b->plug[k].len > KP_PLUG_MAX)
      snap_refuse(c, "%s plugin's record is %u bytes, over its %d-byte buffer", name, b->plug[k].len, KP_PLUG_MAX);
    for (uint32_t j = 0; j < k && !c->bad; j++)
      if (strncmp(b->plug[j].name, name, sizeof b->plug[k].name) == 0)
        snap_refuse(c, "%s plugin's record comes twice", name);
  }
  /* the display */
  snap_ints(c, "P3 display switch", b->p3, 0, 1);
  snap_ints(c, "G29 line count", b->np3, 0, SCR_WORK);
  for (int i = 0; i < b->np3 && i < SCR_WORK && !c->bad; i++) {
    snprintf(what, sizeof what, "G29 line %d parameter", i + 1);
    snap_ints(c, what, b->p3l[i].reg, -1, 113);
    for (int k = 0; k < SCR_COLS; k++) {
      uint32_t ch = b->p3l[i].ch[k];
      if (ch > 0x10FFFF || (ch >= 0xD800 && ch <= 0xDFFF)) {
        snap_refuse(c, "G29 line %d holds U+%X, not a character", i + 1, (unsigned)ch);
        break;
      }
    }
  }
  if (!memchr(b->dirtext, 0, sizeof b->dirtext)) {
    snap_refuse(c, "directive text is not terminated");
  } else if (b->directive) {
    /* an M18 of this program, shown as screen_set_directive keeps it */
    int found = 0;
    for (size_t k = 0; k < p->nblocks && !found; k++)
      found = kp_more(p, kp_attr(p, k))->m18 == b->directive;
    char want[sizeof b->dirtext];
    if (found)
      snprintf(want, sizeof want, "%s", kp_str(p, b->directive));
    if (!found)
      snap_refuse(c, "directive is text %u, which no M18 of this program shows", b->directive);
    else if (strcmp(want, b->dirtext) != 0)
      snap_refuse(c, "directive text is not that of its M18");
  } else if (!snap_utf8_ok(b->dirtext)) {
    snap_refuse(c, "directive text is not UTF-8");
  }
}

int kp_restore(struct mrun *r, const void *buf, size_t len, const char *shown, char *err, size_t n)
{
  struct kp_state *s = kp_st(r);
  static struct kp_blob b;   /* large; restores happen once, on one thread */
  if (len != sizeof b) {
    snprintf(err, n, "%s was written by another version of s42", shown);
    return -1;
  }
  memcpy(&b, buf, sizeof b);
  struct snap_chk c = {r->p, shown, err, n, 0};
  check(&c, &b);
  if (c.bad)
    return -1;
  memcpy(s->m.pos, b.pos, sizeof s->m.pos);
  s->m.t = b.t;
  s->m.wheel = b.wheel;
  s->m.override_pct = b.override_pct;
  r->override = b.override_pct;
  s->m.override_allowed = b.override_allowed;
  s->m.corr_allowed = b.corr_allowed;
  s->scr.p3 = b.p3;
  s->scr.np3 = b.np3;
  memcpy(s->scr.p3l, b.p3l, sizeof s->scr.p3l);
  s->directive = b.directive;
  if (b.dirtext[0])
    screen_set_directive(&s->scr, b.dirtext);
  s->m15_seen = 1;
  for (uint32_t k = 0; k < b.nplug; k++)
    if (kp_plugin_restore(r, b.plug[k].name, b.plug[k].data, b.plug[k].len, err, n))
      return -1;
  kp_restore_screen(r);
  return 0;
}

/* After a restart: the dialog area as the program's dialog left it before
 * the restart point (the G33 headings, each G27 line with the number its
 * G28 stored, now in the restored parameters).  The state keeps no screen
 * buffer: the program text and the parameters say what it held. */
void kp_restore_screen(struct mrun *r)
{
  const struct program *p = r->p;
  struct screen *sc = &kp_st(r)->scr;
  /* the main program's blocks before the restart block, or before the
   * call that leads to it */
  size_t upto = r->vm.cur;
  if (r->vm.depth > 0)
    upto = prog_block_at(p, r->vm.frames[0].ret);
  int p3 = sc->p3, open = 0;
  if (sc->nbuf)
    upto = 0;   /* the state brought the buffer itself */
  for (size_t b = 0; b < upto && b < p->nblocks; b++) {
    const struct kp_attr *at = kp_attr(p, b);
    const struct kp_more *mo = kp_more(p, at);
    if (p->blocks[b].unit != 0)
      continue;
    if ((at->m >> 29) & 1)
      sc->fixed = -1;
    if ((at->m >> 28) & 1)
      sc->at_fixed = 1;
    if ((at->g >> 33) & 1)
      screen_center(sc, kp_str(p, mo->g33));
    if ((at->g >> 27) & 1) {
      sc->editing = 0;   /* a G27 without its G28: the number it took is not known */
      screen_prompt(sc, kp_str(p, mo->g27), mo->g27form == '-');
      if ((at->m >> 27) & 1)
        sc->fixed = sc->last;
      open = 1;
    } else if ((at->m >> 27) & 1) {
      sc->fixed = sc->last >= 0 ? sc->last : sc->nbuf;
    }
    if (((at->g >> 28) & 1) && open && mo->g28reg >= 0) {
      screen_field_type(sc, llround(r->vm.reg[mo->g28reg]));
      screen_field_close(sc);
      open = 0;
    }
  }
  sc->editing = 0;
  sc->at_fixed = 0;
  sc->p3 = p3;
}
