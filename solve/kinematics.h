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

#include "lib/states.h"
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

/* The relative motion of one pair: its normal n, distance d, s = d / (r_i +
 * r_j), u_n, u̇_n, Δu_s and its tangential history t turned into the current
 * contact plane. */
typedef struct {
	double n[3], d, s;
	double un, vn, dus[3], t[3];
} pair_motion;

/* The motion of a pair from dx = x_j - x_i, dv = v_j - v_i, the spins, the
 * radii, d0 and the last step's tangential history t: the one expression of
 * it, so the batches and the fused loops of the laws (law.force_pairs)
 * agree to the bit. */
static inline pair_motion pair_motion_of(const double dx[3], const double dv[3], const double wi[3],
                                         const double wj[3], double ri, double rj, double d0,
                                         const double t[3], double dt)
{
	pair_motion k;
	double d = sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
	double inv = 1 / d, s = d / (ri + rj);
	double n0 = dx[0] * inv, n1 = dx[1] * inv, n2 = dx[2] * inv;
	double ai = s * ri, aj = s * rj;
	double ws0 = aj * wj[0] + ai * wi[0], ws1 = aj * wj[1] + ai * wi[1],
	       ws2 = aj * wj[2] + ai * wi[2];
	double vc0 = dv[0] - (ws1 * n2 - ws2 * n1), vc1 = dv[1] - (ws2 * n0 - ws0 * n2),
	       vc2 = dv[2] - (ws0 * n1 - ws1 * n0);
	double vcn = vc0 * n0 + vc1 * n1 + vc2 * n2;
	k.un = d - d0;
	k.vn = dv[0] * n0 + dv[1] * n1 + dv[2] * n2;
	k.dus[0] = (vc0 - vcn * n0) * dt;
	k.dus[1] = (vc1 - vcn * n1) * dt;
	k.dus[2] = (vc2 - vcn * n2) * dt;
	double spin =
	    0.5 * dt * ((wi[0] + wj[0]) * n0 + (wi[1] + wj[1]) * n1 + (wi[2] + wj[2]) * n2);
	double tn = t[0] * n0 + t[1] * n1 + t[2] * n2;
	double u0 = t[0] - tn * n0, u1 = t[1] - tn * n1, u2 = t[2] - tn * n2;
	k.t[0] = u0 + spin * (n1 * u2 - n2 * u1);
	k.t[1] = u1 + spin * (n2 * u0 - n0 * u2);
	k.t[2] = u2 + spin * (n0 * u1 - n1 * u0);
	k.n[0] = n0;
	k.n[1] = n1;
	k.n[2] = n2;
	k.d = d;
	k.s = s;
	return k;
}

/* A batch of bonds with the particles they join, as law_pairs_load reads
 * them for law.force_pairs: the bonds rec[idx[0..n)] (rec[0..n) when idx
 * is NULL), with their states and constants at the same indices of state
 * and k (NULL: BOND_BROKEN_TENSION, as a contact's, and 0), and the
 * particles' arrays (engine.h). Each of x, v and w has one item (three
 * doubles) more than the particles it holds, as the engine's windows do
 * (window.c): law_pairs_load reads a particle's three values as four, and
 * so the record after the last (pairlist_records). */
struct law_pairs {
	const double *x, *v, *w, *r;
	const pair_rec *rec;
	const uint8_t *state;
	const double *k;
	const int32_t *idx;
	int n;
};

/* A batch's inputs lane by lane (law_pairs_load), as force_pairs' loops
 * read them: dx = x_j - x_i, dv = v_j - v_i, the spins, the radii, and the
 * bonds' fields (bond in law.h). */
struct law_lanes {
	double dx[3][LAW_LANES], dv[3][LAW_LANES], wi[3][LAW_LANES], wj[3][LAW_LANES];
	double ri[LAW_LANES], rj[LAW_LANES];
	double d0[LAW_LANES], k[LAW_LANES], t[3][LAW_LANES], h[LAW_NHIST][LAW_LANES];
	int32_t state[LAW_LANES];
};

/* The inputs of the batch in into L. With AVX2 each group of four lanes
 * reads a particle's three values and a record's eight as vectors and
 * transposes them, instead of one gather instruction for each value of
 * each lane (about 30 a bond), which the compiler would emit for a loop
 * over the lanes. The values are only moved, and dx, dv subtracted as the
 * scalar loop does, so they are the same to the bit on every CPU. */
void law_pairs_load(const law_pairs *restrict in, law_lanes *restrict L);
/* Its lanes q0 <= q < in->n one value at a time: law_pairs_load without
 * AVX2, and for the lanes after the last group of four. */
void law_pairs_load_lanes(const law_pairs *restrict in, law_lanes *restrict L, int q0);

/* Whether any of the n lanes of L is a broken bond (a loop the compiler
 * vectorises, for the laws to choose the version of their force_pairs
 * loop). */
static inline int law_lanes_broken(const law_lanes *restrict L, int n)
{
	int broken = 0;
	for (int q = 0; q < n; q++)
		broken |= L->state[q] >= BOND_BROKEN_TENSION;
	return broken;
}

/* The motion of the pair of lane q (pair_motion_of). */
static inline pair_motion law_lanes_motion(const law_lanes *restrict L, int q, double dt)
{
	double dx[3], dv[3], wi[3], wj[3], t[3];
	for (int c = 0; c < 3; c++) {
		dx[c] = L->dx[c][q];
		dv[c] = L->dv[c][q];
		wi[c] = L->wi[c][q];
		wj[c] = L->wj[c][q];
		t[c] = L->t[c][q];
	}
	return pair_motion_of(dx, dv, wi, wj, L->ri[q], L->rj[q], L->d0[q], t, dt);
}

/* Kinematics of the nq pairs rec[idx[0..nq)] (rec[0..nq) when idx is NULL)
 * into the pair and kinematics lanes of B (B->n = nq), with their
 * tangential histories rotated into B->t, and their histories, constants
 * and states (h, and k and state from the arrays at the same indices, as
 * law_pairs has them).
 * Staged: the records are read into arrays (law_pairs_load), one loop does
 * all the arithmetic on them (so the square roots and divisions of
 * independent pairs overlap, and the compiler can use the vector units).
 * Always inlined: a copy out of line would be compiled for any x86-64, not
 * for the vector units of its callers' versions (clones.h). */
static inline __attribute__((always_inline)) void
batch_kinematics(const double *restrict x, const double *restrict v, const double *restrict w,
                 const double *restrict r, const double *restrict m, const pair_rec *restrict rec,
                 const uint8_t *restrict state, const double *restrict k,
                 const int32_t *restrict idx, int nq, double dt, law_batch *restrict B,
                 batch_geom *restrict g)
{
	law_pairs in = {.x = x,
	                .v = v,
	                .w = w,
	                .r = r,
	                .rec = rec,
	                .state = state,
	                .k = k,
	                .idx = idx,
	                .n = nq};
	law_lanes L;
	law_pairs_load(&in, &L);
	B->n = nq;
	for (int q = 0; q < nq; q++) {
		const pair_rec *b = &rec[idx ? idx[q] : q];
		B->mi[q] = m[b->i];
		B->mj[q] = m[b->j];
	}
	for (int q = 0; q < nq; q++) {
		pair_motion k = law_lanes_motion(&L, q, dt);
		B->ri[q] = L.ri[q];
		B->rj[q] = L.rj[q];
		B->d0[q] = L.d0[q];
		B->un[q] = k.un;
		B->vn[q] = k.vn;
		for (int c = 0; c < 3; c++) {
			B->dus[c][q] = k.dus[c];
			B->t[c][q] = k.t[c];
			g->n[c][q] = k.n[c];
		}
		g->d[q] = k.d;
		g->s[q] = k.s;
		for (int c = 0; c < LAW_NHIST; c++)
			B->h[c][q] = L.h[c][q];
		B->k[q] = L.k[q];
		B->state[q] = L.state[q];
	}
}

/* The histories of B back into the records rec[idx[0..B->n)] and their
 * states. */
static inline void batch_history_store(pair_rec *restrict rec, uint8_t *restrict state,
                                       const int32_t *restrict idx, const law_batch *restrict B)
{
	for (int q = 0; q < B->n; q++) {
		pair_rec *b = &rec[idx[q]];
		for (int c = 0; c < 3; c++)
			b->t[c] = B->t[c][q];
		for (int c = 0; c < LAW_NHIST; c++)
			b->h[c] = B->h[c][q];
		state[idx[q]] = (uint8_t)B->state[q];
	}
}

/* The force on i and the torque per unit radius of a pair of normal n and
 * s = d / (r_i + r_j) from its normal force fn and shear force fs: the
 * torque on i is (a_i n) × F_s = r_i (d / (r_i + r_j)) n × F_s, on j r_j
 * times the same vector (Eq. 4). */
static inline void pair_force(const double n[3], double s, double fn, const double fs[3],
                              double f[6])
{
	for (int c = 0; c < 3; c++)
		f[c] = fn * n[c] + fs[c];
	f[3] = s * (n[1] * fs[2] - n[2] * fs[1]);
	f[4] = s * (n[2] * fs[0] - n[0] * fs[2]);
	f[5] = s * (n[0] * fs[1] - n[1] * fs[0]);
}

/* The same for lane q of a batch from the law's output. */
static inline void batch_force(const law_batch *B, const batch_geom *g, int q, double f[6])
{
	double n[3] = {g->n[0][q], g->n[1][q], g->n[2][q]};
	double fs[3] = {B->fs[0][q], B->fs[1][q], B->fs[2][q]};
	pair_force(n, g->s[q], B->fn[q], fs, f);
}

/* What law.force_pairs gives for each lane q that stays on the law's
 * elastic branch, or that its loop also computes (broken bonds),
 * elastic[q] != 0; nothing for the others: the force on i and the torque
 * per unit radius (pair_force), the viscous energy
 * u̇_n f_viscous Δt, and the bond's new history. A law whose lanes may also
 * flow plastically there (no damage, no failure) sets damage, which the
 * caller sets to 0 first, and gives their plastic work in e_damage; one
 * whose lanes may be friction contacts (broken bonds) sets friction (the
 * same) and gives the work of their sliding in e_friction. */
struct law_fused {
	int history;  /* whether h and state may have changed (else only t) */
	int damage;   /* whether e_damage holds the lanes' plastic work (else 0) */
	int friction; /* whether e_friction holds their sliding work (else 0) */
	int32_t elastic[LAW_LANES];
	double f[6][LAW_LANES];
	double e_viscous[LAW_LANES];
	double e_damage[LAW_LANES];   /* J, as law_out.e_damage */
	double e_friction[LAW_LANES]; /* J, as law_out.e_friction */
	double t[3][LAW_LANES], h[LAW_NHIST][LAW_LANES];
	int32_t state[LAW_LANES];
};

/* A law's force_pairs (law.h), with restrict pointers, so the compiler
 * knows the outputs alias none of the inputs and can vectorise its loop:
 * the law's parameters, the batch's lanes, their count, the time step. */
#define LAW_PAIRS_PARAMS \
	const law_params *restrict lp, const law_lanes *restrict L, int n, double dt

/* A law's force_pairs NAME from its loop BODY, an always-inline function
 * with NAME's parameters, in the versions of DEM_VERSIONS (clones.h). */
#define LAW_PAIRS_VERSIONS(NAME, BODY)                                             \
	DEM_VERSIONS(int, return, NAME, (LAW_PAIRS_PARAMS, law_fused *restrict o), \
	             (lp, L, n, dt, o), BODY)

/* A force_pairs NAME from BODY, an always-inline function with NAME's
 * parameters and then constants that select a variant of its loop, given
 * here (...): LAW_PAIRS_VERSIONS of BODY with them. */
#define LAW_PAIRS_VARIANT(NAME, BODY, ...)                                                  \
	static inline __attribute__((always_inline)) int NAME##_body(LAW_PAIRS_PARAMS,      \
	                                                             law_fused *restrict o) \
	{                                                                                   \
		return BODY(lp, L, n, dt, o, __VA_ARGS__);                                  \
	}                                                                                   \
	LAW_PAIRS_VERSIONS(NAME, NAME##_body)

/* A force_pairs NAME from BODY, whose last parameter `broken` says whether
 * its loop also computes the lanes of broken bonds: its variants without
 * them (NAME_intact) and with them (NAME_broken), and NAME, which runs the
 * second where the batch has a broken bond (law_lanes_broken). */
#define LAW_PAIRS_BROKEN(NAME, BODY)                                            \
	LAW_PAIRS_VARIANT(NAME##_intact, BODY, 0)                               \
	LAW_PAIRS_VARIANT(NAME##_broken, BODY, 1)                               \
	static int NAME(LAW_PAIRS_PARAMS, law_fused *restrict o)                \
	{                                                                       \
		return law_lanes_broken(L, n) ? NAME##_broken(lp, L, n, dt, o)  \
		                              : NAME##_intact(lp, L, n, dt, o); \
	}

/* Lane q of a law_fused from the law's forces fn (its viscous part fv) and
 * fs on the pair k, and the bond's new history: t, and h and state unless h
 * is NULL (a law whose force_pairs sets o->history to 0: nothing reads
 * them). */
static inline void law_fused_put(law_fused *o, int q, int32_t elastic, const pair_motion *k,
                                 double fn, double fv, const double fs[3], double dt,
                                 const double t[3], const double h[LAW_NHIST], int32_t state)
{
	double f[6];
	pair_force(k->n, k->s, fn, fs, f);
	o->elastic[q] = elastic;
	for (int c = 0; c < 6; c++)
		o->f[c][q] = f[c];
	o->e_viscous[q] = fv * k->vn * dt;
	for (int c = 0; c < 3; c++)
		o->t[c][q] = t[c];
	if (!h)
		return;
	for (int c = 0; c < LAW_NHIST; c++)
		o->h[c][q] = h[c];
	o->state[q] = state;
}

#endif
