/* libFuzzer harness for the M15 restart state's loader (src/core/state.h): the
 * input is a state record -- a whole state file, or the record without its
 * header -- given the right header, checksum and program hash, as a file
 * edited by hand would have them.  state_restore must refuse it or give a
 * session that then runs safely: nothing may crash, hang or trip a
 * sanitizer.  The program is tests/restart/sub.kp's text. */
#include "compile.h"
#include "session.h"
#include "state.h"
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char prog[] =
  "; A restart point inside a sub called from the main program, with array\n"
  "; writes, a G29 display and an M18 directive: tests/restart/run.sh edits one\n"
  "; field of its state at a time (tests/restart/forge.c) and wants each refused.\n"
  "№10 R100+R100+1 T11+R100 M15 ^\n"
  "№11 G04 X+1 M17 ^\n"
  "№1 R100+0 F1000 M18 /ПРОХІД ((R100/ ^\n"
  "№2 G29 /ПРОХІД((R100// ^\n"
  "№3 G01 X+1000 L10 H3 ^\n"
  "№4 M02 ^\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  static struct program p;
  static int compiled;
  if (!compiled) {
    struct diag_list d;
    prog_init(&p);
    diag_init(&d, "sub.kp");
    if (comp_program(prog, sizeof prog - 1, &d, &p) != 0)
      abort();
    diag_free(&d);
    compiled = 1;
  }
  struct {
    struct state_header h;
    struct state_payload pl;
  } *f = calloc(1, sizeof *f);
  struct session *s = malloc(sizeof *s);
  if (!f || !s) {
    free(f);
    free(s);
    return 0;
  }
  if (size >= sizeof f->h && memcmp(data, STATE_MAGIC, 8) == 0) {
    data += sizeof f->h;
    size -= sizeof f->h;
  }
  memcpy(&f->pl, data, size < sizeof f->pl ? size : sizeof f->pl);
  uint64_t hash = state_hash(prog, sizeof prog - 1);
  f->pl.prog_hash = hash;
  memcpy(f->h.magic, STATE_MAGIC, 8);
  f->h.version = STATE_VERSION;
  f->h.size = sizeof f->pl;
  f->h.sum = state_hash(&f->pl, sizeof f->pl);
  sess_init(s, &p);
  char err[400];
  if (state_restore(s, f, sizeof *f, "fuzz.state", hash, err, sizeof err) == 0) {
    s->vm.max_blocks = s->vm.blocks + 500;
    for (int i = 0; i < 2000 && sess_run(s) == SE_START; i++)
      ;
  }
  free(s);
  free(f);
  return 0;
}
