/* The exact accumulator: sums correctly rounded (checked against integer
 * arithmetic where the exact sum is known), the same bits whatever the
 * order of the terms and however partial sums are merged, ties to even,
 * subnormals, cancellation, overflow, NaN and infinities. */
#include <float.h>
#include <stdint.h>

#include "lib/rng.h"
#include "lib/xsum.h"
#include "tests/check.h"

static double sum_of(const double *x, int n)
{
	xsum s;
	xsum_clear(&s);
	for (int k = 0; k < n; k++)
		xsum_add(&s, x[k]);
	return xsum_round(&s);
}

/* The terms in `parts` contiguous pieces, each summed and normalized on its
 * own, merged in reverse order (as ranks' partial sums would be). */
static double merged(const double *x, int n, int parts)
{
	xsum total;
	xsum_clear(&total);
	for (int p = parts - 1; p >= 0; p--) {
		xsum s;
		xsum_clear(&s);
		for (int k = p * n / parts; k < (p + 1) * n / parts; k++)
			xsum_add(&s, x[k]);
		xsum_normalize(&s);
		xsum_merge(&total, &s);
	}
	return xsum_round(&total);
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

static void shuffle(double *x, int n, rng *r)
{
	for (int k = n - 1; k > 0; k--) {
		int j = (int)(rng_uniform(r) * (k + 1));
		double t = x[k];
		x[k] = x[j];
		x[j] = t;
	}
}

int main(void)
{
	enum { N = 4000 };
	static double x[N];
	rng r;
	rng_seed(&r, 7);

	/* Multiples of 2^-20 below 2^31 (2^51 units): the exact sum is an integer count of
	 * 2^-20 that int64 holds, and its conversion to double rounds to
	 * nearest even as xsum_round must. */
	int64_t exact = 0;
	for (int k = 0; k < N; k++) {
		int64_t m = (int64_t)(rng_uniform(&r) * 1e12) - 200000000000;
		m *= (int64_t)1 << (int)(rng_uniform(&r) * 12);
		x[k] = ldexp((double)m, -20);
		exact += m;
	}
	double want = ldexp((double)exact, -20);
	CHECK((int64_t)(double)exact != exact); /* the sum needs rounding */
	CHECK(same_bits(sum_of(x, N), want));
	CHECK(same_bits(merged(x, N, 7), want));

	/* Terms over the whole range, with cancellation: the same bits in any
	 * order and any split. */
	for (int k = 0; k < N; k++) {
		double mag = ldexp(rng_uniform(&r), (int)(rng_uniform(&r) * 2000) - 1000);
		x[k] = k % 2 ? mag : -mag;
	}
	double s0 = sum_of(x, N);
	int same = 1;
	for (int t = 0; t < 5; t++) {
		shuffle(x, N, &r);
		same &= same_bits(sum_of(x, N), s0);
		same &= same_bits(merged(x, N, 1 + t * 3), s0);
	}
	CHECK(same);

	/* Well-conditioned terms: close to the plain sum. */
	double plain = 0;
	for (int k = 0; k < N; k++) {
		x[k] = rng_uniform(&r);
		plain += x[k];
	}
	CHECK_REL(sum_of(x, N), plain, 1e-13);

	/* Cancellation the plain sum loses entirely. */
	CHECK(sum_of((const double[]){1e308, 1, -1e308}, 3) == 1);
	/* Nothing, and terms that cancel exactly: +0. One term in the top
	 * digits only, and one in the lowest. */
	CHECK(same_bits(sum_of(NULL, 0), 0.0));
	CHECK(same_bits(sum_of((const double[]){1, 1e300, -1, -1e300}, 4), 0.0));
	CHECK(sum_of((const double[]){DBL_MAX}, 1) == DBL_MAX);
	CHECK(sum_of((const double[]){-DBL_TRUE_MIN}, 1) == -DBL_TRUE_MIN);
	CHECK(sum_of((const double[]){0x1p-1074, 1e300, 0x1p-1074, -1e300}, 4) == 0x1p-1073);
	/* Subnormals, exactly. */
	CHECK(sum_of((const double[]){DBL_TRUE_MIN, DBL_TRUE_MIN, DBL_TRUE_MIN}, 3) ==
	      3 * DBL_TRUE_MIN);
	CHECK(sum_of((const double[]){DBL_MIN, -DBL_TRUE_MIN}, 2) == DBL_MIN - DBL_TRUE_MIN);
	/* Ties to even, and a sticky bit far below. */
	double two53 = 0x1p53;
	CHECK(sum_of((const double[]){two53, 1}, 2) == two53);
	CHECK(sum_of((const double[]){two53, 3}, 2) == two53 + 4);
	CHECK(sum_of((const double[]){two53, 1, 0x1p-900}, 3) == two53 + 2);
	CHECK(sum_of((const double[]){-two53, -1, -0x1p-900}, 3) == -two53 - 2);
	CHECK(sum_of((const double[]){-two53, 1}, 2) == -two53 + 2 - 1); /* exact */
	/* Nothing, and opposite terms. */
	CHECK(same_bits(sum_of(x, 0), 0.0));
	CHECK(sum_of((const double[]){-2.5, 2.5}, 2) == 0);
	/* Overflow, infinities and NaN. */
	CHECK(sum_of((const double[]){DBL_MAX, DBL_MAX}, 2) == INFINITY);
	CHECK(sum_of((const double[]){-DBL_MAX, -DBL_MAX}, 2) == -INFINITY);
	CHECK(sum_of((const double[]){DBL_MAX, DBL_MAX, -DBL_MAX}, 3) == DBL_MAX);
	CHECK(sum_of((const double[]){1, INFINITY}, 2) == INFINITY);
	CHECK(isnan(sum_of((const double[]){INFINITY, -INFINITY}, 2)));
	CHECK(isnan(sum_of((const double[]){1, NAN}, 2)));
	return check_done();
}
