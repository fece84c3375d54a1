/* The state at the start of a run: particles in Morton order (neighbours in
 * space sit near each other in memory, so the bond and gather loops stay in
 * cache), masses and inertias of solid spheres, the specimen frame, bonds
 * within the law's range, the law's packing constants (Eq. 22), the
 * neighbour lists, and the time step. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/morton.h"
#include "lib/vec3.h"
#include "solve/engine.h"

/* Morton (Z-order) permutation of the assembly's particles: their bounding
 * cube scaled to cells 0 to 2^21 - 1 a side (lib/morton.h). */
static int32_t *morton_order(const dem_assembly *a)
{
	double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	for (size_t i = 0; i < a->n; i++)
		for (int k = 0; k < 3; k++) {
			lo[k] = fmin(lo[k], a->x[3 * i + k]);
			hi[k] = fmax(hi[k], a->x[3 * i + k]);
		}
	double span = 0;
	for (int k = 0; k < 3; k++)
		span = fmax(span, hi[k] - lo[k]);
	double scale = span > 0 ? 2097151.0 / span : 0;
	uint64_t *key = xmalloc((a->n + 1) * sizeof *key);
	for (size_t i = 0; i < a->n; i++) {
		uint64_t c[3];
		for (int k = 0; k < 3; k++)
			c[k] = (uint64_t)((a->x[3 * i + k] - lo[k]) * scale);
		key[i] = morton_key(c);
	}
	size_t *order = xmalloc((a->n + 1) * sizeof *order);
	morton_sort(key, a->n, order);
	int32_t *perm = xmalloc((a->n + 1) * sizeof *perm);
	for (size_t i = 0; i < a->n; i++)
		perm[i] = (int32_t)order[i];
	free(key);
	free(order);
	return perm;
}

static int load_particles(engine *e, const dem_assembly *a)
{
	particles *P = &e->p;
	size_t n = a->n;
	P->n = n;
	P->orig = morton_order(a);
	P->x = xmalloc((3 * n + 1) * sizeof *P->x);
	P->v = xcalloc(3 * n + 1, sizeof *P->v);
	P->w = xcalloc(3 * n + 1, sizeof *P->w);
	P->x_ref = xmalloc((3 * n + 1) * sizeof *P->x_ref);
	P->r = xmalloc((n + 1) * sizeof *P->r);
	P->m = xmalloc((n + 1) * sizeof *P->m);
	P->inv_m = xmalloc((n + 1) * sizeof *P->inv_m);
	P->inv_i = xmalloc((n + 1) * sizeof *P->inv_i);
	P->omega2 = xcalloc(n + 1, sizeof *P->omega2);
	P->flag = xcalloc(n + 1, 1);
	P->surf = xmalloc((n + 1) * sizeof *P->surf);
	for (int k = 0; k < 2; k++) {
		P->pslot[k] = xmalloc((n + 1) * sizeof *P->pslot[k]);
		for (size_t i = 0; i < n; i++)
			P->pslot[k][i] = -1;
	}
	double rho = e->cs->mat.density, rsum = 0;
	for (size_t i = 0; i < n; i++) {
		int32_t o = P->orig[i];
		double r = a->r[o];
		const double *x = a->x + 3 * o;
		if (!(r > 0 && isfinite(r)) || !isfinite(x[0] + x[1] + x[2]))
			return err_set(
			    "particle %d: radius %g m at (%g, %g, %g) m: expected a finite "
			    "positive radius and position",
			    o, r, x[0], x[1], x[2]);
		memcpy(P->x + 3 * i, a->x + 3 * o, 3 * sizeof *P->x);
		P->r[i] = r;
		P->m[i] = rho * 4.0 / 3.0 * DEM_PI * r * r * r;
		P->inv_m[i] = 1 / P->m[i];
		P->inv_i[i] = 1 / (0.4 * P->m[i] * r * r);
		if (!(P->inv_m[i] > 0 && P->inv_i[i] > 0 && isfinite(P->inv_i[i])))
			return err_set(
			    "particle %d: mass %g kg from the density %g kg/m^3: expected a "
			    "finite positive mass and moment of inertia (check the "
			    "material's density)",
			    o, P->m[i], rho);
		P->surf[i] = -1;
		rsum += r;
		e->r_max = fmax(e->r_max, r);
	}
	e->r_mean = rsum / (double)n;
	return 0;
}

/* The loading axis (the case's, else the geometry's, else z) through the
 * geometry's centre. */
static void specimen_frame(engine *e, const dem_assembly *a)
{
	const double *ax = e->cs->axis;
	if (ax[0] == 0 && ax[1] == 0 && ax[2] == 0)
		ax = a->geom.axis;
	double l = v3_norm(ax);
	for (int k = 0; k < 3; k++) {
		e->axis[k] = l > 0 ? ax[k] / l : k == 2;
		e->center[k] = a->geom.center[k];
	}
}

/* Porosity and bonds per sphere for the law's setup (Eq. 22). */
static law_packing packing_of(const engine *e, const dem_assembly *a)
{
	double vs = 0;
	for (size_t i = 0; i < e->p.n; i++)
		vs += 4.0 / 3.0 * DEM_PI * e->p.r[i] * e->p.r[i] * e->p.r[i];
	double phi = a->report.solid_fraction > 0 ? a->report.solid_fraction
	             : a->geom.volume > 0         ? vs / a->geom.volume
	                                          : 0.64;
	return (law_packing){.porosity = 1 - phi,
	                     .coordination = 2.0 * (double)e->bonds.n / (double)e->p.n};
}

/* Each particle's share of the bound on ω² from its bonds (timestep.c). */
static void bond_bounds(engine *e)
{
	particles *P = &e->p;
	double xi = e->cs->mat.damping;
	for (size_t b = 0; b < e->bonds.n; b++) {
		const bond *bd = &e->bonds.rec[b];
		int32_t i = bd->i, j = bd->j;
		law_pair q = {
		    .ri = P->r[i], .rj = P->r[j], .mi = P->m[i], .mj = P->m[j], .d0 = bd->d0};
		law_const c;
		e->law->constants(e->lp, &q, &c);
		double ai = bd->d0 * P->r[i] / (P->r[i] + P->r[j]), aj = bd->d0 - ai;
		double w2 = pair_omega2(c.kn, c.ks, P->m[i], P->m[j], 1 / P->inv_i[i],
		                        1 / P->inv_i[j], ai, aj);
		P->omega2[i] += w2;
		P->omega2[j] += w2;
		double mij = P->m[i] * P->m[j] / (P->m[i] + P->m[j]);
		xi = fmax(xi, c.cn / (2 * sqrt(mij * c.kn)));
	}
	e->xi_max = xi;
}

static void geometry_sizes(engine *e, const dem_assembly *a)
{
	e->height0 = e->pl.z[1] - e->pl.z[0];
	const dem_geometry *g = &a->geom;
	if (g->volume > 0 && g->height > 0)
		e->area0 = g->volume / g->height;
	else
		e->area0 = DEM_PI * e->surf.radius * e->surf.radius;
}

static void scratch_alloc(engine *e)
{
	size_t n = e->p.n;
	e->nthreads = e->cs->threads > 0 ? e->cs->threads : omp_get_max_threads();
	/* Below about a thousand particles per thread, synchronisation costs more
	 * than it saves (results do not depend on the team size). */
	e->team = (int)(n / 1000) < e->nthreads ? (int)(n / 1000) : e->nthreads;
	e->team = e->team > 0 ? e->team : 1;
	e->pblock = xcalloc(nblocks(n) + 1, sizeof *e->pblock);
	e->bblock = xcalloc(nblocks(e->bonds.n) + 1, sizeof *e->bblock);
	e->thread_cracks = xcalloc((size_t)e->nthreads, sizeof *e->thread_cracks);
	e->scratch = xmalloc((n + 1) * sizeof *e->scratch);
}

/* Every stage's platen (or end-layer) speed moves the ends by less than a
 * hundredth of the mean radius per step: faster is an impact, not a test.
 * End layers are thinner than half the specimen. */
static int check_stages(const engine *e)
{
	for (int k = 0; k < e->cs->nstages; k++) {
		const stage *s = &e->cs->stages[k];
		if (s->axial == AXIAL_LAYERS && s->thickness >= 0.5 * e->height0)
			return err_set(
			    "loading stage %d: axial.thickness %g m: expected less than half "
			    "the specimen's height (%g m)",
			    k + 1, s->thickness, e->height0);
		double v = fabs(boundary_closing_speed(e, s));
		if (s->axial == AXIAL_NONE || s->axial == AXIAL_HOLD ||
		    !(v * e->dt >= 0.01 * e->r_mean))
			continue;
		return err_set("loading stage %d: the ends would move %g m per time step (%g m/s), "
		               "more than a hundredth of the mean sphere radius (%g m): expected a "
		               "quasi-static loading (lower its %s)",
		               k + 1, v * e->dt, v, e->r_mean,
		               s->axial == AXIAL_VELOCITY ? "velocity" : "rate");
	}
	return 0;
}

int engine_setup(engine *e, const dem_case *cs, const dem_assembly *a, int quiet)
{
	memset(e, 0, sizeof *e);
	e->cs = cs;
	e->law = cs->mat.law;
	e->lp = cs->mat.params;
	if (a->n == 0)
		return err_set("the assembly has no particles");
	if (load_particles(e, a))
		return -1;
	specimen_frame(e, a);
	e->skin = cs->skin > 0 ? cs->skin : 0.25 * e->r_mean;
	if (bonds_form(e))
		return -1;
	law_packing pk = packing_of(e, a);
	e->law->setup(e->lp, &pk);
	bonds_init_history(e);
	bond_bounds(e);
	platens_init(e);
	if (cs->surface_bin > 0 && cs->surface_bin < 0.2 * e->r_mean)
		return err_set("surface.bin %g m: expected at least a tenth of the mean sphere "
		               "diameter (%g m)",
		               cs->surface_bin, 2 * e->r_mean);
	surface_init(e);
	gauge_init(e);
	geometry_sizes(e, a);
	scratch_alloc(e);
	e->peak = e->stage_peak = -INFINITY;
	boundary_begin_stage(e);
	contacts_rebuild(e);
	size_t worst;
	e->dt_crit = timestep_critical(e, 1, &worst);
	if (cs->dt > 0 && cs->dt > e->dt_crit)
		return err_set("time step %g s above the stable limit %g s, set by particle %d "
		               "(radius %g m, %d bonds): lower time_step.dt or leave it out",
		               cs->dt, e->dt_crit, e->p.orig[worst], e->p.r[worst],
		               e->bonds.off[worst + 1] - e->bonds.off[worst]);
	if (!isfinite(e->dt_crit))
		return err_set("no bond or contact: the critical time step is undefined "
		               "(give time_step.dt)");
	if (!(e->dt_crit > 0))
		return err_set(
		    "the critical time step is 0 s, set by particle %d (radius %g m, mass "
		    "%g kg): the material's stiffness is out of range for its density",
		    e->p.orig[worst], e->p.r[worst], e->p.m[worst]);
	if (cs->dt > 0 && cs->dt < 1e-6 * e->dt_crit)
		return err_set("time step %g s below a millionth of the stable limit %g s: the run "
		               "would take a million times the steps it needs (raise time_step.dt "
		               "or leave it out)",
		               cs->dt, e->dt_crit);
	e->dt = cs->dt > 0 ? cs->dt : cs->safety * e->dt_crit;
	if (check_stages(e))
		return -1;
	for (size_t i = 0; i < e->p.n; i++) {
		double v = 1e-12 * e->p.r[i] / e->dt;
		e->ke_noise += 0.5 * e->p.m[i] * v * v;
	}
	if (!quiet)
		fprintf(
		    stderr,
		    "%s: %zu particles, %zu bonds (%.2f per particle, law %s); time step %.4g s "
		    "= %.3g x critical %.4g s (Eq. 11-15, set by particle %d)\n",
		    err_program_name(), e->p.n, e->bonds.n, pk.coordination, e->law->name, e->dt,
		    e->dt / e->dt_crit, e->dt_crit, e->p.orig[worst]);
	return 0;
}

void engine_free(engine *e)
{
	particles *P = &e->p;
	free(P->x), free(P->v), free(P->w), free(P->x_ref), free(P->r), free(P->m);
	free(P->inv_m), free(P->inv_i), free(P->omega2), free(P->flag), free(P->surf);
	free(P->orig), free(P->pslot[0]), free(P->pslot[1]);
	pairlist_free(&e->bonds);
	pairlist_free(&e->contacts);
	pairlist_free(&e->contacts_old);
	platens_free(&e->pl);
	cells_free(&e->grid);
	free(e->surf.idx), free(e->surf.area), free(e->surf.best), free(e->surf.best_rho);
	free(e->gg.idx), free(e->gg.rho0);
	free(e->pblock), free(e->bblock), free(e->cblock), free(e->scratch);
	for (int t = 0; t < e->nthreads; t++)
		free(e->thread_cracks[t].c), free(e->thread_cracks[t].bond);
	free(e->thread_cracks);
	free(e->cracks.c), free(e->cracks.bond);
	memset(e, 0, sizeof *e);
}
