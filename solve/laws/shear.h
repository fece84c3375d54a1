/* The shear history t of a bond (law.h: the engine keeps it in the contact
 * plane), shared by every law here: zero for a new bond and after a
 * failure; after a failure and in Mohr-Coulomb bonds it is the elastic
 * shear displacement of a friction contact, the shear force on particle i
 * being k_s t.
 *
 * Coulomb (Oñate et al. 2015 Eq. 45; seeds/002 Eq. 3.14): |k_s t| <= limit;
 * beyond it the contact slides and t is scaled back onto the limit, so the
 * force keeps its direction and sticks again on reversal.
 *
 * Mohr-Coulomb bond (seeds/002 Eq. 3.12-3.14, Yade's
 * JointedCohesiveFrictionalPM; seeds/001 §3.3.3 for the exponential law):
 * an intact bond holds |k_s t| <= c A + F_nc tan(phi_b), F_nc the normal
 * force counted positive in compression (so tension lowers the strength).
 * Beyond it the bond ruptures: in that step the force is capped at the bond
 * strength, as Yade does, or removed if the bond is in tension (Yade erases
 * the interaction); from then on it is a Coulomb contact with
 * limit F_nc tan(phi_c), nothing when not in compression.
 */
#ifndef DEM_LAWS_SHEAR_H
#define DEM_LAWS_SHEAR_H

#include <string.h>

#include "lib/states.h"
#include "lib/vec3.h"
#include "solve/law.h"

/* law.init of every law here: an intact bond with no history. */
static inline void shear_new_bond(const law_params *p, const law_pair *pair, bond *b)
{
	(void)p, (void)pair;
	memset(b->t, 0, sizeof b->t);
	memset(b->h, 0, sizeof b->h);
	b->state = BOND_INTACT;
}

/* A bond failing in this call: the friction contact it leaves starts from
 * zero shear displacement. */
static inline void shear_break(bond *b, law_out *out, uint8_t state, int crack)
{
	b->state = state;
	out->failed = crack;
	memset(b->t, 0, sizeof b->t);
}

/* Scales the trial displacement t (= t_old + dus) by s <= 1 and returns the
 * energy this dissipates: the work done in the step less the change of
 * stored energy, 1/2 k_s (t_old + t_new) . (t_trial - t_new). It is
 * limit x slip when sliding steadily, and includes what a drop of the limit
 * (a rupture, a falling normal force) releases. */
static inline double shear_scale(double t[3], const double old[3], double ks, double s)
{
	double a[3];
	v3_copy(a, old);
	v3_axpy(a, t, s);
	double e = 0.5 * ks * (1 - s) * v3_dot(a, t);
	v3_scale(t, t, s);
	return e;
}

/* Adds dus to t and applies the Coulomb limit, booking the work of sliding
 * to out->e_friction. */
static inline void shear_slip(double t[3], const double dus[3], double ks, double limit,
                              law_out *out)
{
	double old[3];
	v3_copy(old, t);
	v3_add(t, t, dus);
	double f = ks * v3_norm(t);
	if (f > limit)
		out->e_friction += shear_scale(t, old, ks, limit > 0 ? limit / f : 0);
}

/* shear_slip without branches, for the laws' vector loops (force_pairs)
 * that compute friction contacts (broken bonds) among other lanes: t the
 * trial displacement (the rotated history old plus the increment), f =
 * k_s |t|. Where lane is set and f exceeds the limit, t is scaled back as
 * shear_slip does and the work shear_scale books is returned; else t is
 * left and 0 returned. The same expressions, chosen by law_sel. */
static inline double shear_slip_lane(double t[3], const double old[3], double ks, double f,
                                     double limit, int64_t lane)
{
	int64_t slide = lane & (f > limit);
	double s = law_sel(limit > 0, limit / f, 0);
	double a[3] = {old[0] + t[0] * s, old[1] + t[1] * s, old[2] + t[2] * s};
	double work = 0.5 * ks * (1 - s) * (a[0] * t[0] + a[1] * t[1] + a[2] * t[2]);
	for (int c = 0; c < 3; c++)
		t[c] = law_sel(slide, t[c] * s, t[c]);
	return law_sel(slide, 0.0 + work, 0);
}

/* Adds dus to t and applies the Mohr-Coulomb limits above; fnc is the
 * compressive normal force (negative in tension), cA the cohesive strength
 * c A. Returns 1 when an intact bond ruptures in this call, booking what the
 * rupture releases to out->e_damage and the shear force it judged, k_s |t|,
 * to out->fs_failed; sliding afterwards goes to out->e_friction. */
static inline int shear_mohr_coulomb(double t[3], const double dus[3], double ks, double fnc,
                                     double cA, double tan_b, double tan_c, int intact,
                                     law_out *out)
{
	if (!intact) {
		shear_slip(t, dus, ks, fnc * tan_c, out);
		return 0;
	}
	double old[3];
	v3_copy(old, t);
	v3_add(t, t, dus);
	double limit = cA + fnc * tan_b, f = ks * v3_norm(t);
	if (f <= limit)
		return 0;
	out->fs_failed = f;
	out->e_damage += shear_scale(t, old, ks, fnc < 0 ? 0 : limit / f);
	return 1;
}

#endif
