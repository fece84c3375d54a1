/* Sphere size distributions: what pack samples and what it reports the
 * achieved sizes against. Sizes are radii (m) here; reports show diameters.
 *
 *   uniform    radius uniform in [rmin, rmax]
 *   fuzz       Yade's monodisperse with relative fuzz: r = rmean (1 + f u),
 *              u uniform in [-1, 1] (makeCloud's rRelFuzz)
 *   lognormal  ln r normal with median rmed and deviation sigma, truncated
 *              at +-3 sigma
 *   grading    a sieve curve: sieve sizes (apertures, m) vs. cumulative mass
 *              fraction passing, as concrete mixes are specified. Within a
 *              class [a, b] the mass is spread uniformly in diameter, i.e.
 *              number density ~ d^-3, so the cumulative mass curve is the
 *              table's linear interpolation. */
#ifndef PACK_PSD_H
#define PACK_PSD_H

#include <stddef.h>

#include "lib/cfg.h"
#include "lib/rng.h"

typedef enum { PSD_UNIFORM, PSD_LOGNORMAL, PSD_GRADING } psd_kind;

typedef struct {
	psd_kind kind;
	double rmin, rmax;  /* support (m) */
	double mu, sigma;   /* lognormal: ln r ~ N(mu, sigma^2) on [rmin, rmax] */
	size_t nclass;      /* grading: classes between radii bound[k], bound[k+1] */
	double *bound;      /* [nclass+1] m */
	double *cum_volume; /* [nclass+1] cumulative volume (mass) fraction */
	double *cum_number; /* [nclass+1] cumulative number fraction */
} psd;

void psd_uniform(psd *d, double rmin, double rmax);
void psd_lognormal(psd *d, double median, double sigma);
/* A grading curve from keys "sieve" (m, increasing) and "passing"
 * (fractions, non-decreasing from 0 to 1) of c. */
int psd_grading(psd *d, cfg *c);
void psd_free(psd *d);

/* Multiply every size by s. */
void psd_scale(psd *d, double s);

double psd_sample(const psd *d, rng *g);
/* Fraction of spheres with radius <= r, by number and by volume. */
double psd_cdf_number(const psd *d, double r);
double psd_cdf_volume(const psd *d, double r);
/* E[r^k] by number, k = 1, 2, 3. */
double psd_moment(const psd *d, int k);

#endif
