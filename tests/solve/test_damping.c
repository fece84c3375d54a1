/* The two forms of the global non-viscous damping (case key damping.form)
 * on one free sphere under a constant force, against the closed form of
 * each rule. The force is the confining pressure of the lateral surface
 * (method "paper": π r² p_c, radially inward), on a sphere off the axis
 * moving along its radius, so the force is the same in every step; the
 * sphere also moves along the axis at w, which the force does not act on.
 * With h = Δt/m, F = -f e_x, after n steps from v = (0, 0, w):
 *
 *   components (Yade's NewtonIntegrator, solve/step.c damp): a component
 *   is damped by -α |F_k| against the sign of v_k + ½ h F_k, and nothing
 *   when F_k = 0: v_x = -n h f (1 - α), v_z = w exactly.
 *   vector (Eq. 39-40): F_damp = -α |F| v/|v| with v at t - Δt/2; at rest
 *   (w = 0): the first step undamped, then along F: v_x = -h f (1 + (n-1)(1 - α));
 *   with w > 0 the recurrence v' = v + h (F - α |F| v/|v|): v_z falls, and
 *   v_x grows more than at rest (the damping opposes the velocity vector,
 *   which leans on the axis).
 *
 * The torque-free sphere keeps ω = 0 in both. A bonded pair on the axis,
 * far from it, gives the critical time step a value (the pressure acts
 * on neither: the radial direction of a sphere on the axis is zero). */
#include <math.h>
#include <string.h>

#include "lib/vec3.h"
#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

static const char *case_json =
    "{\"assembly\": \"-\", \"material\": {\"name\": \"m\", \"law\": \"linear\", "
    "\"density\": 2500, \"kn\": 2e6, \"ks\": 7e5, \"tensile_strength\": 1e12, "
    "\"shear_strength\": 1e12},"
    "\"damping\": {\"translational\": %g, \"rotational\": %g, \"form\": \"%s\"},"
    "\"time_step\": {\"dt\": 1e-6}, \"surface\": {\"update_every\": 1},"
    "\"loading\": [{\"axial\": {\"mode\": \"none\"}, \"lateral\": {\"mode\": \"pressure\", "
    "\"method\": \"paper\", \"pressure\": 1e5}}], \"stop\": {\"steps\": 1000000}}";

static void one_sphere(dem_assembly *a, double r)
{
	fixture_spheres(a, 3);
	a->x[0] = 5e-3; /* on the x axis, 5 mm from the loading axis z */
	a->x[5] = -3e-3;
	a->x[8] = -3e-3 - 2 * r;
	a->r[0] = a->r[1] = a->r[2] = r;
	strcpy(a->geom.shape, "cylinder");
	a->geom.axis[2] = 1;
	a->geom.diameter = 12e-3;
	a->geom.height = 8e-3;
	a->geom.volume = DEM_PI * 36e-6 * 8e-3;
}

/* Run n steps from v = (0, 0, w); returns v_x and v_z, and the particle's
 * mass and the force magnitude as the engine has them. */
static void run(const char *form, double alpha, double w, int n, double *vx, double *vz, double *h,
                double *f)
{
	char json[1024];
	snprintf(json, sizeof json, case_json, alpha, alpha, form);
	dem_case c;
	harness_case(&c, json);
	dem_assembly a;
	one_sphere(&a, 1e-3);
	engine e;
	harness_engine(&e, &c, &a);
	CHECK(e.pairs.bonds.n == 1);
	int I = 0; /* the free sphere in the engine's order */
	while (e.p.orig[I] != 0)
		I++;
	double *v = e.p.v + 3 * I, *om = e.p.w + 3 * I;
	v[2] = w;
	for (int s = 0; s < n; s++)
		engine_step(&e, 0);
	*vx = v[0];
	*vz = v[2];
	*h = e.clock.dt / e.p.m[I];
	*f = 1e5 * DEM_PI * 1e-6;
	CHECK(om[0] == 0 && om[1] == 0 && om[2] == 0 && v[1] == 0);
	CHECK(e.p.x[3 * I] > 0); /* still on the same side of the axis: the force unchanged */
	engine_free(&e);
	case_free(&c);
	assembly_free(&a);
}

int main(void)
{
	const double alpha = 0.4, w = 1;
	const int n = 50;
	double vx, vz, h, f;

	/* Components at rest and moving along the axis: the same v_x, v_z = w. */
	run("components", alpha, 0, n, &vx, &vz, &h, &f);
	fprintf(stderr, "components, at rest: v_x %.12g (closed form %.12g)\n", vx,
	        -n * h * f * (1 - alpha));
	CHECK_REL(vx, -n * h * f * (1 - alpha), 1e-12);
	CHECK(vz == 0);
	run("components", alpha, w, n, &vx, &vz, &h, &f);
	CHECK_REL(vx, -n * h * f * (1 - alpha), 1e-12);
	CHECK(vz == w);

	/* Vector at rest: the first step undamped, then α |F| against v ∥ F. */
	run("vector", alpha, 0, n, &vx, &vz, &h, &f);
	double want = -h * f * (1 + (n - 1) * (1 - alpha));
	fprintf(stderr, "vector, at rest: v_x %.12g (closed form %.12g)\n", vx, want);
	CHECK_REL(vx, want, 1e-12);
	CHECK(vz == 0);
	/* Vector moving along the axis: the recurrence of Eq. 39-40. */
	double ux = 0, uz = w;
	for (int s = 0; s < n; s++) {
		double va = sqrt(ux * ux + uz * uz);
		double nx = ux + h * (-f - alpha * f * ux / va);
		uz = uz + h * (-alpha * f * uz / va);
		ux = nx;
	}
	run("vector", alpha, w, n, &vx, &vz, &h, &f);
	fprintf(stderr, "vector, moving: v_x %.12g v_z %.12g (recurrence %.12g %.12g)\n", vx, vz,
	        ux, uz);
	CHECK_REL(vx, ux, 1e-12);
	CHECK_REL(vz, uz, 1e-12);
	CHECK(vz < w && vx < want); /* damped along the axis, less along F than at rest */

	/* The default form is the vector. */
	dem_case c;
	harness_case(
	    &c, "{\"assembly\": \"-\", \"material\": {\"name\": \"m\", \"law\": "
	        "\"linear\", \"density\": 2500, \"kn\": 2e6, \"ks\": 7e5, \"tensile_strength\": 1, "
	        "\"shear_strength\": 1}, \"loading\": "
	        "[{\"axial\": {\"mode\": \"none\"}}], \"stop\": {\"steps\": 1}}");
	CHECK(c.damping_form == DAMPING_VECTOR);
	case_free(&c);
	return check_done();
}
