/* A simple cubic lattice of n x n x n touching spheres (spacing d = 2r),
 * bonds of normal stiffness K_n between nearest neighbours, compressed by
 * its end layers to a small strain and held until at rest. Its deformation
 * is affine (Poisson's ratio 0: lateral bonds stay unloaded, shear springs
 * untouched), so the moduli are exact:
 *   platen stress: n² columns of n-1 bonds in series over the area (n d)²,
 *   strain = Δ / (n d)  =>  E = K_n n / ((n - 1) d)
 *   Love–Weber: Σ l F over the n²(n-1) axial bonds, of current length
 *   l = d - Δ/(n-1) and force K_n Δ/(n-1), is n² l K_n Δ, divided by the
 *   volume the engine reports (history column "volume"); the lateral
 *   components vanish. */
#include <math.h>
#include <stdio.h>

#include "lib/runfile.h"
#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

int main(void)
{
	const int n = 6;
	const double r = 1e-3, d = 2 * r, kn = 1e6;
	lattice l = {.kind = LATTICE_SC, .nx = n, .ny = n, .nz = n, .r = r};
	dem_assembly a;
	fixture_lattice(&a, &l);
	const char *apath = check_tmp("lattice.h5");
	fixture_write(&a, apath);
	char json[2048];
	snprintf(json, sizeof json,
	         "{\"assembly\": \"%s\", \"material\": {\"name\": \"sc\", \"law\": \"linear\", "
	         "\"density\": 2500, \"kn\": %g, \"ks\": 4e5, \"tensile_strength\": 1e12, "
	         "\"shear_strength\": 1e12},"
	         "\"damping\": {\"translational\": 0.5, \"rotational\": 0.5},"
	         "\"output\": {\"history_every\": 50},"
	         "\"loading\": ["
	         " {\"axial\": {\"mode\": \"layers\", \"rate\": 0.25, \"thickness\": %g},"
	         "  \"until\": {\"strain_axial\": 1e-4}},"
	         " {\"axial\": {\"mode\": \"layers\", \"rate\": 0}, \"until\": {\"time\": 2e-3}}]}",
	         apath, kn, r);
	const char *cpath = harness_file("lattice.json", json);
	char args[1024];
	const char *out = check_tmp("lattice-run.h5");
	snprintf(args, sizeof args, "--quiet --output %s %s", out, cpath);
	CHECK(harness_solve(args) == 0);
	dem_run run;
	harness_read(out, &run);
	CHECK_STR(run.status, "complete");
	size_t last = run.nrows - 1;
	double strain = run_column_data(&run, "strain_axial")[last];
	double stress = run_column_data(&run, "stress_axial")[last];
	double szz = run_column_data(&run, "stress_zz")[last];
	double sxx = run_column_data(&run, "stress_xx")[last];
	double volume = run_column_data(&run, "volume")[last];
	double ke = run_column_data(&run, "energy_kinetic")[last];
	double el = run_column_data(&run, "energy_elastic")[last];
	double e_want = kn * n / ((n - 1) * d);
	double delta = strain * n * d;
	double lw_want = n * n * (d - delta / (n - 1)) * kn * delta / volume;
	fprintf(stderr,
	        "strain %.6g: modulus %.8g Pa (analytic %.8g), Love-Weber %.8g Pa "
	        "(analytic %.8g), kinetic/elastic %.2g\n",
	        strain, stress / strain, e_want, szz, lw_want, ke / el);
	CHECK_REL(strain, 1e-4, 0.02);
	CHECK_REL(stress / strain, e_want, 1e-6);
	/* The load itself: n² columns of n - 1 bonds in series. */
	CHECK_REL(run_column_data(&run, "force_axial")[last], n * n * kn * strain * n * d / (n - 1),
	          1e-6);
	CHECK_REL(szz, lw_want, 1e-6);
	CHECK_NEAR(sxx, 0, 1e-9 * szz);
	CHECK_NEAR(run_column_data(&run, "strain_radial")[last], 0, 1e-12);
	CHECK(run.bonds.n == (size_t)(3 * n * n * (n - 1)));
	/* The measured load is the bonds' force on the layers, not the force
	 * that sets them moving: nothing at the start, and no jump when the
	 * second stage stops them. */
	const double *sa = run_column_data(&run, "stress_axial");
	const double *stage = run_column_data(&run, "stage");
	CHECK_NEAR(sa[0], 0, 1e-9 * stress);
	size_t hold = 1;
	while (hold < last && stage[hold] < 2)
		hold++;
	CHECK(stage[hold] == 2);
	CHECK(sa[hold] >= 0.9 * sa[hold - 1] && sa[hold] <= 1.1 * sa[hold - 1]);
	run_free(&run);
	assembly_free(&a);
	return check_done();
}
