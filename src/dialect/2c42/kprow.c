/* The 2С42's trace rows, dump, screen, panel page and Modbus view
 * (contracts.md sections 2 and 6; kprun.h).  Numbers are printed in the C
 * locale with fixed formats (src/core/report.h). */
#include "kprun.h"
#include "ast.h"
#include "compile.h"
#include "report.h"
#include <math.h>
#include <string.h>

static const char axes[] = "xyza";

/* The plugins' trace members (,"osc":"on") in the text trace: " osc=on". */
static void text_members(FILE *f, const char *m)
{
  for (; m && *m; m++) {
    if (*m == ',' && m[1] == '"')
      fputc(' ', f);
    else if (*m == ':' && m[-1] == '"')
      fputc('=', f);
    else if (*m != '"')
      fputc(*m, f);
  }
}

void kp_row_json(const struct mrun *r, FILE *f)
{
  const struct kp_state *s = kp_st(r);
  const struct kp_row *w = &s->row;
  fprintf(f, ",\"motion\":\"%s\"", w->motion);
  for (int i = 0; i < 4; i++)
    fprintf(f, ",\"%c\":%lld", axes[i], (long long)w->d[i]);
  fprintf(f, ",\"f\":%.0f,\"feed\":%.3f,\"t\":%.4f", w->f, w->feed, w->t);
  if (w->has_v)
    fprintf(f, ",\"v\":%.3f", w->v);
  fputs(s->extra, f);
  if (w->override_pct != 100)
    fprintf(f, ",\"override\":%d", w->override_pct);
  if (w->has_jogs)
    fprintf(f, ",\"jogs\":{\"x\":%lld,\"y\":%lld,\"z\":%lld,\"a\":%lld}", (long long)w->jogs[0],
            (long long)w->jogs[1], (long long)w->jogs[2], (long long)w->jogs[3]);
}

void kp_row_text(const struct mrun *r, FILE *f)
{
  const struct kp_state *s = kp_st(r);
  const struct kp_row *w = &s->row;
  int n = mrun_block_number(r);
  if (n >= 0)
    fprintf(f, "N%-4d", n);
  else
    fputs("N-   ", f);
  fprintf(f, " L%-4u %*s%-6s", r->p->blocks[r->vm.cur].line, 2 * r->vm.depth, "", w->motion);
  for (int i = 0; i < 4; i++)
    if (w->d[i])
      fprintf(f, " %c%+lld", "XYZA"[i], (long long)w->d[i]);
  fprintf(f, "  F%.0f", w->f);
  if (w->feed > 0)
    fprintf(f, " feed %.3f", w->feed);
  if (w->has_v)
    fprintf(f, " v %.3f", w->v);
  text_members(f, s->extra);
  if (w->override_pct != 100)
    fprintf(f, " override %d%%", w->override_pct);
  if (w->has_jogs)
    fprintf(f, " jogs X%+lld Y%+lld Z%+lld A%+lld", (long long)w->jogs[0], (long long)w->jogs[1],
            (long long)w->jogs[2], (long long)w->jogs[3]);
  fprintf(f, "  t %.4f", w->t);
}

void kp_dump_json(const struct mrun *r, FILE *f)
{
  if (!r->p) {   /* a program that did not compile: the machine at power-on */
    fputs(",\"time\":0,\"pos\":{\"x\":0,\"y\":0,\"z\":0,\"a\":0},\"r\":[", f);
    for (int i = 0; i < 114; i++)
      fputs(i ? ",0" : "0", f);
    fputs("],\"d1\":0,\"tk\":0,\"ug\":0,\"f\":0,\"wheel\":\"off\",\"arrays\":[", f);
    for (int a = 0; a < KP_ARRAYS; a++) {
      fprintf(f, "%s{\"ptr\":0,\"len\":0,\"cells\":[", a ? "," : "");
      for (int i = 0; i < KP_CELLS; i++)
        fputs(i ? ",0" : "0", f);
      fputs("]}", f);
    }
    fputc(']', f);
    return;
  }
  const struct kp_state *s = kp_st(r);
  const struct vm *vm = &r->vm;
  fprintf(f, ",\"time\":%.6f,\"pos\":{", s->m.t);
  for (int i = 0; i < 4; i++)
    fprintf(f, "%s\"%c\":%lld", i ? "," : "", axes[i], (long long)s->m.pos[i]);
  fputs("},\"r\":[", f);
  for (int i = 0; i < 114; i++) {
    if (i)
      fputc(',', f);
    json_num(f, vm->reg[i]);
  }
  fputs("],\"d1\":", f);
  json_num(f, vm->reg[REG_D1]);
  fputs(",\"tk\":", f);
  json_num(f, vm->reg[REG_TK]);
  fputs(",\"ug\":", f);
  json_num(f, vm->reg[REG_UG]);
  fputs(",\"f\":", f);
  json_num(f, vm->reg[REG_F]);
  static const char *const wheel[] = {"off", "cw", "ccw"};
  fprintf(f, ",\"wheel\":\"%s\",\"arrays\":[", wheel[s->m.wheel]);
  for (uint32_t a = 0; a < r->p->lim.arrays; a++) {
    fprintf(f, "%s{\"ptr\":%d,\"len\":%d,\"cells\":[", a ? "," : "", vm->arr[a].ptr, vm->arr[a].len);
    for (uint32_t i = 0; i < r->p->lim.cells; i++) {
      if (i)
        fputc(',', f);
      json_num(f, vm->arr[a].cell[i]);
    }
    fputs("]}", f);
  }
  fputs("]", f);
  char extra[320];
  kp_plugin_json(r, S42_DESCRIBE_DUMP, extra, sizeof extra);
  fputs(extra, f);
}

static void grid_of(const struct mrun *r, uint32_t grid[SCR_ROWS][SCR_COLS])
{
  const struct kp_state *s = kp_st(r);
  static const double zero[VM_NREG];
  screen_render(&s->scr, r->p ? r->vm.reg : zero, s->en, grid);
}

void kp_screen(const struct mrun *r, FILE *out)
{
  uint32_t grid[SCR_ROWS][SCR_COLS];
  grid_of(r, grid);
  screen_print(out, grid);
}

void kp_page(const struct mrun *r, int k, struct mrun_page *pg)
{
  (void)k;   /* one page: the 16x32 screen */
  uint32_t grid[SCR_ROWS][SCR_COLS];
  grid_of(r, grid);
  memset(pg, 0, sizeof *pg);
  pg->rows = SCR_ROWS;
  pg->cols = SCR_COLS;
  for (int y = 0; y < SCR_ROWS; y++)
    for (int x = 0; x < SCR_COLS; x++)
      pg->cell[y][x] = grid[y][x];
}

/* The Modbus map (contracts.md sec. 6): X Y Z A in discretes, R0-R113,
 * the wheel and the oscillation, the override in effect, and the last
 * block's contour speed as it goes now: the row's, or, when the block
 * ended with the move an override may re-time (mach_override_at), that
 * move's speed now. */
void kp_view(const struct mrun *r, struct mrun_view *v)
{
  const struct kp_state *s = kp_st(r);
  memset(v, 0, sizeof *v);
  memcpy(v->pos, s->m.pos, sizeof v->pos);
  v->naxes = 4;
  memcpy(v->axis_name, "XYZA", 4);
  v->nregs = 114;
  memcpy(v->reg, r->vm.reg, 114 * sizeof *v->reg);
  v->bits = (s->m.wheel != WHEEL_OFF ? MRUN_BIT_SPINDLE : 0) |
            (s->extra[0] && strstr(s->extra, "\"osc\":\"on\"") ? MRUN_BIT_AUX : 0);
  v->override_eff = s->m.override_allowed ? s->m.override_pct : 100;
  v->feed = s->row.feed;
  if (v->feed > 0 && s->m.mv.on && fabs(s->m.mv.t1 - s->m.t) <= 1e-9 * (1 + s->m.t))
    v->feed = s->m.mv.feed;
}
