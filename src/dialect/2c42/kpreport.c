/* The 2С42's trace rows and dump (kpreport.h). */
#include "kpreport.h"
#include "report.h"
#include "error.h"
#include "errors.h"
#include "msgs.h"
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

void report_row(void *ctx, const struct session *s, const struct sess_row *r)
{
  struct trace_ctx *t = ctx;
  FILE *f = t->out;
  (void)s;
  if (t->json) {
    fprintf(f, "{\"seq\":%llu,\"n\":", (unsigned long long)r->seq);
    if (r->n >= 0)
      fprintf(f, "%d", r->n);
    else
      fputs("null", f);
    fprintf(f, ",\"line\":%u,\"depth\":%d,\"motion\":\"%s\"", r->line, r->depth, r->motion);
    for (int i = 0; i < 4; i++)
      fprintf(f, ",\"%c\":%lld", axes[i], (long long)r->d[i]);
    fprintf(f, ",\"f\":%.0f,\"feed\":%.3f,\"t\":%.4f", r->f, r->feed, r->t);
    if (r->has_v)
      fprintf(f, ",\"v\":%.3f", r->v);
    fputs(r->extra ? r->extra : "", f);
    if (r->override_pct != 100)
      fprintf(f, ",\"override\":%d", r->override_pct);
    if (r->has_jogs)
      fprintf(f, ",\"jogs\":{\"x\":%lld,\"y\":%lld,\"z\":%lld,\"a\":%lld}", (long long)r->jogs[0],
              (long long)r->jogs[1], (long long)r->jogs[2], (long long)r->jogs[3]);
    fputs("}\n", f);
  } else {
    fprintf(f, "%6llu ", (unsigned long long)r->seq);
    if (r->n >= 0)
      fprintf(f, "N%-4d", r->n);
    else
      fputs("N-   ", f);
    fprintf(f, " L%-4u %*s%-6s", r->line, 2 * r->depth, "", r->motion);
    for (int i = 0; i < 4; i++)
      if (r->d[i])
        fprintf(f, " %c%+lld", "XYZA"[i], (long long)r->d[i]);
    fprintf(f, "  F%.0f", r->f);
    if (r->feed > 0)
      fprintf(f, " feed %.3f", r->feed);
    if (r->has_v)
      fprintf(f, " v %.3f", r->v);
    text_members(f, r->extra);
    if (r->override_pct != 100)
      fprintf(f, " override %d%%", r->override_pct);
    if (r->has_jogs)
      fprintf(f, " jogs X%+lld Y%+lld Z%+lld A%+lld", (long long)r->jogs[0], (long long)r->jogs[1],
              (long long)r->jogs[2], (long long)r->jogs[3]);
    fprintf(f, "  t %.4f\n", r->t);
  }
}

void report_dump(FILE *f, const char *status, const struct s42_error *err, const struct program *p, int en,
                 const struct session *s)
{
  fprintf(f, "{\"status\":\"%s\",\"error\":", status);
  if (err) {
    char machine[200];
    s42_error_machine(err, p, en, machine, sizeof machine);
    fprintf(f, "{\"code\":\"%s\",\"n\":", err_code(err->code));
    if (err->number >= 0)
      fprintf(f, "%d", err->number);
    else
      fputs("null", f);
    fprintf(f, ",\"line\":%u,\"col\":%u,\"message\":", err->line, err->col);
    json_string(f, err->msg);
    fputs(",\"machine\":", f);
    json_string(f, machine);
    fputc('}', f);
  } else {
    fputs("null", f);
  }
  if (!s) {
    fputs(",\"blocks\":0,\"time\":0,\"pos\":{\"x\":0,\"y\":0,\"z\":0,\"a\":0},\"r\":[", f);
    for (int i = 0; i < 114; i++)
      fputs(i ? ",0" : "0", f);
    fputs("],\"d1\":0,\"tk\":0,\"ug\":0,\"f\":0,\"wheel\":\"off\",\"arrays\":[", f);
    for (int a = 0; a < 2; a++)
      fprintf(f, "%s{\"ptr\":0,\"len\":0,\"cells\":[0,0,0,0,0,0,0,0,0,0,0,0,0,0,0]}", a ? "," : "");
    fputs("]}\n", f);
    return;
  }
  const struct vm *vm = &s->vm;
  fprintf(f, ",\"blocks\":%llu,\"time\":%.6f,\"pos\":{", (unsigned long long)vm->blocks, s->m.t);
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
  for (uint32_t a = 0; a < s->p->lim.arrays; a++) {
    fprintf(f, "%s{\"ptr\":%d,\"len\":%d,\"cells\":[", a ? "," : "", vm->arr[a].ptr, vm->arr[a].len);
    for (uint32_t i = 0; i < s->p->lim.cells; i++) {
      if (i)
        fputc(',', f);
      json_num(f, vm->arr[a].cell[i]);
    }
    fputs("]}", f);
  }
  fputs("]", f);
  char extra[320];
  sess_plugin_json(s, S42_DESCRIBE_DUMP, extra, sizeof extra);
  fputs(extra, f);
  fputs("}\n", f);
}
