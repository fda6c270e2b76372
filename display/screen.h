/* The 2С42-65 screen as a pure model: 16 lines of 32 characters -- line 1
 * the service line (mode, Cyrillic-keyboard R, block number), lines 2-15
 * the work area (the dialog's input buffer, or the P3 current-data display),
 * line 16 the directive/message line.  screen_render draws the model into a
 * grid of cells; headless runs print that grid, the terminal copies it. */
#ifndef S42_SCREEN_H
#define S42_SCREEN_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define SCR_ROWS 16
#define SCR_COLS 32
#define SCR_WORK 14                 /* work lines 2..15 */
#define SCR_BUF (4 * SCR_WORK)      /* the input buffer holds four screens */

enum screen_mode { SCR_AUTO, SCR_MANUAL, SCR_RESULTS };

struct screen_line {
  uint32_t ch[SCR_COLS];            /* code points, 0 = blank */
  int field;                        /* this line holds the G27 number field */
  char value[8];                    /* the number it took, as shown */
  int neg7;                         /* a negative 7-digit number: '-' in column 25 */
};

struct screen_p3 {                     /* one G29 line */
  uint32_t ch[SCR_COLS];
  int reg;                          /* parameter shown at the end, -1 none */
};

/* Display format P5: the results of a tooth-step search (language.md
 * section 15): tooth count, lead TK, helix angle UG and hand (when M10
 * measured them), then the circular steps eight to a page. */
#define SCR_P5_MAX 150
#define SCR_P5_PAGE 8
struct screen_p5 {
  int teeth;                        /* 1..SCR_P5_MAX */
  int lead;                         /* tk, ug, hand were measured */
  double tk, ug;                    /* µm, 0.001° */
  int hand;                         /* 1 right, -1 left, 0 straight */
  double steps[SCR_P5_MAX];         /* 0.001° */
  int page;                         /* first step shown: page * SCR_P5_PAGE */
};

struct screen {
  int mode;
  int cyr;                          /* Cyrillic keyboard mode: the letter R */
  int block;                        /* block number shown, -1 none */
  struct screen_line buf[SCR_BUF];     /* the input buffer (dialog lines) */
  int nbuf, top;                    /* lines used; first line shown */
  int fixed;                        /* M27: the fixed input line, -1 none */
  int last;                         /* the line the last G27/G33 wrote, -1 none */
  int en;                           /* English messages */
  int at_fixed;                     /* M28: the next dialog line goes to the fixed one */
  int p3;                           /* the work area shows the P3 display */
  int p5;                           /* the work area shows the P5 results */
  struct screen_p5 res;
  struct screen_p3 p3l[SCR_WORK];
  int np3;
  char dirtext[SCR_COLS * 4 + 1];   /* the directive as written, ((Rn drawn live */
  uint32_t message[SCR_COLS];
  int has_message;                  /* a message hides the directive until the next key */
  /* the number field being edited */
  int editing, fline;               /* field active; its buffer line */
  char digits[8];                   /* up to 7 digits, ' ' empty */
  int cursor, neg;
};

void screen_init(struct screen *s);
/* Decode UTF-8 into at most n code points; returns how many. */
int screen_decode(const char *utf8, uint32_t *out, int n);
/* G33: text centred on the next work line. */
void screen_center(struct screen *s, const char *text);
/* G27: text from the start of the line, dots to column 25, the field at
 * 26-32 (wrapped: the text runs over two lines, the field on the second).
 * When four screens are full the oldest line goes, with "Обмеження введення". */
void screen_prompt(struct screen *s, const char *text, int wrapped);
/* The field: digits, ЗБ, arrows, minus; the value when ПС ends it. */
void screen_field_digit(struct screen *s, int d);
void screen_field_backspace(struct screen *s);
void screen_field_move(struct screen *s, int delta);
void screen_field_minus(struct screen *s);
double screen_field_value(const struct screen *s);
void screen_field_reopen(struct screen *s);   /* G28 refused: enter again */
void screen_field_close(struct screen *s);
/* Type a whole number into the field (the operator script's `answer`). */
void screen_field_type(struct screen *s, long long v);
/* G29: start (or, after M15, extend) the P3 layout. */
void screen_p3_clear(struct screen *s);
void screen_p3_add(struct screen *s, const char *text);
/* P5: show search results (the work area and the service line
 * РЕЗУЛЬТАТИ); steps in 0.001°, n of them.  -1 when they cannot be shown
 * (no teeth, too many, a value that is not a number). */
int screen_p5_set(struct screen *s, int teeth, const double *steps, int lead, double tk, double ug, int hand);
/* + and - on the P5 display: the next or previous eight steps.  Returns 0
 * when the page changed, -1 when there is none that way (or no P5). */
int screen_p5_page(struct screen *s, int delta);
/* P5 into work lines 2..15 of a grid (a pure function of the results). */
void screen_p5_render(const struct screen_p5 *r, int en, uint32_t g[SCR_ROWS][SCR_COLS]);
/* M18: the directive as written; its ((Rn are drawn live by screen_render. */
void screen_set_directive(struct screen *s, const char *text);
void screen_clear_directive(struct screen *s);
void screen_message(struct screen *s, const char *text);
void screen_scroll(struct screen *s, int delta);
/* The panel's keys on the screen, as one call: a digit (arg 0-9), the
 * minus, ЗБ, the field's cursor (arg -1/+1), the buffer's scroll (arg),
 * P5's pages (arg).  Returns what screen_p5_page returns for that, else 0. */
enum screen_edit_op { SCREEN_DIGIT, SCREEN_MINUS, SCREEN_BACKSPACE, SCREEN_MOVE, SCREEN_SCROLL, SCREEN_P5_PAGE };
int screen_edit(struct screen *s, int op, int arg);
/* Render into cells; regs feeds the ((Rn fields (114 values). */
void screen_render(const struct screen *s, const double *regs, int en, uint32_t grid[SCR_ROWS][SCR_COLS]);
/* The grid as 16 UTF-8 text lines. */
void screen_print(FILE *f, uint32_t grid[SCR_ROWS][SCR_COLS]);
/* Format Rn for a ((Rn field: rounded, right-aligned in 8, ******** if it
 * does not fit. */
void screen_value8(double v, char out[9]);

#endif
