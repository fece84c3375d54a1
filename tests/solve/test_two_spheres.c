/* Two bonded spheres vibrating freely, undamped: the periods of the normal
 * and the shear mode equal 2π sqrt(m/K) to 0.1 %.
 *
 * Normal mode: relative motion along n, m = m_ij = m_i m_j / (m_i + m_j).
 * Shear mode: the shear spring at the contact point also turns both spheres
 * (arms a_i, a_j from the centres), so the mode's mass is
 *   1/m = 1/m_i + 1/m_j + a_i²/I_i + a_j²/I_j
 * (the relative tangential displacement δ obeys δ'' = -K_s δ / m). Started in
 * the pure mode shape: velocities ∝ (1/m_i, -1/m_j) along s and spins
 * ∝ (a_i/I_i, a_j/I_j) about n × s.
 * The pair lies along an oblique direction, spheres of unequal size with a
 * gap at bonding, so nothing relies on the coordinate axes. */
#include <math.h>
#include <string.h>

#include "lib/vec3.h"
#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

static const char *case_json =
    "{\"assembly\": \"-\", \"material\": {\"name\": \"pair\", \"law\": \"linear\", "
    "\"density\": 2500, \"kn\": 2e6, \"ks\": 7e5, \"tensile_strength\": 1e12, "
    "\"shear_strength\": 1e12},"
    "\"damping\": {\"translational\": 0, \"rotational\": 0},"
    "\"time_step\": {\"dt\": %g},"
    "\"loading\": [{\"axial\": {\"mode\": \"none\"}}], \"stop\": {\"steps\": 1000000}}";

static void pair_assembly(dem_assembly *a, const double n[3], double ri, double rj, double d)
{
	fixture_spheres(a, 2);
	for (int k = 0; k < 3; k++)
		a->x[3 + k] = d * n[k];
	a->r[0] = ri;
	a->r[1] = rj;
	strcpy(a->geom.shape, "box");
	a->geom.axis[2] = 1;
	a->geom.volume = 1e-6;
	a->geom.height = 1e-2;
}

/* Mean period of the sign changes of q(step), by linear interpolation. */
static double period(const double *q, int n, double dt)
{
	double first = -1, last = -1;
	int crossings = 0;
	for (int s = 1; s < n; s++)
		if ((q[s - 1] < 0) != (q[s] < 0)) {
			double at = (s - 1 + q[s - 1] / (q[s - 1] - q[s])) * dt;
			if (first < 0)
				first = at;
			last = at;
			crossings++;
		}
	return crossings > 1 ? 2 * (last - first) / (crossings - 1) : 0;
}

/* Run both modes for one geometry; returns nothing, checks the periods. */
static void vibrate(const double dir[3], double ri, double rj, double gap)
{
	double n[3], s[3], tmp[3] = {0.3, -0.5, 0.8}, axis[3];
	v3_scale(n, dir, 1 / v3_norm(dir));
	v3_reject(s, tmp, n);
	v3_scale(s, s, 1 / v3_norm(s));
	v3_cross(axis, n, s);
	double d = (ri + rj) * (1 + gap);
	double mi = 2500 * 4.0 / 3.0 * DEM_PI * ri * ri * ri,
	       mj = 2500 * 4.0 / 3.0 * DEM_PI * rj * rj * rj;
	double ii = 0.4 * mi * ri * ri, ij = 0.4 * mj * rj * rj;
	double ai = d * ri / (ri + rj), aj = d * rj / (ri + rj);
	double mn = mi * mj / (mi + mj);
	double ms = 1 / (1 / mi + 1 / mj + ai * ai / ii + aj * aj / ij);
	double tn = 2 * DEM_PI * sqrt(mn / 2e6), ts = 2 * DEM_PI * sqrt(ms / 7e5);
	double dt = fmin(tn, ts) / 400;
	char json[1024];
	snprintf(json, sizeof json, case_json, dt);
	dem_assembly a;
	pair_assembly(&a, n, ri, rj, d);
	for (int mode = 0; mode < 2; mode++) {
		dem_case c;
		harness_case(&c, json);
		engine e;
		harness_engine(&e, &c, &a);
		CHECK(e.pairs.bonds.n == 1);
		/* Internal order may swap the two spheres: work with their roles. */
		int I = e.p.orig[0] == 0 ? 0 : 1, J = 1 - I;
		double v0 = 1e-4, c0 = 1e-10;
		for (int k = 0; k < 3; k++) {
			if (mode == 0) {
				e.p.v[3 * I + k] = -v0 * n[k];
				e.p.v[3 * J + k] = v0 * n[k] * mi / mj;
			} else {
				e.p.v[3 * I + k] = c0 / mi * s[k];
				e.p.v[3 * J + k] = -c0 / mj * s[k];
				e.p.w[3 * I + k] = c0 * ai / ii * axis[k];
				e.p.w[3 * J + k] = c0 * aj / ij * axis[k];
			}
		}
		int steps = (int)(12 * (mode == 0 ? tn : ts) / dt);
		double *q = malloc((size_t)steps * sizeof *q);
		int sgn = e.pairs.bonds.rec[0].i == I ? 1 : -1;
		for (int st = 0; st < steps; st++) {
			engine_step(&e, 0);
			const double *xi = e.p.x + 3 * I, *xj = e.p.x + 3 * J;
			double dx[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
			/* normal: the bond's stretch; shear: its shear displacement along s */
			q[st] =
			    mode == 0 ? v3_norm(dx) - d : sgn * v3_dot(e.pairs.bonds.rec[0].t, s);
		}
		double got = period(q, steps, dt), want = mode == 0 ? tn : ts;
		fprintf(stderr, "%s mode: period %.9g s, 2 pi sqrt(m/K) = %.9g s (rel %.2e)\n",
		        mode == 0 ? "normal" : "shear", got, want, fabs(got - want) / want);
		CHECK_REL(got, want, 1e-3);
		free(q);
		engine_free(&e);
		case_free(&c);
	}
	assembly_free(&a);
}

/* The pair of vibrate's second geometry pulled apart until its bond
 * breaks in tension: the crack record holds the force the criterion
 * judged in that step, k_n u_n with u_n from the step's positions, above
 * the strength sigma_t A where the step before was below it; the bond
 * forces for the output (bonds_output_forces), at the state between
 * steps, are k_n u_n of the positions then (none beyond the strength:
 * the next step breaks the bond), and leave the bond as it was. */
static void pull(void)
{
	double n[3] = {0.6, -0.3, 0.74}, ri = 1e-3, rj = 0.6e-3;
	v3_scale(n, n, 1 / v3_norm(n));
	double d = (ri + rj) * 1.05, kn = 2e6, sigma_t = 1e6;
	double mi = 2500 * 4.0 / 3.0 * DEM_PI * ri * ri * ri,
	       mj = 2500 * 4.0 / 3.0 * DEM_PI * rj * rj * rj;
	double dt = 2 * DEM_PI * sqrt(mi * mj / (mi + mj) / kn) / 400;
	char json[1024];
	snprintf(json, sizeof json, case_json, dt);
	char *at = strstr(json, "\"tensile_strength\": 1e12");
	memcpy(at, "\"tensile_strength\": 1e06", strlen("\"tensile_strength\": 1e06"));
	dem_assembly a;
	pair_assembly(&a, n, ri, rj, d);
	dem_case c;
	harness_case(&c, json);
	engine e;
	harness_engine(&e, &c, &a);
	CHECK(e.pairs.bonds.n == 1);
	law_pair pair = {.ri = ri, .rj = rj, .mi = mi, .mj = mj, .d0 = d};
	law_const k;
	e.law->constants(e.lp, &pair, &k);
	double strength = sigma_t * k.area;
	int I = e.p.orig[0] == 0 ? 0 : 1, J = 1 - I;
	/* Apart at a speed that reaches the strength in a tenth of a period. */
	double v0 = 4 * strength / kn / (40 * dt);
	for (int c3 = 0; c3 < 3; c3++) {
		e.p.v[3 * I + c3] = -v0 * n[c3] * mj / (mi + mj);
		e.p.v[3 * J + c3] = v0 * n[c3] * mi / (mi + mj);
	}
	double before = 0;
	int st = 0;
	for (; st < 400 && e.out.cracks.n == 0; st++) {
		const double *xi = e.p.x + 3 * I, *xj = e.p.x + 3 * J;
		double dx[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
		double un = v3_norm(dx) - d, t[3];
		memcpy(t, e.pairs.bonds.rec[0].t, sizeof t);
		bonds_output_forces(&e);
		const float *f = e.pairs.bonds.fb;
		int sgn = e.pairs.bonds.rec[0].i == I ? 1 : -1; /* the force on i */
		double fn = sgn * (f[0] * dx[0] + f[1] * dx[1] + f[2] * dx[2]) / v3_norm(dx);
		if (kn * un > strength) /* the force the next step gives: none */
			CHECK(fn == 0);
		else if (un > 1e-3 * strength / kn)
			CHECK_REL(fn, kn * un, 1e-6);
		CHECK(memcmp(t, e.pairs.bonds.rec[0].t, sizeof t) == 0 &&
		      e.pairs.bonds.state[0] == BOND_INTACT);
		engine_step(&e, 0);
		if (e.out.cracks.n == 0)
			before = kn * un;
		else {
			const dem_crack *cr = &e.out.cracks.c[0];
			fprintf(stderr,
			        "pulled: broke at step %d, crack fn %.9g N, k_n u_n %.9g N, "
			        "strength %.9g N, the step before %.9g N\n",
			        st, cr->fn, kn * un, strength, before);
			CHECK(cr->mode == CRACK_TENSION);
			CHECK_REL(cr->fn, kn * un, 1e-12);
			CHECK(cr->fn > strength && before <= strength);
			CHECK(cr->fs <= 1e-9 * cr->fn);
		}
	}
	CHECK(e.out.cracks.n == 1 && st > 10);
	engine_free(&e);
	case_free(&c);
	assembly_free(&a);
}

int main(void)
{
	pull();
	vibrate((double[3]){0, 0, 1}, 1e-3, 1e-3, 0);
	vibrate((double[3]){0.6, -0.3, 0.74}, 1e-3, 0.6e-3, 0.05);
	return check_done();
}
