/* The effective contact area of a bond and the interaction range, as Oñate
 * et al. 2015 define them (seeds/000; equation numbers are the paper's):
 *
 *   A-bar = alpha pi r_c^2,  r_c = min(r_i, r_j)             (Eq. 21)
 *   alpha = 40 P / N_c, P the porosity and N_c the mean number of bonds
 *           per sphere, unless the material gives "alpha"   (Eq. 22)
 *   bonds form for d <= (1 + beta)(r_i + r_j), "beta"        (Eq. 16)
 *
 * The onate and linear laws read both keys; jcfpm and exponential take
 * A = pi r_c^2 (seeds/002 Eq. 3.10), the area with alpha = 1. */
#ifndef DEM_LAWS_AREA_H
#define DEM_LAWS_AREA_H

#include <math.h>

#include "lib/cfg.h"
#include "lib/vec3.h"
#include "solve/law.h"

typedef struct {
	double alpha; /* Eq. 21-22; 0 until area_setup when taken from the packing */
	double beta;  /* Eq. 16 */
} area_keys;

/* "alpha" (default: from the packing) and "beta" (default 0.10, Sect. 4.2). */
int area_parse(cfg *m, area_keys *a);

/* alpha = 40 P / N_c (Eq. 22) unless given; with no bonds at all, the
 * quasi-optimal value 1. Called from the law's setup. */
void area_setup(area_keys *a, const law_packing *pk);

/* law.bond_range: 1 + beta (Eq. 16). */
static inline double area_range(const area_keys *a) { return 1 + a->beta; }

/* The contact radius r_c = min(r_i, r_j) (Eq. 21). */
static inline double area_rc(const law_pair *pair) { return law_min(pair->ri, pair->rj); }

/* A-bar = alpha pi r_c^2 (Eq. 21) of spheres of radii ri, rj. */
static inline double area_of_radii(double alpha, double ri, double rj)
{
	double rc = law_min(ri, rj);
	return alpha * DEM_PI * rc * rc;
}

/* A-bar of a pair. */
static inline double area_of(double alpha, const law_pair *pair)
{
	return area_of_radii(alpha, pair->ri, pair->rj);
}

#endif
