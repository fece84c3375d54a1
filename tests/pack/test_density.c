/* The reference case of the density figures: cylinder 50 x 100 mm, radii
 * uniform in [0.5, 1.5] mm (about 24 000 spheres). Everything is measured
 * again from the written spheres with the cylinder's exact distance
 * function, independently of pack's own report (which must agree):
 *   total solid fraction >= 0.62, core (deeper than 2 mean diameters)
 *   >= 0.64 (Monte Carlo), wall deficit delta* <= 0.15 mean diameters,
 *   core fabric anisotropy < 0.05, largest overlap < 1 % of the smaller
 *   radius, every sphere inside.
 * The case is large enough for every parallel loop to run on threads: it
 * is packed on two threads and again on one, and the spheres must be the
 * same to the bit. */
#include "tests/pack/run.h"

#include "lib/err.h"
#include "lib/rng.h"

enum { BINS = 20, SAMPLES = 2000000 };

static const double R = 0.025, H = 0.1;

static double depth(const double p[3])
{
	return fmin(R - sqrt(p[0] * p[0] + p[1] * p[1]), 0.5 * H - fabs(p[2]));
}

/* Spheres sorted into cubic cells of edge >= 2 r_max + a margin. */
typedef struct {
	double edge;
	int dim;
	long *head, *next;
} grid;

static void grid_build(grid *g, const dem_assembly *a, double edge)
{
	g->edge = edge;
	g->dim = (int)ceil(H / edge) + 2;
	size_t ncell = (size_t)g->dim * (size_t)g->dim * (size_t)g->dim;
	g->head = malloc(ncell * sizeof *g->head);
	g->next = malloc(a->n * sizeof *g->next);
	for (size_t c = 0; c < ncell; c++)
		g->head[c] = -1;
	for (size_t i = 0; i < a->n; i++) {
		int c[3];
		for (int k = 0; k < 3; k++)
			c[k] = (int)floor((a->x[3 * i + k] + 0.5 * H) / edge) + 1;
		size_t id =
		    ((size_t)c[2] * (size_t)g->dim + (size_t)c[1]) * (size_t)g->dim + (size_t)c[0];
		g->next[i] = g->head[id];
		g->head[id] = (long)i;
	}
}

/* The spheres in the 27 cells around p (at most max of them). */
static size_t grid_near(const grid *g, const double p[3], long *out, size_t max)
{
	int c0[3];
	for (int k = 0; k < 3; k++)
		c0[k] = (int)floor((p[k] + 0.5 * H) / g->edge) + 1;
	size_t n = 0;
	for (int dz = -1; dz <= 1; dz++)
		for (int dy = -1; dy <= 1; dy++)
			for (int dx = -1; dx <= 1; dx++) {
				size_t id =
				    ((size_t)(c0[2] + dz) * (size_t)g->dim + (size_t)(c0[1] + dy)) *
				        (size_t)g->dim +
				    (size_t)(c0[0] + dx);
				for (long j = g->head[id]; j >= 0 && n < max; j = g->next[j])
					out[n++] = j;
			}
	return n;
}

int main(void)
{
	const char *path = check_tmp("reference.h5");
	harness_result r =
	    run_pack("--quiet --diameter 0.05 --height 0.1 --rmin 0.0005 --rmax 0.0015 %s", path);
	CHECK(r.status == 0);
	harness_free(&r);
	dem_assembly a;
	if (assembly_read(path, &a)) {
		fprintf(stderr, "%s\n", err_msg());
		return check_done() | 1;
	}
	double vs = 0, rsum = 0, rmax = 0, inside = INFINITY;
	for (size_t i = 0; i < a.n; i++) {
		vs += 4.0 / 3.0 * M_PI * a.r[i] * a.r[i] * a.r[i];
		rsum += a.r[i];
		rmax = fmax(rmax, a.r[i]);
		inside = fmin(inside, depth(a.x + 3 * i) / a.r[i] - 1);
	}
	double phi = vs / (M_PI * R * R * H), dmean = 2 * rsum / (double)a.n, wc = 2 * dmean;
	printf("%zu spheres, solid fraction %.4f\n", a.n, phi);
	CHECK(a.n > 20000 && a.n < 32000);
	CHECK(phi >= 0.62);
	CHECK_NEAR(a.report.solid_fraction, phi, 1e-12);
	CHECK(inside > -0.01);

	/* Monte Carlo: uniform points in the cylinder, binned by depth. */
	grid g;
	grid_build(&g, &a, 2 * rmax);
	double hit[BINS + 1] = {0}, all[BINS + 1] = {0}, dw = wc / BINS;
	rng gen;
	rng_seed(&gen, 12345);
	for (long s = 0; s < SAMPLES; s++) {
		double p[3] = {rng_range(&gen, -R, R), rng_range(&gen, -R, R),
		               rng_range(&gen, -0.5 * H, 0.5 * H)};
		double w = depth(p);
		if (w < 0)
			continue;
		int b = w >= wc ? BINS : (int)(w / dw);
		int covered = 0;
		long near[512];
		size_t nn = grid_near(&g, p, near, 512);
		for (size_t q = 0; q < nn; q++) {
			long j = near[q];
			double d[3] = {p[0] - a.x[3 * j], p[1] - a.x[3 * j + 1],
			               p[2] - a.x[3 * j + 2]};
			covered |= d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < a.r[j] * a.r[j];
		}
		all[b] += 1;
		hit[b] += covered;
	}
	double core = hit[BINS] / all[BINS], deficit = 0;
	for (int b = 0; b < BINS; b++)
		deficit += (core - hit[b] / all[b]) * dw;
	deficit /= dmean;
	printf("core %.4f (report %.4f), delta* %.3f d (report %.3f)\n", core,
	       a.report.solid_fraction_core, deficit, a.report.wall_deficit);
	CHECK(core >= 0.64);
	CHECK(deficit <= 0.15);
	CHECK_NEAR(a.report.solid_fraction_core, core, 0.004);
	CHECK_NEAR(a.report.wall_deficit, deficit, 0.02);

	/* Overlaps and the fabric of the core's pairs within (1 + beta)(ri + rj). */
	double ov = run_max_overlap(&a), f[3][3] = {{0}}, pairs = 0, beta = a.report.beta;
	for (size_t i = 0; i < a.n; i++) {
		if (depth(a.x + 3 * i) < wc)
			continue;
		long near[512];
		size_t nn = grid_near(&g, a.x + 3 * i, near, 512);
		for (size_t q = 0; q < nn; q++) {
			long j = near[q];
			if ((size_t)j <= i || depth(a.x + 3 * j) < wc)
				continue;
			double d[3] = {a.x[3 * j] - a.x[3 * i], a.x[3 * j + 1] - a.x[3 * i + 1],
			               a.x[3 * j + 2] - a.x[3 * i + 2]};
			double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
			if (dist > (1 + beta) * (a.r[i] + a.r[j]))
				continue;
			for (int k = 0; k < 3; k++)
				for (int l = 0; l < 3; l++)
					f[k][l] += d[k] * d[l] / (dist * dist);
			pairs += 1;
		}
	}
	double dd = 0;
	for (int k = 0; k < 3; k++)
		for (int l = 0; l < 3; l++) {
			double dev = f[k][l] / pairs - (k == l ? 1.0 / 3.0 : 0);
			dd += dev * dev;
		}
	double aniso = sqrt(1.5 * dd);
	printf("largest overlap %.3f %%, core anisotropy %.4f (report %.4f)\n", 100 * ov, aniso,
	       a.report.fabric_anisotropy);
	CHECK(ov < 0.01);
	CHECK_NEAR(a.report.overlap_max, ov, 1e-9);
	CHECK(aniso < 0.05);
	CHECK_NEAR(a.report.fabric_anisotropy, aniso, 1e-3);

	/* Bonds per sphere, over all, the core and the boundary layer (centres
	 * less than half a mean diameter deep), and the spheres without one. */
	double ends[3] = {0}, members[3] = {0}, unbonded = 0;
	for (size_t i = 0; i < a.n; i++) {
		long near[512];
		size_t nn = grid_near(&g, a.x + 3 * i, near, 512), bonds = 0;
		for (size_t q = 0; q < nn; q++) {
			long j = near[q];
			double d[3] = {a.x[3 * j] - a.x[3 * i], a.x[3 * j + 1] - a.x[3 * i + 1],
			               a.x[3 * j + 2] - a.x[3 * i + 2]};
			double sum = (1 + beta) * (a.r[i] + a.r[j]);
			bonds +=
			    (size_t)j != i && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= sum * sum;
		}
		double w = depth(a.x + 3 * i);
		int layer[3] = {1, w >= wc, w < 0.5 * dmean};
		for (int k = 0; k < 3; k++) {
			ends[k] += layer[k] * (double)bonds;
			members[k] += layer[k];
		}
		unbonded += bonds == 0;
	}
	printf("coordination %.3f, core %.3f, boundary layer %.3f (%.0f spheres), %.0f "
	       "unbonded (report %.3f %.3f %.3f %.0f)\n",
	       ends[0] / members[0], ends[1] / members[1], ends[2] / members[2], members[2],
	       unbonded, a.report.coordination, a.report.coordination_core,
	       a.report.coordination_boundary, a.report.unbonded);
	CHECK_NEAR(a.report.coordination, ends[0] / members[0], 1e-12);
	CHECK_NEAR(a.report.coordination_core, ends[1] / members[1], 0.01);
	CHECK_NEAR(a.report.coordination_boundary, ends[2] / members[2], 0.01);
	CHECK(a.report.unbonded == unbonded);
	CHECK(a.report.coordination_core > a.report.coordination);
	CHECK(a.report.coordination_boundary < a.report.coordination);
	free(g.head);
	free(g.next);
	assembly_free(&a);
	return check_done();
}
