/* Size distributions: samples of every kind follow their own cumulative
 * distribution (Kolmogorov-Smirnov distance), their moments match the
 * closed forms, the by-volume curve is the r^3-weighted by-number one, a
 * grading curve's samples pass its sieves in the tabulated mass fractions,
 * and bad grading tables give one clear message each. */
#include "tests/check.h"

#include "lib/err.h"
#include "pack/psd.h"

enum { N = 200000 };

static int cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* KS distance of N samples of d from psd_cdf_number, and sample moments. */
static double ks(const psd *d, uint64_t seed, double m[4])
{
	static double r[N];
	rng g;
	rng_seed(&g, seed);
	m[1] = m[2] = m[3] = 0;
	for (int i = 0; i < N; i++) {
		r[i] = psd_sample(d, &g);
		for (int k = 1; k <= 3; k++)
			m[k] += pow(r[i], k) / N;
	}
	qsort(r, N, sizeof *r, cmp);
	double dmax = 0;
	for (int i = 0; i < N; i++) {
		double f = psd_cdf_number(d, r[i]);
		dmax = fmax(dmax, fmax(fabs(f - (double)i / N), fabs(f - (double)(i + 1) / N)));
	}
	return dmax;
}

/* KS at the 0.1 % level: 1.95 / sqrt(N); moments within 5 standard errors
 * (the relative spread of r^k is below 1 for these distributions). */
static void check_sampling(const psd *d, uint64_t seed)
{
	double m[4];
	CHECK(ks(d, seed, m) < 1.95 / sqrt(N));
	for (int k = 1; k <= 3; k++)
		CHECK_REL(m[k], psd_moment(d, k), 5.0 / sqrt(N));
}

/* F_V(r) = int_0^r s^3 dF_N(s) / E[r^3], by the trapezoidal rule. */
static void check_volume_cdf(const psd *d)
{
	int n = 20000;
	double acc = 0, prev = psd_cdf_number(d, d->rmin), worst = 0;
	for (int i = 1; i <= n; i++) {
		double r0 = d->rmin + (d->rmax - d->rmin) * (i - 1) / n;
		double r1 = d->rmin + (d->rmax - d->rmin) * i / n;
		double f = psd_cdf_number(d, r1), rm = 0.5 * (r0 + r1);
		acc += rm * rm * rm * (f - prev);
		prev = f;
		worst = fmax(worst, fabs(acc / psd_moment(d, 3) - psd_cdf_volume(d, r1)));
	}
	CHECK_NEAR(worst, 0, 2e-4);
}

static void test_uniform_and_fuzz(void)
{
	psd d;
	psd_uniform(&d, 0.5e-3, 1.5e-3);
	CHECK_REL(psd_moment(&d, 1), 1e-3, 1e-15);
	CHECK_REL(psd_moment(&d, 3), (pow(1.5e-3, 4) - pow(0.5e-3, 4)) / (4 * 1e-3), 1e-12);
	CHECK_NEAR(psd_cdf_number(&d, 1e-3), 0.5, 1e-15);
	check_sampling(&d, 1);
	check_volume_cdf(&d);
	/* Yade's rMean = 1 mm, rRelFuzz = 0.2: uniform in [0.8, 1.2] mm. */
	psd_uniform(&d, 1e-3 * (1 - 0.2), 1e-3 * (1 + 0.2));
	check_sampling(&d, 2);
	psd_scale(&d, 2);
	CHECK_REL(d.rmin, 1.6e-3, 1e-15);
	CHECK_REL(psd_moment(&d, 1), 2e-3, 1e-14);
}

static void test_lognormal(void)
{
	psd d;
	psd_lognormal(&d, 1e-3, 0.3);
	CHECK_REL(d.rmax, 1e-3 * exp(0.9), 1e-15);
	CHECK_NEAR(psd_cdf_number(&d, 1e-3), 0.5, 1e-12);
	check_sampling(&d, 3);
	check_volume_cdf(&d);
	psd_scale(&d, 0.5);
	CHECK_NEAR(psd_cdf_number(&d, 0.5e-3), 0.5, 1e-12);
}

static const char *GRADING = "{\"sieve\": [0.001, 0.002, 0.004, 0.008],"
                             " \"passing\": [0, 0.2, 0.55, 1]}";

static void test_grading(void)
{
	cfg *c = cfg_parse(GRADING, "mix.json");
	psd d;
	CHECK(psd_grading(&d, c) == 0);
	CHECK(cfg_check_unused(c) == 0);
	cfg_free(c);
	CHECK_REL(d.rmin, 0.5e-3, 1e-15);
	CHECK_REL(d.rmax, 4e-3, 1e-15);
	check_sampling(&d, 4);
	check_volume_cdf(&d);
	/* The sampled mass passing each sieve is the tabulated fraction. */
	static const double sieve[4] = {0.001, 0.002, 0.004, 0.008}, pass[4] = {0, 0.2, 0.55, 1};
	double below[4] = {0}, total = 0;
	rng g;
	rng_seed(&g, 9);
	for (int i = 0; i < N; i++) {
		double r = psd_sample(&d, &g), v = r * r * r;
		total += v;
		for (int k = 0; k < 4; k++)
			below[k] += 2 * r <= sieve[k] ? v : 0;
	}
	for (int k = 0; k < 4; k++)
		CHECK_NEAR(below[k] / total, pass[k], 0.01);
	CHECK_NEAR(psd_cdf_volume(&d, 1.5e-3), 0.2 + 0.35 * 0.5, 1e-12); /* d = 3 mm */
	psd_free(&d);
}

static void bad_grading(const char *json, const char *message)
{
	cfg *c = cfg_parse(json, "mix.json");
	psd d;
	CHECK(psd_grading(&d, c) == -1);
	CHECK_STR(err_msg(), message);
	cfg_free(c);
}

static void test_bad_grading(void)
{
	bad_grading(
	    "{\"sieve\": [0.002, 0.001], \"passing\": [0, 1]}",
	    "mix.json: key 'sieve': value 0.001 after 0.002: expected increasing sizes (m)");
	bad_grading("{\"sieve\": [0.001, 0.002, 0.004], \"passing\": [0, 0.6, 0.5]}",
	            "mix.json: key 'passing': value 0.5 after 0.6: expected a non-decreasing "
	            "cumulative fraction");
	bad_grading(
	    "{\"sieve\": [0.001, 0.002], \"passing\": [0.1, 1]}",
	    "mix.json: key 'passing': first value 0.1: expected 0 (the smallest sieve bounds "
	    "the sizes; add a smaller sieve)");
	bad_grading("{\"sieve\": [0.001, 0.002], \"passing\": [0, 0.9]}",
	            "mix.json: key 'passing': last value 0.9: expected 1 (everything passes the "
	            "largest sieve)");
	bad_grading("{\"sieve\": [0.001, 0.002, 0.003], \"passing\": [0, 1]}",
	            "mix.json: key 'passing': 2 values: expected one per sieve size (3)");
	bad_grading("{\"sieve\": [0.001], \"passing\": [0]}",
	            "mix.json: key 'sieve': 1 value: expected at least 2 sieve sizes (m)");
}

int main(void)
{
	test_uniform_and_fuzz();
	test_lognormal();
	test_grading();
	test_bad_grading();
	return check_done();
}
