/* The lateral surface of the specimen and the radial strain gauge.
 *
 * The lateral surface is divided into n_θ × n_z bins (about one mean
 * diameter wide, fixed at start, stretched with the specimen's current
 * height). The outermost particle of each bin (largest ρ + r, ρ the
 * distance to the axis) is a surface particle; the bin's area on the current
 * boundary, (ρ + r) Δθ Δz, is its tributary area. Updated every few steps,
 * so the set follows the deforming specimen.
 *
 * Confinement p_c (§10.1.1 of Oñate et al. 2015) becomes a radial inward
 * force on each surface particle: π r_i² p_c (the paper's approximation), or
 * p_c times its tributary area (the default: the forces then add up to p_c
 * times the current lateral area). The θ origin is the direction of the
 * outermost particle at start, so the bins turn with the specimen.
 *
 * The gauge, like the lab's strain gauges, is the set of particles in the
 * outermost shell (one mean diameter) of the middle band of the height
 * (a tenth of it, at least a diameter): radial strain = -mean(ρ - ρ0) / R0,
 * compression positive. */
#include <math.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "solve/engine.h"

/* Axial coordinate and radial vector of a position. */
static double frame(const engine *e, const double *x, double rho[3])
{
	double d[3] = {x[0] - e->center[0], x[1] - e->center[1], x[2] - e->center[2]};
	double z = v3_dot(d, e->axis);
	for (int k = 0; k < 3; k++)
		rho[k] = d[k] - z * e->axis[k];
	return z;
}

static void extent(const engine *e, double *lo, double *hi)
{
	const particles *P = &e->p;
	*lo = INFINITY;
	*hi = -INFINITY;
	for (size_t i = 0; i < P->n; i++) {
		double rho[3], z = frame(e, P->x + 3 * i, rho);
		*lo = fmin(*lo, z - P->r[i]);
		*hi = fmax(*hi, z + P->r[i]);
	}
}

void surface_init(engine *e)
{
	particles *P = &e->p;
	surface *S = &e->surf;
	/* θ origin: the outermost particle (lowest index among equals). */
	double best = -1, lo, hi;
	for (size_t i = 0; i < P->n; i++) {
		double rho[3];
		frame(e, P->x + 3 * i, rho);
		double out = v3_norm(rho) + P->r[i];
		if (out > best) {
			best = out;
			v3_copy(e->e1, rho);
		}
	}
	double l = v3_norm(e->e1);
	if (l == 0) {
		/* A column on the axis: any direction normal to it. */
		double t[3] = {1, 0, 0};
		if (fabs(e->axis[0]) > 0.9)
			t[0] = 0, t[1] = 1;
		v3_reject(e->e1, t, e->axis);
		l = v3_norm(e->e1);
	}
	v3_scale(e->e1, e->e1, 1 / l);
	v3_cross(e->e2, e->axis, e->e1);
	extent(e, &lo, &hi);
	S->bin = e->cs->surface_bin > 0 ? e->cs->surface_bin : 2 * e->r_mean;
	S->ntheta = (int)fmax(8, round(2 * DEM_PI * best / S->bin));
	S->nz = (int)fmax(1, round((hi - lo) / S->bin));
	size_t nbins = (size_t)S->ntheta * S->nz;
	S->best = xmalloc(nbins * sizeof *S->best);
	S->best_rho = xmalloc(nbins * sizeof *S->best_rho);
	S->cap = nbins;
	S->idx = xmalloc(nbins * sizeof *S->idx);
	S->area = xmalloc(nbins * sizeof *S->area);
	S->n = 0;
	surface_update(e);
}

void surface_update(engine *e)
{
	particles *P = &e->p;
	surface *S = &e->surf;
	size_t nbins = (size_t)S->ntheta * S->nz;
	double lo, hi;
	extent(e, &lo, &hi);
	double dz = (hi - lo) / S->nz, dth = 2 * DEM_PI / S->ntheta;
	for (size_t b = 0; b < nbins; b++) {
		S->best[b] = -1;
		S->best_rho[b] = -INFINITY;
	}
	for (size_t i = 0; i < P->n; i++) {
		double rho[3], z = frame(e, P->x + 3 * i, rho);
		double th = atan2(v3_dot(rho, e->e2), v3_dot(rho, e->e1));
		int it = (int)floor((th + DEM_PI) / dth), iz = (int)floor((z - lo) / dz);
		it = it < 0 ? 0 : it >= S->ntheta ? S->ntheta - 1 : it;
		iz = iz < 0 ? 0 : iz >= S->nz ? S->nz - 1 : iz;
		size_t b = (size_t)iz * S->ntheta + it;
		double out = v3_norm(rho) + P->r[i];
		if (out > S->best_rho[b]) {
			S->best_rho[b] = out;
			S->best[b] = (int32_t)i;
		}
	}
	for (size_t k = 0; k < S->n; k++)
		P->surf[S->idx[k]] = -1;
	S->n = 0;
	S->lateral_area = 0;
	double rsum = 0;
	size_t used = 0;
	for (size_t b = 0; b < nbins; b++) {
		int32_t i = S->best[b];
		if (i < 0)
			continue;
		double a = S->best_rho[b] * dth * dz;
		if (P->surf[i] < 0) {
			P->surf[i] = (int32_t)S->n;
			S->idx[S->n] = i;
			S->area[S->n++] = 0;
		}
		S->area[P->surf[i]] += a;
		S->lateral_area += a;
		rsum += S->best_rho[b];
		used++;
	}
	S->radius = used ? rsum / used : 0;
	S->updated = e->step;
}

void gauge_init(engine *e)
{
	const particles *P = &e->p;
	gauge *G = &e->gg;
	double lo, hi;
	extent(e, &lo, &hi);
	double mid = 0.5 * (lo + hi), half = fmax(0.05 * (hi - lo), e->r_mean);
	double outer = -INFINITY;
	for (size_t i = 0; i < P->n; i++) {
		double rho[3], z = frame(e, P->x + 3 * i, rho);
		if (fabs(z - mid) <= half)
			outer = fmax(outer, v3_norm(rho) + P->r[i]);
	}
	G->idx = xmalloc((P->n + 1) * sizeof *G->idx);
	G->rho0 = xmalloc((P->n + 1) * sizeof *G->rho0);
	G->n = 0;
	double rsum = 0;
	for (size_t i = 0; i < P->n; i++) {
		double rho[3], z = frame(e, P->x + 3 * i, rho);
		double r = v3_norm(rho);
		if (fabs(z - mid) <= half && r + P->r[i] >= outer - 2 * e->r_mean) {
			G->idx[G->n] = (int32_t)i;
			G->rho0[G->n++] = r;
			rsum += r + P->r[i];
		}
	}
	G->radius0 = G->n ? rsum / G->n : 0;
}

double gauge_strain(const engine *e)
{
	const gauge *G = &e->gg;
	if (!G->n || G->radius0 <= 0)
		return 0;
	double sum = 0;
	for (size_t k = 0; k < G->n; k++) {
		double rho[3];
		frame(e, e->p.x + 3 * G->idx[k], rho);
		sum += v3_norm(rho) - G->rho0[k];
	}
	return -sum / G->n / G->radius0;
}
