/* A regular grid over the specimen's bounding box whose cells carry bounds
 * on the signed distance to the boundary of every point inside them, so
 * most spheres are classified (outside, deep inside, near the wall)
 * without a query of their own. */
#ifndef PACK_ZONES_H
#define PACK_ZONES_H

#include <stddef.h>
#include <stdint.h>

#include "pack/surface.h"

typedef struct {
	double lo[3]; /* m, corner of cell (0, 0, 0) */
	double edge;  /* m */
	int dim[3];
	float *lb, *ub; /* per cell: lower and upper bound of the signed distance (m) */
	int32_t *hint;  /* per cell: a boundary triangle near it */
	long queries;   /* distance queries spent building */
} zones;

/* Classify the cells of edge `edge` covering [bmin, bmax]: a block of cells
 * is split until it is known to lie outside (ub < 0), farther inside than
 * `depth` (lb >= depth), or is a single cell. */
void zones_build(zones *z, const surface *s, const double bmin[3], const double bmax[3],
                 double edge, double depth);
void zones_free(zones *z);

/* The cell holding p (clamped to the grid), and the centre of cell c. */
size_t zones_cell(const zones *z, const double p[3]);
void zones_centre(const zones *z, size_t c, double centre[3]);

#endif
