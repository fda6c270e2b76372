/* The 2С42 parser: one block at a time, from the lexer into struct block. */
#ifndef S42_PARSE_H
#define S42_PARSE_H

#include "ast.h"
#include "lex.h"
#include "words.h"   /* kp_valid_g, kp_valid_m, kp_g_group */

struct plug_set;
struct parser {
  struct lex lx;
  struct arena ar;
  struct diag_list *d;
  /* size_t: the int and unsigned stores of the parse (nodes, words) are
   * no aliases of these, which the compiler then keeps in registers */
  size_t paren;           /* open parentheses in the current expression */
  size_t nodes;           /* expression nodes in the current block, bounded */
  struct expr *nodebuf;   /* the block's nodes (MAX_NODES of them, from the first), or NULL */
  size_t nodecap;         /* MAX_NODES once nodebuf is made, 0 before */
  size_t slash_ends;      /* G28 /min:max/: a '/' outside parentheses closes it */
  const struct plug_set *plugins;  /* functions plugins add (src/core/plugin.h), or NULL */
  /* the block being parsed, and where a syntax error leaves it (parse.c's fail) */
  struct block *b;
  jmp_buf jb;
};

void parse_init(struct parser *p, const char *src, size_t n, struct diag_list *d);
void parse_free(struct parser *p);
/* Parse the next non-empty block into b.  Returns 1 when a block was read,
 * 0 at the end of the text.  Errors are reported and set b->bad. */
int parse_block(struct parser *p, struct block *b);
/* Every block, each one into b and then to each(ctx, b), which returns
 * nonzero to stop: parse_block over the whole text, with one setjmp. */
void parse_all(struct parser *p, struct block *b, int (*each)(void *ctx, struct block *b), void *ctx);

#endif
