/* When a contact starts to push (material "contact.conventions",
 * solve/laws/material.h), step by step in the engine:
 *   1. two unbonded spheres meeting head on, undamped: with "solve" the
 *      contact pushes in the first step they overlap, K_n (r_i + r_j - d);
 *      with "yade" not in that step, then K_n (d_start - d) from the
 *      distance d_start of that step; once they part past d_start it
 *      pushes no more, though they still overlap;
 *   2. a sphere pressed by the top platen ("move": "top"): with "yade" the
 *      platen's load is zero in the step the sphere is first found
 *      overlapping it, then K_n times the overlap gained since;
 *   3. a checkpoint of a run with "yade" holds the contacts' starts, and
 *      the run restarted from it ends with the same bits.
 * (Yade's turn and arm of a platen contact's shear force are checked
 * against Yade itself, tests/workflows/compare-yade.sh.) */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "solve/run.h"
#include "tests/check.h"
#include "tests/harness.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

#define R 1e-3
#define E 1e9
#define KN (E * R) /* jcfpm contact: 2 E r E r / (E r + E r) (002 Eq. 4.4) */

static const char *case_json =
    "{\"assembly\": \"-\", \"material\": {\"name\": \"m\", \"law\": \"jcfpm\", "
    "\"density\": 2500, \"E\": 1e9, \"ks_ratio\": 0.2, \"tensile_strength\": 1e6, "
    "\"cohesion\": 1e6, \"friction_angle_deg\": 30, \"interaction_range\": 1, "
    "\"contact\": {\"conventions\": \"%s\"}},"
    "\"damping\": {\"translational\": 0, \"rotational\": 0},"
    "\"time_step\": {\"dt\": 1e-7}, %s}";

static void two(dem_assembly *a, double gap)
{
	fixture_spheres(a, 2);
	a->x[3] = 2 * R + gap;
	a->r[0] = a->r[1] = R;
	strcpy(a->geom.shape, "box");
	a->geom.axis[2] = 1;
	a->geom.volume = 1e-6;
	a->geom.height = 2 * R;
}

static double distance(const engine *e)
{
	double d2 = 0;
	for (int k = 0; k < 3; k++)
		d2 += pow(e->p.x[3 + k] - e->p.x[k], 2);
	return sqrt(d2);
}

/* The force on the spheres along the line of centres (pushing apart
 * positive), from the change of the relative speed in the step. */
static void meeting(int yade)
{
	char json[1024];
	snprintf(json, sizeof json, case_json, yade ? "yade" : "solve",
	         "\"loading\": [{\"axial\": {\"mode\": \"none\"}}], \"stop\": {\"steps\": 100000}");
	dem_case c;
	harness_case(&c, json);
	dem_assembly a;
	/* Closing 2 v0 dt = 2e-7 m a step: they first overlap by 1.8e-7 m. */
	two(&a, 2e-7 * 10.1);
	engine e;
	harness_engine(&e, &c, &a);
	CHECK(e.pairs.bonds.n == 0);
	double v0 = 1, m = e.p.m[0], dt = e.clock.dt, tol = 1e-9 * KN * v0 * dt;
	e.p.v[0] = v0, e.p.v[3] = -v0;
	int started = 0, ended = 0, pushes = 0, after = 0;
	double d_start = 0;
	for (int s = 0; s < 400 && !ended; s++) {
		double d = distance(&e), closing = e.p.v[0] - e.p.v[3];
		engine_step(&e, 0);
		/* m dv of sphere 0 = -F: F = m (closing before - after) / 2 / dt */
		double f = m * (closing - (e.p.v[0] - e.p.v[3])) / (2 * dt);
		if (!started && d < 2 * R) {
			started = 1;
			d_start = d;
			if (yade)
				CHECK(f == 0);
			else
				CHECK_NEAR(f, KN * (2 * R - d), tol);
			continue;
		}
		if (!started)
			continue;
		if (yade && d > d_start) {
			if (!(f == 0 && d < 2 * R))
				fprintf(stderr, "end: f %g N, d - 2R %g m, d - d_start %g m\n", f,
				        d - 2 * R, d - d_start);
			CHECK(f == 0 && d < 2 * R); /* ended while they still overlap */
			ended = 1;
			continue;
		}
		if (!yade && d >= 2 * R) {
			ended = 1;
			continue;
		}
		CHECK_NEAR(f, KN * ((yade ? d_start : 2 * R) - d), tol);
		pushes++;
		after += e.p.v[0] < 0;
	}
	CHECK(started && ended && pushes > 10 && after > 0); /* bounced */
	engine_free(&e);
	case_free(&c);
	assembly_free(&a);
}

/* One sphere between platens; the top one moves down at v. */
static void pressed(void)
{
	char json[1024];
	snprintf(json, sizeof json, case_json, "yade",
	         "\"loading\": [{\"axial\": {\"mode\": \"velocity\", \"velocity\": 0.01, "
	         "\"move\": \"top\"}}], \"stop\": {\"steps\": 100000}");
	dem_case c;
	harness_case(&c, json);
	dem_assembly a;
	fixture_spheres(&a, 1);
	a.r[0] = R;
	strcpy(a.geom.shape, "box");
	a.geom.axis[2] = 1;
	a.geom.volume = 8 * R * R * R;
	a.geom.height = 2 * R;
	engine e;
	harness_engine(&e, &c, &a);
	int started = 0, checked = 0;
	double u_start = 0;
	for (int s = 0; s < 50; s++) {
		double u = e.bc.pl.z[1] - e.p.x[2] - R; /* top gap, before the step */
		engine_step(&e, 0);
		double load = e.bc.pl.load[1];
		if (!started && u < 0) {
			started = 1;
			u_start = u;
			CHECK(load == 0);
		} else if (started) {
			CHECK_REL(load, KN * 2 * (u_start - u), 1e-9); /* platen: twice a pair's */
			checked++;
		} else
			CHECK(load == 0);
	}
	CHECK(started && checked > 40);
	engine_free(&e);
	case_free(&c);
	assembly_free(&a);
}

/* The jittered cylinder crushed past its first cracks, interrupted with
 * contacts at work and restarted from its checkpoint: the same bits. */
static void restart(void)
{
	dem_assembly a;
	fixture_cylinder(&a, 3);
	const char *apath = check_tmp("conventions.h5");
	fixture_write(&a, apath);
	assembly_free(&a);
	char json[2048], args[4096];
	snprintf(json, sizeof json,
	         "{\"assembly\": \"%s\", \"material\": {\"name\": \"m\", \"law\": \"jcfpm\", "
	         "\"density\": 2500, \"E\": 1e9, \"ks_ratio\": 0.2, \"tensile_strength\": 2e5, "
	         "\"cohesion\": 2e5, \"friction_angle_deg\": 30, \"interaction_range\": 1.0, "
	         "\"contact\": {\"conventions\": \"yade\"}}, \"axis\": [1, 0, 0], "
	         "\"loading\": [{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 20}}], "
	         "\"output\": {\"history_every\": 20, \"snapshot_every\": 300}, "
	         "\"stop\": {\"steps\": 3000}}",
	         apath);
	const char *cpath = harness_file("conventions.json", json);
	char whole[1024], part[1024];
	snprintf(whole, sizeof whole, "%s", check_tmp("conventions-whole.h5"));
	snprintf(part, sizeof part, "%s", check_tmp("conventions-part.h5"));
	snprintf(args, sizeof args, "--quiet --threads 2 --output %s %s", whole, cpath);
	CHECK(harness_solve(args) == 0);
	snprintf(args, sizeof args, "--quiet --threads 1 --max-steps 1700 --output %s %s", part,
	         cpath);
	CHECK(harness_solve(args) == 3);
	snprintf(args, sizeof args, "--quiet --threads 2 --restart %s", part);
	CHECK(harness_solve(args) == 0);
	CHECK(harness_same_runs(whole, part) == 0);
	/* The checkpoint was taken with broken bonds and contacts at work. */
	dem_run r;
	harness_read(whole, &r);
	size_t k = 1700 / 20;
	double broken = run_column_data(&r, "bonds_broken_tension")[k] +
	                run_column_data(&r, "bonds_broken_shear")[k];
	fprintf(stderr, "restart: %g broken bonds and %g contacts at step %zu\n", broken,
	        run_column_data(&r, "contacts")[k], 20 * k);
	CHECK(broken > 10 && run_column_data(&r, "contacts")[k] > 10);
	run_free(&r);
}

int main(void)
{
	meeting(0);
	meeting(1);
	pressed();
	restart();
	return check_done();
}
