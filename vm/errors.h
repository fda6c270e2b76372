/* The error codes of language.md section 17, shared by every dialect
 * (contracts.md section 8): the enum, the code names and a neutral meaning
 * of each, from one table.  What a machine *says* for a code -- the
 * 2С42-65's Ukrainian screen text, say -- is the dialect's, in the message
 * table its front end gives the program (vm/msgs.h). */
#ifndef S42_ERRORS_H
#define S42_ERRORS_H

/* ERR(enum, "code", "neutral meaning") */
#define S42_ERRORS(ERR) \
  ERR(NONE,     "",           "no error") \
  ERR(SYNTAX,   "E-SYNTAX",   "syntax error") \
  ERR(RANGE,    "E-RANGE",    "value out of range") \
  ERR(FUNC,     "E-FUNC",     "unknown function") \
  ERR(GROUP,    "E-GROUP",    "two functions of one group") \
  ERR(BLOCK,    "E-BLOCK",    "forbidden combination in a block") \
  ERR(BLOCKLEN, "E-BLOCKLEN", "block too long") \
  ERR(PLANE,    "E-PLANE",    "interpolation plane error") \
  ERR(ARC,      "E-ARC",      "arc error") \
  ERR(AXIS,     "E-AXIS",     "axis not allowed") \
  ERR(DIV0,     "E-DIV0",     "division by zero") \
  ERR(DOMAIN,   "E-DOMAIN",   "argument out of domain") \
  ERR(TARGET,   "E-TARGET",   "jump or call target missing or duplicated") \
  ERR(SCOPE,    "E-SCOPE",    "jump out of its unit") \
  ERR(SUB,      "E-SUB",      "bad program structure") \
  ERR(NEST,     "E-NEST",     "calls nested too deep") \
  ERR(ARRAYP,   "E-ARRAY+",   "array bound exceeded +") \
  ERR(ARRAYM,   "E-ARRAY-",   "array bound exceeded -") \
  ERR(WHEEL,    "E-WHEEL",    "spindle reversed without a stop") \
  ERR(OSC,      "E-OSC",      "oscillation error") \
  ERR(TEXT,     "E-TEXT",     "text too long or malformed") \
  ERR(ORDER,    "E-ORDER",    "dialog order error") \
  ERR(TEETH,    "E-TEETH",    "tooth search error") \
  ERR(PLUGIN,   "E-PLUGIN",   "function not available") \
  ERR(FEED,     "E-FEED",     "contour speed is zero") \
  ERR(LIMIT,    "E-LIMIT",    "limit exceeded") \
  ERR(STATE,    "E-STATE",    "restart refused") \
  ERR(TRAVEL,   "E-TRAVEL",   "travel limit") \
  ERR(THREAD,   "E-THREAD",   "thread cannot be cut")

enum s42_err {
#define ERR_ENUM(e, c, text) S42_E_##e,
  S42_ERRORS(ERR_ENUM)
#undef ERR_ENUM
  S42_E_COUNT
};

const char *err_code(int e);            /* "E-ARC" */
const char *err_meaning(int e);         /* the neutral meaning: "arc error" */
int err_from_code(const char *code);    /* -1 when unknown */

#endif
