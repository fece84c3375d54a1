/* The shipped demo case, a UCS of a few thousand spheres with the paper's
 * law (onate, the cement of Tables 2-3), runs from the command line past
 * its peak and writes a valid run file:
 * status, provenance with the material resolved, the bond table, a history
 * with a stress peak, bonds broken in both modes, the crack log and
 * snapshots enough to watch the cracks grow (20 or more); the energy
 * balance closes (work in = kinetic + elastic +
 * dissipated, to 1 %). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

int main(void)
{
	dem_assembly a;
	fixture_cylinder(&a, 1);
	const char *apath = check_tmp("demo-assembly.h5"), *out = check_tmp("demo-run.h5");
	fixture_write(&a, apath);
	char args[2048];
	snprintf(args, sizeof args, "--quiet --assembly %s --output %s share/cases/demo-ucs.json",
	         apath, out);
	CHECK(harness_solve(args) == 0);
	dem_run r;
	harness_read(out, &r);
	fprintf(stderr, "%s: %zu particles, %zu bonds, %zu rows, %zu cracks, %zu snapshots\n",
	        r.status, r.assembly.n, r.bonds.n, r.nrows, r.ncracks, r.nsnap);
	CHECK_CONTAINS(r.status, "stopped: axial stress fell below 0.7 of the peak");
	CHECK_STR(r.prov.program, "solve");
	CHECK_CONTAINS(r.prov.config, "\"law\":\t\"onate\"");
	CHECK(r.assembly.n == a.n && r.bonds.n > 5 * a.n);
	size_t n = r.nrows, peak = 0;
	const double *stress = run_column_data(&r, "stress_axial");
	const double *strain = run_column_data(&r, "strain_axial");
	for (size_t k = 0; k < n; k++)
		peak = stress[k] > stress[peak] ? k : peak;
	fprintf(stderr, "peak %.4g MPa at strain %.4g; last %.4g MPa at %.4g\n",
	        1e-6 * stress[peak], strain[peak], 1e-6 * stress[n - 1], strain[n - 1]);
	CHECK(stress[peak] > 5e6);
	CHECK(peak > 0 && peak < n - 1);
	/* The stop rule is checked every step; the last snapshot is the last step
	 * (the history has a row every 100 steps). */
	double last = r.snap_stress[r.nsnap - 1];
	fprintf(stderr, "final snapshot: %.4g MPa\n", 1e-6 * last);
	CHECK(last < 0.7 * stress[peak] && last > 0.5 * stress[peak]);
	const double *t = run_column_data(&r, "t");
	for (size_t k = 1; k < n; k++)
		CHECK(t[k] > t[k - 1]);
	double bt = run_column_data(&r, "bonds_broken_tension")[n - 1];
	double bs = run_column_data(&r, "bonds_broken_shear")[n - 1];
	CHECK(bt > 0 && bs > 0);
	/* Every failure is in the crack log (up to the last row's step). */
	CHECK(r.ncracks >= (size_t)(bt + bs));
	CHECK(r.nsnap >= 20);
	double in = run_column_data(&r, "energy_work")[n - 1];
	double kept = run_column_data(&r, "energy_kinetic")[n - 1] +
	              run_column_data(&r, "energy_elastic")[n - 1] +
	              run_column_data(&r, "energy_damped")[n - 1] +
	              run_column_data(&r, "energy_friction")[n - 1] +
	              run_column_data(&r, "energy_fracture")[n - 1];
	fprintf(stderr, "energy: work %.6g J, accounted %.6g J\n", in, kept);
	CHECK_REL(kept, in, 0.01);
	run_free(&r);
	assembly_free(&a);
	return check_done();
}
