/* Arcs and planes (src/core/geom.h). */
#include "geom.h"
#include <math.h>
#include <stdio.h>

void geom_plane_axes(int plane, int *p, int *q)
{
  switch (plane) {
  case GEOM_XY: *p = 0; *q = 1; break;
  case GEOM_YZ: *p = 1; *q = 2; break;
  default: *p = 0; *q = 2; break;
  }
}

void geom_arc_radii(const struct geom_arc *a, double *r0, double *r1)
{
  *r0 = hypot(a->cp, a->cq);
  *r1 = hypot(a->ep - a->cp, a->eq - a->cq);
}

int geom_arc_check(const struct geom_arc *a, double max_r, double tol, char *msg, size_t n)
{
  double r0, r1;
  geom_arc_radii(a, &r0, &r1);
  if (r0 == 0) {
    snprintf(msg, n, "arc centre at its start point: radius 0");
    return -1;
  }
  if (r0 > max_r || r1 > max_r) {
    snprintf(msg, n, "arc radius %.3f mm is over %.0f mm", fmax(r0, r1) / 1000, max_r / 1000);
    return -1;
  }
  if (fabs(r0 - r1) > tol) {
    snprintf(msg, n, "arc start radius %.0f µm and end radius %.0f µm differ by more than %.0f µm", r0, r1, tol);
    return -1;
  }
  return 0;
}

double geom_arc_sweep(const struct geom_arc *a)
{
  if (a->ep == 0 && a->eq == 0)
    return 2 * M_PI;
  double a0 = atan2(-a->cq, -a->cp), a1 = atan2(a->eq - a->cq, a->ep - a->cp);
  double s = fmod(a->ccw ? a1 - a0 : a0 - a1, 2 * M_PI);
  if (s <= 0)
    s += 2 * M_PI;
  return s;
}

void geom_arc_angles(const struct geom_arc *a, double *t0, double *dt)
{
  double s = geom_arc_sweep(a);
  *t0 = atan2(-a->cq, -a->cp);
  *dt = a->ccw ? s : -s;
}

int geom_in_sweep(double t0, double dt, double t)
{
  double rel = dt >= 0 ? t - t0 : t0 - t;
  rel = fmod(rel, 2 * M_PI);
  if (rel < 0)
    rel += 2 * M_PI;
  return rel <= fabs(dt) + 1e-12;
}

double geom_arc_length(const struct geom_arc *a)
{
  double r0, r1;
  geom_arc_radii(a, &r0, &r1);
  return (r0 + r1) / 2 * geom_arc_sweep(a);
}

void geom_arc_box(const struct geom_arc *a, double lo[2], double hi[2])
{
  lo[0] = fmin(0, a->ep);
  hi[0] = fmax(0, a->ep);
  lo[1] = fmin(0, a->eq);
  hi[1] = fmax(0, a->eq);
  double t0, dt, r = hypot(a->cp, a->cq);
  geom_arc_angles(a, &t0, &dt);
  for (int k = 0; k < 4; k++) {
    double th = k * M_PI / 2;
    if (!geom_in_sweep(t0, dt, th))
      continue;
    double x = a->cp + r * cos(th), y = a->cq + r * sin(th);
    lo[0] = fmin(lo[0], x);
    hi[0] = fmax(hi[0], x);
    lo[1] = fmin(lo[1], y);
    hi[1] = fmax(hi[1], y);
  }
}

void geom_arc_point(const struct geom_arc *a, double u, double *p, double *q)
{
  double t0, dt, r0, r1;
  geom_arc_angles(a, &t0, &dt);
  geom_arc_radii(a, &r0, &r1);
  double th = t0 + dt * u, r = r0 + (r1 - r0) * u;
  *p = a->cp + r * cos(th);
  *q = a->cq + r * sin(th);
}
