/* "Did you mean" (src/core/nearest.h). */
#include "nearest.h"
#include <string.h>

/* Edit distance of a and b (each at most 63 characters) counting a swap of
 * two neighbours as one edit (optimal string alignment), for "did you mean". */
int word_distance(const char *a, const char *b)
{
  size_t na = strlen(a), nb = strlen(b);
  if (na > 63 || nb > 63)
    return 99;
  int d[64][64];
  for (size_t i = 0; i <= na; i++)
    d[i][0] = (int)i;
  for (size_t j = 0; j <= nb; j++)
    d[0][j] = (int)j;
  for (size_t i = 1; i <= na; i++)
    for (size_t j = 1; j <= nb; j++) {
      int best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
      if (d[i - 1][j] + 1 < best) best = d[i - 1][j] + 1;
      if (d[i][j - 1] + 1 < best) best = d[i][j - 1] + 1;
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < best)
        best = d[i - 2][j - 2] + 1;
      d[i][j] = best;
    }
  return d[na][nb];
}

/* The closest of the names (within a third of its length, at least 1
 * edit), or NULL. */
const char *nearest_word(const char *word, const char *const *names, size_t n)
{
  const char *best = NULL;
  int bd = 99, lim = (int)strlen(word) / 3 > 1 ? (int)strlen(word) / 3 : 1;
  for (size_t i = 0; i < n; i++) {
    int d = word_distance(word, names[i]);
    if (d < bd) {
      bd = d;
      best = names[i];
    }
  }
  return bd <= lim ? best : NULL;
}
