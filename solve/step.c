/* One time step: forces at x(t) from the bonds (summed per particle as they
 * are computed, bonds.h) and the contacts (gathered per particle), with the
 * platen contacts and the confinement, then central
 * differences with rotations (Oñate et al. 2015 Eq. 5-10):
 *
 *   v(t + Δt/2) = v(t - Δt/2) + Δt (F + F_damp) / m          (Eq. 5-6)
 *   x(t + Δt)   = x(t) + Δt v(t + Δt/2)                      (Eq. 7)
 *   ω(t + Δt/2) = ω(t - Δt/2) + Δt (T + T_damp) / I,  I = 2/5 m r²   (Eq. 8-9)
 *   (Δθ = ω Δt, Eq. 10, enters the next step's shear increments)
 *
 * with the global non-viscous damping (Eq. 39-40)
 *   F_damp = -α^t |F| v/|v|,  T_damp = -α^r |T| ω/|ω|   (velocities at t - Δt/2),
 * or, with the case's damping.form "components", Yade's per-component rule
 * (damp below).
 *
 * Energies use the central-difference "shadow" kinetic energy
 * ½ m v(t - Δt/2)·v(t + Δt/2), which with the elastic energy at t is exactly
 * conserved by the scheme for a linear undamped system; the work of a force
 * G(t) is G · ½ (v(t - Δt/2) + v(t + Δt/2)) Δt, the matching rule. */
#include <math.h>
#include <omp.h>
#include <stddef.h>
#include <string.h>

#include "lib/vec3.h"
#include "solve/blocks.h"
#include "solve/bonds.h"
#include "solve/boundary.h"
#include "solve/contacts.h"
#include "solve/engine.h"
#include "solve/measure.h"
#include "solve/pairlist.h"
#include "solve/par.h"
#include "solve/platen_contact.h"
#include "solve/platens.h"
#include "solve/ranks.h"
#include "solve/reduce.h"
#include "solve/step.h"
#include "solve/surface.h"
#include "solve/timers.h"
#include "solve/vec4.h"

static inline void gather(const pairlist *L, int32_t i, double ri, double F[3], double T[3])
{
	for (int32_t q = L->off[i]; q < L->off[i + 1]; q++) {
		int32_t ref = L->ref[q];
		const double *f = L->f + 6 * (ref >> 1);
		/* 1 at the contact's end i, -1 at j, without a branch (which
		 * the CPU would guess at random from contact to contact) */
		double s = (double)(1 - 2 * (ref & 1));
		F[0] += s * f[0];
		F[1] += s * f[1];
		F[2] += s * f[2];
		T[0] += ri * f[3];
		T[1] += ri * f[4];
		T[2] += ri * f[5];
	}
}

static inline double dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The unit radial vector at x (from the axis of the frame fr), 0 on the
 * axis; without a branch, so that the particles' vector loop
 * (integrate_free_lanes) vectorises it too. */
static inline __attribute__((always_inline)) void radial_unit(const engine_frame *fr,
                                                              const double *x, double u[3])
{
	double d[3];
	for (int k = 0; k < 3; k++)
		d[k] = x[k] - fr->center[k];
	double z = dot3(d, fr->axis);
	for (int k = 0; k < 3; k++)
		u[k] = d[k] - z * fr->axis[k];
	double l = sqrt(dot3(u, u));
	double inv = law_sel(l > 0, 1 / l, 0);
	for (int k = 0; k < 3; k++)
		u[k] *= inv;
}

/* The confining pressure on surface particle i (slot in the surface list)
 * as a radial inward force ext, added to F. */
static inline void confine(const engine *e, int32_t i, int32_t slot, const double er[3],
                           double F[3], double ext[3], particle_sums *s, int measure)
{
	const loads *ld = &e->bc.loads;
	double ri = e->p.r[i];
	double area = ld->method == PRESSURE_PAPER ? DEM_PI * ri * ri : e->bc.surf.area[slot];
	double mag = ld->pressure * area;
	for (int k = 0; k < 3; k++) {
		ext[k] = -mag * er[k];
		F[k] += ext[k];
	}
	s->lateral_force += mag;
	if (measure)
		for (int p = 0; p < 3; p++)
			for (int q = 0; q < 3; q++)
				s->love[3 * p + q] += ri * er[p] * ext[q];
}

/* Prescribed motion of an end-layer particle (layer k): the reaction R is
 * what keeps it (Yade-style loading). R does the work; the axial load
 * measured is the force of the bonds and contacts, -F, without the inertia
 * of the layer, which would otherwise show the jump to the loading speed as
 * a spike. */
static inline void move_layer(const engine *e, int32_t i, int k, const double F[3], double vn[3],
                              double wn[3], particle_sums *s)
{
	const double *v = e->p.v + 3 * i, *axis = e->frame.axis;
	double m = e->p.m[i], dt = e->clock.dt, R[3];
	for (int c = 0; c < 3; c++) {
		vn[c] = e->bc.loads.layer_vel[k] * axis[c];
		wn[c] = 0;
		R[c] = m * (vn[c] - v[c]) / dt - F[c];
	}
	double fa = -dot3(F, axis);
	s->layer[k] += k == 0 ? fa : -fa;
	s->e_work +=
	    0.5 * dt * (R[0] * (v[0] + vn[0]) + R[1] * (v[1] + vn[1]) + R[2] * (v[2] + vn[2]));
}

/* The global non-viscous damping force fd of a force F on a velocity v
 * (at t - Δt/2), h = Δt / mass (or Δt / inertia for a torque).
 * DAMPING_VECTOR, Eq. 39-40: fd = -α |F| v/|v|.
 * DAMPING_COMPONENTS, Yade's NewtonIntegrator (yade/trunk
 * pkg/dem/NewtonIntegrator.cpp, cundallDamp2nd, as in Debian's 2023.02a):
 * each component on its own, against the sign of the velocity it is
 * predicted to have at t,
 *   fd_k = -α F_k sign(F_k (v_k + ½ h F_k)),
 * i.e. -α |F_k| in the direction opposing v_k + ½ h F_k, zero when F_k or
 * that velocity is zero. */
static inline void damp(int form, double alpha, const double F[3], const double v[3], double h,
                        double fd[3])
{
	if (form == DAMPING_COMPONENTS) {
		for (int c = 0; c < 3; c++) {
			double s = F[c] * (v[c] + 0.5 * h * F[c]);
			fd[c] = s > 0 ? -alpha * F[c] : s < 0 ? alpha * F[c] : 0;
		}
		return;
	}
	double fa = sqrt(dot3(F, F)), va = sqrt(dot3(v, v));
	double cf = va > 0 ? -alpha * fa / va : 0;
	for (int c = 0; c < 3; c++)
		fd[c] = cf * v[c];
}

/* Central differences with the global non-viscous damping (Eq. 5-6, 8-9,
 * 39-40, or Yade's form: damp above) for a free particle. */
static inline void move_free(const engine *e, int32_t i, const double F[3], const double T[3],
                             double vn[3], double wn[3], particle_sums *s)
{
	const particles *P = &e->p;
	const double *v = P->v + 3 * i, *w = P->w + 3 * i;
	double dt = e->clock.dt;
	double im = particle_inv_m(P, (size_t)i), ii = particle_inv_i(P, (size_t)i);
	double fd[3], td[3];
	damp(e->cs->damping_form, e->cs->alpha_t, F, v, dt * im, fd);
	damp(e->cs->damping_form, e->cs->alpha_r, T, w, dt * ii, td);
	for (int c = 0; c < 3; c++) {
		vn[c] = v[c] + dt * im * (F[c] + fd[c]);
		wn[c] = w[c] + dt * ii * (T[c] + td[c]);
	}
	s->e_damped -= 0.5 * dt * (dot3(fd, v) + dot3(fd, vn) + dot3(td, w) + dot3(td, wn));
}

/* Radial displacement held: remove the radial velocity; the force that
 * does so is the constraint's reaction. */
static inline void hold_radially(const engine *e, int32_t i, const double er[3], double vn[3],
                                 particle_sums *s, int measure)
{
	double vr = dot3(vn, er);
	for (int c = 0; c < 3; c++)
		vn[c] -= vr * er[c];
	double R = -e->p.m[i] * vr / e->clock.dt;
	s->constraint_force -= R;
	if (measure)
		for (int p = 0; p < 3; p++)
			for (int q = 0; q < 3; q++)
				s->love[3 * p + q] += e->p.r[i] * er[p] * R * er[q];
}

/* The step's energies of particle i (shadow kinetic, Eq. 7's work of the
 * external force ext), then its new velocities and position, its drift
 * since the last rebuild, and whether its state is still finite. */
static inline void advance(engine *e, int32_t i, const double vn[3], const double wn[3],
                           const double ext[3], particle_sums *s)
{
	particles *P = &e->p;
	double *x = P->x + 3 * i, *v = P->v + 3 * i, *w = P->w + 3 * i;
	double ri = P->r[i], dt = e->clock.dt;
	double mass = P->m[i], inertia = 0.4 * mass * ri * ri;
	s->ke += 0.5 * (mass * dot3(v, vn) + inertia * dot3(w, wn));
	double vv = dot3(vn, vn);
	s->ke_new += 0.5 * (mass * vv + inertia * dot3(wn, wn));
	s->v2max = vv > s->v2max ? vv : s->v2max;
	s->e_work += 0.5 * dt *
	             (ext[0] * (v[0] + vn[0]) + ext[1] * (v[1] + vn[1]) + ext[2] * (v[2] + vn[2]));
	double d2 = 0;
	for (int c = 0; c < 3; c++) {
		v[c] = vn[c];
		w[c] = wn[c];
		x[c] += dt * vn[c];
		double dx = x[c] - P->x_ref[3 * ((size_t)i - P->own0) + c];
		d2 += dx * dx;
	}
	s->disp2 = d2 > s->disp2 ? d2 : s->disp2;
	if (!(isfinite(x[0] + x[1] + x[2] + w[0] + w[1] + w[2])) && s->bad > i)
		s->bad = i;
}

static void integrate_one(engine *e, int32_t i, int measure, particle_sums *s)
{
	particles *P = &e->p;
	const double *acc = engine_acc(e, (size_t)i);
	double F[3] = {acc[0], acc[1], acc[2]}, T[3] = {acc[3], acc[4], acc[5]};
	gather(&e->pairs.contacts, i, P->r[i], F, T);
	for (int k = 0; k < 2; k++)
		if (P->pslot[k][i] >= 0)
			platen_force(e, k, i, &e->bc.pl.pc[k][P->pslot[k][i]], F, T, s, measure);
	double vn[3], wn[3], ext[3] = {0, 0, 0}, er[3] = {0, 0, 0};
	int32_t slot = P->surf[i];
	uint8_t flag = P->flag[i];
	int confined = slot >= 0 && e->bc.loads.lateral == LATERAL_PRESSURE;
	if (confined || (flag & PF_CONSTRAINED))
		radial_unit(&e->frame, P->x + 3 * i, er);
	if (confined)
		confine(e, i, slot, er, F, ext, s, measure);
	if (e->bc.loads.layers && (flag & (PF_LAYER_BOTTOM | PF_LAYER_TOP))) {
		move_layer(e, i, flag & PF_LAYER_TOP ? 1 : 0, F, vn, wn, s);
	} else {
		move_free(e, i, F, T, vn, wn, s);
		if (flag & PF_CONSTRAINED)
			hold_radially(e, i, er, vn, s, measure);
	}
	advance(e, i, vn, wn, ext, s);
}

/* The particles of a block are moved LANES at a time: their lanes
 * (free_lanes) then stay in the first-level cache. */
enum { LANES = 64 };

/* What move_free, hold_radially and advance compute for LANES particles of
 * a block (with the vector form of the damping), lane q for its particle
 * q: the new state and each particle's terms of the block's sums, added in
 * particle order afterwards; used where free[q] (moves_freely). ext is the
 * confining force (0 but on the confined), already in F; lateral its
 * magnitude, where confined. */
typedef struct {
	uint8_t free[LANES], confined[LANES], radial[LANES];
	double F[3][LANES], T[3][LANES], ext[3][LANES], lateral[LANES];
	double v[3][LANES], w[3][LANES], x[3][LANES];
	double damped[LANES], ke[LANES], ke_new[LANES], vv[LANES], work[LANES], d2[LANES];
	double finite[LANES]; /* the sum whose finiteness advance checks */
} free_lanes;

/* move_free (DAMPING_VECTOR), where held and fl->radial hold_radially (the
 * radial unit vector from the frame fr, radial_unit; not the sum of the
 * reactions, which only a measured step reads, and a measured step moves
 * these particles one by one) and advance with ext fl->ext for the nl
 * particles i0 + q (lanes q < nl) of forces fl->F, fl->T, with their
 * expressions, in a loop the compiler can vectorise: the particles' values
 * lie in a row, read as vectors; the division of damp is computed whatever
 * the speed, its result chosen by law_sel only where the speed is positive,
 * as damp uses it (with ?: the AVX2 version kept a branch and stayed
 * scalar). The lanes of particles that do not move freely are computed too,
 * and not used. XR holds the positions at the last rebuild from particle
 * xr0 on. */
static inline __attribute__((always_inline)) void
integrate_free_lanes(const double *restrict X, const double *restrict V, const double *restrict W,
                     const double *restrict R, const double *restrict M, const double *restrict XR,
                     int32_t xr0, const engine_frame *restrict fr, double dt, double alpha_t,
                     double alpha_r, free_lanes *restrict fl, int held, int32_t i0, int nl)
{
	for (int q = 0; q < nl; q++) {
		int32_t i = i0 + q;
		double F[3], T[3], v[3], w[3], x[3], xr[3];
		for (int c = 0; c < 3; c++) {
			F[c] = fl->F[c][q];
			T[c] = fl->T[c][q];
			v[c] = V[3 * i + c];
			w[c] = W[3 * i + c];
			x[c] = X[3 * i + c];
			xr[c] = XR[3 * (i - xr0) + c];
		}
		double mass = M[i], ri = R[i];
		double im = 1 / mass, ii = 1 / (0.4 * mass * ri * ri);
		double fa = sqrt(dot3(F, F)), va = sqrt(dot3(v, v));
		double cfv = -alpha_t * fa / va, cf = law_sel(va > 0, cfv, 0);
		double ta = sqrt(dot3(T, T)), wa = sqrt(dot3(w, w));
		double ctv = -alpha_r * ta / wa, ct = law_sel(wa > 0, ctv, 0);
		double fd[3], td[3], vn[3], wn[3];
		for (int c = 0; c < 3; c++) {
			fd[c] = cf * v[c];
			td[c] = ct * w[c];
		}
		for (int c = 0; c < 3; c++) {
			vn[c] = v[c] + dt * im * (F[c] + fd[c]);
			wn[c] = w[c] + dt * ii * (T[c] + td[c]);
		}
		fl->damped[q] =
		    0.5 * dt * (dot3(fd, v) + dot3(fd, vn) + dot3(td, w) + dot3(td, wn));
		if (held) {
			double er[3];
			radial_unit(fr, x, er);
			double vr = dot3(vn, er);
			int radial = fl->radial[q];
			for (int c = 0; c < 3; c++)
				vn[c] = law_sel(radial, vn[c] - vr * er[c], vn[c]);
		}
		double inertia = 0.4 * mass * ri * ri;
		fl->ke[q] = 0.5 * (mass * dot3(v, vn) + inertia * dot3(w, wn));
		double vv = dot3(vn, vn);
		fl->vv[q] = vv;
		fl->ke_new[q] = 0.5 * (mass * vv + inertia * dot3(wn, wn));
		double ext[3] = {fl->ext[0][q], fl->ext[1][q], fl->ext[2][q]};
		fl->work[q] =
		    0.5 * dt *
		    (ext[0] * (v[0] + vn[0]) + ext[1] * (v[1] + vn[1]) + ext[2] * (v[2] + vn[2]));
		double d2 = 0;
		for (int c = 0; c < 3; c++) {
			x[c] += dt * vn[c];
			double dx = x[c] - xr[c];
			d2 += dx * dx;
		}
		fl->d2[q] = d2;
		fl->finite[q] = x[0] + x[1] + x[2] + wn[0] + wn[1] + wn[2];
		for (int c = 0; c < 3; c++) {
			fl->v[c][q] = vn[c];
			fl->w[c][q] = wn[c];
			fl->x[c][q] = x[c];
		}
	}
}

/* integrate_free_lanes as two loops, held a constant in each: lanes with
 * no particle held radially pay nothing for the constraint. */
static inline __attribute__((always_inline)) void
integrate_free_either(const double *restrict X, const double *restrict V, const double *restrict W,
                      const double *restrict R, const double *restrict M, const double *restrict XR,
                      int32_t xr0, const engine_frame *restrict fr, double dt, double alpha_t,
                      double alpha_r, free_lanes *restrict fl, int held, int32_t i0, int nl)
{
	if (held)
		integrate_free_lanes(X, V, W, R, M, XR, xr0, fr, dt, alpha_t, alpha_r, fl, 1, i0,
		                     nl);
	else
		integrate_free_lanes(X, V, W, R, M, XR, xr0, fr, dt, alpha_t, alpha_r, fl, 0, i0,
		                     nl);
}
DEM_VERSIONS(void, , integrate_free,
             (const double *restrict X, const double *restrict V, const double *restrict W,
              const double *restrict R, const double *restrict M, const double *restrict XR,
              int32_t xr0, const engine_frame *restrict fr, double dt, double alpha_t,
              double alpha_r, free_lanes *restrict fl, int held, int32_t i0, int nl),
             (X, V, W, R, M, XR, xr0, fr, dt, alpha_t, alpha_r, fl, held, i0, nl),
             integrate_free_either)

/* Lane q of fl, particle i, added to the sums s (as integrate_one adds). */
static inline void add_lane(particle_sums *s, const free_lanes *fl, int q, size_t i)
{
	if (fl->confined[q])
		s->lateral_force += fl->lateral[q];
	s->e_damped -= fl->damped[q];
	s->ke += fl->ke[q];
	s->ke_new += fl->ke_new[q];
	s->v2max = fl->vv[q] > s->v2max ? fl->vv[q] : s->v2max;
	s->e_work += fl->work[q];
	s->disp2 = fl->d2[q] > s->disp2 ? fl->d2[q] : s->disp2;
	if (!(isfinite(fl->finite[q])) && s->bad > (double)i)
		s->bad = (double)i;
}

/* Lane q of fl, particle i's new state, into the particles' arrays. */
static inline void store_lane(particles *P, size_t i, const free_lanes *fl, int q)
{
	for (int c = 0; c < 3; c++) {
		P->v[3 * i + c] = fl->v[c][q];
		P->w[3 * i + c] = fl->w[c][q];
		P->x[3 * i + c] = fl->x[c][q];
	}
}

/* The lanes 0..nl) of the values a of particles i0, i0 + 1, ... into
 * their array A: four particles' twelve values at a time, the lanes
 * shuffled into three rows of A (values only moved). */
static inline void store_run(double *restrict A, const double a[3][LANES], size_t i0, int nl)
{
	double *to = A + 3 * i0;
	int q = 0;
	for (; q + 4 <= nl; q += 4, to += 12) {
		vec4 c0 = *(const vec4 *)&a[0][q], c1 = *(const vec4 *)&a[1][q],
		     c2 = *(const vec4 *)&a[2][q];
		vec4 t = __builtin_shufflevector(c0, c1, 0, 4, 1, 5),
		     u = __builtin_shufflevector(c1, c2, 1, 5, 2, 6),
		     w = __builtin_shufflevector(c0, c1, 3, 7, 3, 7);
		*(vec4 *)to = __builtin_shufflevector(t, c2, 0, 1, 4, 2);
		*(vec4 *)(to + 4) = __builtin_shufflevector(u, c0, 0, 1, 6, 2);
		*(vec4 *)(to + 8) = __builtin_shufflevector(c2, w, 2, 4, 5, 3);
	}
	for (; q < nl; q++, to += 3)
		for (int c = 0; c < 3; c++)
			to[c] = a[c][q];
}

/* The bonds' sums acc of particles 0..nl) of a block (force, then torque
 * per unit radius: six values each) into the lanes F and T of fl: four
 * particles at a time, as two transposes of four rows (values only
 * moved). */
static inline void lanes_from_sums(free_lanes *restrict fl, const double *restrict acc, int nl)
{
	int q = 0;
	for (; q + 4 <= nl; q += 4) {
		vec4 row[4], col[4];
		for (int l = 0; l < 4; l++)
			row[l] = *(const vec4 *)(acc + 6 * (q + l)); /* F0 F1 F2 T0 */
		vec4_transpose(row, col);
		for (int c = 0; c < 3; c++)
			*(vec4 *)&fl->F[c][q] = col[c];
		*(vec4 *)&fl->T[0][q] = col[3];
		for (int l = 0; l < 4; l++)
			row[l] = *(const vec4 *)(acc + 6 * (q + l) + 2); /* F2 T0 T1 T2 */
		vec4_transpose(row, col);
		*(vec4 *)&fl->T[1][q] = col[2];
		*(vec4 *)&fl->T[2][q] = col[3];
	}
	for (; q < nl; q++)
		for (int c = 0; c < 3; c++) {
			fl->F[c][q] = acc[6 * q + c];
			fl->T[c][q] = acc[6 * q + 3 + c];
		}
}

/* The nl particles from i0 on (at most LANES) moved and added to the sums
 * s: the free particles all together (integrate_free), the others one by
 * one; every particle's terms added to the sums in particle order. */
static inline __attribute__((always_inline)) void integrate_lanes(engine *e, size_t i0, int nl,
                                                                  int measure, particle_sums *s)
{
	particles *P = &e->p;
	free_lanes fl;
	int nf = 0;
	/* Which particles move freely under their forces alone and, unless
	 * the step measures (whose stress sums they add one by one), the
	 * confining pressure or the radial constraint (move_free, then
	 * hold_radially where radial, then advance, with that pressure as
	 * their external force where confined): no end layer acts on them
	 * (loose), nor a platen, unless every particle of these lanes is loose
	 * (a platen's sums, platen_force's, are then added in particle order
	 * as integrate_one adds them: no particle's integrate_one adds its own
	 * after them). Without branches, so that the compiler vectorises it;
	 * the lanes that do not move freely are computed by integrate_free
	 * too, and not used. */
	const uint8_t *flag = P->flag + i0;
	const int32_t *surf = P->surf + i0, *slot0 = P->pslot[0] + i0, *slot1 = P->pslot[1] + i0,
	              *off = e->pairs.contacts.off + i0;
	int pressure = e->bc.loads.lateral == LATERAL_PRESSURE, unmeasured = !measure, nc = 0,
	    nloose = 0, nradial = 0;
	uint8_t added[LANES]; /* free, and contacts, a platen or the pressure act on it */
	uint8_t layer = e->bc.loads.layers ? PF_LAYER_BOTTOM | PF_LAYER_TOP : 0;
	for (int q = 0; q < nl; q++) {
		int confined = pressure & (surf[q] >= 0), radial = (flag[q] & PF_CONSTRAINED) != 0;
		int loose = (((confined | radial) ^ 1) | unmeasured) & ((flag[q] & layer) == 0);
		fl.free[q] = (uint8_t)loose;
		fl.confined[q] = (uint8_t)confined;
		fl.radial[q] = (uint8_t)radial;
		nloose += loose;
		nradial += radial;
		/* no confining force but where the pressure acts (set below,
		 * with fl.lateral, which only the confined lanes read) */
		for (int c = 0; c < 3; c++)
			fl.ext[c][q] = 0;
	}
	int platens = nloose == nl; /* the lanes at a platen free too */
	for (int q = 0; q < nl; q++) {
		int platen = (slot0[q] >= 0) | (slot1[q] >= 0);
		int free = fl.free[q] & (platens | (platen ^ 1));
		int more = free & ((off[q + 1] != off[q]) | fl.confined[q] | platen);
		fl.free[q] = (uint8_t)free;
		added[q] = (uint8_t)more;
		nf += free;
		nc += more;
	}
	/* Their forces: the bonds' sums, then, where they act, the contacts,
	 * the platens and the pressure (in that order, as integrate_one adds
	 * them). */
	lanes_from_sums(&fl, engine_acc(e, i0), nl);
	/* Those particles listed, without a branch that the CPU would guess
	 * for each particle. */
	int32_t list[LANES];
	for (int q = 0, a = 0; nc && q < nl; q++) {
		list[a] = q;
		a += added[q];
	}
	for (int a = 0; a < nc; a++) {
		int q = list[a];
		size_t i = i0 + (size_t)q;
		double F[3] = {fl.F[0][q], fl.F[1][q], fl.F[2][q]},
		       T[3] = {fl.T[0][q], fl.T[1][q], fl.T[2][q]}, ext[3] = {0, 0, 0};
		gather(&e->pairs.contacts, (int32_t)i, P->r[i], F, T);
		for (int k = 0; k < 2; k++)
			if (P->pslot[k][i] >= 0)
				platen_force(e, k, (int32_t)i, &e->bc.pl.pc[k][P->pslot[k][i]], F,
				             T, s, measure);
		if (fl.confined[q]) { /* as integrate_one: its sum added below */
			double er[3];
			particle_sums lateral = {0};
			radial_unit(&e->frame, P->x + 3 * i, er);
			confine(e, (int32_t)i, P->surf[i], er, F, ext, &lateral, 0);
			fl.lateral[q] = lateral.lateral_force;
		}
		for (int c = 0; c < 3; c++) {
			fl.F[c][q] = F[c];
			fl.T[c][q] = T[c];
			fl.ext[c][q] = ext[c];
		}
	}
	integrate_free(P->x, P->v, P->w, P->r, P->m, P->x_ref, (int32_t)P->own0, &e->frame,
	               e->clock.dt, e->cs->alpha_t, e->cs->alpha_r, &fl, nradial && unmeasured,
	               (int32_t)i0, nl);
	if (nf == nl) {
		/* The sums in a local, which no store can alias (so they stay
		 * in registers), and the state in loops of their own. */
		particle_sums sums = *s;
		for (int q = 0; q < nl; q++)
			add_lane(&sums, &fl, q, i0 + (size_t)q);
		*s = sums;
		store_run(P->v, fl.v, i0, nl);
		store_run(P->w, fl.w, i0, nl);
		store_run(P->x, fl.x, i0, nl);
		return;
	}
	for (int q = 0; q < nl; q++) {
		size_t i = i0 + (size_t)q;
		if (!fl.free[q]) {
			integrate_one(e, (int32_t)i, measure, s);
			continue;
		}
		add_lane(s, &fl, q, i);
		store_lane(P, i, &fl, q);
	}
}

DEM_VECTOR_CLONES static void integrate_block(engine *e, size_t k, int measure)
{
	size_t n = e->p.n;
	particle_sums *s = &e->scratch.pblock[k];
	memset(s, 0, sizeof *s);
	s->bad = (double)n;
	size_t hi = block_end(k, n);
	if (e->cs->damping_form != DAMPING_VECTOR || e->one_by_one) {
		for (size_t i = k * BLOCK; i < hi; i++)
			integrate_one(e, (int32_t)i, measure, s);
		return;
	}
	for (size_t i0 = k * BLOCK; i0 < hi; i0 += LANES)
		integrate_lanes(e, i0, (int)(hi - i0 < LANES ? hi - i0 : LANES), measure, s);
}

/* A thread's particle blocks integrated as soon as their bonds are done
 * (bonds_share's block_done), while the block's positions, velocities and
 * sums are still in the core's caches; on the timing thread, the seconds
 * it took, counted as integration. */
typedef struct {
	int measure, timed;
	double seconds;
} integrate_ctx;

static void integrate_after_bonds(engine *e, size_t blk, void *ctx)
{
	integrate_ctx *c = ctx;
	double t0 = c->timed ? timer_now() : 0;
	integrate_block(e, blk, c->measure);
	if (c->timed)
		c->seconds += timer_now() - t0;
}

/* The sums are arrays of doubles; of a particle_sums, those before disp2
 * (step_part). */
enum { PAIR = STEP_PAIR_SUMS, STRIDE = sizeof(particle_sums) / sizeof(double) };
_Static_assert(sizeof(pair_sums) == PAIR * sizeof(double), "pair_sums: doubles only");
_Static_assert(sizeof(particle_sums) == STRIDE * sizeof(double), "particle_sums: doubles only");

/* Thread tid's part of the step's sums (step_part): the blocks of the
 * shares it took, s0 + tid, s0 + tid + nth, ... (their bonds' and
 * particles' blocks its own, the contacts' complete since the barrier). */
static void step_part_sums(engine *e, int tid, int nth)
{
	const bond_split *S = &e->pairs.split;
	step_part *part = &e->scratch.parts[tid];
	for (int f = 0; f < STEP_SUMS; f++)
		xsum_clear(&part->sum[f]);
	double *top = part->top; /* disp2, v2max, -bad */
	top[0] = top[1] = 0;
	top[2] = -(double)e->p.n;
	for (int k = e->ranks.s0 + tid; k < e->ranks.s1; k += nth) {
		size_t b0 = S->pfirst[k] / BLOCK,
		       nb = S->pfirst[k + 1] > S->pfirst[k] ? nblocks(S->pfirst[k + 1]) - b0 : 0;
		const particle_sums *blk = e->scratch.pblock + b0;
		reduce_part_add(part->sum, (const double *)(e->scratch.bblock + b0), nb, PAIR,
		                PAIR);
		reduce_part_add(part->sum + PAIR, (const double *)(e->scratch.cblock + b0), nb,
		                PAIR, PAIR);
		reduce_part_add(part->sum + 2 * PAIR, (const double *)blk, nb, STRIDE,
		                STEP_PARTICLE_SUMS);
		for (size_t q = 0; q < nb; q++) {
			top[0] = blk[q].disp2 > top[0] ? blk[q].disp2 : top[0];
			top[1] = blk[q].v2max > top[1] ? blk[q].v2max : top[1];
			top[2] = -blk[q].bad > top[2] ? -blk[q].bad : top[2];
		}
	}
}

/* The step's sums over this rank's blocks of bonds, contacts and particles
 * (the threads' parts), the largest displacement and speed, the first bad
 * particle, the count of new failures and the flags of e->sums.agree, all
 * over the ranks in one reduction (reduce.h): the sums exact, the rest the
 * largest of the ranks'. Returns whether some rank found failures in this
 * step. */
static int step_sums(engine *e, size_t ncracks)
{
	particle_sums *t = &e->sums.particles;
	const step_part *parts = e->scratch.parts;
	int np = e->scratch.nparts;
	double top[3];
	for (int c = 0; c < 3; c++) {
		top[c] = parts[0].top[c];
		for (int q = 1; q < np; q++)
			top[c] = parts[q].top[c] > top[c] ? parts[q].top[c] : top[c];
	}
	static reduction r; /* some 35 kB; steps run one at a time */
	reduce_clear(&r);
	int kb = reduce_add_parts(&r, parts->sum, np, sizeof *parts, PAIR);
	int kc = reduce_add_parts(&r, parts->sum + PAIR, np, sizeof *parts, PAIR);
	int kp = reduce_add_parts(&r, parts->sum + 2 * PAIR, np, sizeof *parts, STEP_PARTICLE_SUMS);
	int km = reduce_add_max(&r, top[0]);
	reduce_add_max(&r, top[1]);
	reduce_add_max(&r, top[2]);
	int kf = reduce_add_max(&r, (double)(e->out.cracks.n - ncracks));
	int ka = r.nmax;
	for (int k = 0; k < ENGINE_AGREE; k++)
		reduce_add_max(&r, e->sums.agree[k]);
	reduce_finish(&r);
	reduce_sums(&r, kb, PAIR, (double *)&e->sums.bonds);
	reduce_sums(&r, kc, PAIR, (double *)&e->sums.contacts);
	reduce_sums(&r, kp, STEP_PARTICLE_SUMS, (double *)t);
	t->disp2 = r.max[km];
	t->v2max = r.max[km + 1];
	t->bad = -r.max[km + 2];
	for (int k = 0; k < ENGINE_AGREE; k++)
		e->sums.agree[k] = r.max[ka + k];
	return r.max[kf] > 0;
}

/* Whether the lateral surface is updated at the start of this step. */
static int surface_due(const engine *e)
{
	return e->clock.step - e->bc.surf.updated >= e->cs->surface_every && e->bc.surf.ntheta;
}

void engine_step(engine *e, int measure)
{
	phase_enter(&e->tm, TM_NEIGHBOUR);
	/* The search reads each rank's own particles and its ghosts; the
	 * surface and the gauge each rank's own. */
	if (e->pairs.rebuild)
		contacts_rebuild(e);
	if (surface_due(e))
		surface_update(e);
	bonds_balance(e);
	boundary_prepare(e);
	if (measure) {
		e->sums.meas = (measurement){.t = e->clock.t,
		                             .step = e->clock.step,
		                             .stage = e->prog.stage,
		                             .strain_radial = gauge_strain(e),
		                             .lateral_area = e->bc.surf.lateral_area,
		                             .volume = e->bc.surf.volume};
	}
	phase_switch(&e->tm, TM_NEIGHBOUR, TM_BONDS);
	/* Each thread takes this rank's shares s0 + tid, s0 + tid + team, ...
	 * (bonds.h, ranks.h): the crossing bonds, then the contacts, then, once
	 * the crossing forces have reached the ranks of their j, the other
	 * bonds and the particles, which read and move only the share's own
	 * particles. */
	size_t ncracks = e->out.cracks.n;
	double t0 = omp_get_wtime();
#pragma omp parallel num_threads(e->team)
	{
		int tid = omp_get_thread_num(), nth = omp_get_num_threads(), s0 = e->ranks.s0,
		    s1 = e->ranks.s1;
		for (int k = s0 + tid; k < s1; k += nth)
			bonds_cross(e, k, measure);
#pragma omp master
		phase_switch(&e->tm, TM_BONDS, TM_CONTACTS);
		contacts_forces(e, measure);
#pragma omp master
		{
			ranks_exchange_forces(e);
			phase_switch(&e->tm, TM_CONTACTS, TM_BONDS);
		}
#pragma omp barrier
		/* Each share's time from here (bonds_balance): its bonds and,
		 * block by block behind them, its particles. */
		double *busy = e->pairs.balance.busy;
		integrate_ctx ic = {measure, tid == 0, 0};
		for (int k = s0 + tid; k < s1; k += nth) {
			double t0 = omp_get_wtime();
			bonds_share(e, k, measure, integrate_after_bonds, &ic);
			busy[k] += omp_get_wtime() - t0;
		}
#pragma omp master
		{
			phase_switch(&e->tm, TM_BONDS, TM_INTEGRATE);
			phase_move(&e->tm, TM_BONDS, TM_INTEGRATE, ic.seconds);
		}
		step_part_sums(e, tid, nth);
#pragma omp master
		e->scratch.nparts = nth;
	}
	bonds_tune_prefetch(e, omp_get_wtime() - t0);
	bonds_collect_cracks(e);
	int failures = step_sums(e, ncracks);
	phase_switch(&e->tm, TM_INTEGRATE, TM_NEIGHBOUR);

	const particle_sums *ps = &e->sums.particles;
	e->energy.kinetic = ps->ke;
	e->energy.damped += ps->e_damped + e->sums.bonds.e_viscous + e->sums.contacts.e_viscous +
	                    ps->platen_viscous;
	e->energy.friction +=
	    e->sums.bonds.e_friction + e->sums.contacts.e_friction + ps->platen_friction;
	e->energy.fracture += e->sums.bonds.e_damage;
	e->energy.work += ps->e_work;
	for (int k = 0; k < 2; k++) {
		e->bc.pl.load[k] = e->bc.loads.layers ? ps->layer[k] : ps->load[k];
		e->bc.pl.ksum[k] = ps->ksum[k];
	}
	if (measure) {
		measurement *m = &e->sums.meas;
		m->strain = engine_strain(e);
		for (int k = 0; k < 2; k++)
			m->stress[k] = engine_stress_of(e, k);
		int held = e->bc.loads.lateral == LATERAL_CONSTRAINT;
		m->lateral_force = held ? ps->constraint_force : ps->lateral_force;
		m->pressure = !held                 ? e->bc.loads.pressure
		              : m->lateral_area > 0 ? ps->constraint_force / m->lateral_area
		                                    : 0;
	}
	if (failures)
		ranks_share_cracks(e, ncracks);
	boundary_finish_step(e);
	e->clock.t += e->clock.dt;
	e->clock.step++;
	double drift = sqrt(ps->disp2);
	if (2 * drift >= e->pairs.skin || drift + platens_drift(e) >= e->pairs.skin)
		e->pairs.rebuild = 1;
	/* The next step reads the halo (a neighbour rebuild, its ghosts too:
	 * ranks.h). */
	phase_switch(&e->tm, TM_NEIGHBOUR, TM_INTEGRATE);
	ranks_share_state(e);
	phase_leave(&e->tm, TM_INTEGRATE);
}
