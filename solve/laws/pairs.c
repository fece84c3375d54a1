/* law_pairs_load (kinematics.h): a batch's inputs lane by lane. */
#include <stddef.h>

#include "lib/states.h"
#include "solve/kinematics.h"

/* The record's fields from d0 to h are seven doubles in a row: read as two
 * vectors of four, [d0 t0 t1 t2] and [h0 h1 h2 -], the last value the next
 * record's (pairlist_records keeps one after the last). */
_Static_assert(offsetof(pair_rec, t) == offsetof(pair_rec, d0) + 8 &&
                   offsetof(pair_rec, h) == offsetof(pair_rec, d0) + 32 && LAW_NHIST == 3,
               "pair_rec: d0, t, h are seven doubles in a row");

/* The states and constants of lanes q0 <= q < in->n, a loop for each
 * case, so that none tests a lane (those of records in a row are
 * vectorised). */
static inline __attribute__((always_inline)) void load_state_k(const law_pairs *restrict in,
                                                               law_lanes *restrict L, int q0)
{
	const int32_t *idx = in->idx;
	if (!in->state)
		for (int q = q0; q < in->n; q++)
			L->state[q] = BOND_BROKEN_TENSION;
	else if (idx)
		for (int q = q0; q < in->n; q++)
			L->state[q] = in->state[idx[q]];
	else
		for (int q = q0; q < in->n; q++)
			L->state[q] = in->state[q];
	if (!in->k)
		for (int q = q0; q < in->n; q++)
			L->k[q] = 0;
	else if (idx)
		for (int q = q0; q < in->n; q++)
			L->k[q] = in->k[idx[q]];
	else
		for (int q = q0; q < in->n; q++)
			L->k[q] = in->k[q];
}

/* The lanes' fields but the states and constants. */
static void load_lanes(const law_pairs *restrict in, law_lanes *restrict L, int q0)
{
	for (int q = q0; q < in->n; q++) {
		const pair_rec *b = &in->rec[in->idx ? in->idx[q] : q];
		int32_t i = b->i, j = b->j;
		for (int c = 0; c < 3; c++) {
			L->dx[c][q] = in->x[3 * j + c] - in->x[3 * i + c];
			L->dv[c][q] = in->v[3 * j + c] - in->v[3 * i + c];
			L->wi[c][q] = in->w[3 * i + c];
			L->wj[c][q] = in->w[3 * j + c];
			L->t[c][q] = b->t[c];
		}
		L->ri[q] = in->r[i];
		L->rj[q] = in->r[j];
		L->d0[q] = b->d0;
		for (int c = 0; c < LAW_NHIST; c++)
			L->h[c][q] = b->h[c];
	}
}

void law_pairs_load_lanes(const law_pairs *restrict in, law_lanes *restrict L, int q0)
{
	load_lanes(in, L, q0);
	load_state_k(in, L, q0);
}

#if defined(__x86_64__) && defined(__GNUC__)
#include "solve/vec4.h"

#define AVX2 __attribute__((target("avx2")))

/* The three values of particles p[0..4) of the array a (four read from
 * each: the next item's first, or the spare item's, is not used). */
AVX2 static inline void particles3(const double *a, const int32_t p[4], vec4 out[4])
{
	vec4 row[4];
	for (int l = 0; l < 4; l++)
		row[l] = *(const vec4 *)(a + 3 * (ptrdiff_t)p[l]);
	vec4_transpose(row, out);
}

/* The differences a_j - a_i of the three values of particles j[l] and
 * i[l], l < 4, as particles3 gives them: each row subtracted before the
 * transpose, so one transpose instead of two (the same differences). */
AVX2 static inline void particles3_diff(const double *a, const int32_t i[4], const int32_t j[4],
                                        vec4 out[4])
{
	vec4 row[4];
	for (int l = 0; l < 4; l++)
		row[l] = *(const vec4 *)(a + 3 * (ptrdiff_t)j[l]) -
		         *(const vec4 *)(a + 3 * (ptrdiff_t)i[l]);
	vec4_transpose(row, out);
}

/* listed: whether in->idx lists the records (else they are in a row): a
 * constant in each inlined copy, so that no lane tests it. */
AVX2 static inline __attribute__((always_inline)) void
load_avx2_body(const law_pairs *restrict in, law_lanes *restrict L, int listed)
{
	int q = 0;
	for (; q + 4 <= in->n; q += 4) {
		const pair_rec *b[4];
		int32_t i[4], j[4];
		for (int l = 0; l < 4; l++) {
			b[l] = &in->rec[listed ? in->idx[q + l] : q + l];
			i[l] = b[l]->i;
			j[l] = b[l]->j;
			L->ri[q + l] = in->r[i[l]];
			L->rj[q + l] = in->r[j[l]];
		}
		vec4 pi[4], pj[4];
		particles3_diff(in->x, i, j, pi);
		for (int c = 0; c < 3; c++)
			*(vec4 *)&L->dx[c][q] = pi[c];
		particles3_diff(in->v, i, j, pi);
		for (int c = 0; c < 3; c++)
			*(vec4 *)&L->dv[c][q] = pi[c];
		particles3(in->w, i, pi);
		particles3(in->w, j, pj);
		for (int c = 0; c < 3; c++) {
			*(vec4 *)&L->wi[c][q] = pi[c];
			*(vec4 *)&L->wj[c][q] = pj[c];
		}
		vec4 row[4], lo[4], hi[4];
		for (int l = 0; l < 4; l++)
			row[l] = *(const vec4 *)&b[l]->d0;
		vec4_transpose(row, lo);
		for (int l = 0; l < 4; l++)
			row[l] = *(const vec4 *)&b[l]->h[0];
		vec4_transpose(row, hi);
		double *to[7] = {L->d0, L->t[0], L->t[1], L->t[2], L->h[0], L->h[1], L->h[2]};
		for (int c = 0; c < 4; c++)
			*(vec4 *)(to[c] + q) = lo[c];
		for (int c = 0; c < 3; c++)
			*(vec4 *)(to[4 + c] + q) = hi[c];
	}
	load_lanes(in, L, q);
}

AVX2 static void load_avx2(const law_pairs *restrict in, law_lanes *restrict L)
{
	if (in->idx)
		load_avx2_body(in, L, 1);
	else
		load_avx2_body(in, L, 0);
	load_state_k(in, L, 0);
}

void law_pairs_load(const law_pairs *restrict in, law_lanes *restrict L)
{
	if (__builtin_cpu_supports("avx2"))
		load_avx2(in, L);
	else
		law_pairs_load_lanes(in, L, 0);
}
#else
void law_pairs_load(const law_pairs *restrict in, law_lanes *restrict L)
{
	law_pairs_load_lanes(in, L, 0);
}
#endif
