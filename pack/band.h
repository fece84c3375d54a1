/* Relaxation of the layer along the specimen boundary after tiling: the
 * spheres cut by the boundary are pushed inside and the layer settles
 * against the boundary as against a wall. */
#ifndef PACK_BAND_H
#define PACK_BAND_H

#include "lib/assembly.h"
#include "lib/progress.h"
#include "pack/spheres.h"
#include "pack/surface.h"

typedef struct {
	double width; /* m, spheres whose centre is closer than this to the
	               * boundary move (the band plus its mobile buffer) */
	double otol;  /* stop when the largest relative overlap is below */
	long max_iter;
	long shrink_after; /* iterations before radii may shrink */
	double skin;       /* m, Verlet skin */
	progress *prog;    /* shows the iterations (may be NULL) */
} band_params;

typedef struct {
	size_t mobile, involved; /* spheres moved; spheres in the computation */
	long iter;
	double overlap;                 /* largest relative overlap at the end */
	size_t shrunk;                  /* moved spheres left smaller than drawn */
	double shrink_mean, shrink_max; /* their relative radius reduction */
} band_result;

/* surf is the search tree over g's boundary triangles. */
void band_relax(spheres *S, const surface *surf, const dem_geometry *g, const band_params *p,
                band_result *res);

#endif
