/* The lateral surface of the specimen and the radial strain gauge.
 *
 * The lateral surface is divided into n_θ × n_z bins (about one mean
 * diameter wide, fixed at start, stretched with the specimen's current
 * height). Of the spheres overlapping a bin (as seen from the axis), the
 * outermost one (largest ρ + r, ρ the distance to the axis) is a surface
 * particle, and the bin's area on the current boundary, (ρ + r) Δθ Δz, is
 * part of its tributary area. Binning the spheres rather than their centres
 * keeps a deep particle from claiming a bin that an outer one half covers.
 * The surface layer is every sphere reaching within its own radius of the
 * outermost point of a bin it overlaps (those in the hollows between the
 * outermost ones too); the bins enclose the specimen's current volume
 * Σ ½ (ρ + r)² Δθ Δz. Updated every few steps,
 * so the set follows the deforming specimen.
 *
 * Confinement p_c (§10.1.1 of Oñate et al. 2015) becomes a radial inward
 * force: π r_i² p_c on each particle of the surface layer (the paper's
 * approximation), or p_c times the tributary area of each outermost
 * particle (the default: the forces then add up to p_c times the current
 * lateral area). A lateral constraint holds the surface layer. The θ origin is the direction of the
 * outermost particle at start, so the bins turn with the specimen.
 *
 * The gauge, like the lab's strain gauges, is the set of particles in the
 * outermost shell (one mean diameter) of the middle band of the height
 * (a tenth of it, at least a diameter): radial strain = -mean(ρ - ρ0) / R0,
 * compression positive. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "lib/xsum.h"
#include "solve/engine.h"
#include "solve/par.h"
#include "solve/ranks.h"
#include "solve/surface.h"

/* Axial coordinate and radial vector of a position. */
static double frame(const engine *e, const double *x, double rho[3])
{
	double d[3] = {x[0] - e->frame.center[0], x[1] - e->frame.center[1],
	               x[2] - e->frame.center[2]};
	double z = v3_dot(d, e->frame.axis);
	for (int k = 0; k < 3; k++)
		rho[k] = d[k] - z * e->frame.axis[k];
	return z;
}

/* The axial extent of the particles [p0, p1), over the ranks when split
 * (ranks_own). */
static void extent(const engine *e, size_t p0, size_t p1, int split, double *lo, double *hi)
{
	const particles *P = &e->p;
	double m[2] = {-INFINITY, -INFINITY}; /* -lo, hi */
	for (size_t i = p0; i < p1; i++) {
		double rho[3], z = frame(e, P->x + 3 * i, rho);
		m[0] = fmax(m[0], -(z - P->r[i]));
		m[1] = fmax(m[1], z + P->r[i]);
	}
	if (split)
		par_max(m, 2);
	*lo = -m[0];
	*hi = m[1];
}

int surface_init(engine *e)
{
	particles *P = &e->p;
	surface *S = &e->bc.surf;
	size_t p0, p1;
	int split = ranks_own(e, &p0, &p1);
	/* θ origin: the outermost particle (lowest index among equals). */
	double best = -1, lo, hi;
	int32_t at = 0;
	for (size_t i = p0; i < p1; i++) {
		double rho[3];
		frame(e, P->x + 3 * i, rho);
		double out = v3_norm(rho) + P->r[i];
		if (out > best)
			best = out, at = (int32_t)i;
	}
	if (split)
		par_maxloc(&best, &at, 1);
	double row[PARTICLE_ROW];
	ranks_particle(e, (size_t)at, row);
	frame(e, row, e->frame.e1);
	double l = v3_norm(e->frame.e1);
	if (l == 0) {
		/* A column on the axis: any direction normal to it. */
		double t[3] = {1, 0, 0};
		if (fabs(e->frame.axis[0]) > 0.9)
			t[0] = 0, t[1] = 1;
		v3_reject(e->frame.e1, t, e->frame.axis);
		l = v3_norm(e->frame.e1);
	}
	v3_scale(e->frame.e1, e->frame.e1, 1 / l);
	v3_cross(e->frame.e2, e->frame.axis, e->frame.e1);
	extent(e, p0, p1, split, &lo, &hi);
	S->bin = e->cs->surface_bin > 0 ? e->cs->surface_bin : 2 * e->frame.r_mean;
	double ntheta = fmax(8, round(2 * DEM_PI * best / S->bin)),
	       nz = fmax(1, round((hi - lo) / S->bin));
	/* A specimen of 10^8 spheres has some 10^5 bins: many more say the
	 * particles' positions or sizes are not a specimen's. */
	if (!(ntheta * nz <= SURFACE_MAX_BINS))
		return err_set("the lateral surface would take %.3g x %.3g bins of %g m (radius %g "
		               "m, height %g m): expected at most %g; the assembly's positions or "
		               "radii are not a specimen's",
		               ntheta, nz, S->bin, best, hi - lo, (double)SURFACE_MAX_BINS);
	S->ntheta = (int)ntheta;
	S->nz = (int)nz;
	size_t nbins = (size_t)S->ntheta * S->nz;
	S->best = xmalloc(nbins * sizeof *S->best);
	S->best_rho = xmalloc(nbins * sizeof *S->best_rho);
	S->n = S->cap = 0;
	surface_update(e);
	return 0;
}

/* The bins a sphere overlaps as seen from the axis, and its outer distance. */
typedef struct {
	int t0, t1, z0, z1;
	double out;
} bin_range;

static bin_range sphere_bins(const engine *e, size_t i, double lo, double dz, double dth)
{
	const surface *S = &e->bc.surf;
	double rho[3], z = frame(e, e->p.x + 3 * i, rho), r = e->p.r[i];
	double len = v3_norm(rho), th = atan2(v3_dot(rho, e->frame.e2), v3_dot(rho, e->frame.e1));
	double half = len > r ? asin(r / len) : DEM_PI;
	bin_range b = {(int)floor((th - half + DEM_PI) / dth),
	               (int)floor((th + half + DEM_PI) / dth), (int)floor((z - r - lo) / dz),
	               (int)floor((z + r - lo) / dz), len + r};
	if (b.t1 - b.t0 >= S->ntheta)
		b.t0 = 0, b.t1 = S->ntheta - 1;
	b.z0 = b.z0 < 0 ? 0 : b.z0;
	b.z1 = b.z1 >= S->nz ? S->nz - 1 : b.z1;
	return b;
}

static size_t bin_index(const surface *S, int iz, int t)
{
	return (size_t)iz * S->ntheta + (size_t)(((t % S->ntheta) + S->ntheta) % S->ntheta);
}

void surface_room(surface *S, size_t cap)
{
	S->cap = cap;
	S->idx = xrealloc(S->idx, (cap + 1) * sizeof *S->idx);
	S->area = xrealloc(S->area, (cap + 1) * sizeof *S->area);
}

/* The outermost sphere of each bin among the particles [a, b) into best
 * and rho (nbins each, started at -1 and -inf): the first in index order
 * among equals. */
static void bin_outermost(const engine *e, size_t a, size_t b, double lo, double dz, double dth,
                          int32_t *best, double *rho)
{
	const surface *S = &e->bc.surf;
	for (size_t i = a; i < b; i++) {
		bin_range br = sphere_bins(e, i, lo, dz, dth);
		for (int iz = br.z0; iz <= br.z1; iz++)
			for (int t = br.t0; t <= br.t1; t++) {
				size_t k = bin_index(S, iz, t);
				if (br.out > rho[k]) {
					rho[k] = br.out;
					best[k] = (int32_t)i;
				}
			}
	}
}

/* The particles of [a, b) in the surface layer: reaching within their own
 * radius of the outermost point of a bin they overlap. Into list (grown as
 * needed, room *cap); returns their count. */
static size_t layer_of(const engine *e, size_t a, size_t b, double lo, double dz, double dth,
                       int32_t **list, size_t *cap)
{
	const surface *S = &e->bc.surf;
	size_t n = 0;
	for (size_t i = a; i < b; i++) {
		bin_range br = sphere_bins(e, i, lo, dz, dth);
		int in = 0;
		for (int iz = br.z0; iz <= br.z1 && !in; iz++)
			for (int t = br.t0; t <= br.t1 && !in; t++)
				in = br.out >= S->best_rho[bin_index(S, iz, t)] - e->p.r[i];
		if (in) {
			if (n == *cap) {
				*cap = 2 * *cap + 1024;
				*list = xrealloc(*list, *cap * sizeof **list);
			}
			(*list)[n++] = (int32_t)i;
		}
	}
	return n;
}

/* Each rank bins its own particles, whose state is current (ranks.h); the
 * bins' outermost spheres are then a maximum over the ranks (the lowest
 * index among equals, as on one rank), and the surface layer each rank's
 * list in rank order, which is index order: the same bins and list on
 * every rank, for any number of ranks. Within a rank the step's threads
 * share the particles in runs, combined in run order the same way: the
 * same bins and list for any number of threads. */
void surface_update(engine *e)
{
	particles *P = &e->p;
	surface *S = &e->bc.surf;
	size_t nbins = (size_t)S->ntheta * S->nz, p0, p1;
	int split = ranks_own(e, &p0, &p1);
	double lo, hi;
	extent(e, p0, p1, split, &lo, &hi);
	double dz = (hi - lo) / S->nz, dth = 2 * DEM_PI / S->ntheta;
	int team = e->team;
	int32_t *best = xmalloc((size_t)team * nbins * sizeof *best);
	double *rho = xmalloc((size_t)team * nbins * sizeof *rho);
	int32_t **lists = xcalloc((size_t)team, sizeof *lists);
	size_t *count = xcalloc((size_t)team, sizeof *count);
	for (size_t b = 0; b < (size_t)team * nbins; b++) {
		best[b] = -1;
		rho[b] = -INFINITY;
	}
#pragma omp parallel num_threads(team)
	{
		int t = omp_get_thread_num(), nt = omp_get_num_threads();
		size_t a = p0 + (p1 - p0) * (size_t)t / (size_t)nt,
		       b = p0 + (p1 - p0) * (size_t)(t + 1) / (size_t)nt;
		bin_outermost(e, a, b, lo, dz, dth, best + (size_t)t * nbins,
		              rho + (size_t)t * nbins);
#pragma omp barrier
#pragma omp master
		{
			for (size_t k = 0; k < nbins; k++) {
				S->best[k] = best[k];
				S->best_rho[k] = rho[k];
				for (int q = 1; q < nt; q++)
					if (rho[(size_t)q * nbins + k] > S->best_rho[k]) {
						S->best_rho[k] = rho[(size_t)q * nbins + k];
						S->best[k] = best[(size_t)q * nbins + k];
					}
			}
			if (split)
				par_maxloc(S->best_rho, S->best, nbins);
		}
#pragma omp barrier
		size_t room = 0;
		count[t] = layer_of(e, a, b, lo, dz, dth, &lists[t], &room);
	}
	free(best), free(rho);
	for (size_t i = p0; i < p1; i++)
		P->surf[i] = -1;
	size_t mine = 0;
	for (int t = 0; t < team; t++) {
		if (mine + count[t] > S->cap)
			surface_room(S, 2 * (mine + count[t]) + 1024);
		if (count[t])
			memcpy(S->idx + mine, lists[t], count[t] * sizeof *S->idx);
		mine += count[t];
		free(lists[t]);
	}
	free(lists), free(count);
	size_t cap = S->cap;
	S->n = split ? ranks_gather_list(&S->idx, &cap, mine) : mine;
	if (cap > S->cap) /* the other ranks' entries grew the list */
		surface_room(S, cap);
	for (size_t k = 0; k < S->n; k++) {
		S->area[k] = 0;
		if ((size_t)S->idx[k] >= p0 && (size_t)S->idx[k] < p1)
			P->surf[S->idx[k]] = (int32_t)k;
	}
	S->lateral_area = S->volume = 0;
	double rsum = 0;
	size_t used = 0;
	for (size_t b = 0; b < nbins; b++) {
		int32_t i = S->best[b];
		if (i < 0)
			continue;
		double a = S->best_rho[b] * dth * dz;
		/* i's place in the surface list, which holds it */
		S->area[first_not_below(S->idx, 0, S->n, (size_t)i)] += a;
		S->lateral_area += a;
		S->volume += 0.5 * S->best_rho[b] * a;
		rsum += S->best_rho[b];
		used++;
	}
	S->radius = used ? rsum / used : 0;
	S->updated = e->clock.step;
}

void surface_free(surface *s) { free(s->idx), free(s->area), free(s->best), free(s->best_rho); }

void gauge_init(engine *e)
{
	const particles *P = &e->p;
	gauge *G = &e->bc.gauge;
	size_t p0, p1;
	int split = ranks_own(e, &p0, &p1);
	double lo, hi;
	extent(e, p0, p1, split, &lo, &hi);
	double mid = 0.5 * (lo + hi), half = fmax(0.05 * (hi - lo), e->frame.r_mean);
	double outer = -INFINITY;
	for (size_t i = p0; i < p1; i++) {
		double rho[3], z = frame(e, P->x + 3 * i, rho);
		if (fabs(z - mid) <= half)
			outer = fmax(outer, v3_norm(rho) + P->r[i]);
	}
	if (split)
		par_max(&outer, 1);
	/* Each rank its own gauge particles. */
	G->idx = xmalloc((p1 - p0 + 1) * sizeof *G->idx);
	G->rho0 = xmalloc((p1 - p0 + 1) * sizeof *G->rho0);
	G->n = 0;
	xsum s[2]; /* outer radii, count */
	xsum_clear(&s[0]), xsum_clear(&s[1]);
	for (size_t i = p0; i < p1; i++) {
		double rho[3], z = frame(e, P->x + 3 * i, rho);
		double r = v3_norm(rho);
		if (fabs(z - mid) <= half && r + P->r[i] >= outer - 2 * e->frame.r_mean) {
			G->idx[G->n] = (int32_t)i;
			G->rho0[G->n++] = r;
			xsum_add(&s[0], r + P->r[i]);
			xsum_add(&s[1], 1);
		}
	}
	if (split)
		par_sum(s, 2);
	G->total = xsum_round(&s[1]);
	G->radius0 = G->total > 0 ? xsum_round(&s[0]) / G->total : 0;
	G->idx = xrealloc(G->idx, (G->n + 1) * sizeof *G->idx);
	G->rho0 = xrealloc(G->rho0, (G->n + 1) * sizeof *G->rho0);
}

double gauge_strain(const engine *e)
{
	const gauge *G = &e->bc.gauge;
	if (!(G->total > 0) || G->radius0 <= 0)
		return 0;
	/* Each rank its own gauge particles, summed exactly over the ranks. */
	xsum sum;
	xsum_clear(&sum);
	for (size_t k = 0; k < G->n; k++) {
		double rho[3];
		frame(e, e->p.x + 3 * (size_t)G->idx[k], rho);
		xsum_add(&sum, v3_norm(rho) - G->rho0[k]);
	}
	size_t p0, p1;
	if (ranks_own(e, &p0, &p1))
		par_sum(&sum, 1);
	return -xsum_round(&sum) / G->total / G->radius0;
}

void gauge_free(gauge *g) { free(g->idx), free(g->rho0); }
