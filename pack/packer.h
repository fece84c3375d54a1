/* The packing pipeline: a periodic jammed cell, tiled over the specimen;
 * the wall band relaxed, its voids next to the boundary filled, relaxed
 * again, and the worst remaining overlaps removed. */
#ifndef PACK_PACKER_H
#define PACK_PACKER_H

#include <stdint.h>
#include <stdio.h>

#include "lib/assembly.h"
#include "lib/progress.h"
#include "pack/psd.h"
#include "pack/spheres.h"
#include "pack/surface.h"
#include "pack/zones.h"

typedef struct {
	uint64_t seed;
	long cell_max; /* largest number of spheres in the periodic cell */
	double keep;   /* keep a tiled sphere whose centre is >= keep r inside */
	double band;   /* depth relaxed against the boundary, mean diameters */
	long count;    /* target number of spheres (0: sizes as given) */
} packer_params;

typedef struct {
	size_t cell_n;
	double cell_phi;
	long cell_iter, band_iter;
	size_t tiled, band_mobile, inserted, pruned;
	size_t shrunk;                  /* wall-band spheres left smaller than drawn */
	double shrink_mean, shrink_max; /* their relative radius reduction */
	double time_cell, time_fill;
	/* s, of time_fill (summed over the passes): tiling, wall band, voids,
	 * their settling, pruning */
	double time_tile, time_band, time_voids, time_refill, time_prune;
} packer_stats;

/* The scale on the sizes of d that makes about `count` spheres fill a
 * volume at the solid fraction of a random close packing. */
double packer_count_scale(const psd *d, double volume, long count);

/* Fill S; with params->count > 0, d is rescaled in place so that the
 * assembly holds count spheres within about 1 % (up to two more tiling
 * passes when the first misses). */
void packer_run(spheres *S, psd *d, const dem_geometry *g, const surface *surf, const zones *z,
                const packer_params *params, packer_stats *st);

/* The lines pack prints about how the assembly was made. */
void packer_print(const packer_stats *st, FILE *out);

#endif
