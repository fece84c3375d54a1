/* The state at the start of a run: particles in Morton order (order.h),
 * masses and inertias of solid spheres, the specimen frame, bonds
 * within the law's range, the law's packing constants (Eq. 22), the
 * neighbour lists, and the time step. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "lib/err.h"
#include "lib/vec3.h"
#include "solve/blocks.h"
#include "solve/bonds.h"
#include "solve/boundary.h"
#include "solve/cells.h"
#include "solve/contacts.h"
#include "solve/engine.h"
#include "solve/order.h"
#include "solve/pairlist.h"
#include "solve/par.h"
#include "solve/plan.h"
#include "solve/platens.h"
#include "solve/ranks.h"
#include "solve/surface.h"
#include "solve/timers.h"
#include "solve/timestep.h"
#include "solve/window.h"

/* The exact sum of the values v[i] of this rank's particles, over the
 * ranks once the particles are split (ranks_own): the same bits for any
 * split (lib/xsum.h). */
static double own_sum(const engine *e, double (*v)(const engine *, size_t))
{
	size_t p0, p1;
	int split = ranks_own(e, &p0, &p1);
	xsum s;
	xsum_clear(&s);
	for (size_t i = p0; i < p1; i++)
		xsum_add(&s, v(e, i));
	if (split)
		par_sum(&s, 1);
	return xsum_round(&s);
}

static double radius(const engine *e, size_t i) { return e->p.r[i]; }

/* The particles in Morton order walked within cells (order.h: neighbours
 * in space sit near each other in memory, and a bond's far end comes for
 * the first time in the order of memory, so the bond and gather loops stay
 * in cache), with their masses. With several ranks each holds its share of
 * the order until they are split by their bonds (ranks_split), or, whole,
 * every particle. */
static int load_particles(engine *e, const dem_assembly *a, int whole)
{
	particles *P = &e->p;
	rank_split *R = &e->ranks;
	size_t n = a->n;
	order_range o;
	order_morton(a, e->plain_order, e->law->bond_range(e->lp), &o);
	int ranks = par_size();
	if (ranks > 1 && !whole) {
		R->size = ranks;
		R->rank = par_rank();
		R->pfirst = xmalloc(((size_t)ranks + 1) * sizeof *R->pfirst);
		for (int q = 0; q <= ranks; q++)
			R->pfirst[q] = order_share(n, q, ranks);
		R->p0 = o.first;
		R->p1 = o.first + o.n;
		particles_alloc_own(P, n, R->p0, R->p1);
		memcpy(P->orig + R->p0, o.orig, o.n * sizeof *o.orig);
		memcpy(P->x + 3 * R->p0, o.x, 3 * o.n * sizeof *o.x);
		memcpy(P->r + R->p0, o.r, o.n * sizeof *o.r);
	} else {
		particles_alloc(P, n, 0, n);
		P->own1 = n;
		ranks_allgather_rows(o.orig, o.n, sizeof *o.orig, P->orig);
		ranks_allgather_rows(o.x, o.n, 3 * sizeof *o.x, P->x);
		ranks_allgather_rows(o.r, o.n, sizeof *o.r, P->r);
	}
	order_free(&o);
	double rho = e->cs->mat.density;
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	for (size_t i = p0; i < p1; i++) {
		int32_t orig = P->orig[i];
		double r = P->r[i];
		const double *x = P->x + 3 * i;
		if (!(r > 0 && isfinite(r)) || !isfinite(x[0] + x[1] + x[2]))
			return err_set(
			    "particle %d: radius %g m at (%g, %g, %g) m: expected a finite "
			    "positive radius and position",
			    orig, r, x[0], x[1], x[2]);
		P->m[i] = particle_mass(rho, r);
		double inv_m = particle_inv_m(P, i), inv_i = particle_inv_i(P, i);
		if (!(inv_m > 0 && inv_i > 0 && isfinite(inv_i)))
			return err_set(
			    "particle %d: mass %g kg from the density %g kg/m^3: expected a "
			    "finite positive mass and moment of inertia (check the "
			    "material's density)",
			    orig, P->m[i], rho);
		e->frame.r_max = fmax(e->frame.r_max, r);
	}
	par_max(&e->frame.r_max, 1);
	e->frame.r_mean = own_sum(e, radius) / (double)n;
	return 0;
}

/* The particles fill a compact specimen: cells of a contact's reach would
 * not be fewer than the particles by far (one particle thrown far away
 * would make every neighbour search scan the whole specimen). */
static int check_compact(const engine *e)
{
	const particles *P = &e->p;
	size_t p0, p1;
	int split = ranks_own(e, &p0, &p1);
	double m[6] = {-INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY, -INFINITY};
	xsum mid[3];
	for (int k = 0; k < 3; k++)
		xsum_clear(&mid[k]);
	for (size_t i = p0; i < p1; i++)
		for (int k = 0; k < 3; k++) {
			m[k] = fmax(m[k], -P->x[3 * i + k]); /* -lo */
			m[3 + k] = fmax(m[3 + k], P->x[3 * i + k]);
			xsum_add(&mid[k], P->x[3 * i + k]);
		}
	if (split)
		par_max(m, 6);
	double lo[3] = {-m[0], -m[1], -m[2]}, hi[3] = {m[3], m[4], m[5]};
	double reach = 2 * e->frame.r_max + e->pairs.skin;
	if (cells_size(lo, hi, P->n, reach) == reach)
		return 0;
	if (split)
		par_sum(mid, 3);
	double c[3];
	for (int k = 0; k < 3; k++)
		c[k] = xsum_round(&mid[k]) / (double)P->n;
	/* The farthest from their centre, the first of equals. */
	double d2max = -1;
	int32_t far = 0;
	for (size_t i = p0; i < p1; i++) {
		double d[3];
		v3_sub(d, P->x + 3 * i, c);
		if (v3_dot(d, d) > d2max)
			d2max = v3_dot(d, d), far = (int32_t)i;
	}
	if (split)
		par_maxloc(&d2max, &far, 1);
	double row[PARTICLE_ROW];
	ranks_particle(e, (size_t)far, row);
	return err_set("the particles span %g x %g x %g m, too sparse for spheres of radius up "
	               "to %g m: particle %d at (%g, %g, %g) m lies %g m from their centre: "
	               "expected a packed specimen (check the assembly's positions)",
	               hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], e->frame.r_max,
	               (int)row[PARTICLE_ORIG], row[0], row[1], row[2], sqrt(d2max));
}

/* The loading axis (the case's, else the geometry's, else z) through the
 * geometry's centre. */
static void specimen_frame(engine *e, const dem_assembly *a)
{
	const double *ax = e->cs->axis;
	if (ax[0] == 0 && ax[1] == 0 && ax[2] == 0)
		ax = a->geom.axis;
	if (v3_unit(e->frame.axis, ax))
		v3_copy(e->frame.axis, (double[3]){0, 0, 1});
	v3_copy(e->frame.center, a->geom.center);
}

static double volume(const engine *e, size_t i)
{
	double r = e->p.r[i];
	return 4.0 / 3.0 * DEM_PI * r * r * r;
}

/* Porosity and bonds per sphere for the law's setup (Eq. 22). */
static law_packing packing_of(const engine *e, const dem_assembly *a)
{
	double vs = own_sum(e, volume);
	double phi = a->report.solid_fraction > 0 ? a->report.solid_fraction
	             : a->geom.volume > 0         ? vs / a->geom.volume
	                                          : 0.64;
	return (law_packing){.porosity = 1 - phi,
	                     .coordination = 2.0 * (double)e->pairs.nbonds / (double)e->p.n};
}

/* The kinetic energy of particle i moving 1e-12 of its radius per step. */
static double noise(const engine *e, size_t i)
{
	double v = 1e-12 * e->p.r[i] / e->clock.dt;
	return 0.5 * e->p.m[i] * v * v;
}

static void geometry_sizes(engine *e, const dem_assembly *a)
{
	e->frame.height0 = e->bc.pl.z[1] - e->bc.pl.z[0];
	const dem_geometry *g = &a->geom;
	if (g->volume > 0 && g->height > 0)
		e->frame.area0 = g->volume / g->height;
	else
		e->frame.area0 = DEM_PI * e->bc.surf.radius * e->bc.surf.radius;
}

static void scratch_alloc(engine *e, int threads)
{
	size_t n = e->p.n;
	threads = threads > 0 ? threads : e->cs->threads;
	e->nthreads = threads > 0 ? threads : omp_get_max_threads();
	/* Below about a thousand particles per thread, synchronisation costs more
	 * than it saves (results do not depend on the team size). */
	e->team = (int)(n / 1000) < e->nthreads ? (int)(n / 1000) : e->nthreads;
	e->team = e->team > 0 ? e->team : 1;
	e->scratch.pblock = xcalloc(nblocks(n) + 1, sizeof *e->scratch.pblock);
	e->scratch.bblock = xcalloc(nblocks(n) + 1, sizeof *e->scratch.bblock);
	e->scratch.cblock = xcalloc(nblocks(n) + 1, sizeof *e->scratch.cblock);
	e->scratch.cfirst = xcalloc(nblocks(n) + 1, sizeof *e->scratch.cfirst);
	e->scratch.parts = xcalloc((size_t)e->nthreads, sizeof *e->scratch.parts);
	e->out.thread_cracks = xcalloc((size_t)e->nthreads, sizeof *e->out.thread_cracks);
}

void engine_timestep_set(engine *e) { e->energy.noise = own_sum(e, noise); }

static int setup_done(engine *e)
{
	phase_stop(&e->tm, TM_SETUP);
#ifdef __GLIBC__
	/* Setup's buffers, freed, back to the system rather than kept in the
	 * heap for the rest of the run (tens of MB at 10^6 particles). */
	malloc_trim(0);
#endif
	return 0;
}

int engine_setup(engine *e, const dem_case *cs, const dem_assembly *a, const engine_opts *o)
{
	memset(e, 0, sizeof *e);
	phase_start(&e->tm, TM_SETUP);
	if (bonds_prefetch_setup(e))
		return -1;
	e->cs = cs;
	e->law = cs->mat.law;
	e->lp = e->law->copy(cs->mat.params);
	e->plain_order = o->plain_order;
	const char *one = getenv("DEM_TEST_ONE_BY_ONE");
	e->one_by_one = one && strcmp(one, "1") == 0;
	if (a->n == 0)
		return err_set("the assembly has no particles");
	if (load_particles(e, a, o->whole))
		return -1;
	specimen_frame(e, a);
	e->pairs.skin = cs->skin > 0 ? cs->skin : 0.25 * e->frame.r_mean;
	/* The lists hold the pairs within 2 r + skin: a skin of many radii
	 * (a length meant in mm) makes them grow as its cube. */
	if (cs->skin > 4 * e->frame.r_mean)
		return err_set("neighbours.skin %g m: expected at most two mean sphere diameters "
		               "(%g m; the default is a quarter of the mean radius, %g m): lengths "
		               "are in m",
		               cs->skin, 4 * e->frame.r_mean, 0.25 * e->frame.r_mean);
	if (check_compact(e))
		return -1;
	if (cs->surface_bin > 0 && cs->surface_bin < 0.2 * e->frame.r_mean)
		return err_set("surface.bin %g m: expected at least a tenth of the mean sphere "
		               "diameter (%g m)",
		               cs->surface_bin, 2 * e->frame.r_mean);
	if (bonds_form(e))
		return -1;
	scratch_alloc(e, o->threads);
	/* Every rank splits the particles alike: into shares for the largest
	 * team of any rank, times the ranks (ranks.h). From here on each rank
	 * computes from its own particles, combined over the ranks. */
	double team = e->team;
	par_max(&team, 1);
	bonds_split(e, (int)team * par_size());
	if (e->pairs.split.n < par_size())
		return err_set("%d ranks for %zu particles: a rank takes whole blocks of %d "
		               "particles, so this specimen runs on at most %d rank%s",
		               par_size(), e->p.n, BLOCK, e->pairs.split.n,
		               e->pairs.split.n > 1 ? "s" : "");
	ranks_split(e);
	if (!o->whole)
		window_start(e);
	law_packing pk = packing_of(e, a);
	e->law->setup(e->lp, &pk);
	platens_init(e);
	if (surface_init(e))
		return -1;
	gauge_init(e);
	geometry_sizes(e, a);
	bonds_init_history(e);
	e->prog.peak = e->prog.stage_peak = -INFINITY;
	boundary_begin_stage(e);
	if (o->restart)
		return setup_done(e);
	contacts_rebuild(e);
	size_t worst;
	e->clock.dt_crit = timestep_critical(e, 1, &worst);
	double w[PARTICLE_ROW]; /* that particle, from its rank */
	ranks_particle(e, worst, w);
	int w_orig = (int)w[PARTICLE_ORIG];
	if (cs->dt > 0 && cs->dt > e->clock.dt_crit) {
		int nb;
		timestep_bond_omega2(e, worst, &nb);
		return err_set("time step %g s above the stable limit %g s, set by particle %d "
		               "(radius %g m, %d bonds): lower time_step.dt or leave it out",
		               cs->dt, e->clock.dt_crit, w_orig, w[PARTICLE_R], nb);
	}
	if (!isfinite(e->clock.dt_crit) && !(cs->dt > 0))
		return err_set("no bond or contact: the critical time step is undefined "
		               "(give time_step.dt)");
	if (!(e->clock.dt_crit > 0))
		return err_set(
		    "the critical time step is 0 s, set by particle %d (radius %g m, mass "
		    "%g kg): the material's stiffness is out of range for its density",
		    w_orig, w[PARTICLE_R], w[PARTICLE_M]);
	if (cs->dt > 0 && isfinite(e->clock.dt_crit) && cs->dt < 1e-6 * e->clock.dt_crit)
		return err_set("time step %g s below a millionth of the stable limit %g s: the run "
		               "would take a million times the steps it needs (raise time_step.dt "
		               "or leave it out)",
		               cs->dt, e->clock.dt_crit);
	e->clock.dt = cs->dt > 0 ? cs->dt : cs->safety * e->clock.dt_crit;
	if (plan_check(e, o->quiet))
		return -1;
	engine_timestep_set(e);
	setup_done(e);
	if (!o->quiet)
		fprintf(
		    stderr,
		    "%s: %zu particles, %zu bonds (%.2f per particle, law %s); time step %.4g s "
		    "= %.3g x critical %.4g s (Eq. 11-15, set by particle %d)\n",
		    err_program_name(), e->p.n, e->pairs.nbonds, pk.coordination, e->law->name,
		    e->clock.dt, e->clock.dt / e->clock.dt_crit, e->clock.dt_crit, w_orig);
	if (!o->quiet && e->team < e->nthreads)
		fprintf(
		    stderr,
		    "%s: on %d thread(s), not %d: a thread takes at least about 1 000 particles "
		    "(the results are the same on any number)\n",
		    err_program_name(), e->team, e->nthreads);
	return 0;
}

void engine_free(engine *e)
{
	particles *P = &e->p;
	particles_free(P);
	free(P->x_ref), free(P->fixed);
	pairlist_free(&e->pairs.bonds);
	bonds_search_free(&e->pairs.formed);
	pairlist_free(&e->pairs.contacts);
	pairlist_free(&e->pairs.contacts_old);
	platens_free(&e->bc.pl);
	cells_free(&e->pairs.grid);
	surface_free(&e->bc.surf);
	gauge_free(&e->bc.gauge);
	free(e->scratch.pblock), free(e->scratch.bblock), free(e->scratch.cblock),
	    free(e->scratch.cfirst), free(e->scratch.parts), free(e->scratch.acc);
	bonds_split_free(&e->pairs.split);
	share_balance_free(&e->pairs.balance);
	ranks_free(&e->ranks);
	for (int t = 0; t < e->nthreads; t++)
		free(e->out.thread_cracks[t].c), free(e->out.thread_cracks[t].bond),
		    free(e->out.thread_cracks[t].bad);
	free(e->out.thread_cracks);
	free(e->out.cracks.c), free(e->out.cracks.bond);
	free(e->out.cracks.run_at), free(e->out.cracks.run_n), free(e->out.cracks.held);
	if (e->lp)
		e->law->free(e->lp);
	memset(e, 0, sizeof *e);
}
