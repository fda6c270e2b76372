/* Operator scripts for headless runs (contracts.md section 3): parsed whole
 * before the run; a malformed line refuses the script with its line and
 * column.  Nothing is cut short: a word longer than 63 characters or one
 * with a NUL byte is an error, not read as its first 63 bytes. */
#ifndef S42_OPERATOR_H
#define S42_OPERATOR_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

enum op_kind { OA_ANSWER, OA_KEY, OA_JOG, OA_CORRECT, OA_OVERRIDE, OA_SECTION, OA_MODE, OA_BREAK, OA_ZERO };
/* OA_MODE's switch (n2): single block (П/АВТ), block skip (U/), optional stop (ST) */
enum op_mode { OPMODE_SINGLE, OPMODE_SKIP, OPMODE_OPTSTOP };
enum op_key { OPKEY_PUSK, OPKEY_PS, OPKEY_EXIT, OPKEY_STOP };

struct op_action {
  int kind;
  int key;                 /* OA_KEY */
  int axis, axis2;         /* OA_JOG, OA_CORRECT, OA_SECTION (axis2 -1 none); OA_ZERO: bit k
                              axis k of OPS_AXES given */
  int64_t n, n2;           /* amounts; OA_ANSWER the number; OA_OVERRIDE %; OA_MODE n 1 on, 0 off
                              (`mode auto`: single off), n2 the switch (enum op_mode);
                              OA_BREAK the block number, 0 off */
  int64_t zero[6];         /* OA_ZERO: µm (0.001 deg) of each axis of OPS_AXES */
  unsigned line, col;       /* where the action (or its `at`) starts */
  int at_number;           /* `at N54#3 ...`: block number, -1 not an at line */
  unsigned at_run;         /* which run of it (1 = first) */
  int fired;
};

struct opscript {
  struct op_action *v;     /* the ordered actions */
  size_t n;
  struct op_action *at;    /* the `at` actions */
  size_t nat;
};

#define OPS_WORD_MAX 63     /* characters in a word */
#define OPS_AXES "XYZABC"   /* zero's axes, in canonical order */
#define OPS_NAXES 6

/* Parse; on errors print FILE:LINE:COL: messages to err and return -1. */
int ops_parse(const char *text, size_t len, const char *file, struct opscript *s, FILE *err);
void ops_free(struct opscript *s);
/* Before the run: every `at` and `break` names a block number the program
 * has (have[n] for n 1..999).  -1 with FILE:LINE:COL: errors when one does not. */
int ops_check_at(const struct opscript *s, const unsigned char have[1000], const char *file, FILE *err);
/* After the run: a warning for each ordered action from `next` on that
 * was not used (but `skip`, 1-based, already reported; 0 none), and for
 * each `at` that never fired, with how often its block started (runs[n],
 * or NULL). */
void ops_warn_unused(const struct opscript *s, size_t next, size_t skip, const unsigned *runs, const char *file,
                     FILE *err);
/* Waiting actions are consumed when the machine waits; the others apply at
 * the next block boundary. */
int ops_is_waiting(const struct op_action *a);
const char *ops_describe(const struct op_action *a, char *buf, size_t n);

#endif
