/* Critical time step (Oñate et al. 2015 Eq. 11-15).
 *
 * Δt_cr = 2 / ω_max (Eq. 12), reduced by damping to
 * Δt_cr = 2 / ω_max (sqrt(1 + ξ²) - ξ) (Eq. 13), ξ the largest fraction of
 * critical damping of any contact.
 *
 * ω_max is bounded from above rather than estimated: the mass-scaled
 * stiffness M^-½ K M^-½ is a sum of one term per bond or contact, each
 * acting on the 12 degrees of freedom of its two particles; for a unit
 * vector a, aᵀ (Σ_b A_b) a <= Σ_b λ_b (|a_i|² + |a_j|²), so
 *   ω_max² <= max_i Σ_{b ∋ i} λ_b,
 * a per-particle sum in the spirit of the local eigenproblems of Eq. 14-15
 * that also accounts for the neighbours' motion. For a bond with normal and
 * shear springs K_n, K_s at arms a_i, a_j from the centres,
 *   λ_b = max(K_n (1/m_i + 1/m_j), K_s (1/m_i + 1/m_j + a_i²/I_i + a_j²/I_j))
 * (normal and tangential directions decouple; the shear spring also turns
 * both spheres). A platen contact is the same with one body. Because the
 * bound is rigorous, a safety factor near 1 is stable. */
#include <math.h>
#include <stdlib.h>

#include "lib/err.h"
#include "solve/engine.h"
#include "solve/par.h"
#include "solve/ranks.h"
#include "solve/timestep.h"

double pair_omega2(double kn, double ks, double mi, double mj, double ii, double ij, double ai,
                   double aj)
{
	double lin = 1 / mi + 1 / mj;
	double normal = kn * lin, shear = ks * (lin + ai * ai / ii + aj * aj / ij);
	return normal > shear ? normal : shear;
}

double damping_factor(double xi) { return sqrt(1 + xi * xi) - xi; }

/* The bound on ω² of contact c (0 unless it touches now), which the rank
 * of its i computes (its j is in that rank's halo, ranks.h). */
static double contact_lambda(const engine *e, size_t c)
{
	const particles *P = &e->p;
	const pair_rec *b = &e->pairs.contacts.rec[c];
	double d2 = 0;
	for (int k = 0; k < 3; k++) {
		double dx = P->x[3 * b->j + k] - P->x[3 * b->i + k];
		d2 += dx * dx;
	}
	if (!(d2 < b->d0 * b->d0))
		return isnan(d2) ? NAN : 0; /* no bound from a position that is not finite */
	const double *kk = b->h;
	return pair_omega2(kk[0], kk[1], P->m[b->i], P->m[b->j],
	                   1 / particle_inv_i(P, (size_t)b->i), 1 / particle_inv_i(P, (size_t)b->j),
	                   P->r[b->i], P->r[b->j]);
}

/* Bound on ω² of particle i from the current touching contacts (lam: each
 * contact's contact_lambda) and platen contacts. */
static double contact_omega2(const engine *e, const double *lam, size_t i)
{
	const particles *P = &e->p;
	const pairlist *C = &e->pairs.contacts;
	double sum = 0;
	for (int32_t q = C->off[i]; q < C->off[i + 1]; q++)
		sum += lam[C->ref[q] >> 1];
	for (int k = 0; k < 2; k++) {
		int32_t s = P->pslot[k][i];
		if (s < 0)
			continue;
		const platen_contact *pc = &e->bc.pl.pc[k][s];
		double lin = particle_inv_m(P, i);
		double normal = pc->kn * lin,
		       shear = pc->ks * (lin + P->r[i] * P->r[i] * particle_inv_i(P, i));
		sum += normal > shear ? normal : shear;
	}
	return sum;
}

/* The bound on ω² of bond b, the share of each of its particles. */
static double bond_omega2(const engine *e, size_t b)
{
	const particles *P = &e->p;
	const pair_rec *bd = &e->pairs.bonds.rec[b];
	int32_t i = bd->i, j = bd->j;
	law_pair q = {.ri = P->r[i], .rj = P->r[j], .mi = P->m[i], .mj = P->m[j], .d0 = bd->d0};
	law_const c;
	e->law->constants(e->lp, &q, &c);
	double ai = bd->d0 * P->r[i] / (P->r[i] + P->r[j]), aj = bd->d0 - ai;
	return pair_omega2(c.kn, c.ks, P->m[i], P->m[j], 1 / particle_inv_i(P, (size_t)i),
	                   1 / particle_inv_i(P, (size_t)j), ai, aj);
}

double timestep_bond_omega2(const engine *e, size_t i, int *count)
{
	/* Each bond is one rank's: the sums over every rank's are the whole
	 * specimen's (exact, so the same on any number of ranks). */
	xsum s[2];
	xsum_clear(&s[0]), xsum_clear(&s[1]);
	const pairlist *L = &e->pairs.bonds;
	int64_t l = window_local(&e->p, i); /* the particle here, if held */
	for (size_t b = 0; l >= 0 && b < L->n; b++)
		if (L->rec[b].i == l || L->rec[b].j == l) {
			xsum_add(&s[0], bond_omega2(e, b));
			xsum_add(&s[1], 1);
		}
	par_sum(s, 2);
	*count = (int)xsum_round(&s[1]);
	return xsum_round(&s[0]);
}

double timestep_critical(engine *e, int with_contacts, size_t *worst)
{
	const particles *P = &e->p;
	const pairlist *L = &e->pairs.bonds;
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	/* Each of this rank's particles' bound from its bonds, summed in bond
	 * order: first those of earlier ranks' particles i (the incoming
	 * crossing bonds, whose bounds come from the ranks of their i, in bond
	 * order, bonds.h), then those of its own. */
	double *bw2 = window_array(P->lo, P->hi, sizeof *bw2);
	const bond_split *S = &e->pairs.split;
	double *cw2 = xcalloc(S->ncross + 1, sizeof *cw2);
	for (size_t c = 0; c < S->ncross; c++)
		if (S->cross[c] >= 0)
			cw2[c] = bond_omega2(e, (size_t)S->cross[c]);
	ranks_share_bond_values(e, cw2);
	for (size_t c = 0; c < S->ncross; c++)
		if (S->cross[c] < 0)
			bw2[S->cj[c]] += cw2[c];
	free(cw2);
	for (size_t b = 0; b < L->n; b++) {
		double w2 = bond_omega2(e, b);
		bw2[L->rec[b].i] += w2;
		bw2[L->rec[b].j] += w2;
	}
	/* Each contact's, from the rank of its i. */
	const pairlist *C = &e->pairs.contacts;
	double *lam = xcalloc(C->n + 1, sizeof *lam);
	for (size_t c = 0; with_contacts && c < C->n; c++)
		if ((size_t)C->rec[c].i >= p0)
			lam[c] = contact_lambda(e, c);
	if (with_contacts)
		ranks_share_contact_values(e, lam);
	/* The largest over the particles, the first where two are equal; the
	 * first that is not a number before any. */
	double top[2] = {0, 0}; /* largest bound; 1 if some is NaN */
	int32_t at[2] = {(int32_t)p0, (int32_t)P->n};
	for (size_t i = p0; i < p1; i++) {
		double w2 = bw2[i] + (with_contacts ? contact_omega2(e, lam, i) : 0);
		if (isnan(w2) && !top[1]) {
			top[1] = 1;
			at[1] = (int32_t)i;
		} else if (w2 > top[0]) {
			top[0] = w2;
			at[0] = (int32_t)i;
		}
	}
	window_array_free(bw2, P->lo, sizeof *bw2);
	free(lam);
	par_maxloc(top, at, 2);
	*worst = (size_t)(top[1] > 0 ? at[1] : at[0]);
	if (top[1] > 0)
		return NAN;
	if (top[0] <= 0)
		return INFINITY;
	return 2 / sqrt(top[0]) * damping_factor(e->clock.xi_max);
}
