/* Sizes end to end: for every distribution, the spheres pack writes in the
 * core (deeper than two mean diameters, where nothing but the periodic
 * cell's sample is) follow the target (Kolmogorov-Smirnov distance against
 * its CDF, the cell being a sample of a thousand or more), the whole
 * assembly's median by volume is within a few percent of the target's, the
 * report's target columns are the target, and --count / --mean-radius
 * reach what they ask for. */
#include "tests/pack/run.h"

#include "lib/err.h"
#include "pack/psd.h"

#define BOX "--shape box --length 0.024 --width 0.024 --height 0.024"

static const double HALF = 0.012;

static double depth(const double p[3])
{
	return HALF - fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2])));
}

static int cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* Radius below which half the volume lies, for n radii. */
static double volume_median(const double *r, size_t n)
{
	double *s = malloc(n * sizeof *s + 1), total = 0, acc = 0;
	memcpy(s, r, n * sizeof *s);
	qsort(s, n, sizeof *s, cmp);
	for (size_t i = 0; i < n; i++)
		total += s[i] * s[i] * s[i];
	size_t i = 0;
	while (i < n && (acc += s[i] * s[i] * s[i]) < 0.5 * total)
		i++;
	double m = s[i < n ? i : n - 1];
	free(s);
	return m;
}

/* Pack with `args` and compare with the target distribution d. */
static void check_sizes(const char *what, const char *args, const psd *d)
{
	const char *path = check_tmp("sizes.h5");
	harness_result r = run_pack("--quiet " BOX " %s %s", args, path);
	CHECK(r.status == 0);
	harness_free(&r);
	dem_assembly a;
	if (assembly_read(path, &a)) {
		CHECK(0);
		return;
	}
	double dmean = 2 * a.report.mean_radius, *core = malloc(a.n * sizeof *core);
	size_t m = 0;
	for (size_t i = 0; i < a.n; i++)
		if (depth(a.x + 3 * i) > 2 * dmean)
			core[m++] = a.r[i];
	qsort(core, m, sizeof *core, cmp);
	double ks = 0;
	for (size_t i = 0; i < m; i++) {
		double f = psd_cdf_number(d, core[i]);
		ks = fmax(ks, fmax(fabs(f - (double)i / m), fabs(f - (double)(i + 1) / m)));
	}
	/* The target's median by volume, by bisection on its CDF. */
	double lo = d->rmin, hi = d->rmax;
	for (int k = 0; k < 60; k++) {
		double mid = 0.5 * (lo + hi);
		*(psd_cdf_volume(d, mid) < 0.5 ? &lo : &hi) = mid;
	}
	double med = volume_median(a.r, a.n);
	printf("%-10s %zu spheres, %zu in the core: KS %.3f; median by volume %.4g m (target "
	       "%.4g)\n",
	       what, a.n, m, ks, med, lo);
	CHECK(m > 300);
	CHECK(ks < 0.06);
	CHECK_REL(med, lo, 0.05);
	for (size_t k = 0; k < a.report.npsd; k++)
		CHECK_NEAR(a.report.psd_target_number[k],
		           psd_cdf_number(d, 0.5 * a.report.psd_size[k]), 1e-12);
	free(core);
	assembly_free(&a);
}

static void test_distributions(void)
{
	psd d;
	psd_uniform(&d, 0.0004, 0.0012);
	check_sizes("uniform", "--rmin 0.0004 --rmax 0.0012", &d);
	psd_uniform(&d, 0.0008 * 0.75, 0.0008 * 1.25);
	check_sizes("fuzz", "--dist fuzz --radius 0.0008 --fuzz 0.25", &d);
	psd_lognormal(&d, 0.0007, 0.25);
	check_sizes("lognormal", "--dist lognormal --radius 0.0007 --sigma 0.25", &d);
	const char *mix = check_tmp("sizes_mix.json");
	FILE *f = fopen(mix, "w");
	fputs("{\"sieve\": [0.0008, 0.0012, 0.0016, 0.0024], \"passing\": [0, 0.3, 0.6, 1]}", f);
	fclose(f);
	cfg *c = cfg_load(mix);
	CHECK(psd_grading(&d, c) == 0);
	cfg_free(c);
	char args[1200];
	snprintf(args, sizeof args, "--dist grading --grading %s", mix);
	check_sizes("grading", args, &d);
	psd_free(&d);
}

static void test_count_and_mean(void)
{
	const char *path = check_tmp("sizes.h5");
	harness_result r = run_pack("--quiet " BOX " --count 3000 %s", path);
	CHECK(r.status == 0);
	harness_free(&r);
	dem_assembly a;
	CHECK(assembly_read(path, &a) == 0);
	printf("--count 3000: %zu spheres\n", a.n);
	CHECK_REL((double)a.n, 3000, 0.02);
	assembly_free(&a);
	r = run_pack("--quiet " BOX " --mean-radius 0.0008 %s", path);
	CHECK(r.status == 0);
	harness_free(&r);
	CHECK(assembly_read(path, &a) == 0);
	double sum = 0;
	size_t m = 0;
	for (size_t i = 0; i < a.n; i++)
		if (depth(a.x + 3 * i) > 4 * a.report.mean_radius) {
			sum += a.r[i];
			m++;
		}
	printf("--mean-radius 0.0008: %.4g m in the core\n", sum / (double)m);
	CHECK_REL(sum / (double)m, 0.0008, 0.03);
	assembly_free(&a);
}

int main(void)
{
	test_distributions();
	test_count_and_mean();
	return check_done();
}
