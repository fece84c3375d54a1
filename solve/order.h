/* The particles of the specimen in Morton (Z-order) order, walked breadth
 * first within cells, found across the ranks without any rank holding them
 * all (order.c).
 *
 * Each rank reads a piece of the assembly's rows (assembly_read_rows). The
 * particles' bounding cube, scaled to cells 0 to 2^21 - 1 a side, gives
 * each a key (lib/morton.h); the order is that of the keys, equal keys in
 * the order of the assembly. Then, within Morton cells of some 4 000
 * particles or more (a key's leading bits), the particles are renumbered
 * by a breadth-first walk over neighbours (centres within `reach` times
 * the sum of the radii: the law's bond range), from the first in key
 * order: a bond's far end then comes for the first time in the order of
 * memory (share/doc/solve.md, "The particles numbered by a walk"). Both
 * depend on the particles and the range only, so the order is the same on
 * any number of ranks. Rank k receives the particles of places
 * [first_k, first_k+1) of the order, whole particle blocks (blocks.h) in
 * even shares: a count of the keys by their 16 leading bits (summed over
 * the ranks) sends every cell to one rank, which sorts and walks it, and
 * the sorted cells go on to the ranks whose places they fill. */
#ifndef DEM_ORDER_H
#define DEM_ORDER_H

#include <stddef.h>
#include <stdint.h>

#include "lib/assembly.h"

typedef struct {
	size_t first, n; /* this rank's places [first, first + n) of the order */
	int32_t *orig;   /* [n] index in the assembly */
	double *x, *r;   /* [n][3], [n] m */
} order_range;

/* The first place of rank k's share of the n particles (of `ranks`). */
size_t order_share(size_t n, int k, int ranks);
/* This rank's share of the order of the assembly's particles: of a piece
 * (assembly_read_part, a different one on each rank), or of the whole
 * assembly on every rank. plain: the Morton order alone, without the walk
 * (the order of checkpoints written before it). Collective. */
void order_morton(const dem_assembly *a, int plain, double reach, order_range *o);
/* The walk's version, which checkpoints record (order_walk): any change of
 * the order (its cells, its steps) must change it, since a restart must
 * find the particles in the order of the checkpoint. */
enum { ORDER_WALK = 1 };
void order_free(order_range *o);

#endif
