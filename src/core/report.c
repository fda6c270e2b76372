/* JSON and machine-message helpers every host and dialect uses (report.h). */
#include "report.h"
#include "msgs.h"
#include "program.h"
#include <math.h>
#include <string.h>

void json_string(FILE *f, const char *s)
{
  fputc('"', f);
  for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
    if (*p == '"' || *p == '\\')
      fprintf(f, "\\%c", *p);
    else if (*p == '\n')
      fputs("\\n", f);
    else if (*p < 0x20)
      fprintf(f, "\\u%04x", *p);
    else
      fputc(*p, f);
  }
  fputc('"', f);
}

void json_num(FILE *f, double v)
{
  if (!isfinite(v)) {
    fputs("null", f);
    return;
  }
  if (v == 0)
    v = 0;   /* no -0 */
  if (v == floor(v) && fabs(v) < 1e15)
    fprintf(f, "%.0f", v);
  else
    fprintf(f, "%.10g", v);
}

void report_machine_msg(char *buf, size_t n, const struct program *p, int code, int number, int aux, int en)
{
  vm_msg_machine(buf, n, p ? p->msgs : NULL, code, number, aux, en);
}

