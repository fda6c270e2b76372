/* What the VM says, by the dialect's words.  The VM raises error codes
 * (vm/errors.h, shared by every dialect); the texts -- the machine's title
 * of each code in its own language and in English, the line the machine
 * shows for an error, and the VM's detail messages -- come from a table the
 * front end gives with the program (program.msgs).  An entry left NULL, or
 * no table at all, falls back to the VM's neutral English text.
 *
 * The texts are printf formats with fixed arguments.  VM_DETAILS names the
 * arguments of each detail message; a dialect's format must use them in
 * that order (a leading part of them: later ones may go unused), which
 * vm_msgs_check proves and prog_verify runs (vm/verify.h): a table that
 * passes it is as safe to format as a literal. */
#ifndef S42_MSGS_H
#define S42_MSGS_H

#include "errors.h"
#include <stdarg.h>
#include <stddef.h>

/* D(id, "arguments", "neutral text").  Arguments: d int, u unsigned,
 * L unsigned long long, s string; a number the program computed comes as a
 * string (%.10g). */
#define VM_DETAILS(D) \
  /* vm_init: the program needs more than this VM holds (E-LIMIT) */ \
  D(STACK,    "ud",   "the program needs a stack of %u values; this VM has %d") \
  D(DEPTH,    "ud",   "the program nests calls %u deep; this VM has %d levels") \
  D(ARRAYS,   "uudd", "the program has %u arrays of %u cells; this VM has %d of %d") \
  /* the run: the budget (count), a call too deep (its level, the limit), RET at depth 0 */ \
  D(BUDGET,   "L",    "the budget of %llu blocks ran out") \
  D(NEST,     "dd",   "a call %d levels deep (at most %d)") \
  D(RETMAIN,  "",     "return from the main program") \
  /* arrays: the array's number from 1, the pointer, the last cell */ \
  D(ARRAYM,   "d",    "array %d: pointer already at cell 0, cannot move back") \
  D(ARRAYP,   "ddd",  "array %d: pointer at %d, past the last cell %d") \
  /* a value outside its range: the array or register, the value, lo, hi */ \
  D(CELL,     "usss", "array %u: value %s outside %s..%s") \
  D(PARAM,    "usss", "r%u = %s is outside %s..%s") \
  D(RULE,     "ssss", "%s = %s is outside %s..%s") \
  /* functions: the argument (and the domain's ends) */ \
  D(SIN,      "sss",  "SIN(%s): argument outside %s..%s") \
  D(COS,      "sss",  "COS(%s): argument outside %s..%s") \
  D(TAN,      "sss",  "TAN(%s): argument outside %s..%s") \
  D(TANPOLE,  "s",    "TAN(%s): tangent of an odd multiple of 90 degrees") \
  D(ASIN,     "s",    "ASIN(%s): argument outside -1..1") \
  D(ACOS,     "s",    "ACOS(%s): argument outside -1..1") \
  D(ATAN,     "sss",  "ATAN(%s): argument outside %s..%s") \
  D(LOG,      "ss",   "LOG(%s): argument outside 0 (excluded)..%s") \
  /* arithmetic: the operands (and the operation's opcode name) */ \
  D(DIV0,     "s",    "division of %s by zero") \
  D(POWNEG,   "ss",   "power: negative base %s with the fractional exponent %s") \
  D(POWZERO,  "s",    "power: zero to the negative exponent %s") \
  D(OVERFLOW, "sss",  "intermediate result too large (%s %s %s)")

enum vm_detail {
#define VMSG_ENUM(id, args, text) VMSG_##id,
  VM_DETAILS(VMSG_ENUM)
#undef VMSG_ENUM
  VMSG__COUNT
};

/* The arguments of the other texts: a title gets the error's aux number (d:
 * the array of E-ARRAY±), the machine's line the block number (or "-") and
 * the title (ss). */
#define VM_TITLE_ARGS "d"
#define VM_SCREEN_ARGS "ss"

struct vm_msgs {
  const char *name;                        /* whose texts, for messages: "2С42-65" */
  const char *title[2][S42_E_COUNT];       /* [0] the machine's language, [1] English */
  const char *screen[2];                   /* the error line: "помилка в КП №%s: %s" */
  const char *detail[VMSG__COUNT];
};

/* The VM's own texts, in English (used for every NULL entry). */
extern const struct vm_msgs vm_msgs_neutral;

/* The format of each text (m may be NULL); never NULL. */
const char *vm_msg_title(const struct vm_msgs *m, int code, int en);
const char *vm_msg_screen(const struct vm_msgs *m, int en);
const char *vm_msg_detail(const struct vm_msgs *m, enum vm_detail id);
/* Detail message id with its arguments, into buf. */
void vm_msg_format(char *buf, size_t n, const struct vm_msgs *m, enum vm_detail id, ...);
void vm_msg_vformat(char *buf, size_t n, const struct vm_msgs *m, enum vm_detail id, va_list ap);
/* The machine's line for an error: the title (with aux) in the screen
 * format, with the block number (number <= 0: "-"). */
void vm_msg_machine(char *buf, size_t n, const struct vm_msgs *m, int code, long number, int aux, int en);

/* 0 when every format of m uses its arguments as declared above; -1 with
 * the first that does not in msg ("detail NEST: %s where an int is"). */
int vm_msgs_check(const struct vm_msgs *m, char *msg, size_t n);
/* One format against its arguments (a leading part of args, in order);
 * 0 or -1 with the reason in msg. */
int vm_format_check(const char *fmt, const char *args, char *msg, size_t n);

#endif
