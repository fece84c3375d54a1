/* Copies of the periodic jammed cell laid over the specimen and cut by its
 * boundary. */
#ifndef PACK_TILE_H
#define PACK_TILE_H

#include "pack/jam.h"
#include "pack/spheres.h"
#include "pack/surface.h"
#include "pack/zones.h"

/* Append to S every copy of a cell sphere whose centre lies inside
 * [bmin, bmax] and at least keep r inside the boundary. The cell is centred
 * on the box. */
void tile_fill(spheres *S, const jam_cell *c, const surface *surf, const zones *z,
               const double bmin[3], const double bmax[3], double keep);

#endif
