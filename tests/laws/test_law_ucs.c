/* Each law runs in solve from its shipped material file: a short UCS of a
 * small jittered FCC cylinder goes past its peak, bonds fail in the law's
 * modes, every failure is in the crack log, and the energy the law books
 * (elastic, viscous, fracture, friction) closes the balance with the work
 * of the platens to 1 %. The strain rate (3/s) keeps the runs short and
 * quasi-static by post summary's measure: on the loading branch (from half
 * the peak to the peak) the kinetic energy stays below 5 % of the elastic
 * energy. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

static double last(const dem_run *r, const char *col)
{
	return run_column_data(r, col)[r->nrows - 1];
}

static void ucs(const char *assembly, const char *material, const char *law)
{
	char cwd[1024], text[4096], args[4096], name[256];
	CHECK(getcwd(cwd, sizeof cwd) != NULL);
	snprintf(text, sizeof text,
	         "{\"test\": \"ucs\", \"material\": \"%s/share/materials/%s\","
	         " \"damping\": {\"translational\": 0.1, \"rotational\": 0.1},"
	         " \"output\": {\"history_every\": 100},"
	         " \"loading\": [{\"name\": \"axial\", \"axial\": {\"mode\": \"strain_rate\","
	         " \"rate\": 3.0}}], \"stop\": {\"strain_axial\": 0.01, \"stress_drop\": 0.7}}",
	         cwd, material);
	snprintf(name, sizeof name, "ucs-%s.json", law);
	const char *casefile = harness_file(name, text);
	snprintf(name, sizeof name, "ucs-%s.h5", law);
	const char *out = check_tmp(name);
	snprintf(args, sizeof args, "--quiet --threads 1 --assembly %s --output %s %s", assembly,
	         out, casefile);
	CHECK(harness_solve(args) == 0);
	dem_run r;
	harness_read(out, &r);
	char lawkey[64];
	snprintf(lawkey, sizeof lawkey, "\"law\":\t\"%s\"", law);
	CHECK_CONTAINS(r.prov.config, lawkey);
	size_t n = r.nrows, peak = 0;
	const double *stress = run_column_data(&r, "stress_axial");
	for (size_t k = 0; k < n; k++)
		peak = stress[k] > stress[peak] ? k : peak;
	const double *kinetic = run_column_data(&r, "energy_kinetic"),
	             *elastic = run_column_data(&r, "energy_elastic");
	double dynamic = 0;
	for (size_t k = 0; k <= peak; k++)
		if (stress[k] >= 0.5 * stress[peak] && elastic[k] > 0)
			dynamic = fmax(dynamic, kinetic[k] / elastic[k]);
	double bt = last(&r, "bonds_broken_tension"), bs = last(&r, "bonds_broken_shear");
	double in = last(&r, "energy_work");
	double kept = last(&r, "energy_kinetic") + last(&r, "energy_elastic") +
	              last(&r, "energy_damped") + last(&r, "energy_friction") +
	              last(&r, "energy_fracture");
	fprintf(stderr,
	        "%s: %s; peak %.4g MPa at row %zu of %zu; broken %g in tension, %g in shear; "
	        "work %.4g J, stored + dissipated %.4g J (fracture %.3g J); kinetic / elastic "
	        "%.3g\n",
	        law, r.status, 1e-6 * stress[peak], peak, n, bt, bs, in, kept,
	        last(&r, "energy_fracture"), dynamic);
	CHECK_CONTAINS(r.status, "stopped: axial stress fell below 0.7 of the peak");
	CHECK(stress[peak] > 1e6 && stress[peak] < 1e9);
	CHECK(peak > 0 && peak < n - 1);
	CHECK(dynamic < 0.05);
	CHECK(bt > 0 && bt + bs > 0.05 * r.bonds.n);
	CHECK(r.ncracks >= (size_t)(bt + bs));
	CHECK(last(&r, "energy_fracture") > 0);
	CHECK(fabs(in - kept) < 0.01 * in);
	run_free(&r);
}

int main(void)
{
	lattice l = {.kind = LATTICE_FCC,
	             .nx = 5,
	             .ny = 5,
	             .nz = 8,
	             .r = 1e-3,
	             .jitter = 0.03,
	             .polydisp = 0.03,
	             .diameter = 0.0125,
	             .seed = 5};
	dem_assembly a;
	fixture_lattice(&a, &l);
	const char *apath = check_tmp("laws-ucs-assembly.h5");
	fixture_write(&a, apath);
	ucs(apath, "concrete.json", "onate");
	ucs(apath, "concrete-jcfpm.json", "jcfpm");
	ucs(apath, "concrete-exponential.json", "exponential");
	assembly_free(&a);
	return check_done();
}
