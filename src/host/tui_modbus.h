/* s42 tui --modbus: the Modbus TCP server as a source of the terminal's loop. */
#ifndef S42_TUI_MODBUS_H
#define S42_TUI_MODBUS_H

#include "modbus.h"
#include "tui.h"
#include <stddef.h>

/* Listen as o says (src/host/modbus.h: mb_open) and fill src for tui_main.  -1
 * with a message in err, *usage set when the address itself is bad (exit
 * 2).  A warning about the address goes to stderr now and to the messages
 * pane when the terminal starts. */
int tui_modbus_open(const struct mb_opts *o, struct tui_source *src, char *err, size_t n, int *usage);
void tui_modbus_close(struct tui_source *src);

#endif
