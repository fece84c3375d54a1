/* The boundary-condition building blocks on an elastic cylinder:
 *   1. hydrostatic: lateral pressure p (tributary areas) and both platens
 *      servo-controlled to the axial stress p: the platen stress settles at
 *      p, the applied lateral force equals p times the current lateral area,
 *      and the average (Love–Weber) lateral stress is p;
 *   2. axial loading at constant confinement, 3. unloading by reversing the
 *      platens until the axial stress is back to p, 4. reloading past the
 *      first loading: each stage ends on its rule, the confinement stays p;
 *   5. the paper's confinement (π r² p on each surface particle) on equal
 *      spheres: the lateral force is a whole number of π r² p, visibly short
 *      of p times the lateral area;
 *   6. lateral constraint (uniaxial strain): the radial strain stays near
 *      zero, a confining pressure develops, and the axial stiffness exceeds
 *      that of the unconfined specimen (constrained modulus > Young's). */
#include <math.h>
#include <stdio.h>

#include "lib/runfile.h"
#include "lib/vec3.h"
#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

#define MATERIAL                                                                            \
	"\"material\": {\"name\": \"elastic\", \"law\": \"linear\", \"density\": 2500, "    \
	"\"E\": 1e10, \"nu\": 0.25, \"tensile_strength\": 1e12, \"shear_strength\": 1e12, " \
	"\"mu2\": 0.5}, \"damping\": {\"translational\": 0.3, \"rotational\": 0.3}, "       \
	"\"output\": {\"history_every\": 20}"

static const char *apath;

static void run(const char *name, const char *loading, dem_run *r)
{
	char json[4096], file[64], args[1024];
	snprintf(json, sizeof json, "{\"assembly\": \"%s\", " MATERIAL ", %s}", apath, loading);
	snprintf(file, sizeof file, "%s.json", name);
	const char *cpath = harness_file(file, json);
	snprintf(file, sizeof file, "%s.h5", name);
	const char *out = check_tmp(file);
	snprintf(args, sizeof args, "--quiet --output %s %s", out, cpath);
	CHECK(harness_solve(args) == 0);
	harness_read(out, r);
	fprintf(stderr, "%s: %s, %zu rows\n", name, r->status, r->nrows);
}

static double at(const dem_run *r, const char *col, size_t row)
{
	return run_column_data(r, col)[row];
}

/* Last row of a stage (1-based), or the last row. */
static size_t stage_end(const dem_run *r, int stage)
{
	const double *s = run_column_data(r, "stage");
	size_t last = 0;
	for (size_t k = 0; k < r->nrows; k++)
		if (s[k] == stage)
			last = k;
	return last;
}

int main(void)
{
	lattice l = {.kind = LATTICE_FCC,
	             .nx = 7,
	             .ny = 7,
	             .nz = 11,
	             .r = 1e-3,
	             .jitter = 0.02,
	             .polydisp = 0,
	             .diameter = 0.018,
	             .seed = 4};
	dem_assembly a;
	fixture_lattice(&a, &l);
	apath = check_tmp("bc.h5");
	fixture_write(&a, apath);
	fprintf(stderr, "%zu particles\n", a.n);
	const double p = 2e6;

	dem_run r;
	run("bc-triaxial",
	    "\"loading\": ["
	    "{\"name\": \"hydrostatic\", \"ramp\": 2e-4, \"axial\": {\"mode\": \"stress\", "
	    "\"stress\": 2e6, \"rate\": 2}, \"lateral\": {\"mode\": \"pressure\", \"method\": "
	    "\"tributary\", \"pressure\": "
	    "2e6}, "
	    "\"until\": {\"time\": 1e-3}},"
	    "{\"name\": \"axial\", \"axial\": {\"mode\": \"strain_rate\", \"rate\": 1}, "
	    "\"lateral\": {\"mode\": \"pressure\", \"method\": \"tributary\", \"pressure\": 2e6}, "
	    "\"until\": "
	    "{\"strain_axial\": "
	    "1.2e-3}},"
	    "{\"name\": \"unload\", \"axial\": {\"mode\": \"strain_rate\", \"rate\": -1}, "
	    "\"lateral\": {\"mode\": \"pressure\", \"method\": \"tributary\", \"pressure\": 2e6}, "
	    "\"until\": "
	    "{\"stress_axial\": "
	    "2e6}},"
	    "{\"name\": \"reload\", \"axial\": {\"mode\": \"strain_rate\", \"rate\": 1}, "
	    "\"lateral\": {\"mode\": \"pressure\", \"method\": \"tributary\", \"pressure\": 2e6}, "
	    "\"until\": "
	    "{\"strain_axial\": "
	    "1.5e-3}}]",
	    &r);
	CHECK_STR(r.status, "complete");
	size_t h = stage_end(&r, 1), ax = stage_end(&r, 2), un = stage_end(&r, 3),
	       re = stage_end(&r, 4);
	CHECK(h < ax && ax < un && un < re);
	double sxx = at(&r, "stress_xx", h), syy = at(&r, "stress_yy", h),
	       szz = at(&r, "stress_zz", h);
	fprintf(stderr,
	        "hydrostatic: platens %.4g / %.4g Pa, Love-Weber %.4g %.4g %.4g Pa, lateral force "
	        "%.6g N for %.6g N\n",
	        at(&r, "stress_bottom", h), at(&r, "stress_top", h), sxx, syy, szz,
	        at(&r, "lateral_force", h), at(&r, "lateral_force_target", h));
	CHECK_REL(at(&r, "stress_bottom", h), p, 0.01);
	CHECK_REL(at(&r, "stress_top", h), p, 0.01);
	CHECK_REL(at(&r, "lateral_force", h), at(&r, "lateral_force_target", h), 1e-12);
	CHECK_REL(at(&r, "pressure", h), p, 1e-12);
	CHECK_REL(sxx, p, 0.05);
	CHECK_REL(syy, p, 0.05);
	/* The axial stress of the platens is over the initial cross-section, the
	 * average stress over the volume the lateral surface encloses. */
	double height = a.geom.height * (1 - at(&r, "strain_axial", h));
	double area0 = a.geom.volume / a.geom.height;
	CHECK_REL(szz, p * area0 * height / at(&r, "volume", h), 0.02);
	CHECK(at(&r, "strain_volumetric", h) > 0);
	fprintf(stderr,
	        "axial %.4g at strain %.4g; unloaded to %.4g at %.4g; reloaded %.4g at %.4g\n",
	        at(&r, "stress_axial", ax), at(&r, "strain_axial", ax), at(&r, "stress_axial", un),
	        at(&r, "strain_axial", un), at(&r, "stress_axial", re), at(&r, "strain_axial", re));
	CHECK(at(&r, "strain_axial", ax) >= 1.2e-3 - 1e-5);
	CHECK(at(&r, "stress_axial", ax) > 2 * p);
	CHECK(at(&r, "stress_axial", un) < 1.1 * p);
	CHECK(at(&r, "strain_axial", un) < at(&r, "strain_axial", ax));
	CHECK(at(&r, "strain_axial", re) > at(&r, "strain_axial", ax));
	CHECK(at(&r, "stress_axial", re) > at(&r, "stress_axial", ax));
	CHECK_REL(at(&r, "pressure", re), p, 1e-12);
	CHECK(at(&r, "energy_work", re) > 0);
	run_free(&r);

	run("bc-paper",
	    "\"loading\": [{\"axial\": {\"mode\": \"hold\"}, \"lateral\": {\"mode\": \"pressure\", "
	    "\"pressure\": 2e6, \"method\": \"paper\"}}], \"stop\": {\"steps\": 200}",
	    &r);
	size_t k = r.nrows - 1;
	double count = at(&r, "lateral_force", k) / (p * DEM_PI * l.r * l.r);
	double share = at(&r, "lateral_force", k) / at(&r, "lateral_force_target", k);
	fprintf(stderr, "paper's method: %.12g surface particles, %.3f of p x lateral area\n",
	        count, share);
	CHECK_NEAR(count, round(count), 1e-9 * count);
	CHECK(count > 50);
	CHECK(share > 0.4 && share < 0.95);
	run_free(&r);

	dem_run free_run;
	run("bc-free",
	    "\"loading\": [{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 1}}], \"stop\": "
	    "{\"strain_axial\": 1e-3}",
	    &free_run);
	run("bc-constrained",
	    "\"loading\": [{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 1}, \"lateral\": "
	    "{\"mode\": \"constraint\"}}], \"stop\": {\"strain_axial\": 1e-3}",
	    &r);
	size_t kf = free_run.nrows - 1;
	k = r.nrows - 1;
	fprintf(stderr,
	        "free: stress %.4g, radial strain %.4g; constrained: stress %.4g, radial strain "
	        "%.4g, pressure %.4g\n",
	        at(&free_run, "stress_axial", kf), at(&free_run, "strain_radial", kf),
	        at(&r, "stress_axial", k), at(&r, "strain_radial", k), at(&r, "pressure", k));
	CHECK(at(&free_run, "strain_radial", kf) < -1e-5);
	CHECK(fabs(at(&r, "strain_radial", k)) < 0.2 * fabs(at(&free_run, "strain_radial", kf)));
	CHECK(at(&r, "pressure", k) > 0.05 * at(&r, "stress_axial", k));
	CHECK(at(&r, "stress_axial", k) > 1.02 * at(&free_run, "stress_axial", kf));
	run_free(&r);
	run_free(&free_run);
	assembly_free(&a);
	return check_done();
}
