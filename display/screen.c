/* The 2С42-65 screen model (display/screen.h). */
#include "screen.h"
#include "messages.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

void screen_init(struct screen *s)
{
  memset(s, 0, sizeof *s);
  s->block = -1;
  s->fixed = -1;
  s->fline = -1;
  s->last = -1;
  memset(s->digits, ' ', 7);
}

int screen_decode(const char *p, uint32_t *out, int n)
{
  int k = 0;
  const unsigned char *u = (const unsigned char *)p;
  while (*u && k < n) {
    uint32_t c;
    int len;
    if (*u < 0x80) { c = *u; len = 1; }
    else if ((*u & 0xE0) == 0xC0 && u[1]) { c = ((uint32_t)(*u & 0x1F) << 6) | (u[1] & 0x3F); len = 2; }
    else if ((*u & 0xF0) == 0xE0 && u[1] && u[2]) {
      c = ((uint32_t)(*u & 0x0F) << 12) | ((uint32_t)(u[1] & 0x3F) << 6) | (u[2] & 0x3F); len = 3;
    } else if ((*u & 0xF8) == 0xF0 && u[1] && u[2] && u[3]) {
      c = ((uint32_t)(*u & 0x07) << 18) | ((uint32_t)(u[1] & 0x3F) << 12) | ((uint32_t)(u[2] & 0x3F) << 6) |
          (u[3] & 0x3F); len = 4;
    } else { c = 0xFFFD; len = 1; }
    out[k++] = c;
    u += len;
  }
  return k;
}

static void put(uint32_t *line, int col, const uint32_t *t, int n)
{
  for (int i = 0; i < n && col + i < SCR_COLS; i++)
    if (col + i >= 0)
      line[col + i] = t[i];
}

/* The line the next dialog output goes to (M28: the fixed one). */
static struct screen_line *next_line(struct screen *s, int *idx)
{
  if (s->at_fixed && s->fixed >= 0) {
    s->at_fixed = 0;
    *idx = s->fixed;
    memset(&s->buf[*idx], 0, sizeof s->buf[*idx]);
    return &s->buf[*idx];
  }
  if (s->nbuf >= SCR_BUF) {
    /* four screens are full: the oldest line goes */
    memmove(&s->buf[0], &s->buf[1], (SCR_BUF - 1) * sizeof s->buf[0]);
    s->nbuf--;
    if (s->fixed >= 0)
      s->fixed--;
    if (s->fline >= 0)
      s->fline--;
    screen_message(s, screen_msg_text(MSG_LIMIT, s->en));
  }
  *idx = s->nbuf++;
  memset(&s->buf[*idx], 0, sizeof s->buf[*idx]);
  if (s->nbuf - s->top > SCR_WORK)
    s->top = s->nbuf - SCR_WORK;
  return &s->buf[*idx];
}

void screen_center(struct screen *s, const char *text)
{
  uint32_t t[SCR_COLS];
  int n = screen_decode(text, t, SCR_COLS), idx;
  s->p3 = s->p5 = 0;
  struct screen_line *l = next_line(s, &idx);
  put(l->ch, (SCR_COLS - n) / 2, t, n);
  s->last = idx;
}

void screen_prompt(struct screen *s, const char *text, int wrapped)
{
  uint32_t t[64];
  int n = screen_decode(text, t, 64), idx;
  s->p3 = s->p5 = 0;
  struct screen_line *l = next_line(s, &idx);
  if (wrapped && n > 24) {
    /* the text wraps at a space onto the next line, which gets the field */
    int cut = n < SCR_COLS ? n : SCR_COLS;
    for (int i = cut; i > 0; i--)
      if (t[i - 1] == ' ' && n - i <= 24) {
        cut = i;
        break;
      }
    put(l->ch, 0, t, cut);
    l = next_line(s, &idx);
    n -= cut;
    if (n > 24)
      n = 24;
    put(l->ch, 0, t + cut, n);
  } else {
    put(l->ch, 0, t, n);
  }
  for (int c = n; c < 25; c++)
    l->ch[c] = '.';
  l->field = 1;
  memset(l->value, ' ', 7);
  s->last = idx;
  s->editing = 1;
  s->fline = idx;
  memset(s->digits, ' ', 7);
  s->cursor = 0;
  s->neg = 0;
}

void screen_field_digit(struct screen *s, int d)
{
  if (!s->editing)
    return;
  s->digits[s->cursor] = (char)('0' + d);
  s->cursor = (s->cursor + 1) % 7;   /* after the 7th digit, back to the first */
  s->has_message = 0;
}

void screen_field_backspace(struct screen *s)
{
  if (!s->editing)
    return;
  s->has_message = 0;   /* a message stays until the next key */
  if (s->cursor > 0)
    s->cursor--;
  s->digits[s->cursor] = ' ';
}

void screen_field_move(struct screen *s, int delta)
{
  s->has_message = 0;   /* a message stays until the next key */
  if (s->editing)
    s->cursor = (s->cursor + delta + 7) % 7;
}

void screen_field_minus(struct screen *s)
{
  s->has_message = 0;   /* a message stays until the next key */
  if (s->editing)
    s->neg = !s->neg;
}

double screen_field_value(const struct screen *s)
{
  double v = 0;
  for (int i = 0; i < 7; i++)
    if (s->digits[i] >= '0' && s->digits[i] <= '9')
      v = v * 10 + (s->digits[i] - '0');
  return s->neg ? -v : v;
}

void screen_field_close(struct screen *s)
{
  if (!s->editing)
    return;
  /* leading zeros are dropped: the number is shown right-aligned */
  char shown[9];
  double v = screen_field_value(s);
  snprintf(shown, sizeof shown, "%7.0f", fabs(v));
  int sign_outside = 0;
  if (v < 0) {
    if (shown[0] != ' ') {
      sign_outside = 1;   /* seven digits: the sign takes column 25 */
    } else {
      char *p = shown;
      while (*p == ' ' && p[1] == ' ')
        p++;
      *p = '-';
    }
  }
  memcpy(s->digits, shown, 7);
  if (s->fline >= 0 && s->fline < s->nbuf) {
    memcpy(s->buf[s->fline].value, shown, 8);
    s->buf[s->fline].neg7 = sign_outside;
  }
  s->editing = 0;
}

void screen_field_reopen(struct screen *s)
{
  s->editing = 1;
  memset(s->digits, ' ', 7);
  s->cursor = 0;
  s->neg = 0;
}

void screen_field_type(struct screen *s, long long v)
{
  char d[24];
  snprintf(d, sizeof d, "%lld", v < 0 ? -v : v);
  memset(s->digits, ' ', 7);
  s->cursor = 0;
  s->neg = 0;
  for (const char *p = d; *p && p - d < 7; p++)
    screen_field_digit(s, *p - '0');
  if (v < 0)
    screen_field_minus(s);
}

void screen_p3_clear(struct screen *s)
{
  s->np3 = 0;
}

void screen_p3_add(struct screen *s, const char *text)
{
  if (s->np3 >= SCR_WORK)
    return;
  struct screen_p3 *l = &s->p3l[s->np3++];
  memset(l, 0, sizeof *l);
  l->reg = -1;
  const char *ref = strstr(text, "((");
  char head[256];
  size_t hn = ref ? (size_t)(ref - text) : strlen(text);
  if (hn >= sizeof head)
    hn = sizeof head - 1;
  memcpy(head, text, hn);
  head[hn] = 0;
  screen_decode(head, l->ch, SCR_COLS);
  if (ref) {
    const char *q = ref + 2;
    while (*q == ' ') q++;
    q += (*q == 'R') ? 1 : (strncmp(q, "\xD0\xA0", 2) == 0 ? 2 : 0);
    l->reg = atoi(q);
  }
  s->p3 = 1;
  s->p5 = 0;
}

int screen_p5_set(struct screen *s, int teeth, const double *steps, int lead, double tk, double ug, int hand)
{
  if (teeth < 1 || teeth > SCR_P5_MAX || !steps || !isfinite(tk) || !isfinite(ug))
    return -1;
  for (int i = 0; i < teeth; i++)
    if (!isfinite(steps[i]))
      return -1;
  struct screen_p5 *r = &s->res;
  memset(r, 0, sizeof *r);
  r->teeth = teeth;
  memcpy(r->steps, steps, (size_t)teeth * sizeof *steps);
  r->lead = lead != 0;
  r->tk = tk;
  r->ug = ug;
  r->hand = hand > 0 ? 1 : hand < 0 ? -1 : 0;
  s->p5 = 1;
  s->mode = SCR_RESULTS;
  return 0;
}

int screen_p5_page(struct screen *s, int delta)
{
  if (!s->p5)
    return -1;
  int pages = (s->res.teeth + SCR_P5_PAGE - 1) / SCR_P5_PAGE;
  int p = s->res.page + (delta > 0 ? 1 : -1);
  if (delta == 0 || p < 0 || p >= pages)
    return -1;
  s->res.page = p;
  return 0;
}

void screen_set_directive(struct screen *s, const char *text)
{
  snprintf(s->dirtext, sizeof s->dirtext, "%s", text);
}

void screen_clear_directive(struct screen *s)
{
  s->dirtext[0] = 0;
}

void screen_message(struct screen *s, const char *text)
{
  memset(s->message, 0, sizeof s->message);
  screen_decode(text, s->message, SCR_COLS);
  s->has_message = 1;
}

void screen_scroll(struct screen *s, int delta)
{
  s->top += delta;
  if (s->top > s->nbuf - SCR_WORK)
    s->top = s->nbuf - SCR_WORK;
  if (s->top < 0)
    s->top = 0;
}

void screen_value8(double v, char out[9])
{
  double r = round(v);
  if (fabs(r) > 99999999.0 || (r < 0 && r < -9999999.0) || !isfinite(r)) {
    memcpy(out, "********", 9);
    return;
  }
  snprintf(out, 9, "%8.0f", r == 0 ? 0.0 : r);
}

static void put_ascii(uint32_t *line, int col, const char *t)
{
  for (int i = 0; t[i] && col + i < SCR_COLS; i++)
    line[col + i] = (unsigned char)t[i];
}

/* A P5 line: a label from column 1, an 8-character value at 25..32. */
static void p5_line(uint32_t *line, const char *label, const char *value8)
{
  uint32_t t[SCR_COLS];
  int n = screen_decode(label, t, SCR_COLS - 8);
  put(line, 0, t, n);
  if (value8) {
    n = screen_decode(value8, t, 8);
    put(line, SCR_COLS - n, t, n);
  }
}

void screen_p5_render(const struct screen_p5 *r, int en, uint32_t g[SCR_ROWS][SCR_COLS])
{
  static const char *const lab[2][9] = {
    {"ЗУБІВ", "КРОК ГВИНТА TK, мкм", "КУТ ГВИНТА UG, 0.001°", "ГВИНТ", "ПРАВИЙ", "ЛІВИЙ", "ПРЯМИЙ",
     "КРОКИ, 0.001°", "не вим."},
    {"TEETH", "LEAD TK, µm", "HELIX ANGLE UG, 0.001°", "HAND", "RIGHT", "LEFT", "STRAIGHT", "STEPS, 0.001°",
     "not meas"},
  };
  const char *const *L = lab[en ? 1 : 0];
  char v[9], w[40];
  for (int row = 1; row <= SCR_WORK; row++)
    memset(g[row], 0, sizeof g[row]);
  screen_value8(r->teeth, v);
  p5_line(g[1], L[0], v);
  if (r->lead) {
    screen_value8(r->tk, v);
    p5_line(g[2], L[1], v);
    screen_value8(r->ug, v);
    p5_line(g[3], L[2], v);
    p5_line(g[4], L[3], r->hand > 0 ? L[4] : r->hand < 0 ? L[5] : L[6]);
  } else {
    /* without M10 only the steps are measured: TK and UG keep their values */
    snprintf(w, sizeof w, "%8s", L[8]);
    p5_line(g[2], L[1], w);
    p5_line(g[3], L[2], w);
  }
  int first = r->page * SCR_P5_PAGE, last = first + SCR_P5_PAGE;
  if (last > r->teeth)
    last = r->teeth;
  /* the header: which steps are shown, of how many */
  snprintf(w, sizeof w, "%d-%d/%d", first + 1, last, r->teeth);
  p5_line(g[6], L[7], w);
  for (int i = first; i < last; i++) {
    char num[16];
    snprintf(num, sizeof num, "%3d", i + 1);
    screen_value8(r->steps[i], v);
    p5_line(g[7 + i - first], num, v);
  }
}

void screen_render(const struct screen *s, const double *regs, int en, uint32_t g[SCR_ROWS][SCR_COLS])
{
  memset(g, 0, sizeof(uint32_t) * SCR_ROWS * SCR_COLS);
  static const char *const modes[2][3] = {{"АВТОМАТ", "РУЧНИЙ", "РЕЗУЛЬТАТИ"}, {"AUTO", "MANUAL", "RESULTS"}};
  uint32_t t[SCR_COLS];
  int n = screen_decode(modes[en ? 1 : 0][s->mode], t, SCR_COLS);
  put(g[0], 0, t, n);
  if (s->cyr)
    g[0][n + 1] = 0x0052;   /* R */
  if (s->block > 0) {
    char b[16];
    snprintf(b, sizeof b, "N%d", s->block);
    put_ascii(g[0], SCR_COLS - (int)strlen(b), b);
  }
  if (s->p5) {
    screen_p5_render(&s->res, en, g);
  } else if (s->p3) {
    for (int i = 0; i < s->np3 && i < SCR_WORK; i++) {
      memcpy(g[1 + i], s->p3l[i].ch, sizeof g[1 + i]);
      if (s->p3l[i].reg >= 0 && s->p3l[i].reg <= 113) {
        char v[9];
        screen_value8(regs ? regs[s->p3l[i].reg] : 0, v);
        put_ascii(g[1 + i], SCR_COLS - 8, v);
      }
    }
  } else {
    for (int i = 0; i < SCR_WORK && s->top + i < s->nbuf; i++) {
      const struct screen_line *l = &s->buf[s->top + i];
      memcpy(g[1 + i], l->ch, sizeof g[1 + i]);
      if (l->field) {
        int edit = s->editing && s->top + i == s->fline;
        const char *d = edit ? s->digits : l->value;
        for (int c = 0; c < 7; c++)
          g[1 + i][25 + c] = (unsigned char)d[c];
        if (!edit && l->neg7)
          g[1 + i][24] = '-';
        if (edit && s->neg)
          g[1 + i][24] = '-';
        if (edit && g[1 + i][25 + s->cursor] == ' ')
          g[1 + i][25 + s->cursor] = '_';
      }
    }
  }
  if (s->has_message) {
    memcpy(g[SCR_ROWS - 1], s->message, sizeof g[SCR_ROWS - 1]);
  } else {
    /* the directive, every ((Rn drawn live as its 8-character value */
    int col = 0;
    for (const char *q = s->dirtext; *q && col < SCR_COLS;) {
      if (q[0] == '(' && q[1] == '(') {
        const char *r = q + 2;
        while (*r == ' ') r++;
        if (*r == 'R' || strncmp(r, "\xD0\xA0", 2) == 0) {
          r += *r == 'R' ? 1 : 2;
          while (*r == ' ') r++;
          if (*r >= '0' && *r <= '9') {
            int reg = atoi(r);
            while (*r >= '0' && *r <= '9') r++;
            char v[9];
            screen_value8(regs && reg <= 113 ? regs[reg] : 0, v);
            put_ascii(g[SCR_ROWS - 1], col, v);
            col += 8;
            q = r;
            continue;
          }
        }
      }
      uint32_t one[1];
      const char *start = q;
      q++;
      while ((*q & 0xC0) == 0x80) q++;
      char tmp[8];
      size_t len = (size_t)(q - start) < sizeof tmp - 1 ? (size_t)(q - start) : sizeof tmp - 1;
      memcpy(tmp, start, len);
      tmp[len] = 0;
      if (screen_decode(tmp, one, 1) == 1)
        g[SCR_ROWS - 1][col++] = one[0];
    }
  }
}

void screen_print(FILE *f, uint32_t g[SCR_ROWS][SCR_COLS])
{
  for (int r = 0; r < SCR_ROWS; r++) {
    int end = SCR_COLS;
    while (end > 0 && (g[r][end - 1] == 0 || g[r][end - 1] == ' '))
      end--;
    for (int c = 0; c < end; c++) {
      uint32_t ch = g[r][c] ? g[r][c] : ' ';
      char u[4];
      int n;
      if (ch < 0x80) { u[0] = (char)ch; n = 1; }
      else if (ch < 0x800) { u[0] = (char)(0xC0 | (ch >> 6)); u[1] = (char)(0x80 | (ch & 0x3F)); n = 2; }
      else if (ch < 0x10000) {
        u[0] = (char)(0xE0 | (ch >> 12)); u[1] = (char)(0x80 | ((ch >> 6) & 0x3F)); u[2] = (char)(0x80 | (ch & 0x3F)); n = 3;
      } else {
        u[0] = (char)(0xF0 | (ch >> 18)); u[1] = (char)(0x80 | ((ch >> 12) & 0x3F));
        u[2] = (char)(0x80 | ((ch >> 6) & 0x3F)); u[3] = (char)(0x80 | (ch & 0x3F)); n = 4;
      }
      fwrite(u, 1, (size_t)n, f);
    }
    fputc('\n', f);
  }
}

int screen_edit(struct screen *s, int op, int arg)
{
  switch (op) {
  case SCREEN_DIGIT: screen_field_digit(s, arg); return 0;
  case SCREEN_MINUS: screen_field_minus(s); return 0;
  case SCREEN_BACKSPACE: screen_field_backspace(s); return 0;
  case SCREEN_MOVE: screen_field_move(s, arg); return 0;
  case SCREEN_SCROLL: screen_scroll(s, arg); return 0;
  case SCREEN_P5_PAGE: return screen_p5_page(s, arg);
  default: return 0;
  }
}
