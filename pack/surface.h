/* Inside tests and distances to a closed, outward-oriented triangulated
 * boundary (pack/trimesh.h), answered by a CGAL AABB tree. The C++ lives in
 * surface.cpp; this header is all the rest of pack sees.
 *
 * After surface_new() every query is read-only and may run from many
 * threads at once. */
#ifndef PACK_SURFACE_H
#define PACK_SURFACE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct surface surface;

/* Build the search structure over ntri triangles (vertex indices into vert,
 * outward orientation). The arrays are copied. NULL if the mesh is empty or
 * memory runs out. */
surface *surface_new(const double *vert, size_t nvert, const int32_t *tri, size_t ntri);
void surface_free(surface *s);

/* Signed distance from p to the boundary: positive inside, negative
 * outside. When normal is not NULL it receives the outward unit normal of
 * the boundary at the closest point (the angle-weighted pseudo-normal at
 * edges and vertices, which makes the sign exact; Baerentzen & Aanaes,
 * IEEE TVCG 11(3), 2005). `hint`, when not NULL and >= 0, is a triangle
 * close to p that speeds up the search; it receives the closest triangle. */
double surface_distance(const surface *s, const double p[3], double normal[3], int32_t *hint);

/* The signed distance from p as surface_distance(), searching only the n
 * triangles listed (which must include p's closest one, e.g. those
 * surface_near() found within a radius larger than the distance). */
double surface_distance_among(const surface *s, const double p[3], const int32_t *tri, size_t n);

/* The triangles within `radius` of p, in increasing order: up to max_out
 * are stored in out; the return value is their number. */
size_t surface_near(const surface *s, const double p[3], double radius, int32_t *out,
                    size_t max_out);

#ifdef __cplusplus
}
#endif

#endif
