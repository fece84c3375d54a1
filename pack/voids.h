/* Filling the voids the wall band keeps after its relaxation. */
#ifndef PACK_VOIDS_H
#define PACK_VOIDS_H

#include <stdint.h>

#include "pack/psd.h"
#include "pack/spheres.h"
#include "pack/surface.h"
#include "pack/zones.h"

/* Insert spheres where a sphere of at least d->rmin / (1 + squeeze) fits
 * among the spheres shallower than `depth`: radius drawn from d but no
 * larger than (1 + squeeze) times the room, so the next relaxation has
 * little to push apart. Returns the number inserted. */
size_t voids_fill(spheres *S, const surface *surf, const zones *z, const psd *d, double depth,
                  double squeeze, uint64_t seed);

#endif
