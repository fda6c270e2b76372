/* The Check suites of s42's unit tests, one per area, and the helpers they
 * share (tests/unit/util.c): compile a program from a string, disassemble
 * it into memory, run a VM to its end, look for a diagnostic. */
#ifndef S42_TEST_SUITES_H
#define S42_TEST_SUITES_H

#include <check.h>
#include <stddef.h>

#include "compile.h"
#include "diag.h"
#include "program.h"
#include "vm.h"

Suite *suite_lex(void);
Suite *suite_parse(void);
Suite *suite_compile(void);
Suite *suite_vm(void);
Suite *suite_machine(void);
Suite *suite_operator(void);
Suite *suite_session(void);
Suite *suite_screen(void);
Suite *suite_plugin(void);
Suite *suite_toolmodel(void);
Suite *suite_tuitext(void);
Suite *suite_modbus(void);
Suite *suite_travel(void);
Suite *suite_state(void);
Suite *suite_param(void);
Suite *suite_verify(void);
Suite *suite_words(void);
Suite *suite_lathe(void);
Suite *suite_u22(void);
Suite *suite_lplot(void);
Suite *suite_plot(void);
Suite *suite_mrun(void);

/* A program compiled from a C string, with its diagnostics. */
struct tprog {
  struct program p;
  struct diag_list d;
  int rc;                 /* comp_program's result */
  const char *src;
};

void tp_compile(struct tprog *t, const char *src);
void tp_free(struct tprog *t);
/* The disassembly as a malloc'd string (the caller frees it). */
char *tp_disasm(const struct tprog *t);
/* Run vm to its end or an error, doing nothing for VM_EV_BLOCK and
 * VM_EV_START; returns the last event. */
enum vm_event tp_run(struct vm *vm);
/* The index of the first diagnostic with this severity and code (line and
 * col 0: any), or -1. */
int tp_find(const struct diag_list *d, int sev, int code, unsigned line, unsigned col);
/* Number of diagnostics with this severity. */
size_t tp_count(const struct diag_list *d, int sev);
/* All diagnostics as text, for failure messages (static buffer). */
const char *tp_diags(const struct diag_list *d);

/* Doubles equal within eps, with both values in the failure message. */
#define ck_near(a, b, eps) do { \
    double ck_a_ = (a), ck_b_ = (b); \
    ck_assert_msg(ck_a_ - ck_b_ <= (eps) && ck_b_ - ck_a_ <= (eps), \
                  "%s = %.12g, expected %.12g (within %g)", #a, ck_a_, ck_b_, (double)(eps)); \
  } while (0)

#endif
