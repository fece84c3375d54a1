/* A periodic cell of jammed polydisperse spheres, grown with FIRE. Tiling
 * it over the specimen gives the bulk of the assembly its density and
 * isotropy at almost no cost per sphere. */
#ifndef PACK_JAM_H
#define PACK_JAM_H

#include <stddef.h>
#include <stdint.h>

#include "lib/progress.h"
#include "pack/psd.h"

typedef struct {
	size_t n;
	double *x;     /* [n][3] m, inside [0, box) */
	double *r;     /* [n] m, as sampled from the distribution */
	double box[3]; /* m */
	double phi;    /* solid fraction */
	long iter;     /* FIRE iterations spent */
} jam_cell;

/* n spheres sampled from d (random stream `seed`), in a periodic box whose
 * edges are in the ratio `shape`, jammed with a largest overlap below otol
 * (relative to the smaller radius). prog (may be NULL) shows the iterations. */
void jam_make(jam_cell *c, const psd *d, size_t n, const double shape[3], uint64_t seed,
              double otol, progress *prog);
void jam_free(jam_cell *c);

#endif
