/* Size distributions (see psd.h for the four kinds). Formulas, with Phi the
 * standard normal CDF:
 *
 * uniform on [a, b]:   F_N = (r - a)/(b - a),  F_V = (r^4 - a^4)/(b^4 - a^4),
 *                      E[r^k] = (b^{k+1} - a^{k+1}) / ((k+1)(b - a)).
 * lognormal (mu, s) truncated to z in [-3, 3]:
 *                      F_N = (Phi(z) - Phi(-3)) / (Phi(3) - Phi(-3)),
 *                      z = (ln r - mu)/s; by volume the same with mu + 3 s^2
 *                      (r^3 times a lognormal density is lognormal);
 *                      E[r^k] = e^{k mu + k^2 s^2/2}
 *                               (Phi(3 - k s) - Phi(-3 - k s)) / (Phi(3) - Phi(-3)).
 * grading class [a, b] with number density ~ r^-3:
 *                      F_N within the class = (a^-2 - r^-2)/(a^-2 - b^-2),
 *                      E[r] = 2ab/(a+b), E[r^2] = 2 ln(b/a)/(a^-2 - b^-2),
 *                      E[r^3] = 2 a^2 b^2/(a+b); a class holding the volume
 *                      fraction dV holds the number fraction ~ dV / E[r^3]. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "pack/psd.h"

#define TRUNC 3.0

static double phi(double z) { return 0.5 * erfc(-z / M_SQRT2); }

void psd_uniform(psd *d, double rmin, double rmax)
{
	memset(d, 0, sizeof *d);
	d->kind = PSD_UNIFORM;
	d->rmin = rmin;
	d->rmax = rmax;
}

void psd_lognormal(psd *d, double median, double sigma)
{
	memset(d, 0, sizeof *d);
	d->kind = PSD_LOGNORMAL;
	d->mu = log(median);
	d->sigma = sigma;
	d->rmin = median * exp(-TRUNC * sigma);
	d->rmax = median * exp(TRUNC * sigma);
}

static double class_moment(double a, double b, int k)
{
	switch (k) {
	case 1:
		return 2 * a * b / (a + b);
	case 2:
		return 2 * log(b / a) / (1 / (a * a) - 1 / (b * b));
	default:
		return 2 * a * a * b * b / (a + b);
	}
}

/* A grading table is at least two increasing sieve sizes with a
 * cumulative passing fraction each, from 0 to 1 and never decreasing;
 * returns 0, or -1 with the first fault in c's error. */
static int check_grading(cfg *c, const double *sieve, size_t ns, const double *pass, size_t np)
{
	if (ns < 2)
		return cfg_error(c, "sieve", "%zu value%s: expected at least 2 sieve sizes (m)", ns,
		                 ns == 1 ? "" : "s");
	if (np != ns)
		return cfg_error(c, "passing", "%zu values: expected one per sieve size (%zu)", np,
		                 ns);
	for (size_t k = 1; k < ns; k++)
		if (!(sieve[k] > sieve[k - 1]))
			return cfg_error(c, "sieve",
			                 "value %g after %g: expected increasing sizes (m)",
			                 sieve[k], sieve[k - 1]);
		else if (pass[k] < pass[k - 1])
			return cfg_error(
			    c, "passing",
			    "value %g after %g: expected a non-decreasing cumulative fraction",
			    pass[k], pass[k - 1]);
	if (pass[0] != 0)
		return cfg_error(
		    c, "passing",
		    "first value %g: expected 0 (the smallest sieve bounds the sizes; add "
		    "a smaller sieve)",
		    pass[0]);
	if (pass[ns - 1] != 1)
		return cfg_error(c, "passing",
		                 "last value %g: expected 1 (everything passes the largest sieve)",
		                 pass[ns - 1]);
	return 0;
}

int psd_grading(psd *d, cfg *c)
{
	memset(d, 0, sizeof *d);
	double *sieve = NULL, *pass = NULL;
	size_t ns = 0, np = 0;
	if (cfg_numbers(c, "sieve", &sieve, &ns, 0, "m", CFG_POS, 1e3))
		return -1;
	if (cfg_numbers(c, "passing", &pass, &np, 0, "", 0, 1) ||
	    check_grading(c, sieve, ns, pass, np)) {
		free(sieve);
		free(pass);
		return -1;
	}
	d->kind = PSD_GRADING;
	d->nclass = ns - 1;
	d->bound = sieve;
	d->cum_volume = pass;
	d->cum_number = xcalloc(ns, sizeof *d->cum_number);
	for (size_t k = 0; k < ns; k++)
		d->bound[k] *= 0.5;
	for (size_t k = 0; k < d->nclass; k++) {
		double dv = pass[k + 1] - pass[k];
		d->cum_number[k + 1] =
		    d->cum_number[k] + dv / class_moment(d->bound[k], d->bound[k + 1], 3);
	}
	for (size_t k = 1; k < ns; k++)
		d->cum_number[k] /= d->cum_number[ns - 1];
	/* The support: from the first to the last class holding any volume. */
	size_t lo = 0, hi = d->nclass;
	while (pass[lo + 1] == 0)
		lo++;
	while (pass[hi - 1] == 1)
		hi--;
	d->rmin = d->bound[lo];
	d->rmax = d->bound[hi];
	return 0;
}

void psd_free(psd *d)
{
	free(d->bound);
	free(d->cum_volume);
	free(d->cum_number);
	memset(d, 0, sizeof *d);
}

void psd_scale(psd *d, double s)
{
	d->rmin *= s;
	d->rmax *= s;
	d->mu += log(s);
	for (size_t k = 0; k <= d->nclass && d->bound; k++)
		d->bound[k] *= s;
}

/* The class holding cumulative number fraction u (grading). */
static size_t class_of(const double *cum, size_t nclass, double u)
{
	size_t lo = 0, hi = nclass - 1;
	while (lo < hi) {
		size_t mid = (lo + hi) / 2;
		if (cum[mid + 1] <= u)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

double psd_sample(const psd *d, rng *g)
{
	switch (d->kind) {
	case PSD_UNIFORM:
		return d->rmin + (d->rmax - d->rmin) * rng_uniform(g);
	case PSD_LOGNORMAL: {
		double z;
		do
			z = rng_normal(g);
		while (fabs(z) > TRUNC);
		return exp(d->mu + d->sigma * z);
	}
	case PSD_GRADING: {
		double u = rng_uniform(g);
		size_t k = class_of(d->cum_number, d->nclass, u);
		while (d->cum_number[k + 1] == d->cum_number[k])
			k++; /* empty classes hold no spheres */
		double a = d->bound[k], b = d->bound[k + 1];
		double v = rng_uniform(g), ia = 1 / (a * a), ib = 1 / (b * b);
		return 1 / sqrt(ia - v * (ia - ib));
	}
	}
	return 0;
}

static double lognormal_cdf(const psd *d, double r, double mu)
{
	double lo = phi((log(d->rmin) - mu) / d->sigma), hi = phi((log(d->rmax) - mu) / d->sigma);
	return (phi((log(r) - mu) / d->sigma) - lo) / (hi - lo);
}

double psd_cdf_number(const psd *d, double r)
{
	if (r < d->rmin)
		return 0;
	if (r >= d->rmax)
		return 1;
	switch (d->kind) {
	case PSD_UNIFORM:
		return (r - d->rmin) / (d->rmax - d->rmin);
	case PSD_LOGNORMAL:
		return lognormal_cdf(d, r, d->mu);
	case PSD_GRADING: {
		size_t k = 0;
		while (k + 1 < d->nclass && r >= d->bound[k + 1])
			k++;
		double a = d->bound[k], b = d->bound[k + 1];
		double t = (1 / (a * a) - 1 / (r * r)) / (1 / (a * a) - 1 / (b * b));
		return d->cum_number[k] + (d->cum_number[k + 1] - d->cum_number[k]) * t;
	}
	}
	return 0;
}

double psd_cdf_volume(const psd *d, double r)
{
	if (r < d->rmin)
		return 0;
	if (r >= d->rmax)
		return 1;
	switch (d->kind) {
	case PSD_UNIFORM: {
		double a4 = pow(d->rmin, 4);
		return (pow(r, 4) - a4) / (pow(d->rmax, 4) - a4);
	}
	case PSD_LOGNORMAL:
		return lognormal_cdf(d, r, d->mu + 3 * d->sigma * d->sigma);
	case PSD_GRADING: {
		size_t k = 0;
		while (k + 1 < d->nclass && r >= d->bound[k + 1])
			k++;
		double t = (r - d->bound[k]) / (d->bound[k + 1] - d->bound[k]);
		return d->cum_volume[k] + (d->cum_volume[k + 1] - d->cum_volume[k]) * t;
	}
	}
	return 0;
}

double psd_moment(const psd *d, int k)
{
	switch (d->kind) {
	case PSD_UNIFORM: {
		double a = d->rmin, b = d->rmax;
		if (b == a)
			return pow(a, k);
		return (pow(b, k + 1) - pow(a, k + 1)) / ((k + 1) * (b - a));
	}
	case PSD_LOGNORMAL: {
		double s = d->sigma, norm = phi(TRUNC) - phi(-TRUNC);
		return exp(k * d->mu + 0.5 * k * k * s * s) *
		       (phi(TRUNC - k * s) - phi(-TRUNC - k * s)) / norm;
	}
	case PSD_GRADING: {
		double m = 0;
		for (size_t c = 0; c < d->nclass; c++)
			m += (d->cum_number[c + 1] - d->cum_number[c]) *
			     class_moment(d->bound[c], d->bound[c + 1], k);
		return m;
	}
	}
	return 0;
}
