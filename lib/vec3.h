/* Small 3-vector helpers on plain double[3] arrays (header only). */
#ifndef DEM_VEC3_H
#define DEM_VEC3_H

#include <math.h>

/* π (M_PI is not part of C17). */
#define DEM_PI 3.14159265358979323846

static inline double v3_dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static inline double v3_norm(const double a[3]) { return sqrt(v3_dot(a, a)); }
static inline void v3_sub(double out[3], const double a[3], const double b[3])
{
	out[0] = a[0] - b[0];
	out[1] = a[1] - b[1];
	out[2] = a[2] - b[2];
}
static inline void v3_add(double out[3], const double a[3], const double b[3])
{
	out[0] = a[0] + b[0];
	out[1] = a[1] + b[1];
	out[2] = a[2] + b[2];
}
static inline void v3_scale(double out[3], const double a[3], double s)
{
	out[0] = a[0] * s;
	out[1] = a[1] * s;
	out[2] = a[2] * s;
}
/* out += a * s */
static inline void v3_axpy(double out[3], const double a[3], double s)
{
	out[0] += a[0] * s;
	out[1] += a[1] * s;
	out[2] += a[2] * s;
}
static inline void v3_cross(double out[3], const double a[3], const double b[3])
{
	double x = a[1] * b[2] - a[2] * b[1];
	double y = a[2] * b[0] - a[0] * b[2];
	double z = a[0] * b[1] - a[1] * b[0];
	out[0] = x;
	out[1] = y;
	out[2] = z;
}
static inline void v3_copy(double out[3], const double a[3])
{
	out[0] = a[0];
	out[1] = a[1];
	out[2] = a[2];
}
/* out = a / |a|, also for a vector whose squared length would overflow or
 * underflow (it is scaled by its largest component first); -1 for a zero or
 * non-finite vector. */
static inline int v3_unit(double out[3], const double a[3])
{
	double m = fmax(fabs(a[0]), fmax(fabs(a[1]), fabs(a[2])));
	if (!(m > 0 && m <= 1.7976931348623157e308))
		return -1;
	double s = m > 1e-100 && m < 1e100 ? 1 : m;
	double b[3] = {a[0] / s, a[1] / s, a[2] / s};
	double l = v3_norm(b);
	for (int k = 0; k < 3; k++)
		out[k] = b[k] / l;
	return 0;
}
/* Remove from a its component along the unit vector n. */
static inline void v3_reject(double out[3], const double a[3], const double n[3])
{
	double d = v3_dot(a, n);
	out[0] = a[0] - d * n[0];
	out[1] = a[1] - d * n[1];
	out[2] = a[2] - d * n[2];
}

#endif
