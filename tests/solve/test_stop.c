/* The stop rules end the run where they say, and the history shows it:
 *   1. a stress-drop rule is not fooled by the first steps of loading: an
 *      elastic specimen loaded across (along x, between platens that touch
 *      its side) runs to its step count, where it once stopped at step 5
 *      on a "peak" of a few hundred pascals;
 *   2. the last history row is at the stop: a strain rule that holds between
 *      two rows, and a step count that is no multiple of history_every;
 *   3. a particle thrown at 10^4 m/s (a radius per step) is diagnosed, not
 *      taken for a stress drop. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lib/err.h"
#include "solve/run.h"
#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

static const char *case_text =
    "{\"assembly\": \"-\", \"material\": {\"name\": \"m\", \"law\": \"linear\", "
    "\"density\": 2500, \"E\": 1e10, \"nu\": 0.2, \"tensile_strength\": 1e12, "
    "\"shear_strength\": 1e12}, \"damping\": {\"translational\": 0.1, \"rotational\": 0.1}, "
    "\"output\": {\"history_every\": %d}, %s"
    "\"loading\": [{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 1}}], "
    "\"stop\": {%s}}";

static dem_assembly a;

/* Run the case to its end; returns the exit code and reads the run file. */
static int run(const char *name, int every, const char *extra, const char *stop, double thrown,
               dem_run *r)
{
	char json[2048];
	snprintf(json, sizeof json, case_text, every, extra, stop);
	dem_case c;
	harness_case(&c, json);
	engine e;
	harness_engine(&e, &c, &a);
	e.p.v[3 * 5] = thrown;
	run_opts o = {.output = check_tmp(name), .quiet = 1};
	int code = run_engine(&e, &a, &o);
	engine_free(&e);
	case_free(&c);
	harness_read(o.output, r);
	fprintf(stderr, "%s: exit %d, %s, %zu rows\n", name, code, r->status, r->nrows);
	return code;
}

static double last(const dem_run *r, const char *col)
{
	return run_column_data(r, col)[r->nrows - 1];
}

int main(void)
{
	lattice l = {
	    .kind = LATTICE_FCC, .nx = 4, .ny = 4, .nz = 6, .r = 1e-3, .jitter = 0.02, .seed = 3};
	fixture_lattice(&a, &l);
	dem_run r;

	/* 1. Loaded across, elastic: no peak, so no stress drop. */
	CHECK(run("across.h5", 1, "\"axis\": [1, 0, 0],", "\"stress_drop\": 0.7, \"steps\": 400", 0,
	          &r) == RUN_OK);
	CHECK_CONTAINS(r.status, "stopped: 400 steps done");
	CHECK(r.nrows == 400);
	run_free(&r);

	/* 2. The history ends at the stop. A strain rule between two rows. */
	CHECK(run("strain.h5", 7, "", "\"strain_axial\": 2e-5", 0, &r) == RUN_OK);
	CHECK_CONTAINS(r.status, "stopped: axial strain reached 2e-05");
	CHECK(last(&r, "strain_axial") >= 2e-5);
	run_free(&r);
	/* A step count: the row of the last step. */
	CHECK(run("steps.h5", 7, "", "\"steps\": 300", 0, &r) == RUN_OK);
	CHECK_CONTAINS(r.status, "stopped: 300 steps done");
	CHECK(last(&r, "step") == 299);
	CHECK(r.nrows == 300 / 7 + 2);
	run_free(&r);

	/* 3. A particle thrown out of the specimen. */
	CHECK(run("thrown.h5", 100, "", "\"stress_drop\": 0.7, \"steps\": 400", 1e4, &r) ==
	      RUN_FAILED);
	CHECK_CONTAINS(r.status, "stopped: particle ");
	CHECK_CONTAINS(r.status, " m in one step (speed ");
	CHECK_CONTAINS(r.status, "more than half the Verlet skin");
	run_free(&r);

	assembly_free(&a);
	return check_done();
}
