/* Removal of the spheres that overlap too much after relaxation. */
#ifndef PACK_PRUNE_H
#define PACK_PRUNE_H

#include "pack/spheres.h"
#include "pack/surface.h"

/* Among the spheres shallower than `depth`, remove spheres one at a time,
 * worst overlap first, until no pair overlaps by more than `limit` times the
 * smaller radius and no sphere crosses the boundary by more than `limit`
 * times its radius. Returns the number removed. */
size_t prune_overlaps(spheres *S, const surface *surf, double depth, double limit);

#endif
