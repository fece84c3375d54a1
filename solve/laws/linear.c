/* "linear": a linear elastic–brittle bond that, once broken, is a
 * Cundall–Strack frictional contact (MODELS.md §3).
 *
 * Bonds form between spheres with d <= (1 + β)(r_i + r_j) (Eq. 16), β default
 * 0.10. Local elastic constants (Oñate et al. 2015; Ā and α in area.h):
 *   Ā   = α π r_c²,  r_c = min(r_i, r_j)                      (Eq. 21)
 *   α   = 40 P / N_c from the packing unless given            (Eq. 22)
 *   K_n = Ā E / d0                                            (Eq. 30)
 *   K_s = K_n / (2 (1 + ν))                                   (Eq. 36)
 * or constant K_n, K_s for every bond when "kn" and "ks" are given.
 * Normal viscous damping C_n = 2 ξ sqrt(m_ij K_n), ξ ("xi") a fraction of
 * the critical damping of the pair (0 by default).
 *
 * Intact bond: f_n = K_n u_n + C_n u̇_n (tension positive), F_s = K_s u_s with
 * u_s the accumulated shear displacement (kept in t). Brittle failure:
 *   tension  K_n u_n > σ_t Ā                                  (Eq. 41-42)
 *   shear    |K_s u_s| > τ Ā + μ1 max(-K_n u_n, 0)            (Eq. 41-42)
 * ("tensile_strength" σ_t, "shear_strength" τ, "mu1", "mu2" as in onate)
 * (tension checked first). The stored energy is released as fracture
 * energy; from then on the bond is a Cundall–Strack contact (cundall.h) about
 * its reference length d0 with friction μ2, its shear history starting from
 * the elastic shear force at failure (clipped by the Coulomb limit).
 *
 * History: t = shear displacement (intact) or shear force (broken);
 * h[0..2] = K_n, K_s, C_n. */
#include <math.h>
#include <stdlib.h>

#include "lib/cfg.h"
#include "lib/err.h"
#include "lib/states.h"
#include "lib/vec3.h"
#include "solve/kinematics.h"
#include "solve/law.h"
#include "solve/laws/area.h"
#include "solve/laws/cundall.h"

struct law_params {
	double E, nu;   /* Pa, - (local definitions) */
	double kn, ks;  /* N/m, constant stiffnesses (0 when local) */
	area_keys area; /* alpha (Eq. 21-22), beta (Eq. 16) */
	double sigma_t; /* Pa, tensile strength */
	double tau;     /* Pa, shear strength (cohesion) */
	double mu1;     /* friction in the bond shear strength */
	double mu;      /* friction after failure */
	double xi;      /* fraction of critical damping */
};

/* "xi" defaults to 0, not to the 0.9 of onate and exponential
 * (damage_hardening.c): here it damps a Cundall–Strack contact, a fraction
 * of the critical damping of the pair, C_n = 2 xi sqrt(m_ij K_n), not Oñate's
 * xi / r_c per unit length (Eq. 27). MODELS.md §3 makes that damping
 * optional, and the key began as "damping", undamped by default like the
 * engine's non-bonded contacts ("contact": {"damping"}, material.c), the
 * same Cundall–Strack contact; it took the onate law's name, not its value. */
static law_params *linear_parse(cfg *c)
{
	law_params *p = xcalloc(1, sizeof *p);
	int rc = 0;
	if (cfg_has(c, "kn") || cfg_has(c, "ks")) {
		rc = cfg_number(c, "kn", &p->kn, "N/m", CFG_POS, INFINITY) ||
		     cfg_number(c, "ks", &p->ks, "N/m", CFG_POS, INFINITY);
	} else {
		rc = cfg_number(c, "E", &p->E, "Pa", CFG_POS, INFINITY) ||
		     cfg_number(c, "nu", &p->nu, "", -0.99, 0.5);
	}
	rc = rc || area_parse(c, &p->area) ||
	     cfg_number(c, "tensile_strength", &p->sigma_t, "Pa", 0, INFINITY) ||
	     cfg_number(c, "shear_strength", &p->tau, "Pa", 0, INFINITY) ||
	     cfg_number_or(c, "mu1", &p->mu1, 0, "", 0, INFINITY) ||
	     cfg_number_or(c, "mu2", &p->mu, 0.5, "", 0, INFINITY) ||
	     cfg_number_or(c, "xi", &p->xi, 0, "fraction of critical", 0, 1);
	if (rc) {
		free(p);
		return NULL;
	}
	return p;
}

static void linear_free(law_params *p) { free(p); }

static law_params *linear_copy(const law_params *p) { return law_params_dup(p, sizeof *p); }

static double linear_range(const law_params *p) { return area_range(&p->area); }

static void linear_setup(law_params *p, const law_packing *pk) { area_setup(&p->area, pk); }

static void linear_constants(const law_params *p, const law_pair *q, law_const *out)
{
	double area = area_of(p->area.alpha, q);
	double kn = p->kn > 0 ? p->kn : area * p->E / q->d0;
	double ks = p->kn > 0 ? p->ks : kn / (2 * (1 + p->nu));
	double mij = q->mi * q->mj / (q->mi + q->mj);
	*out = (law_const){
	    .kn = kn, .ks = ks, .cn = 2 * p->xi * sqrt(mij * kn), .area = area, .rc = area_rc(q)};
}

static void linear_init(const law_params *p, const law_pair *q, bond *b)
{
	law_const c;
	linear_constants(p, q, &c);
	for (int k = 0; k < 3; k++)
		b->t[k] = 0;
	b->h[0] = c.kn;
	b->h[1] = c.ks;
	b->h[2] = c.cn;
	b->state = BOND_INTACT;
}

static inline double intact_energy(const bond *b, double un)
{
	double tt = b->t[0] * b->t[0] + b->t[1] * b->t[1] + b->t[2] * b->t[2];
	return 0.5 * b->h[0] * un * un + 0.5 * b->h[1] * tt;
}

static inline void linear_force_one(const law_params *p, const law_pair *q, bond *b,
                                    const law_kin *k, law_out *out)
{
	cundall c = {.kn = b->h[0], .ks = b->h[1], .cn = b->h[2], .mu = p->mu};
	out->failed = 0;
	if (b->state >= BOND_BROKEN_TENSION) {
		cundall_force(&c, k->un, k->vn, k->dus, b->t, out);
		return;
	}
	for (int d = 0; d < 3; d++)
		b->t[d] += k->dus[d];
	double area = area_of(p->area.alpha, q);
	double fe = c.kn * k->un;
	double fs[3] = {c.ks * b->t[0], c.ks * b->t[1], c.ks * b->t[2]};
	double fs2 = fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2];
	double shear_limit = p->tau * area + p->mu1 * (fe < 0 ? -fe : 0);
	int mode = fe > p->sigma_t * area            ? CRACK_TENSION
	           : fs2 > shear_limit * shear_limit ? CRACK_SHEAR
	                                             : 0;
	if (!mode) {
		out->fn_viscous = c.cn * k->vn;
		out->fn = fe + out->fn_viscous;
		for (int d = 0; d < 3; d++)
			out->fs[d] = fs[d];
		return;
	}
	out->fn_failed = fe;
	out->fs_failed = sqrt(fs2);
	double before = intact_energy(b, k->un);
	for (int d = 0; d < 3; d++)
		b->t[d] = fs[d];
	b->state = mode == CRACK_TENSION ? BOND_BROKEN_TENSION : BOND_BROKEN_SHEAR;
	const double none[3] = {0, 0, 0};
	double friction = out->e_friction;
	cundall_force(&c, k->un, k->vn, none, b->t, out);
	/* Sliding in the failing call is part of the failure. */
	out->e_friction = friction;
	out->e_damage += before - cundall_energy(&c, k->un, b->t);
	out->failed = mode;
}

static void linear_force(const law_params *p, const law_pair *q, bond *b, const law_kin *k,
                         law_out *out)
{
	linear_force_one(p, q, b, k, out);
}

/* force_batch: the lanes of intact bonds that stay intact all together,
 * with linear_force_one's expressions (so the same to the bit) and no
 * branches, which the compiler turns into vector instructions; then every
 * other lane (failing or broken) by linear_force_one itself. */
DEM_VECTOR_CLONES __attribute__((flatten)) static void linear_batch(const law_params *p,
                                                                    law_batch *B)
{
	int32_t elastic[LAW_LANES];
	int n = B->n;
	for (int q = 0; q < n; q++) {
		double kn = B->h[0][q], ks = B->h[1][q], cn = B->h[2][q], un = B->un[q];
		double t0 = B->t[0][q] + B->dus[0][q], t1 = B->t[1][q] + B->dus[1][q],
		       t2 = B->t[2][q] + B->dus[2][q];
		double area = area_of_radii(p->area.alpha, B->ri[q], B->rj[q]);
		double fe = kn * un;
		double fs0 = ks * t0, fs1 = ks * t1, fs2 = ks * t2;
		double ff = fs0 * fs0 + fs1 * fs1 + fs2 * fs2;
		double shear_limit = p->tau * area + p->mu1 * (fe < 0 ? -fe : 0);
		int32_t ok = (B->state[q] < BOND_BROKEN_TENSION) & !(fe > p->sigma_t * area) &
		             !(ff > shear_limit * shear_limit);
		elastic[q] = ok;
		double fv = cn * B->vn[q];
		B->fn_viscous[q] = fv;
		B->fn[q] = fe + fv;
		B->fs[0][q] = fs0;
		B->fs[1][q] = fs1;
		B->fs[2][q] = fs2;
		B->t[0][q] = ok ? t0 : B->t[0][q];
		B->t[1][q] = ok ? t1 : B->t[1][q];
		B->t[2][q] = ok ? t2 : B->t[2][q];
	}
	LAW_BATCH_REST(linear_force_one, p, B, elastic);
}

/* force_pairs: linear_batch's vector loop, from the batch's lanes
 * (law_pairs_load) to the forces in one pass (kinematics.h). With
 * `broken`, also the lanes of broken bonds, as cundall_force computes
 * them (a contact in compression, Coulomb friction with its work in
 * o->e_friction); without it (no broken bond in the batch) none of that
 * is computed. */
static inline __attribute__((always_inline)) int
linear_pairs_body(LAW_PAIRS_PARAMS, law_fused *restrict o, int broken)
{
	const law_params *p = lp;
	double alpha = p->area.alpha, tau = p->tau, mu1 = p->mu1, sigma_t = p->sigma_t;
	o->history = 0;
	o->friction = broken;
	int count = 0;
	for (int q = 0; q < n; q++) {
		pair_motion k = law_lanes_motion(L, q, dt);
		double h[LAW_NHIST] = {L->h[0][q], L->h[1][q], L->h[2][q]};
		double kn = h[0], ks = h[1], cn = h[2], un = k.un;
		double t[3] = {k.t[0] + k.dus[0], k.t[1] + k.dus[1], k.t[2] + k.dus[2]};
		double area = area_of_radii(alpha, L->ri[q], L->rj[q]);
		double fe = kn * un;
		double fs[3] = {ks * t[0], ks * t[1], ks * t[2]};
		double ff = fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2];
		double shear_limit = tau * area + mu1 * (fe < 0 ? -fe : 0);
		int32_t ok = (L->state[q] < BOND_BROKEN_TENSION) & !(fe > sigma_t * area) &
		             !(ff > shear_limit * shear_limit);
		double fv = cn * k.vn, fn = fe + fv;
		if (broken) { /* cundall_force; t is the shear force */
			int32_t gone = L->state[q] >= BOND_BROKEN_TENSION;
			double touch = un < 0 ? 1.0 : 0.0;
			double fc = (fn < 0 ? fn : 0) * touch; /* fn: its fe + c_n vn */
			double lim = -p->mu * fc, tr[3];
			for (int c = 0; c < 3; c++)
				tr[c] = (k.t[c] + ks * k.dus[c]) * touch;
			double tt = sqrt(tr[0] * tr[0] + tr[1] * tr[1] + tr[2] * tr[2]);
			double slide = law_sel(tt > lim, 1.0, 0.0);
			double scale = law_sel(tt > lim, lim / tt, 1.0);
			o->e_friction[q] = law_sel(gone, 0.0 + slide * (tt - lim) * lim / ks, 0);
			for (int c = 0; c < 3; c++) {
				double tc = tr[c] * scale;
				t[c] = law_sel(gone, tc, t[c]);
				fs[c] = law_sel(gone, tc, fs[c]);
			}
			fn = law_sel(gone, fc, fn);
			fv = law_sel(gone, (fc - fe) * touch, fv);
			ok |= gone;
		}
		law_fused_put(o, q, ok, &k, fn, fv, fs, dt, t, NULL, 0);
		count += ok;
	}
	return count;
}
LAW_PAIRS_BROKEN(linear_pairs, linear_pairs_body)

static double linear_energy(const law_params *p, const law_pair *q, const bond *b, double un)
{
	(void)q;
	if (b->state < BOND_BROKEN_TENSION)
		return intact_energy(b, un);
	cundall c = {.kn = b->h[0], .ks = b->h[1], .cn = b->h[2], .mu = p->mu};
	return cundall_energy(&c, un, b->t);
}

static void linear_damage(const law_params *p, const bond *b, double *dn, double *ds)
{
	(void)p;
	double broken = b->state >= BOND_BROKEN_TENSION ? 1 : 0;
	*dn = broken;
	*ds = broken;
}

const law law_linear = {
    .name = "linear",
    .summary = "linear elastic-brittle bond, Cundall-Strack friction after failure",
    .parse = linear_parse,
    .free = linear_free,
    .copy = linear_copy,
    .bond_range = linear_range,
    .setup = linear_setup,
    .constants = linear_constants,
    .init = linear_init,
    .force = linear_force,
    .force_batch = linear_batch,
    .force_pairs = linear_pairs,
    .energy = linear_energy,
    .damage = linear_damage,
    .h_dropped = 0,
};
