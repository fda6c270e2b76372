// toothsearch-png.so: the PNG writer of --dump-images (tscv.h), apart from
// the measurement because OpenCV's imgcodecs loads some 120 libraries.  One
// C entry, a ts_png_fn; it catches every exception.
#include "toothsearch.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <vector>

extern "C" __attribute__((visibility("default"))) int ts_png_write(const char *path, int rows, int cols, int channels, const unsigned char *data,
                            size_t step, int compression)
{
  try {
    if (!path || !data || rows <= 0 || cols <= 0 || (channels != 1 && channels != 3))
      return -1;
    const cv::Mat img(rows, cols, CV_8UC(channels), const_cast<unsigned char *>(data), step);
    std::vector<int> params;
    if (compression >= 0)
      params = {cv::IMWRITE_PNG_COMPRESSION, compression};
    return cv::imwrite(path, img, params) ? 0 : -1;
  } catch (...) {
    return -1;
  }
}
