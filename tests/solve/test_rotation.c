/* A specimen and its loading rotated together by an arbitrary rotation give
 * the same test: the same stress–strain curve, radial strain and energies
 * to 1e-9 relative, and a Love–Weber stress tensor rotated with it. Only
 * round-off differs (the particle order and the cell grid change with the
 * rotation), so the engine has no hidden preferred direction. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lib/runfile.h"
#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

static const char *case_text =
    "{\"assembly\": \"%s\", \"material\": {\"name\": \"elastic\", \"law\": \"linear\", "
    "\"density\": 2500, \"E\": 1e10, \"nu\": 0.25, \"tensile_strength\": 1e12, "
    "\"shear_strength\": 1e12, \"contact\": {\"friction\": 0.4, \"platen_friction\": 0.2}},"
    "\"output\": {\"history_every\": 100},"
    "\"loading\": [{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 2}}], %s"
    "\"stop\": {\"strain_axial\": 2e-3}}";

static void run(const dem_assembly *a, const char *name, const char *extra, dem_run *out)
{
	char file[64], json[2048], args[1024];
	snprintf(file, sizeof file, "%s.h5", name);
	const char *apath = check_tmp(file);
	fixture_write(a, apath);
	snprintf(json, sizeof json, case_text, apath, extra);
	snprintf(file, sizeof file, "%s.json", name);
	const char *cpath = harness_file(file, json);
	snprintf(file, sizeof file, "%s-run.h5", name);
	const char *rpath = check_tmp(file);
	snprintf(args, sizeof args, "--quiet --output %s %s", rpath, cpath);
	CHECK(harness_solve(args) == 0);
	harness_read(rpath, out);
}

/* Largest difference between two columns, relative to the column's scale. */
static double column_diff(const double *x, const double *y, size_t n)
{
	double scale = 0, diff = 0;
	for (size_t k = 0; k < n; k++) {
		scale = fmax(scale, fabs(x[k]));
		diff = fmax(diff, fabs(x[k] - y[k]));
	}
	return scale > 0 ? diff / scale : diff;
}

static void tensor(const dem_run *r, size_t row, double s[9])
{
	static const char *names[6] = {"stress_xx", "stress_yy", "stress_zz",
	                               "stress_xy", "stress_yz", "stress_xz"};
	static const int at[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
	for (int c = 0; c < 6; c++) {
		double v = run_column_data(r, names[c])[row];
		s[3 * at[c][0] + at[c][1]] = s[3 * at[c][1] + at[c][0]] = v;
	}
}

/* The rotated run against the plain one: invariant columns equal, the
 * stress tensor rotated by R. */
static void compare(const dem_run *plain, const dem_run *turned, const double R[9])
{
	CHECK(plain->nrows == turned->nrows && plain->nrows > 10);
	if (plain->nrows != turned->nrows)
		return;
	static const char *invariant[] = {"strain_axial",    "stress_axial",   "stress_bottom",
	                                  "stress_top",      "strain_radial",  "strain_volumetric",
	                                  "energy_kinetic",  "energy_elastic", "energy_damped",
	                                  "energy_friction", "energy_work",    "bonds_intact",
	                                  "contacts",        "contacts_platen"};
	for (size_t c = 0; c < sizeof invariant / sizeof *invariant; c++) {
		double d = column_diff(run_column_data(plain, invariant[c]),
		                       run_column_data(turned, invariant[c]), plain->nrows);
		fprintf(stderr, "%-18s relative difference %.3g\n", invariant[c], d);
		CHECK(d <= 1e-9);
	}
	double worst = 0, scale = 0;
	for (size_t k = 0; k < plain->nrows; k++) {
		double s[9], t[9], rs[9] = {0};
		tensor(plain, k, s);
		tensor(turned, k, t);
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++)
				for (int p = 0; p < 3; p++)
					for (int q = 0; q < 3; q++)
						rs[3 * i + j] +=
						    R[3 * i + p] * s[3 * p + q] * R[3 * j + q];
		for (int c = 0; c < 9; c++) {
			scale = fmax(scale, fabs(s[c]));
			worst = fmax(worst, fabs(rs[c] - t[c]));
		}
	}
	fprintf(stderr, "Love-Weber tensor   relative difference %.3g (scale %.3g Pa)\n",
	        worst / scale, scale);
	CHECK(scale > 1e5);
	CHECK(worst <= 1e-9 * scale);
}

int main(void)
{
	lattice l = {.kind = LATTICE_FCC,
	             .nx = 6,
	             .ny = 6,
	             .nz = 9,
	             .r = 1e-3,
	             .jitter = 0.03,
	             .polydisp = 0.05,
	             .diameter = 0.016,
	             .seed = 11};
	dem_assembly a;
	fixture_lattice(&a, &l);
	dem_run plain, turned, axis;
	run(&a, "rot-plain", "", &plain);
	CHECK(run_column_data(&plain, "stress_axial")[plain.nrows - 1] > 1e5);
	double R[9];
	fixture_rotation((double[3]){0.3, -0.7, 0.5}, 2.1, R);
	fixture_rotate(&a, R);
	run(&a, "rot-turned", "", &turned);
	compare(&plain, &turned, R);
	/* The same rotated specimen, its geometry saying z, the case giving the
	 * loading axis. */
	char extra[256];
	snprintf(extra, sizeof extra, "\"axis\": [%.17g, %.17g, %.17g], ", a.geom.axis[0],
	         a.geom.axis[1], a.geom.axis[2]);
	a.geom.axis[0] = a.geom.axis[1] = 0;
	a.geom.axis[2] = 1;
	run(&a, "rot-axis", extra, &axis);
	compare(&plain, &axis, R);
	run_free(&plain);
	run_free(&turned);
	run_free(&axis);
	assembly_free(&a);
	return check_done();
}
