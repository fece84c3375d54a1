/* The packing pipeline: a periodic jammed cell, tiled over the specimen;
 * the wall band relaxed, its voids next to the boundary filled, relaxed
 * again, and the worst remaining overlaps removed. */
#ifndef PACK_PACKER_H
#define PACK_PACKER_H

#include <stdint.h>
#include <stdio.h>

#include "lib/assembly.h"
#include "lib/progress.h"
#include "pack/jam.h"
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
/* About how many spheres of d fill the volume at that solid fraction. */
double packer_count_estimate(const psd *d, double volume);

/* The periodic cell (pack/jam.h) for d and the specimen g, made on the
 * calling thread alone (its parallel loops would meet at a barrier several
 * times per iteration, for a few thousand spheres); with params->count > 0
 * d and the cell are rescaled so that about count spheres fill g. */
void packer_cell(jam_cell *c, psd *d, const dem_geometry *g, const packer_params *params,
                 packer_stats *st);

/* Fill S with the cell tiled over the specimen and repaired along the
 * wall; with params->count > 0, up to two more passes at corrected scales
 * (c and d rescaled in place) bring the count within about 1 %. */
void packer_fill(spheres *S, jam_cell *c, psd *d, const dem_geometry *g, const surface *surf,
                 const zones *z, const packer_params *params, packer_stats *st);

/* The lines pack prints about how the assembly was made. */
void packer_print(const packer_stats *st, FILE *out);

#endif
