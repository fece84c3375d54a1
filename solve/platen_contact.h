/* The contact of one sphere with a platen, computed inside the particle loop
 * (each sphere owns its platen contacts, so no gather is needed). The normal
 * n points from the sphere's centre to the platen (-axis for the bottom one,
 * +axis for the top one); the contact point is where n meets the plane, at
 * the centre-plane distance h; u_n = h - r; the platen moves only along the
 * axis, so the tangential increment is that of the sphere's contact point,
 * reversed (the platen relative to the sphere, as for a pair). The platen
 * does not turn, so the shear force keeps its direction, and the torque
 * acts at the contact point, h n × F_s. With Yade's conventions
 * (laws/material.h) the contact starts and ends as Yade's, its shear force
 * turns about n by half the sphere's spin, ½ ω·n Δt, and its torque has
 * the arm r - overlap/2 = (r + h)/2. */
#ifndef DEM_PLATEN_CONTACT_H
#define DEM_PLATEN_CONTACT_H

#include "solve/engine.h"
#include "solve/laws/cundall.h"

/* Adds the platen's force and torque on sphere i to F and T, and the
 * platen's sums (load, stiffness, dissipation, stress) to s. */
static inline void platen_force(const engine *e, int k, int32_t i, platen_contact *c, double F[3],
                                double T[3], particle_sums *s, int measure)
{
	const particles *P = &e->p;
	const double *x = P->x + 3 * i, *v = P->v + 3 * i, *w = P->w + 3 * i;
	const double *a = e->frame.axis;
	double z = (x[0] - e->frame.center[0]) * a[0] + (x[1] - e->frame.center[1]) * a[1] +
	           (x[2] - e->frame.center[2]) * a[2];
	double side = k == 0 ? -1 : 1;
	double h = k == 0 ? z - e->bc.pl.z[0] : e->bc.pl.z[1] - z;
	double n[3] = {side * a[0], side * a[1], side * a[2]};
	double va = v[0] * a[0] + v[1] * a[1] + v[2] * a[2];
	law_kin kin;
	kin.un = h - P->r[i];
	kin.vn = k == 0 ? va - e->bc.pl.vel[0] : e->bc.pl.vel[1] - va;
	/* Contact-point velocity of the sphere: v + ω × (h n). */
	double vc[3] = {v[0] + h * (w[1] * n[2] - w[2] * n[1]),
	                v[1] + h * (w[2] * n[0] - w[0] * n[2]),
	                v[2] + h * (w[0] * n[1] - w[1] * n[0])};
	double vcn = vc[0] * n[0] + vc[1] * n[1] + vc[2] * n[2];
	double tn = c->t[0] * n[0] + c->t[1] * n[1] + c->t[2] * n[2];
	for (int d = 0; d < 3; d++) {
		kin.dus[d] = -(vc[d] - vcn * n[d]) * e->clock.dt;
		c->t[d] -= tn * n[d];
	}
	int yade = e->cs->mat.conventions == CONTACT_YADE;
	double arm = h;
	if (yade) {
		double spin = 0.5 * e->clock.dt * (w[0] * n[0] + w[1] * n[1] + w[2] * n[2]);
		double u[3] = {c->t[0], c->t[1], c->t[2]};
		c->t[0] = u[0] + spin * (n[1] * u[2] - n[2] * u[1]);
		c->t[1] = u[1] + spin * (n[2] * u[0] - n[0] * u[2]);
		c->t[2] = u[2] + spin * (n[0] * u[1] - n[1] * u[0]);
		arm = 0.5 * (P->r[i] + h);
	}
	if (yade && !cundall_started(&c->u0, kin.un))
		kin.un = 0; /* as just touching: no force, no shear */
	else
		kin.un -= c->u0;
	law_out out = {0};
	cundall cd = {.kn = c->kn, .ks = c->ks, .cn = c->cn, .mu = e->cs->mat.platen_friction};
	cundall_force(&cd, kin.un, kin.vn, kin.dus, c->t, &out);
	double f[3];
	for (int d = 0; d < 3; d++) {
		f[d] = out.fn * n[d] + out.fs[d];
		F[d] += f[d];
	}
	T[0] += arm * (n[1] * out.fs[2] - n[2] * out.fs[1]);
	T[1] += arm * (n[2] * out.fs[0] - n[0] * out.fs[2]);
	T[2] += arm * (n[0] * out.fs[1] - n[1] * out.fs[0]);
	int touch = kin.un < 0;
	s->load[k] -= out.fn;
	s->ksum[k] += touch ? c->kn : 0;
	s->ntouch[k] += touch;
	s->platen_friction += out.e_friction;
	s->platen_viscous += out.fn_viscous * kin.vn * e->clock.dt;
	if (measure) {
		s->platen_elastic += cundall_energy(&cd, kin.un, c->t);
		for (int p = 0; p < 3; p++)
			for (int q = 0; q < 3; q++)
				s->love[3 * p + q] += h * n[p] * f[q];
	}
}

#endif
