/* Jammed periodic cell by soft-sphere growth (see jam.h).
 *
 * Spheres start at random positions at the loose solid fraction 0.5.
 * FIRE relaxes them while every radius grows or shrinks each iteration
 * under pressure control (settle() below), first up to a high pressure
 * P_SQUEEZE, where the overlaps are of tens of percent and the spheres
 * rearrange into a denser arrangement than a gentle compression finds,
 * then down, halving the pressure, until the largest overlap is below the
 * tolerance: the released packing keeps most of the density the squeeze
 * bought (0.66 for radii uniform in [0.5, 1.5], where compressing at the
 * final pressure directly jams near 0.645). Growing radii in a fixed box
 * is the same as compressing the box; at the end the cell is scaled so
 * that the radii are exactly the sampled ones. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/rng.h"
#include "lib/vec3.h"
#include "pack/fire.h"
#include "pack/jam.h"
#include "pack/morton.h"
#include "pack/spheres.h"

static const double PHI_START = 0.50, P_SQUEEZE = 0.4, RATE = 1e-3;
static const long WINDOW = 50, SQUEEZE_ITER = 1500, RELEASE_ITER = 200, MAX_ITER = 60000;
static const double STALL = 1e-4;

/* Pressure-controlled growth: p = (sum over each sphere's contacts of the
 * overlap / smaller radius) / n, a dimensionless pressure; every iteration
 * the radii grow by the factor 1 + RATE clip((target - p) / target, -1, 1)
 * (shrink when p > target). Stops when the solid fraction changed by less
 * than STALL over WINDOW iterations, or after max_iter. */
static void settle(fire_state *st, soft_system *s, const double *r0, double *grow, double target,
                   long max_iter, progress *prog)
{
	long start = st->iter, mark = st->iter;
	double mark_grow = *grow;
	while (st->iter - start < max_iter) {
		fire_move(st, s);
		double p = st->stats.overlap_mean * st->stats.contacts / (double)s->n;
		*grow *= 1 + RATE * fmax(-1, fmin(1, (target - p) / target));
		for (size_t i = 0; i < s->n; i++)
			s->r[i] = r0[i] * *grow;
		fire_forces(st, s);
		if (prog) {
			char detail[64];
			snprintf(detail, sizeof detail, "periodic cell: solid fraction %.4f",
			         PHI_START * *grow * *grow * *grow);
			progress_update(prog, (double)st->iter, detail);
		}
		if (st->iter - mark >= WINDOW) {
			double dphi = 3 * PHI_START * fabs(*grow - mark_grow) / mark_grow;
			if (dphi < STALL)
				return;
			mark = st->iter;
			mark_grow = *grow;
		}
	}
}

/* n radii drawn from d (into r0 and c->r), a box of the given shape that
 * holds them at the solid fraction PHI_START, and uniform random centres in
 * it, laid along a Morton curve so that neighbours sit near in memory. */
static void random_cell(jam_cell *c, const psd *d, size_t n, const double shape[3], uint64_t seed,
                        double *r0)
{
	rng g;
	rng_seed_stream(&g, seed, 0);
	for (size_t i = 0; i < n; i++)
		r0[i] = psd_sample(d, &g);
	double vs = sphere_volume(r0, n);
	double scale = cbrt(vs / PHI_START / (shape[0] * shape[1] * shape[2]));
	for (int k = 0; k < 3; k++)
		c->box[k] = scale * shape[k];
	for (size_t i = 0; i < n; i++)
		for (int k = 0; k < 3; k++)
			c->x[3 * i + k] = c->box[k] * rng_uniform(&g);
	double zero[3] = {0, 0, 0}, *xs = xmalloc(3 * n * sizeof *xs + 1);
	size_t *order = xmalloc(n * sizeof *order + 1);
	morton_order(c->x, n, zero, c->box, order);
	for (size_t i = 0; i < n; i++)
		v3_copy(xs + 3 * i, c->x + 3 * order[i]);
	memcpy(c->x, xs, 3 * n * sizeof *xs);
	free(xs);
	free(order);
	memcpy(c->r, r0, n * sizeof *r0);
}

/* Squeeze the cell, then release the pressure until the overlaps fall
 * below otol (see the top of the file); returns the radius factor grown. */
static double squeeze(jam_cell *c, const double *r0, double otol, progress *prog)
{
	size_t n = c->n;
	double rmean = 0;
	for (size_t i = 0; i < n; i++)
		rmean += r0[i] / (double)n;
	soft_system s;
	soft_init(&s, n, n, c->x, c->r);
	memcpy(s.box, c->box, sizeof s.box);
	s.skin = 0.4 * rmean;
	s.half = 1; /* the cell is made on one thread (pack/packer.h) */
	fire_state st;
	fire_start(&st, &s);
	double grow = 1, p = P_SQUEEZE;
	settle(&st, &s, r0, &grow, p, SQUEEZE_ITER, prog);
	while (st.stats.overlap_max >= otol && st.iter < MAX_ITER) {
		p *= 0.5;
		settle(&st, &s, r0, &grow, p, RELEASE_ITER, prog);
	}
	c->iter = st.iter;
	fire_end(&st);
	soft_free(&s);
	return grow;
}

void jam_make(jam_cell *c, const psd *d, size_t n, const double shape[3], uint64_t seed,
              double otol, progress *prog)
{
	memset(c, 0, sizeof *c);
	c->n = n;
	c->x = xmalloc(3 * n * sizeof *c->x + 1);
	c->r = xmalloc(n * sizeof *c->r + 1);
	double *r0 = xmalloc(n * sizeof *r0 + 1);
	random_cell(c, d, n, shape, seed, r0);
	double grow = squeeze(c, r0, otol, prog);
	c->phi = PHI_START * grow * grow * grow;
	/* Back to the sampled radii: scale the whole cell. */
	double back = 1 / grow;
	for (size_t i = 0; i < 3 * n; i++)
		c->x[i] *= back;
	for (int k = 0; k < 3; k++)
		c->box[k] *= back;
	memcpy(c->r, r0, n * sizeof *r0);
	free(r0);
}

void jam_free(jam_cell *c)
{
	free(c->x);
	free(c->r);
	memset(c, 0, sizeof *c);
}
