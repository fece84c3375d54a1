/* A growable set of spheres with what pack knows of their depth, the
 * signed distance of their centre to the specimen boundary (positive
 * inside): bounds lo <= depth <= hi, equal when it was computed. */
#ifndef PACK_SPHERES_H
#define PACK_SPHERES_H

#include <stddef.h>

typedef struct {
	size_t n, cap;
	double *x;  /* [n][3] m */
	double *r;  /* [n] m */
	double *r0; /* [n] m, the radius drawn for it (the wall band may shrink r) */
	double *lo; /* [n] m, lower bound of the depth */
	double *hi; /* [n] m, upper bound of the depth */
} spheres;

void spheres_push(spheres *S, const double x[3], double r, double lo, double hi);
/* Keep the spheres with keep[i] != 0, in order. */
void spheres_compact(spheres *S, const unsigned char *keep);
void spheres_free(spheres *S);
/* Total volume of n spheres of radii r (m^3). */
double sphere_volume(const double *r, size_t n);

#endif
