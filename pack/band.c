/* Wall-band relaxation (see band.h). The spheres within `width` of the
 * boundary move; those up to 2 r_max + skin deeper are present but fixed,
 * so the band settles against the undisturbed interior. `width` covers the
 * band proper (about two diameters, where the cut disturbs the packing)
 * and a mobile buffer behind it: relaxing the band alone against a frozen
 * interior leaves the wall deficit near 0.15 d, since the band cannot
 * borrow room from the bulk.
 *
 * The cut leaves the band slightly over-full (spheres kept with their
 * centre at least keep r inside stick out by up to (1 - keep) r), and FIRE
 * alone needs thousands of iterations to spread the excess into the
 * buffer, a few crowded spots keeping the largest overlap high. So each
 * mobile sphere carries a radius factor lambda <= 1: an iteration that
 * leaves sphere i with a largest relative overlap o above the tolerance
 * multiplies lambda_i by 1 - SHRINK (o - tol); below half the tolerance
 * lambda_i regrows by the factor 1 + REGROW, up to 1. Crowded spots then
 * resolve locally within a few hundred iterations while the rest of the
 * band keeps its sizes. Radii start shrinking only after `shrink_after`
 * iterations, once FIRE has pushed the spheres cut by the boundary inside:
 * shrinking from the start would shrink those instead of moving them. A later relaxation starts
 * from the factors the previous one left (the drawn radius is kept with each sphere); the radii
 * that stay reduced are counted and show in the achieved distribution. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "pack/band.h"
#include "pack/fire.h"
#include "pack/morton.h"
#include "pack/par.h"

static const double SHRINK = 0.05, REGROW = 1e-3;

/* FIRE with a radius factor per mobile sphere (see the top of the file). */
static void relax(soft_system *sys, const double *r0, const band_params *p, band_result *res)
{
	size_t m = sys->nmobile;
	double *lambda = xmalloc(m * sizeof *lambda + 1);
	for (size_t k = 0; k < m; k++)
		lambda[k] = sys->r[k] / r0[k];
	sys->worst = xcalloc(m + 1, sizeof *sys->worst);
	fire_state st;
	fire_start(&st, sys);
	while (st.iter < p->max_iter) {
		fire_move(&st, sys);
#pragma omp parallel for schedule(static) if (m >= PAR_MIN)
		for (size_t k = 0; k < m; k++) {
			double o = st.iter > p->shrink_after ? sys->worst[k] : 0;
			if (o > p->otol)
				lambda[k] *= 1 - SHRINK * (o - p->otol);
			else if (o < 0.5 * p->otol)
				lambda[k] = fmin(1, lambda[k] * (1 + REGROW));
			sys->r[k] = r0[k] * lambda[k];
		}
		fire_forces(&st, sys);
		if (p->prog)
			progress_update(p->prog, (double)st.iter, "wall band");
	}
	res->iter = st.iter;
	res->overlap = st.stats.overlap_max;
	res->shrunk = 0;
	res->shrink_mean = res->shrink_max = 0;
	for (size_t k = 0; k < m; k++)
		if (lambda[k] < 1) {
			res->shrunk++;
			res->shrink_mean += 1 - lambda[k];
			res->shrink_max = fmax(res->shrink_max, 1 - lambda[k]);
		}
	res->shrink_mean /= res->shrunk ? (double)res->shrunk : 1;
	fire_end(&st);
	free(sys->worst);
	sys->worst = NULL;
	free(lambda);
}

/* Sort idx[first..m) along a Morton curve over g's bounding box. */
static void morton_sort_group(const spheres *S, const dem_geometry *g, size_t *idx, size_t first,
                              size_t m)
{
	double *xg = xmalloc(3 * (m - first) * sizeof *xg + 1);
	size_t *order = xmalloc((m - first) * sizeof *order + 1),
	       *copy = xmalloc((m - first) * sizeof *copy + 1);
	for (size_t k = first; k < m; k++)
		v3_copy(xg + 3 * (k - first), S->x + 3 * idx[k]);
	morton_order(xg, m - first, g->bbox_min, g->bbox_max, order);
	for (size_t k = 0; k < m - first; k++)
		copy[k] = idx[first + order[k]];
	memcpy(idx + first, copy, (m - first) * sizeof *copy);
	free(xg);
	free(order);
	free(copy);
}

/* The spheres of the computation: the moving ones first (*nm of them),
 * then the fixed ones within reach of them, each group along a Morton
 * curve; returns their indices in S, *m of them. */
static size_t *band_spheres(const spheres *S, const dem_geometry *g, const band_params *p,
                            size_t *m, size_t *nm)
{
	double rmax = 0;
	for (size_t i = 0; i < S->n; i++)
		rmax = fmax(rmax, S->r[i]);
	double reach = p->width + 2 * rmax + p->skin;
	size_t *idx = xmalloc(S->n * sizeof *idx + 1), k = 0;
	for (size_t i = 0; i < S->n; i++)
		if (S->hi[i] < p->width)
			idx[k++] = i;
	morton_sort_group(S, g, idx, 0, k);
	*nm = k;
	for (size_t i = 0; i < S->n; i++)
		if (!(S->hi[i] < p->width) && S->lo[i] < reach)
			idx[k++] = i;
	morton_sort_group(S, g, idx, *nm, k);
	*m = k;
	return idx;
}

/* The soft system over spheres idx[0..m) of S (positions x, radii r, the
 * first nm mobile) against the boundary, each sphere's depth bound from S
 * sparing its first query. */
static void band_system(soft_system *sys, const spheres *S, const size_t *idx, size_t m, size_t nm,
                        double *x, double *r, const surface *surf, const dem_geometry *g,
                        double skin)
{
	soft_init(sys, m, nm, x, r);
	for (size_t k = 0; k < m; k++) {
		size_t i = idx[k];
		v3_copy(x + 3 * k, S->x + 3 * i);
		r[k] = S->r[i];
		sys->wall_s0[k] = S->lo[i];
	}
	memcpy(sys->wall_xq, x, 3 * m * sizeof *x);
	sys->wall = surf;
	sys->wall_vert = g->vert;
	sys->wall_tri = g->tri;
	sys->skin = skin;
}

void band_relax(spheres *S, const surface *surf, const dem_geometry *g, const band_params *p,
                band_result *res)
{
	size_t m, nm, *idx = band_spheres(S, g, p, &m, &nm);
	double *x = xmalloc(3 * m * sizeof *x + 1), *r = xmalloc(m * sizeof *r + 1);
	double *r0 = xmalloc(nm * sizeof *r0 + 1);
	for (size_t k = 0; k < nm; k++)
		r0[k] = S->r0[idx[k]];
	soft_system sys;
	band_system(&sys, S, idx, m, nm, x, r, surf, g, p->skin);
	res->mobile = nm;
	res->involved = m;
	relax(&sys, r0, p, res);
	for (size_t k = 0; k < nm; k++) {
		size_t i = idx[k];
		double d[3];
		v3_sub(d, x + 3 * k, S->x + 3 * i);
		v3_copy(S->x + 3 * i, x + 3 * k);
		S->r[i] = r[k];
		S->lo[i] -= v3_norm(d); /* still bounds: the depth is 1-Lipschitz */
		S->hi[i] += v3_norm(d);
	}
	soft_free(&sys);
	free(idx);
	free(x);
	free(r);
	free(r0);
}
