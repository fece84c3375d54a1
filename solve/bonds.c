/* Bonds: formed once at start between spheres within the law's interaction
 * range (d <= range (r_i + r_j), Eq. 16), kept in one flat array sorted by
 * (i, j), each computed once per step in batches handed to the law's
 * force_batch. Forces reach the particles through the CSR gather of step.c.
 * Bond failures are collected per thread and merged in bond order. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/blocks.h"
#include "solve/bonds.h"
#include "solve/cells.h"
#include "solve/engine.h"
#include "solve/kinematics.h"
#include "solve/measure.h"
#include "solve/pairlist.h"

/* Whether the centre of one of spheres i, j lies inside the other. */
static int nested(const particles *P, size_t i, int32_t j)
{
	double d2 = 0;
	for (int k = 0; k < 3; k++) {
		double dx = P->x[3 * j + k] - P->x[3 * i + k];
		d2 += dx * dx;
	}
	double r = fmax(P->r[i], P->r[j]);
	return d2 < r * r;
}

int bonds_form(engine *e)
{
	particles *P = &e->p;
	double range = e->law->bond_range(e->lp);
	cells g = {0};
	cells_build(&g, P->x, P->n, range * 2 * e->frame.r_max);
	pairlist *L = &e->pairs.bonds;
	enum { CAP = 4096 };
	int32_t js[CAP];
	/* Count first, so the bond array is allocated once at its size. */
	size_t count = 0;
	for (size_t i = 0; i < P->n; i++) {
		int nj = cells_partners(&g, P->x, P->r, i, range, 0, js, CAP);
		if (nj < 0) {
			cells_free(&g);
			return err_set(
			    "particle %d has more than %d neighbours within the bond range: "
			    "overlapping spheres?",
			    P->orig[i], CAP);
		}
		for (int q = 0; q < nj; q++)
			if (nested(P, i, js[q])) {
				cells_free(&g);
				const double *xi = P->x + 3 * i;
				return err_set(
				    "particles %d and %d (radii %g and %g m, at (%g, %g, "
				    "%g) m): the centre of one lies inside the other: "
				    "expected the spheres of a packing (a damaged "
				    "assembly?)",
				    P->orig[i], P->orig[js[q]], P->r[i], P->r[js[q]], xi[0], xi[1],
				    xi[2]);
			}
		count += (size_t)nj;
	}
	L->rec = xmalloc((count + 1) * sizeof *L->rec);
	for (size_t i = 0; i < P->n; i++) {
		int nj = cells_partners(&g, P->x, P->r, i, range, 0, js, CAP);
		for (int q = 0; q < nj; q++) {
			bond *b = &L->rec[L->n++];
			memset(b, 0, sizeof *b);
			b->i = (int32_t)i;
			b->j = js[q];
			double d2 = 0;
			for (int k = 0; k < 3; k++) {
				double dx = P->x[3 * js[q] + k] - P->x[3 * i + k];
				d2 += dx * dx;
			}
			b->d0 = sqrt(d2);
		}
	}
	cells_free(&g);
	L->cap = L->n;
	L->f = xcalloc(6 * L->n + 1, sizeof *L->f);
	L->off = xmalloc((P->n + 1) * sizeof *L->off);
	L->ref = xmalloc((2 * L->n + 1) * sizeof *L->ref);
	pairlist_csr(L, P->n);
	return 0;
}

/* The law's pair description of bond b (for init and constants). */
static law_pair pair_of(const particles *P, const bond *b)
{
	return (law_pair){
	    .ri = P->r[b->i], .rj = P->r[b->j], .mi = P->m[b->i], .mj = P->m[b->j], .d0 = b->d0};
}

void engine_bond_entry(const engine *e, size_t b, int32_t ends[2], law_const *c)
{
	const bond *bd = &e->pairs.bonds.rec[b];
	int32_t oi = e->p.orig[bd->i], oj = e->p.orig[bd->j];
	ends[0] = oi < oj ? oi : oj;
	ends[1] = oi < oj ? oj : oi;
	if (c) {
		law_pair q = pair_of(&e->p, bd);
		e->law->constants(e->lp, &q, c);
	}
}

void bonds_init_history(engine *e)
{
	for (size_t b = 0; b < e->pairs.bonds.n; b++) {
		law_pair q = pair_of(&e->p, &e->pairs.bonds.rec[b]);
		e->law->init(e->lp, &q, &e->pairs.bonds.rec[b]);
	}
}

/* A failure as a crack record, with the force the bond carried before it. */
static void record_crack(engine *e, crack_buf *cb, size_t b, int mode, const batch_geom *g, int q)
{
	double n[3] = {g->n[0][q], g->n[1][q], g->n[2][q]}, d = g->d[q];
	if (cb->n == cb->cap) {
		cb->cap = cb->cap ? 2 * cb->cap : 64;
		cb->c = xrealloc(cb->c, cb->cap * sizeof *cb->c);
		cb->bond = xrealloc(cb->bond, cb->cap * sizeof *cb->bond);
	}
	const bond *bd = &e->pairs.bonds.rec[b];
	const particles *P = &e->p;
	const double *f = e->pairs.bonds.f + 6 * b;
	double fn = f[0] * n[0] + f[1] * n[1] + f[2] * n[2];
	double fs[3] = {f[0] - fn * n[0], f[1] - fn * n[1], f[2] - fn * n[2]};
	int32_t oi = P->orig[bd->i], oj = P->orig[bd->j];
	double sign = oi < oj ? 1 : -1;
	double ai = d * P->r[bd->i] / (P->r[bd->i] + P->r[bd->j]);
	dem_crack *c = &cb->c[cb->n];
	cb->bond[cb->n++] = (int32_t)b;
	*c = (dem_crack){.t = e->clock.t,
	                 .step = e->clock.step,
	                 .i = oi < oj ? oi : oj,
	                 .j = oi < oj ? oj : oi,
	                 .mode = mode,
	                 .radius = P->r[bd->i] < P->r[bd->j] ? P->r[bd->i] : P->r[bd->j],
	                 .fn = fn,
	                 .fs = sqrt(fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2])};
	for (int k = 0; k < 3; k++) {
		c->x[k] = P->x[3 * bd->i + k] + ai * n[k];
		c->normal[k] = sign * n[k];
	}
}

/* One block of bonds [lo, hi). */
DEM_VECTOR_CLONES static void bond_block(engine *e, size_t lo, size_t hi, int measure, pair_sums *s,
                                         crack_buf *cb)
{
	const particles *P = &e->p;
	pairlist *L = &e->pairs.bonds;
	law_batch B;
	batch_geom g;
	memset(s, 0, sizeof *s);
	for (size_t b0 = lo; b0 < hi; b0 += BATCH) {
		int nq = (int)(hi - b0 < BATCH ? hi - b0 : BATCH);
		bond *rec = &L->rec[b0];
		batch_kinematics(P->x, P->v, P->w, P->r, P->m, rec, nq, e->clock.dt, &B, &g);
		batch_history_load(rec, &B);
		e->law->force_batch(e->lp, &B);
		batch_history_store(rec, &B);
		for (int q = 0; q < nq; q++) {
			size_t b = b0 + q;
			if (B.failed[q])
				record_crack(e, cb, b, B.failed[q], &g, q);
			double *f = L->f + 6 * b;
			batch_force(&B, &g, q, f);
			s->e_damage += B.e_damage[q];
			s->e_friction += B.e_friction[q];
			s->e_viscous += B.fn_viscous[q] * B.vn[q] * e->clock.dt;
			if (measure) {
				law_pair pair = law_lane_pair(&B, q);
				s->e_elastic += e->law->energy(e->lp, &pair, &rec[q]);
				love_add(s->love, &g, q, f);
				s->count[rec[q].state]++;
			}
		}
	}
}

void bonds_forces(engine *e, int measure)
{
	size_t nb = nblocks(e->pairs.bonds.n);
	crack_buf *cb = &e->out.thread_cracks[omp_get_thread_num()];
#pragma omp for schedule(static) nowait
	for (size_t k = 0; k < nb; k++) {
		bond_block(e, k * BLOCK, block_end(k, e->pairs.bonds.n), measure,
		           &e->scratch.bblock[k], cb);
	}
}

/* Move this step's failures from the thread buffers to e->out.cracks, in bond
 * order (whatever thread found them). */
void bonds_collect_cracks(engine *e)
{
	crack_buf *cb = &e->out.cracks;
	size_t first = cb->n;
	double strain = engine_strain(e);
	for (int t = 0; t < e->nthreads; t++) {
		crack_buf *tc = &e->out.thread_cracks[t];
		for (size_t k = 0; k < tc->n; k++) {
			if (cb->n == cb->cap) {
				cb->cap = cb->cap ? 2 * cb->cap : 256;
				cb->c = xrealloc(cb->c, cb->cap * sizeof *cb->c);
				cb->bond = xrealloc(cb->bond, cb->cap * sizeof *cb->bond);
			}
			cb->c[cb->n] = tc->c[k];
			cb->c[cb->n].strain_axial = strain;
			cb->bond[cb->n++] = tc->bond[k];
		}
		tc->n = 0;
	}
	/* Insertion sort of this step's few failures by bond index. */
	for (size_t k = first + 1; k < cb->n; k++) {
		int32_t b = cb->bond[k];
		dem_crack c = cb->c[k];
		size_t q = k;
		for (; q > first && cb->bond[q - 1] > b; q--) {
			cb->bond[q] = cb->bond[q - 1];
			cb->c[q] = cb->c[q - 1];
		}
		cb->bond[q] = b;
		cb->c[q] = c;
	}
}
