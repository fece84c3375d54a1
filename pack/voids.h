/* Filling the voids the cut leaves along the specimen boundary. */
#ifndef PACK_VOIDS_H
#define PACK_VOIDS_H

#include <stdint.h>

#include "lib/assembly.h"
#include "pack/psd.h"
#include "pack/spheres.h"
#include "pack/surface.h"

/* Insert spheres tangent to the boundary (geo's triangles, searched with
 * surf) wherever one of at least d->rmin fits among the spheres of S,
 * with radii drawn from d but no larger than the room. Returns the number
 * inserted (appended to S). */
size_t voids_fill(spheres *S, const surface *surf, const dem_geometry *geo, const psd *d,
                  uint64_t seed);

#endif
