/* "jcfpm": the Jointed Cohesive Frictional Particle Model of Scholtès &
 * Donzé for bulk bonds, as Yade's Law2_ScGeom_JCFpmPhys_
 * JointedCohesiveFrictionalPM and Ip2_JCFpmMat_JCFpmMat_JCFpmPhys compute it
 * (seeds/002 ch. 3-4; equation numbers are 002's). One material, so
 * E1 = E2 = E.
 *
 * Bonds form between spheres with d <= gamma (r_i + r_j), gamma the
 * interaction range coefficient (Sect. 4.2); d is the equilibrium distance.
 *
 *   k_n = 2 E R1 E R2 / (E R1 + E R2)          (Eq. 4.4)
 *   k_s = (k_s/k_n) k_n                        (Eq. 4.5; Table 4.5: 0.15, Yade's "poisson")
 *   A_int = pi min(R1, R2)^2                   (Eq. 3.10; area.h, alpha = 1)
 *   F_n = k_n u_n in tension and compression   (Eq. 3.8)
 *
 * Tension: brittle rupture (softening factor zeta = 1, Sect. 3.2.2) once
 * u_n > sigma_t A_int / k_n (Eq. 3.10). Shear: incremental with k_s
 * (Eq. 3.12), Mohr-Coulomb bond strength c A_int + F_n tan(phi_b)
 * (Eq. 3.13), rupture beyond it, then friction F_n tan(phi_c) (Eq. 3.14;
 * phi_b = phi_c in Yade, Eq. 3.15, unless the material gives both); see
 * shear.h.
 *
 * Broken bonds are frictional contacts. Yade erases an interaction whose
 * bond broke in tension, or a non-cohesive one whose spheres separate, and
 * detects a new one when they touch again, taking the distance then as its
 * equilibrium distance. Here the reference distance moves instead: once a
 * broken pair is apart it becomes min(distance now, r_i + r_j), so the
 * contact acts again from the moment the spheres touch. With Yade's contact
 * conventions (laws/material.h) the pair follows Yade's rule: ended
 * (h[1] = 1) when it breaks in tension or opens, it starts again without
 * force in the first step it overlaps, at that distance.
 *
 * No contact damping (Yade uses its global damping only): C_n = 0.
 *
 * History: h[0] the shift of the reference distance from d (m), h[1] 1
 * while a broken pair has ended (Yade's conventions), h[2] k_n (Eq. 4.4),
 * the bond's constant, kept so that a step need not divide for it (init,
 * and restore after a checkpoint); t the elastic shear displacement,
 * F_s = k_s t. A JCFPM bond is intact or broken, never damaged.
 */
#include <stdlib.h>

#include "solve/kinematics.h"
#include "solve/laws/area.h"
#include "solve/laws/material.h"
#include "solve/laws/shear.h"

typedef struct {
	double E;          /* Pa */
	double ks_over_kn; /* Table 4.5 */
	double sigma_t;    /* Pa, tensile strength */
	double cohesion;   /* Pa */
	double tan_b;      /* bond friction, Eq. 3.13 */
	double tan_c;      /* contact (residual) friction, Eq. 3.14 */
	double range;      /* gamma */
	int yade;          /* contact.conventions "yade" */
} jcfpm_params;

static const double DEG = DEM_PI / 180;

static law_params *jcfpm_parse(cfg *m)
{
	jcfpm_params *p = calloc(1, sizeof *p);
	double phi_c, phi_b;
	int conventions;
	if (!p || contact_conventions_parse(m, &conventions) ||
	    cfg_number(m, "E", &p->E, "Pa", CFG_POS, INFINITY) ||
	    cfg_number(m, "ks_ratio", &p->ks_over_kn, "", 0, INFINITY) ||
	    cfg_number(m, "tensile_strength", &p->sigma_t, "Pa", 0, INFINITY) ||
	    cfg_number(m, "cohesion", &p->cohesion, "Pa", 0, INFINITY) ||
	    cfg_number(m, "friction_angle_deg", &phi_c, "deg", 0, 89) ||
	    cfg_number_or(m, "bond_friction_angle_deg", &phi_b, phi_c, "deg", 0, 89) ||
	    cfg_number(m, "interaction_range", &p->range, "", 1, 2)) {
		free(p);
		return NULL;
	}
	p->yade = conventions == CONTACT_YADE;
	p->tan_b = tan(phi_b * DEG);
	p->tan_c = tan(phi_c * DEG);
	return (law_params *)p;
}

static void jcfpm_free(law_params *p) { free(p); }

static law_params *jcfpm_copy(const law_params *p)
{
	return law_params_dup(p, sizeof(jcfpm_params));
}

static double jcfpm_range(const law_params *lp) { return ((const jcfpm_params *)lp)->range; }

static void jcfpm_setup(law_params *p, const law_packing *pk) { (void)p, (void)pk; }

/* k_n (Eq. 4.4). */
static double stiffness(const jcfpm_params *p, const law_pair *pair)
{
	double a = p->E * pair->ri, b = p->E * pair->rj;
	return 2 * a * b / (a + b);
}

static void jcfpm_constants(const law_params *lp, const law_pair *pair, law_const *out)
{
	const jcfpm_params *p = (const jcfpm_params *)lp;
	out->kn = stiffness(p, pair);
	out->ks = p->ks_over_kn * out->kn;
	out->cn = 0;
	out->area = area_of(1, pair);
	out->rc = area_rc(pair);
}

/* The bond's k_n kept in h[2]. */
static void jcfpm_restore(const law_params *lp, const law_pair *pair, bond *b)
{
	b->h[2] = stiffness((const jcfpm_params *)lp, pair);
}

/* A new bond: intact, at rest, its k_n kept. */
static void jcfpm_init(const law_params *lp, const law_pair *pair, bond *b)
{
	shear_new_bond(lp, pair, b);
	jcfpm_restore(lp, pair, b);
}

static void no_force(bond *b, law_out *out)
{
	memset(b->t, 0, sizeof b->t);
	out->fn = 0;
	memset(out->fs, 0, sizeof out->fs);
}

/* A broken pair apart: the interaction is gone until the spheres touch
 * (with Yade's conventions, it has ended until they overlap). */
static void apart(const jcfpm_params *p, const law_pair *pair, bond *b, double un, law_out *out)
{
	if (p->yade)
		b->h[1] = 1;
	else
		b->h[0] = law_min(un, pair->ri + pair->rj - pair->d0);
	no_force(b, out);
}

static inline void jcfpm_force(const law_params *lp, const law_pair *pair, bond *b,
                               const law_kin *k, law_out *out)
{
	const jcfpm_params *p = (const jcfpm_params *)lp;
	double kn = b->h[2], ks = p->ks_over_kn * kn, A = area_of(1, pair);
	double u = k->un - b->h[0];
	int intact = b->state == BOND_INTACT;
	out->failed = 0;
	if (intact && u > p->sigma_t * A / kn) { /* its stored energy is released */
		out->fn_failed = kn * u;
		out->fs_failed = ks * v3_norm(b->t);
		out->e_damage += 0.5 * kn * u * u + 0.5 * ks * v3_dot(b->t, b->t);
		shear_break(b, out, BOND_BROKEN_TENSION, CRACK_TENSION);
		apart(p, pair, b, k->un, out);
		return;
	}
	if (!intact && b->h[1] != 0) { /* ended (Yade's conventions): no force */
		if (k->un + pair->d0 - (pair->ri + pair->rj) < 0) { /* overlaps: starts here */
			b->h[0] = k->un;
			b->h[1] = 0;
		}
		no_force(b, out);
		return;
	}
	if (!intact && u > 0) {
		apart(p, pair, b, k->un, out);
		return;
	}
	double fn = kn * u;
	if (shear_mohr_coulomb(b->t, k->dus, ks, -fn, p->cohesion * A, p->tan_b, p->tan_c, intact,
	                       out)) {
		b->state = BOND_BROKEN_SHEAR;
		out->failed = CRACK_SHEAR;
		out->fn_failed = fn;
		if (fn > 0) { /* in tension: erased */
			out->e_damage += 0.5 * fn * fn / kn;
			apart(p, pair, b, k->un, out);
			return;
		}
	}
	out->fn = fn;
	v3_scale(out->fs, b->t, ks);
}

/* force_batch: the lanes of intact bonds that stay intact all together,
 * with jcfpm_force's expressions (so the same to the bit) and no branches,
 * which the compiler turns into vector instructions; then every other lane
 * (breaking or broken) by jcfpm_force itself. */
DEM_VECTOR_CLONES __attribute__((flatten)) static void jcfpm_batch(const law_params *lp,
                                                                   law_batch *B)
{
	const jcfpm_params *p = (const jcfpm_params *)lp;
	int32_t elastic[LAW_LANES];
	int n = B->n;
	for (int q = 0; q < n; q++) {
		double kn = B->h[2][q], ks = p->ks_over_kn * kn,
		       A = area_of_radii(1, B->ri[q], B->rj[q]);
		double u = B->un[q] - B->h[0][q];
		double t0 = B->t[0][q] + B->dus[0][q], t1 = B->t[1][q] + B->dus[1][q],
		       t2 = B->t[2][q] + B->dus[2][q];
		double fn = kn * u;
		double limit = p->cohesion * A + -fn * p->tan_b,
		       f = ks * sqrt(t0 * t0 + t1 * t1 + t2 * t2);
		int32_t ok =
		    (B->state[q] == BOND_INTACT) & !(u > p->sigma_t * A / kn) & (f <= limit);
		elastic[q] = ok;
		B->fn[q] = fn;
		B->fn_viscous[q] = 0;
		B->fs[0][q] = t0 * ks;
		B->fs[1][q] = t1 * ks;
		B->fs[2][q] = t2 * ks;
		B->t[0][q] = ok ? t0 : B->t[0][q];
		B->t[1][q] = ok ? t1 : B->t[1][q];
		B->t[2][q] = ok ? t2 : B->t[2][q];
	}
	LAW_BATCH_REST(jcfpm_force, lp, B, elastic);
}

/* force_pairs: jcfpm_batch's vector loop, from the batch's lanes
 * (law_pairs_load) to the forces in one pass (kinematics.h). With
 * `broken`, also the lanes of broken bonds, as jcfpm_force computes them:
 * a pair apart (no force; its reference distance moved, or its end
 * marked), ended (no force; started again where it overlaps), or in
 * contact under Coulomb friction (shear_slip, its work in
 * o->e_friction); without it (no broken bond in the batch) none of that is
 * computed and the history stays as it is. */
static inline __attribute__((always_inline)) int jcfpm_pairs_body(LAW_PAIRS_PARAMS,
                                                                  law_fused *restrict o, int broken)
{
	const jcfpm_params *p = (const jcfpm_params *)lp;
	o->history = broken;
	o->friction = broken;
	int count = 0;
	for (int q = 0; q < n; q++) {
		pair_motion k = law_lanes_motion(L, q, dt);
		double h[LAW_NHIST] = {L->h[0][q], L->h[1][q], L->h[2][q]};
		double ri = L->ri[q], rj = L->rj[q];
		double kn = h[2], ks = p->ks_over_kn * kn, A = area_of_radii(1, ri, rj);
		double u = k.un - h[0];
		double t[3] = {k.t[0] + k.dus[0], k.t[1] + k.dus[1], k.t[2] + k.dus[2]};
		double fn = kn * u;
		double limit = p->cohesion * A + -fn * p->tan_b,
		       tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2], f = 0;
		int32_t ok =
		    (L->state[q] == BOND_INTACT) & law_surely_below(u * kn, p->sigma_t * A);
		ok &= law_shear_within(broken, ks, tt, limit, &f);
		double fs[3] = {t[0] * ks, t[1] * ks, t[2] * ks};
		if (broken) {
			int32_t gone = L->state[q] != BOND_INTACT, ended = gone & (h[1] != 0);
			int32_t starts = ended & (k.un + L->d0[q] - (ri + rj) < 0);
			int32_t away = gone & !ended & (u > 0), touch = gone & !ended & !(u > 0);
			/* apart; an ended pair that overlaps starts again */
			double from = law_min(k.un, ri + rj - L->d0[q]);
			h[0] = law_sel(starts, k.un, law_sel(away & !p->yade, from, h[0]));
			h[1] = law_sel(starts, 0, law_sel(away & p->yade, 1, h[1]));
			/* in contact: shear_slip with the limit F_nc tan(phi_c) */
			o->e_friction[q] = shear_slip_lane(t, k.t, ks, f, -fn * p->tan_c, touch);
			int64_t none = gone & !touch; /* no_force */
			for (int i = 0; i < 3; i++) {
				t[i] = law_sel(none, 0, t[i]);
				fs[i] = law_sel(none, 0, t[i] * ks);
			}
			fn = law_sel(none, 0, fn);
			ok |= gone;
		}
		law_fused_put(o, q, ok, &k, fn, 0, fs, dt, t, broken ? h : NULL, L->state[q]);
		count += ok;
	}
	return count;
}

/* law_lanes_broken's states from BOND_BROKEN_TENSION on are those other
 * than BOND_INTACT here: a JCFPM bond is never BOND_DAMAGED. */
LAW_PAIRS_BROKEN(jcfpm_pairs, jcfpm_pairs_body)

static double jcfpm_energy(const law_params *lp, const law_pair *pair, const bond *b, double un)
{
	const jcfpm_params *p = (const jcfpm_params *)lp;
	double kn = stiffness(p, pair), u = un - b->h[0];
	if (b->state != BOND_INTACT && (u > 0 || b->h[1] != 0))
		return 0;
	return 0.5 * kn * u * u + 0.5 * p->ks_over_kn * kn * v3_dot(b->t, b->t);
}

static void jcfpm_damage(const law_params *p, const bond *b, double *dn, double *ds)
{
	(void)p;
	*dn = b->state == BOND_BROKEN_TENSION;
	*ds = b->state == BOND_BROKEN_SHEAR;
}

const law law_jcfpm = {
    .name = "jcfpm",
    .summary = "JCFPM (Scholtès & Donzé; Yade's JointedCohesiveFrictionalPM) for bulk "
               "bonds: brittle tension, Mohr-Coulomb shear",
    .parse = jcfpm_parse,
    .free = jcfpm_free,
    .copy = jcfpm_copy,
    .bond_range = jcfpm_range,
    .setup = jcfpm_setup,
    .constants = jcfpm_constants,
    .init = jcfpm_init,
    .restore = jcfpm_restore,
    .force = jcfpm_force,
    .force_batch = jcfpm_batch,
    .force_pairs = jcfpm_pairs,
    .energy = jcfpm_energy,
    .damage = jcfpm_damage,
    .h_dropped = 1,
};
