/* A test driver for the plot engine's lathe view (src/host/plot.h):
 * canonical calls from a little text file, as the lathe would make them,
 * into the engine (a lathe's machine), and the picture out.
 *
 *   driver CALLS OUT.{png,svg,pdf} [--stock DxL] [--xy R Z]...
 *
 * CALLS, one a line (X a diameter as in the programs, mm; '#' comments):
 *   at X Z            where the tool is (a CANON_TOOL call there)
 *   G0 X Z            STRAIGHT_TRAVERSE
 *   G1 X Z            STRAIGHT_FEED
 *   G2 X Z I K        ARC_FEED round the centre (I a diameter, absolute)
 *   G3 X Z I K        the other way
 *   G33 X Z P         a thread of pitch P: SYNCH_START, FEED, SYNCH_STOP
 *   end               the run ended (plot_end, status 0)
 *   error CODE N      the run failed at block N with CODE (status 1)
 * Prints "xy R Z X Y" for each --xy (where the point lands in the picture)
 * and "chuck Z" when the path cut past the stock's end.  Exit 0, or 1 with
 * the error on stderr. */
#include "canon.h"
#include "geom.h"
#include "plot.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double lmm[CANON_AXES] = {0.0005, 0.001, 0.001, 0.001, 0.001, 0.001};
static int64_t here[CANON_AXES];   /* where the last call left the tool */

static struct canon_call at(int kind, double x, double z)
{
  struct canon_call c;
  memset(&c, 0, sizeof c);
  c.kind = kind;
  memcpy(c.from, here, sizeof here);
  c.pos[0] = llround(x / 0.001);   /* the diameter in µm: 0.5 µm of radius */
  c.pos[2] = llround(z / 0.001);
  c.mm = lmm;
  c.f = 100;
  return c;
}

static void call(struct plot *pl, const struct canon_call *c)
{
  memcpy(here, c->pos, sizeof here);
  plot_call(pl, c);
}

int main(int argc, char **argv)
{
  if (argc < 3) {
    fprintf(stderr, "usage: driver CALLS OUT [--stock DxL] [--xy R Z]...\n");
    return 1;
  }
  struct plot_stock st = {0, 0, 0};
  char why[300];
  for (int i = 3; i < argc; i++)
    if (!strcmp(argv[i], "--stock") && i + 1 < argc) {
      if (plot_parse_stock(argv[++i], &st, why, sizeof why)) {
        fprintf(stderr, "driver: %s\n", why);
        return 1;
      }
    }
  FILE *f = fopen(argv[1], "r");
  if (!f) {
    perror(argv[1]);
    return 1;
  }
  struct plot *pl = plot_new(&st);
  struct canon_info in;
  memset(&in, 0, sizeof in);
  in.kind = "lathe";
  in.name = "16Б16Ф3";
  in.naxes = 2;
  for (int a = 0; a < CANON_AXES; a++)
    in.axis[a].mm = lmm[a];
  plot_begin(pl, &in, here);
  char line[256];
  int ln = 0;
  double cx = 0, cz = 0;   /* where the tool is, X a diameter */
  while (fgets(line, sizeof line, f)) {
    ln++;
    char *h = strchr(line, '#');
    if (h)
      *h = 0;
    char w[32] = "", code[64] = "";
    double x, z, i, k;
    int n;
    if (sscanf(line, "%31s", w) != 1)
      continue;
    struct canon_call c;
    int moved = 1;
    if (!strcmp(w, "at") && sscanf(line, "%*s %lf %lf", &x, &z) == 2) {
      c = at(CANON_TOOL, x, z);
      call(pl, &c);
    } else if ((!strcmp(w, "G0") || !strcmp(w, "G1")) && sscanf(line, "%*s %lf %lf", &x, &z) == 2) {
      c = at(w[1] == '0' ? CANON_TRAVERSE : CANON_FEED_LINE, x, z);
      call(pl, &c);
    } else if ((!strcmp(w, "G2") || !strcmp(w, "G3")) && sscanf(line, "%*s %lf %lf %lf %lf", &x, &z, &i, &k) == 4) {
      c = at(CANON_FEED_ARC, x, z);
      c.plane = GEOM_XZ;
      c.centre[0] = llround(i / 0.001);
      c.centre[1] = llround(k / 0.001);
      c.ccw = w[1] == '2';   /* the sink's sense: from X towards Z, a G02 */
      call(pl, &c);
    } else if (!strcmp(w, "G33") && sscanf(line, "%*s %lf %lf %lf", &x, &z, &k) == 3) {
      /* the synchronisation calls are where the tool is */
      c = at(CANON_SYNCH_START, cx, cz);
      c.v = k;
      call(pl, &c);
      c = at(CANON_FEED_LINE, x, z);
      call(pl, &c);
      c = at(CANON_SYNCH_STOP, x, z);
      call(pl, &c);
    } else if (!strcmp(w, "end")) {
      moved = 0;
      struct plot_result res = {0};
      res.n = -1;
      plot_end(pl, &res);
    } else if (!strcmp(w, "error") && sscanf(line, "%*s %63s %d", code, &n) == 2) {
      moved = 0;
      struct plot_result res = {0};
      res.status = 1;
      res.code = code;
      res.n = n;
      plot_end(pl, &res);
    } else {
      fprintf(stderr, "%s:%d: not understood: %s", argv[1], ln, line);
      return 1;
    }
    if (moved) {
      cx = x;
      cz = z;
    }
  }
  fclose(f);
  for (int a = 3; a + 2 < argc; a++)
    if (!strcmp(argv[a], "--xy")) {
      double r = atof(argv[a + 1]), zz = atof(argv[a + 2]), px, py;
      plot_lathe_page_xy(pl, r, zz, &px, &py);
      printf("xy %g %g %.2f %.2f\n", r, zz, px, py);
    }
  double chz;
  if (plot_lathe_chuck(pl, &chz))
    printf("chuck %.3f\n", chz);
  if (plot_write(pl, argv[1], argv[2], why, sizeof why)) {
    fprintf(stderr, "driver: %s\n", why);
    plot_free(pl);
    return 1;
  }
  plot_free(pl);
  return 0;
}
