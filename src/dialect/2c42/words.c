/* The G and M table (words.h) as arrays indexed by number, and the
 * questions asked of it.  Nothing here lists a function by hand: every
 * array and name comes from KP_WORDS. */
#include "words.h"
#include <stdio.h>
#include <string.h>

#define KP_SA(slash) KP_SA_##slash
#define KP_MO_OWN(code) MO_##code
#define KP_MO_NONE(code) MO_NONE
#define KP_MO_DIALOG(code) MO_DIALOG
#define ROW(kind, n, code, group, flags, plane, motion, slash, owner, name) \
  [n] = {kind, n, group, (flags), plane, KP_MO_##motion(code), KP_SA(slash), #code, owner, name},
#define G_ROW(...) ROW('G', __VA_ARGS__)
#define M_ROW(...) ROW('M', __VA_ARGS__)
#define SKIP(...)

const struct kp_word kp_gwords[64] = {KP_WORDS(G_ROW, SKIP)};
const struct kp_word kp_mwords[32] = {KP_WORDS(SKIP, M_ROW)};

/* The names of the motions, in enum order: the codes of the OWN rows. */
#define NAME_OWN(code) #code,
#define NAME_NONE(code)
#define NAME_DIALOG(code)
#define NAME(n, code, group, flags, plane, motion, ...) NAME_##motion(code)
const char *const kp_motion_name[MO__COUNT] = {"none", KP_WORDS(NAME, NAME) "dialog", "plugin"};

/* The flags of each motion's row (MO_NONE, MO_DIALOG, MO_PLUGIN: none). */
#define FLAGS_OWN(code, flags) [MO_##code] = (flags),
#define FLAGS_NONE(code, flags)
#define FLAGS_DIALOG(code, flags)
#define FLAGS(n, code, group, flags, plane, motion, ...) FLAGS_##motion(code, flags)
static const uint8_t motion_flags[MO__COUNT] = {KP_WORDS(FLAGS, FLAGS)};

const char *kp_codes(char *buf, size_t n, int (*pick)(const struct kp_word *w))
{
  size_t k = 0;
  if (n)
    buf[0] = 0;
  for (int i = 0; i < 64 + 32; i++) {
    const struct kp_word *w = i < 64 ? kp_g(i) : kp_m(i - 64);
    if (!w || !pick(w))
      continue;
    size_t need = strlen(w->code) + (k ? 1 : 0);
    if (k + need >= n)
      break;   /* a list cut short, never a code cut in two */
    k += (size_t)snprintf(buf + k, n - k, "%s%s", k ? " " : "", w->code);
  }
  return buf;
}

int kp_motion_arc(int motion)
{
  return motion >= 0 && motion < MO__COUNT && (motion_flags[motion] & KP_ARC);
}

int kp_valid_g(int n)
{
  return kp_g(n) != NULL;
}

int kp_valid_m(int n)
{
  return kp_m(n) != NULL;
}

int kp_g_group(int n)
{
  const struct kp_word *w = kp_g(n);
  return w ? w->group : 1;
}
