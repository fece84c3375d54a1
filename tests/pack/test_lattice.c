/* --arrangement hcp end to end, measured from the written spheres: every
 * sphere lies wholly inside the specimen; deep inside, each touches exactly
 * 12 others and none overlaps; the centres in a box of whole lattice
 * periods around the middle number 4 per period, the solid fraction
 * pi / (3 sqrt 2) = 0.7405 of the hexagonal close packing; --count reaches
 * its count; sizes other than equal spheres are refused. */
#include "tests/pack/run.h"

#include "lib/err.h"
#include "pack/lattice.h"

static const double R = 0.0005, HALF = 0.008; /* m: spheres in a 16 mm cube */

static int read_pack(const char *args, dem_assembly *a)
{
	const char *path = check_tmp("lattice.h5");
	harness_result r = run_pack("--quiet --arrangement hcp %s %s", args, path);
	int ok = r.status == 0;
	if (!ok)
		printf("pack %s: %s", args, r.err);
	harness_free(&r);
	return ok && assembly_read(path, a) == 0 ? 0 : -1;
}

static double dist(const dem_assembly *a, size_t i, size_t j)
{
	double d2 = 0;
	for (int k = 0; k < 3; k++)
		d2 += (a->x[3 * i + k] - a->x[3 * j + k]) * (a->x[3 * i + k] - a->x[3 * j + k]);
	return sqrt(d2);
}

/* The sphere nearest the origin (the middle of the specimen). */
static size_t middle(const dem_assembly *a)
{
	size_t best = 0;
	for (size_t i = 1; i < a->n; i++)
		if (hypot(hypot(a->x[3 * i], a->x[3 * i + 1]), a->x[3 * i + 2]) <
		    hypot(hypot(a->x[3 * best], a->x[3 * best + 1]), a->x[3 * best + 2]))
			best = i;
	return best;
}

static void test_box(void)
{
	dem_assembly a;
	if (read_pack("--shape box --length 0.016 --width 0.016 --height 0.016 --radius 0.0005",
	              &a)) {
		CHECK(0);
		return;
	}
	int outside = 0;
	for (size_t i = 0; i < a.n; i++) {
		CHECK(a.r[i] == R);
		for (int k = 0; k < 3; k++)
			outside += fabs(a.x[3 * i + k]) + R > HALF * (1 + 1e-9);
	}
	CHECK(outside == 0);
	/* Deep inside (the 12 neighbours are all in): touching neighbours. */
	size_t deep = 0;
	int bad = 0;
	for (size_t i = 0; i < a.n; i++) {
		double depth =
		    HALF - fmax(fabs(a.x[3 * i]), fmax(fabs(a.x[3 * i + 1]), fabs(a.x[3 * i + 2])));
		if (depth < 4 * R)
			continue;
		int touch = 0;
		for (size_t j = 0; j < a.n; j++) {
			double d = j == i ? INFINITY : dist(&a, i, j);
			touch += fabs(d - 2 * R) < 1e-9 * R;
			bad += d < 2 * R * (1 - 1e-9);
		}
		bad += touch != 12;
		deep++;
	}
	printf("box: %zu spheres, %zu deep inside, %d with other than 12 touching neighbours "
	       "or an overlap\n",
	       a.n, deep, bad);
	CHECK(deep > 500);
	CHECK(bad == 0);
	/* Whole periods (2r along x, 2 sqrt(3) r along y, two layers of
	 * 2 sqrt(6)/3 r along z) from a middle sphere, shifted by half the
	 * smallest spacing of the centres in each direction so that no centre
	 * lies on the box's faces: 4 centres per period exactly. */
	size_t m = middle(&a);
	const double period[3] = {2 * R, 2 * sqrt(3.0) * R, 4 * sqrt(6.0) / 3 * R};
	const double shift[3] = {R / 2, sqrt(3.0) / 6 * R, sqrt(6.0) / 3 * R};
	const int periods[3] = {6, 3, 2};
	double lo[3], hi[3], volume = 1;
	for (int k = 0; k < 3; k++) {
		lo[k] = a.x[3 * m + k] - periods[k] / 2 * period[k] + shift[k];
		hi[k] = lo[k] + periods[k] * period[k];
		volume *= hi[k] - lo[k];
	}
	size_t in = 0;
	for (size_t i = 0; i < a.n; i++) {
		int inside = 1;
		for (int k = 0; k < 3; k++)
			inside &= a.x[3 * i + k] > lo[k] && a.x[3 * i + k] < hi[k];
		in += (size_t)inside;
	}
	double phi = (double)in * 4.0 / 3.0 * M_PI * R * R * R / volume;
	printf("box: %zu centres in %d x %d x %d periods: solid fraction %.6f (hcp %.6f)\n", in,
	       periods[0], periods[1], periods[2], phi, LATTICE_PHI_HCP);
	CHECK(in == 4 * 6 * 3 * 2);
	CHECK_REL(phi, M_PI / (3 * sqrt(2.0)), 1e-9);
	CHECK_NEAR(a.report.coordination_core, 12, 1e-9);
	assembly_free(&a);
}

/* A cylinder: every sphere within the circle and the ends, the layers at
 * whole spacings 2 sqrt(6)/3 r from the bottom face (Yade's regularHexa
 * starts its lattice at the lower corner of the bounding box), --count
 * within a few percent. */
static void test_cylinder(void)
{
	dem_assembly a;
	if (read_pack("--diameter 0.02 --height 0.03 --count 4000", &a)) {
		CHECK(0);
		return;
	}
	double r = a.r[0], layer = 2 * sqrt(6.0) / 3 * r;
	int outside = 0, off_layer = 0;
	for (size_t i = 0; i < a.n; i++) {
		outside += hypot(a.x[3 * i], a.x[3 * i + 1]) + r > 0.01 * (1 + 1e-9) ||
		           fabs(a.x[3 * i + 2]) + r > 0.015 * (1 + 1e-9);
		double k = (a.x[3 * i + 2] + 0.015) / layer;
		off_layer += fabs(k - round(k)) > 1e-9;
	}
	printf("cylinder --count 4000: %zu spheres of radius %.4g mm, solid fraction %.4f, "
	       "%d outside\n",
	       a.n, 1e3 * r, a.report.solid_fraction, outside);
	CHECK(outside == 0);
	CHECK(off_layer == 0);
	CHECK_REL((double)a.n, 4000, 0.03);
	assembly_free(&a);
}

static void test_refused(void)
{
	const char *path = check_tmp("lattice_bad.h5");
	harness_result r = run_pack("--arrangement hcp --dist fuzz --fuzz 0.2 %s", path);
	CHECK(r.status == 1);
	CHECK_CONTAINS(r.err, "--arrangement hcp places equal spheres: --fuzz 0.2: expected 0");
	harness_free(&r);
	r = run_pack("--arrangement hcp --dist lognormal %s", path);
	CHECK(r.status == 1);
	CHECK_CONTAINS(r.err, "--dist lognormal with its sizes does not apply");
	harness_free(&r);
	r = run_pack("--arrangement hexagonal %s", path);
	CHECK(r.status == 2);
	CHECK_CONTAINS(r.err, "--arrangement hexagonal: expected random or hcp");
	harness_free(&r);
	CHECK(!harness_exists(path));
}

int main(void)
{
	test_box();
	test_cylinder();
	test_refused();
	return check_done();
}
