/* Writing a picture (src/host/picture.h). */
#include "picture.h"
#include "atomic.h"
#include "cairo_dl.h"
#include <errno.h>
#include <locale.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

int picture_check_path(const char *path, char *err, size_t n)
{
  const char *dot = path ? strrchr(path, '.') : NULL;
  const char *slash = path ? strrchr(path, '/') : NULL;
  if (dot && (!slash || dot > slash + 1) &&
      (!strcasecmp(dot, ".png") || !strcasecmp(dot, ".svg") || !strcasecmp(dot, ".pdf")))
    return 0;
  snprintf(err, n, "cannot tell the picture format of '%s': the output file must end in .png, .svg or .pdf",
           path ? path : "");
  return -1;
}

int picture_check_output(const char *path, const char *program, char *err, size_t n)
{
  if (picture_check_path(path, err, n))
    return -1;
  if (file_same_as(path, program)) {
    snprintf(err, n, "-o %s is the program %s (the same file): the picture would take its place; "
             "write it to another file", path, program);
    return -1;
  }
  return 0;
}

void picture_fix_point(char *s)
{
  const char *dp = localeconv()->decimal_point;
  if (!dp || !strcmp(dp, "."))
    return;
  size_t l = strlen(dp);
  char *p = strstr(s, dp);
  if (p) {
    *p = '.';
    memmove(p + 1, p + l, strlen(p + l) + 1);
  }
}

static cairo_status_t write_fn(void *closure, const unsigned char *data, unsigned int len)
{
  FILE *f = closure;
  return fwrite(data, 1, len, f) == len ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

/* The SVG cairo wrote, with head after the root's tag: 0 or an errno. */
static int svg_out(FILE *f, const char *svg, size_t len, const char *head)
{
  const char *root = svg ? strstr(svg, "<svg") : NULL;
  const char *gt = root ? strchr(root, '>') : NULL;
  size_t at = gt ? (size_t)(gt + 1 - svg) : len;
  if (fwrite(svg, 1, at, f) != at)
    return errno ? errno : EIO;
  if (gt)
    fputs(head, f);
  if (fwrite(svg + at, 1, len - at, f) != len - at || ferror(f))
    return errno ? errno : EIO;
  return 0;
}

int picture_write(const char *path, double w, double h, const char *title, void (*draw)(cairo_t *cr, void *ctx),
                  char *(*svg_head)(void *ctx), void *ctx, char *err, size_t n)
{
  if (picture_check_path(path, err, n) || s42_cairo_load(err, n))
    return -1;
  const char *ext = strrchr(path, '.');
  int kind = !strcasecmp(ext, ".png") ? 0 : !strcasecmp(ext, ".svg") ? 1 : 2;
  size_t len = strlen(path);
  char *tmp = malloc(len + 16);
  if (!tmp) {
    snprintf(err, n, "out of memory");
    return -1;
  }
  snprintf(tmp, len + 16, "%s.tmpXXXXXX", path);
  int fd = mkstemp(tmp);
  if (fd < 0) {
    int e = errno;
    const char *slash = strrchr(path, '/');
    int dlen = slash ? (int)(slash - path) : 1;
    snprintf(err, n, "cannot create a file in %.*s: %s", dlen > 0 ? dlen : 1, slash && dlen > 0 ? path : slash ? "/" : ".",
             strerror(e));
    free(tmp);
    return -1;
  }
  mode_t um = umask(0);
  umask(um);
  if (fchmod(fd, 0666 & ~um) != 0) {
    /* not fatal: the file keeps mkstemp's 0600 */
  }
  FILE *f = fdopen(fd, "wb");
  if (!f) {
    snprintf(err, n, "%s", strerror(errno));
    close(fd);
    unlink(tmp);
    free(tmp);
    return -1;
  }
  /* an SVG with a head is written to memory first, then with the head put in */
  char *svg = NULL;
  size_t svg_len = 0;
  FILE *out = f;
  if (kind == 1 && svg_head && !(out = open_memstream(&svg, &svg_len))) {
    snprintf(err, n, "out of memory");
    fclose(f);
    unlink(tmp);
    free(tmp);
    return -1;
  }
  cairo_surface_t *sf;
  if (kind == 0)
    sf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, (int)w, (int)h);
  else if (kind == 1)
    sf = cairo_svg_surface_create_for_stream(write_fn, out, w, h);
  else
    sf = cairo_pdf_surface_create_for_stream(write_fn, f, w, h);
  cairo_status_t st = cairo_surface_status(sf);
  if (st == CAIRO_STATUS_SUCCESS) {
    if (kind == 2)
      cairo_pdf_surface_set_metadata(sf, CAIRO_PDF_METADATA_TITLE, title ? title : "");
    cairo_t *cr = cairo_create(sf);
    draw(cr, ctx);
    st = cairo_status(cr);
    cairo_destroy(cr);
    if (st == CAIRO_STATUS_SUCCESS && kind == 0)
      st = cairo_surface_write_to_png_stream(sf, write_fn, f);
    cairo_surface_finish(sf);
    if (st == CAIRO_STATUS_SUCCESS)
      st = cairo_surface_status(sf);
  }
  cairo_surface_destroy(sf);
  /* nothing of cairo is left: let it drop its font caches (leak checkers
   * would count them) */
  cairo_debug_reset_static_data();
  int ioerr = 0;
  if (out != f) {
    if (fclose(out) != 0)
      ioerr = ENOMEM;
    else if (st == CAIRO_STATUS_SUCCESS) {
      char *head = svg_head(ctx);
      ioerr = head ? svg_out(f, svg, svg_len, head) : ENOMEM;
      free(head);
    }
    free(svg);
  }
  if (!ioerr && (fflush(f) != 0 || fsync(fileno(f)) != 0))
    ioerr = errno ? errno : EIO;
  if (fclose(f) != 0 && !ioerr)
    ioerr = errno ? errno : EIO;
  if (st != CAIRO_STATUS_SUCCESS || ioerr) {
    if (st != CAIRO_STATUS_SUCCESS)
      snprintf(err, n, "cairo: %s", cairo_status_to_string(st));
    else
      snprintf(err, n, "%s", strerror(ioerr));
    unlink(tmp);
    free(tmp);
    return -1;
  }
  if (rename(tmp, path) != 0) {
    snprintf(err, n, "cannot rename the finished picture into place: %s", strerror(errno));
    unlink(tmp);
    free(tmp);
    return -1;
  }
  free(tmp);
  return 0;
}
