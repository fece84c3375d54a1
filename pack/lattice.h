/* Hexagonal close packing of equal spheres cut to the specimen (pack
 * --arrangement hcp): the regular arrangement beside the random one, as in
 * 002 §5.6 (Table 5.2), where Yade's regularHexa made it. */
#ifndef PACK_LATTICE_H
#define PACK_LATTICE_H

#include <stddef.h>

#include "lib/assembly.h"
#include "pack/spheres.h"
#include "pack/surface.h"
#include "pack/zones.h"

/* The solid fraction of the infinite lattice, pi / (3 sqrt 2). */
#define LATTICE_PHI_HCP 0.74048048969306104

/* Add to S every sphere of radius r of the lattice that lies wholly inside
 * the specimen g (its centre at least r from the boundary). The lattice is
 * Yade's regularHexa (gap 0), which made the hexagonal specimens of 002
 * §5.6: its origin at the lower corner of g's bounding box, its close packed
 * layers normal to z stacked ABAB (the c axis along z, the loading axis of
 * the built-in shapes); its spheres touch their 12 neighbours. Cut to the
 * same shape, it keeps the same spheres as regularHexa. Returns the number
 * added. */
size_t lattice_hcp(spheres *S, double r, const dem_geometry *g, const surface *surf,
                   const zones *z);

/* The radius of equal spheres of which about n fill a volume at the
 * lattice's solid fraction. */
double lattice_hcp_radius(double volume, long n);

#endif
