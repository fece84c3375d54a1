/* Tiling the periodic cell (see tile.h). Because the cell is periodic, its
 * copies join without seams: the tiled packing is as dense and isotropic
 * as the cell everywhere. Cutting it keeps a sphere when its centre is at
 * least keep r inside (the prototype's lesson: keep = 1/2 leaves the wall
 * band enough spheres for its relaxation to fill it, where keep = 1
 * leaves a gap and keep = 0 makes the band too crowded). Most spheres are
 * decided from their zone's distance bounds; only those near the cut need
 * a query of their own. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "pack/tile.h"

void tile_fill(spheres *S, const jam_cell *c, const surface *surf, const zones *z,
               const double bmin[3], const double bmax[3], double keep)
{
	long lo[3], count[3];
	double origin[3];
	for (int k = 0; k < 3; k++) {
		origin[k] = 0.5 * (bmin[k] + bmax[k]) - 0.5 * c->box[k];
		lo[k] = (long)floor((bmin[k] - origin[k]) / c->box[k]);
		count[k] = (long)ceil((bmax[k] - origin[k]) / c->box[k]) - lo[k];
	}
	long ncopy = count[0] * count[1] * count[2];
	spheres *part = xcalloc((size_t)ncopy, sizeof *part);
#pragma omp parallel for schedule(dynamic, 1)
	for (long q = 0; q < ncopy; q++) {
		long idx[3] = {q % count[0], q / count[0] % count[1], q / count[0] / count[1]};
		double shift[3];
		for (int k = 0; k < 3; k++)
			shift[k] = origin[k] + (double)(lo[k] + idx[k]) * c->box[k];
		for (size_t i = 0; i < c->n; i++) {
			double p[3], r = c->r[i];
			int in = 1;
			for (int k = 0; k < 3; k++) {
				p[k] = c->x[3 * i + k] + shift[k];
				in &= p[k] >= bmin[k] && p[k] <= bmax[k];
			}
			if (!in)
				continue;
			size_t cell = zones_cell(z, p);
			if (z->ub[cell] < keep * r)
				continue;
			if (z->lb[cell] >= keep * r) {
				spheres_push(&part[q], p, r, z->lb[cell], z->ub[cell]);
				continue;
			}
			int32_t hint = z->hint[cell];
			double s = surface_distance(surf, p, NULL, &hint);
			if (s >= keep * r)
				spheres_push(&part[q], p, r, s, s);
		}
	}
	for (long q = 0; q < ncopy; q++) {
		for (size_t i = 0; i < part[q].n; i++)
			spheres_push(S, part[q].x + 3 * i, part[q].r[i], part[q].lo[i],
			             part[q].hi[i]);
		spheres_free(&part[q]);
	}
	free(part);
}
