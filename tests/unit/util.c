/* Helpers shared by the unit suites (tests/unit/suites.h). */
#include "suites.h"
#include "disasm.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void tp_compile(struct tprog *t, const char *src)
{
  t->src = src;
  prog_init(&t->p);
  diag_init(&t->d, "t.kp");
  t->rc = comp_program(src, strlen(src), &t->d, &t->p);
}

void tp_free(struct tprog *t)
{
  prog_free(&t->p);
  diag_free(&t->d);
}

char *tp_disasm(const struct tprog *t)
{
  char *buf = NULL;
  size_t n = 0;
  FILE *f = open_memstream(&buf, &n);
  ck_assert_ptr_nonnull(f);
  vm_disasm(f, &t->p, t->src, strlen(t->src));
  fclose(f);
  return buf;
}

enum vm_event tp_run(struct vm *vm)
{
  for (;;) {
    enum vm_event ev = vm_run(vm);
    if (ev == VM_EV_END || ev == VM_EV_ERROR)
      return ev;
  }
}

int tp_find(const struct diag_list *d, int sev, int code, unsigned line, unsigned col)
{
  for (size_t i = 0; i < d->n; i++) {
    const struct diag *g = &d->v[i];
    if (g->sev == sev && g->code == code && (!line || g->line == line) && (!col || g->col == col))
      return (int)i;
  }
  return -1;
}

size_t tp_count(const struct diag_list *d, int sev)
{
  size_t n = 0;
  for (size_t i = 0; i < d->n; i++)
    n += d->v[i].sev == sev;
  return n;
}

const char *tp_diags(const struct diag_list *d)
{
  static char buf[8192];
  FILE *f = fmemopen(buf, sizeof buf, "w");
  if (!f)
    return "?";
  diag_print(f, d);
  fclose(f);
  buf[sizeof buf - 1] = 0;
  return buf;
}
