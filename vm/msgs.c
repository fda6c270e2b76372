/* The VM's texts and the check of a dialect's table (vm/msgs.h). */
#include "msgs.h"
#include <stdio.h>
#include <string.h>

const struct vm_msgs vm_msgs_neutral = {
  .name = "the VM's neutral texts",
  .title = {
#define TITLE(e, c, text) text,
    {S42_ERRORS(TITLE)},
    {S42_ERRORS(TITLE)},
#undef TITLE
  },
  .screen = {"error in block %s: %s", "error in block %s: %s"},
  .detail = {
#define DETAIL(id, args, text) text,
    VM_DETAILS(DETAIL)
#undef DETAIL
  },
};

static const char *const detail_args[VMSG__COUNT] = {
#define ARGS(id, args, text) args,
  VM_DETAILS(ARGS)
#undef ARGS
};

static const char *const detail_name[VMSG__COUNT] = {
#define NAME(id, args, text) #id,
  VM_DETAILS(NAME)
#undef NAME
};

const char *vm_msg_title(const struct vm_msgs *m, int code, int en)
{
  if (code < 0 || code >= S42_E_COUNT)
    return "?";
  en = en ? 1 : 0;
  return m && m->title[en][code] ? m->title[en][code] : vm_msgs_neutral.title[en][code];
}

const char *vm_msg_screen(const struct vm_msgs *m, int en)
{
  en = en ? 1 : 0;
  return m && m->screen[en] ? m->screen[en] : vm_msgs_neutral.screen[en];
}

const char *vm_msg_detail(const struct vm_msgs *m, enum vm_detail id)
{
  if ((unsigned)id >= VMSG__COUNT)
    return "?";
  return m && m->detail[id] ? m->detail[id] : vm_msgs_neutral.detail[id];
}

/* The formats are the table's, not literals: vm_msgs_check proves each
 * uses the arguments given here, in order. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
void vm_msg_vformat(char *buf, size_t n, const struct vm_msgs *m, enum vm_detail id, va_list ap)
{
  vsnprintf(buf, n, vm_msg_detail(m, id), ap);
}

void vm_msg_machine(char *buf, size_t n, const struct vm_msgs *m, int code, long number, int aux, int en)
{
  char nb[24], title[200];
  if (number > 0)
    snprintf(nb, sizeof nb, "%ld", number);
  else
    strcpy(nb, "-");
  snprintf(title, sizeof title, vm_msg_title(m, code, en), aux);
  snprintf(buf, n, vm_msg_screen(m, en), nb, title);
}
#pragma GCC diagnostic pop

void vm_msg_format(char *buf, size_t n, const struct vm_msgs *m, enum vm_detail id, ...)
{
  va_list ap;
  va_start(ap, id);
  vm_msg_vformat(buf, n, m, id, ap);
  va_end(ap);
}

static int bad(char *msg, size_t n, const char *what, const char *fmt, const char *why)
{
  if (msg && n)
    snprintf(msg, n, "%s \"%s\": %s", what, fmt, why);
  return -1;
}

/* One format: each conversion, in order, must be the next of args. */
static int check(const char *fmt, const char *args, const char *what, char *msg, size_t n)
{
  if (!fmt)
    return 0;   /* the VM's text is used */
  size_t used = 0, nargs = strlen(args);
  for (const char *p = fmt; *p; p++) {
    if (*p != '%')
      continue;
    p++;
    if (*p == '%')
      continue;
    while (*p && strchr("-+ #0", *p))
      p++;
    while (*p >= '0' && *p <= '9')
      p++;
    if (*p == '.') {
      p++;
      while (*p >= '0' && *p <= '9')
        p++;
    }
    if (*p == '*' || *p == '$')
      return bad(msg, n, what, fmt, "a width, precision or position taken from the arguments is not allowed");
    char kind = 0;
    if (p[0] == 'l' && p[1] == 'l') {
      p += 2;
      if (*p && strchr("uxXo", *p))
        kind = 'L';
    } else if (*p && strchr("di", *p)) {
      kind = 'd';
    } else if (*p && strchr("uxXo", *p)) {
      kind = 'u';
    } else if (*p == 's') {
      kind = 's';
    }
    if (!*p)
      return bad(msg, n, what, fmt, "it ends inside a conversion");
    if (!kind)
      return bad(msg, n, what, fmt, "a conversion that is not %d, %u, %llu or %s (or their x/o forms)");
    if (used == nargs) {
      char why[80];
      snprintf(why, sizeof why, "conversion %zu, but it has %zu argument%s", used + 1, nargs, nargs == 1 ? "" : "s");
      return bad(msg, n, what, fmt, why);
    }
    if (kind != args[used]) {
      static const char *const names[] = {"d", "an int", "u", "an unsigned", "L", "an unsigned long long", "s",
                                          "a string"};
      const char *want = "?", *got = "?";
      for (int i = 0; i < 8; i += 2) {
        if (names[i][0] == args[used])
          want = names[i + 1];
        if (names[i][0] == kind)
          got = names[i + 1];
      }
      char why[120];
      snprintf(why, sizeof why, "conversion %zu takes %s where the argument is %s", used + 1, got, want);
      return bad(msg, n, what, fmt, why);
    }
    used++;
  }
  return 0;
}

int vm_format_check(const char *fmt, const char *args, char *msg, size_t n)
{
  return check(fmt, args, "format", msg, n);
}

int vm_msgs_check(const struct vm_msgs *m, char *msg, size_t n)
{
  char what[64];
  if (!m)
    return 0;
  for (int en = 0; en < 2; en++) {
    for (int e = 0; e < S42_E_COUNT; e++) {
      snprintf(what, sizeof what, "title of %s (%s)", e ? err_code(e) : "no error", en ? "English" : "own language");
      if (check(m->title[en][e], VM_TITLE_ARGS, what, msg, n))
        return -1;
    }
    snprintf(what, sizeof what, "error line (%s)", en ? "English" : "own language");
    if (check(m->screen[en], VM_SCREEN_ARGS, what, msg, n))
      return -1;
  }
  for (int id = 0; id < VMSG__COUNT; id++) {
    snprintf(what, sizeof what, "detail %s", detail_name[id]);
    if (check(m->detail[id], detail_args[id], what, msg, n))
      return -1;
  }
  return 0;
}
