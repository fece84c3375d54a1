#include <math.h>

#include "pack/lattice.h"

/* The centres, in units of r from the lattice's origin: layer k at height
 * 2 sqrt(6)/3 k, row j of layer k at sqrt(3) (j + (k mod 2)/3), sphere i of
 * the row at 2 i + (j + k) mod 2: rows of touching spheres 2r apart, each
 * layer seated in the hollows of the one below: the simple hcp lattice of
 * Yade's regularHexa (py/pack/pack.py) with no gap. */
static void centre(double r, const double o[3], long i, long j, long k, double x[3])
{
	x[0] = o[0] + r * (double)(2 * i + (j + k) % 2);
	x[1] = o[1] + r * sqrt(3.0) * ((double)j + (double)(k % 2) / 3.0);
	x[2] = o[2] + r * 2.0 * sqrt(6.0) / 3.0 * (double)k;
}

/* Bounds lo <= d <= hi on the signed distance d from x (inside the
 * bounding box) to the boundary, from the zones alone when they show that
 * a sphere of radius r there fits or does not, else from a query. */
static void depth(const double x[3], double r, const surface *surf, const zones *z, double *lo,
                  double *hi)
{
	size_t c = zones_cell(z, x);
	*lo = z->lb[c];
	*hi = z->ub[c];
	if (*hi < r || *lo >= r)
		return;
	int32_t hint = z->hint[c];
	*lo = *hi = surface_distance(surf, x, NULL, &hint);
}

size_t lattice_hcp(spheres *S, double r, const dem_geometry *g, const surface *surf, const zones *z)
{
	double o[3], ext[3];
	for (int a = 0; a < 3; a++) {
		o[a] = g->bbox_min[a];
		ext[a] = g->bbox_max[a] - r - o[a];
	}
	if (ext[0] < 0 || ext[1] < 0 || ext[2] < 0)
		return 0;
	long ni = (long)floor(ext[0] / (2 * r)) + 1, nj = (long)floor(ext[1] / (sqrt(3.0) * r)) + 1,
	     nk = (long)floor(ext[2] / (2 * sqrt(6.0) / 3 * r)) + 1;
	/* A sphere touching the boundary is kept whatever the rounding of its
	 * distance. */
	double fit = r * (1 - 1e-9);
	size_t n0 = S->n;
	for (long k = 0; k < nk; k++)
		for (long j = 0; j < nj; j++)
			for (long i = 0; i < ni; i++) {
				double x[3];
				centre(r, o, i, j, k, x);
				if (x[0] > g->bbox_max[0] - fit || x[1] > g->bbox_max[1] - fit)
					continue;
				double lo, hi;
				depth(x, fit, surf, z, &lo, &hi);
				if (lo >= fit)
					spheres_push(S, x, r, lo, hi);
			}
	return S->n - n0;
}

double lattice_hcp_radius(double volume, long n)
{
	return cbrt(LATTICE_PHI_HCP * volume / ((double)n * 4.0 / 3.0 * M_PI));
}
