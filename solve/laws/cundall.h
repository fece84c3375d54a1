/* Linear Cundall–Strack frictional contact (Cundall & Strack 1979; MODELS.md
 * §3): the engine's law for non-bonded contacts and sphere–platen contacts,
 * and the behaviour of a broken bond of the "linear" law.
 *
 *   u_n < 0 (compression; u_n = d - d0, d0 the zero-force distance):
 *     f_n = K_n u_n + C_n u̇_n,  clipped to f_n <= 0 (no attraction)
 *   u_n >= 0: f_n = 0 and the shear history is forgotten.
 *   Shear, incremental: F_s <- F_s + K_s Δu_s (the history t is the shear
 *   force on i, already rotated into the current contact plane by the
 *   caller), then the Coulomb limit |F_s| <= μ |f_n|. The sliding part is
 *   dissipated: e_friction = (|F_s,trial| - μ|f_n|) μ|f_n| / K_s.
 *   Stored energy f_e² / (2 K_n) + |F_s|² / (2 K_s), f_e = K_n u_n.
 *
 * Selects rather than branches, so loops over contacts vectorise. */
#ifndef DEM_CUNDALL_H
#define DEM_CUNDALL_H

#include <math.h>

#include "solve/law.h"

typedef struct {
	double kn, ks; /* N/m */
	double cn;     /* N s/m, normal viscous coefficient */
	double mu;     /* Coulomb friction coefficient */
} cundall;

/* Forces for normal displacement un (opening positive), normal velocity vn
 * and tangential increment dus; t is the shear force history (in/out). Adds
 * the dissipation to out->e_friction and sets out->fn, fs, fn_viscous. */
static inline void cundall_force(const cundall *c, double un, double vn, const double dus[3],
                                 double t[3], law_out *out)
{
	double touch = un < 0 ? 1.0 : 0.0;
	double fe = c->kn * un;
	double fn = fe + c->cn * vn;
	fn = (fn < 0 ? fn : 0) * touch;
	double lim = -c->mu * fn;
	double tr[3];
	for (int k = 0; k < 3; k++)
		tr[k] = (t[k] + c->ks * dus[k]) * touch;
	double tt = sqrt(tr[0] * tr[0] + tr[1] * tr[1] + tr[2] * tr[2]);
	double slide = tt > lim ? 1.0 : 0.0;
	double scale = slide ? lim / tt : 1.0;
	for (int k = 0; k < 3; k++) {
		t[k] = tr[k] * scale;
		out->fs[k] = t[k];
	}
	out->fn = fn;
	out->fn_viscous = (fn - fe) * touch;
	out->e_friction += slide * (tt - lim) * lim / c->ks;
}

/* Yade's start of a contact (laws/material.h, CONTACT_YADE): u is the normal
 * displacement from touching (d - (r_i + r_j), or h - r for a platen), *u0
 * the overlap at which the contact started (< 0), 0 while it has not.
 * Returns whether the contact acts in this step, at u - *u0; when it does
 * not, it must exert no force and forget its shear history. */
static inline int cundall_started(double *u0, double u)
{
	if (*u0 < 0) {
		if (u - *u0 <= 0)
			return 1;
		*u0 = 0; /* open past its start: it has ended */
	} else if (u < 0)
		*u0 = u; /* found overlapping: it starts, without force */
	return 0;
}

/* Elastic energy of a contact at normal displacement un with shear force t. */
static inline double cundall_energy(const cundall *c, double un, const double t[3])
{
	double fe = un < 0 ? c->kn * un : 0;
	return 0.5 * fe * fe / c->kn + 0.5 * (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]) / c->ks;
}

#endif
