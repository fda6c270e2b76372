/* The renderer against its definition: every model given is rendered in a
 * few views (sections, turns, an edge exactly at camera angle 0 and just
 * short of 360) by ts_render and by ts_render_reference, which makes every
 * pixel as the renderer was first written; the images must be the same
 * byte for byte.
 *   render_ref tests/toothsearch/NAME.tool ...   exit 1 on any difference */
#include "render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
  int bad = 0, images = 0;
  for (int i = 1; i < argc; i++) {
    struct tm_model m;
    char err[512];
    if (tm_load(&m, argv[i], err, sizeof err) != 0) {
      printf("FAIL %s\n", err);
      bad++;
      continue;
    }
    size_t size = (size_t)m.image * m.image;
    unsigned char *fast = malloc(size), *ref = malloc(size);
    if (!fast || !ref)
      return 1;
    double edge[TM_MAX_TEETH], width[TM_MAX_TEETH];
    ts_geometry(&m, 0, edge, width);
    /* x, A, mount, section, shot: the last two put tooth 0's edge at camera
     * angle 0 exactly and a hair below 360 */
    const struct ts_view views[] = {
      {0, 0, 0, 0, 0},
      {5000, 17.3, 3.7, 1, 3},
      {-12345.6, 1e6 + 0.1, 211.25, 0, 7},
      {0, -edge[0], 0, 1, 1},
      {0, -edge[0] - 1e-9, 0, 0, 2},
    };
    int nv = (int)(sizeof views / sizeof views[0]), differ = 0;
    for (int k = 0; k < nv; k++) {
      if (ts_render(&m, &views[k], fast, NULL, err, sizeof err) != 0 ||
          ts_render_reference(&m, &views[k], ref, NULL, err, sizeof err) != 0) {
        printf("FAIL %s: %s\n", argv[i], err);
        bad++;
        break;
      }
      images++;
      if (memcmp(fast, ref, size) != 0) {
        size_t n = 0;
        for (size_t p = 0; p < size; p++)
          n += fast[p] != ref[p];
        printf("FAIL %s view %d: %zu pixels differ from the reference\n", argv[i], k, n);
        differ++;
      }
    }
    bad += differ;
    free(fast);
    free(ref);
  }
  printf("render_ref: %d images, %s\n", images, bad ? "DIFFERENCES" : "all equal to the reference");
  return bad ? 1 : 0;
}
