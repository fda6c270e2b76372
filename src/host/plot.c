/* The plot engine (src/host/plot.h): what a run did, collected once from
 * its stream for every dialect, the result caption, the view chosen by the
 * machine's kind, and the picture written through picture.c.  The views
 * (plot_view.h) draw what is collected here.
 *
 * The path is kept as pieces (struct seg): a programmed move a record, the
 * hand moves made after it as steps, and a mark where a block started that
 * moved no programmed axis (hand moves only, or after a position change).
 * Where one piece ends and the next starts elsewhere, the position changed
 * outside the program (a correction; a lathe's tool or part zero): the
 * views draw that apart.
 *
 * Oscillation moves an axis outside the contour: the plugin's displacement
 * comes at once, while the block's records come when it commits, so each
 * record's start and end have the displacement of their moments (t0, t1)
 * taken out -- the programmed path stays the program's, and the strokes are
 * drawn apart (osc). */
#include "plot_view.h"
#include "picture.h"
#include "geom.h"
#include "mrun.h"
#include "cairo_dl.h"
#include <limits.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

struct plot *plot_new(const struct plot_stock *stock)
{
  struct plot *pl = calloc(1, sizeof *pl);
  if (!pl)
    return NULL;
  if (stock && stock->has && stock->d > 0 && stock->len > 0 && isfinite(stock->d) && isfinite(stock->len))
    pl->stock = *stock;
  for (int a = 0; a < PLOT_AXES; a++) {
    pl->unit[a] = 1000.0;
    pl->axis_name[a] = "XYZA"[a];
  }
  return pl;
}

void plot_free(struct plot *pl)
{
  if (!pl)
    return;
  if (pl->view && pl->view->free)
    pl->view->free(pl);
  free(pl->v);
  free(pl->steps);
  free(pl->osc);
  free(pl);
}

/* ---- the view by the machine's kind ---- */

static const struct plot_view *view_of(const char *kind)
{
  if (kind && !strcmp(kind, "grinder"))
    return &plot_view_grinder;
  if (kind && !strcmp(kind, "lathe"))
    return &plot_view_lathe;
  return &plot_view_planes;
}

static void set_kind(struct plot *pl, const char *kind)
{
  if (pl->view && pl->view->free)
    pl->view->free(pl);
  pl->vs = NULL;
  pl->view = view_of(kind);
  snprintf(pl->kind, sizeof pl->kind, "%s", kind ? kind : "none");
}

const char *plot_view_name(const struct plot *pl)
{
  return pl && pl->view ? pl->view->name : "none";
}

void plot_begin(struct plot *pl, const struct canon_info *in, const int64_t pos[CANON_AXES])
{
  if (!pl)
    return;
  set_kind(pl, in ? in->kind : NULL);
  snprintf(pl->name, sizeof pl->name, "%s", in && in->name ? in->name : "");
  for (int a = 0; a < PLOT_AXES; a++) {
    if (in && in->naxes) {
      pl->axis_name[a] = in->axis[a].name;
      if (in->axis[a].mm > 0 && isfinite(in->axis[a].mm))
        pl->unit[a] = 1.0 / in->axis[a].mm;
    }
    pl->start_pos[a] = pl->cur[a] = pos ? pos[a] : 0;
  }
  pl->begun = 1;
}

/* ---- collecting ---- */

static int grow(void **v, size_t *cap, size_t n, size_t size)
{
  if (n < *cap)
    return 0;
  size_t nc = *cap ? *cap * 2 : 1024;
  void *nv = realloc(*v, nc * size);
  if (!nv)
    return -1;
  *v = nv;
  *cap = nc;
  return 0;
}

static int32_t clamp32(int64_t v)
{
  return v > INT32_MAX ? INT32_MAX : v < -INT32_MAX ? -INT32_MAX : (int32_t)v;
}

/* b - a, within int32 (saturated, never overflowing) */
static int32_t delta(int64_t a, int64_t b)
{
  int64_t d;
  if (__builtin_sub_overflow(b, a, &d))
    return b > a ? INT32_MAX : -INT32_MAX;
  return clamp32(d);
}

/* The displacement reported up to time t is taken out of the records from here. */
static void osc_upto(struct plot *pl, double t)
{
  while (pl->ocur < pl->nosc && !(pl->osc[pl->ocur].t > t)) {
    const struct osc_pt *o = &pl->osc[pl->ocur++];
    pl->dapp[o->axis] = o->off;
  }
}

static void osc_all(struct plot *pl)
{
  pl->ocur = pl->nosc;
  memcpy(pl->dapp, pl->disp, sizeof pl->dapp);
}

static struct seg *push_seg(struct plot *pl, const int64_t start[PLOT_AXES])
{
  if (pl->oom || grow((void **)&pl->v, &pl->cap, pl->n, sizeof *pl->v)) {
    pl->oom = 1;
    return NULL;
  }
  struct seg *g = &pl->v[pl->n++];
  memset(g, 0, sizeof *g);
  memcpy(g->start, start, sizeof g->start);
  g->n = -1;
  g->step = (uint32_t)pl->nsteps;
  pl->step_open = 0;
  return g;
}

/* Where the last piece ends (the start, before any). */
static void last_end(const struct plot *pl, int64_t e[PLOT_AXES])
{
  if (!pl->n) {
    memcpy(e, pl->start_pos, PLOT_AXES * sizeof *e);
    return;
  }
  const struct seg *g = &pl->v[pl->n - 1];
  for (int a = 0; a < PLOT_AXES; a++)
    e[a] = g->start[a] + g->d[a] + g->jog[a];
}

void plot_call(struct plot *pl, const struct canon_call *c)
{
  if (!pl || !c)
    return;
  if (c->kind == CANON_SYNCH_START) {
    pl->thread = 1;
    pl->pitch = isfinite(c->v) && c->v > 0 ? c->v : 0;
    return;
  }
  if (c->kind == CANON_SYNCH_STOP) {
    pl->thread = 0;
    return;
  }
  if (c->kind != CANON_FEED_LINE && c->kind != CANON_FEED_ARC && c->kind != CANON_TRAVERSE)
    return;
  if (c->mm)
    for (int a = 0; a < PLOT_AXES; a++)
      if (c->mm[a] > 0 && isfinite(c->mm[a]))
        pl->unit[a] = 1.0 / c->mm[a];
  int64_t from[PLOT_AXES], to[PLOT_AXES];
  osc_upto(pl, c->t0);
  for (int a = 0; a < PLOT_AXES; a++)
    from[a] = c->from[a] - pl->dapp[a];
  osc_upto(pl, c->t1);
  int moves = 0;
  for (int a = 0; a < PLOT_AXES; a++) {
    to[a] = c->pos[a] - pl->dapp[a];
    moves |= to[a] != from[a];
  }
  int arc = 0, p = 0, q = 0;
  double cp = 0, cq = 0;
  if (c->kind == CANON_FEED_ARC) {
    geom_plane_axes(c->plane >= 0 && c->plane <= 2 ? c->plane : GEOM_XY, &p, &q);
    cp = (double)c->centre[0] - (double)c->from[p];
    cq = (double)c->centre[1] - (double)c->from[q];
    arc = (cp != 0 || cq != 0) && isfinite(cp) && isfinite(cq);
  }
  memcpy(pl->cur, to, sizeof pl->cur);
  if (!moves && !arc)
    return;   /* nowhere (a full circle ends where it starts, and moves) */
  struct seg *g = push_seg(pl, from);
  if (!g)
    return;
  for (int a = 0; a < PLOT_AXES; a++)
    g->d[a] = delta(from[a], to[a]);
  g->t0 = c->t0;
  g->t1 = c->t1;
  g->kind = c->kind == CANON_TRAVERSE ? K_TRAV : K_LINE;
  if (pl->thread && c->kind != CANON_TRAVERSE)
    g->flags |= F_THREAD;
  if (!arc)
    return;
  struct geom_arc ga = {(double)g->d[p], (double)g->d[q], cp, cq, c->ccw ? 1 : 0};
  double sw = geom_arc_sweep(&ga);
  if (c->turns > 0 && c->turns < 1000)
    sw += 2 * M_PI * c->turns;
  g->kind = K_ARC;
  g->plane = (uint8_t)(c->plane >= 0 && c->plane <= 2 ? c->plane : GEOM_XY);
  g->cp = (float)cp;
  g->cq = (float)cq;
  g->sweep = (float)(c->ccw ? sw : -sw);
  if (c->ccw)
    g->flags |= F_CCW;
}

void plot_move(struct plot *pl, int kind, int axis, int64_t d, const int64_t pos[CANON_AXES], double t)
{
  if (!pl || pl->oom)
    return;
  if (kind == MRV_DISPLACE) {
    if (axis < 0 || axis >= PLOT_AXES)
      return;
    if (grow((void **)&pl->osc, &pl->caposc, pl->nosc, sizeof *pl->osc)) {
      pl->oom = 1;
      return;
    }
    pl->disp[axis] += d;
    pl->osc[pl->nosc++] = (struct osc_pt){t, pl->disp[axis], axis, d == 0};
    return;
  }
  /* the block's records up to here are in: what was displaced is */
  osc_all(pl);
  int64_t now[PLOT_AXES];
  for (int a = 0; a < PLOT_AXES; a++)
    now[a] = pos[a] - pl->disp[a];
  if (kind == MRV_CORRECT) {
    /* a position change: where the path goes on shows it */
    memcpy(pl->cur, now, sizeof pl->cur);
    pl->step_open = 0;
    return;
  }
  /* a hand move: after the block's last piece, or from a mark where the
   * block started or the position changed (the mark is the open block's
   * first piece when it has none yet: block_seg is its index) */
  int64_t e[PLOT_AXES];
  last_end(pl, e);
  if (pl->block_seg >= pl->n || memcmp(e, pl->cur, sizeof e)) {
    struct seg *g = push_seg(pl, pl->cur);
    if (!g)
      return;
    g->kind = K_MARK;
    g->t0 = pl->t;
    g->t1 = t;
  }
  struct seg *g = &pl->v[pl->n - 1];
  int32_t dd[PLOT_AXES];
  for (int a = 0; a < PLOT_AXES; a++)
    dd[a] = delta(pl->cur[a], now[a]);
  /* the axes a runtime moves together (a teach-in step along a line or an
   * arc) come one by one at one time: one step */
  struct step *s = pl->nsteps > g->step ? &pl->steps[pl->nsteps - 1] : NULL;
  if (!(s && pl->step_open && pl->step_kind == kind && s->t == t && axis >= 0 && axis < PLOT_AXES &&
        s->d[axis] == 0)) {
    if (grow((void **)&pl->steps, &pl->capsteps, pl->nsteps, sizeof *pl->steps)) {
      pl->oom = 1;
      return;
    }
    s = &pl->steps[pl->nsteps++];
    memset(s, 0, sizeof *s);
    s->t = t;
  }
  for (int a = 0; a < PLOT_AXES; a++) {
    s->d[a] = clamp32((int64_t)s->d[a] + dd[a]);
    g->jog[a] = clamp32((int64_t)g->jog[a] + dd[a]);
  }
  pl->step_open = 1;
  pl->step_kind = kind;
  memcpy(pl->cur, now, sizeof pl->cur);
}

/* The open block's pieces: the first gets its number. */
static void close_block(struct plot *pl, int n, double t)
{
  size_t b = pl->block_seg;
  for (size_t i = b; i < pl->n; i++) {
    pl->v[i].n = i == b ? n : -1;
    if (pl->v[i].kind == K_MARK)
      pl->v[i].t1 = t;
  }
  pl->block_seg = pl->n;
  pl->step_open = 0;
}

void plot_row(struct plot *pl, int n, double t)
{
  if (!pl)
    return;
  osc_all(pl);
  int64_t e[PLOT_AXES];
  last_end(pl, e);
  if (pl->block_seg >= pl->n && memcmp(e, pl->cur, sizeof e)) {
    /* a block that moved nothing of its own, after a position change: its
     * start is where the change is drawn to */
    struct seg *g = push_seg(pl, pl->cur);
    if (g) {
      g->kind = K_MARK;
      g->t0 = pl->t;
      g->t1 = t;
    }
  }
  close_block(pl, n, t);
  pl->rows++;
  pl->t = t;
}

/* ---- the result caption ---- */

static void where(char *at, size_t size, int n, unsigned line)
{
  at[0] = 0;
  if (n > 0)
    snprintf(at, size, " at N%d", n);
  else if (line)
    snprintf(at, size, " at line %u", line);
}

void plot_end(struct plot *pl, const struct plot_result *res)
{
  if (!pl || !res)
    return;
  osc_all(pl);
  if (pl->block_seg != pl->n)
    close_block(pl, res->status == 3 ? res->n : -1, res->t);
  pl->ended = 1;
  pl->status = res->status;
  pl->blocks = res->blocks;
  pl->t_end = res->t;
  for (int a = 0; a < PLOT_AXES; a++)
    pl->end_pos[a] = res->has_pos ? res->pos[a] : pl->cur[a] + pl->disp[a];
  pl->why[0] = 0;
  char at[48];
  where(at, sizeof at, res->n, res->line);
  if (res->status == 1)
    snprintf(pl->why, sizeof pl->why, "stopped: %s%s", res->code ? res->code : "error", at);
  else if (res->status == 3 && res->stop == PLOT_STOP_SCRIPT)
    snprintf(pl->why, sizeof pl->why, "stopped: the operator script had no action for %s%s",
             res->waited ? res->waited : "what the machine waited for", at);
  else if (res->status == 3 && res->stop == PLOT_STOP_KEY)
    snprintf(pl->why, sizeof pl->why, "stopped (key STOP)%s", at);
  else if (res->status == 3)
    snprintf(pl->why, sizeof pl->why, "stopped%s", at);
}

void plot_refused(struct plot *pl, const char *kind, const char *code, int n, unsigned line)
{
  if (!pl)
    return;
  set_kind(pl, kind);
  pl->ended = 1;
  pl->status = 1;
  pl->blocks = 0;
  pl->t_end = 0;
  memset(pl->end_pos, 0, sizeof pl->end_pos);
  char at[48];
  where(at, sizeof at, n, line);
  snprintf(pl->why, sizeof pl->why, "not run: %s%s (the program does not compile)", code ? code : "error", at);
}

/* ---- the file ---- */

int plot_check_path(const char *path, const char *program, char *err, size_t n)
{
  return picture_check_output(path, program, err, n);
}

struct drawing { struct plot *pl; int raster; };

static void draw_picture(cairo_t *cr, void *ctx)
{
  struct drawing *d = ctx;
  d->pl->view->draw(cr, d->pl, d->raster);
}

static char *svg_head(void *ctx)
{
  struct plot *pl = ((struct drawing *)ctx)->pl;
  return pl->view->svg_head(pl);
}

int plot_write(struct plot *pl, const char *program, const char *path, char *err, size_t n)
{
  if (!pl) {
    snprintf(err, n, "no plot");
    return -1;
  }
  if (picture_check_path(path, err, n))
    return -1;
  if (!pl->view)
    set_kind(pl, NULL);
  pl->program = program ? program : "";
  /* S42_PLOT_PLAIN: no band, every stroke as it is (to compare) */
  const char *ext = strrchr(path, '.');
  struct drawing d = {pl, ext && !strcasecmp(ext, ".png") && !getenv("S42_PLOT_PLAIN")};
  return picture_write(path, pl->view->w, pl->view->h, pl->program, draw_picture,
                       pl->view->svg_head ? svg_head : NULL, &d, err, n);
}

/* ---- the stock ---- */

static int parse_mm(const char *s, const char **end, double *v)
{
  /* digits with at most one '.', no sign, no exponent, no locale */
  const char *p = s;
  double x = 0, scale = 0;
  int digits = 0;
  for (; *p; p++) {
    if (*p >= '0' && *p <= '9') {
      if (digits < 30) {
        if (scale == 0)
          x = x * 10 + (*p - '0');
        else {
          x += (*p - '0') * scale;
          scale /= 10;
        }
      }
      digits++;
    } else if (*p == '.' && scale == 0)
      scale = 0.1;
    else
      break;
  }
  *end = p;
  *v = x;
  return digits > 0 && digits < 30 ? 0 : -1;
}

int plot_parse_stock(const char *text, struct plot_stock *s, char *why, size_t n)
{
  struct plot_stock z = {0, 0, 0};
  if (s)
    *s = z;
  const char *p = text ? text : "", *e;
  double d, len;
  if (parse_mm(p, &e, &d) || (*e != 'x' && *e != 'X')) {
    snprintf(why, n, "--stock '%s': expected DIAMETERxLENGTH in mm, e.g. 40x100", text ? text : "");
    return -1;
  }
  if (parse_mm(e + 1, &e, &len) || *e) {
    snprintf(why, n, "--stock '%s': expected DIAMETERxLENGTH in mm, e.g. 40x100 (the length is not a number)",
             text);
    return -1;
  }
  if (!(d > 0) || !(len > 0)) {
    snprintf(why, n, "--stock '%s': the diameter and the length must be more than 0", text);
    return -1;
  }
  if (d > 10000 || len > 10000) {
    snprintf(why, n, "--stock '%s': a stock over 10000 mm is not a lathe's", text);
    return -1;
  }
  if (s) {
    s->has = 1;
    s->d = d;
    s->len = len;
  }
  return 0;
}

/* ---- shared drawing helpers ---- */

void plot_rgb(cairo_t *cr, unsigned c)
{
  cairo_set_source_rgb(cr, ((c >> 16) & 255) / 255.0, ((c >> 8) & 255) / 255.0, (c & 255) / 255.0);
}

void plot_rgba(cairo_t *cr, unsigned c, double a)
{
  cairo_set_source_rgba(cr, ((c >> 16) & 255) / 255.0, ((c >> 8) & 255) / 255.0, (c & 255) / 255.0, a);
}

void plot_font(cairo_t *cr, double size, int bold)
{
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

double plot_text_w(cairo_t *cr, const char *s, double size, int bold)
{
  plot_font(cr, size, bold);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s, &e);
  return e.x_advance;
}

void plot_text_at(cairo_t *cr, double x, double y, const char *s, double size, int bold, double align)
{
  double w = plot_text_w(cr, s, size, bold);
  cairo_move_to(cr, x - align * w, y);
  cairo_show_text(cr, s);
}

void plot_fmt_num(char *buf, size_t n, double v, int dec, int trim)
{
  if (fabs(v) < 0.5 * pow(10, -dec))
    v = 0;
  snprintf(buf, n, "%.*f", dec, v);
  picture_fix_point(buf);
  if (trim && strchr(buf, '.')) {
    char *e = buf + strlen(buf) - 1;
    while (*e == '0')
      *e-- = 0;
    if (*e == '.')
      *e = 0;
  }
}

double plot_nice_step(double x, int *dec)
{
  if (!(x > 0) || !isfinite(x))
    x = 1;
  double e = floor(log10(x)), b = pow(10, e), m = x / b;
  double s = m >= 5 ? 5 : m >= 2 ? 2 : 1;
  if (dec)
    *dec = e < 0 ? (int)-e : 0;
  return s * b;
}

void plot_stop_sign(cairo_t *cr, double x, double y)
{
  const double r = 7.5;
  cairo_new_path(cr);
  for (int k = 0; k < 8; k++) {
    double th = M_PI / 8 + k * M_PI / 4;
    if (k)
      cairo_line_to(cr, x + r * cos(th), y + r * sin(th));
    else
      cairo_move_to(cr, x + r * cos(th), y + r * sin(th));
  }
  cairo_close_path(cr);
  plot_rgb(cr, C_STOP);
  cairo_fill_preserve(cr);
  plot_rgb(cr, C_TEXT);
  cairo_set_line_width(cr, 1.6);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
  cairo_stroke(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
}

void plot_xml_text(FILE *f, const char *s)
{
  for (; *s; s++)
    switch (*s) {
    case '<': fputs("&lt;", f); break;
    case '>': fputs("&gt;", f); break;
    case '&': fputs("&amp;", f); break;
    default: fputc(*s, f);
    }
}

const char *plot_base(const char *program)
{
  const char *p = program ? program : "", *b = strrchr(p, '/');
  return b ? b + 1 : p;
}
