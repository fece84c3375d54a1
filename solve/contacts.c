/* Non-bonded contacts: a Verlet list of the pairs that are not bonded and
 * closer than r_i + r_j + skin, built from a cell grid and rebuilt only when
 * some particle has moved more than half the skin since the last build (so
 * no pair can come into contact unseen). Each pair is a Cundall–Strack
 * contact (laws/cundall.h) about d0 = r_i + r_j (with Yade's
 * conventions, about the distance at which it started); its shear
 * history and d0 survive rebuilds by merging the old and new lists, both
 * sorted by (i, j). */
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "solve/blocks.h"
#include "solve/cells.h"
#include "solve/contacts.h"
#include "solve/engine.h"
#include "solve/kinematics.h"
#include "solve/laws/contact.h"
#include "solve/laws/cundall.h"
#include "solve/pairlist.h"
#include "solve/platens.h"
#include "solve/ranks.h"

/* Whether the pair (a, b) comes before (i, j) in pair order. */
static int before(int32_t a, int32_t b, int32_t i, int32_t j) { return a < i || (a == i && b < j); }

/* The first of the n records rec, sorted by (i, j), that does not come
 * before (i, j). */
static size_t first_not_before(const pair_rec *rec, size_t n, int32_t i, int32_t j)
{
	size_t lo = 0;
	for (size_t hi = n; lo < hi;) {
		size_t mid = lo + (hi - lo) / 2;
		if (before(rec[mid].i, rec[mid].j, i, j))
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

/* Whether i < j are bonded: a binary search of this rank's bonds (those of
 * its particles i) or, for an earlier rank's i, of the incoming crossing
 * bonds (bonds.h), both sorted by (i, j). */
static int bonded(const engine *e, int32_t i, int32_t j)
{
	const pairlist *B = &e->pairs.bonds;
	const bond_split *S = &e->pairs.split;
	size_t p0, p1, lo, hi;
	ranks_own(e, &p0, &p1);
	if ((size_t)i >= p0) {
		lo = first_not_before(B->rec, B->n, i, j);
		return lo < B->n && B->rec[lo].i == i && B->rec[lo].j == j;
	}
	for (lo = S->cfirst[S->n], hi = S->ncross; lo < hi;) {
		size_t mid = lo + (hi - lo) / 2;
		if (before(S->ci[mid], S->cj[mid], i, j))
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo < S->ncross && S->ci[lo] == i && S->cj[lo] == j;
}

/* Room for n pairs, and the gather index of this rank's particles. */
static void reserve(const engine *e, pairlist *l, size_t n)
{
	if (n <= l->cap && l->off)
		return;
	size_t cap = l->cap > n ? l->cap : n + n / 8 + 64; /* an eighth to grow into */
	l->rec = pairlist_records(l->rec, l->n, cap);
	l->f = xrealloc(l->f, 6 * cap * sizeof *l->f);
	l->ref = xrealloc(l->ref, 2 * cap * sizeof *l->ref);
	if (!l->off) {
		size_t p0, p1;
		ranks_own(e, &p0, &p1);
		l->off = window_array(p0, p1 + 1, sizeof *l->off);
		l->off0 = p0;
	}
	l->cap = cap;
}

/* The contact (i, j) into c, with the shear history and start of the same
 * pair in the old list, which *o walks along (it is the first old pair
 * not before the previous one). */
static void new_contact(const engine *e, pair_rec *c, const pairlist *old, size_t *o, int32_t i,
                        int32_t j)
{
	const particles *P = &e->p;
	memset(c, 0, sizeof *c);
	c->i = i;
	c->j = j;
	c->d0 = P->r[i] + P->r[j];
	while (*o < old->n && before(old->rec[*o].i, old->rec[*o].j, i, j))
		(*o)++;
	if (*o < old->n && old->rec[*o].i == i && old->rec[*o].j == j) {
		memcpy(c->t, old->rec[*o].t, sizeof c->t);
		c->d0 = old->rec[*o].d0;
	}
	contact_constants(&e->cs->mat, e->lp, P->r[i], P->r[j], P->m[i], P->m[j], c->d0, c->h);
}

void contacts_index_blocks(engine *e)
{
	const pairlist *L = &e->pairs.contacts;
	size_t nb = nblocks(e->p.n);
	for (size_t blk = 0, c = 0; blk <= nb; blk++) {
		while (c < L->n && (size_t)L->rec[c].i < blk * BLOCK)
			c++;
		e->scratch.cfirst[blk] = c;
	}
}

/* The particles a rank's search looks at: with several ranks its own and
 * its ghosts (ranks_share_ghosts, which the window then holds, window.h),
 * in increasing order, their positions and radii copied to x and r; with
 * one, all of them in place. */
typedef struct {
	size_t n;
	int32_t *idx; /* index of each in the window, or NULL: all particles */
	const double *x, *r;
	double *xb, *rb;
} search_set;

/* A ghost's row (ranks_share_ghosts) into the particle arrays: its index
 * there. */
static int32_t ghost_place(particles *P, const double *row)
{
	size_t g = (size_t)row[0];
	size_t i = P->glob ? (size_t)window_local(P, g) : g;
	particle_set_row(P, i, row + 1);
	return (int32_t)i;
}

static void search_set_make(engine *e, search_set *s)
{
	particles *P = &e->p;
	memset(s, 0, sizeof *s);
	if (e->ranks.size == 1) {
		s->n = P->n;
		s->x = P->x;
		s->r = P->r;
		return;
	}
	/* A pair within reach is closer than 2 r_max + skin along each axis;
	 * the margin covers the rounding of both tests. */
	double reach = (2 * e->frame.r_max + e->pairs.skin) * (1 + 1e-9);
	size_t p0 = e->ranks.p0, p1 = e->ranks.p1;
	double *gh;
	size_t ng = ranks_share_ghosts(e, reach, &gh);
	int32_t *want = xmalloc((ng + 1) * sizeof *want);
	for (size_t k = 0; k < ng; k++)
		want[k] = (int32_t)gh[GHOST_COLS * k];
	/* Once the run has started, the window holds the ghosts from now on
	 * (and the current contacts, renumbered, are the rebuild's old ones);
	 * before, every particle has its place. */
	if (P->glob)
		window_set(e, want, ng);
	s->idx = xmalloc((ng + p1 - p0 + 1) * sizeof *s->idx);
	size_t k = 0;
	while (k < ng && (size_t)want[k] < p0)
		s->idx[s->n++] = ghost_place(P, gh + GHOST_COLS * k++);
	for (size_t i = p0; i < p1; i++)
		s->idx[s->n++] = (int32_t)i;
	while (k < ng)
		s->idx[s->n++] = ghost_place(P, gh + GHOST_COLS * k++);
	free(want), free(gh);
	s->xb = xmalloc((3 * s->n + 1) * sizeof *s->xb);
	s->rb = xmalloc((s->n + 1) * sizeof *s->rb);
	for (size_t a = 0; a < s->n; a++) {
		memcpy(s->xb + 3 * a, P->x + 3 * (size_t)s->idx[a], 3 * sizeof *s->xb);
		s->rb[a] = P->r[s->idx[a]];
	}
	s->x = s->xb;
	s->r = s->rb;
}

static void search_set_free(search_set *s) { free(s->idx), free(s->xb), free(s->rb); }

/* A thread's run of the search: the pairs (i, j) it found, in order, as
 * ij[2 q], ij[2 q + 1]; where they go in the list; and the set's entry a
 * with too many neighbours (SIZE_MAX: none). */
enum { CONTACTS_CAP = 4096 };
typedef struct {
	int32_t *ij;
	size_t n, cap, first, a;
} found_pairs;

static void found_add(found_pairs *f, int32_t i, int32_t j)
{
	if (f->n == f->cap) {
		f->cap = f->cap ? 2 * f->cap : 1024;
		f->ij = xrealloc(f->ij, 2 * f->cap * sizeof *f->ij);
	}
	f->ij[2 * f->n] = i;
	f->ij[2 * f->n++ + 1] = j;
}

/* The pairs within reach of the set s (grid g) that a rank with the
 * particles [p0, p1) lists, unbonded, those of its particles i and of
 * earlier ranks' i with its own j: a run of the set's particles i for each
 * of the step's threads (e->team runs, in order), each listing its pairs
 * in pair order, so the runs one after the other are the pairs in pair
 * order whatever the number of threads. */
static found_pairs *search_pairs(const engine *e, const search_set *s, const cells *g, size_t p0,
                                 size_t p1)
{
	size_t na = 0; /* the set's particles i: those before p1 */
	while (na < s->n && (size_t)(s->idx ? s->idx[na] : (int32_t)na) < p1)
		na++;
	int team = e->team;
	found_pairs *runs = xcalloc((size_t)team, sizeof *runs);
	for (int t = 0; t < team; t++)
		runs[t].a = SIZE_MAX;
#pragma omp parallel num_threads(team)
	{
		int t = omp_get_thread_num(), nt = omp_get_num_threads();
		found_pairs *run = &runs[t];
		int32_t js[CONTACTS_CAP];
		size_t a1 = na * (size_t)(t + 1) / (size_t)nt;
		for (size_t a = na * (size_t)t / (size_t)nt; a < a1; a++) {
			size_t i = s->idx ? (size_t)s->idx[a] : a;
			int nj =
			    cells_partners(g, s->x, s->r, a, 1, e->pairs.skin, js, CONTACTS_CAP);
			if (nj < 0) { /* reported after the search */
				run->a = a;
				break;
			}
			for (int q = 0; q < nj; q++) {
				int32_t j = s->idx ? s->idx[js[q]] : js[q];
				if ((i >= p0 || ((size_t)j >= p0 && (size_t)j < p1)) &&
				    !bonded(e, (int32_t)i, j))
					found_add(run, (int32_t)i, j);
			}
		}
	}
	for (int t = 0; t < team; t++)
		if (runs[t].a != SIZE_MAX) {
			size_t a = runs[t].a, i = s->idx ? (size_t)s->idx[a] : a;
			fatal("particle %d has more than %d neighbours within its reach: "
			      "overlapping spheres?",
			      e->p.orig[i], CONTACTS_CAP);
		}
	return runs;
}

/* The list L of the pairs of the runs (search_pairs, released), each run's
 * records made on a thread of its own. */
static void contacts_from(engine *e, pairlist *L, const pairlist *old, found_pairs *runs)
{
	int team = e->team;
	size_t total = 0;
	for (int t = 0; t < team; t++) {
		runs[t].first = total;
		total += runs[t].n;
	}
	reserve(e, L, total);
	L->n = total;
#pragma omp parallel for num_threads(team) schedule(static, 1)
	for (int t = 0; t < team; t++) {
		const found_pairs *run = &runs[t];
		size_t o = run->n ? first_not_before(old->rec, old->n, run->ij[0], run->ij[1]) : 0;
		for (size_t q = 0; q < run->n; q++)
			new_contact(e, &L->rec[run->first + q], old, &o, run->ij[2 * q],
			            run->ij[2 * q + 1]);
	}
	for (int t = 0; t < team; t++)
		free(runs[t].ij);
	free(runs);
}

void contacts_rebuild(engine *e)
{
	particles *P = &e->p;
	search_set s;
	search_set_make(e, &s);
	pairlist tmp = e->pairs.contacts_old;
	e->pairs.contacts_old = e->pairs.contacts;
	e->pairs.contacts = tmp;
	pairlist *L = &e->pairs.contacts;
	const pairlist *old = &e->pairs.contacts_old;
	L->n = 0;
	reserve(e, L, 0);
	/* A rank lists the pairs of its particles i and, before them, those of
	 * earlier ranks' particles i with its own j (whose forces it receives,
	 * ranks.h): every pair with an end of its own, as one process lists
	 * them. */
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	cells *g = &e->pairs.grid;
	cells_build(g, s.x, s.n, 2 * e->frame.r_max + e->pairs.skin);
	contacts_from(e, L, old, search_pairs(e, &s, g, p0, p1));
	search_set_free(&s);
	pairlist_csr(L, p0, p1); /* the forces gathered by this rank's particles */
	contacts_index_blocks(e);
	memcpy(P->x_ref + 3 * (p0 - P->own0), P->x + 3 * p0, 3 * (p1 - p0) * sizeof *P->x);
	platens_rebuild(e);
	ranks_contacts(e);
	e->pairs.rebuilds++;
	e->pairs.rebuild = 0;
}

void contacts_restore(engine *e)
{
	pairlist *L = &e->pairs.contacts;
	const rank_split *R = &e->ranks;
	if (R->size > 1) {
		size_t m = 0;
		for (size_t c = 0; c < L->n; c++) {
			size_t i = (size_t)L->rec[c].i, j = (size_t)L->rec[c].j;
			if ((i >= R->p0 && i < R->p1) || (j >= R->p0 && j < R->p1)) {
				L->rec[m] = L->rec[c];
				memcpy(L->f + 6 * m++, L->f + 6 * c, 6 * sizeof *L->f);
			}
		}
		L->n = m;
	}
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	/* The gather index's offsets, which no search has made at a restart
	 * (its pairs' room is read_pairs', checkpoint.c). */
	if (!L->off) {
		L->off = window_array(p0, p1 + 1, sizeof *L->off);
		L->off0 = p0;
	}
	pairlist_csr(L, p0, p1);
	contacts_index_blocks(e);
	ranks_contacts(e);
}

DEM_VECTOR_CLONES static void contact_block(engine *e, size_t lo, size_t hi, int measure,
                                            pair_sums *s)
{
	const particles *P = &e->p;
	pairlist *L = &e->pairs.contacts;
	double mu = e->cs->mat.friction;
	int yade = e->cs->mat.conventions == CONTACT_YADE;
	law_batch B;
	batch_geom g;
	memset(s, 0, sizeof *s);
	for (size_t c0 = lo; c0 < hi; c0 += BATCH) {
		int nq = (int)(hi - c0 < BATCH ? hi - c0 : BATCH);
		pair_rec *rec = &L->rec[c0];
		batch_kinematics(P->x, P->v, P->w, P->r, P->m, rec, NULL, NULL, NULL, nq,
		                 e->clock.dt, &B, &g);
		for (int q = 0; q < nq; q++) {
			size_t c = c0 + q;
			const double *k = rec[q].h;
			cundall cd = {.kn = k[0], .ks = k[1], .cn = k[2], .mu = mu};
			law_out out = {0};
			double dus[3] = {B.dus[0][q], B.dus[1][q], B.dus[2][q]};
			double *t = rec[q].t;
			for (int d = 0; d < 3; d++)
				t[d] = B.t[d][q];
			if (yade) {
				double rs = B.ri[q] + B.rj[q], u0 = rec[q].d0 - rs;
				if (!cundall_started(&u0, B.un[q] + u0)) {
					rec[q].d0 = rs + u0;
					B.un[q] = 0; /* as just touching: no force, no shear */
				}
			}
			cundall_force(&cd, B.un[q], B.vn[q], dus, t, &out);
			for (int d = 0; d < 3; d++)
				B.fs[d][q] = out.fs[d];
			B.fn[q] = out.fn;
			double *f = L->f + 6 * c;
			batch_force(&B, &g, q, f);
			s->e_friction += out.e_friction;
			s->e_viscous += out.fn_viscous * B.vn[q] * e->clock.dt;
			if (measure) {
				s->e_elastic += cundall_energy(&cd, B.un[q], t);
				love_add(s->love, &g, q, f);
				s->count[4] += B.un[q] < 0;
			}
		}
	}
}

/* In the blocks of their particle i, as the bonds (the same sums whatever
 * the shares), this rank's blocks (ranks.h); the blocks hold very
 * different numbers of contacts, so they are handed out a few at a time. */
void contacts_forces(engine *e, int measure)
{
	size_t b0 = e->ranks.blk0, b1 = e->ranks.blk1;
	const size_t *first = e->scratch.cfirst;
#pragma omp for schedule(dynamic, 4)
	for (size_t k = b0; k < b1; k++)
		contact_block(e, first[k], first[k + 1], measure, &e->scratch.cblock[k]);
}
