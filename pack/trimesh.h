/* Boundary triangulations as pack needs them: welded, closed, manifold and
 * oriented with outward normals, so that inside tests and signed distances
 * (pack/surface.h) are well defined. */
#ifndef PACK_TRIMESH_H
#define PACK_TRIMESH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
	size_t nvert, ntri;
	double *vert; /* [nvert][3] */
	int32_t *tri; /* [ntri][3] */
} trimesh;

/* Merge vertices with identical coordinates, drop unused ones, check that
 * the surface is closed (every edge shared by exactly two triangles),
 * manifold, orientable and free of self-intersections, and orient every
 * shell so that normals (b-a)x(c-a) point out of the solid (shells nested
 * inside another shell bound cavities and point into them); the work is
 * CGAL's (pack/trimesh_close.cpp). `source` names the input in messages.
 * Returns 0 or -1. */
int trimesh_close(trimesh *m, const char *source);

/* Enclosed volume (m^3), surface area (m^2) and bounding box of a closed,
 * oriented mesh. */
void trimesh_measure(const trimesh *m, double *volume, double *area, double bmin[3],
                     double bmax[3]);

void trimesh_free(trimesh *m);

/* The point q of triangle (a, b, c) closest to p. */
void trimesh_closest_point(const double a[3], const double b[3], const double c[3],
                           const double p[3], double q[3]);

#ifdef __cplusplus
}
#endif

#endif
