#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "pack/cells.h"

void pack_cells_coord(const pack_cells *g, const double p[3], int c[3])
{
	for (int k = 0; k < 3; k++) {
		c[k] = (int)floor((p[k] - g->lo[k]) / g->edge[k]);
		if (g->periodic)
			c[k] = ((c[k] % g->dim[k]) + g->dim[k]) % g->dim[k];
		else
			c[k] = c[k] < 0 ? 0 : c[k] >= g->dim[k] ? g->dim[k] - 1 : c[k];
	}
}

size_t pack_cells_index(const pack_cells *g, const int c[3])
{
	size_t w[3];
	for (int k = 0; k < 3; k++)
		w[k] = (size_t)(((c[k] % g->dim[k]) + g->dim[k]) % g->dim[k]);
	return (w[2] * (size_t)g->dim[1] + w[1]) * (size_t)g->dim[0] + w[0];
}

void pack_cells_build(pack_cells *g, const double *x, size_t n, double reach, const double *box)
{
	double hi[3];
	g->periodic = box != NULL;
	for (int k = 0; k < 3; k++) {
		g->lo[k] = box ? 0 : INFINITY;
		hi[k] = box ? box[k] : -INFINITY;
	}
	if (!box)
		for (size_t i = 0; i < n; i++)
			for (int k = 0; k < 3; k++) {
				g->lo[k] = fmin(g->lo[k], x[3 * i + k]);
				hi[k] = fmax(hi[k], x[3 * i + k]);
			}
	size_t ncell = 1;
	for (int k = 0; k < 3; k++) {
		double ext = n || box ? hi[k] - g->lo[k] : 0;
		int m = (int)fmin(fmax(floor(ext / reach), 1), 1024);
		if (box && m < 3)
			m = 1;
		g->dim[k] = m;
		g->edge[k] = box ? ext / m : fmax(ext / m, reach);
		ncell *= (size_t)m;
	}
	g->start = xcalloc(ncell + 1, sizeof *g->start);
	g->item = xmalloc(n * sizeof *g->item);
	g->cell = xmalloc(n * sizeof *g->cell);
	for (size_t i = 0; i < n; i++) {
		int c[3];
		pack_cells_coord(g, x + 3 * i, c);
		g->cell[i] = (int32_t)pack_cells_index(g, c);
		g->start[g->cell[i] + 1]++;
	}
	for (size_t c = 0; c < ncell; c++)
		g->start[c + 1] += g->start[c];
	size_t *fill = xmalloc(ncell * sizeof *fill);
	memcpy(fill, g->start, ncell * sizeof *fill);
	for (size_t i = 0; i < n; i++)
		g->item[fill[g->cell[i]]++] = (int32_t)i;
	free(fill);
}

void pack_cells_free(pack_cells *g)
{
	free(g->start);
	free(g->item);
	free(g->cell);
	memset(g, 0, sizeof *g);
}
