/* Pair lists: the bonds and the non-bonded contacts are both a flat array of
 * pair records with one force per pair, computed once per step; the
 * contacts also have a CSR index through which every particle gathers the
 * forces of its contacts in a fixed order (so sums do not depend on the
 * number of threads; the bonds add theirs as they are computed, bonds.h).
 * Also the per-block sums over pairs (blocks.h) and the Love–Weber sum of a
 * pair. */
#ifndef DEM_PAIRLIST_H
#define DEM_PAIRLIST_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "solve/kinematics.h"
#include "solve/law.h"

typedef struct {
	size_t n, cap;
	pair_rec *rec;  /* a contact keeps its K_n, K_s, C_n in h[0..2]; 64-byte
	                   aligned, one record more than cap (pairlist_records) */
	uint8_t *state; /* bonds: [n] their states (law.h); NULL for the contacts */
	double *k;      /* bonds: [n] the law's constant of each (bond.k), or NULL
	                   when the law keeps none (law.keeps_k) */
	double *f;      /* contacts: [n][6] force on i (N) then the torque per unit
	                   radius (N): the torque on i is r_i times it, on j r_j
	                   times it. NULL for the bonds. */
	float *fb;      /* bonds: [n][3] force on i (N) at the state between
	                   steps, for the output only (snapshots, checkpoints), so
	                   single precision: filled when one needs it
	                   (bonds_output_forces); a step adds each bond's force
	                   and torque to its particles and keeps none (bonds.h). */
	int32_t *off;   /* [off0, own1 + 1]: this rank's particles' (contacts
	                   only: bonds add their forces as they are computed,
	                   bonds.h); its memory starts at off0 */
	size_t off0;
	int32_t *ref; /* [2n] pair index * 2 + 1 if the particle is its j */
} pairlist;

/* The law's view of bond b of the bonds l, and back (its state and k into
 * their arrays; k only where the law keeps it). */
static inline bond pairlist_bond(const pairlist *l, size_t b)
{
	return pair_bond(&l->rec[b], l->state[b], l->k ? l->k[b] : 0);
}
static inline void pairlist_put(pairlist *l, size_t b, const bond *bd)
{
	pair_rec *r = &l->rec[b];
	r->i = bd->i;
	r->j = bd->j;
	r->d0 = bd->d0;
	memcpy(r->t, bd->t, sizeof r->t);
	memcpy(r->h, bd->h, sizeof r->h);
	l->state[b] = bd->state;
	if (l->k)
		l->k[b] = bd->k;
}

/* Sums over one block of pairs. */
typedef struct {
	double e_damage, e_friction, e_viscous;
	double e_elastic; /* measuring steps only */
	double love[9];   /* Σ (x_c - x_p) ⊗ f, measuring steps only */
	double count[5];  /* bonds by state / contacts touching */
} pair_sums;

void pairlist_free(pairlist *l);
/* Records for cap pairs, the first n of rec kept (rec may be NULL when n is
 * 0): 64-byte aligned, each in a cache line of its own, and one record
 * more, which law_pairs_load may read past the last one. */
pair_rec *pairlist_records(pair_rec *rec, size_t n, size_t cap);
/* Build the gather index of the l->n pairs, sorted by (i, j), for the
 * particles [lo, hi) (l->off, for every particle, and l->ref allocated by
 * the caller). */
void pairlist_csr(pairlist *l, size_t lo, size_t hi);
/* The number of pairs particle i belongs to (a scan: for messages). */
int pairlist_count(const pairlist *l, size_t i);
/* Love–Weber sums Σ (x_j - x_i) ⊗ F_i of pair q of a batch. */
void love_add(double love[9], const batch_geom *g, int q, const double f[6]);

#endif
