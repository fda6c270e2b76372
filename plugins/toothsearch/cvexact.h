/* OpenCV's results without OpenCV's calls, for the measurement (measure.cpp):
 * each function here gives, to the last bit, what the OpenCV call in its
 * comment gives on the same input, by OpenCV's own arithmetic in OpenCV's
 * order, without the images, maps and buffers that call would make.  With
 * another OpenCV they may drift apart: tests/toothsearch/cvexact.cpp holds
 * them against the OpenCV the library is built with (make toothsearch). */
#ifndef S42_TS_CVEXACT_H
#define S42_TS_CVEXACT_H

#include <opencv2/core.hpp>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <vector>

namespace cvexact {

// The camera image as the float image img8.convertTo(img, CV_32F, 1 / 255.)
// would be (each level's value taken from convertTo itself), sampled at
// (mx, my) as cv::remap(img, dst, mapx, mapy, INTER_LINEAR, border)
// samples it from float maps (border REPLICATE or CONSTANT 0), for one
// point without the maps or the float image: the position rounded to 1/32
// pixel (INTER_TAB_SIZE, half to even), the weights of its 32 x 32 table
// (products of multiples of 1/32, exact in float), the four products summed
// in OpenCV's order, and its border rule.  Equal to cv::remap on 6.1
// million random points, borders included.
struct sampler {
  const unsigned char *data;
  size_t step;             // bytes a row
  int W, H, border;
  const float *level;      // the float of each 8-bit level

  sampler(const cv::Mat &img8, int border_)
    : data(img8.ptr()), step(img8.step), W(img8.cols), H(img8.rows), border(border_), level(levels()) {}

  static const float *levels()
  {
    static const cv::Mat lut = [] {
      cv::Mat l8(1, 256, CV_8U), l;
      for (int v = 0; v < 256; v++)
        l8.at<unsigned char>(v) = (unsigned char)v;
      l8.convertTo(l, CV_32F, 1.0 / 255);
      return l;
    }();
    return lut.ptr<float>();
  }

  // the weights of a position's 1/32 fractions (fy, fx): [fy * 32 + fx]
  static constexpr std::array<std::array<float, 4>, 32 * 32> weights = [] {
    std::array<std::array<float, 4>, 32 * 32> t{};
    for (int y = 0; y < 32; y++)
      for (int x = 0; x < 32; x++) {
        const float ty[2] = {1.f - y * (1.f / 32), y * (1.f / 32)}, tx[2] = {1.f - x * (1.f / 32), x * (1.f / 32)};
        for (int a = 0; a < 2; a++)
          for (int b = 0; b < 2; b++)
            t[y * 32 + x][a * 2 + b] = ty[a] * tx[b];
      }
    return t;
  }();

  __attribute__((always_inline)) float operator()(float mx, float my) const
  {
    const int X = (int)std::lrint(mx * 32.0f), Y = (int)std::lrint(my * 32.0f);
    const float *w = weights[(Y & 31) * 32 + (X & 31)].data();
    const int sx = X >> 5, sy = Y >> 5;
    if ((unsigned)sx < (unsigned)(W - 1) && (unsigned)sy < (unsigned)(H - 1)) {
      const unsigned char *s0 = data + sy * step + sx, *s1 = s0 + step;
      return level[s0[0]] * w[0] + level[s0[1]] * w[1] + level[s1[0]] * w[2] + level[s1[1]] * w[3];
    }
    return edge(std::clamp(sx, -32768, 32767), std::clamp(sy, -32768, 32767), w);   // remap's shorts
  }

  __attribute__((noinline)) float edge(int sx, int sy, const float *w) const
  {
    if (border == cv::BORDER_CONSTANT && (sx >= W || sx + 1 < 0 || sy >= H || sy + 1 < 0))
      return 0.0f;
    auto at = [&](int x, int y) {
      if (border == cv::BORDER_REPLICATE)
        return level[data[std::clamp(y, 0, H - 1) * step + std::clamp(x, 0, W - 1)]];
      return x >= 0 && x < W && y >= 0 && y < H ? level[data[y * step + x]] : 0.0f;
    };
    return at(sx, sy) * w[0] + at(sx + 1, sy) * w[1] + at(sx, sy + 1) * w[2] + at(sx + 1, sy + 1) * w[3];
  }
};

// The float image's polar unwrap as cv::warpPolar(img, dst, Size(cols,
// rows), c, rmax, INTER_LINEAR | WARP_POLAR_LINEAR | WARP_FILL_OUTLIERS)
// makes it (column j radius j * rmax / cols, row i angle 360 * i / rows), a
// column at a time: warpPolar's own map (its float centre, float radii and
// double angles, the same arithmetic) sampled as its cv::remap samples it.
struct polar {
  sampler at;
  int rows;
  double kmag;
  cv::Point2f cf;
  std::vector<double> cs, sn;

  polar(const cv::Mat &img8, cv::Point2d c, double rmax, int cols, int rows_)
    : at(img8, cv::BORDER_CONSTANT), rows(rows_), kmag(rmax / cols), cf(c), cs(rows_), sn(rows_)
  {
    const double kangle = CV_2PI / rows;
    for (int i = 0; i < rows; i++) {
      cs[i] = std::cos(kangle * i);
      sn[i] = std::sin(kangle * i);
    }
  }

  void column(int j, float *out) const
  {
    const float rho = (float)(j * kmag);
    for (int i = 0; i < rows; i++)
      out[i] = at((float)(rho * cs[i] + cf.x), (float)(rho * sn[i] + cf.y));
  }
};

// The silhouette's centroid as cv::moments(bin, true) gives it, bin the
// image cv::threshold(img8, bin, thresh * 255, 255, THRESH_BINARY) makes
// (pixels above the threshold rounded down), without either image: per
// 32 x 32 tile the pixel count and coordinate sums (integers, exact), then
// moments()'s own arithmetic, the 1/255 of its binary mode and the tiles'
// order included, so that the sums are the same to the last bit.
inline void centroid(const cv::Mat &img8, double thresh, double &m00, double &m10, double &m01)
{
  const double ft = std::floor(thresh * 255.0);
  const int level = ft < 0 ? -1 : ft > 255 ? 255 : (int)ft;
  const int H = img8.rows, W = img8.cols, T = 32;
  m00 = m10 = m01 = 0;
  for (int ty = 0; ty < H; ty += T)
    for (int tx = 0; tx < W; tx += T) {
      const int tile_h = std::min(T, H - ty), tile_w = std::min(T, W - tx);
      int cnt = 0, sx = 0, sy = 0;        // in the tile's coordinates
      for (int yy = 0; yy < tile_h; yy++) {
        const unsigned char *p = img8.ptr(ty + yy) + tx;
        int rc = 0;
        for (int xx = 0; xx < tile_w; xx++) {
          const int on = p[xx] > level;
          rc += on;
          sx += on * xx;
        }
        cnt += rc;
        sy += rc * yy;
      }
      const double s = 1. / 255;
      const double mom0 = (double)(255 * cnt) * s, mom1 = (double)(255 * sx) * s, mom2 = (double)(255 * sy) * s;
      const double xm = tx * mom0, ym = ty * mom0;
      m00 += mom0;
      m10 += mom1 + xm;
      m01 += mom2 + ym;
    }
}

// The threshold cv::threshold(img8, dst, 0, 255, THRESH_BINARY | THRESH_OTSU)
// returns, without making dst: OpenCV's Otsu (the between-class variance
// over the 256 levels, its arithmetic step for step; equal on 4,000 random
// images).
inline double otsu(const cv::Mat &img8)
{
  // four histograms, so that runs of one level do not wait on one counter
  int h[256] = {0}, h4[3][256] = {{0}};
  for (int y = 0; y < img8.rows; y++) {
    const unsigned char *p = img8.ptr(y);
    int x = 0;
    for (; x + 4 <= img8.cols; x += 4) {
      h[p[x]]++;
      h4[0][p[x + 1]]++;
      h4[1][p[x + 2]]++;
      h4[2][p[x + 3]]++;
    }
    for (; x < img8.cols; x++)
      h[p[x]]++;
  }
  double mu = 0, scale = 1. / (img8.cols * img8.rows);
  for (int i = 0; i < 256; i++) {
    h[i] += h4[0][i] + h4[1][i] + h4[2][i];
    mu += i * (double)h[i];
  }
  mu *= scale;
  double mu1 = 0, q1 = 0, max_sigma = 0, max_val = 0;
  for (int i = 0; i < 256; i++) {
    double p_i = h[i] * scale, q2, mu2, sigma;
    mu1 *= q1;
    q1 += p_i;
    q2 = 1. - q1;
    if (std::min(q1, q2) < FLT_EPSILON || std::max(q1, q2) > 1. - FLT_EPSILON)
      continue;
    mu1 = (mu1 + i * p_i) / q1;
    mu2 = (mu - q1 * mu1) / q2;
    sigma = q1 * q2 * (mu1 - mu2) * (mu1 - mu2);
    if (sigma > max_sigma) {
      max_sigma = sigma;
      max_val = i;
    }
  }
  return max_val;
}

}  // namespace cvexact

#endif
