/* Boundary triangles near each moving sphere of the soft-sphere system
 * (see soft_walls.h).
 *
 * At each build a sphere near the boundary lists the triangles within
 * r + skin + WALL_MARGIN skins of it, nearest first; the list serves the
 * following builds while the sphere stays within the margin of where it was
 * made, and each force evaluation finds the sphere's closest boundary point
 * among them (soft_wall_contact). Since the signed distance is
 * 1-Lipschitz, a sphere with s_q - |x - x_q| > r + skin cannot touch the
 * boundary before the next build and is not queried. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "pack/soft.h"
#include "pack/soft_walls.h"

void soft_walls_prepare(soft_system *s)
{
	if (s->wall_pool)
		return;
	s->wall_pool = xmalloc(s->nmobile * WALL_MAX * sizeof *s->wall_pool + 1);
	s->wall_near = xmalloc(s->nmobile * sizeof *s->wall_near + 1);
	s->wall_first = xmalloc(s->nmobile * sizeof *s->wall_first + 1);
	s->wall_second = xmalloc(s->nmobile * sizeof *s->wall_second + 1);
	for (size_t i = 0; i < s->nmobile; i++)
		s->wall_near[i] = INFINITY;
}

/* The triangles of e[0..m) sorted by their distance from p (then by
 * index), with that distance rounded down to single precision. */
static void sort_by_distance(const soft_system *s, const double p[3], wall_entry *e, size_t m)
{
	double q[3];
	for (size_t k = 0; k < m; k++) { /* insertion sort: m is small */
		wall_entry ek = e[k];
		double dk = soft_triangle_distance(s, ek.tri, p, q);
		ek.dist = (float)dk;
		if (ek.dist > dk)
			ek.dist = nextafterf(ek.dist, -INFINITY);
		size_t at = k;
		for (; at > 0 && (e[at - 1].dist > ek.dist ||
		                  (e[at - 1].dist == ek.dist && e[at - 1].tri > ek.tri));
		     at--)
			e[at] = e[at - 1];
		e[at] = ek;
	}
}

/* The first two entries of sphere i's list, kept apart (see soft_wall_contact). */
static void wall_inline(soft_system *s, size_t i)
{
	const wall_entry *e = s->wall_pool + i * WALL_MAX;
	int m = s->wall_count[i];
	s->wall_near[i] = m > 0 ? e[0].dist : INFINITY;
	s->wall_first[i] = m > 0 ? e[0].tri : -1;
	s->wall_second[i] = m > 1 ? e[1].dist : INFINITY;
}

/* The boundary triangles sphere i may touch before the next build. A query
 * at x_q lists the triangles within r + skin + WALL_MARGIN (the WALL_MAX
 * nearest, the margin shrinking to what they cover if there are more);
 * the list serves every build while the sphere stays within the margin of
 * x_q. At every build the list is sorted again by the distances from the
 * sphere's position then, the base point x_b, so that the bound in
 * soft_wall_contact() stays tight. Without a list, the depth bound
 * s_q - |x - x_q| tells whether the sphere can reach the boundary at all. */
void soft_walls_update(soft_system *s, size_t i)
{
	double d[3], *xi = s->x + 3 * i;
	wall_entry *pool = s->wall_pool + i * WALL_MAX;
	v3_sub(d, xi, s->wall_xq + 3 * i);
	double moved = v3_norm(d), reach = s->r[i] + s->skin;
	v3_copy(s->wall_xb + 3 * i, xi);
	if (s->wall_count[i] && moved <= s->wall_margin[i]) {
		sort_by_distance(s, xi, pool, s->wall_count[i]);
		wall_inline(s, i);
		return;
	}
	s->wall_count[i] = 0;
	wall_inline(s, i);
	if (s->wall_s0[i] - moved > reach)
		return;
	v3_copy(s->wall_xq + 3 * i, xi);
	s->wall_s0[i] = surface_distance(s->wall, xi, NULL, &s->wall_hint[i]);
	if (s->wall_s0[i] > reach + WALL_MARGIN * s->skin)
		return;
	enum { CAP = 4 * WALL_MAX };
	int32_t found[CAP];
	wall_entry buf[CAP];
	double margin = WALL_MARGIN * s->skin;
	size_t m = surface_near(s->wall, xi, reach + margin, found, CAP);
	m = m < CAP ? m : CAP;
	for (size_t k = 0; k < m; k++)
		buf[k].tri = found[k];
	sort_by_distance(s, xi, buf, m);
	if (m > WALL_MAX) { /* keep the nearest; the list covers less */
		margin = fmin(margin, buf[WALL_MAX].dist - reach);
		m = WALL_MAX;
	}
	memcpy(pool, buf, m * sizeof *buf);
	s->wall_count[i] = (uint8_t)m;
	wall_inline(s, i);
	s->wall_margin[i] = margin;
}
