/* A failing simulation stops with a diagnosis naming the particle or bond,
 * and the run file written so far stays valid (status "stopped: ..."):
 *   - a time step above the stable limit is refused at start, and so are
 *     values that would make the run hang or exhaust memory (a time step
 *     far below it, a stiffness or density out of range, tiny surface bins);
 *   - a NaN in a particle's velocity is traced to the bond whose force it
 *     made non-finite;
 *   - a time step forced above the limit makes the kinetic energy run away;
 *   - after a neighbour rebuild, the time step is checked again. */
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
    "\"shear_strength\": 1e12}, %s \"output\": {\"history_every\": 1},"
    "\"loading\": [{\"axial\": {\"mode\": \"%s\", \"rate\": 1}}], "
    "\"stop\": {\"steps\": 300}}";

static dem_assembly a;

/* Setup refuses the case (JSON text) with a message containing `expect`. */
static void refused(const char *json, const char *expect)
{
	dem_case c;
	harness_case(&c, json);
	engine e;
	CHECK(engine_setup(&e, &c, &a, &(engine_opts){.quiet = 1}) == -1);
	CHECK_CONTAINS(err_msg(), expect);
	engine_free(&e);
	case_free(&c);
}

/* The same for the case made of the material's density and E, the strain
 * rate, and more keys. */
static void refused_at_setup(const char *density, const char *E, const char *rate,
                             const char *extra, const char *expect)
{
	char json[2048];
	snprintf(json, sizeof json,
	         "{\"assembly\": \"-\", \"material\": {\"name\": \"m\", \"law\": \"linear\", "
	         "\"density\": %s, \"E\": %s, \"nu\": 0.2, \"tensile_strength\": 1e12, "
	         "\"shear_strength\": 1e12}, %s \"loading\": [{\"axial\": {\"mode\": "
	         "\"strain_rate\", \"rate\": %s}}], \"stop\": {\"steps\": 300}}",
	         density, E, extra, rate);
	refused(json, expect);
}

/* Run an engine prepared by the caller to its end; returns the status. */
static char *run_to_end(engine *e, const char *name, int *code)
{
	run_opts o = {.output = check_tmp(name), .quiet = 1};
	*code = run_engine(e, &a, &o);
	dem_run r;
	harness_read(o.output, &r);
	fprintf(stderr, "%s: %s (%zu history rows)\n", name, r.status, r.nrows);
	CHECK(r.nrows >= 1);
	char *status = xstrdup(r.status);
	run_free(&r);
	return status;
}

int main(void)
{
	lattice l = {
	    .kind = LATTICE_FCC, .nx = 3, .ny = 3, .nz = 4, .r = 1e-3, .jitter = 0.02, .seed = 2};
	fixture_lattice(&a, &l);
	char json[2048];

	/* A time step above the bound at start. */
	snprintf(json, sizeof json, case_text, "\"time_step\": {\"dt\": 1e-3},", "strain_rate");
	dem_case c;
	harness_case(&c, json);
	engine e;
	CHECK(engine_setup(&e, &c, &a, &(engine_opts){.quiet = 1}) == -1);
	CHECK_CONTAINS(err_msg(), "time step 0.001 s above the stable limit ");
	CHECK_CONTAINS(err_msg(), " s, set by particle ");
	CHECK_CONTAINS(err_msg(), "lower time_step.dt or leave it out");
	engine_free(&e);
	case_free(&c);

	/* Values that would hang, crash or run out of memory: refused at start. */
	refused_at_setup("2500", "1e10", "1", "\"time_step\": {\"dt\": 1e-300},",
	                 "time step 1e-300 s below a millionth of the stable limit ");
	refused_at_setup("2500", "1e308", "1", "",
	                 "the critical time step is 0 s, set by particle ");
	refused_at_setup("1e308", "1e10", "1", "",
	                 "mass inf kg from the density 1e+308 kg/m^3: expected a finite positive "
	                 "mass");
	refused_at_setup("2500", "1e10", "1", "\"surface\": {\"bin\": 1e-12},",
	                 "surface.bin 1e-12 m: expected at least a tenth of the mean sphere "
	                 "diameter (0.002 m)");

	refused_at_setup("2500", "1e10", "1", "\"neighbours\": {\"skin\": 0.3},",
	                 "neighbours.skin 0.3 m: expected at most two mean sphere diameters ");
	refused_at_setup("2500", "1e10", "1e6", "", "loading stage 1: the ends would move ");
	refused_at_setup("2500", "1e10", "1e6", "", "(lower its axial.rate)");
	/* A density that makes the time step absurd is blamed, not the rate. */
	refused_at_setup("1e300", "1e10", "1", "",
	                 "it comes from the material's density (1e+300 kg/m^3) and stiffness)");
	/* Ends that stand still, with only a strain rule to end the run. */
	refused("{\"assembly\": \"-\", \"material\": {\"name\": \"m\", \"law\": \"linear\", "
	        "\"density\": 2500, \"E\": 1e10, \"nu\": 0.2, \"tensile_strength\": 1e12, "
	        "\"shear_strength\": 1e12}, \"loading\": [{\"axial\": {\"mode\": "
	        "\"strain_rate\", \"rate\": 0}}], \"stop\": {\"strain_axial\": 0.01}}",
	        "loading stage 1: axial.rate 0: the ends stand still, so its strain rule can "
	        "never hold");
	/* Rules the loading moves away from, or holds short of: the run would
	 * never end. */
	const char *head = "{\"assembly\": \"-\", \"material\": {\"name\": \"m\", \"law\": "
	                   "\"linear\", \"density\": 2500, \"E\": 1e10, \"nu\": 0.2, "
	                   "\"tensile_strength\": 1e12, \"shear_strength\": 1e12}, \"loading\": ";
	const char *never[][2] = {
	    {"[{\"axial\": {\"mode\": \"strain_rate\", \"rate\": -2}}], \"stop\": "
	     "{\"strain_axial\": 0.01}}",
	     "loading stage 1: axial.rate -2: the ends open, so the axial strain falls from 0 "
	     "and never reaches 0.01"},
	    {"[{\"axial\": {\"mode\": \"strain_rate\", \"rate\": -1}}], \"stop\": "
	     "{\"strain_axial\": 0.03, \"stress_drop\": 0.7}}",
	     "loading stage 1: axial.rate -1: the ends open, so the axial strain falls from 0 "
	     "and never reaches 0.03"},
	    {"[{\"axial\": {\"mode\": \"velocity\", \"velocity\": 0.01}}], \"stop\": "
	     "{\"strain_axial\": -0.01}}",
	     "axial.velocity 0.01: the ends close, so the axial strain grows from 0 and never "
	     "reaches -0.01"},
	    {"[{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 1}, \"until\": "
	     "{\"strain_axial\": 0.01}}, {\"axial\": {\"mode\": \"strain_rate\", \"rate\": 1}, "
	     "\"until\": {\"strain_axial\": 0.005}}], \"stop\": {\"strain_axial\": -0.01}}",
	     "loading stage 2: axial.rate 1: the ends close, so the axial strain grows from "
	     "0.01 and never reaches 0.005"},
	    {"[{\"axial\": {\"mode\": \"stress\", \"stress\": 1e6}, \"until\": "
	     "{\"stress_axial\": 2e6}}, {\"axial\": {\"mode\": \"strain_rate\", \"rate\": "
	     "1}}], \"stop\": {\"strain_axial\": 0.01}}",
	     "loading stage 1: axial.stress 1e+06 Pa: the servo holds the stress there"},
	    {"[{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 1}}], \"stop\": "
	     "{\"strain_axial\": 0}}",
	     "stop.strain_axial 0: the run starts at that strain"},
	};
	for (size_t k = 0; k < sizeof never / sizeof never[0]; k++) {
		char text[2048];
		snprintf(text, sizeof text, "%s%s", head, never[k][0]);
		refused(text, never[k][1]);
	}
	/* ... but not the rules they reach: pulling to a negative strain, a
	 * servo's target and beyond it on a later stage, unloading to a strain
	 * below where a stress rule left it (not known before the run). */
	const char *ends[] = {
	    "[{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 1}, \"until\": "
	    "{\"stress_axial\": 1e6}}, {\"axial\": {\"mode\": \"strain_rate\", \"rate\": -1}, "
	    "\"until\": {\"strain_axial\": 0.0001}}, {\"axial\": {\"mode\": \"strain_rate\", "
	    "\"rate\": 1}}], \"stop\": {\"strain_axial\": 0.01}}",
	    "[{\"axial\": {\"mode\": \"strain_rate\", \"rate\": -2}}], \"stop\": "
	    "{\"strain_axial\": -0.001}}",
	    "[{\"axial\": {\"mode\": \"stress\", \"stress\": 1e6}, \"until\": "
	    "{\"stress_axial\": 1e6}}, {\"axial\": {\"mode\": \"strain_rate\", \"rate\": "
	    "1}}], \"stop\": {\"strain_axial\": 0.01}}",
	};
	for (size_t k = 0; k < sizeof ends / sizeof ends[0]; k++) {
		char text[2048];
		snprintf(text, sizeof text, "%s%s", head, ends[k]);
		harness_case(&c, text);
		CHECK(engine_setup(&e, &c, &a, &(engine_opts){.quiet = 1}) == 0);
		engine_free(&e);
		case_free(&c);
	}

	/* A particle a thousand kilometres away: refused, not a search grid of
	 * 1e19 bytes. */
	snprintf(json, sizeof json, case_text, "", "strain_rate");
	double x0 = a.x[3 * 7];
	a.x[3 * 7] = 1e6;
	refused(json, "too sparse for spheres of radius up to ");
	refused(json, ": particle 7 at (1e+06, ");
	refused(json, "expected a packed specimen (check the assembly's positions)");
	a.x[3 * 7] = x0;

	/* Axes whose squared length overflows or underflows are still axes. */
	const char *axes[] = {"[1e200, 0, 0]", "[1e-320, 0, 0]", "[-3e-310, 0, 0]"};
	for (int k = 0; k < 3; k++) {
		snprintf(json, sizeof json, case_text, "", "strain_rate");
		char with_axis[2200];
		snprintf(with_axis, sizeof with_axis, "%.*s, \"axis\": %s}", (int)strlen(json) - 1,
		         json, axes[k]);
		harness_case(&c, with_axis);
		harness_engine(&e, &c, &a);
		fprintf(stderr, "axis %s: (%g, %g, %g)\n", axes[k], e.frame.axis[0],
		        e.frame.axis[1], e.frame.axis[2]);
		CHECK(fabs(e.frame.axis[0]) == 1 && e.frame.axis[1] == 0 && e.frame.axis[2] == 0);
		engine_free(&e);
		case_free(&c);
	}
	/* End layers thicker than half the specimen. */
	refused("{\"assembly\": \"-\", \"material\": {\"name\": \"m\", \"law\": \"linear\", "
	        "\"density\": 2500, \"E\": 1e10, \"nu\": 0.2, \"tensile_strength\": 1e12, "
	        "\"shear_strength\": 1e12}, \"loading\": [{\"axial\": {\"mode\": \"layers\", "
	        "\"rate\": 1, \"thickness\": 1}}], \"stop\": {\"steps\": 300}}",
	        "loading stage 1: axial.thickness 1 m: expected less than half the specimen's "
	        "height");

	/* A skin so wide (the widest taken) that no neighbour rebuild (and its
	 * time-step check) comes. */
	snprintf(json, sizeof json, case_text, "\"neighbours\": {\"skin\": 0.004},", "layers");
	/* A NaN velocity: the bond it poisons is named. */
	harness_case(&c, json);
	harness_engine(&e, &c, &a);
	size_t k = 17;
	e.p.v[3 * k] = NAN;
	int32_t bad = e.p.orig[k];
	int nb = pairlist_count(&e.pairs.bonds, k);
	int code;
	char *status = run_to_end(&e, "nan.h5", &code);
	CHECK(code == RUN_FAILED);
	char want[256];
	snprintf(
	    want, sizeof want,
	    "stopped: non-finite state at step 0 (t = 0 s): particle %d (radius 0.001 m): %d of "
	    "its bonds have non-finite forces, first bond ",
	    bad, nb);
	CHECK_CONTAINS(status, want);
	CHECK_CONTAINS(status, "(law linear)");
	free(status);
	engine_free(&e);

	/* Twice the stable time step: the energy of a vibrating specimen runs
	 * away. */
	harness_engine(&e, &c, &a);
	e.clock.dt = 2 * e.clock.dt_crit;
	for (size_t i = 0; i < e.p.n; i++)
		e.p.v[3 * i] = 1e-3 * (double)(i % 3);
	status = run_to_end(&e, "runaway.h5", &code);
	CHECK(code == RUN_FAILED);
	CHECK_CONTAINS(status, "stopped: kinetic energy ");
	CHECK_CONTAINS(status, "the integration is unstable; fastest particle ");
	free(status);
	engine_free(&e);

	/* Just above the limit, caught at the first neighbour rebuild. */
	case_free(&c);
	snprintf(json, sizeof json, case_text, "", "strain_rate");
	harness_case(&c, json);
	harness_engine(&e, &c, &a);
	e.clock.dt = 1.05 * e.clock.dt_crit;
	e.pairs.rebuild = 1;
	status = run_to_end(&e, "rebuild.h5", &code);
	CHECK(code == RUN_FAILED);
	CHECK_CONTAINS(status, "stopped: time step ");
	CHECK_CONTAINS(status, " above the stable limit ");
	CHECK_CONTAINS(status, " at step 1: particle ");
	free(status);
	engine_free(&e);
	case_free(&c);
	assembly_free(&a);
	return check_done();
}
