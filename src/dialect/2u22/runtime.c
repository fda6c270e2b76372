/* The 2У22 runtime on the neutral runner (src/core/mrun.h): what a block
 * means to the 16Б16Ф3 lathe, as calls of the canonical table
 * (src/core/canon.h) on the lathe (src/machine/lathe).
 *
 * A block runs in the order of D-11: the tool, the spindle's range, speed
 * and direction, coolant and the modal G changes first; then the motion;
 * then G04's dwell; then the stops and the end.  A block is a transaction
 * (D-33): it runs on a copy of the state, and only a block that succeeds
 * keeps its changes; the runner's journal holds the lathe's records and
 * warnings until the block commits. */
#include "u22.h"
#include "canon.h"
#include "diag.h"
#include "errors.h"
#include "geom.h"
#include "lathe.h"
#include "mrun.h"
#include "snapshot.h"
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

struct u22_state {
  struct lathe l;
  int motion;          /* group 1: UG01, UG02, UG03 or UG33 */
  int incremental;     /* G91 */
  double f;            /* the F in force as written (0: none, or cancelled by G94 <-> G95) */
  int f_override, s_override;   /* G20, G21 (D-6) */
  /* the last block, for its row */
  const char *what;    /* its motion's name (contracts.md sec. 8) */
  double feed;         /* its effective speed, mm/min */
};

/* The state and the copy a block runs on. */
struct u22_rt {
  struct u22_state cur, tmp;
};

static struct u22_state *state(const struct mrun *r) { return &((struct u22_rt *)r->st)->cur; }

static void reset(struct mrun *r)
{
  struct u22_state *s = state(r);
  lathe_init(&s->l, &lathe_16b16f3);
  s->motion = UG01;    /* D-7: G01 G23 G90 G94 G97 */
  s->what = "none";
}

static int skippable(const struct mrun *r, uint32_t b)
{
  return u22_attr(r->p, b)->skip;
}

#define HAS_G(a, n) (((a)->g >> (n)) & 1)
#define HAS_M(a, n) (((a)->m >> (n)) & 1)
#define HAS_W(a, n) (((a)->words >> (n)) & 1)

/* A word's value in µm (X Z I K in the program's unit). */
static int64_t um(const struct mrun *r, int slot)
{
  double unit = ((const struct u22_ext *)r->p->ext)->unit;
  return (int64_t)llround(r->vm.w[slot] * unit * 1000.0);
}

static int fail(struct mrun *r, int code, const char *msg)
{
  mrun_fail(r, code, "%s", msg);
  return -1;
}

/* A call of the canonical table on the lathe of s (a switch, a setting:
 * the lathe refuses nothing of these but with a warning). */
static void set(struct lathe *l, int kind, int n, int on, double v)
{
  struct canon_dev d = lathe_dev(l);
  struct canon_call c = canon_of(kind);
  char msg[160];
  c.n = n;
  c.on = c.dir = on;
  c.v = v;
  canon_do(&d, &c, msg, sizeof msg);
}

/* A motion of kind to `to` (X, Z: part coordinates, µm, X a diameter). */
static int move(struct lathe *l, struct canon_call *c, const int64_t to[2], char *msg, size_t n)
{
  struct canon_dev d = lathe_dev(l);
  c->pos[0] = to[LX];
  c->pos[2] = to[LZ];
  return canon_do(&d, c, msg, n);
}

/* The block's work on s (a copy); 0, 1 for a programmed stop, -1 failed. */
static int work(struct mrun *r, struct u22_state *s, const struct u22_attr *a)
{
  struct lathe *l = &s->l;
  char msg[200];
  int e;
  s->what = "none";
  s->feed = 0;

  /* the tool, the spindle, coolant (D-11) */
  if (HAS_W(a, U22_T)) {
    double t = r->vm.w[U22_T];
    if (!(t >= 0 && t < LATHE_TOOLS)) {
      snprintf(msg, sizeof msg, "T%.0f: the turret's tools are T0..T%d", t, LATHE_TOOLS - 1);
      return fail(r, S42_E_RANGE, msg);
    }
    set(l, CANON_TOOL, (int)t, 0, 0);
  }
  if (HAS_M(a, UM38))
    set(l, CANON_SPINDLE_RANGE, 1, 0, 0);
  if (HAS_M(a, UM39))
    set(l, CANON_SPINDLE_RANGE, 2, 0, 0);
  /* modal G changes before the motion */
  if (HAS_G(a, UG90))
    s->incremental = 0;
  if (HAS_G(a, UG91))
    s->incremental = 1;
  if (HAS_G(a, UG94) || HAS_G(a, UG95)) {
    int per_rev = HAS_G(a, UG95);
    if (per_rev != l->per_rev)
      s->f = 0;        /* a switch cancels F (L672); the same mode again keeps it (D-30) */
    set(l, CANON_FEED_MODE, 0, per_rev, 0);
  }
  if (HAS_G(a, UG96))
    set(l, CANON_SPINDLE_MODE, 0, 1, 0);
  if (HAS_G(a, UG97))
    set(l, CANON_SPINDLE_MODE, 0, 0, 0);
  if (HAS_W(a, U22_S))
    set(l, CANON_SPINDLE_SPEED, 0, 0, r->vm.w[U22_S]);
  if (HAS_M(a, UM03))
    set(l, CANON_SPINDLE, 0, 1, 0);
  if (HAS_M(a, UM04))
    set(l, CANON_SPINDLE, 0, -1, 0);
  if (HAS_M(a, UM05))
    set(l, CANON_SPINDLE, 0, 0, 0);
  if (HAS_M(a, UM08))
    set(l, CANON_COOLANT, 0, 1, 0);
  if (HAS_M(a, UM09))
    set(l, CANON_COOLANT, 0, 0, 0);
  if (HAS_G(a, UG20))
    s->f_override = 1;
  if (HAS_G(a, UG21))
    s->s_override = 1;
  if (HAS_G(a, UG23))
    s->f_override = s->s_override = 0;
  if (HAS_G(a, UG20) || HAS_G(a, UG23))
    set(l, CANON_OVERRIDE, 0, s->f_override, 0);   /* F% acts under G20 only (D-6, D-46) */
  if (HAS_W(a, U22_F))
    s->f = r->vm.w[U22_F];
  static const int group1[] = {UG01, UG02, UG03, UG33};
  for (size_t i = 0; i < sizeof group1 / sizeof group1[0]; i++)
    if (HAS_G(a, group1[i]))
      s->motion = group1[i];

  /* the motion */
  double f = l->per_rev ? s->f / 100.0 : s->f;   /* G95: F in 0.01 mm/rev */
  if (HAS_G(a, UG25)) {
    struct canon_dev d = lathe_dev(l);
    struct canon_call c = canon_of(CANON_HOME);
    c.axes = (a->home & 1 ? 1u : 0) | (a->home & 2 ? 4u : 0);   /* X, Z */
    if ((e = canon_do(&d, &c, msg, sizeof msg)))
      return fail(r, e, msg);
    s->what = "home";
    s->feed = l->feed;
  } else if (HAS_W(a, U22_X) || HAS_W(a, U22_Z)) {
    int64_t to[2] = {lathe_pos(l, LX), lathe_pos(l, LZ)};
    if (HAS_W(a, U22_X))
      to[LX] = s->incremental ? to[LX] + um(r, U22_X) : um(r, U22_X);
    if (HAS_W(a, U22_Z))
      to[LZ] = s->incremental ? to[LZ] + um(r, U22_Z) : um(r, U22_Z);
    switch (s->motion) {
    case UG02:
    case UG03: {
      /* absolute: I K are the centre; incremental: from the start
       * (L598-606); a centre word not written: the start's (offset 0) */
      int64_t c[2];
      static const int slot[2] = {U22_I, U22_K};
      for (int ax = LX; ax <= LZ; ax++) {
        int64_t v = HAS_W(a, slot[ax]) ? um(r, slot[ax]) : 0;
        c[ax] = s->incremental || !HAS_W(a, slot[ax]) ? lathe_pos(l, ax) + v : v;
      }
      if (f <= 0)
        return fail(r, S42_E_FEED, s->f == 0 && l->per_rev ? "an arc with no F: the G94/G95 switch cancelled it"
                                                           : "an arc with F0");
      struct canon_call cc = canon_of(CANON_FEED_ARC);
      cc.plane = GEOM_XZ;
      cc.centre[0] = c[LX];
      cc.centre[1] = c[LZ];
      cc.ccw = s->motion == UG02;   /* geom's X -> Z turn: G02 in G18 */
      cc.f = f;
      if ((e = move(l, &cc, to, msg, sizeof msg)))
        return fail(r, e, msg);
      s->what = s->motion == UG02 ? "arc_cw" : "arc_ccw";
      break;
    }
    case UG33: {
      if (!HAS_W(a, U22_K))
        return fail(r, S42_E_THREAD, "G33 needs the pitch K (µm per revolution)");
      /* K under G33 is µm as written (Table 1.1), whatever the resolution */
      struct canon_call c = canon_of(CANON_THREAD);
      c.v = r->vm.w[U22_K];   /* counts (µm) of Z per revolution */
      if ((e = move(l, &c, to, msg, sizeof msg)))
        return fail(r, e, msg);
      s->what = "thread";
      break;
    }
    default:
      if (f <= 0)
        return fail(r, S42_E_FEED, s->f == 0 && l->per_rev != 0 ? "a move with no F: G95 cancelled it (L672)"
                                                                : "a move with no F (F0 or none given)");
      struct canon_call c = canon_of(CANON_FEED_LINE);
      c.f = f;
      if ((e = move(l, &c, to, msg, sizeof msg)))
        return fail(r, e, msg);
      s->what = "line";
      break;
    }
    s->feed = l->feed;
  }
  /* after the motion: the dwell, the stops, the end */
  if (HAS_G(a, UG04)) {
    double sec = HAS_W(a, U22_E) ? r->vm.w[U22_E] / 10.0 : 0;
    if (sec > 0)
      set(l, CANON_DWELL, 0, 0, sec);
    if (!strcmp(s->what, "none"))
      s->what = "dwell";
  }
  if (HAS_M(a, UM02) || HAS_M(a, UM30))
    set(l, CANON_END, 0, 0, 0);
  if (HAS_M(a, UM00))
    return 1;
  if (HAS_M(a, UM01) && r->optstop)
    return 1;
  return 0;
}

/* Would the block's motion be a feed move that the override acts on (G01,
 * G02, G03 under G20), as it stands after the block's own modal words? */
static int override_move(const struct u22_state *s, const struct u22_attr *a)
{
  if (HAS_G(a, UG25) || !(HAS_W(a, U22_X) || HAS_W(a, U22_Z)))
    return 0;
  int on = HAS_G(a, UG20) || (s->f_override && !HAS_G(a, UG23));
  int motion = HAS_G(a, UG33) ? UG33 : HAS_G(a, UG01) ? UG01 : HAS_G(a, UG02) ? UG02 : HAS_G(a, UG03) ? UG03
                                                                                             : s->motion;
  return on && motion != UG33;
}

static int block(struct mrun *r)
{
  struct u22_state *s = state(r);
  const struct u22_attr *a = u22_attr(r->p, r->vm.cur);
  /* a feed move at an override of 0 %: it waits before anything of the block runs */
  if (r->override == 0 && override_move(s, a))
    return mrun_wait(r, MRW_FEED);
  struct u22_state *tmp = &((struct u22_rt *)r->st)->tmp;
  *tmp = *s;
  tmp->l.out = mrun_sink(r);   /* the lathe's records and warnings: the block's journal */
  tmp->l.ovr_pct = r->override;
  int st = work(r, tmp, a);
  if (st < 0)
    return -1;
  *s = *tmp;
  return st;
}

/* mm from µm, as JSON: no trailing zeros */
static void mm(FILE *out, int64_t v)
{
  char b[32];
  snprintf(b, sizeof b, "%.3f", (double)v / 1000.0);
  char *e = b + strlen(b);
  while (e[-1] == '0')
    *--e = 0;
  if (e[-1] == '.')
    *--e = 0;
  fputs(strcmp(b, "-0") ? b : "0", out);
}

static void num(FILE *out, double v)
{
  fprintf(out, "%.10g", fabs(v) < 5e-11 ? 0.0 : v);
}

/* The spindle's speed as the panel shows it: the S in force (G97, also
 * while stopped: the S stays programmed), or under G96 the speed the
 * cutting speed gives where the tool is. */
static double speed(const struct lathe *l)
{
  return l->css ? lathe_rpm(l, lathe_pos(l, LX)) : l->s;
}

static void pos_json(const struct lathe *l, FILE *out)
{
  fputs("\"pos\":{\"x\":", out);
  mm(out, lathe_pos(l, LX));
  fputs(",\"z\":", out);
  mm(out, lathe_pos(l, LZ));
  fputc('}', out);
}

static void row_json(const struct mrun *r, FILE *out)
{
  const struct u22_state *s = state(r);
  fprintf(out, ",\"motion\":\"%s\",", s->what);
  pos_json(&s->l, out);
  fputs(",\"feed\":", out);
  num(out, s->feed);
  fputs(",\"t\":", out);
  num(out, s->l.t);
  fputs(",\"s\":", out);
  num(out, speed(&s->l));
  fprintf(out, ",\"tool\":%d", s->l.tool);
}

static void row_text(const struct mrun *r, FILE *out)
{
  const struct u22_state *s = state(r);
  char nb[16];
  fprintf(out, "%-6s L%-4u", diag_block(mrun_block_number(r), nb), r->p->blocks[r->vm.cur].line);
  fprintf(out, " %-7s X%10.3f Z%10.3f F%8.1f S%5.0f T%-2d t %.4f", s->what, (double)lathe_pos(&s->l, LX) / 1000.0,
          (double)lathe_pos(&s->l, LZ) / 1000.0, s->feed, speed(&s->l), s->l.tool,
          s->l.t);
}

static void dump_json(const struct mrun *r, FILE *out)
{
  const struct u22_state *s = state(r);
  const struct lathe *l = &s->l;
  fputs(",\"time\":", out);
  num(out, l->t);
  fputc(',', out);
  pos_json(l, out);
  fputs(",\"r\":[", out);
  for (int i = 0; i < 10; i++) {
    if (i)
      fputc(',', out);
    num(out, r->vm.reg[i]);
  }
  fprintf(out, "],\"tool\":%d,\"spindle\":{\"dir\":\"%s\",\"rpm\":", l->tool,
          l->dir > 0 ? "cw" : l->dir < 0 ? "ccw" : "off");
  num(out, speed(l));
  fprintf(out, ",\"range\":%d},\"feed_mode\":\"%s\",\"css\":%s,\"coolant\":%s,\"zero\":{\"x\":", l->range,
          l->per_rev ? "mm/rev" : "mm/min", l->css ? "true" : "false", l->coolant ? "true" : "false");
  mm(out, l->zero[LX]);
  fputs(",\"z\":", out);
  mm(out, l->zero[LZ]);
  fputs("},\"machine\":{\"x\":", out);
  mm(out, l->slide[LX]);
  fputs(",\"z\":", out);
  mm(out, l->slide[LZ]);
  fputc('}', out);
}

static int zero(struct mrun *r, const double *v, int n, char *why, size_t nwhy)
{
  struct lathe *l = &state(r)->l;
  int64_t z[2] = {l->zero[LX], l->zero[LZ]};
  for (int i = 0; i < n && i < 2; i++) {
    if (isnan(v[i]))
      continue;
    if (!(fabs(v[i]) <= 10000)) {
      snprintf(why, nwhy, "a part zero of %g mm is off the machine", v[i]);
      return -1;
    }
    z[i] = (int64_t)llround(v[i] * 1000.0);
  }
  lathe_set_zero(l, z[LX], z[LZ]);
  return 0;
}

/* The operator's inputs the lathe takes itself: the part zero (V0). */
static int input(struct mrun *r, const struct mrun_input *in, char *why, size_t n)
{
  if (in->kind == MRI_ZERO) {
    double v[2] = {in->v[0], in->v[2]};   /* X, Z */
    return zero(r, v, 2, why, n);
  }
  snprintf(why, n, "the machine does not wait for it");
  return -1;
}

/* What the 16Б16Ф3's panel has not (D-34). */
static const char *refuses(const struct mrun *r, const struct mrun_input *in)
{
  (void)r;
  switch (in->kind) {
  case MRI_PS: case MRI_EXIT: case MRI_KEY:
    return "this machine's panel has Пуск and Стоп (key PUSK, key STOP)";
  case MRI_ANSWER: case MRI_JOG: case MRI_SECTION: case MRI_CORRECT:
    return "not an action of this machine (key PUSK, key STOP, mode single|skip|optstop on|off, zero X Z, "
           "override N, break N, at)";
  default:
    return NULL;
  }
}

/* The F% switch (D-46): kept always, acting under G20; turned within a
 * move, the rest of the move goes at the new speed. */
static int override(struct mrun *r, int pct, double now, double *shift)
{
  struct u22_state *s = state(r);
  *shift = 0;
  s->l.ovr_pct = pct;
  if (r->state == MR_WAIT && r->wait == MRW_FEED)
    return pct > 0 ? 1 : 0;
  if (!s->l.ovr_on)
    return 0;
  if (pct == 0)
    return lathe_in_move(&s->l, now) ? 2 : 0;
  *shift = lathe_override_at(&s->l, now);
  return 0;
}

static double time_of(const struct mrun *r) { return state(r)->l.t; }

static int load(struct mrun *r, const char *what, const char *text, size_t len, const char *file, char *err,
                size_t nerr)
{
  if (strcmp(what, "tools")) {
    snprintf(err, nerr, "the lathe reads no %s file", what);
    return -2;
  }
  return lathe_tools_parse(&state(r)->l, text, len, file, err, nerr);
}

/* A new cycle (Пуск after M02): the slides, the tool table, the part zero
 * and the time stay; the language's modal state is at power-on (D-7). */
static void renew(struct mrun *r, const double *reg)
{
  (void)reg;   /* R0-R9 at 0 again, as at power-on */
  struct u22_state *s = state(r);
  struct lathe keep = s->l;
  reset(r);
  keep.per_rev = 0;    /* G94 G97 again (D-7): a switch the next block's calls report */
  keep.css = 0;
  s->l = keep;
}

static const char *const pages[] = {"DG", "DI", NULL};

/* name: 3 columns as written (Δ is one column of two bytes) */
static void mm_text(FILE *out, const char *name, int64_t v)
{
  fprintf(out, "%s %+11.3f\n", name, (double)v / 1000.0);
}

/* DG: where the tool is (part coordinates, X a diameter), the following
 * error (none in a simulation), the part zero and the slides; DI: the
 * mode, the block, F S G, the tool and its corrections (L130-490). */
static void page_text(const struct mrun *r, int k, FILE *out)
{
  const struct u22_state *s = state(r);
  const struct lathe *l = &s->l;
  if (k == 0) {
    fputs("DG  position (X a diameter)\n", out);
    mm_text(out, "X  ", lathe_pos(l, LX));
    mm_text(out, "Z  ", lathe_pos(l, LZ));
    fputs("following error\n", out);
    mm_text(out, "ΔX ", 0);
    mm_text(out, "ΔZ ", 0);
    fputs("part zero\n", out);
    mm_text(out, "OX ", l->zero[LX]);
    mm_text(out, "OZ ", l->zero[LZ]);
    fputs("machine (slides)\n", out);
    mm_text(out, "MX ", l->slide[LX]);
    mm_text(out, "MZ ", l->slide[LZ]);
    return;
  }
  int n = r->p->nblocks ? mrun_block_number(r) : -1;
  fprintf(out, "DI  %s%s%s%s\n", r->single ? "П/АВТ" : "АВТ", r->optstop ? " ST" : "", r->skip ? " U/" : "",
          r->state == MR_WAIT ? "  waits: Пуск" : "");
  if (n >= 0)
    fprintf(out, "N%05d\n", n);
  else
    fputs("N-----\n", out);
  static const char *const g1[] = {[UG01] = "G01", [UG02] = "G02", [UG03] = "G03", [UG33] = "G33"};
  fprintf(out, "G %s %s %s %s %s\n", g1[s->motion], s->incremental ? "G91" : "G90",
          s->f_override && s->s_override ? "G20 G21" : s->f_override ? "G20" : s->s_override ? "G21" : "G23",
          l->per_rev ? "G95" : "G94", l->css ? "G96" : "G97");
  fprintf(out, "F %-7.0f %s\n", s->f, l->per_rev ? "0.01 mm/rev" : "mm/min");
  fprintf(out, "S %-7.0f %s  range %d\n", l->s, l->css ? "m/min" : "rpm", l->range);
  fprintf(out, "spindle %s  %.0f rpm\n", l->dir > 0 ? "M03" : l->dir < 0 ? "M04" : "M05",
          lathe_rpm(l, lathe_pos(l, LX)));
  fprintf(out, "coolant %s\n", l->coolant ? "M08" : "M09");
  const struct lathe_tool *t = &l->tools[l->tool];
  fprintf(out, "T%02d  KX %+9.3f  KZ %+9.3f\n", l->tool, (double)t->d[LX] / 1000.0, (double)t->d[LZ] / 1000.0);
  fprintf(out, "R0-R4 %g %g %g %g %g\n", r->vm.reg[0], r->vm.reg[1], r->vm.reg[2], r->vm.reg[3], r->vm.reg[4]);
  fprintf(out, "R5-R9 %g %g %g %g %g\n", r->vm.reg[5], r->vm.reg[6], r->vm.reg[7], r->vm.reg[8], r->vm.reg[9]);
  fprintf(out, "t %.1f s\n", l->t);
}

static void page(const struct mrun *r, int k, struct mrun_page *pg)
{
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  if (f) {
    page_text(r, k, f);
    if (fclose(f))
      len = 0;
  }
  mrun_page_text(pg, buf ? buf : "", buf ? len : 0);
  free(buf);
}

/* --screen: the two pages the display shows, DG above DI. */
static void screen(const struct mrun *r, FILE *out)
{
  page_text(r, 0, out);
  fputc('\n', out);
  page_text(r, 1, out);
}

/* ---- the restart snapshot: where a run stopped (the 2У22 has no save
 * word; a run that stops saves with --state, --restart goes on there) ---- */

struct u22_blob {
  int32_t motion, incremental, f_override, s_override;
  double f;
  int64_t slide[2], zero[2];
  struct lathe_tool tools[LATHE_TOOLS];
  int32_t tool, dir, range, per_rev, css, coolant, ovr_pct, ovr_on;
  double t, s;
};

static size_t save(const struct mrun *r, void *buf, size_t cap, char *err, size_t n)
{
  (void)err;
  (void)n;
  const struct u22_state *s = state(r);
  const struct lathe *l = &s->l;
  struct u22_blob b;
  if (cap < sizeof b)
    return sizeof b;
  memset(&b, 0, sizeof b);
  b.motion = s->motion;
  b.incremental = s->incremental;
  b.f_override = s->f_override;
  b.s_override = s->s_override;
  b.f = s->f;
  memcpy(b.slide, l->slide, sizeof b.slide);
  memcpy(b.zero, l->zero, sizeof b.zero);
  memcpy(b.tools, l->tools, sizeof b.tools);
  b.tool = l->tool;
  b.dir = l->dir;
  b.range = l->range;
  b.per_rev = l->per_rev;
  b.css = l->css;
  b.coolant = l->coolant;
  b.ovr_pct = l->ovr_pct;
  b.ovr_on = l->ovr_on;
  b.t = l->t;
  b.s = l->s;
  memcpy(buf, &b, sizeof b);
  return sizeof b;
}

static int restore(struct mrun *r, const void *buf, size_t len, const char *shown, char *err, size_t n)
{
  struct snap_chk c = {r->p, shown, err, n, 0};
  struct u22_blob b;
  if (len != sizeof b) {
    snprintf(err, n, "%s was written by another version of s42", shown);
    return -1;
  }
  memcpy(&b, buf, sizeof b);
  struct u22_state *s = state(r);
  struct lathe *l = &s->l;
  if (b.motion != UG01 && b.motion != UG02 && b.motion != UG03 && b.motion != UG33)
    snap_refuse(&c, "motion is G code %d, not G01 G02 G03 G33", (int)b.motion);
  snap_ints(&c, "G90/G91 switch", b.incremental, 0, 1);
  snap_ints(&c, "G20 switch", b.f_override, 0, 1);
  snap_ints(&c, "G21 switch", b.s_override, 0, 1);
  snap_range(&c, "F", b.f, 0, 9999999, 0);
  static const char *const ax[2] = {"X", "Z"};
  char what[48];
  for (int a = 0; a < 2; a++) {
    snprintf(what, sizeof what, "%s slide", ax[a]);
    snap_range(&c, what, (double)b.slide[a], (double)l->lo[a], (double)l->hi[a], 1);
    snprintf(what, sizeof what, "%s part zero", ax[a]);
    snap_range(&c, what, (double)b.zero[a], -1e7, 1e7, 1);
  }
  for (int t = 0; t < LATHE_TOOLS; t++) {
    snprintf(what, sizeof what, "T%d in-table mark", t);
    snap_ints(&c, what, b.tools[t].has, 0, 1);
    for (int a = 0; a < 2; a++) {
      snprintf(what, sizeof what, "T%d %s correction", t, ax[a]);
      snap_range(&c, what, (double)b.tools[t].d[a], -1e7, 1e7, 1);
    }
  }
  snap_ints(&c, "tool", b.tool, 0, LATHE_TOOLS - 1);
  snap_ints(&c, "spindle direction", b.dir, -1, 1);
  snap_ints(&c, "spindle range", b.range, 0, l->model.nranges);
  snap_ints(&c, "G94/G95 switch", b.per_rev, 0, 1);
  snap_ints(&c, "G96/G97 switch", b.css, 0, 1);
  snap_ints(&c, "coolant", b.coolant, 0, 1);
  snap_ints(&c, "feed override", b.ovr_pct, 0, 150);
  snap_ints(&c, "feed override switch", b.ovr_on, 0, 1);
  snap_range(&c, "time", b.t, 0, SNAP_TIME_MAX, 0);
  snap_range(&c, "S", b.s, 0, 1e6, 0);
  if (c.bad)
    return -1;
  s->motion = b.motion;
  s->incremental = b.incremental;
  s->f_override = b.f_override;
  s->s_override = b.s_override;
  s->f = b.f;
  memcpy(l->slide, b.slide, sizeof b.slide);
  memcpy(l->zero, b.zero, sizeof b.zero);
  memcpy(l->tools, b.tools, sizeof b.tools);
  l->tool = b.tool;
  l->dir = b.dir;
  l->range = b.range;
  l->per_rev = b.per_rev;
  l->css = b.css;
  l->coolant = b.coolant;
  l->ovr_pct = b.ovr_pct;
  l->ovr_on = b.ovr_on;
  l->t = b.t;
  l->s = b.s;
  l->rpm_now = lathe_rpm(l, lathe_pos(l, LX));
  r->override = b.ovr_pct;
  return 0;
}

/* R0-R9 with the parameters' range (D-27); the rest are unused. */
static int reg_range(const struct mrun *r, int k, char *name, size_t n, double *lo, double *hi, int *whole)
{
  *whole = 0;
  if (k > 9)
    return 0;
  snprintf(name, n, "R%d", k);
  *lo = r->p->lim.param_lo;
  *hi = r->p->lim.param_hi;
  return 1;
}

static void position(const struct mrun *r, int64_t pos[CANON_AXES])
{
  const struct lathe *l = &state(r)->l;
  memset(pos, 0, CANON_AXES * sizeof *pos);
  pos[0] = lathe_pos(l, LX);   /* a diameter, counts of 0.0005 mm of radius */
  pos[2] = lathe_pos(l, LZ);
}

static void info(const struct mrun *r, struct canon_info *in)
{
  lathe_ops.info(r->st ? &state(r)->l : NULL, in);
}

/* The Modbus map (contracts.md sec. 6): X (a diameter) and Z in µm at 10
 * and 12, R0-R9 at 100 and 600, the spindle and the coolant, F% in effect
 * (under G20; 100 otherwise), and the last block's feed as it goes now (an
 * F% turned within its move re-times it: lathe_override_at). */
static void view(const struct mrun *r, struct mrun_view *v)
{
  const struct u22_state *s = state(r);
  memset(v, 0, sizeof *v);
  v->pos[0] = lathe_pos(&s->l, LX);
  v->pos[1] = lathe_pos(&s->l, LZ);
  v->naxes = 2;
  v->axis_name[0] = 'X';
  v->axis_name[1] = 'Z';
  v->nregs = 10;
  for (int i = 0; i < 10; i++)
    v->reg[i] = r->vm.reg[i];
  v->bits = (s->l.dir ? MRUN_BIT_SPINDLE : 0) | (s->l.coolant ? MRUN_BIT_AUX : 0);
  v->feed = s->feed > 0 ? s->l.feed : 0;
  v->override_eff = s->l.ovr_on ? r->override : 100;
}

const struct mrun_rt u22_runtime = {
  .machine = "16Б16Ф3",
  .tool_table = 1,
  .note_uk = "",
  .note_en = "",
  .input = input,
  .refuses = refuses,
  .override = override,
  .resume = block,
  .info = info,
  .view = view,
  .position = position,
  .renew = renew,
  .pages = pages,
  .page = page,
  .screen = screen,
  .save = save,
  .restore = restore,
  .reg_range = reg_range,
  .size = sizeof(struct u22_rt),
  .reset = reset,
  .skippable = skippable,
  .block = block,
  .row_json = row_json,
  .row_text = row_text,
  .dump_json = dump_json,
  .time = time_of,
  .load = load,
};
