/* The 2У22's function tables (u22.h) and its message table (u22c.h). */
#include "u22.h"
#include "u22c.h"

const int u22_g_number[UG_N] = {
  [UG01] = 1, [UG02] = 2, [UG03] = 3, [UG04] = 4, [UG09] = 9, [UG20] = 20, [UG21] = 21, [UG23] = 23,
  [UG25] = 25, [UG33] = 33, [UG90] = 90, [UG91] = 91, [UG94] = 94, [UG95] = 95, [UG96] = 96, [UG97] = 97,
};

const int u22_m_number[UM_N] = {
  [UM00] = 0, [UM01] = 1, [UM02] = 2, [UM03] = 3, [UM04] = 4, [UM05] = 5, [UM08] = 8, [UM09] = 9,
  [UM17] = 17, [UM20] = 20, [UM30] = 30, [UM38] = 38, [UM39] = 39,
};

/* The machine itself shows only "?" (L207, L488): the titles are s42's, in
 * Ukrainian as the 2С42's are and in English; the details that the VM's
 * neutral wording fits are left NULL. */
const struct vm_msgs u22_msgs = {
  .name = "the 2У22",
  .title = {
    {
      [S42_E_NONE] = "немає помилки",
      [S42_E_SYNTAX] = "помилка синтаксису",
      [S42_E_RANGE] = "значення поза діапазоном",
      [S42_E_FUNC] = "невідома функція",
      [S42_E_GROUP] = "дві функції однієї групи",
      [S42_E_BLOCK] = "адреса повторюється в кадрі",
      [S42_E_BLOCKLEN] = "кадр довший за 80 символів",
      [S42_E_PLANE] = "помилка площини інтерполяції",
      [S42_E_ARC] = "помилка дуги",
      [S42_E_AXIS] = "недопустима координата",
      [S42_E_DIV0] = "ділення на нуль",
      [S42_E_DOMAIN] = "аргумент поза областю визначення",
      [S42_E_TARGET] = "немає підпрограми",
      [S42_E_SCOPE] = "перехід за межі програми",
      [S42_E_SUB] = "помилка структури програми",
      [S42_E_NEST] = "понад 2 рівні вкладеності",
      [S42_E_ARRAYP] = "Порушена межа масиву %d +",
      [S42_E_ARRAYM] = "Порушена межа масиву %d –",
      [S42_E_WHEEL] = "реверс шпинделя без зупинки",
      [S42_E_OSC] = "помилка осциляції",
      [S42_E_TEXT] = "помилка тексту",
      [S42_E_ORDER] = "порушено порядок діалогу",
      [S42_E_TEETH] = "помилка пошуку зубців",
      [S42_E_PLUGIN] = "функція недоступна",
      [S42_E_FEED] = "подача дорівнює нулю",
      [S42_E_LIMIT] = "вичерпано ліміт кадрів",
      [S42_E_STATE] = "повторний пуск неможливий",
      [S42_E_TRAVEL] = "вихід за межу переміщення",
      [S42_E_THREAD] = "різьбу неможливо нарізати",
    },
    {
      [S42_E_NONE] = "no error",
      [S42_E_SYNTAX] = "syntax error",
      [S42_E_RANGE] = "value out of range",
      [S42_E_FUNC] = "unknown function",
      [S42_E_GROUP] = "two functions of one group",
      [S42_E_BLOCK] = "address repeated in a block",
      [S42_E_BLOCKLEN] = "block longer than 80 characters",
      [S42_E_PLANE] = "interpolation plane error",
      [S42_E_ARC] = "arc error",
      [S42_E_AXIS] = "axis not allowed",
      [S42_E_DIV0] = "division by zero",
      [S42_E_DOMAIN] = "argument out of domain",
      [S42_E_TARGET] = "subprogram missing or duplicated",
      [S42_E_SCOPE] = "jump out of its unit",
      [S42_E_SUB] = "bad program structure",
      [S42_E_NEST] = "more than 2 nested levels",
      [S42_E_ARRAYP] = "array %d bound broken +",
      [S42_E_ARRAYM] = "array %d bound broken –",
      [S42_E_WHEEL] = "spindle reversed without a stop",
      [S42_E_OSC] = "oscillation error",
      [S42_E_TEXT] = "text too long or malformed",
      [S42_E_ORDER] = "dialog order error",
      [S42_E_TEETH] = "tooth search error",
      [S42_E_PLUGIN] = "function not available",
      [S42_E_FEED] = "feed is zero",
      [S42_E_LIMIT] = "block budget exhausted",
      [S42_E_STATE] = "restart refused",
      [S42_E_TRAVEL] = "travel limit",
      [S42_E_THREAD] = "thread cannot be cut",
    },
  },
  .screen = {"помилка в кадрі %s: %s", "error in block %s: %s"},
  .detail = {
    [VMSG_BUDGET] = "the budget of %llu blocks ran out (--max-blocks)",
    [VMSG_NEST] = "a sub call %d levels deep (the 2У22 nests 2)",
    [VMSG_RETMAIN] = "M17 reached outside a subprogram",
    [VMSG_PARAM] = "R%u = %s is outside %s..%s",
  },
};
