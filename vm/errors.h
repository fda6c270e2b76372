/* The error codes of language.md section 17, with the machine's own message
 * for each (Ukrainian, as on the 2С42-65 screen, and English).  One table:
 * the enum, the code names and both message columns all come from it. */
#ifndef S42_ERRORS_H
#define S42_ERRORS_H

/* ERR(enum, "code", "uk", "en") */
#define S42_ERRORS(ERR) \
  ERR(NONE,     "",           "немає помилки",                       "no error") \
  ERR(SYNTAX,   "E-SYNTAX",   "помилка синтаксису",                  "syntax error") \
  ERR(RANGE,    "E-RANGE",    "значення поза діапазоном",            "value out of range") \
  ERR(FUNC,     "E-FUNC",     "невідома функція",                    "unknown function") \
  ERR(GROUP,    "E-GROUP",    "дві функції однієї групи",            "two functions of one group") \
  ERR(BLOCK,    "E-BLOCK",    "недопустиме поєднання в кадрі",       "forbidden combination in a block") \
  ERR(BLOCKLEN, "E-BLOCKLEN", "кадр довший за 320 символів",         "block longer than 320 characters") \
  ERR(PLANE,    "E-PLANE",    "помилка площини інтерполяції",        "interpolation plane error") \
  ERR(ARC,      "E-ARC",      "помилка дуги",                        "arc error") \
  ERR(AXIS,     "E-AXIS",     "недопустима координата",              "axis not allowed") \
  ERR(DIV0,     "E-DIV0",     "ділення на нуль",                     "division by zero") \
  ERR(DOMAIN,   "E-DOMAIN",   "аргумент поза областю визначення",    "argument out of domain") \
  ERR(TARGET,   "E-TARGET",   "немає кадру переходу",                "jump or call target missing or duplicated") \
  ERR(SCOPE,    "E-SCOPE",    "перехід за межі програми",            "jump out of its unit") \
  ERR(SUB,      "E-SUB",      "помилка структури програми",          "bad program structure") \
  ERR(NEST,     "E-NEST",     "понад 8 рівнів вкладеності ПП",       "more than 8 nested sub calls") \
  ERR(ARRAYP,   "E-ARRAY+",   "Порушена межа масиву +",              "array bound exceeded +") \
  ERR(ARRAYM,   "E-ARRAY-",   "Порушена межа масиву –",              "array bound exceeded -") \
  ERR(WHEEL,    "E-WHEEL",    "реверс круга без M5",                 "wheel reversed without M5") \
  ERR(OSC,      "E-OSC",      "помилка осциляції",                   "oscillation error") \
  ERR(TEXT,     "E-TEXT",     "помилка тексту",                      "text too long or malformed") \
  ERR(ORDER,    "E-ORDER",    "порушено порядок діалогу",            "dialog order error") \
  ERR(TEETH,    "E-TEETH",    "помилка пошуку зубців",               "tooth search error") \
  ERR(PLUGIN,   "E-PLUGIN",   "функція недоступна",                  "function not available") \
  ERR(FEED,     "E-FEED",     "контурна швидкість дорівнює нулю",    "contour speed is zero") \
  ERR(LIMIT,    "E-LIMIT",    "вичерпано ліміт кадрів",              "block budget exhausted") \
  ERR(STATE,    "E-STATE",    "повторний пуск неможливий",           "restart refused") \
  ERR(TRAVEL,   "E-TRAVEL",   "вихід за межу переміщення",           "travel limit")

enum s42_err {
#define ERR_ENUM(e, c, uk, en) S42_E_##e,
  S42_ERRORS(ERR_ENUM)
#undef ERR_ENUM
  S42_E_COUNT
};

const char *err_code(int e);            /* "E-ARC" */
const char *err_title(int e, int en);   /* the machine message */
int err_from_code(const char *code);    /* -1 when unknown */

#endif
