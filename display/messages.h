/* The machine's own screen messages and directives, Ukrainian (as on the
 * 2С42-65) and English (--lang en), from one table.  PROBE1 .. HANDR are
 * those of a tooth-step search (language.md section 15), which plugins
 * show through the host's text() (include/s42_plugin.h S42_MSG_*). */
#ifndef S42_MESSAGES_H
#define S42_MESSAGES_H

/* MSG(id, "uk", "en") */
#define S42_MESSAGES(MSG) \
  MSG(BELOW,  "знач. менше допустимого", "value below the minimum") \
  MSG(ABOVE,  "знач. більше допустимого", "value above the maximum") \
  MSG(DONE,   "Введення завершено",       "Input complete") \
  MSG(LIMIT,  "Обмеження введення",       "Input buffer full") \
  MSG(NOCORR, "корекцію заборонено M23",  "corrections forbidden: M23") \
  MSG(NOOVR,  "корекцію F заборонено M25", "feed override forbidden: M25") \
  MSG(PROBE1, "упор в перетин 1",         "probe into section 1") \
  MSG(SEARCH1, "пошук в перетині 1",      "searching in section 1") \
  MSG(PROBE2, "упорку в переріз 2",       "probe into section 2") \
  MSG(SEARCH2, "пошук в перетині 2",      "searching in section 2") \
  MSG(RETRACT, "відвести упорку",         "retract the probe") \
  MSG(HANDL,  "виміряно лівий гвинт, не G10", "measured left hand, not G10") \
  MSG(HANDR,  "виміряно правий гвинт, не G11", "measured right hand, not G11")

enum screen_msg {
#define MSG_ENUM(id, uk, en) MSG_##id,
  S42_MESSAGES(MSG_ENUM)
#undef MSG_ENUM
  MSG__COUNT
};

static inline const char *screen_msg_text(int id, int en)
{
  static const char *const t[][2] = {
#define MSG_ROW(id, uk, en) {uk, en},
    S42_MESSAGES(MSG_ROW)
#undef MSG_ROW
  };
  return t[id][en ? 1 : 0];
}

#endif
