/* Relative motion at the contact point of two spheres during one step, as a
 * law sees it (law.h conventions; Oñate et al. 2015 Eq. 26 and 34):
 *
 *   n    = (x_j - x_i) / d,  d = |x_j - x_i|,   u_n = d - d0
 *   u̇_n  = (v_j - v_i) · n
 *   the contact point splits d in proportion to the radii: arms
 *   a_i = d r_i / (r_i + r_j) along +n from i, a_j = d r_j / (r_i + r_j) along -n from j
 *   Δu_s = [(v_j + ω_j × (-a_j n)) - (v_i + ω_i × (a_i n))]_tangential Δt   (Eq. 34)
 *
 * Velocities are those at t - Δt/2, which moved the particles from the last
 * step's positions to these (Eq. 6-7, 9-10), so Δu_s is the increment of the
 * last step. A rigid rotation of the pair gives Δu_s = 0.
 *
 * The tangential history t lies in the previous step's contact plane. It is
 * turned into the current one by projecting it on the plane and restoring its
 * length (the tilt of the normal), then rotated about n by the pair's mean
 * spin ½ (ω_i + ω_j)·n Δt (the twist), so laws never see rigid rotations. */
#ifndef DEM_KINEMATICS_H
#define DEM_KINEMATICS_H

#include <math.h>
#include <stdint.h>

#include "solve/law.h"

static inline void pair_kinematics(const double *restrict x, const double *restrict v,
                                   const double *restrict w, const double *restrict r,
                                   const double *restrict m, int32_t i, int32_t j, double d0,
                                   double dt, double t[3], law_pair *pair, law_kin *k, double n[3],
                                   double *dist)
{
	const double *xi = x + 3 * i, *xj = x + 3 * j;
	double dx[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
	double d = sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
	double inv = 1 / d;
	for (int c = 0; c < 3; c++)
		n[c] = dx[c] * inv;
	double ri = r[i], rj = r[j];
	*pair = (law_pair){.ri = ri, .rj = rj, .mi = m[i], .mj = m[j], .d0 = d0};
	*dist = d;
	const double *vi = v + 3 * i, *vj = v + 3 * j, *wi = w + 3 * i, *wj = w + 3 * j;
	double ai = d * ri / (ri + rj), aj = d - ai;
	double dv[3] = {vj[0] - vi[0], vj[1] - vi[1], vj[2] - vi[2]};
	double ws[3] = {aj * wj[0] + ai * wi[0], aj * wj[1] + ai * wi[1], aj * wj[2] + ai * wi[2]};
	double vc[3] = {dv[0] - (ws[1] * n[2] - ws[2] * n[1]),
	                dv[1] - (ws[2] * n[0] - ws[0] * n[2]),
	                dv[2] - (ws[0] * n[1] - ws[1] * n[0])};
	double vcn = vc[0] * n[0] + vc[1] * n[1] + vc[2] * n[2];
	k->un = d - d0;
	k->vn = dv[0] * n[0] + dv[1] * n[1] + dv[2] * n[2];
	for (int c = 0; c < 3; c++)
		k->dus[c] = (vc[c] - vcn * n[c]) * dt;

	double tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
	double tt = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
	double p = tt - tn * tn;
	double s = p > 0 ? sqrt(tt / p) : 0;
	double spin =
	    0.5 * dt * ((wi[0] + wj[0]) * n[0] + (wi[1] + wj[1]) * n[1] + (wi[2] + wj[2]) * n[2]);
	double u[3] = {(t[0] - tn * n[0]) * s, (t[1] - tn * n[1]) * s, (t[2] - tn * n[2]) * s};
	t[0] = u[0] + spin * (n[1] * u[2] - n[2] * u[1]);
	t[1] = u[1] + spin * (n[2] * u[0] - n[0] * u[2]);
	t[2] = u[2] + spin * (n[0] * u[1] - n[1] * u[0]);
}

/* The force on i and the torque per unit radius from a law's output: the
 * torque on i is (a_i n) × F_s = r_i (d / (r_i + r_j)) n × F_s, on j r_j times
 * the same vector (Eq. 4). */
static inline void pair_force(const law_out *o, const double n[3], double d, double ri, double rj,
                              double f[6])
{
	double s = d / (ri + rj);
	for (int c = 0; c < 3; c++)
		f[c] = o->fn * n[c] + o->fs[c];
	f[3] = s * (n[1] * o->fs[2] - n[2] * o->fs[1]);
	f[4] = s * (n[2] * o->fs[0] - n[0] * o->fs[2]);
	f[5] = s * (n[0] * o->fs[1] - n[1] * o->fs[0]);
}

#endif
