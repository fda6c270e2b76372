/* `--machine FILE`: what an installed machine adds to the model -- for
 * the ВЗ-208Ф3 the travel of each axis, which the seed does not give (so by
 * default there is none).  The file is `key = value` lines, `;` comments:
 *   travel x = -200 .. 200      ; mm, relative to the program's start position
 *   travel a = none             ; no limit (the default)
 * README "Travel limits" documents it. */
#ifndef S42_MACHFILE_H
#define S42_MACHFILE_H

#include "machine.h"
#include <stddef.h>
#include <stdio.h>

/* Parse the text of a machine file into *t.  0, or -1 after printing each
 * mistake as FILE:LINE:COL: error: ... on err. */
int machfile_parse(const char *text, size_t n, const char *file, struct mach_travel *t, FILE *err);

#endif
