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

#include "lib/runfile.h"
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

static inline void shear_slip(double t[3], double ks, double limit)
{
	double f = ks * v3_norm(t);
	if (f > limit)
		v3_scale(t, t, limit > 0 ? limit / f : 0);
}

/* Adds dus to t and applies the limits above; fnc is the compressive normal
 * force (negative in tension), cA the cohesive strength c A. Returns 1 when
 * an intact bond ruptures in this call. */
static inline int shear_mohr_coulomb(double t[3], const double dus[3], double ks, double fnc,
                                     double cA, double tan_b, double tan_c, int intact)
{
	v3_add(t, t, dus);
	if (!intact) {
		shear_slip(t, ks, fnc * tan_c);
		return 0;
	}
	double limit = cA + fnc * tan_b, f = ks * v3_norm(t);
	if (f <= limit)
		return 0;
	v3_scale(t, t, fnc < 0 ? 0 : limit / f);
	return 1;
}

#endif
