// cvexact.h against the OpenCV it stands in for: random images, maps,
// centres and thresholds, each result compared to the last bit with the
// OpenCV call it replaces (cv::remap of the float image, cv::warpPolar,
// cv::threshold with cv::moments, Otsu's cv::threshold).
//   cvexact        exit 1 on any difference
#include "cvexact.h"

#include <opencv2/imgproc.hpp>

#include <cstdint>
#include <cstdio>
#include <cstring>

namespace {

uint64_t state = 0x5eed2c42;
int rnd(int n)   // 0 .. n-1
{
  state = state * 6364136223846793005ULL + 1442695040888963407ULL;
  return (int)((state >> 33) % (uint64_t)n);
}
float frnd(float lo, float hi) { return lo + (hi - lo) * (float)rnd(1 << 20) / (float)(1 << 20); }

bool same(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// an 8-bit image: noise, two levels with noise, a flat level, or a bright disc
cv::Mat image(int W, int H)
{
  cv::Mat img(H, W, CV_8U);
  const int mode = rnd(4), a = rnd(256), b = rnd(256), spread = 1 + rnd(40);
  for (int y = 0; y < H; y++)
    for (int x = 0; x < W; x++) {
      int v = mode == 0 ? rnd(256)
              : mode == 1 ? (rnd(2) ? a : b) + rnd(spread) - spread / 2
              : mode == 2 ? a
              : ((x - W / 2) * (x - W / 2) + (y - H / 3) * (y - H / 3) < W * H / 6 ? a : b) + rnd(spread) - spread / 2;
      img.at<unsigned char>(y, x) = (unsigned char)std::clamp(v, 0, 255);
    }
  return img;
}

}  // namespace

int main()
{
  long points = 0, bad = 0;
  int cases = 0;
  auto fail = [&](const char *what, int W, int H) {
    if (bad++ < 10)
      std::printf("FAIL %s (%d x %d image)\n", what, W, H);
  };

  // the sampler: cv::remap of the float image, both borders, positions
  // inside and out, on 1/64 and whole pixels
  for (int it = 0; it < 150; it++) {
    const int W = 2 + rnd(300), H = 2 + rnd(300), R = 1 + rnd(20), C = 1 + rnd(500);
    cv::Mat img8 = image(W, H), img;
    img8.convertTo(img, CV_32F, 1.0 / 255);
    cv::Mat mx(R, C, CV_32F), my(R, C, CV_32F);
    for (int i = 0; i < R; i++)
      for (int j = 0; j < C; j++) {
        float a = frnd(-3, W + 3), b = frnd(-3, H + 3);
        const int kind = rnd(4);
        if (kind == 1) {
          a = std::round(a * 64) / 64;
          b = std::round(b * 64) / 64;
        } else if (kind == 2) {
          a = (float)rnd(W);
          b = (float)rnd(H);
        }
        mx.at<float>(i, j) = a;
        my.at<float>(i, j) = b;
      }
    for (int border : {cv::BORDER_REPLICATE, cv::BORDER_CONSTANT}) {
      cv::Mat out;
      cv::remap(img, out, mx, my, cv::INTER_LINEAR, border);
      const cvexact::sampler at(img8, border);
      for (int i = 0; i < R; i++)
        for (int j = 0; j < C; j++, points++)
          if (!same(at(mx.at<float>(i, j), my.at<float>(i, j)), out.at<float>(i, j)))
            fail("sampler against cv::remap", W, H);
    }
  }

  // the polar unwrap: every column of cv::warpPolar
  for (int it = 0; it < 40; it++, cases++) {
    const int N = 64 + rnd(400);
    cv::Mat img8 = image(N, N), img;
    img8.convertTo(img, CV_32F, 1.0 / 255);
    const cv::Point2d c(N / 2.0 + frnd(-5, 5), N / 2.0 + frnd(-5, 5));
    const double rmax = std::floor(std::min({c.x, c.y, N - 1 - c.x, N - 1 - c.y}));
    const int cols = (int)rmax + rnd(3) * rnd(40), rows = 50 + rnd(1000);
    cv::Mat full;
    cv::warpPolar(img, full, cv::Size(cols, rows), c, rmax, cv::INTER_LINEAR | cv::WARP_POLAR_LINEAR | cv::WARP_FILL_OUTLIERS);
    const cvexact::polar unwrap(img8, c, rmax, cols, rows);
    std::vector<float> column(rows);
    for (int j = 0; j < cols; j++) {
      unwrap.column(j, column.data());
      for (int i = 0; i < rows; i++, points++)
        if (!same(column[i], full.at<float>(i, j)))
          fail("polar against cv::warpPolar", N, N);
    }
  }

  // the centroid and Otsu's threshold
  for (int it = 0; it < 1500; it++, cases++) {
    const int W = 1 + rnd(300), H = 1 + rnd(300);
    cv::Mat img8 = image(W, H), bin;
    const double t = it % 3 ? (rnd(300) - 20) / 255.0 + frnd(0, 1) / 255.0 : rnd(256) / 255.0;
    cv::threshold(img8, bin, t * 255.0, 255, cv::THRESH_BINARY);
    const cv::Moments mo = cv::moments(bin, true);
    double m00, m10, m01;
    cvexact::centroid(img8, t, m00, m10, m01);
    if (!same(m00, mo.m00) || !same(m10, mo.m10) || !same(m01, mo.m01))
      fail("centroid against cv::moments", W, H);
    const double otsu = cv::threshold(img8, bin, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    if (!same(cvexact::otsu(img8), otsu))
      fail("otsu against cv::threshold", W, H);
  }

  std::printf("cvexact: %ld sampled points and %d images against OpenCV %s: %s\n", points, cases, CV_VERSION,
              bad ? "DIFFERENCES" : "all equal");
  return bad ? 1 : 0;
}
