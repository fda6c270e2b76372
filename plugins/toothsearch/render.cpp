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
};

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

    cv::Mat cover(N, N, CV_32F);
    const double rin = std::max(0.0, R - h - 2), rout = R + 2;
    for (int y = 0; y < N; y++) {
      float *row = cover.ptr<float>(y);
      const double dy = y - cy;
      for (int x = 0; x < N; x++) {
        const double dx = x - cx, r2 = dx * dx + dy * dy;
        if (r2 <= rin * rin) { row[x] = 1.0f; continue; }
        if (r2 >= rout * rout) { row[x] = 0.0f; continue; }
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
        row[x] = (float)std::clamp(0.5 + inside, 0.0, 1.0);
      }
    }
    if (m->blur > 0)
      cv::GaussianBlur(cover, cover, cv::Size(0, 0), m->blur, m->blur, cv::BORDER_REPLICATE);

    // sensor noise: normal deviates from a table of the inverse normal law
    // (65536 quantiles; four per 64-bit draw), much faster than Box-Muller
    static const std::vector<float> quant = [] {
      std::vector<float> q(65536);
      for (int i = 0; i < 65536; i++)
        q[i] = (float)inv_normal((i + 0.5) / 65536.0);
      return q;
    }();
    rng rn(mix(((uint64_t)m->seed << 32) ^ ((uint64_t)v->section << 24) ^ v->shot));
    const float sigma = (float)m->noise;
    uint64_t bits = 0;
    int left = 0;
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
  } catch (const std::exception &e) {
    if (err && errlen)
      std::snprintf(err, errlen, "render: %s", e.what());
  } catch (...) {
    if (err && errlen)
      std::snprintf(err, errlen, "render: unknown exception");
  }
  return -1;
}
