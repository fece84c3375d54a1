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
 * turned into the current one by projecting it on the plane (the tilt of the
 * normal; the length it loses is of second order in the normal's turn per
 * step, below 1e-10 even for a pair spinning at 1e-5 rad per step), then
 * rotated about n by the pair's mean spin ½ (ω_i + ω_j)·n Δt (the twist), so
 * laws never see rigid rotations. */
#ifndef DEM_KINEMATICS_H
#define DEM_KINEMATICS_H

#include <math.h>
#include <stdint.h>

#include "solve/blocks.h"
#include "solve/law.h"

/* Geometry of a batch of pairs, kept for turning the law's output into
 * forces: unit normals, distances and d / (r_i + r_j). */
typedef struct {
	double n[3][BATCH];
	double d[BATCH];
	double s[BATCH];
} batch_geom;

_Static_assert((int)BATCH == (int)LAW_LANES, "a batch of pairs is a batch of the laws' lanes");

/* Kinematics of the nq pairs rec[idx[0..nq)] (rec[0..nq) when idx is NULL)
 * into the pair and kinematics lanes of B (B->n = nq), with their
 * tangential histories rotated into B->t.
 * Staged: the records are read into arrays, one loop does all the
 * arithmetic on them (so the square roots and divisions of independent
 * pairs overlap, and the compiler can use the vector units). */
static inline void batch_kinematics(const double *restrict x, const double *restrict v,
                                    const double *restrict w, const double *restrict r,
                                    const double *restrict m, const bond *restrict rec,
                                    const int32_t *restrict idx, int nq, double dt,
                                    law_batch *restrict B, batch_geom *restrict g)
{
	double dx[3][BATCH], dv[3][BATCH], wi[3][BATCH], wj[3][BATCH];
	B->n = nq;
	for (int q = 0; q < nq; q++) {
		const bond *b = &rec[idx ? idx[q] : q];
		int32_t i = b->i, j = b->j;
		for (int c = 0; c < 3; c++) {
			dx[c][q] = x[3 * j + c] - x[3 * i + c];
			dv[c][q] = v[3 * j + c] - v[3 * i + c];
			wi[c][q] = w[3 * i + c];
			wj[c][q] = w[3 * j + c];
			B->t[c][q] = b->t[c];
		}
		B->ri[q] = r[i];
		B->rj[q] = r[j];
		B->mi[q] = m[i];
		B->mj[q] = m[j];
		B->d0[q] = b->d0;
	}
	for (int q = 0; q < nq; q++) {
		double d = sqrt(dx[0][q] * dx[0][q] + dx[1][q] * dx[1][q] + dx[2][q] * dx[2][q]);
		double inv = 1 / d, s = d / (B->ri[q] + B->rj[q]);
		double n0 = dx[0][q] * inv, n1 = dx[1][q] * inv, n2 = dx[2][q] * inv;
		double ai = s * B->ri[q], aj = s * B->rj[q];
		double ws0 = aj * wj[0][q] + ai * wi[0][q], ws1 = aj * wj[1][q] + ai * wi[1][q],
		       ws2 = aj * wj[2][q] + ai * wi[2][q];
		double vc0 = dv[0][q] - (ws1 * n2 - ws2 * n1),
		       vc1 = dv[1][q] - (ws2 * n0 - ws0 * n2),
		       vc2 = dv[2][q] - (ws0 * n1 - ws1 * n0);
		double vcn = vc0 * n0 + vc1 * n1 + vc2 * n2;
		B->un[q] = d - B->d0[q];
		B->vn[q] = dv[0][q] * n0 + dv[1][q] * n1 + dv[2][q] * n2;
		B->dus[0][q] = (vc0 - vcn * n0) * dt;
		B->dus[1][q] = (vc1 - vcn * n1) * dt;
		B->dus[2][q] = (vc2 - vcn * n2) * dt;
		double spin = 0.5 * dt *
		              ((wi[0][q] + wj[0][q]) * n0 + (wi[1][q] + wj[1][q]) * n1 +
		               (wi[2][q] + wj[2][q]) * n2);
		double t0 = B->t[0][q], t1 = B->t[1][q], t2 = B->t[2][q];
		double tn = t0 * n0 + t1 * n1 + t2 * n2;
		double u0 = t0 - tn * n0, u1 = t1 - tn * n1, u2 = t2 - tn * n2;
		B->t[0][q] = u0 + spin * (n1 * u2 - n2 * u1);
		B->t[1][q] = u1 + spin * (n2 * u0 - n0 * u2);
		B->t[2][q] = u2 + spin * (n0 * u1 - n1 * u0);
		g->n[0][q] = n0;
		g->n[1][q] = n1;
		g->n[2][q] = n2;
		g->d[q] = d;
		g->s[q] = s;
	}
}

/* The law's history of the bonds rec[idx[0..B->n)] into B, and back. */
static inline void batch_history_load(const bond *restrict rec, const int32_t *restrict idx,
                                      law_batch *restrict B)
{
	for (int q = 0; q < B->n; q++) {
		const bond *b = &rec[idx[q]];
		for (int c = 0; c < LAW_NHIST; c++)
			B->h[c][q] = b->h[c];
		B->state[q] = b->state;
	}
}
static inline void batch_history_store(bond *restrict rec, const int32_t *restrict idx,
                                       const law_batch *restrict B)
{
	for (int q = 0; q < B->n; q++) {
		bond *b = &rec[idx[q]];
		for (int c = 0; c < 3; c++)
			b->t[c] = B->t[c][q];
		for (int c = 0; c < LAW_NHIST; c++)
			b->h[c] = B->h[c][q];
		b->state = (uint8_t)B->state[q];
	}
}

/* The force on i and the torque per unit radius of lane q of a batch from
 * the law's output: the torque on i is (a_i n) × F_s = r_i (d / (r_i + r_j))
 * n × F_s, on j r_j times the same vector (Eq. 4). */
static inline void batch_force(const law_batch *B, const batch_geom *g, int q, double f[6])
{
	double n[3] = {g->n[0][q], g->n[1][q], g->n[2][q]}, s = g->s[q];
	double fs[3] = {B->fs[0][q], B->fs[1][q], B->fs[2][q]};
	for (int c = 0; c < 3; c++)
		f[c] = B->fn[q] * n[c] + fs[c];
	f[3] = s * (n[1] * fs[2] - n[2] * fs[1]);
	f[4] = s * (n[2] * fs[0] - n[0] * fs[2]);
	f[5] = s * (n[0] * fs[1] - n[1] * fs[0]);
}

#endif
