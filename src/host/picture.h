/* Writing a picture for the plot engine (plot.c and its views, plot_view.h):
 * its format by the file's extension (.png, .svg, .pdf), drawn
 * with cairo (loaded at the first picture, cairo_dl.h) into a temporary
 * file beside the target, synced and renamed into place, so a failed or
 * interrupted plot never leaves half a picture under the name. */
#ifndef S42_PICTURE_H
#define S42_PICTURE_H

#include <stddef.h>

typedef struct _cairo cairo_t;

/* A number printed with %f in the C locale's decimal point whatever the
 * locale (the captions' numbers): the locale's point, if another, made '.'. */
void picture_fix_point(char *s);
/* Does the path end in .png, .svg or .pdf?  0, or -1 with err. */
int picture_check_path(const char *path, char *err, size_t n);
/* picture_check_path, and the path is not the program's file (program:
 * its path; NULL, no program): 0, or -1 with err. */
int picture_check_output(const char *path, const char *program, char *err, size_t n);
/* Draw a w x h picture (px of the PNG, pt of the SVG and PDF) into path:
 * draw(cr, ctx) paints it; title: the PDF's title; svg_head, or NULL: after
 * the drawing, the text (malloc'd; NULL out of memory) to put right after
 * an SVG's root tag -- its <title> and <desc>, since cairo writes the
 * picture's text as glyphs.  0, or -1 with err. */
int picture_write(const char *path, double w, double h, const char *title, void (*draw)(cairo_t *cr, void *ctx),
                  char *(*svg_head)(void *ctx), void *ctx, char *err, size_t n);

#endif
