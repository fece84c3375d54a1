/* "onate": the local constitutive model of Oñate et al. 2015 (seeds/000;
 * equation numbers are the paper's).
 *
 * Bonds form between spheres with d <= (1 + beta)(r_i + r_j) (Eq. 16),
 * beta = 0.10 (Sect. 4.2); d, the distance at bonding, is the zero-force
 * reference length. With r_c = min(r_i, r_j):
 *
 *   A   = alpha pi r_c^2,  alpha = 40 P / N_c or given   (Eq. 21-22, area.h)
 *   K_n = A E0 / d,  K_s = K_n / (2 (1 + nu)),  C_n (Eq. 30)   (damage_hardening.h)
 *   F_n = K_n u_n + C_n du_n/dt                              (Eq. 29)
 *
 * Tension: elasto-damage with linear softening (Eq. 41-42, 46-49a),
 * strength sigma_t A, u_n^l = sigma_t A / K_n, u_n^f = (1 + delta_n) u_n^l;
 * at d_n = 1 the bond breaks in tension (damage_hardening.h).
 *
 * Shear, on the accumulated shear displacement u_s = t (Eq. 34-38), same
 * softening (Eq. 46, 49b) with the strength
 *
 *   F_s = tau^f A + mu1 |F_nc|                 uncoupled criterion (Eq. 42, Fig. 7a)
 *   F_s = tau^f A (1 - e / u_n^l) in tension   coupled criterion (Fig. 7b), option
 *
 * so u_s^l = F_s / K_s moves with the normal force; F_nc is the elastic
 * compressive force. In the coupled criterion the shear strength falls
 * linearly with the opening e (from the permanent indentation) to zero at
 * the tensile limit: in elastic states F_nt / (sigma_t A) + F_s / (tau^f A)
 * = 1, the line of Fig. 7b from (sigma_t A, 0) to (0, tau^f A); compression
 * is as in the uncoupled criterion. At d_s = 1 the bond breaks in shear.
 *
 * Compression: elasto-plastic (Eq. 52-53, Fig. 10). On the contact stress
 * sigma = F_nc / A and strain u_n / d the loading curve has slope E0 up to
 * LCS1, then E0/YRC1 up to LCS2, E0/YRC2 up to LCS3, E0/YRC3 beyond;
 * unloading and reloading below the historical maximum go with K_n0 and
 * leave a permanent indentation (damage_hardening.h).
 *
 * After failure in either mode: no tension, compression as before (the
 * reference length is kept, as Kratos' DEM_Dempack_CL keeps the initial
 * distance), and Coulomb friction |F_s| <= mu2 |F_nc| (Eq. 45) on an
 * elastic shear displacement that starts from zero at the failure, where
 * the softening branch ends at zero force.
 *
 * History: h[0] d_n, h[1] d_s, h[2] historical maximum compressive strain,
 * (damage_hardening.h); t the accumulated shear displacement u_s while
 * bonded, the elastic shear displacement of the frictional contact after.
 * A bond is BOND_DAMAGED once d_n or d_s > 0. The bond's constant k is its
 * C_n (Eq. 30), so a step does not take its square root and divisions.
 */
#include <stdio.h>
#include <stdlib.h>

#include "solve/kinematics.h"
#include "solve/laws/area.h"
#include "solve/laws/damage_hardening.h"
#include "solve/laws/shear.h"

typedef struct {
	dh_params q;
	area_keys area;    /* alpha (Eq. 21-22), beta (Eq. 16) */
	double tau;        /* Pa, shear strength tau^f */
	double mu1, mu2;   /* Eq. 42, 45 */
	double delta_s;    /* Eq. 47 */
	int coupled;       /* Fig. 7b */
	double lcs[3];     /* Pa, limit compressive stresses */
	double slope[3];   /* Pa, E0 / YRC_k */
	double eps[3];     /* compressive strain at LCS_k on the curve */
	double ks_over_kn; /* 1 / (2 (1 + nu)), Eq. 36 */
} onate_params;

static law_params *onate_parse(cfg *m)
{
	onate_params *p = calloc(1, sizeof *p);
	static const char *const criteria[] = {"uncoupled", "coupled", NULL};
	double yrc[3];
	if (!p || dh_parse(m, &p->q) ||
	    cfg_number(m, "shear_strength", &p->tau, "Pa", 0, INFINITY) ||
	    cfg_number(m, "mu1", &p->mu1, "", 0, INFINITY) ||
	    cfg_number(m, "mu2", &p->mu2, "", 0, INFINITY) ||
	    cfg_number(m, "delta_s", &p->delta_s, "", 0, INFINITY) ||
	    cfg_choice_or(m, "criterion", &p->coupled, criteria, 0) || area_parse(m, &p->area))
		goto fail;
	for (int k = 0; k < 3; k++) {
		char lcs[16], prev[16];
		snprintf(lcs, sizeof lcs, "LCS%d", k + 1);
		snprintf(prev, sizeof prev, "LCS%d", k);
		if (cfg_number(m, lcs, &p->lcs[k], "Pa", CFG_POS, INFINITY))
			goto fail;
		if (k && p->lcs[k] <= p->lcs[k - 1]) {
			cfg_error(m, lcs,
			          "value %.17g: expected a number greater than %s = %.17g (Pa)",
			          p->lcs[k], prev, p->lcs[k - 1]);
			goto fail;
		}
	}
	/* The YRC after the LCS so messages come in the order of the table. */
	for (int k = 0; k < 3; k++) {
		char yrck[16];
		snprintf(yrck, sizeof yrck, "YRC%d", k + 1);
		if (cfg_number(m, yrck, &yrc[k], "", 1, INFINITY))
			goto fail;
		p->slope[k] = p->q.E0 / yrc[k];
	}
	p->eps[0] = p->lcs[0] / p->q.E0;
	for (int k = 1; k < 3; k++)
		p->eps[k] = p->eps[k - 1] + (p->lcs[k] - p->lcs[k - 1]) / p->slope[k - 1];
	p->ks_over_kn = 1 / (2 * (1 + p->q.nu));
	return (law_params *)p;
fail:
	free(p);
	return NULL;
}

static void onate_free(law_params *p) { free(p); }

static law_params *onate_copy(const law_params *p)
{
	return law_params_dup(p, sizeof(onate_params));
}

static double onate_range(const law_params *lp)
{
	return area_range(&((const onate_params *)lp)->area);
}

static void onate_setup(law_params *lp, const law_packing *pk)
{
	area_setup(&((onate_params *)lp)->area, pk);
}

/* Fig. 10: compressive stress at compressive strain c, and the permanent
 * strain the bond keeps when unloaded from there (Eq. 52b). */
static double onate_curve(const void *law, double c, double *cp)
{
	const onate_params *p = law;
	int k = (c > p->eps[0]) + (c > p->eps[1]) + (c > p->eps[2]);
	if (k == 0) {
		*cp = 0;
		return p->q.E0 * c;
	}
	double s = p->lcs[k - 1] + p->slope[k - 1] * (c - p->eps[k - 1]);
	*cp = c - s / p->q.E0;
	return s;
}

/* onate_curve with law_sel in place of its branches, for the vector loop
 * of force_pairs: the same expressions, so the same values. */
static inline double onate_curve_sel(const onate_params *restrict p, double c, double *cp)
{
	int64_t k1 = c > p->eps[0], k2 = c > p->eps[1], k3 = c > p->eps[2];
	double lcs = law_sel(k3, p->lcs[2], law_sel(k2, p->lcs[1], p->lcs[0]));
	double slope = law_sel(k3, p->slope[2], law_sel(k2, p->slope[1], p->slope[0]));
	double eps = law_sel(k3, p->eps[2], law_sel(k2, p->eps[1], p->eps[0]));
	double s = lcs + slope * (c - eps);
	*cp = law_sel(k1, c - s / p->q.E0, 0);
	return law_sel(k1, s, p->q.E0 * c);
}

static void onate_constants(const law_params *lp, const law_pair *pair, law_const *out)
{
	const onate_params *p = (const onate_params *)lp;
	out->area = area_of(p->area.alpha, pair);
	out->kn = out->area * p->q.E0 / pair->d0;
	out->ks = out->kn * p->ks_over_kn;
	out->cn = dh_cn(&p->q, pair, out->area, out->kn);
	out->rc = area_rc(pair);
}

/* law.init and law.restore: the bond's C_n (Eq. 30) into k, with the
 * expressions onate_force used to compute it in every step (so the same
 * bits). */
static void onate_restore(const law_params *lp, const law_pair *pair, bond *b)
{
	const onate_params *p = (const onate_params *)lp;
	double A = area_of(p->area.alpha, pair), kn = A * p->q.E0 * (1 / pair->d0);
	b->k = dh_cn(&p->q, pair, A, kn);
}

static void onate_init(const law_params *lp, const law_pair *pair, bond *b)
{
	shear_new_bond(lp, pair, b);
	onate_restore(lp, pair, b);
}

static inline void onate_force(const law_params *lp, const law_pair *pair, bond *b,
                               const law_kin *k, law_out *out)
{
	const onate_params *p = (const onate_params *)lp;
	double inv_d = 1 / pair->d0, A = area_of(p->area.alpha, pair), kn = A * p->q.E0 * inv_d;
	double ks = kn * p->ks_over_kn;
	int intact = b->state < BOND_BROKEN_TENSION, broke = 0;
	double open, w = 0, dn = b->h[0];
	out->failed = 0;
	double fn =
	    A * dh_normal(&p->q, onate_curve, p, k->un * inv_d, b->h, !intact, &open, &broke, &w);
	out->e_damage += A * pair->d0 * w;
	double fnc = fn < 0 ? -fn : 0;
	if (broke) { /* the shear spring goes with the bond */
		double ss = dh_secant(b->h[1], p->delta_s);
		out->fn_failed = A * p->q.E0 * open * dh_secant(dn, p->q.delta_n);
		out->fs_failed = ks * ss * v3_norm(b->t);
		out->e_damage += 0.5 * ks * ss * v3_dot(b->t, b->t);
		shear_break(b, out, BOND_BROKEN_TENSION, CRACK_TENSION);
	} else if (intact) {
		v3_add(b->t, b->t, k->dus);
		double strength = p->tau * A + p->mu1 * fnc;
		if (p->coupled && open > 0)
			strength = p->tau * A * (1 - law_min(1, open / p->q.eps_t));
		double us = v3_norm(b->t), d = b->h[1], ds = d;
		if (ks * us > strength) { /* beyond the elastic limit */
			double dnew =
			    law_min(1, law_max(d, dh_damage_at(us, strength / ks, p->delta_s)));
			/* Work of the shear softening: 1/2 F_s u_s^f per unit of damage. */
			out->e_damage +=
			    0.5 * strength * strength / ks * (1 + p->delta_s) * (dnew - d);
			d = b->h[1] = dnew;
		}
		if (d >= 1) {
			out->fn_failed = fn;
			out->fs_failed = ks * dh_secant(ds, p->delta_s) * us;
			shear_break(b, out, BOND_BROKEN_SHEAR, CRACK_SHEAR);
			if (fn > 0) { /* the tension spring goes with the bond */
				out->e_damage +=
				    0.5 * fn * fn / (kn * dh_secant(b->h[0], p->q.delta_n));
				fn = 0;
			}
		} else
			b->state = b->h[0] > 0 || d > 0 ? BOND_DAMAGED : BOND_INTACT;
	} else {
		shear_slip(b->t, k->dus, ks, p->mu2 * fnc, out);
	}
	double ss = b->state < BOND_BROKEN_TENSION ? dh_secant(b->h[1], p->delta_s) : 1;
	v3_scale(out->fs, b->t, ks * ss);
	out->fn_viscous = 0;
	if (b->state < BOND_BROKEN_TENSION || fnc > 0)
		out->fn_viscous = b->k * k->vn;
	out->fn = fn + out->fn_viscous;
}

/* force_batch: the lanes of bonds that stay on their elastic branches (no
 * damage growing, no plastic flow, no failure) all together, with
 * onate_force's expressions (so the same to the bit) and no branches, which
 * the compiler turns into vector instructions; then every other lane by
 * onate_force itself. On the elastic part of the loading curve (strain
 * below LCS1 / E0 now and at the historical maximum) the permanent
 * indentation is 0, and in tension below the limit strain the tension
 * damage stays as it is (dh_normal). */
DEM_VECTOR_CLONES __attribute__((flatten)) static void onate_batch(const law_params *lp,
                                                                   law_batch *B)
{
	const onate_params *p = (const onate_params *)lp;
	int32_t elastic[LAW_LANES];
	double fnq[LAW_LANES], area[LAW_LANES], open[LAW_LANES];
	int n = B->n;
	for (int q = 0; q < n; q++) { /* normal: dh_normal on the curve's first segment */
		double A = area_of_radii(p->area.alpha, B->ri[q], B->rj[q]), inv_d = 1 / B->d0[q];
		double c = -(B->un[q] * inv_d), h2 = B->h[2][q];
		double sigma = dh_normal_first(&p->q, p->eps[0], c, B->h[0][q], 0, &h2, &open[q],
		                               &elastic[q], 0);
		fnq[q] = A * sigma;
		area[q] = A;
		B->h[2][q] = h2;
	}
	for (int q = 0; q < n; q++) { /* shear, viscous force */
		double A = area[q], kn = A * p->q.E0 * (1 / B->d0[q]), ks = kn * p->ks_over_kn;
		double fn = fnq[q], fnc = fn < 0 ? -fn : 0, e = open[q];
		double t0 = B->t[0][q] + B->dus[0][q], t1 = B->t[1][q] + B->dus[1][q],
		       t2 = B->t[2][q] + B->dus[2][q];
		double strength = p->tau * A + p->mu1 * fnc;
		double coupled = p->tau * A * (1 - law_min(1, e / p->q.eps_t));
		strength = ((p->coupled != 0) & (e > 0)) ? coupled : strength;
		double us = sqrt(t0 * t0 + t1 * t1 + t2 * t2);
		double h1 = B->h[1][q];
		int32_t ok =
		    elastic[q] & (B->state[q] < BOND_BROKEN_TENSION) & !(ks * us > strength);
		elastic[q] = ok;
		double ss = ks * dh_secant(h1, p->delta_s);
		B->fs[0][q] = t0 * ss;
		B->fs[1][q] = t1 * ss;
		B->fs[2][q] = t2 * ss;
		double fv = B->k[q] * B->vn[q];
		B->fn_viscous[q] = fv;
		B->fn[q] = fn + fv;
		B->t[0][q] = ok ? t0 : B->t[0][q];
		B->t[1][q] = ok ? t1 : B->t[1][q];
		B->t[2][q] = ok ? t2 : B->t[2][q];
	}
	for (int q = 0; q < n; q++)
		if (elastic[q])
			B->state[q] = B->h[0][q] > 0 || B->h[1][q] > 0 ? BOND_DAMAGED : BOND_INTACT;
	LAW_BATCH_REST(onate_force, lp, B, elastic);
}

/* force_pairs: onate_batch's vector loops as one, from the batch's lanes
 * (law_pairs_load) to the forces in one pass (kinematics.h). With `curve`,
 * the normal force on every part of the loading curve (dh_normal_curve):
 * loading past the largest compression so far with its plastic work
 * (o->e_damage), unloading and reloading about the permanent indentation;
 * else on its first part only (dh_normal_first), which costs less. With
 * `broken`, also the lanes of broken bonds, as onate_force computes them:
 * the normal force without tension, Coulomb friction (shear_slip) with its
 * work (o->e_friction), the viscous force only in compression; without it
 * (no broken bond in the batch) none of that is computed. With `plain` (no
 * bond of the batch damaged, the uncoupled criterion) the secants are 1
 * and the coupled strength is not computed: three divisions fewer. Without
 * `broken` the shear test is law_surely_within's, without a square root. */
static inline __attribute__((always_inline)) int
onate_pairs_body(LAW_PAIRS_PARAMS, law_fused *restrict o, int curve, int broken, int plain)
{
	const onate_params *p = (const onate_params *)lp;
	o->history = 1;
	o->damage = curve;
	o->friction = broken;
	int count = 0;
	for (int q = 0; q < n; q++) {
		pair_motion k = law_lanes_motion(L, q, dt);
		double h[LAW_NHIST] = {L->h[0][q], L->h[1][q], L->h[2][q]}, d0 = L->d0[q];
		int32_t gone = broken & (L->state[q] >= BOND_BROKEN_TENSION);
		/* normal: dh_normal */
		double A = area_of_radii(p->area.alpha, L->ri[q], L->rj[q]), inv_d = 1 / d0;
		double c = -(k.un * inv_d), e, fn;
		int32_t elastic;
		if (curve) {
			double cp, cp0, w;
			double s = onate_curve_sel(p, c, &cp), s0 = onate_curve_sel(p, h[2], &cp0);
			fn = A * dh_normal_curve(&p->q, c, s, cp, s0, cp0, h[0], gone, &h[2], &e,
			                         &w, &elastic);
			o->e_damage[q] = 0.0 + A * d0 * w;
		} else {
			fn = A * dh_normal_first(&p->q, p->eps[0], c, h[0], gone, &h[2], &e,
			                         &elastic, plain);
		}
		/* shear, viscous force */
		double kn = A * p->q.E0 * (1 / d0), ks = kn * p->ks_over_kn;
		double fnc = fn < 0 ? -fn : 0;
		double t[3] = {k.t[0] + k.dus[0], k.t[1] + k.dus[1], k.t[2] + k.dus[2]};
		double strength = p->tau * A + p->mu1 * fnc;
		if (!plain) {
			double coupled = p->tau * A * (1 - law_min(1, e / p->q.eps_t));
			strength = ((p->coupled != 0) & (e > 0)) ? coupled : strength;
		}
		double tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2], us = 0;
		int32_t sheared; /* ks u_s > strength, or not sure it is not */
		if (broken) {
			us = sqrt(tt);
			sheared = ks * us > strength;
		} else
			sheared = !law_surely_within(ks * ks * tt, strength);
		int32_t ok = elastic & (gone | ((L->state[q] < BOND_BROKEN_TENSION) & !sheared));
		double ss = plain ? ks : ks * dh_secant(h[1], p->delta_s);
		double fv = L->k[q] * k.vn;
		int32_t st = ((h[0] > 0) | (h[1] > 0)) ? BOND_DAMAGED : BOND_INTACT;
		if (broken) { /* shear_slip; onate_force's ss = 1 */
			o->e_friction[q] = shear_slip_lane(t, k.t, ks, ks * us, p->mu2 * fnc, gone);
			ss = law_sel(gone, ks, ss);
			fv = law_sel(gone & !(fnc > 0), 0, fv);
			st = gone ? L->state[q] : st;
		}
		double fs[3] = {t[0] * ss, t[1] * ss, t[2] * ss};
		law_fused_put(o, q, ok, &k, fn + fv, fv, fs, dt, t, h, st);
		count += ok;
	}
	return count;
}

LAW_PAIRS_VARIANT(onate_pairs_plain, onate_pairs_body, 0, 0, 1)
LAW_PAIRS_VARIANT(onate_pairs_first, onate_pairs_body, 0, 0, 0)
LAW_PAIRS_VARIANT(onate_pairs_curve, onate_pairs_body, 1, 0, 0)
LAW_PAIRS_VARIANT(onate_pairs_first_broken, onate_pairs_body, 0, 1, 0)
LAW_PAIRS_VARIANT(onate_pairs_curve_broken, onate_pairs_body, 1, 1, 0)

/* The whole curve where a bond of the batch has been compressed past its
 * first part (LCS1); else the first part, whose lanes that now load past
 * it go the staged way, this once; `plain` where no bond of the batch is
 * damaged either. The broken bonds' branch where the batch has one. In
 * the vector versions (clones.h), so that the scans of the lanes are
 * vectorised: GCC leaves the scan of doubles scalar for any x86-64. */
DEM_VECTOR_CLONES static int onate_pairs(LAW_PAIRS_PARAMS, law_fused *restrict o)
{
	const onate_params *p = (const onate_params *)lp;
	int hardened = 0, damaged = 0;
	for (int q = 0; q < n; q++) {
		hardened |= L->h[2][q] > p->eps[0];
		damaged |= (L->h[0][q] != 0) | (L->h[1][q] != 0);
	}
	if (law_lanes_broken(L, n))
		return hardened ? onate_pairs_curve_broken(lp, L, n, dt, o)
		                : onate_pairs_first_broken(lp, L, n, dt, o);
	if (hardened)
		return onate_pairs_curve(lp, L, n, dt, o);
	return damaged || p->coupled ? onate_pairs_first(lp, L, n, dt, o)
	                             : onate_pairs_plain(lp, L, n, dt, o);
}

static double onate_energy(const law_params *lp, const law_pair *pair, const bond *b, double un)
{
	const onate_params *p = (const onate_params *)lp;
	int intact = b->state < BOND_BROKEN_TENSION;
	double A = area_of(p->area.alpha, pair), kn = A * p->q.E0 / pair->d0,
	       ks = kn * p->ks_over_kn;
	double ss = intact ? dh_secant(b->h[1], p->delta_s) : 1;
	return dh_normal_energy(&p->q, onate_curve, p, A, pair->d0, b->h, !intact, un) +
	       0.5 * ks * ss * v3_dot(b->t, b->t);
}

const law law_onate = {
    .name = "onate",
    .summary = "Oñate et al. 2015 local model: elasto-damage tension and shear, "
               "elasto-plastic compression",
    .parse = onate_parse,
    .free = onate_free,
    .copy = onate_copy,
    .bond_range = onate_range,
    .setup = onate_setup,
    .constants = onate_constants,
    .init = onate_init,
    .restore = onate_restore,
    .force = onate_force,
    .force_batch = onate_batch,
    .force_pairs = onate_pairs,
    .energy = onate_energy,
    .damage = dh_damage,
    .keeps_k = 1,
    .h_dropped = 3,
};
