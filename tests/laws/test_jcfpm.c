/* JCFPM (seeds/002 ch. 3-4, Yade's JointedCohesiveFrictionalPM for bulk
 * bonds) driven on one bond by prescribed relative displacements. Concrete
 * of Table 4.4. */
#include "tests/laws/drive.h"

#include "lib/rng.h"

static const char *concrete =
    "{\"name\": \"jcfpm concrete\", \"law\": \"jcfpm\", \"density\": 2400,"
    " \"E\": 17e9, \"ks_ratio\": 0.15, \"tensile_strength\": 3.163e6,"
    " \"cohesion\": 9e6, \"friction_angle_deg\": 34.25,"
    " \"interaction_range\": 1.4}";

#define E 17e9
#define SIGT 3.163e6
#define COH 9e6
#define TANPHI tan(34.25 * PI / 180)

static const double ri = 1.25e-3, rj = 1.0e-3;

static law_pair pair_at(double d0)
{
	law_pair q = {.ri = ri, .rj = rj, .d0 = d0};
	q.mi = 2400 * 4.0 / 3.0 * PI * ri * ri * ri;
	q.mj = 2400 * 4.0 / 3.0 * PI * rj * rj * rj;
	return q;
}

#define KN (2 * E * ri * E * rj / (E * ri + E * rj)) /* Eq. 4.4 */
#define KS (0.15 * KN)
#define AREA (PI * rj * rj)   /* A_int = pi min(R)^2 */
#define UT (SIGT * AREA / KN) /* tensile rupture opening, Eq. 3.10 */

static const law *L;
static law_params *P;

static void test_constants(void)
{
	law_pair q = pair_at(2.4e-3);
	law_const c;
	L->constants(P, &q, &c);
	CHECK_REL(c.kn, KN, 1e-15);
	CHECK_REL(c.ks, KS, 1e-15);
	CHECK_REL(c.area, AREA, 1e-15);
	CHECK(c.rc == rj && c.cn == 0);
	CHECK_REL(L->bond_range(P), 1.4, 1e-15);
	law_packing pk = {.porosity = 0.4, .coordination = 10};
	L->setup(P, &pk); /* nothing depends on the packing */
	law_const c2;
	L->constants(P, &q, &c2);
	CHECK(memcmp(&c, &c2, sizeof c) == 0);
}

/* Linear in tension up to sigma_t A_int (Eq. 3.8, 3.10), brittle rupture
 * (zeta = 1), linear in compression without limit. */
static void test_normal(void)
{
	law_pair q = pair_at(2.4e-3);
	bond b = drive_bond(L, P, &q);
	for (int s = 1; s <= 10; s++) {
		double u = UT * s / 10;
		law_out o = drive_step(L, P, &q, &b, u, 0, 0, 0, 0);
		CHECK_REL(o.fn, KN * u, 1e-13);
		CHECK(o.failed == 0 && b.state == BOND_INTACT);
		CHECK_REL(drive_energy(L, P, &q, &b), 0.5 * KN * u * u, 1e-13);
	}
	double stored = drive_energy(L, P, &q, &b);
	CHECK_REL(stored, 0.5 * SIGT * AREA * UT, 1e-12);
	law_out o = drive_step(L, P, &q, &b, UT * (1 + 1e-9), 0, 0, 0, 0);
	CHECK(o.failed == CRACK_TENSION && o.fn == 0 && b.state == BOND_BROKEN_TENSION);
	/* The crack record's forces: those the criterion judged. */
	CHECK_REL(o.fn_failed, KN * UT * (1 + 1e-9), 1e-13);
	CHECK(o.fs_failed == 0);
	/* Brittle: the energy dissipated is the elastic energy at the peak, the
	 * area under the (vertical) softening branch. */
	CHECK(drive_energy(L, P, &q, &b) == 0);
	double dn, ds;
	L->damage(P, &b, &dn, &ds);
	CHECK(dn == 1 && ds == 0);
	o = drive_step(L, P, &q, &b, UT * 0.5, 0, 0, 0, 0);
	CHECK(o.fn == 0 && o.failed == 0);

	b = drive_bond(L, P, &q);
	for (int s = 1; s <= 10; s++) {
		double u = -200 * UT * s / 10;
		o = drive_step(L, P, &q, &b, u, 0, 0, 0, 0);
		CHECK_REL(o.fn, KN * u, 1e-13);
	}
	o = drive_step(L, P, &q, &b, 0.5 * UT, 0, 0, 0, 0); /* elastic: no plasticity */
	CHECK_REL(o.fn, 0.5 * KN * UT, 1e-13);
	CHECK(b.state == BOND_INTACT);
}

/* Incremental shear with k_s, bond strength c A + F_n tan(phi_b) rising
 * with compression (Eq. 3.12-3.13), rupture, then friction (Eq. 3.14). */
static void test_shear(void)
{
	law_pair q = pair_at(2.4e-3);
	const double comp[3] = {0, 5 * UT, 40 * UT};
	for (int c = 0; c < 3; c++) {
		bond b = drive_bond(L, P, &q);
		/* Up to just below the strength, then just beyond it. */
		double fnc = KN * comp[c], lim = COH * AREA + fnc * TANPHI;
		double du = lim / KS / 10 * (1 - 1e-9);
		law_out o;
		for (int s = 1; s <= 10; s++) {
			o = drive_step(L, P, &q, &b, -comp[c], 0, du, 0, 0);
			CHECK_REL(o.fs[0], KS * du * s, 1e-12);
			CHECK(o.failed == 0);
			CHECK_REL(drive_energy(L, P, &q, &b),
			          0.5 * KS * du * du * s * s + 0.5 * KN * comp[c] * comp[c], 1e-12);
		}
		CHECK_REL(o.fs[0], lim, 1e-8);
		o = drive_step(L, P, &q, &b, -comp[c], 0, 0.01 * du, 0, 0);
		CHECK(o.failed == CRACK_SHEAR && b.state == BOND_BROKEN_SHEAR);
		/* The crack record's forces: the trial shear force beyond the
		 * strength, and the normal force. */
		CHECK_REL(o.fs_failed, KS * du * 10.01, 1e-12);
		CHECK(c == 0 ? o.fn_failed == 0 : fabs(o.fn_failed + fnc) <= 1e-12 * fnc);
		/* In the step it breaks the force is capped at the bond strength. */
		CHECK_REL(o.fs[0], lim, 1e-12);
		double dn, ds;
		L->damage(P, &b, &dn, &ds);
		CHECK(dn == 0 && ds == 1);
		o = drive_step(L, P, &q, &b, -comp[c], 0, du, 0, 0);
		CHECK_NEAR(o.fs[0], fnc * TANPHI, 1e-12 * lim);
		CHECK(c == 0 ? o.fn == 0 : fabs(o.fn + fnc) <= 1e-12 * fnc);
		if (c) { /* sliding, sticking on reversal */
			o = drive_step(L, P, &q, &b, -comp[c], 0, -0.1 * du, 0, 0);
			CHECK_REL(o.fs[0], fnc * TANPHI - 0.1 * KS * du, 1e-12);
		}
	}
	/* Tension lowers the strength: c A - F_n tan(phi_b); breaking in
	 * tension removes the interaction altogether. */
	bond b = drive_bond(L, P, &q);
	double ft = 0.5 * KN * UT, lim = COH * AREA - ft * TANPHI, du = lim / KS;
	law_out o = drive_step(L, P, &q, &b, 0.5 * UT, 0, du, 0, 0);
	CHECK_REL(o.fs[0], lim, 1e-12);
	CHECK(o.failed == 0);
	o = drive_step(L, P, &q, &b, 0.5 * UT, 0, 1e-3 * du, 0, 0);
	CHECK(o.failed == CRACK_SHEAR && o.fn == 0 && drive_fs(&o) == 0);
}

/* A bond of pair q (bonded across a gap) broken in shear under
 * compression, still pushing about its bonding distance while compressed,
 * then opened and brought back to a distance beyond r_i + r_j: no force
 * there. Returns the bond, apart. */
static bond broken_in_shear_then_apart(const law_params *p, const law_pair *q)
{
	bond b = drive_bond(L, p, q);
	double fnc = KN * 10 * UT;
	drive_step(L, p, q, &b, -10 * UT, 0, 2 * (COH * AREA + fnc * TANPHI) / KS, 0, 0);
	CHECK(b.state == BOND_BROKEN_SHEAR);
	law_out o = drive_step(L, p, q, &b, -5 * UT, 0, 0, 0, 0);
	CHECK_REL(o.fn, -5 * KN * UT, 1e-12);
	o = drive_step(L, p, q, &b, 0.5 * UT, 0, 0, 0, 0);
	CHECK(o.fn == 0);
	o = drive_step(L, p, q, &b, -5 * UT, 0, 0, 0, 0); /* d > ri + rj: apart */
	CHECK(o.fn == 0);
	return b;
}

/* A broken pair loses its reference length once apart: it interacts again
 * as a frictional contact from the distance at which it touches again, as
 * Yade erases the interaction and detects a new one. */
static void test_recontact(void)
{
	/* Bonded across a gap: d0 > ri + rj. */
	law_pair q = pair_at(2.4e-3);
	bond b = drive_bond(L, P, &q);
	drive_step(L, P, &q, &b, 2 * UT, 0, 0, 0, 0);
	CHECK(b.state == BOND_BROKEN_TENSION);
	law_out o = drive_step(L, P, &q, &b, -0.1e-3, 0, 1e-6, 0, 0); /* d = 2.3 mm: apart */
	CHECK(o.fn == 0 && drive_fs(&o) == 0);
	o = drive_step(L, P, &q, &b, -0.2e-3, 0, 0, 0, 0); /* d = 2.2 mm: overlap 0.05 mm */
	CHECK_REL(o.fn, -KN * 0.05e-3, 1e-9);
	o = drive_step(L, P, &q, &b, -0.2e-3, 0, 1.0, 0, 0); /* slides */
	CHECK_REL(o.fs[0], KN * 0.05e-3 * TANPHI, 1e-9);
	CHECK(o.failed == 0 && b.state == BOND_BROKEN_TENSION);

	/* Bonded with an overlap: still touching after rupture, the new contact
	 * starts from the distance at rupture. */
	q = pair_at(2.2e-3);
	b = drive_bond(L, P, &q);
	drive_step(L, P, &q, &b, 2 * UT, 0, 0, 0, 0);
	CHECK(b.state == BOND_BROKEN_TENSION);
	o = drive_step(L, P, &q, &b, 2 * UT, 0, 0, 0, 0);
	CHECK(o.fn == 0);
	o = drive_step(L, P, &q, &b, UT, 0, 0, 0, 0);
	CHECK_REL(o.fn, -KN * UT, 1e-9);

	/* Broken in shear under compression: keeps its reference length while
	 * compressed (the interaction survives in Yade), loses it once apart. */
	q = pair_at(2.4e-3);
	b = broken_in_shear_then_apart(P, &q);
}

/* contact.conventions "yade" (Yade's rule): a pair whose bond broke in
 * tension, or that opened after breaking, has ended; it starts again
 * without force in the first step it overlaps, at that distance, and ends
 * again in the first step it is open past it. */
static void test_recontact_yade(void)
{
	char json[512];
	snprintf(json, sizeof json, "%.*s, \"contact\": {\"conventions\": \"yade\"}}",
	         (int)strlen(concrete) - 1, concrete);
	law_params *F = drive_parse(L, json, "jcfpm-yade.json");
	CHECK(F != NULL);
	if (!F)
		return;
	/* Bonded across a gap: d0 = 2.4 mm > ri + rj = 2.25 mm. */
	law_pair q = pair_at(2.4e-3);
	bond b = drive_bond(L, F, &q);
	drive_step(L, F, &q, &b, 2 * UT, 0, 0, 0, 0);
	CHECK(b.state == BOND_BROKEN_TENSION);
	law_out o = drive_step(L, F, &q, &b, -0.1e-3, 0, 1e-6, 0, 0); /* d = 2.3 mm: apart */
	CHECK(o.fn == 0 && drive_fs(&o) == 0);
	o = drive_step(L, F, &q, &b, -0.2e-3, 0, 1e-6, 0, 0); /* d = 2.2 mm: starts here */
	CHECK(o.fn == 0 && drive_fs(&o) == 0);
	o = drive_step(L, F, &q, &b, -0.25e-3, 0, 0, 0, 0); /* 0.05 mm closer */
	CHECK_REL(o.fn, -KN * 0.05e-3, 1e-9);
	o = drive_step(L, F, &q, &b, -0.25e-3, 0, 1.0, 0, 0); /* slides */
	CHECK_REL(o.fs[0], KN * 0.05e-3 * TANPHI, 1e-9);
	o = drive_step(L, F, &q, &b, -0.21e-3, 0, 0, 0, 0);
	CHECK_REL(o.fn, -KN * 0.01e-3, 1e-6);
	o = drive_step(L, F, &q, &b, -0.19e-3, 0, 0, 0, 0); /* open past 2.2 mm: ends */
	CHECK(o.fn == 0 && drive_fs(&o) == 0);
	o = drive_step(L, F, &q, &b, -0.195e-3, 0, 0, 0, 0); /* overlapping: starts again */
	CHECK(o.fn == 0);
	o = drive_step(L, F, &q, &b, -0.2e-3, 0, 0, 0, 0);
	CHECK_REL(o.fn, -KN * 0.005e-3, 1e-6);
	CHECK(b.state == BOND_BROKEN_TENSION && o.failed == 0);

	/* Bonded with an overlap: still overlapping after the rupture, so it
	 * starts again in the next step, at that distance. */
	q = pair_at(2.2e-3);
	b = drive_bond(L, F, &q);
	drive_step(L, F, &q, &b, 2 * UT, 0, 0, 0, 0);
	CHECK(b.state == BOND_BROKEN_TENSION);
	o = drive_step(L, F, &q, &b, 2 * UT, 0, 0, 0, 0);
	CHECK(o.fn == 0 && drive_energy(L, F, &q, &b) == 0);
	o = drive_step(L, F, &q, &b, UT, 0, 0, 0, 0);
	CHECK_REL(o.fn, -KN * UT, 1e-9);

	/* Broken in shear under compression: acts about its bonding distance
	 * while compressed, ends once open. */
	q = pair_at(2.4e-3);
	b = broken_in_shear_then_apart(F, &q);
	o = drive_step(L, F, &q, &b, -0.2e-3, 0, 0, 0, 0); /* d = 2.2 mm: starts */
	CHECK(o.fn == 0);
	o = drive_step(L, F, &q, &b, -0.21e-3, 0, 0, 0, 0);
	CHECK_REL(o.fn, -KN * 0.01e-3, 1e-6);
	L->free(F);

	snprintf(json, sizeof json, "%.*s, \"contact\": {\"conventions\": \"dem\"}}",
	         (int)strlen(concrete) - 1, concrete);
	const char *msg = drive_error(L, json, "bad.json");
	CHECK(strstr(msg, "conventions") && strstr(msg, "yade"));
	if (!strstr(msg, "yade"))
		fprintf(stderr, "message: %s\n", msg);
}

static void test_no_healing(void)
{
	law_pair q = pair_at(2.3e-3);
	rng g;
	rng_seed(&g, 7);
	for (int run = 0; run < 20; run++) {
		bond b = drive_bond(L, P, &q);
		int broken = 0;
		double dn, ds, dn0 = 0, ds0 = 0;
		for (int s = 0; s < 300; s++) {
			double un = rng_range(&g, -30 * UT, 1.05 * UT);
			double du = rng_range(&g, -0.2, 0.2) * COH * AREA / KS;
			law_out o = drive_step(L, P, &q, &b, un, 0, du, -du, 0);
			L->damage(P, &b, &dn, &ds);
			CHECK(dn >= dn0 && ds >= ds0);
			CHECK(!broken || (b.state >= BOND_BROKEN_TENSION && o.failed == 0));
			CHECK(b.state != BOND_DAMAGED);
			broken = b.state >= BOND_BROKEN_TENSION;
			dn0 = dn, ds0 = ds;
		}
	}
}

/* The energy the law books: work done = change of stored energy +
 * dissipation in every step; a rupture dissipates what the bond stored. */
static void test_energy_books(void)
{
	law_pair q = pair_at(2.4e-3);
	bond b = drive_bond(L, P, &q);
	drive_books k = {0};
	double g = 0.5 * SIGT * AREA * UT;
	for (int s = 1; s <= 10; s++)
		CHECK_NEAR(drive_balance(L, P, &q, &b, &k, UT * s / 10, 0, 0, 0), 0, 1e-12 * g);
	drive_booked(L, P, &q, &b, &k, UT * (1 + 1e-9), 0, 0, 0);
	CHECK(b.state == BOND_BROKEN_TENSION && drive_energy(L, P, &q, &b) == 0);
	CHECK_REL(k.dissipated, g, 1e-8);

	/* Shear rupture under compression, then sliding. */
	b = drive_bond(L, P, &q);
	k = (drive_books){0};
	double fnc = 10 * KN * UT, lim = COH * AREA + fnc * TANPHI, fric = fnc * TANPHI;
	double scale = 0.5 * lim * lim / KS;
	CHECK_NEAR(drive_balance(L, P, &q, &b, &k, -10 * UT, 0, 0, 0), 0, 1e-12 * scale);
	for (int s = 1; s <= 30; s++)
		CHECK_NEAR(drive_balance(L, P, &q, &b, &k, -10 * UT, lim / KS / 10, 0, 0), 0,
		           1e-12 * scale);
	CHECK(b.state == BOND_BROKEN_SHEAR);
	CHECK(k.dissipated > 0 && k.last.e_friction > 0);
	CHECK_REL(k.last.e_friction, fric * lim / KS / 10, 1e-12); /* steady sliding */
}

int main(void)
{
	L = law_find("jcfpm");
	CHECK(L != NULL);
	P = L ? drive_parse(L, concrete, "jcfpm.json") : NULL;
	CHECK(P != NULL);
	if (!L || !P) {
		fprintf(stderr, "%s\n", err_msg());
		return check_done();
	}
	test_constants();
	test_normal();
	test_shear();
	test_recontact();
	test_recontact_yade();
	test_no_healing();
	test_energy_books();
	L->free(P);
	return check_done();
}
