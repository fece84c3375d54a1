/* Running the pack program from a test (tests/harness.h); assemblies it
 * writes are checked with an independent brute-force pass. */
#ifndef DEM_TESTS_PACK_RUN_H
#define DEM_TESTS_PACK_RUN_H

#include <math.h>
#include <stdlib.h>

#include "lib/assembly.h"
#include "tests/harness.h"

/* Run "pack <args>" (args formatted printf-style) from the source root. */
#define run_pack(...) harness_run("pack", __VA_ARGS__)

static const double *run_sort_x;
static inline int run_cmp_x(const void *a, const void *b)
{
	double u = run_sort_x[3 * *(const size_t *)a], v = run_sort_x[3 * *(const size_t *)b];
	return (u > v) - (u < v);
}

/* Largest overlap of any pair relative to the smaller radius, by sweeping
 * the spheres sorted along x. */
static inline double run_max_overlap(const dem_assembly *a)
{
	size_t n = a->n, *o = malloc(n * sizeof *o + 1);
	double rmax = 0, worst = 0;
	for (size_t i = 0; i < n; i++) {
		o[i] = i;
		rmax = fmax(rmax, a->r[i]);
	}
	run_sort_x = a->x;
	qsort(o, n, sizeof *o, run_cmp_x);
	for (size_t p = 0; p < n; p++)
		for (size_t q = p + 1; q < n; q++) {
			size_t i = o[p], j = o[q];
			double dx = a->x[3 * j] - a->x[3 * i];
			if (dx > 2 * rmax)
				break;
			double dy = a->x[3 * j + 1] - a->x[3 * i + 1],
			       dz = a->x[3 * j + 2] - a->x[3 * i + 2];
			double d = sqrt(dx * dx + dy * dy + dz * dz);
			worst = fmax(worst, (a->r[i] + a->r[j] - d) / fmin(a->r[i], a->r[j]));
		}
	free(o);
	return worst;
}

#endif
