/* cairo, loaded with dlopen the first time a plot is drawn: linked
 * directly, its two dozen libraries (fontconfig, freetype, X11, png...)
 * tripled the start-up of every `s42 run`.  plot.c includes this after the
 * cairo headers and calls the functions by their usual names. */
#ifndef S42_CAIRO_DL_H
#define S42_CAIRO_DL_H

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <stddef.h>

#define S42_CAIRO_FNS(F) \
  F(cairo_arc) \
  F(cairo_arc_negative) \
  F(cairo_clip) \
  F(cairo_close_path) \
  F(cairo_create) \
  F(cairo_debug_reset_static_data) \
  F(cairo_destroy) \
  F(cairo_fill) \
  F(cairo_fill_preserve) \
  F(cairo_image_surface_create) \
  F(cairo_line_to) \
  F(cairo_move_to) \
  F(cairo_new_path) \
  F(cairo_paint) \
  F(cairo_pdf_surface_create_for_stream) \
  F(cairo_pdf_surface_set_metadata) \
  F(cairo_rectangle) \
  F(cairo_restore) \
  F(cairo_save) \
  F(cairo_select_font_face) \
  F(cairo_set_dash) \
  F(cairo_set_font_size) \
  F(cairo_set_line_cap) \
  F(cairo_set_line_join) \
  F(cairo_set_line_width) \
  F(cairo_set_source_rgb) \
  F(cairo_set_source_rgba) \
  F(cairo_show_text) \
  F(cairo_status) \
  F(cairo_status_to_string) \
  F(cairo_stroke) \
  F(cairo_stroke_preserve) \
  F(cairo_surface_destroy) \
  F(cairo_surface_finish) \
  F(cairo_surface_status) \
  F(cairo_surface_write_to_png_stream) \
  F(cairo_svg_surface_create_for_stream) \
  F(cairo_text_extents) \
  F(cairo_text_path)

struct s42_cairo {
#define S42_CAIRO_PTR(name) __typeof__(name) *name;
  S42_CAIRO_FNS(S42_CAIRO_PTR)
#undef S42_CAIRO_PTR
};
extern struct s42_cairo s42_cairo;

/* Load libcairo and resolve every function above: 0, or -1 with err. */
int s42_cairo_load(char *err, size_t n);

#ifndef S42_CAIRO_DL_IMPL
#define cairo_arc (*s42_cairo.cairo_arc)
#define cairo_arc_negative (*s42_cairo.cairo_arc_negative)
#define cairo_clip (*s42_cairo.cairo_clip)
#define cairo_close_path (*s42_cairo.cairo_close_path)
#define cairo_create (*s42_cairo.cairo_create)
#define cairo_debug_reset_static_data (*s42_cairo.cairo_debug_reset_static_data)
#define cairo_destroy (*s42_cairo.cairo_destroy)
#define cairo_fill (*s42_cairo.cairo_fill)
#define cairo_fill_preserve (*s42_cairo.cairo_fill_preserve)
#define cairo_image_surface_create (*s42_cairo.cairo_image_surface_create)
#define cairo_line_to (*s42_cairo.cairo_line_to)
#define cairo_move_to (*s42_cairo.cairo_move_to)
#define cairo_new_path (*s42_cairo.cairo_new_path)
#define cairo_paint (*s42_cairo.cairo_paint)
#define cairo_pdf_surface_create_for_stream (*s42_cairo.cairo_pdf_surface_create_for_stream)
#define cairo_pdf_surface_set_metadata (*s42_cairo.cairo_pdf_surface_set_metadata)
#define cairo_rectangle (*s42_cairo.cairo_rectangle)
#define cairo_restore (*s42_cairo.cairo_restore)
#define cairo_save (*s42_cairo.cairo_save)
#define cairo_select_font_face (*s42_cairo.cairo_select_font_face)
#define cairo_set_dash (*s42_cairo.cairo_set_dash)
#define cairo_set_font_size (*s42_cairo.cairo_set_font_size)
#define cairo_set_line_cap (*s42_cairo.cairo_set_line_cap)
#define cairo_set_line_join (*s42_cairo.cairo_set_line_join)
#define cairo_set_line_width (*s42_cairo.cairo_set_line_width)
#define cairo_set_source_rgb (*s42_cairo.cairo_set_source_rgb)
#define cairo_set_source_rgba (*s42_cairo.cairo_set_source_rgba)
#define cairo_show_text (*s42_cairo.cairo_show_text)
#define cairo_status (*s42_cairo.cairo_status)
#define cairo_status_to_string (*s42_cairo.cairo_status_to_string)
#define cairo_stroke (*s42_cairo.cairo_stroke)
#define cairo_stroke_preserve (*s42_cairo.cairo_stroke_preserve)
#define cairo_surface_destroy (*s42_cairo.cairo_surface_destroy)
#define cairo_surface_finish (*s42_cairo.cairo_surface_finish)
#define cairo_surface_status (*s42_cairo.cairo_surface_status)
#define cairo_surface_write_to_png_stream (*s42_cairo.cairo_surface_write_to_png_stream)
#define cairo_svg_surface_create_for_stream (*s42_cairo.cairo_svg_surface_create_for_stream)
#define cairo_text_extents (*s42_cairo.cairo_text_extents)
#define cairo_text_path (*s42_cairo.cairo_text_path)
#endif

#endif
