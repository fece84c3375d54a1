/* Points sorted into a regular grid of cells no smaller than a search
 * reach, so all points within the reach of a point lie in the 27 cells
 * around its own (or in fewer along a periodic direction too short for
 * three cells, where the one cell holds every image). This is pack's grid:
 * an edge per axis, and a periodic box for the jammed cell. solve's
 * (solve/cells.h) has one cell size, no periodic box, and keeps its
 * buffers from one Verlet rebuild to the next; hence two grids, and the
 * pack_ prefix here. */
#ifndef PACK_CELLS_H
#define PACK_CELLS_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
	double lo[3], edge[3];
	int dim[3];
	int periodic;
	size_t *start; /* [ncell+1] */
	int32_t *item; /* point indices, by cell */
	int32_t *cell; /* cell of each point */
} pack_cells;

/* Over the points' bounding box, or over the periodic box [0, box) when box
 * is not NULL (points must lie inside it). */
void pack_cells_build(pack_cells *g, const double *x, size_t n, double reach, const double *box);
void pack_cells_free(pack_cells *g);
/* Cell coordinates of p: clamped to the grid, or wrapped when periodic. */
void pack_cells_coord(const pack_cells *g, const double p[3], int c[3]);
/* Index of the cell at coordinates c, which are wrapped or must be valid. */
size_t pack_cells_index(const pack_cells *g, const int c[3]);
/* The coordinates c of the cell at offset k from c0, k = (dx + 1) + 3 (dy +
 * 1) + 9 (dz + 1) from 0 to 26 (13: c0 itself); returns whether it lies in
 * a grid of dim cells (any grid: voids.c's linked cells use it too).
 * Inline, as the searches call it 27 times per point. */
static inline int pack_cells_near(const int dim[3], const int c0[3], int k, int c[3])
{
	c[0] = c0[0] + k % 3 - 1;
	c[1] = c0[1] + k / 3 % 3 - 1;
	c[2] = c0[2] + k / 9 - 1;
	return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < dim[0] && c[1] < dim[1] &&
	       c[2] < dim[2];
}

#endif
