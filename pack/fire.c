/* FIRE minimiser (see fire.h). With unit masses, one iteration is
 *
 *   P = F.v;  P > 0 for N_delay steps: dt <- min(f_inc dt, dt_max),
 *             alpha <- f_alpha alpha;
 *   P <= 0:   x <- x - dt v / 2, v <- 0, dt <- f_dec dt, alpha <- alpha_0;
 *   v <- v + dt F;  v <- (1 - alpha) v + alpha |v| F / |F|;  x <- x + dt v.
 *
 * Unit contact stiffness and unit mass make the time scale independent of
 * the sphere size: dt_max = 0.25 is stable for a dozen contacts per sphere.
 * The global sums P, |F|^2, |v|^2 are added in fixed blocks so that the
 * result does not depend on the number of threads. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "pack/fire.h"
#include "pack/par.h"

#define BLOCK 4096

enum { N_DELAY = 5 };
static const double F_INC = 1.1, F_DEC = 0.5, ALPHA0 = 0.1, F_ALPHA = 0.99;
static const double DT_START = 0.05, DT_MAX = 0.25, DT_MIN = 0.002;

/* Over fixed blocks of BLOCK components: f.v, or with kick, first v += dt f
 * and then |f|^2 and |v|^2. Blocks make the sums the same whatever the
 * number of threads. */
static void sums(double *v, const double *f, size_t n, double dt, int kick, double out[3])
{
	size_t nblock = (n + BLOCK - 1) / BLOCK;
	double part[3 * 64], *p = nblock <= 64 ? part : xmalloc(3 * nblock * sizeof *p);
#pragma omp parallel for schedule(static) if (n >= 3 * PAR_MIN)
	for (size_t blk = 0; blk < nblock; blk++) {
		double fv = 0, ff = 0, vv = 0;
		size_t end = (blk + 1) * BLOCK < n ? (blk + 1) * BLOCK : n;
		for (size_t k = blk * BLOCK; k < end; k++) {
			if (kick)
				v[k] += dt * f[k];
			fv += f[k] * v[k];
			ff += f[k] * f[k];
			vv += v[k] * v[k];
		}
		p[3 * blk] = fv;
		p[3 * blk + 1] = ff;
		p[3 * blk + 2] = vv;
	}
	out[0] = out[1] = out[2] = 0;
	for (size_t blk = 0; blk < nblock; blk++)
		for (int k = 0; k < 3; k++)
			out[k] += p[3 * blk + k];
	if (p != part)
		free(p);
}

void fire_start(fire_state *st, soft_system *s)
{
	memset(st, 0, sizeof *st);
	st->v = xcalloc(3 * s->nmobile + 1, sizeof *st->v);
	st->f = xcalloc(3 * s->nmobile + 1, sizeof *st->f);
	st->dt = DT_START;
	st->alpha = ALPHA0;
	soft_update(s, 0);
	soft_forces(s, st->f, &st->stats);
}

void fire_move(fire_state *st, soft_system *s)
{
	size_t n = 3 * s->nmobile;
	double *v = st->v, *f = st->f, *x = s->x, sm[3];
	sums(v, f, n, 0, 0, sm);
	if (sm[0] > 0) {
		if (++st->npos > N_DELAY) {
			st->dt = fmin(st->dt * F_INC, DT_MAX);
			st->alpha *= F_ALPHA;
		}
	} else {
		st->npos = 0;
		st->dt = fmax(st->dt * F_DEC, DT_MIN);
		st->alpha = ALPHA0;
		double back = 0.5 * st->dt;
#pragma omp parallel for schedule(static) if (n >= 3 * PAR_MIN)
		for (size_t k = 0; k < n; k++) {
			x[k] -= back * v[k];
			v[k] = 0;
		}
	}
	double dt = st->dt, alpha = st->alpha;
	sums(v, f, n, dt, 1, sm);
	double mix = sm[1] > 0 ? alpha * sqrt(sm[2] / sm[1]) : 0;
#pragma omp parallel for schedule(static) if (n >= 3 * PAR_MIN)
	for (size_t k = 0; k < n; k++) {
		v[k] = (1 - alpha) * v[k] + mix * f[k];
		x[k] += dt * v[k];
	}
	st->iter++;
}

void fire_forces(fire_state *st, soft_system *s)
{
	soft_update(s, 0);
	soft_forces(s, st->f, &st->stats);
}

void fire_step(fire_state *st, soft_system *s)
{
	fire_move(st, s);
	fire_forces(st, s);
}

void fire_end(fire_state *st)
{
	free(st->v);
	free(st->f);
	memset(st, 0, sizeof *st);
}

long fire_minimise(soft_system *s, long max_iter, double otol, double ftol, double *overlap)
{
	fire_state st;
	fire_start(&st, s);
	while (st.iter < max_iter && st.stats.overlap_max >= otol && st.stats.fmax >= ftol)
		fire_step(&st, s);
	long iter = st.iter;
	if (overlap)
		*overlap = st.stats.overlap_max;
	fire_end(&st);
	return iter;
}
