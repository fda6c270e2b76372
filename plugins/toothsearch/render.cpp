// Probe-image renderer (render.h).  Each pixel's coverage comes from a
// signed distance to the cross-section's outline (tip circle, straight rake
// face, curved flute back), so edges are anti-aliased without supersampling;
// then optical blur (Gaussian), illumination, sensor noise, 8-bit output.
#include "render.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

namespace {

const double kPi = 3.14159265358979323846;
const double kRake = 6.0;        // rake angle of the face, degrees
const double kMaxFlute = 75.0;   // widest flute, degrees
const double kFluteShare = 0.7;  // flute width / step
const double kMaxOffset = 0.012; // axis offset, fraction of the image side

inline double rad(double d) { return d * kPi / 180.0; }

// splitmix64: seeds from (model seed, section, shot); xoshiro256** draws.
uint64_t mix(uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

struct rng {
  uint64_t s[4];
  explicit rng(uint64_t seed)
  {
    for (auto &w : s)
      w = seed = mix(seed);
  }
  static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  uint64_t next()
  {
    uint64_t r = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0]; s[3] ^= s[1]; s[1] ^= s[2]; s[0] ^= s[3];
    s[2] ^= t; s[3] = rotl(s[3], 45);
    return r;
  }
  double uniform() { return (double)(next() >> 11) * (1.0 / 9007199254740992.0); }  // [0,1)
};

// The inverse of the standard normal CDF (P. J. Acklam's rational
// approximation, relative error below 1.2e-9), for 0 < p < 1.
double inv_normal(double p)
{
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  if (p < 0.02425) {
    double q = std::sqrt(-2 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  if (p > 1 - 0.02425) {
    double q = std::sqrt(-2 * std::log(1 - p));
    return -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
}

double wrap360(double a)
{
  a = std::fmod(a, 360.0);
  return a < 0 ? a + 360.0 : a;
}

struct flute {
  double edge;     // camera angle of the cutting edge, degrees in [0,360)
  double width;    // flute width, degrees
  double ex, ey;   // the edge point relative to the axis, px
  double nx, ny;   // face normal, pointing into the flute
  double margin;   // how far sback can be off with the angle kAngleErr off (outline)
  double lip;      // how much inside can change from a pixel to the next in a row (outline)
};

// A pixel's coverage, 0..1, from its offset (dx, dy) from the axis (r2 =
// dx^2 + dy^2, inside the annulus where the outline is): the definition of
// the image.  fl is sorted by edge.
float cover_exact(const std::vector<flute> &fl, double R, double h, double dx, double dy, double r2)
{
  const double r = std::sqrt(r2), phi = wrap360(std::atan2(dy, dx) * 180.0 / kPi);
  // the flute that may hold this pixel starts at the last edge <= phi
  auto it = std::upper_bound(fl.begin(), fl.end(), phi,
                             [](double p, const flute &f) { return p < f.edge; });
  const flute &f = it == fl.begin() ? fl.back() : *(it - 1);
  double u = wrap360(phi - f.edge) / f.width;
  double sback;                          // > 0 above the back curve
  if (u >= 1) {
    sback = r - R;
  } else {
    // the back: a rounded bottom at the face rising smoothly to the
    // heel, where it meets the tip circle tangentially
    double wr = rad(f.width), rho = R - h * (1 - u * u * (3 - 2 * u));
    double drho = 6 * h * u * (1 - u) / wr;   // d rho / d phi (radians)
    sback = (r - rho) / std::sqrt(1 + (drho / r) * (drho / r));
  }
  double sface = (dx - f.ex) * f.nx + (dy - f.ey) * f.ny;   // > 0 on the flute side
  double influte = std::min(sface, sback);
  double inside = std::min(R - r, -influte);
  return (float)std::clamp(0.5 + inside, 0.0, 1.0);
}

// atan2(dy, dx) in degrees, in [0, 360], within kAngleErr of cover_exact's
// phi: an odd polynomial in t = min/max(|dx|, |dy|) on [0, 1] (a Chebyshev
// fit of atan(t)/t in t^2, 6.4e-8 rad at worst: 3.7e-6 degrees over a
// sweep of 10^8 values of t and 5*10^7 random points), then the octant.
const double kAngleErr = 1e-4;
inline double fast_deg(double dx, double dy)
{
  const double ax = std::fabs(dx), ay = std::fabs(dy);
  const double t = std::min(ax, ay) / std::max(ax, ay), s = t * t;
  double a = t * (0.99999988199649311 + s * (-0.33331812655627827 + s * (0.19966961829591536 +
             s * (-0.14003290184652271 + s * (0.098688654581324674 + s * (-0.05882975314306535 +
             s * (0.02378051859716587 + s * -0.0045597919861304548)))))));
  if (ay > ax)
    a = kPi / 2 - a;
  if (dx < 0)
    a = kPi - a;
  if (dy < 0)
    a = 2 * kPi - a;
  return a * (180.0 / kPi);
}

// The columns [lo, hi) of a row where dx^2 + dy2 is below lim (at most lim
// with eq), dx = x - cx: a run about cx, from the square root, then made
// exact with the pixel loop's own arithmetic.
void run_within(int N, double cx, double dy2, double lim, bool eq, int &lo, int &hi)
{
  auto in = [&](int x) {
    const double dx = x - cx, r2 = dx * dx + dy2;
    return eq ? r2 <= lim : r2 < lim;
  };
  const int mid = (int)std::clamp(std::round(cx), 0.0, N - 1.0);   // the least r2
  if (!in(mid)) {
    lo = hi = 0;
    return;
  }
  const double half = std::sqrt(std::max(0.0, lim - dy2));
  lo = (int)std::clamp(std::floor(cx - half), 0.0, (double)mid);
  hi = (int)std::clamp(std::ceil(cx + half), (double)mid, N - 1.0);
  while (lo > 0 && in(lo - 1))
    lo--;
  while (!in(lo))
    lo++;
  while (hi < N - 1 && in(hi + 1))
    hi++;
  while (!in(hi))
    hi--;
  hi++;
}

// The same coverage without atan2 where that cannot change the byte: most
// of the annulus is exactly 0 (flute, outside the tip) or exactly 1 (tool)
// after the clamp, and by more than a pixel's worth, so that whole runs of
// a row are decided by one pixel.
//
// With the angle from fast_deg, the flute is the one cover_exact picks
// unless an edge (or 0/360) is within kAngleErr; then the face distance
// sface and R - r are cover_exact's own, and the back's distance sback is
// off by at most f.margin (its slope in the angle, bounded once per flute).
// A pixel whose value is 0 or 1 by more than that is decided here, any
// other goes to cover_exact.
//
// A decided pixel's slack is how far its signed distance `inside' is from
// the nearest other value's (0.5 + slack >= 1 or 0.5 - slack <= 0).  Along
// a row, inside changes by at most f.lip a pixel (the gradient of R - r and
// sface is 1, sback's is bounded in ts_render) as long as the row stays in
// the flute's sector: a row's angle is monotonic, so when the run's last
// pixel is inside the sector (kAngleErr from its edges) so is every pixel
// before it.  R - r alone (beyond the tip) holds in any sector.
const int kBins = 360;
struct outline {
  std::vector<flute> fl;   // sorted by edge
  int first[kBins];        // the edges <= b degrees, where the search for the flute starts
  double R, h;
  double cx, cy;

  struct sure {
    float value;           // 0 or 1; -1: cover_exact decides
    double any;            // slack from R - r alone: slope 1, any sector
    double face;           // slack from R - r and sface: slope 1 in the sector
    double all;            // slack with sback too: slope f.lip in the sector
    int k;                 // the sector (fl[k - 1]'s flute, fl.back()'s for 0)
  };

  // the sector of angle phi: k edges <= phi, the flute fl[k - 1] (or the
  // last one) from the edge `from' on; false within kAngleErr of an edge
  bool sector(double phi, int &k, double &from) const
  {
    const int n = (int)fl.size();
    if (!(phi >= kAngleErr && phi <= 360.0 - kAngleErr))
      return false;
    k = first[std::min((int)phi, kBins - 1)];
    while (k < n && fl[k].edge <= phi)
      k++;
    from = k > 0 ? fl[k - 1].edge : fl[n - 1].edge - 360.0;
    const double to = k < n ? fl[k].edge : fl[0].edge + 360.0;
    return phi - from >= kAngleErr && to - phi >= kAngleErr;
  }

  sure classify(double dx, double dy, double r2) const
  {
    const double none = -HUGE_VAL;
    const double r = std::sqrt(r2), outside = R - r;
    if (outside <= -0.5)                 // beyond the tip: 0 whatever the flutes
      return {0.0f, -0.5 - outside, none, none, -1};
    int k;
    double from;
    const double phi = fast_deg(dx, dy);
    if (!sector(phi, k, from))
      return {-1.0f, none, none, none, -1};
    const flute &f = k > 0 ? fl[k - 1] : fl.back();
    const double sface = (dx - f.ex) * f.nx + (dy - f.ey) * f.ny;
    const double face = std::min(outside, -sface) - 0.5;
    if (face >= 0)                       // inside the tip, behind the face
      return {1.0f, none, face, none, k};
    const double u = (phi - from) / f.width;
    double sback;
    if (u >= 1) {
      sback = r - R;
    } else {
      double wr = rad(f.width), rho = R - h * (1 - u * u * (3 - 2 * u));
      double drho = 6 * h * u * (1 - u) / wr;
      sback = (r - rho) / std::sqrt(1 + (drho / r) * (drho / r));
    }
    // inside = min(outside, max(-sface, -sback)), sback within f.margin
    const double lo = std::min(outside, std::max(-sface, -sback - f.margin));
    if (lo >= 0.5)
      return {1.0f, none, face, lo - 0.5, k};
    const double hi = std::min(outside, std::max(-sface, -sback + f.margin));
    if (hi <= -0.5)
      return {0.0f, none, none, -0.5 - hi, k};
    return {-1.0f, none, none, none, -1};
  }

  // pixels [x0, x1) of row y (dy = y - cy), all in the annulus
  void row(float *out, int x0, int x1, double dy, double dy2) const
  {
    for (int x = x0; x < x1;) {
      const double dx = x - cx, r2 = dx * dx + dy2;
      const sure s = classify(dx, dy, r2);
      if (s.value < 0) {
        out[x++] = cover_exact(fl, R, h, dx, dy, r2);
        continue;
      }
      // the pixels after it that cannot differ (2e-9: the rounding of both)
      const double e = 2e-9;
      int j = 0;
      if (s.k >= 0) {
        const double lip = (s.k > 0 ? fl[s.k - 1] : fl.back()).lip;
        j = (int)std::min((double)(x1 - 1 - x), std::max(std::floor(s.face - e), std::floor((s.all - e) / lip)));
        for (; j > 0; j /= 2) {
          int k;
          double from;
          if (sector(fast_deg(x + j - cx, dy), k, from) && k == s.k)
            break;
        }
      }
      j = std::max(j, (int)std::min((double)(x1 - 1 - x), std::floor(s.any - e)));
      j = std::max(j, 0);
      std::fill(out + x, out + x + j + 1, s.value);
      x += j + 1;
    }
  }
};

// Sensor noise: normal deviates from a table of the inverse normal law
// (65536 quantiles; four per 64-bit draw), much faster than Box-Muller.
const std::vector<float> &quantiles()
{
  static const std::vector<float> quant = [] {
    std::vector<float> q(65536);
    for (int i = 0; i < 65536; i++)
      q[i] = (float)inv_normal((i + 0.5) / 65536.0);
    return q;
  }();
  return quant;
}

// The image of ts_render, or with reference of ts_render_reference: every
// step as it was first written, which defines the image.
int render(const struct tm_model *m, const struct ts_view *v, unsigned char *pix, struct ts_truth *truth,
           char *err, size_t errlen, bool reference);

}  // namespace

extern "C" void ts_geometry(const struct tm_model *m, double x_um, double *edge_deg, double *flute_deg)
{
  tm_tooth_angles(m, edge_deg);
  double shift = m->lead > 0 ? m->hand * 360.0 * x_um / m->lead : 0.0;
  int n = m->teeth;
  for (int j = 0; j < n; j++) {
    edge_deg[j] += shift;
    // tooth j's flute runs forward to tooth j-1, one step (steps[j-1]) away
    double gap = n == 1 ? 360.0 : m->steps[(j + n - 1) % n];
    flute_deg[j] = std::min(kFluteShare * gap, kMaxFlute);
  }
}

extern "C" double ts_flute_depth(const struct tm_model *m)
{
  double tip = TM_TIP_FRACTION * m->image;
  double wmin = kMaxFlute;
  for (int j = 0; j < m->teeth; j++)
    wmin = std::min(wmin, kFluteShare * (m->teeth == 1 ? 360.0 : m->steps[j]));
  return std::min(0.3 * tip, 0.7 * tip * rad(wmin));
}

extern "C" int ts_render(const struct tm_model *m, const struct ts_view *v, unsigned char *pix,
                         struct ts_truth *truth, char *err, size_t errlen)
{
  return render(m, v, pix, truth, err, errlen, false);
}

extern "C" int ts_render_reference(const struct tm_model *m, const struct ts_view *v, unsigned char *pix,
                                   struct ts_truth *truth, char *err, size_t errlen)
{
  return render(m, v, pix, truth, err, errlen, true);
}

namespace {

int render(const struct tm_model *m, const struct ts_view *v, unsigned char *pix, struct ts_truth *truth,
           char *err, size_t errlen, bool reference)
{
  try {
    const int N = m->image, n = m->teeth;
    const double R = TM_TIP_FRACTION * N, h = ts_flute_depth(m);
    // the axis: image centre ((N-1)/2 in the pixel-centre convention) plus
    // an offset drawn for the section
    rng rs(((uint64_t)m->seed << 8) ^ (uint64_t)(v->section & 0xff) ^ 0x5ec7104ULL);
    double orad = kMaxOffset * N * std::sqrt(rs.uniform()), oang = 2 * kPi * rs.uniform();
    const double cx = (N - 1) / 2.0 + orad * std::cos(oang), cy = (N - 1) / 2.0 + orad * std::sin(oang);
    // illumination: a linear gradient in a fixed direction for the model
    rng rl((uint64_t)m->seed ^ 0x11c0ULL);
    double gang = 2 * kPi * rl.uniform();
    double gx = std::cos(gang) / N, gy = std::sin(gang) / N;

    std::vector<double> edge(n), width(n);
    ts_geometry(m, v->x_um, edge.data(), width.data());
    std::vector<flute> fl(n);
    for (int j = 0; j < n; j++) {
      flute &f = fl[j];
      f.edge = wrap360(edge[j] + v->mount_deg + v->a_deg);
      f.width = width[j];
      double a = rad(f.edge);
      f.ex = R * std::cos(a);
      f.ey = R * std::sin(a);
      double al = rad(f.edge - kRake);       // the face runs inward along -u(al)
      f.nx = -std::sin(al);
      f.ny = std::cos(al);
    }
    std::sort(fl.begin(), fl.end(), [](const flute &p, const flute &q) { return p.edge < q.edge; });
    if (truth) {
      truth->cx = cx;
      truth->cy = cy;
      truth->tip_px = R;
      truth->depth_px = h;
      for (int j = 0; j < n; j++) {
        truth->edge_deg[j] = wrap360(edge[j] + v->mount_deg + v->a_deg);
        truth->flute_deg[j] = width[j];
      }
    }

    const std::vector<float> &quant = quantiles();
    rng rn(mix(((uint64_t)m->seed << 32) ^ ((uint64_t)v->section << 24) ^ v->shot));
    const float sigma = (float)m->noise;
    uint64_t bits = 0;
    int left = 0;

    if (reference) {
      cv::Mat cover(N, N, CV_32F);
      const double rin = std::max(0.0, R - h - 2), rout = R + 2;
      for (int y = 0; y < N; y++) {
        float *row = cover.ptr<float>(y);
        const double dy = y - cy;
        for (int x = 0; x < N; x++) {
          const double dx = x - cx, r2 = dx * dx + dy * dy;
          if (r2 <= rin * rin) { row[x] = 1.0f; continue; }
          if (r2 >= rout * rout) { row[x] = 0.0f; continue; }
          row[x] = cover_exact(fl, R, h, dx, dy, r2);
        }
      }
      if (m->blur > 0)
        cv::GaussianBlur(cover, cover, cv::Size(0, 0), m->blur, m->blur, cv::BORDER_REPLICATE);
      for (int y = 0; y < N; y++) {
        const float *row = cover.ptr<float>(y);
        unsigned char *out = pix + (size_t)y * N;
        const double g0 = (0 - cx) * gx + (y - cy) * gy;
        for (int x = 0; x < N; x++) {
          float g = (float)(g0 + x * gx);                        // -0.7 .. 0.7
          float bg = 0.10f + 0.05f * g, fg = 0.78f + 0.12f * g;
          float val = bg + (fg - bg) * row[x];
          if (sigma > 0) {
            if (left == 0) {
              bits = rn.next();
              left = 4;
            }
            val += sigma * quant[bits & 0xffff];
            bits >>= 16;
            left--;
          }
          val = std::clamp(val, 0.0f, 1.0f) * 255.0f + 0.5f;
          out[x] = (unsigned char)val;
        }
      }
      return 0;
    }

    // The back's distance sback = (r - rho) / D, D = sqrt(1 + q^2),
    // q = rho' / (wr r) (u the position across the flute, rho' = d rho / du,
    // wr the width in radians), moves with u by at most
    // |rho'| / D + |r - rho| 0.385 |dq/du| (|q| / D^3 <= 0.385), where
    // |rho'| <= 1.5 h, |rho'| / D <= wr r and |dq/du| <= 6h / (wr r); and
    // with r by at most 1 + |r - rho| 0.385 / r (q^2 / D^3 <= 0.385).  In
    // the annulus, and between two of its pixels in a row, r >= rlo and
    // |r - rho| <= h + 2.5.  So an angle kAngleErr degrees off
    // (kAngleErr / width of u) moves sback by f.margin (1e-9 px more for
    // the rounding), and a pixel along a row (du <= 1 / (wr r)) by f.lip:
    // the radial and angular slopes' hypotenuse.  (rin is at least
    // 0.7 R - 2, some 17 px.)
    const double rin = std::max(0.0, R - h - 2), rout = R + 2, rlo = rin - 0.5;
    for (flute &f : fl) {
      const double wr = rad(f.width), du = 1.5 * h + (h + 2.5) * 0.39 * 6 * h / (wr * rlo);
      const double radial = 1 + 0.39 * (h + 2.5) / rlo;
      const double angular = 1 + (h + 2.5) * 0.39 * 6 * h / ((wr * rlo) * (wr * rlo));
      f.margin = rlo >= 1 ? du * kAngleErr / f.width + 1e-9 : HUGE_VAL;
      f.lip = rlo >= 1 ? std::hypot(radial, angular) : HUGE_VAL;
    }
    static thread_local outline ol;
    ol.fl = fl;
    ol.R = R;
    ol.h = h;
    ol.cx = cx;
    ol.cy = cy;
    for (int b = 0, k = 0; b < kBins; b++) {
      while (k < n && fl[k].edge <= b)
        k++;
      ol.first[b] = k;
    }

    // every pixel's coverage, rendered into a buffer kept for the next image
    // (fresh pages cost more than the arithmetic).  Inside rin the tool
    // covers the pixel, outside rout nothing does: a row is 0, then the
    // annulus, 1 inside rin, the annulus again, 0.
    static thread_local cv::Mat cover;
    cover.create(N, N, CV_32F);
    const double rin2 = rin * rin, rout2 = rout * rout;
    for (int y = 0; y < N; y++) {
      float *row = cover.ptr<float>(y);
      const double dy = y - cy, dy2 = dy * dy;
      int a0, a1, i0, i1;   // r2 < rout2 in [a0, a1), r2 <= rin2 in [i0, i1)
      run_within(N, cx, dy2, rout2, false, a0, a1);
      run_within(N, cx, dy2, rin2, true, i0, i1);
      if (i0 == i1)
        i0 = i1 = a1;
      std::fill(row, row + a0, 0.0f);
      ol.row(row, a0, i0, dy, dy2);
      std::fill(row + i0, row + i1, 1.0f);
      ol.row(row, i1, a1, dy, dy2);
      std::fill(row + a1, row + N, 0.0f);
    }
    if (m->blur > 0)
      cv::GaussianBlur(cover, cover, cv::Size(0, 0), m->blur, m->blur, cv::BORDER_REPLICATE);

    // the noise (quantiles()) as in the reference, a row at a time
    std::vector<float> noise(N, 0.0f);
    for (int y = 0; y < N; y++) {
      // a row's deviates first (the generator is sequential, and a draw
      // begun on one row goes on into the next), then the arithmetic,
      // which vectorizes (module.mk)
      if (sigma > 0) {
        int x = 0;
        for (; left > 0 && x < N; x++, left--, bits >>= 16)
          noise[x] = sigma * quant[bits & 0xffff];
        for (; x + 4 <= N; x += 4) {
          const uint64_t b = rn.next();
          noise[x] = sigma * quant[b & 0xffff];
          noise[x + 1] = sigma * quant[(b >> 16) & 0xffff];
          noise[x + 2] = sigma * quant[(b >> 32) & 0xffff];
          noise[x + 3] = sigma * quant[b >> 48];
        }
        if (x < N) {
          bits = rn.next();
          for (left = 4; x < N; x++, left--, bits >>= 16)
            noise[x] = sigma * quant[bits & 0xffff];
        }
      }
      const float *row = cover.ptr<float>(y), *nz = noise.data();
      unsigned char *out = pix + (size_t)y * N;
      const double g0 = (0 - cx) * gx + (y - cy) * gy;
      for (int x = 0; x < N; x++) {
        float g = (float)(g0 + x * gx);                        // -0.7 .. 0.7
        float bg = 0.10f + 0.05f * g, fg = 0.78f + 0.12f * g;
        float val = bg + (fg - bg) * row[x] + nz[x];
        // clamp(val, 0, 1) * 255 + 0.5 truncated, the same byte as the
        // clamp after the rounding (|val| < 6: the noise is 5 sigma at most)
        int v8 = (int)(val * 255.0f + 0.5f);
        out[x] = (unsigned char)std::min(std::max(v8, 0), 255);
      }
    }
    return 0;
  } catch (const std::exception &e) {
    if (err && errlen)
      std::snprintf(err, errlen, "render: %s", e.what());
  } catch (...) {
    if (err && errlen)
      std::snprintf(err, errlen, "render: unknown exception");
  }
  return -1;
}

}  // namespace
