#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/cells.h"

double cells_size(const double lo[3], const double hi[3], size_t n, double h)
{
	for (;;) {
		double total = 1;
		for (int k = 0; k < 3; k++)
			total *= floor((hi[k] - lo[k]) / h) + 1;
		if (total <= (double)(8 * n + 27))
			return h;
		h *= 1.5;
	}
}

void cells_build(cells *g, const double *x, size_t n, double h)
{
	double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	for (size_t i = 0; i < n; i++)
		for (int k = 0; k < 3; k++) {
			lo[k] = fmin(lo[k], x[3 * i + k]);
			hi[k] = fmax(hi[k], x[3 * i + k]);
		}
	if (n == 0)
		for (int k = 0; k < 3; k++)
			lo[k] = hi[k] = 0;
	/* Coarsen a sparse grid so that cells never outnumber 8 n + 27 (counted
	 * as doubles: a far particle would overflow an integer count). */
	h = fmax(h, cells_size(lo, hi, n, h));
	for (int k = 0; k < 3; k++)
		g->dim[k] = (int)floor((hi[k] - lo[k]) / h) + 1;
	memcpy(g->lo, lo, sizeof lo);
	g->h = h;
	g->ncell = (size_t)g->dim[0] * g->dim[1] * g->dim[2];
	if (g->ncell + 1 > g->cap_cell) {
		g->cap_cell = g->ncell + 1;
		free(g->start), free(g->fill);
		g->start = xmalloc(g->cap_cell * sizeof *g->start);
		g->fill = xmalloc(g->cap_cell * sizeof *g->fill);
	}
	if (n > g->cap_item) {
		g->cap_item = n;
		free(g->item), free(g->cell);
		g->item = xmalloc(n * sizeof *g->item);
		g->cell = xmalloc(n * sizeof *g->cell);
	}
	memset(g->start, 0, (g->ncell + 1) * sizeof *g->start);
	for (size_t i = 0; i < n; i++) {
		int c[3];
		for (int k = 0; k < 3; k++) {
			c[k] = (int)((x[3 * i + k] - lo[k]) / h);
			c[k] = c[k] < 0 ? 0 : c[k] >= g->dim[k] ? g->dim[k] - 1 : c[k];
		}
		g->cell[i] = c[0] + g->dim[0] * (c[1] + g->dim[1] * c[2]);
		g->start[g->cell[i] + 1]++;
	}
	for (size_t c = 0; c < g->ncell; c++)
		g->start[c + 1] += g->start[c];
	/* Stable placement keeps particles of a cell in index order. */
	memcpy(g->fill, g->start, g->ncell * sizeof *g->fill);
	for (size_t i = 0; i < n; i++)
		g->item[g->fill[g->cell[i]]++] = (int32_t)i;
}

int cells_around(const cells *g, int32_t c, int32_t out[27])
{
	int cx = c % g->dim[0], cy = (c / g->dim[0]) % g->dim[1], cz = c / (g->dim[0] * g->dim[1]);
	int m = 0;
	for (int z = cz - 1; z <= cz + 1; z++)
		for (int y = cy - 1; y <= cy + 1; y++)
			for (int x = cx - 1; x <= cx + 1; x++)
				if (x >= 0 && y >= 0 && z >= 0 && x < g->dim[0] && y < g->dim[1] &&
				    z < g->dim[2])
					out[m++] = x + g->dim[0] * (y + g->dim[1] * z);
	return m;
}

static int cmp_i32(const void *a, const void *b)
{
	int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
	return (x > y) - (x < y);
}

int cells_pairs_within(const double *x, const double *r, size_t n, double scale, double h,
                       cells_pairs *p, size_t *crowded)
{
	cells g = {0};
	cells_build(&g, x, n, h);
	int32_t js[CELLS_CAP];
	/* Count first, so the arrays are allocated once at their size. */
	size_t count = 0;
	for (size_t i = 0; i < n; i++) {
		int nj = cells_partners(&g, x, r, i, scale, 0, js, CELLS_CAP);
		if (nj < 0) {
			cells_free(&g);
			*crowded = i;
			return -1;
		}
		count += (size_t)nj;
	}
	p->n = 0;
	p->i = xmalloc((count + 1) * sizeof *p->i);
	p->j = xmalloc((count + 1) * sizeof *p->j);
	p->d = xmalloc((count + 1) * sizeof *p->d);
	for (size_t i = 0; i < n; i++) {
		int nj = cells_partners(&g, x, r, i, scale, 0, js, CELLS_CAP);
		for (int q = 0; q < nj; q++) {
			double d2 = 0;
			for (int k = 0; k < 3; k++) {
				double dx = x[3 * (size_t)js[q] + k] - x[3 * i + k];
				d2 += dx * dx;
			}
			p->i[p->n] = (int32_t)i;
			p->j[p->n] = js[q];
			p->d[p->n++] = sqrt(d2);
		}
	}
	cells_free(&g);
	return 0;
}

int cells_partners(const cells *g, const double *x, const double *r, size_t i, double scale,
                   double add, int32_t *js, int cap)
{
	int32_t near[27];
	int nj = 0, nc = cells_around(g, g->cell[i], near);
	for (int c = 0; c < nc; c++)
		for (int32_t q = g->start[near[c]]; q < g->start[near[c] + 1]; q++) {
			int32_t j = g->item[q];
			if ((size_t)j <= i)
				continue;
			double d2 = 0;
			for (int k = 0; k < 3; k++) {
				double dx = x[3 * j + k] - x[3 * i + k];
				d2 += dx * dx;
			}
			double reach = scale * (r[i] + r[j]) + add;
			if (d2 <= reach * reach) {
				if (nj == cap)
					return -1;
				js[nj++] = j;
			}
		}
	qsort(js, (size_t)nj, sizeof *js, cmp_i32);
	return nj;
}

void cells_free(cells *g)
{
	free(g->start), free(g->item), free(g->cell), free(g->fill);
	memset(g, 0, sizeof *g);
}

void cells_pairs_free(cells_pairs *p)
{
	free(p->i), free(p->j), free(p->d);
	memset(p, 0, sizeof *p);
}
