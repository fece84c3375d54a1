/* The local model of Oñate et al. 2015 (seeds/000) driven on one bond by
 * prescribed relative displacements: every branch of the force path against
 * the paper's equations, computed here independently from the material's
 * numbers. Concrete of Table 5, alpha = 1. */
#include "tests/laws/drive.h"

#include "lib/rng.h"

static const char *concrete = "{\"name\": \"concrete\", \"law\": \"onate\", \"density\": 2500,"
                              " \"E0\": 28e9, \"nu\": 0.2, \"tensile_strength\": 5e6,"
                              " \"shear_strength\": 16e6, \"mu1\": 0.9, \"mu2\": 0.25,"
                              " \"LCS1\": 20e6, \"LCS2\": 45e6, \"LCS3\": 70e6,"
                              " \"YRC1\": 3, \"YRC2\": 12, \"YRC3\": 22,"
                              " \"delta_n\": 0.2, \"delta_s\": 0.2, \"alpha\": 1.0}";

#define E0 28e9
#define NU 0.2
#define SIGT 5e6
#define TAU 16e6
#define MU1 0.9
#define MU2 0.25
#define DELTA 0.2 /* delta_n = delta_s */
#define LCS1_STRAIN (20e6 / E0)

/* Two spheres with a gap inside the interaction range (Eq. 16). */
static const double ri = 1.0e-3, rj = 1.5e-3, d0 = 2.6e-3;

static law_pair pair_of(void)
{
	law_pair q = {.ri = ri, .rj = rj, .d0 = d0};
	q.mi = 2500 * 4.0 / 3.0 * PI * ri * ri * ri;
	q.mj = 2500 * 4.0 / 3.0 * PI * rj * rj * rj;
	return q;
}

/* Eq. 21, 30, 36 with alpha = 1. */
#define A (PI * ri * ri)
#define KN (A * E0 / d0)
#define KS (KN / (2 * (1 + NU)))
#define UL (SIGT * A / KN) /* u_n^l of Eq. 49a */
#define UF ((1 + DELTA) * UL)

/* The compressive stress-strain curve of Fig. 10 for Table 5. */
static double sigma_curve(double eps)
{
	const double l1 = 20e6, l2 = 45e6, l3 = 70e6, y1 = 3, y2 = 12, y3 = 22;
	double e1 = l1 / E0, e2 = e1 + (l2 - l1) / (E0 / y1), e3 = e2 + (l3 - l2) / (E0 / y2);
	if (eps <= e1)
		return E0 * eps;
	if (eps <= e2)
		return l1 + E0 / y1 * (eps - e1);
	if (eps <= e3)
		return l2 + E0 / y2 * (eps - e2);
	return l3 + E0 / y3 * (eps - e3);
}

static const law *L;
static law_params *P;

static void test_constants(void)
{
	law_pair q = pair_of();
	law_const c;
	L->constants(P, &q, &c);
	double mij = q.mi * q.mj / (q.mi + q.mj);
	CHECK_REL(c.area, A, 1e-15);
	CHECK_REL(c.kn, KN, 1e-15);
	CHECK_REL(c.ks, KS, 1e-15);
	CHECK_REL(c.cn, 2 * PI * ri * 1.0 * 0.9 / d0 * sqrt(mij * KN),
	          1e-14); /* Eq. 30, xi = 0.9 */
	CHECK(c.rc == ri);
	CHECK_REL(L->bond_range(P), 1.10, 1e-15); /* beta = 0.10 (Sect. 4.2) */

	/* alpha = 40 P / N_c (Eq. 22) when the material does not give it. */
	const char *noalpha = "{\"name\": \"noalpha\", \"law\": \"onate\", \"density\": 2500,"
	                      " \"E0\": 28e9, \"nu\": 0.2, \"tensile_strength\": 5e6,"
	                      " \"shear_strength\": 16e6, \"mu1\": 0.9, \"mu2\": 0.25,"
	                      " \"LCS1\": 20e6, \"LCS2\": 45e6, \"LCS3\": 70e6, \"YRC1\": 3,"
	                      " \"YRC2\": 12, \"YRC3\": 22, \"delta_n\": 0.2, \"delta_s\": 0.2,"
	                      " \"beta\": 0.2, \"xi\": 0.5}";
	law_params *p = drive_parse(L, noalpha, "noalpha.json");
	CHECK(p != NULL);
	law_params *copy = L->copy(p);
	law_packing pk = {.porosity = 0.12, .coordination = 8};
	L->setup(p, &pk);
	L->constants(p, &q, &c);
	CHECK_REL(c.area, 0.6 * PI * ri * ri, 1e-15);
	CHECK_REL(c.kn, 0.6 * KN, 1e-15);
	CHECK_REL(c.cn, 2 * PI * ri * 0.6 * 0.5 / d0 * sqrt(mij * 0.6 * KN), 1e-14);
	CHECK_REL(L->bond_range(p), 1.2, 1e-15);
	/* A copy is set up on its own (the engine's, law.copy). */
	law_packing other = {.porosity = 0.1, .coordination = 10};
	L->setup(copy, &other);
	L->constants(copy, &q, &c);
	CHECK_REL(c.area, 0.4 * PI * ri * ri, 1e-15);
	L->constants(p, &q, &c);
	CHECK_REL(c.area, 0.6 * PI * ri * ri, 1e-15);
	L->free(copy);
	L->free(p);
	/* A given alpha is kept. */
	L->setup(P, &pk);
	L->constants(P, &q, &c);
	CHECK_REL(c.area, A, 1e-15);
}

/* Elastic loading, the softening branch of Eq. 46/49a ending at u_n^f,
 * then nothing in tension ever again. */
static void test_tension(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	double dn, ds, w = 0, fprev = 0, uprev = 0;
	int cracks = 0;
	for (int s = 1; s <= 100; s++) { /* elastic: F = K_n u_n (Eq. 29) */
		double u = UL * s / 100;
		law_out o = drive_step(L, P, &q, &b, u, 0, 0, 0, 0);
		CHECK_REL(o.fn, KN * u, 1e-12);
		CHECK(o.failed == 0 && b.state == BOND_INTACT);
		w += 0.5 * (o.fn + fprev) * (u - uprev);
		fprev = o.fn, uprev = u;
		CHECK_REL(drive_energy(L, P, &q, &b), w, 1e-12);
	}
	L->damage(P, &b, &dn, &ds);
	CHECK(dn == 0 && ds == 0);
	for (int s = 1; s < 20; s++) { /* softening: F = (1 - d_n) K_n u_n^l */
		double u = UL + (UF - UL) * s / 20;
		law_out o = drive_step(L, P, &q, &b, u, 0, 0, 0, 0);
		double d = (u / UL - 1) / DELTA;
		CHECK_REL(o.fn, (1 - d) * KN * UL, 1e-11);
		L->damage(P, &b, &dn, &ds);
		CHECK_NEAR(dn, d, 1e-12);
		CHECK(o.failed == 0 && b.state == BOND_DAMAGED);
	}
	/* The crack record's forces: the tension at the failing opening with
	 * the damage of the step before, and no shear. */
	double u19 = UL + (UF - UL) * 19 / 20, d19 = (u19 / UL - 1) / DELTA;
	law_out o = drive_step(L, P, &q, &b, UF, 0, 0, 0, 0);
	CHECK_NEAR(o.fn, 0, 1e-12 * KN * UL);
	if (o.failed == CRACK_TENSION)
		CHECK_REL(o.fn_failed, KN * UF * (1 - d19) * UL / u19, 1e-10);
	cracks += o.failed == CRACK_TENSION;
	int failed_first = o.failed == CRACK_TENSION;
	o = drive_step(L, P, &q, &b, UF * (1 + 1e-9), 0, 0, 0, 0);
	if (o.failed == CRACK_TENSION && !failed_first)
		CHECK_REL(o.fn_failed, KN * UF * (1 + 1e-9) * (1 - d19) * UL / u19, 1e-10);
	cracks += o.failed == CRACK_TENSION;
	CHECK(cracks == 1 && (failed_first || o.fs_failed == 0));
	CHECK(o.fn == 0 && b.state == BOND_BROKEN_TENSION);
	L->damage(P, &b, &dn, &ds);
	CHECK(dn == 1);
	/* Broken: no tension at any opening, and never a second crack. */
	for (double u = 2 * UF; u > 0; u -= UF / 7) {
		o = drive_step(L, P, &q, &b, u, 0, 0, 0, 0);
		CHECK(o.fn == 0 && o.failed == 0);
	}
	/* Compression is still carried (damage acts in tension and shear only). */
	o = drive_step(L, P, &q, &b, -UL, 0, 0, 0, 0);
	CHECK_REL(o.fn, -KN * UL, 1e-12);
	CHECK(b.state == BOND_BROKEN_TENSION);
}

/* Unloading from the softening branch follows the damaged secant K_n^d of
 * Eq. 46 back to the origin, reloading returns along it, damage stays. */
static void test_tension_unloading(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	double ustar = UL * (1 + 0.5 * DELTA); /* d_n = 0.5 */
	double fstar, dn, ds;
	drive_normal(L, P, &q, &b, 0, ustar, 30, &fstar);
	CHECK_REL(fstar, 0.5 * KN * UL, 1e-12);
	for (int s = 10; s >= 0; s--) {
		double u = ustar * s / 10;
		law_out o = drive_step(L, P, &q, &b, u, 0, 0, 0, 0);
		CHECK_NEAR(o.fn, fstar * u / ustar, 1e-12 * fstar);
		CHECK_NEAR(drive_energy(L, P, &q, &b), 0.5 * fstar * u * u / ustar,
		           1e-12 * fstar * UL);
		L->damage(P, &b, &dn, &ds);
		CHECK_NEAR(dn, 0.5, 1e-12);
	}
	/* Compression unaffected by tensile damage. */
	law_out o = drive_step(L, P, &q, &b, -0.5 * UL, 0, 0, 0, 0);
	CHECK_REL(o.fn, -0.5 * KN * UL, 1e-12);
	o = drive_step(L, P, &q, &b, ustar, 0, 0, 0, 0);
	CHECK_REL(o.fn, fstar, 1e-12);
	double u = UL * (1 + 0.75 * DELTA);
	o = drive_step(L, P, &q, &b, u, 0, 0, 0, 0);
	CHECK_REL(o.fn, 0.25 * KN * UL, 1e-11);
	L->damage(P, &b, &dn, &ds);
	CHECK_NEAR(dn, 0.75, 1e-12);
}

/* The work of a tension failure is the area under the force-displacement
 * curve, 1/2 F_nt u_n^f, and all of it is dissipated; a partial unloading
 * dissipates the area between the loading path and the secant. */
static void test_dissipation(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	double w = drive_normal(L, P, &q, &b, 0, 1.8 * UL, 180, NULL);
	CHECK(b.state == BOND_BROKEN_TENSION);
	CHECK_REL(w, 0.5 * SIGT * A * UF, 1e-12);
	CHECK(drive_energy(L, P, &q, &b) == 0);

	b = drive_bond(L, P, &q);
	double ustar = UL * (1 + 0.5 * DELTA), fstar = 0.5 * SIGT * A;
	double wl = drive_normal(L, P, &q, &b, 0, ustar, 110, NULL);
	CHECK_REL(wl, 0.5 * KN * UL * UL + 0.5 * (SIGT * A + fstar) * (ustar - UL), 1e-12);
	double wu = drive_normal(L, P, &q, &b, ustar, 0, 50, NULL);
	CHECK_REL(-wu, 0.5 * fstar * ustar, 1e-12); /* the secant gives back its triangle */
	CHECK_NEAR(drive_energy(L, P, &q, &b), 0, 1e-20);
}

/* Shear with no normal force: elastic K_s, softening of Eq. 46/49b with
 * strength tau^f A, failure at u_s^f, then Coulomb with no compression. */
static void test_shear(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	const double dir[3] = {0.6, 0.8, 0};
	double usl = TAU * A / KS, usf = (1 + DELTA) * usl, us = 0, dn, ds;
	for (int s = 1; s <= 40; s++) {
		double du = usl / 40;
		law_out o = drive_step(L, P, &q, &b, 0, 0, du * dir[0], du * dir[1], 0);
		us += du;
		for (int k = 0; k < 3; k++)
			CHECK_NEAR(o.fs[k], KS * us * dir[k], 1e-12 * TAU * A);
		CHECK(o.fn == 0 && o.failed == 0);
		CHECK_REL(drive_energy(L, P, &q, &b), 0.5 * KS * us * us, 1e-12);
	}
	for (int s = 1; s < 10; s++) {
		double du = (usf - usl) / 10;
		law_out o = drive_step(L, P, &q, &b, 0, 0, du * dir[0], du * dir[1], 0);
		us += du;
		double d = (us / usl - 1) / DELTA;
		CHECK_REL(drive_fs(&o), (1 - d) * TAU * A, 1e-10);
		CHECK_NEAR(o.fs[0] * dir[1] - o.fs[1] * dir[0], 0, 1e-12 * TAU * A);
		CHECK(o.fs[0] > 0 && o.failed == 0 && b.state == BOND_DAMAGED);
		L->damage(P, &b, &dn, &ds);
		CHECK_NEAR(ds, d, 1e-10);
		CHECK(dn == 0);
	}
	double du = (usf - usl) / 10 * (1 + 1e-6), dp = (us / usl - 1) / DELTA;
	law_out o = drive_step(L, P, &q, &b, 0, 0, du * dir[0], du * dir[1], 0);
	CHECK(o.failed == CRACK_SHEAR && b.state == BOND_BROKEN_SHEAR);
	CHECK(drive_fs(&o) == 0);
	/* The crack record's forces: the shear force at the failing slip with
	 * the damage of the step before, and the normal force (none). */
	CHECK_REL(o.fs_failed, (1 - dp) * TAU * A * (us + du) / us, 1e-10);
	CHECK(o.fn_failed == 0);
	L->damage(P, &b, &dn, &ds);
	CHECK(ds == 1 && dn == 0);
	/* Broken in shear: no tension, no shear without compression (Eq. 45). */
	o = drive_step(L, P, &q, &b, 0.5 * UL, 0, du, 0, 0);
	CHECK(o.fn == 0 && drive_fs(&o) == 0 && o.failed == 0);
}

/* The shear strength rises with the compressive force, tau^f A + mu1 |F_nc|
 * (Eq. 42); after shear failure the contact slides with mu2 |F_nc|
 * (Eq. 45), building up with K_s from zero and reversing with K_s. */
static void test_shear_compression(void)
{
	law_pair q = pair_of();
	const double sig[3] = {5e6, 10e6, 15e6}; /* below LCS1: elastic */
	for (int c = 0; c < 3; c++) {
		bond b = drive_bond(L, P, &q);
		double delta = sig[c] / E0 * d0, fnc = KN * delta;
		double fsl = TAU * A + MU1 * fnc, usl = fsl / KS, du = usl / 20, peak = 0;
		law_out o = drive_step(L, P, &q, &b, -delta, 0, 0, 0, 0);
		CHECK_REL(o.fn, -fnc, 1e-12);
		int s = 0;
		while (b.state != BOND_BROKEN_SHEAR && s < 100) {
			o = drive_step(L, P, &q, &b, -delta, 0, 0, du, 0);
			peak = fmax(peak, drive_fs(&o));
			s++;
			if (s == 20)
				CHECK_REL(drive_fs(&o), fsl, 1e-12);
			if (s == 22) /* d_s = 0.1 / 0.2 */
				CHECK_REL(drive_fs(&o), 0.5 * fsl, 1e-10);
			CHECK_REL(o.fn, -fnc, 1e-12);
		}
		CHECK_REL(peak, fsl, 1e-12);
		CHECK(s == 24 || s == 25); /* u_s^f = 1.2 u_s^l, at step 24 up to rounding */
		/* Friction: from zero with K_s up to mu2 F_nc, then sliding. */
		double lim = MU2 * fnc, dslide = lim / KS / 4.5;
		for (int k = 1; k <= 8; k++) {
			o = drive_step(L, P, &q, &b, -delta, 0, 0, dslide, 0);
			CHECK_REL(o.fs[1], fmin(KS * dslide * k, lim), 1e-12);
			CHECK(o.failed == 0);
		}
		o = drive_step(L, P, &q, &b, -delta, 0, 0, -dslide, 0); /* sticks on reversal */
		CHECK_REL(o.fs[1], lim - KS * dslide, 1e-12);
		for (int k = 0; k < 12; k++)
			o = drive_step(L, P, &q, &b, -delta, 0, 0, -dslide, 0);
		CHECK_REL(o.fs[1], -lim, 1e-12);
		CHECK_REL(drive_energy(L, P, &q, &b), 0.5 * fnc * fnc / KN + 0.5 * lim * lim / KS,
		          1e-12);
	}
}

/* After a tension failure, compression brings back Coulomb friction. */
static void test_friction_after_tension_failure(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	drive_normal(L, P, &q, &b, 0, 1.5 * UF, 40, NULL);
	CHECK(b.state == BOND_BROKEN_TENSION);
	double delta = 0.5 * LCS1_STRAIN * d0;
	law_out o = drive_step(L, P, &q, &b, -delta, 0, 0, 0, 0);
	double fnc = KN * delta, lim = MU2 * fnc;
	CHECK_REL(o.fn, -fnc, 1e-12);
	o = drive_step(L, P, &q, &b, -delta, 0, 10 * lim / KS, 0, 0);
	CHECK_REL(o.fs[0], lim, 1e-12);
	CHECK(o.failed == 0 && b.state == BOND_BROKEN_TENSION);
}

/* Elasto-plastic compression (Eq. 52-53, Fig. 10): loading along each
 * branch, elastic unloading with K_n0 from it, permanent indentation,
 * reloading with K_n0 back to the curve. */
static void test_compression(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	/* A point in each of the four branches (strain; LCS at 7.1e-4, 3.4e-3, 1.4e-2). */
	const double target[4] = {5e-4, 2.0e-3, 9e-3, 2.0e-2};
	double cmax = 0;
	for (int k = 0; k < 4; k++) {
		for (int s = 1; s <= 10; s++) { /* loading */
			double c = cmax + (target[k] - cmax) * s / 10;
			law_out o = drive_step(L, P, &q, &b, -c * d0, 0, 0, 0, 0);
			CHECK_REL(o.fn, -A * sigma_curve(c), 1e-12);
		}
		cmax = target[k];
		double fpk = A * sigma_curve(cmax), dmax = cmax * d0;
		double dp = dmax - fpk / KN; /* permanent indentation */
		CHECK(k == 0 ? fabs(dp) < 1e-12 * dmax : dp > 0);
		for (int s = 1; s <= 10; s++) { /* unloading to zero force, K_n0 */
			double d = dmax + (dp - dmax) * s / 10;
			law_out o = drive_step(L, P, &q, &b, -d, 0, 0, 0, 0);
			CHECK_NEAR(o.fn, -(fpk - KN * (dmax - d)), 1e-12 * fpk);
			CHECK_NEAR(drive_energy(L, P, &q, &b), 0.5 * o.fn * o.fn / KN,
			           1e-12 * fpk * dmax);
		}
		/* Beyond the permanent indentation: elastic tension from it. */
		law_out o = drive_step(L, P, &q, &b, -(dp - 0.5 * UL), 0, 0, 0, 0);
		CHECK_REL(o.fn, 0.5 * KN * UL, 1e-9);
		/* Reloading with K_n0 up to the historical maximum, then the curve. */
		double w = drive_normal(L, P, &q, &b, -dp, -dmax, 10, &o.fn);
		CHECK_REL(o.fn, -fpk, 1e-12);
		CHECK_REL(w, 0.5 * fpk * fpk / KN, 1e-10);
		CHECK_REL(drive_energy(L, P, &q, &b), w, 1e-10);
	}
	double dn, ds;
	L->damage(P, &b, &dn, &ds);
	CHECK(dn == 0 && ds == 0 && b.state == BOND_INTACT);
}

/* After plastic compression the tensile limit is reached at u_n^l from the
 * permanent indentation. */
static void test_tension_after_plasticity(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	double c = 2.0e-3, dmax = c * d0, dp = dmax - A * sigma_curve(c) / KN;
	drive_normal(L, P, &q, &b, 0, -dmax, 20, NULL);
	law_out o = drive_step(L, P, &q, &b, -dp + UL, 0, 0, 0, 0);
	CHECK_REL(o.fn, SIGT * A, 1e-9);
	CHECK(b.state == BOND_INTACT);
	o = drive_step(L, P, &q, &b, -dp + UL * (1 + 0.5 * DELTA), 0, 0, 0, 0);
	CHECK_REL(o.fn, 0.5 * SIGT * A, 1e-9);
	o = drive_step(L, P, &q, &b, -dp + UF * 1.001, 0, 0, 0, 0);
	CHECK(o.failed == CRACK_TENSION && o.fn == 0);
}

/* Fig. 7b: in tension the shear strength falls linearly from tau^f A at
 * zero opening to zero at u_n^l. */
static void test_coupled(void)
{
	char json[1024];
	snprintf(json, sizeof json, "%.*s, \"criterion\": \"coupled\"}", (int)strlen(concrete) - 1,
	         concrete);
	law_params *p = drive_parse(L, json, "coupled.json");
	CHECK(p != NULL);
	law_pair q = pair_of();
	for (int half = 0; half < 2; half++) {
		bond b = drive_bond(L, p, &q);
		double un = half ? 0.5 * UL : 0.25 * UL;
		double fsl = TAU * A * (1 - un / UL), du = fsl / KS / 10;
		double peak = 0;
		for (int s = 1; s <= 11; s++) {
			law_out o = drive_step(L, p, &q, &b, un, 0, du, 0, 0);
			CHECK_REL(o.fn, KN * un, 1e-12);
			peak = fmax(peak, o.fs[0]);
		}
		CHECK_REL(peak, fsl, 1e-12);
		double dn, ds;
		L->damage(p, &b, &dn, &ds);
		CHECK_NEAR(ds, 0.5, 1e-9); /* 11 steps: 1.1 u_s^l */
		CHECK(dn == 0);
	}
	/* At the tensile limit any shear displacement breaks the bond in shear. */
	bond b = drive_bond(L, p, &q);
	drive_step(L, p, &q, &b, UL, 0, 0, 0, 0);
	law_out o = drive_step(L, p, &q, &b, UL, 0, 1e-15, 0, 0);
	CHECK(o.failed == CRACK_SHEAR);
	/* In compression the criterion is the uncoupled one (mu1). */
	b = drive_bond(L, p, &q);
	double delta = 1e-4 * d0, fsl = TAU * A + MU1 * KN * delta;
	o = drive_step(L, p, &q, &b, -delta, 0, fsl / KS * (1 - 1e-9), 0, 0);
	CHECK_REL(o.fs[0], fsl, 1e-8);
	CHECK(b.state == BOND_INTACT);
	o = drive_step(L, p, &q, &b, -delta, 0, 1e-6 * fsl / KS, 0, 0);
	CHECK(b.state == BOND_DAMAGED);
	L->free(p);
}

/* Contact damping C_n du_n/dt (Eq. 29) adds to the normal force and leaves
 * the damage, which follows the elastic force, unchanged. */
static void test_damping(void)
{
	law_pair q = pair_of();
	law_const c;
	L->constants(P, &q, &c);
	bond a = drive_bond(L, P, &q), b = drive_bond(L, P, &q);
	for (int s = 1; s <= 30; s++) {
		double u = 1.1 * UL * s / 30, v = 0.01 * (s % 7 - 3);
		law_out oa = drive_step(L, P, &q, &a, u, 0, 0, 0, 0);
		law_out ob = drive_step(L, P, &q, &b, u, v, 0, 0, 0);
		CHECK_NEAR(ob.fn, oa.fn + c.cn * v, 1e-12 * SIGT * A);
		CHECK(memcmp(a.h, b.h, sizeof a.h) == 0 && memcmp(a.t, b.t, sizeof a.t) == 0);
	}
}

/* Damage and the historical maximum compression never decrease, a broken
 * bond stays broken, along an arbitrary path. */
static void test_no_healing(void)
{
	law_pair q = pair_of();
	rng g;
	rng_seed(&g, 5);
	for (int run = 0; run < 20; run++) {
		bond b = drive_bond(L, P, &q);
		double dn0 = 0, ds0 = 0, cmax0 = 0, dn, ds;
		int broken = 0;
		for (int s = 0; s < 400; s++) {
			double un = rng_range(&g, -0.02 * d0, 1.3 * UF);
			double du = rng_range(&g, -0.3, 0.3) * TAU * A / KS;
			drive_step(L, P, &q, &b, un, 0, du, 0.5 * du, 0);
			L->damage(P, &b, &dn, &ds);
			CHECK(dn >= dn0 && ds >= ds0 && dn <= 1 && ds <= 1);
			CHECK(b.h[2] >= cmax0);
			CHECK(!broken || b.state >= BOND_BROKEN_TENSION);
			broken = b.state >= BOND_BROKEN_TENSION;
			dn0 = dn, ds0 = ds, cmax0 = b.h[2];
		}
	}
}

/* The energy the law books: in every step the work done on the bond is the
 * change of its elastic energy plus what it reports as dissipated by damage,
 * plastic flow and friction (steps end on the kinks of the path, so the
 * trapezoidal work is exact); a tension failure dissipates 1/2 F_nt u_n^f. */
static void test_energy_books(void)
{
	law_pair q = pair_of();
	bond b = drive_bond(L, P, &q);
	drive_books k = {0};
	double g = 0.5 * SIGT * A * UF;
	for (int s = 1; s <= 180; s++)
		CHECK_NEAR(drive_balance(L, P, &q, &b, &k, 1.8 * UL * s / 180, 0, 0, 0), 0,
		           1e-12 * g);
	CHECK(b.state == BOND_BROKEN_TENSION);
	CHECK_REL(k.dissipated, g, 1e-12);

	/* Plastic compression: loading through three branches, unloading,
	 * reloading, unloading to the permanent indentation. */
	b = drive_bond(L, P, &q);
	k = (drive_books){0};
	const double path[5] = {2.0e-3, 9e-3, 8e-3, 1.2e-2, 1.2e-2 - sigma_curve(1.2e-2) / E0};
	double c = 0, scale = 0.5 * A * 70e6 * 70e6 / E0 * d0;
	for (int n = 0; n < 5; n++) {
		for (int s = 1; s <= 40; s++) {
			double cs = c + (path[n] - c) * s / 40;
			CHECK_NEAR(drive_balance(L, P, &q, &b, &k, -cs * d0, 0, 0, 0), 0,
			           1e-12 * scale);
		}
		c = path[n];
	}
	CHECK(k.dissipated > 0 && b.state == BOND_INTACT);

	/* Shear to failure under compression, then sliding. */
	b = drive_bond(L, P, &q);
	k = (drive_books){0};
	double delta = 0.5 * LCS1_STRAIN * d0, fnc = KN * delta;
	double fsl = TAU * A + MU1 * fnc, usl = fsl / KS, lim = MU2 * fnc;
	for (int s = 1; s <= 10; s++)
		CHECK_NEAR(drive_balance(L, P, &q, &b, &k, -delta * s / 10, 0, 0, 0), 0,
		           1e-12 * fsl * usl);
	for (int s = 1; s <= 24; s++) /* the last step just past u_s^f */
		CHECK_NEAR(drive_balance(L, P, &q, &b, &k, -delta, usl / 20 * (1 + 1e-9), 0, 0), 0,
		           1e-9 * fsl * usl);
	CHECK(b.state == BOND_BROKEN_SHEAR);
	double before = k.dissipated;
	CHECK_REL(before, 0.5 * fsl * (1 + DELTA) * usl, 1e-9);
	for (int s = 1; s <= 20; s++)
		CHECK_NEAR(drive_balance(L, P, &q, &b, &k, -delta, lim / KS / 4, 0, 0), 0,
		           1e-9 * fsl * usl);
	CHECK_REL(k.dissipated - before, lim * 16 * lim / KS / 4, 1e-9); /* 16 steps sliding */

	/* The viscous part of the normal force. */
	law_const cst;
	L->constants(P, &q, &cst);
	b = drive_bond(L, P, &q);
	law_out o = drive_step(L, P, &q, &b, 0.5 * UL, 0.02, 0, 0, 0);
	CHECK_REL(o.fn_viscous, cst.cn * 0.02, 1e-14);
	CHECK_REL(o.fn - o.fn_viscous, 0.5 * KN * UL, 1e-12);
}

int main(void)
{
	L = law_find("onate");
	CHECK(L != NULL);
	P = drive_parse(L, concrete, "concrete.json");
	CHECK(P != NULL);
	if (!L || !P) {
		fprintf(stderr, "%s\n", err_msg());
		return check_done();
	}
	test_constants();
	test_tension();
	test_tension_unloading();
	test_dissipation();
	test_shear();
	test_shear_compression();
	test_friction_after_tension_failure();
	test_compression();
	test_tension_after_plasticity();
	test_coupled();
	test_damping();
	test_no_healing();
	test_energy_books();
	L->free(P);
	return check_done();
}
