/* What a compiled 2С42 block means to the machine and the display: the
 * front end's per-block attributes, kept in program.ext and indexed like
 * program.blocks.  The VM never reads these; the session does. */
#ifndef S42_KP_H
#define S42_KP_H

#include "ast.h"
#include "program.h"
#include "words.h"   /* enum motion, kp_motion_name */
#include <stdint.h>

/* What few blocks have -- the texts, the dialog's forms, M16's list --
 * kept apart (kp_ext.more) so that every block's record stays small. */
struct kp_more {
  uint32_t g27, g33, m18;   /* string offsets + 1 into kp_ext.str; 0 none */
  uint32_t g29, ng29;       /* first index into kp_ext.lines, count */
  uint32_t m16, nm16;       /* first index into kp_ext.m16, count */
  int16_t g28reg;           /* -1 none */
  char g27form;             /* ':' or '-' */
  char g37axis;
};

struct kp_attr {
  uint64_t g;          /* bit n: Gn */
  uint32_t m;          /* bit n: Mn */
  uint16_t slots;      /* bit s: word slot s given (ast.h SL_*) */
  uint8_t motion;      /* enum motion */
  uint8_t plane;       /* 0, 17, 18 or 19 */
  uint8_t has_f;       /* the block sets the contour speed */
  uint8_t plug_g;      /* MO_PLUGIN: the plugin's group-1 G number */
  int8_t bare[4];      /* M19: axis word X Y Z A is +Rn (n+1) or -Rn (-(n+1)); 0 not bare */
  uint8_t zero[2];     /* 0: the record has no padding (the compiler compares records whole) */
  uint32_t plugins;    /* bit i: plugin i of the session's set runs in this block */
  uint32_t more;       /* 1 + its index in kp_ext.more; 0: none (kp_more: a record of nothing) */
};
_Static_assert(sizeof(struct kp_attr) == 32, "struct kp_attr: 32 bytes, no padding");

/* The machine's switches as the session publishes them to the VM (vm.sw),
 * for a block that sets nothing else (MACHS: compile.c, session.c). */
#define KP_SW_CORR 1u       /* M22 on, M23 off: the operational corrections allowed */
#define KP_SW_OVERRIDE 2u   /* M26 on, M25 off: the feed override allowed */

/* Blocks share their attributes: a program has few different ones (the
 * same kinds of block over and over), so kp_ext.a holds each once and a
 * block has only its index there -- 16 bits while there are at most 65,536
 * (ai16), 32 beyond (ai32, ai16 then NULL). */
struct plug_set;
struct kp_ext {
  struct kp_attr *a;   /* the different attributes */
  size_t n, cap;
  uint16_t *ai16;      /* each block's index in a */
  uint32_t *ai32;
  size_t nai, capai;
  struct kp_more *more;
  size_t nmore, capmore;
  char *str;
  size_t nstr, capstr;
  uint32_t *lines;     /* string offsets + 1 */
  size_t nlines, caplines;
  struct m16_item *m16;
  size_t nm16, capm16;
  int uses_tk;         /* TK or UG is read somewhere */
  unsigned tk_line, tk_col; int tk_number;   /* the first place */
  int has_m10;         /* some block measures TK and UG (G10/G11 M10) */
  struct plug_set *plugins;   /* the plugin set it was compiled with (its runtime starts them) */
};

static inline const struct kp_attr *kp_attr(const struct program *p, size_t b)
{
  const struct kp_ext *x = p->ext;
  return &x->a[x->ai32 ? x->ai32[b] : x->ai16[b]];
}

/* The block's texts, dialog forms and M16 list (all none for most). */
static inline const struct kp_more *kp_more(const struct program *p, const struct kp_attr *at)
{
  static const struct kp_more none = {.g28reg = -1};
  return at->more ? &((const struct kp_ext *)p->ext)->more[at->more - 1] : &none;
}

static inline const char *kp_str(const struct program *p, uint32_t off)
{
  return off ? ((const struct kp_ext *)p->ext)->str + off - 1 : NULL;
}

/* The 2С42 runtime on the session (runtime.c). */
struct sess_runtime;
extern const struct sess_runtime kp_runtime;
/* After a restart: the dialog area on the screen as the program's dialog
 * left it before the restart point (the terminal shows it). */
struct session;
void kp_restore_dialog(struct session *s);

#endif
