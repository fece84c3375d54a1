/* The soft-sphere system itself (see soft.h): its arrays and the
 * minimum-image separation. The rest is in three files, one per concern:
 * soft_neighbours.c (the Verlet list), soft_walls.c (the boundary
 * triangles near each sphere) and soft_forces.c (the forces). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "pack/soft.h"

void soft_init(soft_system *s, size_t n, size_t nmobile, double *x, double *r)
{
	memset(s, 0, sizeof *s);
	s->n = n;
	s->x = x;
	s->r = r;
	s->nmobile = nmobile;
	s->nb_start = xcalloc(n + 1, sizeof *s->nb_start);
	s->xr = xmalloc(4 * n * sizeof *s->xr + 1);
	s->x_built = xmalloc(3 * n * sizeof *s->x_built + 1);
	s->r_built = xmalloc(n * sizeof *s->r_built + 1);
	s->wall_s0 = xmalloc(n * sizeof *s->wall_s0 + 1);
	s->wall_xq = xmalloc(3 * n * sizeof *s->wall_xq + 1);
	s->wall_xb = xmalloc(3 * n * sizeof *s->wall_xb + 1);
	s->wall_hint = xmalloc(n * sizeof *s->wall_hint + 1);
	s->wall_margin = xcalloc(n + 1, sizeof *s->wall_margin);
	s->wall_count = xcalloc(n + 1, 1);
	for (size_t i = 0; i < n; i++) {
		s->wall_s0[i] = -INFINITY;
		s->wall_hint[i] = -1;
	}
	memcpy(s->wall_xq, x, 3 * n * sizeof *x);
	s->stale = 1;
}

void soft_free(soft_system *s)
{
	free(s->nb_start);
	free(s->xr);
	free(s->nb);
	free(s->nb_shift);
	free(s->x_built);
	free(s->r_built);
	free(s->wall_s0);
	free(s->wall_xq);
	free(s->wall_xb);
	free(s->wall_hint);
	free(s->wall_margin);
	free(s->wall_count);
	free(s->wall_pool);
	free(s->wall_near);
	free(s->wall_first);
	free(s->wall_second);
	memset(s, 0, sizeof *s);
}

void soft_delta(const soft_system *s, size_t i, size_t j, double d[3])
{
	v3_sub(d, s->x + 3 * j, s->x + 3 * i);
	if (soft_periodic(s))
		for (int k = 0; k < 3; k++)
			d[k] -= s->box[k] * nearbyint(d[k] / s->box[k]);
}
