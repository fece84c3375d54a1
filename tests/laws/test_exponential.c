/* The exponential high-confinement law (seeds/001 §3.3.3, Tran, Donzé &
 * Marin 2011) driven on one bond by prescribed relative displacements.
 * Parameters of 001 Table 5 (elasticity of 000 Table 5). */
#include "tests/laws/drive.h"

#include "lib/rng.h"

static const char *concrete = "{\"name\": \"exp\", \"law\": \"exponential\", \"density\": 2500,"
                              " \"E0\": 28e9, \"nu\": 0.2, \"tensile_strength\": 10e6,"
                              " \"delta_n\": 0.2, \"cohesion\": 13e6,"
                              " \"friction_angle_deg\": 30, \"contact_friction_angle_deg\": 30,"
                              " \"interaction_range\": 1.1}";

#define E0 28e9
#define SIGT 10e6
#define COH 13e6
#define TANPHI tan(30 * PI / 180)
#define DELTA 0.2

static const double ri = 1.0e-3, rj = 1.5e-3, d0 = 2.6e-3;

static law_pair pair_of(void)
{
	law_pair q = {.ri = ri, .rj = rj, .d0 = d0};
	q.mi = 2500 * 4.0 / 3.0 * PI * ri * ri * ri;
	q.mj = 2500 * 4.0 / 3.0 * PI * rj * rj * rj;
	return q;
}

#define A (PI * ri * ri)
#define K0 (A * E0 / d0)
#define KS (K0 / 2.4)
#define UL (SIGT * A / K0)
#define UF ((1 + DELTA) * UL)

/* Compressive force at strain eps on the loading curve (001 §3.3.3). */
static double curve(double eps, double g1, double g2, double g3, double em)
{
	if (eps <= em)
		return K0 * d0 * eps;
	double knl = fmin(K0, K0 * (g3 + g1 * exp(g2 * (eps - em))));
	return K0 * d0 * em + knl * (d0 * eps - d0 * em);
}

static const law *L;
static law_params *P;

static void test_constants(void)
{
	law_pair q = pair_of();
	law_const c;
	L->constants(P, &q, &c);
	double mij = q.mi * q.mj / (q.mi + q.mj);
	CHECK_REL(c.kn, K0, 1e-15);
	CHECK_REL(c.ks, KS, 1e-15);
	CHECK_REL(c.area, A, 1e-15);
	CHECK_REL(c.cn, 2 * PI * ri * 0.9 / d0 * sqrt(mij * K0), 1e-14);
	CHECK(c.rc == ri);
	CHECK_REL(L->bond_range(P), 1.1, 1e-15);
}

/* Linear up to eps_max, the exponential stiffening beyond it (default
 * gamma1..3, eps_max = 0.2, 16, 0.275, 0.002) capped at K_n0, unloading and
 * reloading with K_n0 below the historical maximum. */
static void test_compression(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	const double target[4] = {0.0015, 0.01, 0.05, 0.12};
	double cmax = 0;
	for (int k = 0; k < 4; k++) {
		for (int s = 1; s <= 20; s++) {
			double c = cmax + (target[k] - cmax) * s / 20;
			law_out o = drive_step(L, P, &q, &b, -c * d0, 0, 0, 0, 0);
			CHECK_REL(o.fn, -curve(c, 0.2, 16, 0.275, 0.002), 1e-12);
		}
		cmax = target[k];
		double fpk = curve(cmax, 0.2, 16, 0.275, 0.002), dmax = cmax * d0;
		double dp = dmax - fpk / K0;
		for (int s = 1; s <= 10; s++) {
			double d = dmax + (dp - dmax) * s / 10;
			law_out o = drive_step(L, P, &q, &b, -d, 0, 0, 0, 0);
			CHECK_NEAR(o.fn, -(fpk - K0 * (dmax - d)), 1e-12 * fpk);
			CHECK_NEAR(drive_energy(L, P, &q, &b), 0.5 * o.fn * o.fn / K0,
			           1e-12 * fpk * dmax);
		}
		double w = drive_normal(L, P, &q, &b, -dp, -dmax, 10, NULL);
		CHECK_REL(w, 0.5 * fpk * fpk / K0, 1e-9);
	}
	/* Beyond the cap the force is back on the elastic line K_n0 u. */
	CHECK_REL(curve(0.12, 0.2, 16, 0.275, 0.002), K0 * 0.12 * d0, 1e-15);

	/* Every constant is a parameter. */
	char json[1024];
	snprintf(json, sizeof json,
	         "%.*s, \"gamma1\": 0.3, \"gamma2\": 40, \"gamma3\": 0.1, \"eps_max\": 0.001}",
	         (int)strlen(concrete) - 1, concrete);
	law_params *p = drive_parse(L, json, "g.json");
	CHECK(p != NULL);
	b = drive_bond(L, p, &q);
	law_out o = drive_step(L, p, &q, &b, -0.005 * d0, 0, 0, 0, 0);
	CHECK_REL(o.fn, -curve(0.005, 0.3, 40, 0.1, 0.001), 1e-12);
	CHECK(fabs(curve(0.005, 0.3, 40, 0.1, 0.001) - curve(0.005, 0.2, 16, 0.275, 0.002)) >
	      0.01 * K0 * d0 * 0.005);
	L->free(p);
}

/* Tension as in the local model: linear softening to u_n^f, the work of the
 * failure is 1/2 sigma_t A u_n^f. */
static void test_tension(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	double fl;
	double w = drive_normal(L, P, &q, &b, 0, UL, 50, &fl);
	CHECK_REL(fl, SIGT * A, 1e-12);
	CHECK_REL(drive_energy(L, P, &q, &b), w, 1e-12);
	double u = UL * (1 + 0.5 * DELTA);
	law_out o = drive_step(L, P, &q, &b, u, 0, 0, 0, 0);
	CHECK_REL(o.fn, 0.5 * SIGT * A, 1e-10);
	CHECK(b.state == BOND_DAMAGED);
	double dn, ds;
	L->damage(P, &b, &dn, &ds);
	CHECK_NEAR(dn, 0.5, 1e-10);
	/* Beyond u_n^f in one step: the crack record's forces are the tension
	 * there with the damage of the step before, and no shear. */
	o = drive_step(L, P, &q, &b, UF * (1 + 1e-6), 0, 0, 0, 0);
	CHECK(o.failed == CRACK_TENSION && o.fn == 0);
	CHECK_REL(o.fn_failed, K0 * UF * (1 + 1e-6) * 0.5 / (1 + 0.5 * DELTA), 1e-9);
	CHECK(o.fs_failed == 0);

	b = drive_bond(L, P, &q);
	w = drive_normal(L, P, &q, &b, 0, 1.8 * UL, 180, NULL);
	CHECK(b.state == BOND_BROKEN_TENSION);
	CHECK_REL(w, 0.5 * SIGT * A * UF, 1e-12);
	CHECK(drive_energy(L, P, &q, &b) == 0);
}

/* Modified Mohr-Coulomb: bonded strength c A + F_n tan(phi_i), signed F_n
 * (compression raises it, tension lowers it); then purely frictional
 * F_n tan(phi_c). */
static void test_shear(void)
{
	law_pair q = pair_of();
	const double un[4] = {0, -0.5 * UL, -2 * UL, 0.5 * UL};
	for (int c = 0; c < 4; c++) {
		bond b = drive_bond(L, P, &q);
		/* Up to just below the strength, then just beyond it. */
		double fn = K0 * un[c], lim = COH * A - fn * TANPHI,
		       du = lim / KS / 10 * (1 - 1e-9);
		law_out o;
		for (int s = 1; s <= 10; s++) {
			o = drive_step(L, P, &q, &b, un[c], 0, 0, du, 0);
			CHECK_REL(o.fs[1], KS * du * s, 1e-12);
			CHECK(o.failed == 0);
		}
		CHECK_REL(o.fs[1], lim, 1e-8);
		o = drive_step(L, P, &q, &b, un[c], 0, 0, 0.01 * du, 0);
		CHECK(o.failed == CRACK_SHEAR && b.state == BOND_BROKEN_SHEAR);
		/* The crack record's forces: the trial shear force beyond the
		 * strength, and the normal force. */
		CHECK_REL(o.fs_failed, KS * du * 10.01, 1e-12);
		CHECK(fn == 0 ? o.fn_failed == 0 : fabs(o.fn_failed - fn) <= 1e-12 * fabs(fn));
		double dn, ds;
		L->damage(P, &b, &dn, &ds);
		CHECK(ds == 1);
		o = drive_step(L, P, &q, &b, un[c], 0, 0, du, 0);
		CHECK_NEAR(o.fs[1], fn < 0 ? -fn * TANPHI : 0, 1e-12 * lim);
		CHECK(fn < 0 ? fabs(o.fn - fn) <= 1e-12 * -fn : o.fn == 0);
	}
}

static void test_no_healing(void)
{
	law_pair q = pair_of();
	rng g;
	rng_seed(&g, 11);
	for (int run = 0; run < 20; run++) {
		bond b = drive_bond(L, P, &q);
		double dn0 = 0, ds0 = 0, cmax0 = 0, dn, ds;
		int broken = 0;
		for (int s = 0; s < 300; s++) {
			double un = rng_range(&g, -0.03 * d0, 1.3 * UF);
			double du = rng_range(&g, -0.2, 0.2) * COH * A / KS;
			drive_step(L, P, &q, &b, un, 0, 0, du, du);
			L->damage(P, &b, &dn, &ds);
			CHECK(dn >= dn0 && ds >= ds0);
			CHECK(b.h[2] >= cmax0);
			CHECK(!broken || b.state >= BOND_BROKEN_TENSION);
			broken = b.state >= BOND_BROKEN_TENSION;
			dn0 = dn, ds0 = ds, cmax0 = b.h[2];
		}
	}
}

/* The energy the law books: work done = change of stored energy +
 * dissipation in every step, through compaction, unloading and reloading,
 * a tension failure (1/2 sigma_t A u_n^f) and a shear rupture with sliding. */
static void test_energy_books(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	drive_books k = {0};
	const double path[4] = {0.02, 0.015, 0.04, 0.035};
	double c = 0, scale = K0 * d0 * d0 * 0.05 * 0.05;
	for (int n = 0; n < 4; n++) {
		for (int s = 1; s <= 50; s++) {
			double cs = c + (path[n] - c) * s / 50;
			CHECK_NEAR(drive_balance(L, P, &q, &b, &k, -cs * d0, 0, 0, 0), 0,
			           1e-12 * scale);
		}
		c = path[n];
	}
	CHECK(k.dissipated > 0);

	b = drive_bond(L, P, &q);
	k = (drive_books){0};
	double g = 0.5 * SIGT * A * UF;
	for (int s = 1; s <= 180; s++)
		CHECK_NEAR(drive_balance(L, P, &q, &b, &k, 1.8 * UL * s / 180, 0, 0, 0), 0,
		           1e-12 * g);
	CHECK_REL(k.dissipated, g, 1e-12);

	b = drive_bond(L, P, &q);
	k = (drive_books){0};
	double lim = COH * A + K0 * UL * TANPHI;
	CHECK_NEAR(drive_balance(L, P, &q, &b, &k, -UL, 0, 0, 0), 0, 1e-12 * g);
	for (int s = 1; s <= 30; s++)
		CHECK_NEAR(drive_balance(L, P, &q, &b, &k, -UL, 0, lim / KS / 10, 0), 0,
		           1e-12 * lim * lim / KS);
	CHECK(b.state == BOND_BROKEN_SHEAR && k.last.e_friction > 0);
}

int main(void)
{
	L = law_find("exponential");
	CHECK(L != NULL);
	P = L ? drive_parse(L, concrete, "exp.json") : NULL;
	CHECK(P != NULL);
	if (!L || !P) {
		fprintf(stderr, "%s\n", err_msg());
		return check_done();
	}
	test_constants();
	test_compression();
	test_tension();
	test_shear();
	test_no_healing();
	test_energy_books();
	L->free(P);
	return check_done();
}
