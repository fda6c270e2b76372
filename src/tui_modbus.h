/* s42 tui --modbus: the Modbus TCP server as a source of the terminal's loop. */
#ifndef S42_TUI_MODBUS_H
#define S42_TUI_MODBUS_H

#include "tui.h"
#include <stddef.h>

/* Listen on addr (src/modbus.h: mb_open) and fill src for tui_main.  -1 with
 * a message in err, *usage set when the address itself is bad (exit 2). */
int tui_modbus_open(const char *addr, struct tui_source *src, char *err, size_t n, int *usage);
void tui_modbus_close(struct tui_source *src);

#endif
