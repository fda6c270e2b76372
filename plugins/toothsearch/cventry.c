/* The one entry of toothsearch-cv.so (tscv.h): the table of the search's
 * functions.  Everything else in that library is hidden. */
#include "tscv.h"

static const struct ts_cv api = {
  .size = sizeof(struct ts_cv),
  .version = TS_CV_VERSION,
  .pass = ts_search_pass,
  .combine = ts_search_combine,
  .first_tooth = ts_first_tooth,
  .follow_flute = ts_follow_flute,
  .revolution_time = ts_revolution_time,
};

__attribute__((visibility("default"))) const struct ts_cv *ts_cv_entry(void);
__attribute__((visibility("default"))) const struct ts_cv *ts_cv_entry(void)
{
  return &api;
}
