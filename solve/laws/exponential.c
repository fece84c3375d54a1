/* "exponential": the high-confinement law of Tran, Donzé & Marin 2011 as
 * described in seeds/001 §3.3.3 (its Eq. 60-66; the formulas are those of
 * ../shared/MODELS.md §4, the constants of 001 Table 5 are parameters).
 *
 * Bonds form between spheres with d <= gamma (r_i + r_j), gamma the
 * interaction range; d is the zero-force reference length. With
 * A = pi r_c^2 (r_c = min(r_i, r_j); area.h with alpha = 1):
 *
 *   K_n0 = A E0 / d,  K_s = K_n0 / (2 (1 + nu)),  C_n as Eq. 30   (damage_hardening.h)
 *
 * Compression, compressive strain eps = -u_n / d:
 *
 *   F_n = K_n0 d eps                                     eps <= eps_max
 *   F_n = K_n0 d eps_max + K_nl (d eps - d eps_max)      loading beyond
 *   K_nl = K_n0 (gamma3 + gamma1 exp(gamma2 (eps - eps_max))), at most K_n0
 *
 * with unloading and reloading below the historical maximum at K_n0
 * (damage_hardening.h). Defaults gamma1 = 0.2, gamma2 = 16, gamma3 = 0.275,
 * eps_max = 0.002 (001 Table 5; Kratos' DEM_ExponentialHC hard-codes
 * them). Once K_nl reaches K_n0 the force is back on the line K_n0 d eps.
 *
 * Tension as in the local model of Oñate et al. 2015: strength
 * sigma_t A (001 Eq. 64), linear softening with delta_n (000 Eq. 46-49a).
 *
 * Shear: modified Mohr-Coulomb (001 Fig. 22, Eq. 65-66; shear.h) on an
 * elastic shear displacement t, F_s = K_s t: a bond holds up to
 * c A + F_n tan(phi_i), F_n compressive positive, and ruptures beyond it;
 * broken bonds (in either mode) are purely frictional, F_n tan(phi_c).
 *
 * History as in damage_hardening.h but for h[1]: h[0] d_n, h[1] C_n, the
 * bond's constant, kept so that a step need not compute it (init, and
 * restore after a checkpoint: those written before hold d_s there, 0 or 1,
 * which the state also says), h[2] historical maximum compressive strain.
 * d_s is 1 once broken in shear, else 0.
 */
#include <stdlib.h>

#include "solve/kinematics.h"
#include "solve/laws/area.h"
#include "solve/laws/damage_hardening.h"
#include "solve/laws/shear.h"

typedef struct {
	dh_params q;
	double range;        /* gamma, interaction range */
	double cohesion;     /* Pa */
	double tan_i, tan_c; /* bonded and contact friction */
	double g1, g2, g3;   /* gamma1..3 */
	double eps_max;      /* elastic limit strain */
	double ks_over_kn;   /* Eq. 36 */
} exp_params;

static const double DEG = DEM_PI / 180;

static law_params *exp_parse(cfg *m)
{
	exp_params *p = calloc(1, sizeof *p);
	double phi_i, phi_c;
	if (!p || dh_parse(m, &p->q) || cfg_number(m, "interaction_range", &p->range, "", 1, 2) ||
	    cfg_number(m, "cohesion", &p->cohesion, "Pa", 0, INFINITY) ||
	    cfg_number(m, "friction_angle_deg", &phi_i, "deg", 0, 89) ||
	    cfg_number(m, "contact_friction_angle_deg", &phi_c, "deg", 0, 89) ||
	    cfg_number_or(m, "gamma1", &p->g1, 0.2, "", 0, INFINITY) ||
	    cfg_number_or(m, "gamma2", &p->g2, 16, "", 0, INFINITY) ||
	    cfg_number_or(m, "gamma3", &p->g3, 0.275, "", 0, INFINITY) ||
	    cfg_number_or(m, "eps_max", &p->eps_max, 0.002, "", 0, 1)) {
		free(p);
		return NULL;
	}
	p->tan_i = tan(phi_i * DEG);
	p->tan_c = tan(phi_c * DEG);
	p->ks_over_kn = 1 / (2 * (1 + p->q.nu));
	return (law_params *)p;
}

static void exp_free(law_params *p) { free(p); }

static law_params *exp_copy(const law_params *p) { return law_params_dup(p, sizeof(exp_params)); }

static double exp_range(const law_params *lp) { return ((const exp_params *)lp)->range; }

static void exp_setup(law_params *p, const law_packing *pk) { (void)p, (void)pk; }

/* Compressive stress at compressive strain c on the loading curve, and the
 * permanent strain left on unloading from it. */
static double exp_curve(const void *law, double c, double *cp)
{
	const exp_params *p = law;
	if (c <= p->eps_max) {
		*cp = 0;
		return p->q.E0 * c;
	}
	double r = law_min(1, p->g3 + p->g1 * exp(p->g2 * (c - p->eps_max)));
	double s = p->q.E0 * p->eps_max + r * p->q.E0 * (c - p->eps_max);
	*cp = c - s / p->q.E0;
	return s;
}

/* The bond's C_n (Eq. 30), with k_n as exp_force computes it, kept in h[1]. */
static void exp_restore(const law_params *lp, const law_pair *pair, bond *b)
{
	const exp_params *p = (const exp_params *)lp;
	double A = area_of(1, pair), kn = A * p->q.E0 * (1 / pair->d0);
	b->h[1] = dh_cn(&p->q, pair, A, kn);
}

/* A new bond: intact, at rest, its C_n kept. */
static void exp_init(const law_params *lp, const law_pair *pair, bond *b)
{
	shear_new_bond(lp, pair, b);
	exp_restore(lp, pair, b);
}

static void exp_constants(const law_params *lp, const law_pair *pair, law_const *out)
{
	const exp_params *p = (const exp_params *)lp;
	out->area = area_of(1, pair);
	out->kn = out->area * p->q.E0 / pair->d0;
	out->ks = out->kn * p->ks_over_kn;
	out->cn = dh_cn(&p->q, pair, out->area, out->kn);
	out->rc = area_rc(pair);
}

static inline void exp_force(const law_params *lp, const law_pair *pair, bond *b, const law_kin *k,
                             law_out *out)
{
	const exp_params *p = (const exp_params *)lp;
	double inv_d = 1 / pair->d0, A = area_of(1, pair), kn = A * p->q.E0 * inv_d;
	double ks = kn * p->ks_over_kn;
	int intact = b->state < BOND_BROKEN_TENSION, broke = 0;
	double open, w = 0, dn = b->h[0];
	out->failed = 0;
	double fn =
	    A * dh_normal(&p->q, exp_curve, p, k->un * inv_d, b->h, !intact, &open, &broke, &w);
	out->e_damage += A * pair->d0 * w;
	if (broke) { /* the shear spring goes with the bond */
		out->fn_failed = A * p->q.E0 * open * dh_secant(dn, p->q.delta_n);
		out->fs_failed = ks * v3_norm(b->t);
		out->e_damage += 0.5 * ks * v3_dot(b->t, b->t);
		shear_break(b, out, BOND_BROKEN_TENSION, CRACK_TENSION);
	} else if (shear_mohr_coulomb(b->t, k->dus, ks, -fn, p->cohesion * A, p->tan_i, p->tan_c,
	                              intact, out)) {
		b->state = BOND_BROKEN_SHEAR;
		out->failed = CRACK_SHEAR;
		out->fn_failed = fn;
		if (fn > 0) { /* the tension spring goes with the bond */
			out->e_damage += 0.5 * fn * fn / (kn * dh_secant(b->h[0], p->q.delta_n));
			fn = 0;
		}
	} else if (intact)
		b->state = b->h[0] > 0 ? BOND_DAMAGED : BOND_INTACT;
	v3_scale(out->fs, b->t, ks);
	out->fn_viscous = 0;
	if (b->state < BOND_BROKEN_TENSION || fn < 0)
		out->fn_viscous = b->h[1] * k->vn;
	out->fn = fn + out->fn_viscous;
}

LAW_BATCH(exp, exp_force)

/* force_pairs: the lanes of bonds that stay on their elastic branches (no
 * damage growing, no plastic flow, no failure: the first part of the
 * loading curve, strain below eps_max now and at the historical maximum, a
 * tension below the limit strain, a shear force within the Mohr-Coulomb
 * limit) from the batch's lanes (law_pairs_load) to the forces in one
 * vectorised pass (kinematics.h), with exp_force's expressions, so the
 * same to the bit; every other lane goes through exp_force. With `broken`,
 * also the lanes of broken bonds on that part of the curve: no tension,
 * Coulomb friction with the contact angle (shear_slip, its work in
 * o->e_friction), the viscous force only in compression; without it (no
 * broken bond in the batch) none of that is computed. */
static inline __attribute__((always_inline)) int exp_pairs_body(LAW_PAIRS_PARAMS,
                                                                law_fused *restrict o, int broken)
{
	const exp_params *p = (const exp_params *)lp;
	o->history = 1;
	o->friction = broken;
	int count = 0;
	for (int q = 0; q < n; q++) {
		pair_motion k = law_lanes_motion(L, q, dt);
		double h[LAW_NHIST] = {L->h[0][q], L->h[1][q], L->h[2][q]};
		int32_t gone = broken & (L->state[q] >= BOND_BROKEN_TENSION);
		/* normal: dh_normal on the curve's first part */
		double inv_d = 1 / L->d0[q], A = area_of_radii(1, L->ri[q], L->rj[q]),
		       kn = A * p->q.E0 * inv_d;
		double ks = kn * p->ks_over_kn;
		double e;
		int32_t elastic;
		double fn = A * dh_normal_first(&p->q, p->eps_max, -(k.un * inv_d), h[0], gone,
		                                &h[2], &e, &elastic, 0);
		/* shear: shear_mohr_coulomb within its limit */
		double t[3] = {k.t[0] + k.dus[0], k.t[1] + k.dus[1], k.t[2] + k.dus[2]};
		double limit = p->cohesion * A + -fn * p->tan_i,
		       tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2], f = 0;
		int32_t within = law_shear_within(broken, ks, tt, limit, &f);
		int32_t ok = elastic & (gone | ((L->state[q] < BOND_BROKEN_TENSION) & within));
		double fv = h[1] * k.vn;
		int32_t st = h[0] > 0 ? BOND_DAMAGED : BOND_INTACT;
		if (broken) { /* shear_slip with the limit F_nc tan(phi_c) */
			o->e_friction[q] = shear_slip_lane(t, k.t, ks, f, -fn * p->tan_c, gone);
			fv = law_sel(gone & !(fn < 0), 0, fv);
			st = gone ? L->state[q] : st;
		}
		double fs[3] = {t[0] * ks, t[1] * ks, t[2] * ks};
		law_fused_put(o, q, ok, &k, fn + fv, fv, fs, dt, t, h, st);
		count += ok;
	}
	return count;
}
LAW_PAIRS_BROKEN(exp_pairs, exp_pairs_body)

static double exp_energy(const law_params *lp, const law_pair *pair, const bond *b, double un)
{
	const exp_params *p = (const exp_params *)lp;
	int intact = b->state < BOND_BROKEN_TENSION;
	double A = area_of(1, pair), ks = A * p->q.E0 / pair->d0 * p->ks_over_kn;
	return dh_normal_energy(&p->q, exp_curve, p, A, pair->d0, b->h, !intact, un) +
	       0.5 * ks * v3_dot(b->t, b->t);
}

static void exp_damage(const law_params *p, const bond *b, double *dn, double *ds)
{
	(void)p;
	*dn = b->h[0];
	*ds = b->state == BOND_BROKEN_SHEAR;
}

const law law_exponential = {
    .name = "exponential",
    .summary = "Tran, Donzé & Marin 2011 high-confinement law: exponential compaction "
               "stiffening, modified Mohr-Coulomb",
    .parse = exp_parse,
    .free = exp_free,
    .copy = exp_copy,
    .bond_range = exp_range,
    .setup = exp_setup,
    .constants = exp_constants,
    .init = exp_init,
    .restore = exp_restore,
    .force = exp_force,
    .force_batch = exp_batch,
    .force_pairs = exp_pairs,
    .energy = exp_energy,
    .damage = exp_damage,
    .h_dropped = 3,
};
