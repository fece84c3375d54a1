/* The specimen frame: origin at the geometry centre, unit loading axis a
 * (/geometry axis) and two unit vectors e1, e2 completing a right-handed
 * frame (e1, e2, a). For a = z, e1 = x and e2 = y; otherwise e1 is the
 * coordinate axis least aligned with a, made orthogonal to it.
 * Cylindrical coordinates of a point p, d = p - origin:
 *   h   = d . a                 (m, along the axis)
 *   rho = |d - h a|             (m, distance to the axis)
 *   phi = atan2(d . e2, d . e1) (deg, in [0, 360))
 * and the orientation of a direction n relative to the loading:
 *   theta = asin(|n . a| / |n|) (deg, 0 horizontal, 90 along the axis). */
#ifndef DEM_POST_FRAME_H
#define DEM_POST_FRAME_H

#include "lib/assembly.h"

#define POST_PI 3.14159265358979323846
#define POST_DEG (180.0 / POST_PI)

typedef struct {
	double o[3], a[3], e1[3], e2[3];
} frame;

void frame_of(frame *f, const dem_geometry *g);
void frame_cyl(const frame *f, const double p[3], double *h, double *rho, double *phi);
double frame_theta(const frame *f, const double n[3]);

#endif
