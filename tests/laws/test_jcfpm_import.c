/* JCFPM on an imported sphere list, the way a Yade user brings an assembly
 * over: a list of lines "x y z r" goes through pack --import and solve runs
 * a UCS with the JCFPM concrete of seeds/002. The bonds are exactly the
 * pairs within the interaction range gamma (r_i + r_j) of the list, and the
 * specimen goes past its peak with bonds broken and logged. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "lib/rng.h"
#include "tests/check.h"
#include "tests/solve/harness.h"

enum { MAXS = 4000 };

/* A jittered hexagonal stack of spheres with gaps, inside a 12.5 x 25 mm
 * cylinder centred at the origin. */
static size_t sphere_list(const char *path, double x[][3], double r[])
{
	const double R = 0.8e-3, D = 0.0125, H = 0.025, a = 2.1 * R;
	rng g;
	rng_seed(&g, 9);
	size_t n = 0;
	FILE *f = fopen(path, "w");
	fprintf(f, "# x y z r (m)\n");
	for (int k = 0; k < 40; k++)
		for (int i = -10; i <= 10; i++)
			for (int j = -10; j <= 10; j++) {
				double p[3] = {(i + 0.5 * (k % 2)) * a, (j + 0.5 * (k % 2)) * a,
				               -H / 2 + R + k * a * 0.75};
				for (int c = 0; c < 3; c++)
					p[c] += 0.05 * R * rng_range(&g, -1, 1);
				double ri = R * rng_range(&g, 0.85, 1.0);
				if (hypot(p[0], p[1]) > D / 2 - ri || p[2] + ri > H / 2 ||
				    n == MAXS)
					continue;
				fprintf(f, "%.17g %.17g %.17g %.17g\n", p[0], p[1], p[2], ri);
				x[n][0] = p[0], x[n][1] = p[1], x[n][2] = p[2], r[n++] = ri;
			}
	fclose(f);
	return n;
}

int main(void)
{
	static double x[MAXS][3], r[MAXS];
	const char *list = check_tmp("jcfpm-spheres.txt"), *assembly = check_tmp("jcfpm-import.h5");
	const char *out = check_tmp("jcfpm-import-run.h5");
	size_t n = sphere_list(list, x, r);
	size_t pairs = 0;
	for (size_t i = 0; i < n; i++)
		for (size_t j = i + 1; j < n; j++) {
			double d = sqrt(pow(x[j][0] - x[i][0], 2) + pow(x[j][1] - x[i][1], 2) +
			                pow(x[j][2] - x[i][2], 2));
			pairs += d <= 1.4 * (r[i] + r[j]);
		}
	const char *bin = getenv("DEM_BIN");
	char cmd[4096], cwd[1024], text[2048];
	snprintf(cmd, sizeof cmd,
	         "%s/pack --quiet --import %s --diameter 0.0125 --height 0.025 --threads 1 %s",
	         bin && bin[0] ? bin : "build/bin", list, assembly);
	fprintf(stderr, "$ %s\n", cmd);
	CHECK(system(cmd) == 0);
	CHECK(getcwd(cwd, sizeof cwd) != NULL);
	snprintf(text, sizeof text,
	         "{\"test\": \"ucs\", \"material\": \"%s/share/materials/concrete-jcfpm.json\","
	         " \"damping\": {\"translational\": 0.4, \"rotational\": 0.4},"
	         " \"output\": {\"history_every\": 100},"
	         " \"loading\": [{\"name\": \"axial\", \"axial\": {\"mode\": \"strain_rate\","
	         " \"rate\": 1.0}}], \"stop\": {\"strain_axial\": 0.01, \"stress_drop\": 0.7}}",
	         cwd);
	const char *casefile = harness_file("jcfpm-import.json", text);
	snprintf(cmd, sizeof cmd, "--quiet --threads 1 --assembly %s --output %s %s", assembly, out,
	         casefile);
	CHECK(harness_solve(cmd) == 0);
	dem_run run;
	harness_read(out, &run);
	size_t rows = run.nrows, peak = 0;
	const double *stress = run_column_data(&run, "stress_axial");
	for (size_t k = 0; k < rows; k++)
		peak = stress[k] > stress[peak] ? k : peak;
	double bt = run_column_data(&run, "bonds_broken_tension")[rows - 1];
	double bs = run_column_data(&run, "bonds_broken_shear")[rows - 1];
	fprintf(stderr,
	        "%zu spheres, %zu bonds (%zu pairs within 1.4 (ri + rj)); %s; peak %.4g MPa; "
	        "broken %g in tension, %g in shear\n",
	        n, run.bonds.n, pairs, run.status, 1e-6 * stress[peak], bt, bs);
	CHECK(run.assembly.n == n);
	CHECK(run.bonds.n == pairs);
	CHECK_CONTAINS(run.status, "stopped: axial stress fell below 0.7 of the peak");
	CHECK(stress[peak] > 1e6 && peak > 0 && peak < rows - 1);
	CHECK(bt > 0 && run.ncracks >= (size_t)(bt + bs));
	run_free(&run);
	return check_done();
}
