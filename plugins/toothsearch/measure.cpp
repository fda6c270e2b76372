// Tooth-angle measurement with OpenCV (toothsearch.h): per search, images
// at known A over one revolution; the rotation axis is calibrated from them
// (silhouette centroids orbiting the axis, then the angular disagreement
// between the images), each image is unwrapped with cv::warpPolar, the faces
// are found with sub-pixel precision on circles just inside the tip, and
// the tooth positions become the A values at which the probe meets them.
#include "toothsearch.h"
#include "cvexact.h"
#include "render.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace {

const double kPi = 3.14159265358979323846;

double wrap360(double a)
{
  a = std::fmod(a, 360.0);
  return a < 0 ? a + 360.0 : a;
}
double wrap180(double a)
{
  a = wrap360(a);
  return a >= 180.0 ? a - 360.0 : a;
}

// A failure that becomes a status and a message at the C boundary.
struct ts_error {
  int status;
  std::string msg;
};

struct shot {
  cv::Mat img8;               // the camera image
  double a;                   // A when it was taken, degrees
  double thresh;              // Otsu threshold (0..1)
  std::vector<double> faces;  // camera angles of the faces, degrees, sorted
  bool ok = false;
};

// The radii (px) on which the faces are measured, found once per search.
struct band {
  double tip = 0, core = 0;
  std::vector<double> radii;
  int rmax = 0;               // unwrap to this radius
  int rbins = 0;              // columns of the polar image: 1 per pixel of radius
  int abins = 0;              // angle bins of a circle over 360 degrees
};

struct search_out {
  int teeth = 0;
  std::vector<double> psi;    // tool-frame angle of each face (camera - A), degrees
  cv::Point2d centre;
  std::vector<std::vector<double>> shot_faces;   // per shot, aligned with psi (camera deg)
};

double col_of(const band &b, double r) { return r * b.rbins / b.rmax; }


// The flute depth's circle: the first column, from 0.2 tip on, of the polar
// unwrap (cv::warpPolar(img, p, Size(rbins, abins / 2), c, rmax,
// INTER_LINEAR | WARP_POLAR_LINEAR | WARP_FILL_OUTLIERS): column j is
// radius j * rmax / rbins, row i angle 360 * i / (abins / 2)) where under
// 98 % of the angles are brighter than t; 0 when there is none before the
// tip.  The unwrap is made a column at a time and only as far as the
// answer (cvexact::polar: every value is warpPolar's).
double core_radius(const cv::Mat &img8, cv::Point2d c, const band &b, double t)
{
  const cvexact::polar unwrap(img8, c, b.rmax, b.rbins, b.abins / 2);
  static thread_local std::vector<float> column;
  column.resize(unwrap.rows);
  for (int col = (int)col_of(b, 0.2 * b.tip); col < b.rbins && col < col_of(b, b.tip); col++) {
    unwrap.column(col, column.data());
    int on = 0;
    for (float v : column)
      on += v > t;
    if (on < 0.98 * unwrap.rows)
      return col * (double)b.rmax / b.rbins;
  }
  return 0;
}

// Cyclic smoothing of a signal with a Gaussian of sigma bins.
std::vector<double> smooth(const std::vector<double> &s, double sigma)
{
  int n = (int)s.size(), k = std::max(1, (int)std::ceil(3 * sigma));
  std::vector<double> w(2 * k + 1);
  double sum = 0;
  for (int j = -k; j <= k; j++)
    sum += w[j + k] = std::exp(-0.5 * j * j / (sigma * sigma));
  // the signal with k wrapped samples each side: no index arithmetic per
  // tap (the sums are the same, term for term)
  std::vector<double> ext(n + 2 * k);
  for (int i = -k; i < n + k; i++)
    ext[i + k] = s[i >= 0 && i < n ? i : ((i % n) + n) % n];
  std::vector<double> out(n);
  for (int i = 0; i < n; i++) {
    const double *e = &ext[i];
    double a = 0;
    for (int j = 0; j <= 2 * k; j++)
      a += w[j] * e[j];
    out[i] = a / sum;
  }
  return out;
}

// Solve the 4x4 system A x = b (Gaussian elimination, partial pivoting).
bool solve4(double A[4][4], double b[4], double x[4])
{
  for (int c = 0; c < 4; c++) {
    int p = c;
    for (int r = c + 1; r < 4; r++)
      if (std::fabs(A[r][c]) > std::fabs(A[p][c]))
        p = r;
    if (!(std::fabs(A[p][c]) > 1e-300))
      return false;
    std::swap(A[p], A[c]);
    std::swap(b[p], b[c]);
    for (int r = c + 1; r < 4; r++) {
      double f = A[r][c] / A[c][c];
      for (int k = c; k < 4; k++)
        A[r][k] -= f * A[c][k];
      b[r] -= f * b[c];
    }
  }
  for (int c = 3; c >= 0; c--) {
    double v = b[c];
    for (int k = c + 1; k < 4; k++)
      v -= A[c][k] * x[k];
    x[c] = v / A[c][c];
  }
  return true;
}

// A falling edge fitted in the raw samples y[0..n) (positions 0..n-1):
// y = lo + (hi - lo) Q((x - x0) / w), Q the upper tail of the normal law,
// by Levenberg-Marquardt on (x0, w, lo, hi).  The profile of a blurred
// straight edge across the circle is that curve; without blur it is a
// symmetric ramp, whose centre the fit finds too.  Returns false when the
// fit does not settle inside the window.
bool fit_edge(const std::vector<double> &y, double &x0, double &w, bool fixw)
{
  const int n = (int)y.size();
  if (n < 6)
    return false;
  double p[4] = {x0, w > 0 ? w : 1.5, 0, 0};   // x0, w, lo, hi
  for (int j = 0; j < 3; j++) {
    p[3] += y[j] / 3;
    p[2] += y[n - 1 - j] / 3;
  }
  // the cost keeps its Q values: the next Jacobian, at the same p when the
  // step is taken, reads them instead of calling erfc again
  std::vector<double> qp(n), qq(n);
  auto cost = [&](const double *q, std::vector<double> &qs) {
    double c = 0;
    for (int j = 0; j < n; j++) {
      double z = (j - q[0]) / q[1], Q = qs[j] = 0.5 * std::erfc(z / std::sqrt(2.0));
      double r = y[j] - (q[2] + (q[3] - q[2]) * Q);
      c += r * r;
    }
    return c;
  };
  double lambda = 1e-3, c0 = cost(p, qp);
  for (int it = 0; it < 30; it++) {
    double A[4][4] = {{0}}, g[4] = {0};
    for (int j = 0; j < n; j++) {
      double z = (j - p[0]) / p[1], Q = qp[j];
      double ph = std::exp(-0.5 * z * z) / std::sqrt(2 * kPi), d = p[3] - p[2];
      double J[4] = {d * ph / p[1], fixw ? 0.0 : d * ph * z / p[1], 1 - Q, Q};
      double r = y[j] - (p[2] + d * Q);
      for (int a = 0; a < 4; a++) {
        g[a] += J[a] * r;
        for (int b = 0; b < 4; b++)
          A[a][b] += J[a] * J[b];
      }
    }
    bool better = false;
    for (int tries = 0; tries < 8 && !better; tries++) {
      double M[4][4], rhs[4], dx[4];
      for (int a = 0; a < 4; a++) {
        for (int b = 0; b < 4; b++)
          M[a][b] = A[a][b];
        M[a][a] *= 1 + lambda;
        rhs[a] = g[a];
      }
      if (fixw) {
        M[1][1] = 1;
        rhs[1] = 0;
      }
      if (!solve4(M, rhs, dx))
        return false;
      double q[4] = {p[0] + dx[0], std::clamp(p[1] + dx[1], 0.2, 0.5 * n), p[2] + dx[2], p[3] + dx[3]};
      double c1 = cost(q, qq);
      if (c1 <= c0) {
        bool done = std::fabs(q[0] - p[0]) < 1e-5;
        std::copy(q, q + 4, p);
        qp.swap(qq);
        c0 = c1;
        lambda = std::max(lambda * 0.3, 1e-7);
        better = true;
        if (done)
          it = 30;
      } else {
        lambda *= 10;
      }
    }
    if (!better)
      break;
  }
  if (!(p[0] > 1 && p[0] < n - 2) || !(p[3] > p[2]))
    return false;
  x0 = p[0];
  w = p[1];
  return true;
}

// Cyclic moving average over 2k+1 bins.
std::vector<double> box(const std::vector<double> &s, int k)
{
  int n = (int)s.size();
  std::vector<double> out(n);
  double a = 0;
  for (int j = -k; j <= k; j++)
    a += s[((j % n) + n) % n];
  for (int i = 0; i < n; i++) {
    out[i] = a / (2 * k + 1);
    a += s[(i + k + 1) % n] - s[((i - k) % n + n) % n];
  }
  return out;
}

// Faces on one circle: falling edges (tool -> flute, with A's direction),
// found with hysteresis about the local mid level in a lightly smoothed
// copy, then each fitted in the raw samples between the midpoints to the
// neighbouring transitions (at most 16 bins each side).
std::vector<double> faces_on_circle(const std::vector<double> &sig, const std::vector<double> &mid,
                                    const std::vector<double> &hyst, bool precise)
{
  const int n = (int)sig.size();
  std::vector<double> s = smooth(sig, 1.0);
  std::vector<double> out;
  int start = -1, state = 0;
  for (int i = 0; i < n && start < 0; i++) {
    if (s[i] > mid[i] + hyst[i]) { start = i; state = 1; }
    else if (s[i] < mid[i] - hyst[i]) { start = i; state = -1; }
  }
  if (start < 0)
    return out;
  // transitions as (unwrapped position, falling?)
  std::vector<std::pair<double, bool>> tr;
  int last = start;                       // last definite sample
  for (int k = 1; k <= n; k++) {
    int u = start + k, i = u % n;
    int st = s[i] > mid[i] + hyst[i] ? 1 : s[i] < mid[i] - hyst[i] ? -1 : 0;
    if (st == 0)
      continue;
    if (st != state) {
      // where the smoothed signal crosses the mid level between them
      double pos = last + 0.5 * (u - last);
      for (int v = last; v < u; v++) {
        double a = s[v % n] - mid[v % n], b = s[(v + 1) % n] - mid[(v + 1) % n];
        if ((a > 0) != (b > 0)) {
          pos = v + a / (a - b);
          break;
        }
      }
      tr.push_back({pos, st < 0});
      state = st;
    }
    last = u;
  }
  const int m = (int)tr.size();
  struct win { int lo; double xf; std::vector<double> y; double x0, w; bool ok; };
  std::vector<win> ws;
  for (int t = 0; t < m; t++) {
    if (!tr[t].second)
      continue;
    double xf = tr[t].first;
    double prev = m > 1 ? tr[(t + m - 1) % m].first : xf - n;
    double next = m > 1 ? tr[(t + 1) % m].first : xf + n;
    if (prev >= xf) prev -= n;
    if (next <= xf) next += n;
    win w;
    w.lo = (int)std::ceil(xf - std::min(16.0, 0.5 * (xf - prev)));
    int hi = (int)std::floor(xf + std::min(16.0, 0.5 * (next - xf)));
    w.xf = xf;
    for (int j = w.lo; j <= hi; j++)
      w.y.push_back(sig[((j % n) + n) % n]);
    w.x0 = xf - w.lo;
    w.w = 0;
    w.ok = false;
    ws.push_back(std::move(w));
  }
  if (precise) {
    // every edge on a circle has the same width (the same blur, the same
    // crossing): fit freely, then again with the median width, which keeps
    // the width from trading off against the levels where the teeth are
    // too close for the signal to reach them
    std::vector<double> wl;
    for (auto &w : ws)
      if ((w.ok = fit_edge(w.y, w.x0, w.w, false)))
        wl.push_back(w.w);
    if (!wl.empty()) {
      std::nth_element(wl.begin(), wl.begin() + wl.size() / 2, wl.end());
      double wm = wl[wl.size() / 2];
      for (auto &w : ws) {
        w.x0 = w.xf - w.lo;
        w.w = wm;
        w.ok = fit_edge(w.y, w.x0, w.w, true);
      }
    }
  }
  for (auto &w : ws)
    out.push_back(wrap360((w.ok ? w.lo + w.x0 : w.xf) * 360.0 / n));
  std::sort(out.begin(), out.end());
  return out;
}

// The most frequent size among lists of angles.
int mode_count(const std::vector<std::vector<double>> &lists)
{
  std::vector<int> sz;
  for (auto &l : lists)
    sz.push_back((int)l.size());
  int best = 0, bestn = 0;
  for (int v : sz) {
    int c = (int)std::count(sz.begin(), sz.end(), v);
    if (c > bestn || (c == bestn && v > best)) { best = v; bestn = c; }
  }
  return best;
}

// The rotation of list that best matches ref (same size, both sorted).
int align(const std::vector<double> &ref, const std::vector<double> &list)
{
  int n = (int)ref.size(), best = 0;
  double bestd = 1e30;
  for (int o = 0; o < n; o++) {
    double d = std::fabs(wrap180(list[o] - ref[0]));
    if (d < bestd) { bestd = d; best = o; }
  }
  return best;
}

// Average of aligned lists, each entry near ref's.
std::vector<double> average(const std::vector<double> &ref, const std::vector<std::vector<double>> &lists)
{
  int n = (int)ref.size();
  std::vector<double> sum(n, 0.0);
  int m = 0;
  for (auto &l : lists) {
    if ((int)l.size() != n)
      continue;
    int o = align(ref, l);
    for (int k = 0; k < n; k++)
      sum[k] += wrap180(l[(k + o) % n] - ref[k]);
    m++;
  }
  std::vector<double> out(n);
  for (int k = 0; k < n; k++)
    out[k] = wrap360(ref[k] + (m ? sum[k] / m : 0.0));
  return out;
}

// The circles a shot is read on, about c: the band's radii, then five
// radii just inside the core (the tool's level) and four outside the tip
// (the background's).  warpPolar would unwrap every radius from 0 to rmax;
// the faces need a dozen circles, so this is the same bilinear unwrap
// (cv::remap's: cvexact::sampler) on those radii alone (some forty times less work).
cv::Mat unwrap_circles(const cv::Mat &img8, cv::Point2d c, const band &b, std::vector<double> &radii)
{
  radii = b.radii;
  for (int k = 0; k < 5; k++)
    radii.push_back(std::max(1.0, b.core - 6 + k));
  for (int k = 0; k < 4; k++)
    radii.push_back(b.tip * (1.04 + 0.01 * k));
  const int n = b.abins;
  static thread_local std::vector<double> cs, sn;
  if ((int)cs.size() != n) {
    cs.resize(n);
    sn.resize(n);
    for (int i = 0; i < n; i++) {
      cs[i] = std::cos(2 * kPi * i / n);
      sn[i] = std::sin(2 * kPi * i / n);
    }
  }
  cv::Mat out((int)radii.size(), n, CV_32F);
  const cvexact::sampler at(img8, cv::BORDER_REPLICATE);
  for (int k = 0; k < (int)radii.size(); k++) {
    float *o = out.ptr<float>(k);
    for (int i = 0; i < n; i++)
      o[i] = at((float)(c.x + radii[k] * cs[i]), (float)(c.y + radii[k] * sn[i]));
  }
  return out;
}

// Faces in one shot, unwrapped about c: per circle, then averaged.
void measure_shot(shot &s, cv::Point2d c, const band &b, bool precise)
{
  std::vector<double> radii;
  cv::Mat p = unwrap_circles(s.img8, c, b, radii);
  const int n = b.abins, nb = (int)b.radii.size();
  std::vector<double> hi(n, 0.0), lo(n, 0.0), mid(n), hyst(n);
  for (int i = 0; i < n; i++) {
    for (int k = 0; k < 5; k++)
      hi[i] += p.at<float>(nb + k, i) / 5;
    for (int k = 0; k < 4; k++)
      lo[i] += p.at<float>(nb + 5 + k, i) / 4;
  }
  hi = box(hi, 25);
  lo = box(lo, 25);
  for (int i = 0; i < n; i++) {
    mid[i] = 0.5 * (hi[i] + lo[i]);
    hyst[i] = 0.2 * std::fabs(hi[i] - lo[i]);
  }
  std::vector<std::vector<double>> per;
  std::vector<double> sig(n);
  for (int k = 0; k < nb; k++) {
    const float *row = p.ptr<float>(k);
    for (int i = 0; i < n; i++)
      sig[i] = row[i];
    per.push_back(faces_on_circle(sig, mid, hyst, precise));
  }
  int cnt = mode_count(per);
  s.faces.clear();
  s.ok = false;
  if (cnt == 0)
    return;
  const std::vector<double> *ref = nullptr;
  for (auto &l : per)
    if ((int)l.size() == cnt) { ref = &l; break; }
  s.faces = average(*ref, per);
  s.ok = true;
}

// The rotation axis from the silhouettes' centroids: a centroid turns about
// the axis with A, m_i = c + Rot(A_i) v; least squares for c and v.
cv::Point2d centroid_axis(const std::vector<shot> &shots)
{
  cv::Mat M((int)shots.size() * 2, 4, CV_64F), y((int)shots.size() * 2, 1, CV_64F);
  for (size_t i = 0; i < shots.size(); i++) {
    double m00, m10, m01;
    cvexact::centroid(shots[i].img8, shots[i].thresh, m00, m10, m01);
    if (m00 <= 0)
      throw ts_error{TS_E_TEETH, "no teeth found: the image shows no tool"};
    double a = shots[i].a * kPi / 180, ca = std::cos(a), sa = std::sin(a);
    int r = (int)i * 2;
    double row0[4] = {1, 0, ca, -sa}, row1[4] = {0, 1, sa, ca};
    for (int k = 0; k < 4; k++) {
      M.at<double>(r, k) = row0[k];
      M.at<double>(r + 1, k) = row1[k];
    }
    y.at<double>(r) = m10 / m00;
    y.at<double>(r + 1) = m01 / m00;
  }
  cv::Mat x;
  cv::solve(M, y, x, cv::DECOMP_SVD);
  return {x.at<double>(0), x.at<double>(1)};
}

// Tool-frame angles of the teeth in every shot, aligned to shot 0's order.
// Returns the tooth count; shots with another count are marked not ok.
int tool_frame(std::vector<shot> &shots, std::vector<std::vector<double>> &psi)
{
  std::vector<std::vector<double>> lists;
  for (auto &s : shots)
    lists.push_back(s.faces);
  int cnt = mode_count(lists);
  int agree = 0;
  for (auto &s : shots)
    if (s.ok && (int)s.faces.size() == cnt)
      agree++;
  if (cnt == 0)
    throw ts_error{TS_E_TEETH, "no teeth found"};
  if (cnt > TM_MAX_TEETH)
    throw ts_error{TS_E_TEETH, "more than 150 teeth (" + std::to_string(cnt) + " found)"};
  if (2 * agree <= (int)shots.size())
    throw ts_error{TS_E_TEETH, "the tooth count differs between the images"};
  psi.assign(shots.size(), {});
  const std::vector<double> *ref = nullptr;
  for (size_t i = 0; i < shots.size(); i++) {
    shot &s = shots[i];
    if (!s.ok || (int)s.faces.size() != cnt) {
      s.ok = false;
      continue;
    }
    std::vector<double> t(cnt);
    for (int k = 0; k < cnt; k++)
      t[k] = wrap360(s.faces[k] - s.a);
    std::sort(t.begin(), t.end());
    if (!ref) {
      psi[i] = t;
      ref = &psi[i];
    } else {
      int o = align(*ref, t);
      for (int k = 0; k < cnt; k++)
        psi[i].push_back(t[(k + o) % cnt]);
    }
  }
  return cnt;
}

// One search: one revolution, TS_SHOTS images.
search_out run_search(const tm_model *m, double x, double a0, double mount, int section,
                      uint32_t shot0, const char *dump, ts_png_fn png, const std::string &tag, bool &io_fail)
{
  const int N = m->image, K = TS_SHOTS;
  std::vector<shot> shots(K);
  // the images live on from search to search (fresh pages cost more than
  // the arithmetic on them); shots[i] shares cache8[i]
  static thread_local cv::Mat cache8[K];
  char err[256];
  for (int i = 0; i < K; i++) {
    ts_view v{x, a0 + 360.0 * i / K, mount, section, shot0 + (uint32_t)i};
    cache8[i].create(N, N, CV_8U);
    if (ts_render(m, &v, cache8[i].ptr(), nullptr, err, sizeof err) != 0)
      throw ts_error{TS_E_INTERNAL, err};
    shots[i].img8 = cache8[i];
    shots[i].a = v.a_deg;
    shots[i].thresh = cvexact::otsu(shots[i].img8) / 255.0;
  }

  // 1. the axis, roughly, from the centroids
  cv::Point2d c = centroid_axis(shots);

  // 2. the band: the tip radius is the camera's framing; the flute depth is
  // where the tool stops covering every angle
  band b;
  b.tip = TM_TIP_FRACTION * N;
  b.rmax = (int)std::floor(std::min({c.x, c.y, N - 1 - c.x, N - 1 - c.y}));
  if (b.rmax < b.tip * 1.08)
    throw ts_error{TS_E_TEETH, "no teeth found: the tool is not centred in the image"};
  b.rbins = b.rmax;
  b.abins = (int)std::ceil(2 * kPi * b.tip * 1.25);
  {
    b.core = core_radius(shots[0].img8, c, b, shots[0].thresh);
    double h = b.tip - b.core;
    if (b.core <= 0 || h < 2.5)
      throw ts_error{TS_E_TEETH, "no teeth found: no flutes in the image"};
    // circles from just inside the tip down into the upper part of the
    // flute, a pixel apart (their noise is then independent), at most 16
    double dlo = std::max(2.5, std::min(0.2 * h, 8.0));
    double dhi = std::max(dlo + 1.0, std::min(0.7 * h, dlo + 0.08 * b.tip));
    int nc = std::clamp((int)std::floor(dhi - dlo) + 1, 2, 16);
    for (int k = 0; k < nc; k++)
      b.radii.push_back(b.tip - dhi + (dhi - dlo) * k / (nc - 1));
  }

  // 3. faces in every shot; then the axis from the disagreement between
  // the shots (an axis off by e moves a face at angle phi, radius r by
  // (-ex sin phi + ey cos phi) / r radians): re-unwrap about the corrected
  // axis until the correction is small, then apply the last one to the
  // angles directly (it is linear that close)
  double rmean = 0;
  for (double r : b.radii)
    rmean += r / b.radii.size();
  std::vector<std::vector<double>> psi;
  int cnt = 0;
  for (int iter = 0; iter < 4; iter++) {
    // the first pass only finds the edges (the axis is then still some
    // tenths of a pixel off); the next ones fit them
    const bool precise = iter > 0;
    for (auto &s : shots)
      measure_shot(s, c, b, precise);
    cnt = tool_frame(shots, psi);
    const std::vector<double> *ref = nullptr;
    for (auto &q : psi)
      if (!q.empty()) { ref = &q; break; }
    double saa = 0, sab = 0, sbb = 0, say = 0, sby = 0;
    for (int k = 0; k < cnt; k++) {
      double ybar = 0, ms = 0, mc = 0;
      int n = 0;
      for (size_t i = 0; i < shots.size(); i++) {
        if (!shots[i].ok)
          continue;
        double phi = (psi[i][k] + shots[i].a) * kPi / 180;
        ybar += wrap180(psi[i][k] - (*ref)[k]);
        ms += std::sin(phi);
        mc += std::cos(phi);
        n++;
      }
      ybar /= n;
      ms /= n;
      mc /= n;
      for (size_t i = 0; i < shots.size(); i++) {
        if (!shots[i].ok)
          continue;
        double phi = (psi[i][k] + shots[i].a) * kPi / 180;
        double yv = (wrap180(psi[i][k] - (*ref)[k]) - ybar) * kPi / 180;
        double av = -(std::sin(phi) - ms) / rmean, bv = (std::cos(phi) - mc) / rmean;
        saa += av * av; sab += av * bv; sbb += bv * bv;
        say += av * yv; sby += bv * yv;
      }
    }
    double det = saa * sbb - sab * sab;
    if (!(det > 0))
      break;
    double ex = (sbb * say - sab * sby) / det, ey = (saa * sby - sab * say) / det;
    c.x += ex;
    c.y += ey;
    if ((precise && std::hypot(ex, ey) < 0.05) || iter == 3) {
      for (size_t i = 0; i < shots.size(); i++)
        for (int k = 0; shots[i].ok && k < cnt; k++) {
          double phi = (psi[i][k] + shots[i].a) * kPi / 180;
          psi[i][k] = wrap360(psi[i][k] - (-ex * std::sin(phi) + ey * std::cos(phi)) / rmean * 180 / kPi);
        }
      break;
    }
  }

  // 4. each tooth's tool-frame angle: the mean over the revolution
  search_out out;
  out.teeth = cnt;
  out.centre = c;
  const std::vector<double> *ref = nullptr;
  for (auto &q : psi)
    if (!q.empty()) { ref = &q; break; }
  out.psi.assign(cnt, 0.0);
  for (int k = 0; k < cnt; k++) {
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i < shots.size(); i++)
      if (shots[i].ok) { sum += wrap180(psi[i][k] - (*ref)[k]); n++; }
    out.psi[k] = wrap360((*ref)[k] + sum / n);
  }
  for (size_t i = 0; i < shots.size(); i++) {
    std::vector<double> f;
    if (shots[i].ok)
      for (int k = 0; k < cnt; k++)
        f.push_back(wrap360(psi[i][k] + shots[i].a));
    out.shot_faces.push_back(f);
  }

  if (dump && !png)
    io_fail = true;
  else if (dump) {
    // through png (tscv.h: imgcodecs is loaded for --dump-images alone)
    auto write = [&](const std::string &path, const cv::Mat &img, int compression) {
      if (png(path.c_str(), img.rows, img.cols, img.channels(), img.ptr(), img.step, compression) != 0)
        io_fail = true;
    };
    for (int i = 0; i < K; i++) {
      std::string base = std::string(dump) + "/" + tag + "_shot" + std::to_string(i + 1);
      write(base + ".png", shots[i].img8, -1);
      cv::Mat col;
      cv::cvtColor(shots[i].img8, col, cv::COLOR_GRAY2BGR);
      auto at = [&](double r, double deg) {
        double a = deg * kPi / 180;
        return cv::Point2d(c.x + r * std::cos(a), c.y + r * std::sin(a));
      };
      const int sh = 4, one = 1 << sh;   // sub-pixel drawing
      auto P = [&](cv::Point2d q) { return cv::Point((int)std::lround(q.x * one), (int)std::lround(q.y * one)); };
      for (double r : {b.radii.front(), b.radii.back()})
        cv::circle(col, P(c), (int)std::lround(r * one), cv::Scalar(255, 160, 0), 1, cv::LINE_AA, sh);
      cv::drawMarker(col, cv::Point((int)std::lround(c.x), (int)std::lround(c.y)), cv::Scalar(0, 0, 255),
                     cv::MARKER_CROSS, 15, 1);
      // text kept inside the picture, centred on q, whatever the image size
      const double fs = std::clamp(N / 1600.0, 0.3, 0.6);
      auto label = [&](const std::string &text, cv::Point2d q, double scale, cv::Scalar colour) {
        int base_line = 0;
        cv::Size ts = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base_line);
        int lx = std::clamp((int)std::lround(q.x - ts.width / 2.0), 2, std::max(2, N - ts.width - 2));
        int ly = std::clamp((int)std::lround(q.y + ts.height / 2.0), ts.height + 2, N - base_line - 2);
        cv::putText(col, text, cv::Point(lx, ly), cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
      };
      const double probe_out = std::min(b.tip + 34, 0.5 * N - 2);
      cv::line(col, P(at(b.tip + 4, 0)), P(at(probe_out, 0)), cv::Scalar(0, 220, 255), 3, cv::LINE_AA, sh);
      label("probe", at(0.5 * (b.tip + probe_out), 0) + cv::Point2d(0, -12 * fs / 0.4), fs,
            cv::Scalar(0, 220, 255));
      if (!out.shot_faces[i].empty()) {
        for (int k = 0; k < cnt; k++) {
          double ang = out.shot_faces[i][k];
          cv::line(col, P(at(b.radii.front() - 6, ang)), P(at(b.tip + 12, ang)), cv::Scalar(0, 0, 255), 1,
                   cv::LINE_AA, sh);
          if (cnt <= 40) {
            char lab[32];
            std::snprintf(lab, sizeof lab, "%.3f", wrap360(ang - shots[i].a));
            label(lab, at(b.tip + 26 * fs / 0.4, ang), 0.9 * fs, cv::Scalar(0, 0, 255));
          }
        }
      }
      char head[160];
      std::snprintf(head, sizeof head, "%s  A=%.3f  teeth %d", tag.c_str(), shots[i].a, cnt);
      cv::putText(col, head, cv::Point(6, (int)std::lround(30 * fs)), cv::FONT_HERSHEY_SIMPLEX, fs,
                  cv::Scalar(0, 255, 0), 1, cv::LINE_AA);
      std::snprintf(head, sizeof head, "axis (%.2f, %.2f) px", c.x, c.y);
      cv::putText(col, head, cv::Point(6, (int)std::lround(60 * fs)), cv::FONT_HERSHEY_SIMPLEX, fs,
                  cv::Scalar(0, 255, 0), 1, cv::LINE_AA);
      // the annotated copy is colour: zlib's best halves it
      write(base + "_annotated.png", col, 9);
    }
  }
  return out;
}

// The A at which each tooth meets the probe (camera angle 0) when A turns
// forward from a0: a0 + mod360(-psi - a0), in the order met.
std::vector<double> positions(const std::vector<double> &psi, double a0)
{
  std::vector<double> p;
  for (double t : psi)
    p.push_back(a0 + wrap360(-t - a0));
  std::sort(p.begin(), p.end());
  return p;
}

void set_err(char *err, size_t errlen, const std::string &msg)
{
  if (err && errlen)
    std::snprintf(err, errlen, "%s", msg.c_str());
}

}  // namespace

extern "C" double ts_revolution_time(double speed)
{
  if (!(speed > 0))
    speed = TS_DEFAULT_SPEED;
  return 360.0 / speed * 60.0;
}

extern "C" double ts_mount(const struct tm_model *m, double x1, double a1)
{
  double edge[TM_MAX_TEETH], width[TM_MAX_TEETH];
  ts_geometry(m, x1, edge, width);
  return -0.4 * width[0] - a1 - edge[0];
}

extern "C" double ts_follow_flute(const struct tm_model *m, double x1, double a1, double x2)
{
  double e1[TM_MAX_TEETH], e2[TM_MAX_TEETH], w[TM_MAX_TEETH];
  ts_geometry(m, x1, e1, w);
  ts_geometry(m, x2, e2, w);
  return a1 + e1[0] - e2[0];
}

namespace {

// The request's values for the searches asked for; throws ts_error.
void check_request(const tm_model *m, const ts_request *rq, bool section2)
{
  char merr[256];
  if (tm_check(m, merr, sizeof merr) != 0)
    throw ts_error{TS_E_ARG, merr};
  if (rq->hand != TM_RIGHT && rq->hand != TM_LEFT)
    throw ts_error{TS_E_ARG, "the hand is neither right (G10) nor left (G11)"};
  if (!std::isfinite(rq->x1_um) || !std::isfinite(rq->a1_deg) || std::fabs(rq->a1_deg) > 1e7 ||
      std::fabs(rq->x1_um) > 1e9)
    throw ts_error{TS_E_ARG, "section 1: X or A is not a usable number"};
  if (section2) {
    if (!std::isfinite(rq->x2_um) || !std::isfinite(rq->a2_deg) || std::fabs(rq->a2_deg) > 1e7 ||
        std::fabs(rq->x2_um) > 1e9)
      throw ts_error{TS_E_ARG, "section 2: X or A is not a usable number"};
    if (std::fabs(rq->x2_um - rq->x1_um) < 1.0)
      throw ts_error{TS_E_ARG, "section 2 is at the X of section 1: the lead cannot be measured"};
  }
  if (rq->speed_deg_min > TS_MAX_SPEED || std::isnan(rq->speed_deg_min))
    throw ts_error{TS_E_ARG, "search speed above " + std::to_string((int)TS_MAX_SPEED) + " deg/min"};
  if (rq->dump_dir && mkdir(rq->dump_dir, 0777) != 0 && errno != EEXIST)
    throw ts_error{TS_E_IO, std::string(rq->dump_dir) + ": " + std::strerror(errno)};
}

int caught(char *err, size_t errlen)
{
  try {
    throw;
  } catch (const ts_error &e) {
    set_err(err, errlen, e.msg);
    return e.status;
  } catch (const std::bad_alloc &) {
    set_err(err, errlen, "tooth search: out of memory");
  } catch (const std::exception &e) {
    set_err(err, errlen, std::string("tooth search: ") + e.what());
  } catch (...) {
    set_err(err, errlen, "tooth search: unknown exception");
  }
  return TS_E_INTERNAL;
}

}  // namespace

extern "C" int ts_search_pass(const struct tm_model *m, const struct ts_request *rq, int which,
                              struct ts_pass *out, char *err, size_t errlen)
{
  try {
    if (!m || !rq || !out || (which != 0 && which != 1))
      throw ts_error{TS_E_ARG, "ts_search_pass: a null argument or a pass other than 0 and 1"};
    std::memset(out, 0, sizeof *out);
    const bool m10 = !std::isnan(rq->x2_um);
    check_request(m, rq, which == 1 && m10);
    const double mount = ts_mount(m, rq->x1_um, rq->a1_deg);
    const std::string pre = rq->dump_prefix ? rq->dump_prefix : "";
    bool io_fail = false;
    search_out s;
    double a0;
    if (which == 0) {
      a0 = rq->a1_deg;
      s = run_search(m, rq->x1_um, a0, mount, 0, 0, rq->dump_dir, rq->write_png, pre + "section1", io_fail);
    } else if (m10) {
      a0 = rq->a2_deg;
      s = run_search(m, rq->x2_um, a0, mount, 1, 0, rq->dump_dir, rq->write_png, pre + "section2", io_fail);
    } else {
      a0 = rq->a1_deg + 360.0;      // the second revolution follows the first
      s = run_search(m, rq->x1_um, a0, mount, 0, TS_SHOTS, rq->dump_dir, rq->write_png, pre + "section1_search2", io_fail);
    }
    out->teeth = s.teeth;
    out->a0_deg = a0;
    for (int k = 0; k < s.teeth && k < TM_MAX_TEETH; k++)
      out->psi_deg[k] = s.psi[k];
    out->centre_px[0] = s.centre.x;
    out->centre_px[1] = s.centre.y;
    out->images_failed = io_fail;
    return TS_OK;
  } catch (...) {
    return caught(err, errlen);
  }
}

extern "C" int ts_search_combine(const struct tm_model *m, const struct ts_request *rq, const struct ts_pass *s1,
                                 const struct ts_pass *s2, struct ts_result *out, char *err, size_t errlen)
{
  try {
    if (!m || !rq || !s1 || !s2 || !out)
      throw ts_error{TS_E_ARG, "ts_search_combine: a null argument"};
    std::memset(out, 0, sizeof *out);
    const bool m10 = !std::isnan(rq->x2_um);
    if (s1->teeth < 1 || s1->teeth > TM_MAX_TEETH || s2->teeth < 1 || s2->teeth > TM_MAX_TEETH)
      throw ts_error{TS_E_ARG, "ts_search_combine: a pass without a valid tooth count"};
    if (s1->teeth != s2->teeth)
      throw ts_error{TS_E_TEETH, "the tooth count differs between the searches (" + std::to_string(s1->teeth) +
                                     ", " + std::to_string(s2->teeth) + ")"};
    const int n = s1->teeth;
    std::vector<double> psi1(s1->psi_deg, s1->psi_deg + n), psi2(s2->psi_deg, s2->psi_deg + n);
    std::vector<double> p1 = positions(psi1, s1->a0_deg), p2 = positions(psi2, s2->a0_deg);
    out->teeth = n;
    double shift = 0;
    for (int k = 0; k < n; k++) {
      double st1 = (k + 1 < n ? p1[k + 1] : p1[0] + 360.0) - p1[k];
      double st2 = (k + 1 < n ? p2[k + 1] : p2[0] + 360.0) - p2[k];
      out->steps[k] = 0.5 * (st1 + st2);
      out->positions[0][k] = p1[k];
      out->positions[1][k] = p2[k];
      shift += (p2[k] - p1[k]) / n;
    }
    for (int i = 0; i < 2; i++) {
      out->centre_px[0][i] = s1->centre_px[i];
      out->centre_px[1][i] = s2->centre_px[i];
    }
    if (m10) {
      double L = rq->x2_um - rq->x1_um;
      out->shift_deg = shift;
      double tk = std::fabs(shift) > 0 ? 360.0 * std::fabs(L) / std::fabs(shift) : HUGE_VAL;
      if (tk <= TM_MAX_LEAD) {
        double d = rq->diameter_um > 0 ? rq->diameter_um : m->diameter;
        out->tk_um = tk;
        out->ug_mdeg = std::atan(kPi * d / tk) * 180.0 / kPi * 1000.0;
        // turning A forward meets a right-hand helix's teeth earlier in a
        // section further along X: the shift and L have opposite signs
        out->measured_hand = shift * L < 0 ? TM_RIGHT : TM_LEFT;
        out->hand_mismatch = out->measured_hand != rq->hand;
      }
    }
    out->images = 2 * TS_SHOTS;
    out->time_s = 2 * ts_revolution_time(rq->speed_deg_min);
    return TS_OK;
  } catch (...) {
    return caught(err, errlen);
  }
}

extern "C" int ts_first_tooth(const struct tm_model *m, double x1_um, double a1_deg, double x_um, double a_deg)
{
  if (!m || m->teeth < 1 || m->teeth > TM_MAX_TEETH)
    return -1;
  double edge[TM_MAX_TEETH], width[TM_MAX_TEETH];
  const double mount = ts_mount(m, x1_um, a1_deg);
  ts_geometry(m, x_um, edge, width);
  int best = -1;
  double bestd = 1e30;
  for (int k = 0; k < m->teeth; k++) {
    double d = wrap360(-(edge[k] + mount) - a_deg);
    if (d < bestd) {
      bestd = d;
      best = k;
    }
  }
  return best;
}

extern "C" int ts_search(const struct tm_model *m, const struct ts_request *rq, struct ts_result *out,
                         char *err, size_t errlen)
{
  try {
    if (!m || !rq || !out)
      throw ts_error{TS_E_ARG, "ts_search: a null argument"};
    std::memset(out, 0, sizeof *out);
    check_request(m, rq, !std::isnan(rq->x2_um));
  } catch (...) {
    return caught(err, errlen);
  }
  struct ts_pass s1, s2;
  int st = ts_search_pass(m, rq, 0, &s1, err, errlen);
  if (st == TS_OK)
    st = ts_search_pass(m, rq, 1, &s2, err, errlen);
  if (st == TS_OK)
    st = ts_search_combine(m, rq, &s1, &s2, out, err, errlen);
  if (st == TS_OK && (s1.images_failed || s2.images_failed)) {
    set_err(err, errlen, std::string(rq->dump_dir) + ": the images could not all be written");
    return TS_E_IO;
  }
  return st;
}
