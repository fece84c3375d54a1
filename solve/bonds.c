/* Bonds: formed once at start between spheres within the law's interaction
 * range (d <= range (r_i + r_j), Eq. 16), kept in one flat array sorted by
 * (i, j), each computed once per step in batches handed to the law's
 * force_batch, each force added to both its particles in bond order (the
 * shares of bond_split, bonds.h). Bond failures are collected per thread
 * and merged in bond order. */
#include <inttypes.h>
#include <math.h>
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
#include "solve/par.h"
#include "solve/ranks.h"
#include "solve/vec4.h"

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

/* The particles j > i within the bond range of particle i (Eq. 16), in
 * increasing order, into js (CELLS_CAP): their number, or -1. */
static int partners(const engine *e, size_t i, int32_t *js)
{
	const bond_search *f = &e->pairs.formed;
	size_t lo = f->lo;
	int nj = cells_partners(&f->grid, e->p.x + 3 * lo, e->p.r + lo, i - lo, f->range, 0, js,
	                        CELLS_CAP);
	for (int q = 0; q < nj; q++)
		js[q] += (int32_t)lo;
	return nj;
}

/* The search's grid over the particles this rank holds: with several
 * ranks its own and the others' within the bond range of them (window.h),
 * which a pair within range is closer than along each axis (the margin
 * covers the rounding of both tests). */
void bonds_search_grid(engine *e)
{
	particles *P = &e->p;
	bond_search *f = &e->pairs.formed;
	double reach = f->range * 2 * e->frame.r_max;
	if (P->glob)
		window_ghosts(e, reach * (1 + 1e-9));
	f->lo = P->lo;
	cells_build(&f->grid, P->x + 3 * P->lo, P->hi - P->lo, reach);
}

int bonds_form(engine *e)
{
	particles *P = &e->p;
	bond_search *f = &e->pairs.formed;
	f->range = e->law->bond_range(e->lp);
	bonds_search_grid(e);
	/* Count them by particle block, each rank its own particles' (whole
	 * blocks), gathered: the bonds are found again where they are needed
	 * (bonds_split, bonds_own). */
	size_t nblk = nblocks(P->n), p0, p1;
	int split = ranks_own(e, &p0, &p1);
	size_t b0 = p0 / BLOCK, nb = p1 > p0 ? nblocks(p1) - b0 : 0;
	size_t *count = xcalloc(nb + 1, sizeof *count);
	int32_t js[CELLS_CAP];
	for (size_t i = p0; i < p1; i++) {
		int nj = partners(e, i, js);
		if (nj < 0)
			return err_set("particle %d has more than %d neighbours within the bond "
			               "range: overlapping spheres?",
			               P->orig[i], CELLS_CAP);
		for (int q = 0; q < nj; q++)
			if (nested(P, i, js[q])) {
				const double *xi = P->x + 3 * i;
				return err_set("particles %d and %d (radii %g and %g m, at (%g, "
				               "%g, %g) m): the centre of one lies inside the "
				               "other: expected the spheres of a packing (a "
				               "damaged assembly?)",
				               P->orig[i], P->orig[js[q]], P->r[i], P->r[js[q]],
				               xi[0], xi[1], xi[2]);
			}
		count[i / BLOCK - b0] += (size_t)nj;
	}
	f->bfirst = xcalloc(nblk + 1, sizeof *f->bfirst);
	if (split)
		ranks_allgather_rows(count, nb, sizeof *count, f->bfirst + 1);
	else
		memcpy(f->bfirst + 1, count, nb * sizeof *count);
	free(count);
	for (size_t k = 0; k < nblk; k++)
		f->bfirst[k + 1] += f->bfirst[k];
	e->pairs.nbonds = f->bfirst[nblk];
	return 0;
}

void bonds_search_free(bond_search *f)
{
	cells_free(&f->grid);
	free(f->bfirst);
	f->bfirst = NULL;
}

/* Call visit(ctx, b, i, j) for each bond b (of the whole specimen) of
 * the particles [p0, p1), p0 the first of a block, in bond order; from the
 * search, or (one rank, every record its own) from the records. */
typedef void (*bond_visit)(void *ctx, size_t b, int32_t i, int32_t j);
static void each_bond(const engine *e, size_t p0, size_t p1, bond_visit visit, void *ctx)
{
	const bond_search *f = &e->pairs.formed;
	if (!f->bfirst) {
		const pairlist *L = &e->pairs.bonds;
		const size_t *bfirst = e->pairs.split.bfirst;
		for (size_t b = bfirst[p0 / BLOCK]; b < L->n && (size_t)L->rec[b].i < p1; b++)
			visit(ctx, b, L->rec[b].i, L->rec[b].j);
		return;
	}
	int32_t js[CELLS_CAP];
	size_t b = f->bfirst[p0 / BLOCK];
	for (size_t i = p0; i < p1; i++) {
		int nj = partners(e, i, js);
		for (int q = 0; q < nj; q++)
			visit(ctx, b++, (int32_t)i, js[q]);
	}
}

/* A bond's record, its length from the search (as cells_pairs_within
 * measures it). */
typedef struct {
	const particles *P;
	pair_rec *rec;
	size_t b0;
} keep_ctx;

static void keep_one(void *ctx, size_t b, int32_t i, int32_t j)
{
	keep_ctx *k = ctx;
	const double *x = k->P->x;
	double d2 = 0;
	for (int c = 0; c < 3; c++) {
		double dx = x[3 * (size_t)j + c] - x[3 * (size_t)i + c];
		d2 += dx * dx;
	}
	pair_rec *bd = &k->rec[b - k->b0];
	bd->i = i;
	bd->j = j;
	bd->d0 = sqrt(d2);
}

/* The records of the bonds of the particles [p0, p1), bonds [b0, b1) of the
 * whole specimen, as this rank's (the search released), or, after that,
 * the records it holds (one rank: all of them). */
static void bonds_keep(engine *e, size_t p0, size_t p1, size_t b0, size_t b1)
{
	pairlist *L = &e->pairs.bonds;
	bond_search *f = &e->pairs.formed;
	if (!f->bfirst) {
		if (b1 - b0 != L->n || (L->n && b0 != e->pairs.bond0))
			fatal("the bonds are split again on other ranks than they were formed for");
		e->pairs.bond0 = b0;
		return;
	}
	pairlist_free(L);
	L->n = L->cap = b1 - b0;
	L->rec = pairlist_records(NULL, 0, L->n);
	each_bond(e, p0, p1, keep_one, &(keep_ctx){&e->p, L->rec, b0});
	L->state = xcalloc(L->n + 1, sizeof *L->state);
	L->k = e->law->keeps_k ? xcalloc(L->n + 1, sizeof *L->k) : NULL;
	L->fb = xcalloc(3 * L->n + 1, sizeof *L->fb);
	e->pairs.bond0 = b0;
	bonds_search_free(f);
}

/* The law's pair description of bond b (for init and constants). */
static law_pair pair_of(const particles *P, const pair_rec *b)
{
	return (law_pair){
	    .ri = P->r[b->i], .rj = P->r[b->j], .mi = P->m[b->i], .mj = P->m[b->j], .d0 = b->d0};
}

void engine_bond_entry(const engine *e, const pairlist *L, size_t b, int32_t ends[2], law_const *c)
{
	const pair_rec *bd = &L->rec[b];
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
	const particles *P = &e->p;
	pairlist *L = &e->pairs.bonds;
	double xi = e->cs->mat.damping;
	for (size_t b = 0; b < L->n; b++) {
		law_pair q = pair_of(P, &L->rec[b]);
		bond bd = pair_bond(&L->rec[b], BOND_INTACT, 0);
		e->law->init(e->lp, &q, &bd);
		pairlist_put(L, b, &bd);
		law_const c;
		e->law->constants(e->lp, &q, &c);
		double mij = q.mi * q.mj / (q.mi + q.mj);
		xi = fmax(xi, c.cn / (2 * sqrt(mij * c.kn)));
	}
	par_max(&xi, 1);
	e->clock.xi_max = xi;
}

void bonds_restore(engine *e)
{
	if (!e->law->restore)
		return;
	pairlist *L = &e->pairs.bonds;
	for (size_t b = 0; b < L->n; b++) {
		law_pair q = pair_of(&e->p, &L->rec[b]);
		bond bd = pairlist_bond(L, b);
		e->law->restore(e->lp, &q, &bd);
		pairlist_put(L, b, &bd);
	}
}

/* Lane q of B, failing, as a crack record, with the forces its law judged
 * (law_out.fn_failed, fs_failed). */
static void record_crack(engine *e, crack_buf *cb, size_t b, const law_batch *B,
                         const batch_geom *g, int q)
{
	double n[3] = {g->n[0][q], g->n[1][q], g->n[2][q]}, d = g->d[q];
	if (cb->n == cb->cap) {
		cb->cap = cb->cap ? 2 * cb->cap : 64;
		cb->c = xrealloc(cb->c, cb->cap * sizeof *cb->c);
		cb->bond = xrealloc(cb->bond, cb->cap * sizeof *cb->bond);
	}
	const pair_rec *bd = &e->pairs.bonds.rec[b];
	const particles *P = &e->p;
	b += e->pairs.bond0; /* its place in the whole specimen's bond order */
	int32_t oi = P->orig[bd->i], oj = P->orig[bd->j];
	double sign = oi < oj ? 1 : -1;
	double ai = d * P->r[bd->i] / (P->r[bd->i] + P->r[bd->j]);
	dem_crack *c = &cb->c[cb->n];
	cb->bond[cb->n++] = (int64_t)b;
	*c = (dem_crack){.t = e->clock.t,
	                 .step = e->clock.step,
	                 .i = oi < oj ? oi : oj,
	                 .j = oi < oj ? oj : oi,
	                 .mode = B->failed[q],
	                 .radius = P->r[bd->i] < P->r[bd->j] ? P->r[bd->i] : P->r[bd->j],
	                 .fn = B->fn_failed[q],
	                 .fs = B->fs_failed[q]};
	for (int k = 0; k < 3; k++) {
		c->x[k] = P->x[3 * bd->i + k] + ai * n[k];
		c->normal[k] = sign * n[k];
	}
}

/* The kinematics of the nq bonds idx[0..nq) into B and g, and the law's
 * forces on B, a copy: no bond changes. Always inlined into its callers'
 * vector versions, as batch_kinematics is. */
static inline __attribute__((always_inline)) void batch_law(engine *e, const int32_t *idx, int nq,
                                                            law_batch *B, batch_geom *g)
{
	const particles *P = &e->p;
	const pairlist *L = &e->pairs.bonds;
	batch_kinematics(P->x, P->v, P->w, P->r, P->m, L->rec, L->state, L->k, idx, nq, e->clock.dt,
	                 B, g);
	e->law->force_batch(e->lp, B);
}

/* The nq bonds idx[0..nq) computed (kinematics, law, failures): what each
 * adds, into part[0..nq). */
DEM_VECTOR_CLONES static void bonds_staged(engine *e, const int32_t *idx, int nq, int measure,
                                           crack_buf *cb, bond_part *part)
{
	pairlist *L = &e->pairs.bonds;
	law_batch B;
	batch_geom g;
	batch_law(e, idx, nq, &B, &g);
	batch_history_store(L->rec, L->state, idx, &B);
	for (int q = 0; q < nq; q++) {
		bond_part *o = &part[q];
		if (B.failed[q])
			record_crack(e, cb, (size_t)idx[q], &B, &g, q);
		batch_force(&B, &g, q, o->f);
		o->e_damage = B.e_damage[q];
		o->e_friction = B.e_friction[q];
		o->e_viscous = B.fn_viscous[q] * B.vn[q] * e->clock.dt;
		if (measure) {
			law_pair pair = law_lane_pair(&B, q);
			bond bd = pairlist_bond(L, (size_t)idx[q]);
			o->e_elastic = e->law->energy(e->lp, &pair, &bd, B.un[q]);
			memset(o->love, 0, sizeof o->love);
			love_add(o->love, &g, q, o->f);
			o->state = bd.state;
		}
	}
}

void bonds_output_forces(engine *e)
{
	pairlist *L = &e->pairs.bonds;
	ptrdiff_t batches = (ptrdiff_t)((L->n + BATCH - 1) / BATCH);
#pragma omp parallel for num_threads(e->team) schedule(static)
	for (ptrdiff_t k = 0; k < batches; k++) {
		size_t b0 = (size_t)k * BATCH;
		int nq = L->n - b0 < BATCH ? (int)(L->n - b0) : BATCH;
		int32_t idx[BATCH];
		for (int q = 0; q < nq; q++)
			idx[q] = (int32_t)(b0 + (size_t)q);
		law_batch B;
		batch_geom g;
		batch_law(e, idx, nq, &B, &g);
		for (int q = 0; q < nq; q++) {
			double f[6];
			batch_force(&B, &g, q, f);
			for (int c = 0; c < 3; c++)
				L->fb[3 * (b0 + (size_t)q) + c] = (float)f[c];
		}
	}
}

/* Lane q of force_pairs' output, on the law's elastic branch: the new
 * history of its bond into its record r, t and, when history is set
 * (o->history, or 0 where the caller knows it is not), h; the caller
 * stores the state (a byte, whose store may alias anything: the compiler
 * would read every pointer and flag again after it, so loops store the
 * states apart). */
static inline void fused_history(pair_rec *r, const law_fused *o, int q, int history)
{
	for (int c = 0; c < 3; c++)
		r->t[c] = o->t[c][q];
	if (history)
		for (int c = 0; c < LAW_NHIST; c++)
			r->h[c] = o->h[c][q];
}

/* The nq bonds idx[0..nq) (or b0 + q, q < nq, when idx is NULL) through
 * the law's force_pairs (kinematics.h):
 * the lanes on its elastic branch (o->elastic[q]) from its one loop, their
 * records updated (unless keep is set and every lane is elastic: the
 * caller then updates them, fused_history); the others as bonds_staged
 * computes them, into part[q]. Returns the count of elastic lanes.
 * Inlined, so the vector versions of its callers (clones.h) run their own
 * copy of it. */
static inline __attribute__((always_inline)) int bonds_fused(engine *e, size_t b0,
                                                             const int32_t *idx, int nq, int keep,
                                                             crack_buf *cb, law_lanes *L,
                                                             law_fused *o, bond_part *part)
{
	const particles *P = &e->p;
	pairlist *bl = &e->pairs.bonds;
	size_t at = idx ? 0 : b0; /* the batch's records, states, constants */
	law_pairs in = {.x = P->x,
	                .v = P->v,
	                .w = P->w,
	                .r = P->r,
	                .rec = bl->rec + at,
	                .state = bl->state + at,
	                .k = bl->k ? bl->k + at : NULL,
	                .idx = idx,
	                .n = nq};
	law_pairs_load(&in, L);
	o->damage = o->friction = 0;
	int elastic = e->law->force_pairs(e->lp, L, nq, e->clock.dt, o);
	if (keep && elastic == nq)
		return elastic;
	int32_t rest[BATCH] = {0}, lane[BATCH];
	int nr = 0;
	for (int q = 0; q < nq; q++) {
		int32_t b = idx ? idx[q] : (int32_t)(b0 + (size_t)q);
		if (!o->elastic[q]) {
			rest[nr] = b;
			lane[nr++] = q;
			continue;
		}
		fused_history(&bl->rec[b], o, q, o->history);
		if (o->history)
			bl->state[b] = (uint8_t)o->state[q];
	}
	if (elastic == nq)
		return elastic;
	bond_part rp[BATCH];
	bonds_staged(e, rest, nr, 0, cb, rp);
	for (int k = 0; k < nr; k++)
		part[lane[k]] = rp[k];
	return elastic;
}

/* Whether this step's bonds go through the law's force_pairs: when it has
 * one and the step measures nothing. */
static int bonds_use_fused(const engine *e, int measure) { return !measure && e->law->force_pairs; }

/* What each of the nq bonds idx[0..nq) adds, into part[0..nq). */
static void bonds_compute(engine *e, const int32_t *idx, int nq, int measure, crack_buf *cb,
                          bond_part *part)
{
	if (!bonds_use_fused(e, measure)) {
		bonds_staged(e, idx, nq, measure, cb, part);
		return;
	}
	law_lanes L;
	law_fused o;
	bonds_fused(e, 0, idx, nq, 0, cb, &L, &o, part);
	for (int q = 0; q < nq; q++)
		if (o.elastic[q]) {
			bond_part *d = &part[q];
			for (int c = 0; c < 6; c++)
				d->f[c] = o.f[c][q];
			d->e_damage = o.damage ? o.e_damage[q] : 0;
			d->e_friction = o.friction ? o.e_friction[q] : 0;
			d->e_viscous = o.e_viscous[q];
		}
}

/* Six doubles added to a particle's sums a (force, torque per unit radius)
 * as three vectors of two (which any x86-64 has), built in registers: the
 * same additions, each sum's in the same order, in fewer instructions.
 * Read and written as vectors of doubles, not with memcpy, whose stores
 * might alias anything and would make the compiler read the engine's
 * pointers again after each. */
typedef double acc_v2 __attribute__((vector_size(16), aligned(8)));
static inline void acc_add(double *a, double d0, double d1, double d2, double d3, double d4,
                           double d5)
{
	acc_v2 d[3] = {{d0, d1}, {d2, d3}, {d4, d5}};
	acc_v2 *x = (acc_v2 *)a;
	for (int k = 0; k < 3; k++)
		x[k] += d[k];
}

/* The force of a bond (i, j) on j (-f) and its torque per unit radius added
 * to j's sums. */
static inline void add_to_j(engine *e, int32_t j, const double f[6])
{
	double rj = e->p.r[j];
	acc_add(engine_acc(e, (size_t)j), -f[0], -f[1], -f[2], rj * f[3], rj * f[4], rj * f[5]);
}

/* Bond b's force, found not finite, noted for the diagnosis. */
static __attribute__((cold, noinline)) void note_bad(engine *e, size_t b)
{
	crack_buf *cb = &e->out.thread_cracks[omp_get_thread_num()];
	if (cb->nbad == cb->badcap) {
		cb->badcap = cb->badcap ? 2 * cb->badcap : 16;
		cb->bad = xrealloc(cb->bad, cb->badcap * sizeof *cb->bad);
	}
	cb->bad[cb->nbad++] = (int32_t)b;
}

/* Bond b's force and torque f added to particle i and, when both, to j
 * (and the bond noted when its force is not finite). */
static inline void bond_add_force(engine *e, size_t b, const double f[6], int both)
{
	const pair_rec *bd = &e->pairs.bonds.rec[b];
	if (!isfinite(f[0] + f[1] + f[2]))
		note_bad(e, b);
	double ri = e->p.r[bd->i];
	acc_add(engine_acc(e, (size_t)bd->i), f[0], f[1], f[2], ri * f[3], ri * f[4], ri * f[5]);
	if (both)
		add_to_j(e, bd->j, f);
}

/* Bond b's part added to its block's sums s, and its force (bond_add_force). */
static inline void bond_add(engine *e, size_t b, const bond_part *o, int measure, pair_sums *s,
                            int both)
{
	s->e_damage += o->e_damage;
	s->e_friction += o->e_friction;
	s->e_viscous += o->e_viscous;
	if (measure) {
		s->e_elastic += o->e_elastic;
		for (int c = 0; c < 9; c++)
			s->love[c] += o->love[c];
		s->count[o->state]++;
	}
	bond_add_force(e, b, o->f, both);
}

/* Bond b's force from lane q of force_pairs' output (bond_add_force). */
static inline void bond_add_lane(engine *e, size_t b, const law_fused *o, int q)
{
	double f[6];
	for (int c = 0; c < 6; c++)
		f[c] = o->f[c][q];
	bond_add_force(e, b, f, 1);
}

/* bond_add for lane q of force_pairs' output, a bond of the share: it
 * dissipates nothing but its viscous energy and any plastic work or work
 * of sliding, where o holds them (o->damage, o->friction; adding the zeros
 * would leave the sums as they are: started at +0, a sum is never -0). */
static inline void bond_add_fused(engine *e, size_t b, const law_fused *o, int q, pair_sums *s)
{
	if (o->damage)
		s->e_damage += o->e_damage[q];
	if (o->friction)
		s->e_friction += o->e_friction[q];
	s->e_viscous += o->e_viscous[q];
	bond_add_lane(e, b, o, q);
}

/* Eight states as int32, read at any 4-byte boundary, and as bytes. */
typedef int32_t state_v8 __attribute__((vector_size(32), aligned(4)));
typedef uint8_t state_b8 __attribute__((vector_size(8), aligned(1)));

/* The states s[0..n) as bytes into to[0..n), eight at a time where they
 * can be: a byte store may alias anything, so the compiler keeps a loop
 * of them scalar, reading each state again after each store. */
static inline void states_store(uint8_t *to, const int32_t *s, int n)
{
	int q = 0;
	for (; q + 8 <= n; q += 8)
		*(state_b8 *)(to + q) =
		    __builtin_convertvector(*(const state_v8 *)(s + q), state_b8);
	for (; q < n; q++)
		to[q] = (uint8_t)s[q];
}

/* The lanes of u and w paired: out[l] = (u[l], w[l]). */
static inline void vec4_pairs(vec4 u, vec4 w, acc_v2 out[4])
{
	vec4 t0 = __builtin_shufflevector(u, w, 0, 4, 2, 6),
	     t1 = __builtin_shufflevector(u, w, 1, 5, 3, 7);
	out[0] = __builtin_shufflevector(t0, t0, 0, 1);
	out[1] = __builtin_shufflevector(t1, t1, 0, 1);
	out[2] = __builtin_shufflevector(t0, t0, 2, 3);
	out[3] = __builtin_shufflevector(t1, t1, 2, 3);
}

/* The sums a particle gets from lanes q..q+3 of o, r the radii of that end
 * of each lane and sign -1 for the ends j: head[l] the force and the first
 * torque component of lane q + l, tail[l] the other two. */
static inline void lanes_sums(const law_fused *o, int q, const double *r, double sign, vec4 head[4],
                              acc_v2 tail[4])
{
	vec4 rv = *(const vec4 *)(r + q);
	vec4 col[4] = {sign * *(const vec4 *)(o->f[0] + q), sign * *(const vec4 *)(o->f[1] + q),
	               sign * *(const vec4 *)(o->f[2] + q), rv * *(const vec4 *)(o->f[3] + q)};
	vec4_transpose(col, head);
	vec4_pairs(rv * *(const vec4 *)(o->f[4] + q), rv * *(const vec4 *)(o->f[5] + q), tail);
}

/* The new histories of lanes q..q+3 of o into the records r[0..4), as
 * fused_history stores them: t and h are six doubles in a row in a record
 * (pairs.c), so t and h[0] of each lane are transposed into one row, and
 * with history h[1] and h[2] into a pair; without it, h is as the records
 * had it (L) and h[0] is written back unchanged, one store of a row
 * instead of three of single values. */
static inline void records_store(pair_rec *r, const law_fused *o, const law_lanes *L, int q,
                                 int history)
{
	vec4 col[4] = {*(const vec4 *)(o->t[0] + q), *(const vec4 *)(o->t[1] + q),
	               *(const vec4 *)(o->t[2] + q),
	               *(const vec4 *)((history ? o->h[0] : L->h[0]) + q)},
	     row[4];
	vec4_transpose(col, row);
	for (int l = 0; l < 4; l++)
		*(vec4 *)r[l].t = row[l];
	if (!history)
		return;
	acc_v2 tail[4];
	vec4_pairs(*(const vec4 *)(o->h[1] + q), *(const vec4 *)(o->h[2] + q), tail);
	for (int l = 0; l < 4; l++)
		*(acc_v2 *)(r[l].h + 1) = tail[l];
}

/* head and tail added to the sums a of a particle. */
static inline void acc_add_rows(double *a, vec4 head, acc_v2 tail)
{
	*(vec4 *)a += head;
	*(acc_v2 *)(a + 4) += tail;
}

/* The bonds b0 + q of lanes q < nq of force_pairs' output, all on the
 * law's elastic branch: each record updated and each bond added.
 * full: whether o's history, plastic work and work of sliding may be set
 * (else only t and the viscous energy are); a constant in each inlined
 * copy, so that the loop tests none. Four lanes at a time, their forces
 * and torques (times the radii of L) are transposed into one row per lane
 * and end instead of being read value by value: the same values added in
 * the same order as bond_add_fused adds them; and their histories into
 * the records (records_store). */
static inline __attribute__((always_inline)) void bonds_add_elastic(engine *e, size_t b0,
                                                                    const law_lanes *L,
                                                                    const law_fused *o, int nq,
                                                                    pair_sums *s, int full)
{
	pairlist *B = &e->pairs.bonds;
	int history = full && o->history;
	int q = 0;
	for (; q + 4 <= nq; q += 4)
		records_store(&B->rec[b0 + (size_t)q], o, L, q, history);
	for (; q < nq; q++)
		fused_history(&B->rec[b0 + (size_t)q], o, q, history);
	for (q = 0; q < nq; q++) {
		if (full && o->damage)
			s->e_damage += o->e_damage[q];
		if (full && o->friction)
			s->e_friction += o->e_friction[q];
		s->e_viscous += o->e_viscous[q];
	}
	if (history)
		states_store(B->state + b0, o->state, nq);
	vec4 sum = {0, 0, 0, 0}; /* not finite if a force is not */
	for (q = 0; q + 4 <= nq; q += 4) {
		vec4 hi[4], hj[4];
		acc_v2 ti[4], tj[4];
		lanes_sums(o, q, L->ri, 1, hi, ti);
		lanes_sums(o, q, L->rj, -1, hj, tj);
		for (int l = 0; l < 4; l++) {
			size_t b = b0 + (size_t)(q + l);
			const pair_rec *bd = &B->rec[b];
			sum += hi[l];
			acc_add_rows(engine_acc(e, (size_t)bd->i), hi[l], ti[l]);
			acc_add_rows(engine_acc(e, (size_t)bd->j), hj[l], tj[l]);
		}
	}
	if (!isfinite(sum[0] + sum[1] + sum[2]))
		for (int l = 0; l < q; l++)
			if (!isfinite(o->f[0][l] + o->f[1][l] + o->f[2][l]))
				note_bad(e, b0 + (size_t)l);
	for (; q < nq; q++)
		bond_add_lane(e, b0 + (size_t)q, o, q);
}

DEM_VECTOR_CLONES void bonds_cross(engine *e, int k, int measure)
{
	bond_split *S = &e->pairs.split;
	crack_buf *cb = &e->out.thread_cracks[omp_get_thread_num()];
	for (size_t c0 = S->cfirst[k]; c0 < S->cfirst[k + 1]; c0 += BATCH) {
		size_t left = S->cfirst[k + 1] - c0;
		bonds_compute(e, &S->cross[c0], (int)(left < BATCH ? left : BATCH), measure, cb,
		              &S->part[c0]);
	}
}

/* Ahead of the batch at bond b0: the records of the batch PREFETCH_RECORDS
 * batches on into the cache (their first read otherwise waits for memory),
 * and the positions, velocities, spins, radii and sums of the particles j
 * of the batch PREFETCH_PARTICLES batches on, whose records came in a
 * batch ago (the particles i follow the bond order, which the CPU's own
 * prefetcher sees; those j are scattered). Into the second-level cache
 * (locality 2, prefetcht1 on x86): into the first, the bond loop took
 * some 8 % more time beyond the caches (solve.md). Only the speed depends
 * on it. The lines of a whole batch, a record each (pairlist_records),
 * unrolled: past the last record they fetch what follows, and prefetching
 * never faults. Always inlined: GCC takes a function of prefetches alone
 * for one without effects and drops its calls. */
enum {
	PREFETCH_RECORDS = 4,
	PREFETCH_PARTICLES = 3,
	PREFETCH_LINES = BATCH * sizeof(pair_rec) / 64
};
static inline __attribute__((always_inline)) void bonds_prefetch(const engine *e, size_t b0)
{
	size_t r1 = b0 + PREFETCH_PARTICLES * BATCH, own1 = e->p.own1;
	if (r1 + BATCH <= e->pairs.bonds.n) {
		const pair_rec *rec = e->pairs.bonds.rec + r1;
		for (int l = 0; l < BATCH; l++) {
			size_t j = (size_t)rec[l].j;
			__builtin_prefetch(e->p.x + 3 * j, 0, 2);
			__builtin_prefetch(e->p.v + 3 * j, 0, 2);
			__builtin_prefetch(e->p.w + 3 * j, 0, 2);
			__builtin_prefetch(e->p.r + j, 0, 2);
			/* The sums of this rank's particles only (a ghost j
			 * has none). */
			__builtin_prefetch(engine_acc(e, j < own1 ? j : own1 - 1), 0, 2);
		}
	}
	size_t r0 = b0 + PREFETCH_RECORDS * BATCH;
	if (r0 >= e->pairs.bonds.n)
		return;
	const char *p0 = (const char *)(e->pairs.bonds.rec + r0);
#pragma GCC unroll 32
	for (int l = 0; l < PREFETCH_LINES; l++)
		__builtin_prefetch(p0 + 64 * l, 0, 2);
}

/* The steps a batch with more than a quarter of its lanes off the law's
 * elastic branch goes the staged way before it tries force_pairs again
 * (bond_split.staged): such lanes cost force_pairs' loop and then the
 * staged path's, which beyond about a quarter of the lanes is more than
 * the staged path's for the whole batch. */
enum { STAGED_STEPS = 64 };

DEM_VECTOR_CLONES void bonds_share(engine *e, int k, int measure, block_done done, void *ctx)
{
	bond_split *S = &e->pairs.split;
	const pair_rec *rec = e->pairs.bonds.rec;
	crack_buf *cb = &e->out.thread_cracks[omp_get_thread_num()];
	size_t p0 = S->pfirst[k], p1 = S->pfirst[k + 1], base = e->pairs.bond0;
	if (p0 == p1)
		return;
	/* The crossing bonds of earlier shares that reach this one come first
	 * in bond order: they add to their particle j here. */
	for (size_t q = S->infirst[k]; q < S->infirst[k + 1]; q++) {
		size_t c = (size_t)S->in[q];
		add_to_j(e, S->cj[c], S->part[c].f);
	}
	size_t slot = S->cfirst[k];
	int fused_law = bonds_use_fused(e, measure), prefetch = !e->pairs.prefetch.off;
	for (size_t blk = p0 / BLOCK; blk * BLOCK < p1; blk++) {
		/* Summed in a local, which no store to the particles' sums can
		 * alias, so its members stay in registers. */
		pair_sums sums = {0}, *s = &sums;
		size_t hi = S->bfirst[blk + 1] - base;
		for (size_t b0 = S->bfirst[blk] - base; b0 < hi; b0 += BATCH) {
			size_t b1 = hi - b0 < BATCH ? hi : b0 + BATCH;
			int32_t idx[BATCH];
			bond_part part[BATCH];
			if (prefetch)
				bonds_prefetch(e, b0);
			/* Whether the batch holds none of the share's crossing
			 * bonds: they are its slots, in bond order, so the next
			 * slot's bond says it. */
			int own = slot == S->cfirst[k + 1] || (size_t)S->cross[slot] >= b1;
			/* A batch that was largely off the law's elastic branch
			 * (broken, damaging, flowing bonds, whose lanes are
			 * computed twice: by force_pairs, then staged) goes the
			 * staged way for STAGED_STEPS steps, then tries again. */
			int fused = fused_law && !S->staged[b0];
			/* The batch's bonds, listed unless they are b0..b1 and go
			 * through force_pairs, which reads them in a row. */
			int nq = 0;
			if (own && fused)
				nq = (int)(b1 - b0);
			else
				for (size_t b = b0; b < b1; b++)
					if (own || (size_t)rec[b].j < p1)
						idx[nq++] = (int32_t)b;
			law_lanes L;
			law_fused o;
			int elastic = 0;
			if (fused) {
				elastic =
				    bonds_fused(e, b0, own ? NULL : idx, nq, own, cb, &L, &o, part);
				if (4 * elastic < 3 * nq)
					S->staged[b0] = STAGED_STEPS;
			} else {
				bonds_staged(e, idx, nq, measure, cb, part);
				if (fused_law)
					S->staged[b0]--;
			}
			if (fused && own && elastic == nq) {
				/* The whole batch is the share's own and on the
				 * law's elastic branch: no lane to tell apart. */
				if (o.history || o.damage || o.friction)
					bonds_add_elastic(e, b0, &L, &o, nq, s, 1);
				else
					bonds_add_elastic(e, b0, &L, &o, nq, s, 0);
				continue;
			}
			int q = 0;
			for (size_t b = b0; b < b1; b++) {
				if ((size_t)rec[b].j >= p1)
					bond_add(e, b, &S->part[slot++], measure, s, 0);
				else if (fused && o.elastic[q])
					bond_add_fused(e, b, &o, q++, s);
				else
					bond_add(e, b, &part[q++], measure, s, 1);
			}
		}
		e->scratch.bblock[blk] = sums;
		done(e, blk, ctx);
		/* The block's sums used: zero again for the next step, while
		 * in the cache (rather than all the share's before its bonds). */
		size_t lo = blk * BLOCK > p0 ? blk * BLOCK : p0,
		       end = (blk + 1) * BLOCK < p1 ? (blk + 1) * BLOCK : p1;
		memset(engine_acc(e, lo), 0, 6 * (end - lo) * sizeof *e->scratch.acc);
	}
}

/* A share's bond reaching past its particles (up to p1) as a crossing
 * slot, its index counted from base: the first bond of the particles whose
 * slots are listed, so that it fits the slot's 32 bits however many bonds
 * the whole specimen has over the ranks. */
typedef struct {
	bond_split *S;
	size_t p1, cap, base;
} cross_ctx;

static void add_cross(void *ctx, size_t b, int32_t i, int32_t j)
{
	cross_ctx *c = ctx;
	bond_split *S = c->S;
	if ((size_t)j < c->p1)
		return;
	if (S->ncross == c->cap) {
		c->cap = c->cap ? 2 * c->cap : 1024;
		S->cross = xrealloc(S->cross, c->cap * sizeof *S->cross);
		S->ci = xrealloc(S->ci, c->cap * sizeof *S->ci);
		S->cj = xrealloc(S->cj, c->cap * sizeof *S->cj);
	}
	S->cross[S->ncross] = (int32_t)(b - c->base);
	S->ci[S->ncross] = i;
	S->cj[S->ncross++] = j;
}

/* The crossing bonds of the shares [s0, s1) as slots, in bond order, each
 * counted from the first bond of share s0. */
static void cross_slots(engine *e, int s0, int s1)
{
	bond_split *S = &e->pairs.split;
	cross_ctx c = {S, 0, 0, S->bfirst[nblocks(S->pfirst[s0])]};
	for (int k = s0; k < s1; k++) {
		S->cfirst[k] = S->ncross;
		c.p1 = S->pfirst[k + 1];
		each_bond(e, S->pfirst[k], c.p1, add_cross, &c);
	}
	S->cfirst[s1] = S->ncross;
}

/* The bonds across the start of each particle block (crossing bonds if a
 * share began there): span[b], b <= nblk, counts those (i, j) with
 * i < b BLOCK <= j, over the ranks. */
typedef struct {
	uint64_t *from, *past; /* [nblk + 2] */
} span_ctx;

static void span_one(void *ctx, size_t b, int32_t i, int32_t j)
{
	span_ctx *c = ctx;
	(void)b;
	c->from[i / BLOCK + 1]++;
	c->past[j / BLOCK + 1]++;
}

static uint64_t *crossing_span(engine *e, size_t nblk)
{
	span_ctx c = {xcalloc(nblk + 2, sizeof *c.from), xcalloc(nblk + 2, sizeof *c.past)};
	size_t p0, p1;
	int split = ranks_own(e, &p0, &p1);
	each_bond(e, p0, p1, span_one, &c);
	if (split) {
		par_sum_u64(c.from, nblk + 2);
		par_sum_u64(c.past, nblk + 2);
	}
	uint64_t open = 0;
	for (size_t b = 0; b <= nblk; b++) {
		open += c.from[b] - c.past[b];
		c.from[b] = open;
	}
	free(c.past);
	return c.from;
}

/* The work of share k - 1 of split_blocks ending at block b, from block
 * a, less its part f of the work left, taking the ends left to cross as
 * many bonds as b (m shares left, of weight w out of the left's). */
static double share_excess(const double *before, const uint64_t *span, size_t nblk, size_t a,
                           size_t b, int m, double w, double left)
{
	double cross = (double)span[b];
	return before[b] - before[a] + cross -
	       (before[nblk] - before[a] + (m - 1) * cross) * w / left;
}

/* The first particles of shares 1 .. shares - 1 into pfirst, and the work
 * of each share into work: whole particle blocks, at least one a share,
 * the work in proportion to weight (NULL: equal). A share's work is taken
 * as its particles and bonds (a bond costs about as much as a particle's
 * step) and the bonds that cross its end, once more: such a bond is
 * computed apart, before the barrier of the step (bonds_cross), its force
 * kept and added later on its own, and the batch it leaves has a gap,
 * which takes the slower way. Each end is the block boundary nearest to
 * the share's part of the work left (not the first past it, which made
 * the first share the heaviest by up to a block). */
static void split_blocks(engine *e, int shares, const double *weight, size_t *pfirst, double *work)
{
	const size_t *bfirst = e->pairs.split.bfirst;
	size_t n = e->p.n, nblk = nblocks(n);
	/* before[b]: the work of the blocks before b. */
	double *before = xmalloc((nblk + 1) * sizeof *before);
	for (size_t b = 0; b < nblk; b++)
		before[b] = (double)(bfirst[b] + b * BLOCK);
	before[nblk] = (double)(e->pairs.nbonds + n);
	uint64_t *span = shares > 1 ? crossing_span(e, nblk) : NULL;
	double left = 0;
	for (int k = 0; k < shares; k++)
		left += weight ? weight[k] : 1;
	for (int k = 1; k < shares; k++) {
		int m = shares - k + 1;
		double w = weight ? weight[k - 1] : 1;
		size_t a = pfirst[k - 1] / BLOCK, last = nblk - (size_t)(shares - k), b = a + 1;
		while (b < last && share_excess(before, span, nblk, a, b, m, w, left) < 0)
			b++;
		if (b > a + 1 && -share_excess(before, span, nblk, a, b - 1, m, w, left) <
		                     share_excess(before, span, nblk, a, b, m, w, left))
			b--;
		left -= w;
		pfirst[k] = b * BLOCK;
		work[k - 1] = before[b] - before[a] + (double)span[b];
	}
	work[shares - 1] = before[nblk] - before[pfirst[shares - 1] / BLOCK];
	free(before);
	free(span);
}

/* bonds_split with each share's work in proportion to weight (NULL:
 * equal). */
static void split_weighted(engine *e, int shares, const double *weight)
{
	bond_split *S = &e->pairs.split;
	size_t n = e->p.n, nblk = nblocks(n), nb = e->pairs.nbonds;
	uint8_t *staged = S->staged;
	S->staged = NULL;
	bonds_split_free(S);
	S->staged = staged;
	S->bfirst = xmalloc((nblk + 1) * sizeof *S->bfirst);
	const bond_search *f = &e->pairs.formed;
	const pairlist *L = &e->pairs.bonds;
	for (size_t blk = 0, b = 0; blk <= nblk; blk++) {
		while (!f->bfirst && b < nb && (size_t)L->rec[b].i < blk * BLOCK)
			b++;
		S->bfirst[blk] = f->bfirst ? f->bfirst[blk] : b;
	}
	/* Shares of about equal work, in whole particle blocks. */
	if ((size_t)shares > nblk)
		shares = (int)nblk;
	if (shares < 1)
		shares = 1;
	S->n = shares;
	S->pfirst = xmalloc(((size_t)shares + 1) * sizeof *S->pfirst);
	S->cfirst = xmalloc(((size_t)shares + 1) * sizeof *S->cfirst);
	S->work = xmalloc((size_t)shares * sizeof *S->work);
	S->pfirst[0] = 0;
	split_blocks(e, shares, weight, S->pfirst, S->work);
	S->pfirst[shares] = n;
	/* Every share's crossing bonds, in bond order (bonds_own keeps this
	 * rank's), where this rank holds every particle; else each rank finds
	 * its own shares' (bonds_own). */
	memset(S->cfirst, 0, ((size_t)shares + 1) * sizeof *S->cfirst);
	if (!e->p.glob)
		cross_slots(e, 0, shares);
	share_balance *B = &e->pairs.balance;
	if (B->n != shares) {
		share_balance_free(B);
		B->n = shares;
		B->busy = xcalloc((size_t)shares, sizeof *B->busy);
		B->busy_run = xcalloc((size_t)shares, sizeof *B->busy_run);
		const char *t = getenv("DEM_BALANCE_TEST");
		B->test = t && *t && strcmp(t, "0") != 0;
		rng_seed(&B->gen, 1);
	}
}

void bonds_split(engine *e, int shares) { split_weighted(e, shares, NULL); }

/* The steps between looks at the shares' times (about a second of a
 * 70 000-sphere specimen: long enough to average out the steps' jitter,
 * short enough to follow a core that slows down), and the gain in the
 * step's time that moves their ends (a split again costs about half a
 * step). */
enum { BALANCE_STEPS = 200, BALANCE_TEST_STEPS = 3 };
static const double BALANCE_GAIN = 0.03;

void bonds_balance(engine *e)
{
	bond_split *S = &e->pairs.split;
	share_balance *B = &e->pairs.balance;
	int n = S->n;
	if (n < 2 || e->ranks.size > 1 || B->n != n ||
	    ++B->steps < (B->test ? BALANCE_TEST_STEPS : BALANCE_STEPS))
		return;
	/* Each share's speed, its work over its time; the step's time now,
	 * that of the slowest, and if each took a part of the work in
	 * proportion to its speed. */
	double *speed = xmalloc((size_t)n * sizeof *speed), sum = 0, work = 0, slowest = 0;
	for (int k = 0; k < n; k++) {
		speed[k] = B->busy[k] > 0 ? S->work[k] / B->busy[k] : 0;
		sum += speed[k];
		work += S->work[k];
		slowest = B->busy[k] > slowest ? B->busy[k] : slowest;
		B->busy_run[k] += B->busy[k];
		B->busy[k] = 0;
	}
	B->steps = 0;
	int move = sum > 0 && work / sum < (1 - BALANCE_GAIN) * slowest;
	for (int k = 0; move && k < n; k++)
		move = speed[k] > 0;
	if (B->test) {
		for (int k = 0; k < n; k++)
			speed[k] = rng_range(&B->gen, 0.1, 1);
		move = 1;
	}
	if (move) {
		split_weighted(e, n, speed);
		bonds_own(e, 0, n);
		B->resplits++;
	}
	free(speed);
}

/* The steps of a window, the windows of a trial (with and without in
 * turn; each way's quickest window counts, which a slower spell of the
 * machine, only ever adding time, leaves alone), the steps before the
 * first trial (the first steps touch memory for the first time) and
 * between trials. */
enum { TUNE_WINDOW = 25, TUNE_WINDOWS = 8, TUNE_FIRST = 50, TUNE_EVERY = 5000 };

int bonds_prefetch_setup(engine *e)
{
	const char *v = getenv("DEM_PREFETCH");
	prefetch_tune *P = &e->pairs.prefetch;
	*P = (prefetch_tune){0};
	if (!v || !*v)
		return 0;
	if (strcmp(v, "on") && strcmp(v, "off"))
		return err_set("DEM_PREFETCH=%s: expected on or off (unset: timed choice)", v);
	*P = (prefetch_tune){.fixed = 1, .off = !strcmp(v, "off")};
	return 0;
}

void bonds_tune_prefetch(engine *e, double seconds)
{
	prefetch_tune *P = &e->pairs.prefetch;
	if (P->fixed)
		return;
	P->steps++;
	if (!P->window) {
		if (P->steps >= (P->trials ? TUNE_EVERY : TUNE_FIRST))
			*P = (prefetch_tune){.window = 1, .trials = P->trials};
		return;
	}
	P->now += seconds;
	if (P->steps < TUNE_WINDOW)
		return;
	double *best = &P->best[P->off];
	*best = *best > 0 && *best < P->now ? *best : P->now;
	P->now = 0;
	P->steps = 0;
	if (P->window++ < TUNE_WINDOWS) {
		P->off = !P->off;
		return;
	}
	P->off = P->best[1] < P->best[0];
	P->window = 0;
	P->trials++;
}

void share_balance_free(share_balance *b)
{
	free(b->busy), free(b->busy_run);
	memset(b, 0, sizeof *b);
}

/* Slot c's share in [s0, s1) by its particle j, or -1. */
static int slot_share(const bond_split *S, size_t c, int s0, int s1)
{
	if ((size_t)S->cj[c] < S->pfirst[s0] || (size_t)S->cj[c] >= S->pfirst[s1])
		return -1;
	return run_of(S->pfirst, S->n, (size_t)S->cj[c]);
}

void bonds_own(engine *e, int s0, int s1)
{
	bond_split *S = &e->pairs.split;
	size_t p0 = S->pfirst[s0], p1 = S->pfirst[s1];
	size_t b0 = S->bfirst[nblocks(p0)], b1 = S->bfirst[nblocks(p1)];
	/* With several ranks, each finds its shares' slots (the search holds
	 * its particles and those within the bond range), and receives the
	 * incoming ones from the ranks of their i. */
	int64_t *in = NULL;
	size_t nin = 0;
	if (e->p.glob) {
		cross_slots(e, s0, s1);
		nin = ranks_incoming(e, &in);
	}
	size_t c0 = S->cfirst[s0], c1 = S->cfirst[s1];
	/* The slots of the shares [s0, s1), then the incoming ones: the earlier
	 * shares' (bond order) whose j is in [p0, p1). */
	size_t m = c1 - c0 + nin;
	for (size_t c = 0; c < c0; c++)
		m += (size_t)S->cj[c] >= p0 && (size_t)S->cj[c] < p1;
	int32_t *cross = xmalloc((m + 1) * sizeof *cross), *ci = xmalloc((m + 1) * sizeof *ci),
	        *cj = xmalloc((m + 1) * sizeof *cj);
	/* The slots count their bonds from the first of the shares that
	 * cross_slots listed: this rank's (b0), or where it holds every
	 * particle, the specimen's. */
	int32_t from = e->p.glob ? 0 : (int32_t)b0;
	m = 0;
	for (size_t c = c0; c < c1; c++, m++) {
		cross[m] = S->cross[c] - from;
		ci[m] = S->ci[c];
		cj[m] = S->cj[c];
	}
	for (size_t c = 0; c < c0; c++)
		if ((size_t)S->cj[c] >= p0 && (size_t)S->cj[c] < p1) {
			cross[m] = -1;
			ci[m] = S->ci[c];
			cj[m++] = S->cj[c];
		}
	for (size_t q = 0; q < nin; q++, m++) {
		int64_t i = window_local(&e->p, (size_t)in[3 * q + 1]),
		        j = window_local(&e->p, (size_t)in[3 * q + 2]);
		if (i < 0 || j < 0)
			fatal("bonds_own: bond %" PRId64 " between particles %" PRId64
			      " and %" PRId64 " not held (an internal error)",
			      in[3 * q], in[3 * q + 1], in[3 * q + 2]);
		cross[m] = -1;
		ci[m] = (int32_t)i;
		cj[m] = (int32_t)j;
	}
	free(in);
	free(S->cross), free(S->ci), free(S->cj);
	S->cross = cross, S->ci = ci, S->cj = cj;
	S->ncross = m;
	for (int k = 0; k <= S->n; k++)
		S->cfirst[k] = k < s0 ? 0 : k > s1 ? c1 - c0 : S->cfirst[k] - c0;
	S->part = xrealloc(S->part, (m + 1) * sizeof *S->part);
	/* Each share's incoming slots in bond order: the earlier ranks' first,
	 * then this rank's earlier shares'. A share scans only its own,
	 * however many shares (and ranks) there are. */
	free(S->infirst), free(S->in);
	S->infirst = xcalloc((size_t)S->n + 2, sizeof *S->infirst);
	S->in = xmalloc((m + 1) * sizeof *S->in);
	size_t own = c1 - c0;
	for (size_t c = 0; c < m; c++) {
		int k = slot_share(S, c, s0, s1);
		if (k >= 0)
			S->infirst[k + 2]++;
	}
	for (int k = 0; k < S->n; k++)
		S->infirst[k + 2] += S->infirst[k + 1];
	for (size_t q = 0; q < m; q++) {
		size_t c = q < m - own ? own + q : q - (m - own);
		int k = slot_share(S, c, s0, s1);
		if (k >= 0)
			S->in[S->infirst[k + 1]++] = (int32_t)c;
	}
	bonds_keep(e, p0, p1, b0, b1);
	if (!S->staged)
		S->staged = xcalloc(e->pairs.bonds.n + 1, sizeof *S->staged);
}

void bonds_split_free(bond_split *s)
{
	free(s->pfirst), free(s->cfirst), free(s->cross), free(s->ci), free(s->cj), free(s->part);
	free(s->bfirst), free(s->infirst), free(s->in), free(s->staged), free(s->work);
	memset(s, 0, sizeof *s);
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
		int64_t b = cb->bond[k];
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
