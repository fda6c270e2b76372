/* The G and M functions of the 2С42 (language.md sec. 8 and 9): one row per
 * function, and everything the front end, the plugin loader and the
 * session know of a word comes from here -- which numbers exist, a G's
 * group, the motion a block gets, the separate-block and arc rules, the
 * slash argument it takes, the plugin it belongs to and its name.  Adding a
 * function is adding a row (a new kind of motion then also has a name: the
 * code of its row).  Rows are in number order, G before M: the order of
 * enum motion, and of the lists messages print ("G02 G03 G12 G13"). */
#ifndef S42_WORDS_H
#define S42_WORDS_H

#include <stddef.h>
#include <stdint.h>

/* KP_WORDS(G, M): G(...) for a preparatory function, M(...) for an
 * auxiliary one, both with the same columns:
 *   number  the function's number (G 0..63, M 0..31)
 *   code    its name as printed, a token (G01): the motion's name too
 *   group   G: its group, 1..4 (at most one of each in a block); M: 0
 *   flags   KP_SEP, KP_ARC, KP_HELIX, KP_NODIR (below), | joined, or 0
 *   plane   the plane a G17/G18/G19 selects (17 18 19), otherwise 0
 *   motion  OWN: a block with it moves as MO_<code> (the first such G in
 *           number order; an M's overrides the G's); DIALOG: the block is
 *           a dialog (MO_DIALOG) when nothing else moves it; NONE
 *   slash   the /argument/ that follows it (enum kp_slash, without KP_SA_)
 *   owner   the plugin that does its work ("helix"), or NULL: the core's
 *   name    what it does, as E-PLUGIN messages say it */
#define KP_WORDS(G, M)                                                                                         \
  /* number code group flags              plane motion  slash    owner          name */                      \
  G( 1, G01, 1, 0,                  0,  OWN,    NONE,    NULL,          "linear interpolation")                \
  G( 2, G02, 1, KP_ARC,             0,  OWN,    NONE,    NULL,          "circular interpolation, clockwise")   \
  G( 3, G03, 1, KP_ARC,             0,  OWN,    NONE,    NULL,          "circular interpolation, counter-clockwise") \
  G( 4, G04, 1, KP_SEP,             0,  OWN,    NONE,    NULL,          "dwell")                               \
  G( 7, G07, 1, KP_SEP,             0,  OWN,    NONE,    "oscillation", "oscillation parameters")              \
  G( 9, G09, 3, 0,                  0,  NONE,   NONE,    NULL,          "decelerate to zero at the block's end") \
  G(10, G10, 1, KP_SEP | KP_NODIR,  0,  OWN,    NONE,    "toothsearch", "tooth-step search")                   \
  G(11, G11, 1, KP_SEP | KP_NODIR,  0,  OWN,    NONE,    "toothsearch", "tooth-step search")                   \
  G(12, G12, 1, KP_ARC | KP_HELIX,  0,  OWN,    NONE,    "helix",       "helical interpolation")               \
  G(13, G13, 1, KP_ARC | KP_HELIX,  0,  OWN,    NONE,    "helix",       "helical interpolation")               \
  G(17, G17, 2, 0,                 17,  NONE,   NONE,    NULL,          "plane XY")                            \
  G(18, G18, 2, 0,                 18,  NONE,   NONE,    NULL,          "plane YZ")                            \
  G(19, G19, 2, 0,                 19,  NONE,   NONE,    NULL,          "plane XZ")                            \
  G(20, G20, 1, KP_SEP,             0,  OWN,    NONE,    NULL,          "manual mode until Пуск")              \
  G(27, G27, 4, KP_NODIR,           0,  DIALOG, PROMPT,  NULL,          "show a text and take a number")       \
  G(28, G28, 4, KP_NODIR,           0,  DIALOG, BOUNDS,  NULL,          "check the number taken and store it") \
  G(29, G29, 4, 0,                  0,  DIALOG, LINES,   NULL,          "define the current data display")     \
  G(33, G33, 4, KP_NODIR,           0,  DIALOG, TEXT,    NULL,          "show a text centred")                 \
  G(34, G34, 4, KP_NODIR,           0,  DIALOG, NONE,    NULL,          "end of input")                        \
  G(37, G37, 1, KP_SEP,             0,  OWN,    AXIS,    NULL,          "return to the home position")         \
  M( 2, M02, 0, 0,                  0,  NONE,   NONE,    NULL,          "end of program")                      \
  M( 3, M03, 0, 0,                  0,  NONE,   NONE,    NULL,          "wheel on, clockwise")                 \
  M( 4, M04, 0, 0,                  0,  NONE,   NONE,    NULL,          "wheel on, counter-clockwise")         \
  M( 5, M05, 0, 0,                  0,  NONE,   NONE,    NULL,          "wheel off")                           \
  M(10, M10, 0, 0,                  0,  NONE,   NONE,    "toothsearch", "lead and helix angle")                \
  M(12, M12, 0, 0,                  0,  NONE,   NONE,    "toothsearch", "search speed from F")                 \
  M(13, M13, 0, 0,                  0,  NONE,   NONE,    "oscillation", "oscillation on")                      \
  M(14, M14, 0, 0,                  0,  NONE,   NONE,    "oscillation", "oscillation off")                     \
  M(15, M15, 0, 0,                  0,  NONE,   NONE,    NULL,          "restart point")                       \
  M(16, M16, 0, 0,                  0,  NONE,   CORR,    NULL,          "store the operator's corrections")    \
  M(17, M17, 0, 0,                  0,  NONE,   NONE,    NULL,          "end of sub")                          \
  M(18, M18, 0, 0,                  0,  NONE,   TEXT,    NULL,          "show a directive")                    \
  M(19, M19, 0, 0,                  0,  OWN,    NONE,    NULL,          "conditional move for manual mode")    \
  M(20, M20, 0, 0,                  0,  NONE,   PARAMS,  NULL,          "integer part of parameters")          \
  M(21, M21, 0, 0,                  0,  NONE,   NONE,    NULL,          "erase the directive")                 \
  M(22, M22, 0, 0,                  0,  NONE,   NONE,    NULL,          "allow operational correction")        \
  M(23, M23, 0, 0,                  0,  NONE,   NONE,    NULL,          "forbid operational correction")       \
  M(25, M25, 0, 0,                  0,  NONE,   NONE,    NULL,          "forbid the feed override")            \
  M(26, M26, 0, 0,                  0,  NONE,   NONE,    NULL,          "allow the feed override")             \
  M(27, M27, 0, 0,                  0,  NONE,   NONE,    NULL,          "fix the input line")                  \
  M(28, M28, 0, 0,                  0,  NONE,   NONE,    NULL,          "return to the fixed line")            \
  M(29, M29, 0, 0,                  0,  NONE,   NONE,    NULL,          "cancel the fixing")

/* flags */
enum {
  KP_SEP = 1,     /* stands in a separate block: no other group-1 function,
                     no axis or centre word beside it (G04 and G07 take
                     their own words: compile.c says which) */
  KP_ARC = 2,     /* an arc: needs a plane (group 2) in the block, takes
                     centre words, checked as a circle */
  KP_HELIX = 4,   /* with KP_ARC: one axis outside the plane may move */
  KP_NODIR = 8    /* no PP jump, no directive M18 or M21 beside it (the
                     block takes the operator's answer or runs a search) */
};

/* The slash arguments (parse.c reads each). */
enum kp_slash {
  KP_SA_NONE,
  KP_SA_PROMPT,   /* G27 /text/ then ':' or '-' (the answer's form) */
  KP_SA_TEXT,     /* /text/: G33, M18 */
  KP_SA_LINES,    /* /line/line/.../ /: G29 */
  KP_SA_BOUNDS,   /* /min:max/ Rn: G28 */
  KP_SA_AXIS,     /* /Y/: G37 */
  KP_SA_PARAMS,   /* /R12R15/: M20 */
  KP_SA_CORR      /* /R1+X R2-Z//: M16 */
};

/* The motion of a block: none, one per OWN row (MO_G01 ... MO_M19), a
 * dialog, a plugin's own G. */
#define KP_MO_ENUM_OWN(code) MO_##code,
#define KP_MO_ENUM_NONE(code)
#define KP_MO_ENUM_DIALOG(code)
#define KP_MO_ENUM(n, code, group, flags, plane, motion, ...) KP_MO_ENUM_##motion(code)
enum motion { MO_NONE, KP_WORDS(KP_MO_ENUM, KP_MO_ENUM) MO_DIALOG, MO_PLUGIN, MO__COUNT };

/* One row. */
struct kp_word {
  char kind;             /* 'G' or 'M'; 0: no such function */
  uint8_t number, group, flags, plane;
  uint8_t motion;        /* enum motion: MO_NONE, MO_DIALOG or its own */
  uint8_t slash;         /* enum kp_slash */
  const char *code;      /* "G01" */
  const char *owner;     /* plugin name, or NULL */
  const char *name;
};

/* The row of Gn / Mn, or NULL when the 2С42 has no such function (a
 * plugin's G50, any n outside 0..99). */
extern const struct kp_word kp_gwords[64], kp_mwords[32];   /* indexed by number (words.c) */
static inline const struct kp_word *kp_g(int n)
{
  return n >= 0 && n < 64 && kp_gwords[n].kind ? &kp_gwords[n] : NULL;
}
static inline const struct kp_word *kp_m(int n)
{
  return n >= 0 && n < 32 && kp_mwords[n].kind ? &kp_mwords[n] : NULL;
}
static inline const struct kp_word *kp_word(char kind, int n)
{
  return kind == 'G' ? kp_g(n) : kind == 'M' ? kp_m(n) : NULL;
}

/* The codes of the rows `pick` selects, G then M in number order, joined
 * by spaces ("G02 G03 G12 G13"), in buf; returns buf. */
const char *kp_codes(char *buf, size_t n, int (*pick)(const struct kp_word *w));

/* The motion's name in the trace ("G01", "M19", "none", "dialog",
 * "plugin"), and whether it is an arc (its row has KP_ARC). */
extern const char *const kp_motion_name[MO__COUNT];
int kp_motion_arc(int motion);

/* What the lists used to say: Gn / Mn is a function of the 2С42; Gn's
 * group (1 for a number the table has not: a plugin's G declares its own). */
int kp_valid_g(int n);
int kp_valid_m(int n);
int kp_g_group(int n);

#endif
