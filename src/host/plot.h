/* `s42 plot`: the tool path of a headless run drawn with cairo (PNG, SVG or
 * PDF by the file's extension): the planes XY, XZ and YZ side by side with
 * coordinate ticks and scale bars, block numbers at block starts, arcs as
 * true arcs, manual and jog moves drawn apart from programmed ones, and A
 * against time; a run that failed is marked where and how it stopped. */
#ifndef S42_PLOT_H
#define S42_PLOT_H

#include "session.h"
#include <stddef.h>

struct plot;

struct plot *plot_new(void);
/* A session row sink: record the block's path. */
void plot_row(struct plot *pl, const struct session *s, const struct sess_row *r);
/* A session `moved` sink: a plugin moved an axis outside the contour
 * (oscillation), by d discretes; drawn apart from the programmed path. */
void plot_sample(struct plot *pl, const struct session *s, int axis, int64_t d);
/* How the run ended, at its end: s the session (NULL: the program did not
 * compile), status the exit status (0 end, 1 program error, 3 stopped),
 * code, n and line the error's code, block number (-1 none) and source
 * line (0 unknown) for status 1.  The header counts s's blocks, as the
 * dump does. */
void plot_result(struct plot *pl, const struct session *s, int status, const char *code, int n, unsigned line);
/* Is the output path's extension one we can write (.png .svg .pdf), and
 * is it not the program's file (program: its path, or NULL)?  0, or -1
 * with err. */
int plot_check_path(const char *path, const char *program, char *err, size_t n);
/* Draw and write the file (title: the program's name).  0, or -1 with err. */
int plot_write(struct plot *pl, const char *program, const char *path, char *err, size_t n);
void plot_free(struct plot *pl);

#endif
