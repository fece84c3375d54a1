/* The boundary triangles listed near each moving sphere of a soft system
 * (soft_walls.c), for soft_neighbours.c, which lists them at every build,
 * and soft_forces.c, which finds each sphere's contact among them. */
#ifndef PACK_SOFT_WALLS_H
#define PACK_SOFT_WALLS_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "lib/vec3.h"
#include "pack/soft.h"
#include "pack/trimesh.h"

/* The lists' arrays, allocated at the first build. */
void soft_walls_prepare(soft_system *s);

/* List again, at a build, the triangles sphere i may touch before the next
 * one (see soft_walls.c). */
void soft_walls_update(soft_system *s, size_t i);

/* The contact query below runs for every sphere near the boundary at every
 * force evaluation: it is inline here so that the force loop keeps it
 * inlined, without a call per sphere. */

/* Distance from p to the triangle k (pack/trimesh.h) and the closest point. */
static inline double soft_triangle_distance(const soft_system *s, int32_t k, const double p[3],
                                            double q[3])
{
	const int32_t *t = s->wall_tri + 3 * (size_t)k;
	trimesh_closest_point(s->wall_vert + 3 * t[0], s->wall_vert + 3 * t[1],
	                      s->wall_vert + 3 * t[2], p, q);
	double d[3];
	v3_sub(d, p, q);
	return v3_norm(d);
}

/* The closest point q of the boundary to sphere i among its listed
 * triangles, if closer than its radius; returns that distance (or
 * INFINITY). A triangle listed at distance d_k from x_b is at least
 * d_k - |x - x_b| from x (the distance is 1-Lipschitz), so the ascending
 * list is cut as soon as that bound reaches the best found or the radius.
 * Most spheres are decided by the first two entries, kept apart from the
 * list so that the test reads memory in sphere order only. */
static inline double soft_wall_contact(const soft_system *s, size_t i, double q[3])
{
	const double *xi = s->x + 3 * i;
	double d[3], qk[3], best = s->r[i];
	v3_sub(d, xi, s->wall_xb + 3 * i);
	double moved = v3_norm(d), found = INFINITY;
	if (s->wall_near[i] - moved >= best)
		return found;
	double d0 = soft_triangle_distance(s, s->wall_first[i], xi, qk);
	if (d0 < best) {
		best = found = d0;
		v3_copy(q, qk);
	}
	if (s->wall_second[i] - moved >= best)
		return found;
	const wall_entry *e = s->wall_pool + i * WALL_MAX;
	for (int k = 1; k < s->wall_count[i] && e[k].dist - moved < best; k++) {
		double dk = soft_triangle_distance(s, e[k].tri, xi, qk);
		if (dk < best) {
			best = found = dk;
			v3_copy(q, qk);
		}
	}
	return found;
}

#endif
