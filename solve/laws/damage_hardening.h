/* The damage and hardening core (prefix dh_) that the exponential law
 * shares with the local model of Oñate et al. 2015 (seeds/000, "onate"):
 * the elastic constants and contact damping, tension by elasto-damage with
 * linear softening, and compression loading along a hardening curve with
 * unloading and reloading at the initial stiffness.
 *
 * Elastic constants (Eq. 21, 29-30, 36), with A the effective area:
 *
 *     K_n = A E0 / d          K_s = K_n / (2 (1 + nu))
 *     C_n = 2 xi A / (r_c d) sqrt(m_ij K_n)        (= Eq. 30 for A = alpha pi r_c^2;
 *                                                    Eq. 27 carries xi / r_c)
 *
 * Linear softening (Eq. 46-49), for a displacement measure x with elastic
 * limit x_l and x_f = (1 + delta) x_l:
 *
 *     d = 0 for x <= x_l,  (x / x_l - 1) / delta on the branch,  1 for x >= x_f
 *     d = max(d, history): damage never decreases (no healing)
 *     F = K x (1 - d) / (1 + delta d)
 *
 * The last line is Eq. 46 written with the secant stiffness of the point
 * reached: on the branch x = x_l (1 + delta d), so F = (1 - d) K x_l as in
 * Eq. 46; below it the bond unloads and reloads along that secant towards
 * the origin (Fig. 8), so damage alone fixes the force and the area under
 * the branch, 1/2 F_l x_f, is the work of a failure (Sect. 7.2).
 *
 * Normal direction, in strains eps = u_n / d (opening positive) and
 * contact stresses (F = A sigma, Eq. 20). Compression c = -eps follows a
 * loading curve sigma_c(c) (Fig. 10 for onate; the exponential curve of
 * 001 for exponential) while c exceeds its historical maximum c_max
 * (Eq. 52a); below it the bond unloads and reloads with E0, the initial
 * stiffness K_n0 (Eq. 52b), about the permanent indentation
 *
 *     c_p = c_max - sigma_c(c_max) / E0.
 *
 * Opening beyond c_p is tension of the bond, measured from c_p: e = c_p - c,
 * sigma = E0 e (1 - d_n) / (1 + delta_n d_n), d_n from x = e with the
 * limit x_l = sigma_t / E0 (u_n^l / d of Eq. 49a). Tensile damage leaves
 * compression untouched; a broken bond carries no tension.
 *
 * History layout shared by both laws (bond.h):
 *   h[0]  d_n, tension damage in [0, 1]
 *   h[1]  d_s, shear damage in [0, 1] (exponential: C_n, its d_s being
 *         the state's)
 *   h[2]  c_max, the largest compressive strain reached (>= 0)
 * c_p is recomputed from c_max, so the plastic state costs one slot.
 */
#ifndef DEM_LAWS_DAMAGE_HARDENING_H
#define DEM_LAWS_DAMAGE_HARDENING_H

#include <math.h>

#include "lib/cfg.h"
#include "lib/states.h"
#include "lib/vec3.h"
#include "solve/law.h"
#include "solve/laws/area.h"

/* The keys both laws read (see share/doc/materials.md). */
typedef struct {
	double E0;      /* Pa, Young modulus at the onset of loading */
	double nu;      /* Poisson ratio, for K_s (Eq. 36) */
	double sigma_t; /* Pa, tensile strength sigma_t^f (Eq. 42) */
	double delta_n; /* (u_n^f - u_n^l) / u_n^l (Eq. 47) */
	double xi;      /* fraction of critical damping (Eq. 27) */
	double eps_t;   /* sigma_t / E0: tensile limit strain */
} dh_params;

int dh_parse(cfg *m, dh_params *q);

/* Loading curve: compressive stress at compressive strain c, and the
 * permanent strain c - sigma / E0 (exactly 0 on the elastic part). */
typedef double (*dh_curve)(const void *law, double c, double *c_p);

/* Damage of Eq. 49 for the measure x with elastic limit xl. */
static inline double dh_damage_at(double x, double xl, double delta)
{
	if (x <= xl)
		return 0;
	if (delta <= 0 || x >= (1 + delta) * xl)
		return 1;
	return (x / xl - 1) / delta;
}

/* Secant stiffness of the damaged branch over the undamaged one (Eq. 46). */
static inline double dh_secant(double d, double delta) { return (1 - d) / (1 + delta * d); }

/* Normal stress (tension positive) at strain eps, updating h[0] and h[2]
 * (see the layout above). *open is the opening strain e from the permanent
 * indentation (negative in compression). *broke is set when the tension
 * damage reaches 1 in this call; a broken bond (broken != 0) carries no
 * tension. Adds to *w the energy dissipated in this call per unit volume
 * A d (J/m^3): by damage, G d_n with G = 1/2 sigma_t eps_t (1 + delta_n)
 * the work of a whole failure (the area between the loading path and the
 * secant grows linearly with d_n), and by plastic flow along the curve,
 * the work of the trapezoid less the change of recoverable energy. */
static inline double dh_normal(const dh_params *q, dh_curve curve, const void *law, double eps,
                               double h[LAW_NHIST], int broken, double *open, int *broke, double *w)
{
	double c = -eps, cp;
	if (c > h[2]) { /* loading past the historical maximum, Eq. 52a */
		double s = curve(law, c, &cp);
		if (cp > 0) {
			double cp0, s0 = curve(law, h[2], &cp0);
			*w += 0.5 * (s0 + s) * (c - h[2]) - 0.5 * (s * s - s0 * s0) / q->E0;
		}
		h[2] = c;
		*open = cp - c;
		return -s;
	}
	curve(law, h[2], &cp);
	double e = cp - c;
	*open = e;
	if (e <= 0) /* unloading or reloading with K_n0, Eq. 52b */
		return q->E0 * e;
	if (broken)
		return 0;
	double d = law_min(1, law_max(h[0], dh_damage_at(e, q->eps_t, q->delta_n)));
	*w += 0.5 * q->E0 * q->eps_t * q->eps_t * (1 + q->delta_n) * (d - h[0]);
	h[0] = d;
	if (d >= 1) {
		*broke = 1;
		return 0;
	}
	return q->E0 * e * dh_secant(d, q->delta_n);
}

/* dh_normal without branches where it changes no damage and no plastic
 * state, for the vector loops of the laws: on the loading curve's first
 * part (compressive strain up to eps_max, where it is E0 c, now and at
 * the largest compression so far, so the permanent indentation is 0), and
 * in tension up to the limit strain (the tension damage stays h0), or at
 * any opening when the bond is broken (broken != 0: no tension). The
 * normal stress at compressive strain c with dh_normal's expressions, the
 * opening strain *e, h[2] in *h2 (c when loading) and whether the bond
 * is on that branch (*elastic; else dh_normal must compute it). With
 * `undamaged` (a constant: h0 is 0) the secant is 1, its division not
 * made. */
static inline double dh_normal_first(const dh_params *q, double eps_max, double c, double h0,
                                     int32_t broken, double *h2, double *e, int32_t *elastic,
                                     int undamaged)
{
	double c_max = *h2, open = 0.0 - c;
	int32_t loading = c > c_max;
	double secant = undamaged ? 1 : dh_secant(h0, q->delta_n);
	double tension = law_sel(broken, 0, q->E0 * open * secant);
	double sigma = loading ? -(q->E0 * c) : open <= 0 ? q->E0 * open : tension;
	int32_t load_ok = !(c > eps_max), first = !(c_max > eps_max);
	int32_t unload_ok = first & ((open <= q->eps_t) | broken);
	int32_t ok = (loading & load_ok) | ((1 - loading) & unload_ok);
	*h2 = (ok & loading) ? c : c_max;
	*e = open;
	*elastic = ok;
	return sigma;
}

/* dh_normal without branches for every state that changes no damage, for
 * the vector loops of laws with a hardening curve: loading past the
 * largest compression so far on any part of the curve (with its plastic
 * work), unloading and reloading about the permanent indentation, tension
 * up to the limit strain, any opening of a broken bond (broken != 0: no
 * tension). s, cp: the curve's stress and permanent strain
 * at the compressive strain c; s0, cp0 at the largest so far, *h2. The
 * normal stress, as dh_normal gives it, with the opening strain *e, the
 * new *h2 (c when loading), the dissipated energy per unit volume *w (0
 * but when loading where the curve has left its elastic part) and whether
 * the bond is on that branch (*elastic; else dh_normal must compute it).
 * The same expressions as dh_normal, chosen by law_sel. */
static inline double dh_normal_curve(const dh_params *q, double c, double s, double cp, double s0,
                                     double cp0, double h0, int32_t broken, double *h2, double *e,
                                     double *w, int32_t *elastic)
{
	double c_max = *h2;
	int64_t loading = c > c_max;
	double open = law_sel(loading, cp - c, cp0 - c);
	double tension = law_sel(broken, 0, q->E0 * open * dh_secant(h0, q->delta_n));
	double sigma = law_sel(loading, -s, law_sel(open <= 0, q->E0 * open, tension));
	double work = 0.5 * (s0 + s) * (c - c_max) - 0.5 * (s * s - s0 * s0) / q->E0;
	int32_t ok = (int32_t)loading | (open <= q->eps_t) | broken;
	*w = law_sel(loading & (cp > 0), 0.0 + work, 0);
	*h2 = law_sel(ok & loading, c, c_max);
	*e = open;
	*elastic = ok;
	return sigma;
}

/* Elastic energy of the normal spring in the state stored in h at the
 * normal displacement un of the last force() call (changing nothing):
 * 1/2 F^2 / K with the current stiffness, K_n0 in compression and
 * the damaged secant in tension, i.e. 1/2 A d sigma^2 / E. */
static inline double dh_normal_energy(const dh_params *q, dh_curve curve, const void *law,
                                      double area, double d0, const double h[LAW_NHIST], int broken,
                                      double un)
{
	double copy[LAW_NHIST] = {h[0], h[1], h[2]}, open, w = 0;
	int broke = 0;
	double s = dh_normal(q, curve, law, un * (1 / d0), copy, broken, &open, &broke, &w);
	if (s == 0)
		return 0;
	double e = q->E0 * (s < 0 ? 1 : dh_secant(h[0], q->delta_n));
	return 0.5 * area * d0 * s * s / e;
}

/* law.damage of onate. */
static inline void dh_damage(const law_params *p, const bond *b, double *dn, double *ds)
{
	(void)p;
	*dn = b->h[0];
	*ds = b->h[1];
}

/* Contact damping coefficient (Eq. 30) for effective area A. */
static inline double dh_cn(const dh_params *q, const law_pair *pair, double area, double kn)
{
	double rc = area_rc(pair), mij = pair->mi * pair->mj / (pair->mi + pair->mj);
	return 2 * q->xi * area / (rc * pair->d0) * sqrt(mij * kn);
}

#endif
