/* What every report needs: JSON strings and numbers as the trace and the
 * dump print them (the C locale, fixed formats), and a machine's message
 * for an error in its dialect's texts. */
#ifndef S42_REPORT_H
#define S42_REPORT_H

#include <stddef.h>
#include <stdio.h>

struct program;
void json_string(FILE *f, const char *s);
void json_num(FILE *f, double v);
/* The machine's message for an error, in the texts of program p (its
 * dialect's table, vm/msgs.h; NULL: the VM's neutral ones): the 2С42-65's
 * "помилка в КП №n: ..." (number <= 0: "-"). */
void report_machine_msg(char *buf, size_t n, const struct program *p, int code, int number, int aux, int en);

#endif
