/* Void filling (see voids.h). The room at a point p is
 *     c(p) = min( min_j |p - x_j| - r_j ,  s(p) )
 * (distance to the nearest sphere surface or to the boundary). It is
 * sampled on a lattice of spacing rmin/2 inside every zone cell shallower
 * than `depth`; lattice points with c >= rmin / (1 + squeeze) are visited
 * from the roomiest down and a sphere goes in wherever the room is still
 * there once the spheres already inserted are counted. A lattice point
 * lies within rmin/2 sqrt(3)/2 of the void's centre, so the sphere
 * inserted there touches about four neighbours after relaxation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/rng.h"
#include "lib/vec3.h"
#include "pack/cells.h"
#include "pack/voids.h"

typedef struct {
	double c, lo, hi; /* room, bounds of the depth */
	double p[3];
	uint64_t key; /* lattice point number: a total order for ties */
} candidate;

static int cmp_candidate(const void *x, const void *y)
{
	const candidate *a = x, *b = y;
	if (a->c != b->c)
		return a->c > b->c ? -1 : 1;
	return (a->key > b->key) - (a->key < b->key);
}

/* Room left by the spheres of g (points x, radii r) around p, capped. */
static double room(const cells *g, const double *x, const double *r, const double p[3], double cap)
{
	int c0[3];
	cells_coord(g, p, c0);
	double c = cap;
	for (int dz = -1; dz <= 1; dz++)
		for (int dy = -1; dy <= 1; dy++)
			for (int dx = -1; dx <= 1; dx++) {
				int c1[3] = {c0[0] + dx, c0[1] + dy, c0[2] + dz}, out = 0;
				for (int k = 0; k < 3; k++)
					out |= c1[k] < 0 || c1[k] >= g->dim[k];
				if (out)
					continue;
				size_t id = cells_index(g, c1);
				for (size_t q = g->start[id]; q < g->start[id + 1]; q++) {
					size_t j = (size_t)g->item[q];
					double d[3];
					v3_sub(d, p, x + 3 * j);
					c = fmin(c, v3_norm(d) - r[j]);
				}
			}
	return c;
}

/* Candidates in zone cell `cell`, appended to *out. */
static void scan_cell(const zones *z, size_t cell, int m, const cells *g, const double *x,
                      const double *r, const surface *surf, double cmin, double cap,
                      candidate **out, size_t *n, size_t *capn)
{
	size_t ijk[3] = {cell % (size_t)z->dim[0], cell / (size_t)z->dim[0] % (size_t)z->dim[1],
	                 cell / ((size_t)z->dim[0] * (size_t)z->dim[1])};
	double h = z->edge / m;
	for (int q = 0; q < m * m * m; q++) {
		int o[3] = {q % m, q / m % m, q / (m * m)};
		candidate cd;
		for (int k = 0; k < 3; k++)
			cd.p[k] = z->lo[k] + (double)ijk[k] * z->edge + (o[k] + 0.5) * h;
		cd.c = room(g, x, r, cd.p, cap);
		if (cd.c < cmin)
			continue;
		cd.lo = z->lb[cell];
		cd.hi = z->ub[cell];
		if (cd.lo < cap) {
			int32_t hint = z->hint[cell];
			cd.lo = cd.hi = surface_distance(surf, cd.p, NULL, &hint);
			cd.c = fmin(cd.c, cd.lo);
			if (cd.c < cmin)
				continue;
		}
		cd.key = (uint64_t)cell * (uint64_t)(m * m * m) + (uint64_t)q;
		if (*n == *capn) {
			*capn = *capn ? 2 * *capn : 64;
			*out = xrealloc(*out, *capn * sizeof **out);
		}
		(*out)[(*n)++] = cd;
	}
}

size_t voids_fill(spheres *S, const surface *surf, const zones *z, const psd *d, double depth,
                  double squeeze, uint64_t seed)
{
	double rmax = d->rmax;
	for (size_t i = 0; i < S->n; i++)
		rmax = fmax(rmax, S->r[i]);
	double cmin = d->rmin / (1 + squeeze), cap = rmax;
	/* The spheres that can bound the room of a lattice point: a point lies
	 * at most a zone cell's diagonal deeper than `depth`. */
	double reach = depth + sqrt(3.0) * z->edge + rmax + cap;
	size_t m0 = 0, *idx = xmalloc(S->n * sizeof *idx);
	for (size_t i = 0; i < S->n; i++)
		if (S->lo[i] < reach)
			idx[m0++] = i;
	double *x = xmalloc(3 * m0 * sizeof *x), *r = xmalloc(m0 * sizeof *r);
	for (size_t k = 0; k < m0; k++) {
		v3_copy(x + 3 * k, S->x + 3 * idx[k]);
		r[k] = S->r[idx[k]];
	}
	free(idx);
	cells g;
	cells_build(&g, x, m0, rmax + cap, NULL);
	int m = (int)ceil(z->edge / (0.5 * d->rmin));
	size_t ncell = (size_t)z->dim[0] * (size_t)z->dim[1] * (size_t)z->dim[2];
	candidate *all = NULL;
	size_t nall = 0;
#pragma omp parallel
	{
		candidate *mine = NULL;
		size_t n = 0, capn = 0;
#pragma omp for schedule(dynamic, 16) nowait
		for (size_t c = 0; c < ncell; c++)
			if (z->ub[c] >= cmin && z->lb[c] < depth)
				scan_cell(z, c, m, &g, x, r, surf, cmin, cap, &mine, &n, &capn);
#pragma omp critical
		{
			all = xrealloc(all, (nall + n) * sizeof *all);
			memcpy(all + nall, mine, n * sizeof *mine);
			nall += n;
		}
		free(mine);
	}
	cells_free(&g);
	free(x);
	free(r);
	qsort(all, nall, sizeof *all, cmp_candidate);

	/* Greedy insertion, checking each point against the spheres inserted
	 * so far (kept in their own cell list, rebuilt as it grows). */
	rng gen;
	rng_seed_stream(&gen, seed, 0x766f6964);
	size_t first = S->n, inserted = 0;
	cells ins = {0};
	size_t ins_built = 0;
	for (size_t k = 0; k < nall; k++) {
		candidate *cd = &all[k];
		double room_ins =
		    ins_built ? room(&ins, S->x + 3 * first, S->r + first, cd->p, cap) : cap;
		for (size_t j = first + ins_built; j < S->n; j++) {
			double dd[3];
			v3_sub(dd, cd->p, S->x + 3 * j);
			room_ins = fmin(room_ins, v3_norm(dd) - S->r[j]);
		}
		cd->c = fmin(cd->c, room_ins);
		if (cd->c < cmin)
			continue;
		double rad = psd_sample(d, &gen);
		for (int t = 0; t < 20 && rad > (1 + squeeze) * cd->c; t++)
			rad = psd_sample(d, &gen);
		rad = fmax(d->rmin, fmin(rad, (1 + squeeze) * cd->c));
		spheres_push(S, cd->p, rad, cd->lo, cd->hi);
		inserted++;
		if (S->n - first >= 2 * ins_built + 64) {
			cells_free(&ins);
			cells_build(&ins, S->x + 3 * first, S->n - first, rmax + cap, NULL);
			ins_built = S->n - first;
		}
	}
	if (ins_built)
		cells_free(&ins);
	free(all);
	return inserted;
}
