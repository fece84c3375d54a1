/* Distance bounds on a grid by recursive subdivision (see zones.h). A block
 * of cells with centre c and half-diagonal h holds only points p with
 * |s(p) - s(c)| <= h, the signed distance s being 1-Lipschitz. Blocks far
 * from the boundary are decided with one query, so the number of queries
 * grows with the boundary's area, not with the specimen's volume. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "pack/zones.h"

typedef struct {
	int lo[3], hi[3]; /* cell index range, hi exclusive */
} block;

static void assign(zones *z, const block *b, float lb, float ub, int32_t hint)
{
	for (int k = b->lo[2]; k < b->hi[2]; k++)
		for (int j = b->lo[1]; j < b->hi[1]; j++)
			for (int i = b->lo[0]; i < b->hi[0]; i++) {
				size_t c = ((size_t)k * (size_t)z->dim[1] + (size_t)j) *
				               (size_t)z->dim[0] +
				           (size_t)i;
				z->lb[c] = lb;
				z->ub[c] = ub;
				z->hint[c] = hint;
			}
}

static long classify(zones *z, const surface *s, const block *b, double depth, int32_t hint)
{
	double c[3], h2 = 0;
	int n[3];
	for (int k = 0; k < 3; k++) {
		n[k] = b->hi[k] - b->lo[k];
		c[k] = z->lo[k] + 0.5 * (b->lo[k] + b->hi[k]) * z->edge;
		h2 += 0.25 * n[k] * n[k] * z->edge * z->edge;
	}
	double h = sqrt(h2), d = surface_distance(s, c, NULL, &hint);
	/* Rounding the bounds outward keeps them bounds in single precision. */
	float lb = nextafterf((float)(d - h), -INFINITY), ub = nextafterf((float)(d + h), INFINITY);
	if (ub < 0 || lb >= depth || (n[0] == 1 && n[1] == 1 && n[2] == 1)) {
		assign(z, b, lb, ub, hint);
		return 1;
	}
	long queries = 1;
	int half[3];
	for (int k = 0; k < 3; k++)
		half[k] = (n[k] + 1) / 2;
	for (int oz = 0; oz < 2; oz++)
		for (int oy = 0; oy < 2; oy++)
			for (int ox = 0; ox < 2; ox++) {
				int o[3] = {ox, oy, oz};
				block sub;
				int empty = 0;
				for (int k = 0; k < 3; k++) {
					sub.lo[k] = b->lo[k] + o[k] * half[k];
					sub.hi[k] = o[k] ? b->hi[k] : b->lo[k] + half[k];
					empty |= sub.lo[k] >= sub.hi[k];
				}
				if (!empty)
					queries += classify(z, s, &sub, depth, hint);
			}
	return queries;
}

void zones_build(zones *z, const surface *s, const double bmin[3], const double bmax[3],
                 double edge, double depth)
{
	memset(z, 0, sizeof *z);
	z->edge = edge;
	int root = 1 << 30;
	for (int k = 0; k < 3; k++) {
		z->dim[k] = (int)ceil((bmax[k] - bmin[k]) / edge);
		if (z->dim[k] < 1)
			z->dim[k] = 1;
		z->lo[k] = 0.5 * (bmin[k] + bmax[k]) - 0.5 * z->dim[k] * edge;
		while (root > z->dim[k] && root > 1)
			root >>= 1;
	}
	size_t ncell = (size_t)z->dim[0] * (size_t)z->dim[1] * (size_t)z->dim[2];
	z->lb = xmalloc(ncell * sizeof *z->lb);
	z->ub = xmalloc(ncell * sizeof *z->ub);
	z->hint = xmalloc(ncell * sizeof *z->hint);
	int nr[3];
	for (int k = 0; k < 3; k++)
		nr[k] = (z->dim[k] + root - 1) / root;
	long nroot = (long)nr[0] * nr[1] * nr[2], queries = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : queries)
	for (long q = 0; q < nroot; q++) {
		int idx[3] = {(int)(q % nr[0]), (int)(q / nr[0] % nr[1]), (int)(q / nr[0] / nr[1])};
		block b;
		for (int k = 0; k < 3; k++) {
			b.lo[k] = idx[k] * root;
			b.hi[k] = b.lo[k] + root < z->dim[k] ? b.lo[k] + root : z->dim[k];
		}
		queries += classify(z, s, &b, depth, -1);
	}
	z->queries = queries;
}

void zones_free(zones *z)
{
	free(z->lb);
	free(z->ub);
	free(z->hint);
	memset(z, 0, sizeof *z);
}

size_t zones_cell(const zones *z, const double p[3])
{
	int c[3];
	for (int k = 0; k < 3; k++) {
		c[k] = (int)floor((p[k] - z->lo[k]) / z->edge);
		c[k] = c[k] < 0 ? 0 : c[k] >= z->dim[k] ? z->dim[k] - 1 : c[k];
	}
	return ((size_t)c[2] * (size_t)z->dim[1] + (size_t)c[1]) * (size_t)z->dim[0] + (size_t)c[0];
}

void zones_centre(const zones *z, size_t c, double centre[3])
{
	size_t ijk[3] = {c % (size_t)z->dim[0], c / (size_t)z->dim[0] % (size_t)z->dim[1],
	                 c / ((size_t)z->dim[0] * (size_t)z->dim[1])};
	for (int k = 0; k < 3; k++)
		centre[k] = z->lo[k] + ((double)ijk[k] + 0.5) * z->edge;
}
