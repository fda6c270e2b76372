/* What the 2С42-65 says: its message table for the VM (vm/msgs.h), which
 * the front end gives every program it builds (comp_program).  The titles
 * are the machine's own screen texts, Ukrainian as on the 2С42-65 and
 * English for --lang en; the details are the messages of `s42 check` and a
 * run, in the language's own words (SI, TG, R12, M17, --max-blocks).  One
 * table: the rows below fill kp_msgs (kpmsg.c).  Named kpmsg.h, not
 * messages.h: display/messages.h (the screen's directives) is on the same
 * include paths. */
#ifndef S42_KPMSG_H
#define S42_KPMSG_H

#include "msgs.h"

/* KP_TITLE(code, "uk", "en"): a title may show the error's aux number with
 * one %d (E-ARRAY±: the array). */
#define KP_TITLES(T) \
  T(NONE,     "немає помилки",                       "no error") \
  T(SYNTAX,   "помилка синтаксису",                  "syntax error") \
  T(RANGE,    "значення поза діапазоном",            "value out of range") \
  T(FUNC,     "невідома функція",                    "unknown function") \
  T(GROUP,    "дві функції однієї групи",            "two functions of one group") \
  T(BLOCK,    "недопустиме поєднання в кадрі",       "forbidden combination in a block") \
  T(BLOCKLEN, "кадр довший за 320 символів",         "block longer than 320 characters") \
  T(PLANE,    "помилка площини інтерполяції",        "interpolation plane error") \
  T(ARC,      "помилка дуги",                        "arc error") \
  T(AXIS,     "недопустима координата",              "axis not allowed") \
  T(DIV0,     "ділення на нуль",                     "division by zero") \
  T(DOMAIN,   "аргумент поза областю визначення",    "argument out of domain") \
  T(TARGET,   "немає кадру переходу",                "jump or call target missing or duplicated") \
  T(SCOPE,    "перехід за межі програми",            "jump out of its unit") \
  T(SUB,      "помилка структури програми",          "bad program structure") \
  T(NEST,     "понад 8 рівнів вкладеності ПП",       "more than 8 nested sub calls") \
  T(ARRAYP,   "Порушена межа масиву %d +",           "array %d bound broken +") \
  T(ARRAYM,   "Порушена межа масиву %d –",           "array %d bound broken –") \
  T(WHEEL,    "реверс круга без M5",                 "wheel reversed without M5") \
  T(OSC,      "помилка осциляції",                   "oscillation error") \
  T(TEXT,     "помилка тексту",                      "text too long or malformed") \
  T(ORDER,    "порушено порядок діалогу",            "dialog order error") \
  T(TEETH,    "помилка пошуку зубців",               "tooth search error") \
  T(PLUGIN,   "функція недоступна",                  "function not available") \
  T(FEED,     "контурна швидкість дорівнює нулю",    "contour speed is zero") \
  T(LIMIT,    "вичерпано ліміт кадрів",              "block budget exhausted") \
  T(STATE,    "повторний пуск неможливий",           "restart refused") \
  T(TRAVEL,   "вихід за межу переміщення",           "travel limit") \
  T(THREAD,   "різьбу нарізати неможливо",           "thread cannot be cut")

/* The error line under the screen: the block number ("-": none), the title. */
#define KP_SCREEN_UK "помилка в КП №%s: %s"
#define KP_SCREEN_EN "error in block %s: %s"

/* KP_DETAIL(id, "text"): the arguments are vm/msgs.h's VM_DETAILS. */
#define KP_DETAILS(D) \
  D(STACK,    "the program needs a stack of %u values; this VM has %d") \
  D(DEPTH,    "the program nests calls %u deep; this VM has %d levels") \
  D(ARRAYS,   "the program has %u arrays of %u cells; this VM has %d of %d") \
  D(BUDGET,   "the budget of %llu blocks ran out (--max-blocks)") \
  D(NEST,     "a %dth nested sub call (at most %d levels)") \
  D(RETMAIN,  "M17 reached in the main program") \
  D(ARRAYM,   "array %d: pointer already at cell 0, cannot move back") \
  D(ARRAYP,   "array %d: pointer at %d, past the last cell %d") \
  D(CELL,     "array %u: value %s outside %s..%s") \
  D(PARAM,    "R%u = %s is outside %s..%s") \
  D(RULE,     "%s = %s is outside %s..%s") \
  D(SIN,      "SI(%s): argument outside %s..%s") \
  D(COS,      "CO(%s): argument outside %s..%s") \
  D(TAN,      "TG(%s): argument outside %s..%s") \
  D(TANPOLE,  "TG(%s): tangent of an odd multiple of 90 degrees") \
  D(ASIN,     "ASI(%s): argument outside -1..1") \
  D(ACOS,     "ACO(%s): argument outside -1..1") \
  D(ATAN,     "ATG(%s): argument outside %s..%s") \
  D(LOG,      "LO(%s): argument outside 0 (excluded)..%s") \
  D(DIV0,     "division of %s by zero") \
  D(POWNEG,   "power: negative base %s with the fractional exponent %s") \
  D(POWZERO,  "power: zero to the negative exponent %s") \
  D(OVERFLOW, "intermediate result too large (%s %s %s)")

extern const struct vm_msgs kp_msgs;

#endif
