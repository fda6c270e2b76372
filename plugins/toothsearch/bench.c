/* Tooth-search timings for make bench: the time to render one probe image
 * and to run one whole search (with M10: two sections, 2 x TS_SHOTS images),
 * as "bench NAME VALUE UNIT" lines, for each tool model given. */
#include "render.h"
#include "toothsearch.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + t.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
  for (int i = 1; i < argc; i++) {
    struct tm_model m;
    char err[512];
    if (tm_load(&m, argv[i], err, sizeof err) != 0) {
      fprintf(stderr, "%s\n", err);
      return 1;
    }
    unsigned char *pix = malloc((size_t)m.image * m.image);
    if (!pix)
      return 1;
    const int nimg = 8, nsearch = 3;
    double t0 = now();
    for (int k = 0; k < nimg; k++) {
      struct ts_view v = {0, 45.0 * k, 0, 0, (uint32_t)k};
      if (ts_render(&m, &v, pix, NULL, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return 1;
      }
    }
    double ti = (now() - t0) / nimg;
    struct ts_request rq;
    memset(&rq, 0, sizeof rq);
    rq.x2_um = 40000;
    rq.a2_deg = ts_follow_flute(&m, 0, 0, rq.x2_um);
    rq.hand = m.hand;
    struct ts_result r;
    t0 = now();
    for (int k = 0; k < nsearch; k++)
      if (ts_search(&m, &rq, &r, err, sizeof err) != TS_OK) {
        fprintf(stderr, "%s\n", err);
        return 1;
      }
    double ts = (now() - t0) / nsearch;
    printf("bench toothsearch_image %.1f ms  (%s, %d px, %d teeth)\n", ti * 1000, argv[i], m.image, m.teeth);
    printf("bench toothsearch_search %.1f ms  (%s, M10, %d images)\n", ts * 1000, argv[i], r.images);
    printf("bench toothsearch_measure_per_image %.1f ms\n", (ts - r.images * ti) / r.images * 1000);
    free(pix);
  }
  return 0;
}
