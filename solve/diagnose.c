#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/diagnose.h"
#include "solve/par.h"
#include "solve/ranks.h"
#include "solve/timestep.h"
#include "solve/window.h"

/* Whether the force of contact b of L is finite. */
static int finite_contact(const pairlist *L, size_t b)
{
	double s = 0;
	for (size_t c = 0; c < 6; c++)
		s += L->f[6 * b + c];
	return isfinite(s);
}

static int by_index(const void *a, const void *b)
{
	int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
	return (x > y) - (x < y);
}

/* This rank's bonds whose force the step found not finite (a step keeps
 * no bond's force: it notes those, crack_buf.bad), in bond order: their
 * number, into *list. */
static size_t bad_bonds(const engine *e, int32_t **list)
{
	size_t n = 0;
	for (int t = 0; t < e->nthreads; t++)
		n += e->out.thread_cracks[t].nbad;
	int32_t *b = xmalloc((n + 1) * sizeof *b);
	n = 0;
	for (int t = 0; t < e->nthreads; t++) {
		const crack_buf *cb = &e->out.thread_cracks[t];
		for (size_t k = 0; k < cb->nbad; k++)
			b[n++] = cb->bad[k];
	}
	qsort(b, n, sizeof *b, by_index);
	*list = b;
	return n;
}

/* The pairs of every rank's list L (the bonds, or the contacts of its own
 * particles i) whose force is not finite, in the order of one process's
 * list (rank order), their ends the indices of the whole specimen: their
 * number, and in *bad their ends, on every rank. Few: the state is checked
 * every step. Collective. */
static size_t bad_pairs(const engine *e, const pairlist *L, int32_t **bad)
{
	size_t b0 = 0, b1 = L->n;
	if (L == &e->pairs.contacts && e->ranks.size > 1) {
		b0 = e->scratch.cfirst[e->ranks.blk0];
		b1 = e->scratch.cfirst[e->ranks.blk1];
	}
	int32_t *list = NULL;
	size_t nlist = 0;
	if (L == &e->pairs.bonds) {
		nlist = bad_bonds(e, &list);
	} else {
		for (size_t b = b0; b < b1; b++)
			nlist += !finite_contact(L, b);
		list = xmalloc((nlist + 1) * sizeof *list); /* room for the few, not every pair */
		nlist = 0;
		for (size_t b = b0; b < b1; b++)
			if (!finite_contact(L, b))
				list[nlist++] = (int32_t)b;
	}
	size_t cap = 2 * nlist, n = 0;
	int32_t *ends = xmalloc((cap + 1) * sizeof *ends);
	for (size_t k = 0; k < nlist; k++) {
		const pair_rec *r = &L->rec[list[k]];
		ends[n++] = (int32_t)particle_global(&e->p, (size_t)r->i);
		ends[n++] = (int32_t)particle_global(&e->p, (size_t)r->j);
	}
	free(list);
	*bad = ends;
	return ranks_gather_list(bad, &cap, n) / 2;
}

/* Of the n pairs (ends) with a non-finite force, the particle in most of
 * them (the lowest index of equals), where the trouble started: its index
 * (*who), how many (*count), and the first of them (its index in bad). */
static size_t worst_pair(const int32_t *bad, size_t n, size_t *who, int *count)
{
	int32_t *ends = xmalloc((2 * n + 1) * sizeof *ends);
	memcpy(ends, bad, 2 * n * sizeof *ends);
	qsort(ends, 2 * n, sizeof *ends, by_index);
	size_t best = 0, most = 0;
	for (size_t k = 0, m; k < 2 * n; k += m) {
		for (m = 1; k + m < 2 * n && ends[k + m] == ends[k]; m++)
			;
		if (m > most) {
			most = m;
			best = (size_t)ends[k];
		}
	}
	free(ends);
	*who = best;
	*count = (int)most;
	size_t b = 0;
	while ((size_t)bad[2 * b] != best && (size_t)bad[2 * b + 1] != best)
		b++;
	return b;
}

void diagnose_nan(const engine *e, size_t i, char *msg, size_t n)
{
	/* Every rank finds the same particle from the pairs the ranks share,
	 * and asks its rank for it; rank 0's message is the run's. */
	const char *what = "bond", *law = e->law->name;
	int32_t *bad;
	size_t nbad = bad_pairs(e, &e->pairs.bonds, &bad);
	if (!nbad) {
		free(bad);
		what = "contact";
		law = "contact";
		nbad = bad_pairs(e, &e->pairs.contacts, &bad);
	}
	double row[PARTICLE_ROW];
	if (!nbad) {
		free(bad);
		ranks_particle(e, i, row);
		snprintf(
		    msg, n,
		    "stopped: non-finite state at step %" PRId64 " (t = %g s): particle %d (radius "
		    "%g m): its forces are finite, so its motion diverged (time step too large?)",
		    e->clock.step - 1, e->clock.t - e->clock.dt, (int)row[PARTICLE_ORIG],
		    row[PARTICLE_R]);
		return;
	}
	size_t who;
	int count;
	size_t b = worst_pair(bad, nbad, &who, &count);
	size_t other = (size_t)bad[2 * b + ((size_t)bad[2 * b] == who)];
	free(bad);
	double orow[PARTICLE_ROW];
	ranks_particle(e, who, row);
	ranks_particle(e, other, orow);
	int32_t p = (int32_t)row[PARTICLE_ORIG], q = (int32_t)orow[PARTICLE_ORIG];
	snprintf(msg, n,
	         "stopped: non-finite state at step %" PRId64
	         " (t = %g s): particle %d (radius %g m): "
	         "%d of its %ss have non-finite forces, first %s %d-%d (law %s)",
	         e->clock.step - 1, e->clock.t - e->clock.dt, p, row[PARTICLE_R], count, what, what,
	         p < q ? p : q, p < q ? q : p, law);
}

/* Bound on ω of particle i from its bonds times the time step (2 is the
 * stability limit). Collective. */
static double omega_dt(const engine *e, size_t i)
{
	int count;
	return sqrt(timestep_bond_omega2(e, i, &count)) * e->clock.dt;
}

/* m v² of particle i at t + dt/2, with m = 1 unless `mass`. */
static double speed2(const particles *P, size_t i, int mass)
{
	const double *v = P->v + 3 * i;
	return (mass ? P->m[i] : 1) * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* The particle with the largest speed2 of all (the first of equals, as
 * one scan finds it; each rank scans its own), and that value in *top.
 * Collective. */
static size_t fastest(const engine *e, int mass, double *top)
{
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	double v[1] = {-1};
	int32_t at[1] = {(int32_t)p0};
	for (size_t i = p0; i < p1; i++) {
		double k = speed2(&e->p, i, mass);
		if (k > v[0]) {
			v[0] = k;
			at[0] = (int32_t)i;
		}
	}
	par_maxloc(v, at, 1);
	*top = v[0];
	return (size_t)at[0];
}

int diagnose_speed(engine *e, char *msg, size_t n)
{
	double dt = e->clock.dt, limit = 0.5 * e->pairs.skin;
	if (!(sqrt(e->sums.particles.v2max) * dt > limit))
		return 0;
	double v2, info[PARTICLE_ROW];
	size_t i = fastest(e, 0, &v2);
	ranks_particle(e, i, info);
	double odt = omega_dt(e, i);
	snprintf(msg, n,
	         "stopped: particle %d moved %g m in one step (speed %g m/s) at step %" PRId64
	         ", more than half the Verlet skin (%g m): contacts would pass unseen; the "
	         "integration is unstable, or the particle was thrown out by an overlap "
	         "(bonds give omega dt = %.3g, stable below 2)",
	         (int)info[PARTICLE_ORIG], sqrt(v2) * dt, sqrt(v2), e->clock.step - 1,
	         e->pairs.skin, odt);
	return 1;
}

int diagnose_runaway(engine *e, char *msg, size_t n)
{
	/* The shadow energy v- · v+ turns negative in a diverging oscillation:
	 * use the kinetic energy at t + dt/2. Below energy.noise, motion is the
	 * rounding of forces that balance (a specimen held at rest), which a
	 * divergence leaves behind within a few dozen steps. */
	double input = e->energy.initial + fabs(e->energy.work), ke = e->sums.particles.ke_new;
	if (!(ke > 2 * input + e->energy.noise))
		return 0;
	double top, info[PARTICLE_ROW];
	size_t worst = fastest(e, 1, &top);
	ranks_particle(e, worst, info);
	double odt = omega_dt(e, worst);
	snprintf(msg, n,
	         "stopped: kinetic energy %g J exceeds twice the energy put in (%g J) at step "
	         "%" PRId64 ": the integration is unstable; fastest particle %d (speed %g m/s, "
	         "bonds give omega dt = %.3g, stable below 2)",
	         ke, input, e->clock.step - 1, (int)info[PARTICLE_ORIG],
	         sqrt(top / info[PARTICLE_M]), odt);
	return 1;
}

int diagnose_timestep(engine *e, char *msg, size_t n)
{
	size_t worst, p0, p1;
	double crit = timestep_critical(e, 1, &worst);
	if (e->clock.dt <= crit)
		return 0;
	double info[PARTICLE_ROW];
	ranks_particle(e, worst, info);
	/* The contacts of a particle are on its rank's list (ranks.h). */
	ranks_own(e, &p0, &p1);
	int nc = worst >= p0 && worst < p1 ? pairlist_count(&e->pairs.contacts, worst) : 0, nb;
	par_max_int(&nc, 1);
	timestep_bond_omega2(e, worst, &nb);
	snprintf(msg, n,
	         "stopped: time step %g s above the stable limit %g s at step %" PRId64
	         ": particle %d has %d bonds and %d contacts (lower time_step.safety)",
	         e->clock.dt, crit, e->clock.step, (int)info[PARTICLE_ORIG], nb, nc);
	return 1;
}
