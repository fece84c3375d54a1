/* Forces of the soft-sphere system (soft.h gives the energy they derive
 * from): over the full list, by fixed blocks of mobile spheres on any
 * number of threads, or over a half list on one thread; the statistics are
 * summed by the same blocks, so results do not depend on the threads. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/vec3.h"
#include "pack/par.h"
#include "pack/soft.h"
#include "pack/soft_walls.h"

/* soft_forces() over a half list: each pair once, its force added to
 * both spheres, in list order on one thread (so, again, the same result
 * every time). The statistics count each touching pair from both sides,
 * as the full list does. */
static void forces_half(soft_system *s, double *f, soft_stats *out)
{
	size_t n = s->n;
	double worst = 0, fmx = 0, sum = 0, count = 0;
	memset(f, 0, 3 * n * sizeof *f);
	for (size_t i = 0; i < n; i++) {
		const double *xi = s->x + 3 * i;
		double ri = s->r[i], fi[3] = {0, 0, 0};
		for (size_t q = s->nb_start[i]; q < s->nb_start[i + 1]; q++) {
			size_t j = (size_t)s->nb[q];
			const double *xj = s->x + 3 * j, *sh = s->shift[s->nb_shift[q]];
			double d[3] = {xj[0] - xi[0] + sh[0], xj[1] - xi[1] + sh[1],
			               xj[2] - xi[2] + sh[2]};
			double dist = sqrt(v3_dot(d, d)), rj = s->r[j], delta = ri + rj - dist,
			       touch = delta > 0;
			double rmin = ri < rj ? ri : rj, inv = touch / (dist * rmin),
			       c = delta * rmin * inv;
			v3_axpy(fi, d, -c);
			v3_axpy(f + 3 * j, d, c);
			double rel = delta * dist * inv;
			worst = rel > worst ? rel : worst;
			sum += 2 * rel;
			count += 2 * touch;
		}
		v3_add(f + 3 * i, f + 3 * i, fi);
	}
	for (size_t i = 0; i < n; i++) {
		double fr = sqrt(v3_dot(f + 3 * i, f + 3 * i)) / s->r[i];
		fmx = fr > fmx ? fr : fmx;
	}
	out->overlap_max = worst;
	out->overlap_mean = count > 0 ? sum / count : 0;
	out->contacts = count;
	out->fmax = fmx;
}

/* The boundary's push on sphere i (radius ri) if it touches the boundary:
 * away from its closest boundary point, added to fi, its relative overlap
 * to the sphere's largest (wi) and to the sums. */
static inline void wall_force(const soft_system *s, size_t i, double ri, double fi[3], double *wi,
                              double *sum, double *count)
{
	if (!s->wall_count[i])
		return;
	double q[3] = {0, 0, 0}, dmin = soft_wall_contact(s, i, q);
	if (!(dmin < ri && dmin > 0))
		return;
	double delta = ri - dmin, d[3];
	v3_sub(d, s->x + 3 * i, q);
	v3_axpy(fi, d, delta / dmin);
	*wi = delta / ri > *wi ? delta / ri : *wi;
	*sum += delta / ri;
	*count += 1;
}

/* Forces on the mobile spheres [first, end) over the full list, into f;
 * their largest relative overlap and force per radius raise *worst and
 * *fmx, and part[0], part[1] take the block's sums of relative overlaps
 * and of contacts. Positions and radii are read side by side from xr, one
 * cache line per neighbour, as soft_update() laid them out. */
static void forces_block(soft_system *s, double *f, size_t first, size_t end, double *worst,
                         double *fmx, double part[2])
{
	const double *xr = s->xr;
	double sum = 0, count = 0;
	for (size_t i = first; i < end; i++) {
		const double *pi = xr + 4 * i;
		double fi[3] = {0, 0, 0}, wi = 0, ri = pi[3];
		/* Without branches (about half the listed pairs touch, at
		 * random): a pair apart adds zeros, exactly. The image shift of
		 * code 13 is zero. */
		for (size_t q = s->nb_start[i]; q < s->nb_start[i + 1]; q++) {
			const double *pj = xr + 4 * (size_t)s->nb[q],
			             *sh = s->shift[s->nb_shift[q]];
			double d[3] = {pj[0] - pi[0] + sh[0], pj[1] - pi[1] + sh[1],
			               pj[2] - pi[2] + sh[2]};
			double dist = sqrt(v3_dot(d, d)), rs = ri + pj[3];
			double delta = rs - dist, touch = delta > 0;
			/* One division for both delta/dist and delta/min(r). */
			double rmin = ri < pj[3] ? ri : pj[3], inv = touch / (dist * rmin);
			v3_axpy(fi, d, -delta * rmin * inv);
			double rel = delta * dist * inv;
			wi = rel > wi ? rel : wi;
			sum += rel;
			count += touch;
		}
		wall_force(s, i, ri, fi, &wi, &sum, &count);
		*worst = wi > *worst ? wi : *worst;
		double fr = sqrt(v3_dot(fi, fi)) / ri;
		*fmx = fr > *fmx ? fr : *fmx;
		v3_copy(f + 3 * i, fi);
		if (s->worst)
			s->worst[i] = wi;
	}
	part[0] = sum;
	part[1] = count;
}

#define FORCE_BLOCK 1024

void soft_forces(soft_system *s, double *f, soft_stats *out)
{
	if (s->half) {
		forces_half(s, f, out);
		return;
	}
	size_t n = s->nmobile, nblock = (n + FORCE_BLOCK - 1) / FORCE_BLOCK;
	double *part = xcalloc(2 * nblock + 1, sizeof *part);
	double worst = 0, fmx = 0;
#pragma omp parallel for reduction(max : worst, fmx) schedule(static) if (n >= PAR_MIN)
	for (size_t b = 0; b < nblock; b++) {
		size_t end = (b + 1) * FORCE_BLOCK < n ? (b + 1) * FORCE_BLOCK : n;
		forces_block(s, f, b * FORCE_BLOCK, end, &worst, &fmx, part + 2 * b);
	}
	double sum = 0, count = 0;
	for (size_t b = 0; b < nblock; b++) {
		sum += part[2 * b];
		count += part[2 * b + 1];
	}
	free(part);
	out->overlap_max = worst;
	out->overlap_mean = count > 0 ? sum / count : 0;
	out->contacts = count;
	out->fmax = fmx;
}
