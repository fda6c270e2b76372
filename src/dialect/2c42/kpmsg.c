/* The 2С42-65's message table (kpmsg.h). */
#include "kpmsg.h"

const struct vm_msgs kp_msgs = {
  .name = "the 2С42-65",
  .title = {
#define UK(e, uk, en) [S42_E_##e] = uk,
#define EN(e, uk, en) [S42_E_##e] = en,
    {KP_TITLES(UK)},
    {KP_TITLES(EN)},
#undef UK
#undef EN
  },
  .screen = {KP_SCREEN_UK, KP_SCREEN_EN},
  .detail = {
#define DETAIL(id, text) [VMSG_##id] = text,
    KP_DETAILS(DETAIL)
#undef DETAIL
  },
};
