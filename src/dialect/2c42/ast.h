/* The parsed form of one 2С42 block: its words in text order with their
 * expressions, and its slash arguments.  Lives in an arena that is reset
 * after the block is compiled: the compiler never holds more than a block. */
#ifndef S42_AST_H
#define S42_AST_H

#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>

/* Registers of the 2С42 dialect in the VM's register file. */
enum { REG_R0 = 0, REG_D1 = 114, REG_TK = 115, REG_UG = 116, REG_F = 117 };

/* Word slots of the pending block record. */
enum { SL_X, SL_Y, SL_Z, SL_A, SL_I, SL_J, SL_K, SL_H, SL_MIN, SL_MAX, SL_OSCF, SL_SRCHF, SL__COUNT };

enum ex_kind { EX_NUM, EX_REG, EX_SLOT, EX_ARR, EX_NEG, EX_BIN, EX_FN, EX_CMP, EX_AND, EX_OR };

struct expr {
  uint8_t kind;
  uint8_t op;         /* EX_BIN/EX_FN: the vm opcode; EX_CMP: relation mask */
  uint8_t fk;         /* the compiler's last fold of it: 1 constant (v), 2 not, 0 not folded */
  uint16_t need;      /* the stack its code needs at most (the parser's count: a bound) */
  unsigned col;
  double v;           /* EX_NUM; the folded value of another constant node */
  unsigned idx;       /* EX_REG register, EX_SLOT slot, EX_ARR arr | mode << 2; EX_NUM its
                         value when an integer of INT's operand (~0u for P1) */
  struct expr *a, *b;
};

enum word_kind {
  WK_G, WK_M,
  WK_REG,      /* R n, D1, F: assignment to a register (idx) */
  WK_SLOT,     /* X Y Z A I J K H, G04's X, G07's F...: a word slot (idx) */
  WK_AWR,      /* T11±E ...: array write (idx = arr | mode << 2) */
  WK_AOP,      /* TT, T0, T03: op = vm opcode, idx = mask */
  WK_L, WK_P, WK_PCOND, WK_PP
};

struct word {
  uint8_t kind;
  char letter;        /* address letter as written ('R', 'X', 'F', 'T' ...) */
  unsigned col;
  int num;            /* G/M number, R index, L/P target */
  unsigned idx;
  uint8_t op;
  struct expr *e;
};

struct text {
  unsigned col;       /* of the first character after the opening slash */
  char *s;            /* UTF-8, NUL-terminated */
  unsigned nchars;
};

struct m16_item { unsigned reg; char axis; int sign; unsigned col; };

#define MAX_WORDS 200
#define MAX_LINES 16
#define MAX_ITEMS 40

struct block {
  unsigned line, col;       /* first character of the block */
  int number;               /* -1: none */
  unsigned ncol;            /* column of the number */
  unsigned len;             /* significant characters (E-BLOCKLEN) */
  int bad;                  /* a parse error was reported */
  int badnum;               /* ... in its block number: what number it has is unknown */
  uint64_t g;               /* bit n: Gn present */
  uint32_t m;               /* bit n: Mn present */
  unsigned gcol[64], mcol[32];
  struct word w[MAX_WORDS];
  size_t nw;                  /* (size_t: no alias of the int and unsigned stores into its words) */
  /* the words indexed as the parser adds them (the compiler's questions) */
  uint16_t wslots;            /* bit s: a word fills slot s (WK_SLOT) */
  uint16_t wkinds;            /* bit k: a word of kind k (enum word_kind) */
  uint8_t wfirst[WK_PP + 1];  /* the index of the first word of each kind in wkinds */
  int wF;                     /* the index of the F word, -1 none */
  int hasD;                   /* a D1 word */
  uint8_t gw[64];             /* the indices of the G words, in text order */
  int ngw;
  int slashed;                /* a word with a slash argument (struct kp_more may be needed) */
  int slotrd;                 /* an operand X Y Z or A (an expression may read the slot it stores) */
  unsigned slotcol[SL__COUNT];  /* the column of the word filling each slot in wslots */
  struct expr *cond;        /* P(cond) */
  /* slash arguments */
  struct text g27, g33, m18;
  char g27form;             /* ':' (or none) or '-' (wrapped) */
  struct text g29[MAX_LINES];
  int ng29;
  struct expr *g28min, *g28max;
  int g28reg;               /* -1 none */
  unsigned g28col;
  char g37axis;
  unsigned g37col;
  struct m16_item m16[MAX_ITEMS];
  int nm16;
  unsigned m20[MAX_ITEMS];
  unsigned m20col[MAX_ITEMS];
  int nm20;
};

/* Bump allocator for one block's nodes and strings. */
struct arena {
  char *buf;
  size_t used, cap;
  struct arena_chunk *more;
  jmp_buf *oom;          /* where a failed allocation goes (the block being parsed), or NULL */
};

void *arena_alloc(struct arena *a, size_t n);
void arena_reset(struct arena *a);
void arena_free(struct arena *a);

#endif
