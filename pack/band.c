/* Wall-band relaxation (see band.h). The spheres within `width` of the
 * boundary move; those up to 2 r_max + skin deeper are present but fixed,
 * so the band settles against the undisturbed interior. `width` covers the
 * band proper (about two diameters, where the cut disturbs the packing)
 * and a mobile buffer behind it: relaxing the band alone against a frozen
 * interior leaves the wall deficit near 0.15 d, since the band cannot
 * borrow room from the bulk. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "pack/band.h"
#include "pack/fire.h"

void band_relax(spheres *S, const surface *surf, const dem_geometry *g, const band_params *p,
                band_result *res)
{
	double rmax = 0;
	for (size_t i = 0; i < S->n; i++)
		rmax = fmax(rmax, S->r[i]);
	double reach = p->width + 2 * rmax + p->skin;
	size_t *idx = xmalloc(S->n * sizeof *idx + 1), m = 0;
	for (size_t i = 0; i < S->n; i++)
		if (S->lo[i] < reach)
			idx[m++] = i;
	double *x = xmalloc(3 * m * sizeof *x + 1), *r = xmalloc(m * sizeof *r + 1);
	uint8_t *mobile = xmalloc(m + 1);
	soft_system sys;
	soft_init(&sys, m, x, r, mobile);
	res->mobile = 0;
	for (size_t k = 0; k < m; k++) {
		size_t i = idx[k];
		v3_copy(x + 3 * k, S->x + 3 * i);
		r[k] = S->r[i];
		mobile[k] = S->hi[i] < p->width;
		res->mobile += mobile[k];
		sys.wall_s0[k] = S->lo[i];
	}
	memcpy(sys.wall_xq, x, 3 * m * sizeof *x);
	sys.wall = surf;
	sys.wall_vert = g->vert;
	sys.wall_tri = g->tri;
	sys.skin = p->skin;
	res->involved = m;
	res->iter = fire_minimise(&sys, p->max_iter, p->otol, p->ftol, &res->overlap);
	for (size_t k = 0; k < m; k++) {
		size_t i = idx[k];
		if (!mobile[k])
			continue;
		double d[3];
		v3_sub(d, x + 3 * k, S->x + 3 * i);
		v3_copy(S->x + 3 * i, x + 3 * k);
		S->lo[i] -= v3_norm(d); /* still bounds: the depth is 1-Lipschitz */
		S->hi[i] += v3_norm(d);
	}
	soft_free(&sys);
	free(idx);
	free(x);
	free(r);
	free(mobile);
}
