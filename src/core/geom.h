/* Geometry of arcs and planes, once: the check at compile time, the
 * machine's speed limits and travel, the helix's host side and the plot all
 * take arcs from here.  Axes are indices (0 X, 1 Y, 2 Z, 3 A); an arc is
 * given relative to its start point, in discretes, as the 2С42 writes it. */
#ifndef S42_GEOM_H
#define S42_GEOM_H

#include <stddef.h>

/* The planes by their axes: XY, YZ, XZ (the 2С42's G17, G18, G19). */
enum geom_plane { GEOM_XY, GEOM_YZ, GEOM_XZ };

/* The plane's two axes, in the order its angles are measured (p, then q). */
void geom_plane_axes(int plane, int *p, int *q);

/* An arc from the start (0, 0) to (ep, eq) round the centre (cp, cq), in
 * the plane's axes; ccw turns from p towards q.  An end at the start is a
 * full turn. */
struct geom_arc {
  double ep, eq, cp, cq;
  int ccw;
};

/* The radius at the start and at the end. */
void geom_arc_radii(const struct geom_arc *a, double *r0, double *r1);
/* Check the arc: its radius is not 0, at most max_r, and the end's radius
 * is the start's within tol.  0, or -1 with the reason in msg (E-ARC). */
int geom_arc_check(const struct geom_arc *a, double max_r, double tol, char *msg, size_t n);
/* The start angle t0 and the signed sweep dt (radians; > 0 ccw). */
void geom_arc_angles(const struct geom_arc *a, double *t0, double *dt);
/* The sweep, unsigned: (0, 2 pi]. */
double geom_arc_sweep(const struct geom_arc *a);
/* Is the angle t on the sweep from t0 of signed length dt? */
int geom_in_sweep(double t0, double dt, double t);
/* Its length, in the units of its words (the mean of the two radii times
 * the sweep). */
double geom_arc_length(const struct geom_arc *a);
/* The box the arc stays in, relative to its start: lo[0..1], hi[0..1] in
 * (p, q) -- the ends and every quadrant point it passes. */
void geom_arc_box(const struct geom_arc *a, double lo[2], double hi[2]);
/* The point at the share u (0..1) of the sweep, relative to the start. */
void geom_arc_point(const struct geom_arc *a, double u, double *p, double *q);

#endif
