/* The particles split among the ranks, and what crosses between them
 * (ranks.h). With one rank, everything here but the split is a no-op. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef DEM_MPI
#include <mpi.h>
#endif

#include "lib/err.h"
#include "lib/timer.h"
#include "solve/blocks.h"
#include "solve/bonds.h"
#include "solve/engine.h"
#include "solve/par.h"
#include "solve/ranks.h"

/* The rank of particle p (ranks may be empty). */
static int rank_of(const rank_split *R, size_t p) { return run_of(R->pfirst, R->size, p); }

static void link_add(rank_links *ls, int peer, size_t idx)
{
	rank_link *l = NULL;
	for (int k = 0; k < ls->n && !l; k++)
		if (ls->l[k].peer == peer)
			l = &ls->l[k];
	if (!l) {
		ls->l = xrealloc(ls->l, ((size_t)ls->n + 1) * sizeof *ls->l);
		l = &ls->l[ls->n++];
		*l = (rank_link){.peer = peer};
	}
	if (l->n == l->cap) {
		l->cap = l->cap ? 2 * l->cap : 64;
		l->idx = xrealloc(l->idx, l->cap * sizeof *l->idx);
	}
	l->idx[l->n++] = idx;
}

static void links_free(rank_links *ls)
{
	for (int k = 0; k < ls->n; k++)
		free(ls->l[k].idx), free(ls->l[k].buf);
	free(ls->l);
	memset(ls, 0, sizeof *ls);
}

/* Empty the links, keeping their peers' buffers for reuse. */
static void links_clear(rank_links *ls)
{
	for (int k = 0; k < ls->n; k++)
		ls->l[k].n = 0;
}

/* Buffers of `width` doubles per entry. */
static void links_buffers(rank_links *ls, size_t width)
{
	for (int k = 0; k < ls->n; k++)
		ls->l[k].buf =
		    xrealloc(ls->l[k].buf, (width * ls->l[k].n + 1) * sizeof *ls->l[k].buf);
}

static int cmp_size(const void *a, const void *b)
{
	size_t x = *(const size_t *)a, y = *(const size_t *)b;
	return (x > y) - (x < y);
}

/* The halo links h from the crossing bonds' links b and contacts' links c:
 * for each peer, the particles j of those pairs, each once, in increasing
 * order (so the sender's list and the receiver's match). */
static void halo_links(const engine *e, const rank_links *b, const rank_links *c, rank_links *h)
{
	const pair_rec *crec = e->pairs.contacts.rec;
	const int32_t *cj = e->pairs.split.cj;
	links_clear(h);
	for (int k = 0; k < b->n; k++)
		for (size_t q = 0; q < b->l[k].n; q++)
			link_add(h, b->l[k].peer, (size_t)cj[b->l[k].idx[q]]);
	for (int k = 0; k < c->n; k++)
		for (size_t q = 0; q < c->l[k].n; q++)
			link_add(h, c->l[k].peer, (size_t)crec[c->l[k].idx[q]].j);
	for (int k = 0; k < h->n; k++) {
		rank_link *l = &h->l[k];
		qsort(l->idx, l->n, sizeof *l->idx, cmp_size);
		size_t m = 0;
		for (size_t q = 0; q < l->n; q++)
			if (!m || l->idx[q] != l->idx[m - 1])
				l->idx[m++] = l->idx[q];
		l->n = m;
	}
	links_buffers(h, 9);
}

/* The particles this rank held in setup, [own0, own1) of its share of the
 * order (order.h), sent to the ranks that own them now (R->pfirst): its
 * window becomes its own particles. Collective. */
static void move_particles(engine *e)
{
	rank_split *R = &e->ranks;
	particles *P = &e->p;
	size_t q0 = P->own0, q1 = P->own1;
	double *rows = xmalloc((PARTICLE_ROW * (q1 - q0) + 1) * sizeof *rows);
	size_t *count = xcalloc((size_t)R->size, sizeof *count);
	for (size_t i = q0; i < q1; i++) {
		particle_row(P, i, rows + PARTICLE_ROW * (i - q0));
		count[rank_of(R, i)]++;
	}
	size_t n = P->n;
	particles_free(P);
	double *got;
	size_t m = par_alltoall_rows(rows, count, PARTICLE_ROW * sizeof *rows, (void **)&got);
	free(rows), free(count);
	if (m != R->p1 - R->p0)
		fatal("ranks_split: %zu particles received for %zu (an internal error)", m,
		      R->p1 - R->p0);
	particles_alloc_own(P, n, R->p0, R->p1);
	for (size_t i = R->p0; i < R->p1; i++)
		particle_set_row(P, i, got + PARTICLE_ROW * (i - R->p0));
	free(got);
}

size_t ranks_incoming(const engine *e, int64_t **in)
{
	const rank_split *R = &e->ranks;
	const bond_split *S = &e->pairs.split;
	const particles *P = &e->p;
	int64_t *rows = xmalloc((3 * S->ncross + 1) * sizeof *rows);
	int *to = xmalloc((S->ncross + 1) * sizeof *to);
	/* The slots count their bonds from the first of this rank's shares
	 * (cross_slots, bonds.c). */
	int64_t base = (int64_t)S->bfirst[nblocks(S->pfirst[R->s0])];
	for (size_t c = 0; c < S->ncross; c++) {
		int64_t *row = rows + 3 * c;
		row[0] = base + S->cross[c];
		row[1] = (int64_t)particle_global(P, (size_t)S->ci[c]);
		row[2] = (int64_t)particle_global(P, (size_t)S->cj[c]);
		to[c] = rank_of(R, (size_t)row[2]);
		to[c] = to[c] == R->rank ? -1 : to[c];
	}
	size_t m = par_send_rows(rows, to, S->ncross, 3 * sizeof *rows, (void **)in);
	free(rows), free(to);
	return m;
}

size_t ranks_share_pairs(const engine *e, const pair_rec *rec, size_t n, pair_rec **in)
{
	const rank_split *R = &e->ranks;
	int *to = xmalloc((n + 1) * sizeof *to);
	for (size_t c = 0; c < n; c++) {
		to[c] = rank_of(R, (size_t)rec[c].j);
		to[c] = to[c] == R->rank ? -1 : to[c];
	}
	size_t m = par_send_rows(rec, to, n, sizeof *rec, (void **)in);
	free(to);
	return m;
}

/* The arrays only a rank's own particles need (the positions at the last
 * rebuild, the sums of the bond forces), made for its own particles (all
 * of them with one rank), whose range a split may change. */
static void keep_own(engine *e)
{
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	particles *P = &e->p;
	P->own0 = p0;
	P->own1 = p1;
	free(P->x_ref), free(e->scratch.acc);
	P->x_ref = xcalloc(3 * (p1 - p0) + 1, sizeof *P->x_ref);
	e->scratch.acc = xcalloc(6 * (p1 - p0) + 1, sizeof *e->scratch.acc);
}

void ranks_split(engine *e)
{
	rank_split *R = &e->ranks;
	const bond_split *S = &e->pairs.split;
	/* In setup with several ranks each holds its share of the order
	 * (order.h) until here. */
	int moving = e->p.glob && e->pairs.formed.bfirst;
	ranks_free(R);
	R->size = par_size();
	R->rank = par_rank();
	const char *poison = getenv("DEM_RANKS_POISON");
	R->poison = poison && *poison && strcmp(poison, "0") != 0;
	R->pfirst = xmalloc(((size_t)R->size + 1) * sizeof *R->pfirst);
	for (int q = 0; q <= R->size; q++)
		R->pfirst[q] = S->pfirst[(size_t)q * (size_t)S->n / (size_t)R->size];
	R->s0 = (int)((size_t)R->rank * (size_t)S->n / (size_t)R->size);
	R->s1 = (int)((size_t)(R->rank + 1) * (size_t)S->n / (size_t)R->size);
	R->p0 = S->pfirst[R->s0];
	R->p1 = S->pfirst[R->s1];
	R->blk0 = nblocks(R->p0);
	R->blk1 = R->p1 > R->p0 ? nblocks(R->p1) : R->blk0;
	if (moving) {
		move_particles(e);
		bonds_search_grid(e);
	}
	bonds_own(e, R->s0, R->s1);
	/* This rank's crossing bonds whose j is another rank's send it their
	 * forces; the incoming ones receive theirs from the rank of their i.
	 * Both lists go in bond order, so sender's and receiver's match. */
	const particles *P = &e->p;
	for (size_t c = 0; c < S->ncross; c++) {
		int ri = rank_of(R, particle_global(P, (size_t)S->ci[c])),
		    rj = rank_of(R, particle_global(P, (size_t)S->cj[c]));
		if (ri == R->rank && rj != R->rank)
			link_add(&R->bsend, rj, c);
		else if (rj == R->rank && ri != R->rank)
			link_add(&R->brecv, ri, c);
	}
	links_buffers(&R->bsend, 6);
	links_buffers(&R->brecv, 6);
	keep_own(e);
}

void ranks_contacts(engine *e)
{
	rank_split *R = &e->ranks;
	if (R->size == 1)
		return;
	const pairlist *L = &e->pairs.contacts;
	links_clear(&R->csend);
	links_clear(&R->crecv);
	const particles *P = &e->p;
	for (size_t c = 0; c < L->n; c++) {
		int ri = rank_of(R, particle_global(P, (size_t)L->rec[c].i)),
		    rj = rank_of(R, particle_global(P, (size_t)L->rec[c].j));
		if (ri == rj)
			continue;
		if (ri == R->rank)
			link_add(&R->csend, rj, c);
		else if (rj == R->rank)
			link_add(&R->crecv, ri, c);
	}
	links_buffers(&R->csend, 6);
	links_buffers(&R->crecv, 6);
	/* The state this rank reads of the others' particles comes with its
	 * crossing pairs; that of its own the others read, with theirs. */
	halo_links(e, &R->bsend, &R->csend, &R->hrecv);
	halo_links(e, &R->brecv, &R->crecv, &R->hsend);
}

#ifdef DEM_MPI
enum { TAG_BONDS = 1, TAG_CONTACTS = 2, TAG_STATE = 3 };

/* Post the receives (or pack and post the sends) of links ls. */
static void post(rank_links *ls, int send, int tag, double *src, size_t stride, MPI_Request *req,
                 int *nreq)
{
	for (int k = 0; k < ls->n; k++) {
		rank_link *l = &ls->l[k];
		if (send) {
			for (size_t q = 0; q < l->n; q++)
				memcpy(l->buf + 6 * q, src + stride * l->idx[q],
				       6 * sizeof *l->buf);
			MPI_Isend(l->buf, (int)(6 * l->n), MPI_DOUBLE, l->peer, tag, MPI_COMM_WORLD,
			          &req[(*nreq)++]);
		} else {
			MPI_Irecv(l->buf, (int)(6 * l->n), MPI_DOUBLE, l->peer, tag, MPI_COMM_WORLD,
			          &req[(*nreq)++]);
		}
	}
}

static void unpack(const rank_links *ls, double *dst, size_t stride)
{
	for (int k = 0; k < ls->n; k++) {
		const rank_link *l = &ls->l[k];
		for (size_t q = 0; q < l->n; q++)
			memcpy(dst + stride * l->idx[q], l->buf + 6 * q, 6 * sizeof *l->buf);
	}
}
#endif

void ranks_exchange_forces(engine *e)
{
#ifdef DEM_MPI
	rank_split *R = &e->ranks;
	if (R->size == 1)
		return;
	double t0 = timer_now();
	int nreq = 0;
	MPI_Request *req =
	    xmalloc((size_t)(R->bsend.n + R->brecv.n + R->csend.n + R->crecv.n + 1) * sizeof *req);
	/* A crossing bond's part is a bond_part; its force is what j needs. */
	double *parts = (double *)e->pairs.split.part;
	const size_t pstride = sizeof(bond_part) / sizeof(double);
	_Static_assert(sizeof(bond_part) % sizeof(double) == 0 && offsetof(bond_part, f) == 0,
	               "bond_part: its force first, in doubles");
	post(&R->brecv, 0, TAG_BONDS, NULL, 0, req, &nreq);
	post(&R->crecv, 0, TAG_CONTACTS, NULL, 0, req, &nreq);
	post(&R->bsend, 1, TAG_BONDS, parts, pstride, req, &nreq);
	post(&R->csend, 1, TAG_CONTACTS, e->pairs.contacts.f, 6, req, &nreq);
	MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
	free(req);
	unpack(&R->brecv, parts, pstride);
	unpack(&R->crecv, e->pairs.contacts.f, 6);
	for (int k = 0; k < R->brecv.n; k++)
		R->recv_forces += 6.0 * sizeof(double) * (double)R->brecv.l[k].n;
	for (int k = 0; k < R->crecv.n; k++)
		R->recv_forces += 6.0 * sizeof(double) * (double)R->crecv.l[k].n;
	R->sec[RANKS_FORCES] += timer_now() - t0;
#else
	(void)e;
#endif
}

#ifdef DEM_MPI
/* Every rank's rows [first[q], first[q + 1]) of an array of rows of `row`
 * bytes gathered on rank root into base, or on every rank (ALL); this
 * rank's rows are at `mine` (base is read only where the rows gather). */
enum { ALL = -1 };
static double ngathers_;
static void gather_rows_from(const void *mine, void *base, const size_t *first, size_t row,
                             int size, int root)
{
	ngathers_++;
	int *cnt = xmalloc((size_t)size * sizeof *cnt), *dsp = xmalloc((size_t)size * sizeof *dsp);
	MPI_Datatype t;
	MPI_Type_contiguous((int)row, MPI_BYTE, &t);
	MPI_Type_commit(&t);
	for (int q = 0; q < size; q++) {
		cnt[q] = (int)(first[q + 1] - first[q]);
		dsp[q] = (int)first[q];
	}
	int rank = par_rank();
	if (root == ALL || rank == root) {
		char *place = (char *)base + first[rank] * row;
		if (place != mine)
			memmove(place, mine, (size_t)cnt[rank] * row);
	}
	if (root == ALL)
		MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, base, cnt, dsp, t,
		               MPI_COMM_WORLD);
	else if (rank == root)
		MPI_Gatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, base, cnt, dsp, t, root,
		            MPI_COMM_WORLD);
	else
		MPI_Gatherv(mine, cnt[rank], t, NULL, NULL, NULL, t, root, MPI_COMM_WORLD);
	MPI_Type_free(&t);
	free(cnt), free(dsp);
}

/* The same with this rank's rows in place in base. */
static void gather_rows(void *base, const size_t *first, size_t row, int size, int root)
{
	gather_rows_from((char *)base + first[par_rank()] * row, base, first, row, size, root);
}
#endif

/* The bytes of state (x, v, ω) of n particles. */
static double state_bytes(size_t n) { return 9.0 * sizeof(double) * (double)n; }

#ifdef DEM_MPI
/* The halo's state from its ranks, point to point; the others' particles
 * beyond it are stale (NaN when poisoned). */
static void share_halo(engine *e)
{
	rank_split *R = &e->ranks;
	particles *P = &e->p;
	double *const arr[3] = {P->x, P->v, P->w};
	double t0 = timer_now();
	MPI_Request *req = xmalloc((size_t)(R->hsend.n + R->hrecv.n + 1) * sizeof *req);
	int nreq = 0;
	/* A peer with an empty list on one side has one on the other. */
	for (int k = 0; k < R->hrecv.n; k++) {
		rank_link *l = &R->hrecv.l[k];
		if (l->n)
			MPI_Irecv(l->buf, (int)(9 * l->n), MPI_DOUBLE, l->peer, TAG_STATE,
			          MPI_COMM_WORLD, &req[nreq++]);
	}
	for (int k = 0; k < R->hsend.n; k++) {
		rank_link *l = &R->hsend.l[k];
		if (!l->n)
			continue;
		for (size_t q = 0; q < l->n; q++)
			for (int a = 0; a < 3; a++)
				memcpy(l->buf + 9 * q + 3 * a, arr[a] + 3 * l->idx[q],
				       3 * sizeof *l->buf);
		MPI_Isend(l->buf, (int)(9 * l->n), MPI_DOUBLE, l->peer, TAG_STATE, MPI_COMM_WORLD,
		          &req[nreq++]);
	}
	MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
	free(req);
	if (R->poison)
		for (size_t i = P->lo; i < P->hi; i++)
			if (i < R->p0 || i >= R->p1)
				for (int a = 0; a < 3; a++)
					for (int c = 0; c < 3; c++)
						arr[a][3 * i + c] = NAN;
	for (int k = 0; k < R->hrecv.n; k++) {
		const rank_link *l = &R->hrecv.l[k];
		for (size_t q = 0; q < l->n; q++)
			for (int a = 0; a < 3; a++)
				memcpy(arr[a] + 3 * l->idx[q], l->buf + 9 * q + 3 * a,
				       3 * sizeof *l->buf);
		R->recv_halo += state_bytes(l->n);
	}
	R->sec[RANKS_HALO] += timer_now() - t0;
}

#endif

void ranks_share_state(engine *e)
{
#ifdef DEM_MPI
	if (e->ranks.size > 1)
		share_halo(e);
#else
	(void)e;
#endif
}

#ifdef DEM_MPI
enum { TAG_GHOSTS = 4, TAG_VALUES = 5, TAG_CELLS = 6 };

/* Whether ranks p and q hold particles within `reach` of each other along
 * each axis, as far as their boxes (lo, hi: 6 doubles each) tell; the same
 * answer on both. */
static int ranks_near(const double *box, int p, int q, double reach)
{
	const double *a = box + 6 * (p < q ? p : q), *b = box + 6 * (p < q ? q : p);
	for (int k = 0; k < 3; k++)
		if (!(a[k] <= b[3 + k] + reach && a[3 + k] >= b[k] - reach))
			return 0;
	return 1;
}

/* Whether x lies within `reach` of the box b along each axis. */
static int in_reach(const double *x, const double *b, double reach)
{
	for (int k = 0; k < 3; k++)
		if (!(x[k] >= b[k] - reach && x[k] <= b[3 + k] + reach))
			return 0;
	return 1;
}

/* Cells of size h (the reach) over the boxes of every rank: two particles
 * within reach of each other lie in the same or adjacent cells. */
typedef struct {
	double lo[3], h;
	int64_t dim[3];
} ghost_grid;

static void ghost_grid_make(const double *box, int size, double h, ghost_grid *g)
{
	double hi[3];
	for (int k = 0; k < 3; k++)
		g->lo[k] = INFINITY, hi[k] = -INFINITY;
	for (int q = 0; q < size; q++)
		for (int k = 0; k < 3; k++) {
			g->lo[k] = fmin(g->lo[k], box[6 * q + k]);
			hi[k] = fmax(hi[k], box[6 * q + 3 + k]);
		}
	g->h = h;
	for (int k = 0; k < 3; k++)
		g->dim[k] = hi[k] >= g->lo[k] ? (int64_t)floor((hi[k] - g->lo[k]) / h) + 1 : 1;
}

static void cell_coords(const ghost_grid *g, const double *x, int64_t c[3])
{
	for (int k = 0; k < 3; k++) {
		double t = floor((x[k] - g->lo[k]) / g->h);
		c[k] = t >= 0 ? (t < (double)g->dim[k] ? (int64_t)t : g->dim[k] - 1) : 0;
	}
}

static int64_t cell_id(const ghost_grid *g, const int64_t c[3])
{
	return c[0] + g->dim[0] * (c[1] + g->dim[1] * c[2]);
}

static int cmp_i64(const void *a, const void *b)
{
	int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
	return (x > y) - (x < y);
}

/* Whether a cell next to x's (or x's own) is among the n sorted cells. */
static int next_to(const ghost_grid *g, const double *x, const int64_t *cells, size_t n)
{
	int64_t c[3], d[3];
	cell_coords(g, x, c);
	for (d[2] = c[2] - 1; d[2] <= c[2] + 1; d[2]++)
		for (d[1] = c[1] - 1; d[1] <= c[1] + 1; d[1]++)
			for (d[0] = c[0] - 1; d[0] <= c[0] + 1; d[0]++) {
				int inside = 1;
				for (int k = 0; k < 3; k++)
					inside = inside && d[k] >= 0 && d[k] < g->dim[k];
				int64_t id = cell_id(g, d);
				if (inside && bsearch(&id, cells, n, sizeof id, cmp_i64))
					return 1;
			}
	return 0;
}

/* Receive from `from` a message of `type` (item size `item` bytes), into
 * *buf (grown): its item count. */
static size_t receive_any(int from, int tag, MPI_Datatype type, size_t item, void **buf)
{
	MPI_Status st;
	int cnt;
	MPI_Probe(from, tag, MPI_COMM_WORLD, &st);
	MPI_Get_count(&st, type, &cnt);
	*buf = xrealloc(*buf, ((size_t)cnt + 1) * item);
	MPI_Recv(*buf, cnt, type, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
	return (size_t)cnt;
}
#endif

size_t ranks_share_ghosts(engine *e, double reach, double **ghosts)
{
#ifdef DEM_MPI
	rank_split *R = &e->ranks;
	*ghosts = NULL;
	if (R->size == 1)
		return 0;
	particles *P = &e->p;
	double t0 = timer_now();
	/* Every rank's box: 6 doubles each, the one collective. */
	double *box = xmalloc(6 * (size_t)R->size * sizeof *box), *mine = box + 6 * R->rank;
	for (int k = 0; k < 3; k++)
		mine[k] = INFINITY, mine[3 + k] = -INFINITY;
	for (size_t i = R->p0; i < R->p1; i++)
		for (int k = 0; k < 3; k++) {
			mine[k] = fmin(mine[k], P->x[3 * i + k]);
			mine[3 + k] = fmax(mine[3 + k], P->x[3 * i + k]);
		}
	MPI_Allgather(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, box, 6, MPI_DOUBLE, MPI_COMM_WORLD);
	ngathers_++;
	ghost_grid g;
	ghost_grid_make(box, R->size, reach, &g);
	/* The peers: the ranks whose boxes come within reach of this one's, in
	 * increasing order. */
	int *peer = xmalloc((size_t)R->size * sizeof *peer), np = 0;
	for (int q = 0; q < R->size; q++)
		if (q != R->rank && ranks_near(box, R->rank, q, reach))
			peer[np++] = q;
	MPI_Request *req = xmalloc((2 * (size_t)np + 1) * sizeof *req);
	void **out = xcalloc(2 * (size_t)np + 1, sizeof *out);
	int nreq = 0;
	/* First each peer learns the cells this rank's particles occupy near
	 * its box (two cells deep: a neighbour of its particle's cell). */
	for (int u = 0; u < np; u++) {
		const double *bq = box + 6 * peer[u];
		int64_t *cl = NULL;
		size_t m = 0, cap = 0;
		for (size_t i = R->p0; i < R->p1; i++)
			if (in_reach(P->x + 3 * i, bq, 2 * reach)) {
				int64_t c[3];
				cell_coords(&g, P->x + 3 * i, c);
				if (m == cap) {
					cap = cap ? 2 * cap : 1024;
					cl = xrealloc(cl, cap * sizeof *cl);
				}
				cl[m++] = cell_id(&g, c);
			}
		if (m)
			qsort(cl, m, sizeof *cl, cmp_i64);
		size_t k = 0;
		for (size_t q = 0; q < m; q++)
			if (!k || cl[q] != cl[k - 1])
				cl[k++] = cl[q];
		out[u] = cl;
		MPI_Isend(cl, (int)k, MPI_INT64_T, peer[u], TAG_CELLS, MPI_COMM_WORLD,
		          &req[nreq++]);
	}
	/* Then it sends each peer its particles in or next to the cells the
	 * peer occupies, as (index, x, v, ω), in increasing order. */
	int64_t *cells = NULL;
	for (int u = 0; u < np; u++) {
		size_t nc =
		    receive_any(peer[u], TAG_CELLS, MPI_INT64_T, sizeof *cells, (void **)&cells);
		const double *bq = box + 6 * peer[u];
		double *o = NULL;
		size_t m = 0, cap = 0;
		for (size_t i = R->p0; i < R->p1; i++) {
			const double *x = P->x + 3 * i;
			if (!in_reach(x, bq, reach) || !next_to(&g, x, cells, nc))
				continue;
			if (m == cap) {
				cap = cap ? 2 * cap : 1024;
				o = xrealloc(o, GHOST_COLS * cap * sizeof *o);
			}
			double *row = o + GHOST_COLS * m++;
			row[0] = (double)i;
			particle_row(P, i, row + 1);
		}
		out[np + u] = o;
		MPI_Isend(o, (int)(GHOST_COLS * m), MPI_DOUBLE, peer[u], TAG_GHOSTS, MPI_COMM_WORLD,
		          &req[nreq++]);
	}
	/* The peers' particles, in rank order: the ranks hold increasing runs
	 * of particles, so the ghosts come sorted. */
	size_t ng = 0, cap = 0;
	double *in = NULL;
	*ghosts = NULL;
	for (int u = 0; u < np; u++) {
		size_t cnt = receive_any(peer[u], TAG_GHOSTS, MPI_DOUBLE, sizeof *in, (void **)&in);
		if (!cnt)
			continue;
		if (ng * GHOST_COLS + cnt > cap) {
			cap = 2 * (ng * GHOST_COLS + cnt);
			*ghosts = xrealloc(*ghosts, cap * sizeof **ghosts);
		}
		memcpy(*ghosts + ng * GHOST_COLS, in, cnt * sizeof *in);
		ng += cnt / GHOST_COLS;
		R->recv_ghosts += (double)(cnt * sizeof *in);
	}
	MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
	for (int u = 0; u < 2 * np; u++)
		free(out[u]);
	free(out), free(req), free(in), free(cells), free(peer), free(box);
	R->sec[RANKS_GHOSTS] += timer_now() - t0;
	return ng;
#else
	(void)e, (void)reach;
	*ghosts = NULL;
	return 0;
#endif
}

#ifdef DEM_MPI
/* For each entry of the links `send`, the value v[idx] this rank holds sent
 * to the peer, into v[idx] of the matching entry of its links `recv`. */
static void share_values(rank_links *send, rank_links *recv, double *v, int tag)
{
	MPI_Request *req = xmalloc((size_t)(send->n + recv->n + 1) * sizeof *req);
	int nreq = 0;
	for (int k = 0; k < recv->n; k++)
		MPI_Irecv(recv->l[k].buf, (int)recv->l[k].n, MPI_DOUBLE, recv->l[k].peer, tag,
		          MPI_COMM_WORLD, &req[nreq++]);
	for (int k = 0; k < send->n; k++) {
		rank_link *l = &send->l[k];
		for (size_t q = 0; q < l->n; q++)
			l->buf[q] = v[l->idx[q]];
		MPI_Isend(l->buf, (int)l->n, MPI_DOUBLE, l->peer, tag, MPI_COMM_WORLD,
		          &req[nreq++]);
	}
	MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
	free(req);
	for (int k = 0; k < recv->n; k++)
		for (size_t q = 0; q < recv->l[k].n; q++)
			v[recv->l[k].idx[q]] = recv->l[k].buf[q];
}
#endif

void ranks_share_contact_values(engine *e, double *v)
{
#ifdef DEM_MPI
	if (e->ranks.size > 1)
		share_values(&e->ranks.csend, &e->ranks.crecv, v, TAG_VALUES);
#else
	(void)e, (void)v;
#endif
}

void ranks_share_bond_values(engine *e, double *v)
{
#ifdef DEM_MPI
	if (e->ranks.size > 1)
		share_values(&e->ranks.bsend, &e->ranks.brecv, v, TAG_VALUES);
#else
	(void)e, (void)v;
#endif
}

#ifdef DEM_MPI
/* Where each rank's rows of a list go, in rank order from row `first`, when
 * this rank has `mine` of them: [size + 1] offsets, the last the end
 * (free them). Collective. */
static size_t *rank_rows(size_t first, size_t mine, int size)
{
	int own = (int)mine, *cnt = xmalloc((size_t)size * sizeof *cnt);
	MPI_Allgather(&own, 1, MPI_INT, cnt, 1, MPI_INT, MPI_COMM_WORLD);
	ngathers_++;
	size_t *at = xmalloc(((size_t)size + 1) * sizeof *at);
	at[0] = first;
	for (int q = 0; q < size; q++)
		at[q + 1] = at[q] + (size_t)cnt[q];
	free(cnt);
	return at;
}
#endif

void ranks_share_cracks(engine *e, size_t first)
{
#ifdef DEM_MPI
	rank_split *R = &e->ranks;
	crack_buf *cb = &e->out.cracks;
	if (R->size == 1) {
		cb->all = cb->most = cb->n;
		return;
	}
	size_t mine = cb->n - first;
	double t0 = timer_now();
	/* This step's rows follow those not yet written, in rank order, which
	 * is bond order (ranks own increasing particles, bonds go by i). */
	size_t *at = rank_rows(cb->all, mine, R->size);
	if (mine) {
		if (cb->nruns == cb->runcap) {
			cb->runcap = cb->runcap ? 2 * cb->runcap : 64;
			cb->run_at = xrealloc(cb->run_at, cb->runcap * sizeof *cb->run_at);
			cb->run_n = xrealloc(cb->run_n, cb->runcap * sizeof *cb->run_n);
		}
		cb->run_at[cb->nruns] = at[R->rank];
		cb->run_n[cb->nruns++] = mine;
	}
	cb->all = at[R->size];
	if (!cb->held)
		cb->held = xcalloc((size_t)R->size, sizeof *cb->held);
	for (int q = 0; q < R->size; q++) {
		cb->held[q] += at[q + 1] - at[q];
		cb->most = cb->held[q] > cb->most ? cb->held[q] : cb->most;
	}
	free(at);
	R->sec[RANKS_GATHERS] += timer_now() - t0;
#else
	(void)first;
	e->out.cracks.all = e->out.cracks.most = e->out.cracks.n;
#endif
}

void ranks_own_pairs(const engine *e, pairs_view *v)
{
	v->bonds = &e->pairs.bonds;
	v->contacts = &e->pairs.contacts;
	for (int k = 0; k < 2; k++) {
		v->ncand[k] = e->bc.pl.ncand[k];
		v->pc[k] = e->bc.pl.pc[k];
		v->who[k] = e->bc.pl.who[k];
	}
}

int ranks_own(const engine *e, size_t *p0, size_t *p1)
{
	const rank_split *R = &e->ranks;
	int split = R->pfirst != NULL;
	*p0 = split ? R->p0 : 0;
	*p1 = split ? R->p1 : e->p.n;
	return split;
}

void ranks_particle(const engine *e, size_t g, double row[PARTICLE_ROW])
{
	size_t p0, p1;
	int split = ranks_own(e, &p0, &p1);
	int64_t i = window_local(&e->p, g);
	if (i >= 0 && g >= p0 && g < p1)
		particle_row(&e->p, (size_t)i, row);
	else
		for (int k = 0; k < PARTICLE_ROW; k++)
			row[k] = -INFINITY;
	if (split && e->ranks.size > 1)
		par_max(row, PARTICLE_ROW);
}

size_t ranks_gather_list(int32_t **list, size_t *cap, size_t mine)
{
#ifdef DEM_MPI
	int size = par_size(), rank = par_rank();
	if (size == 1)
		return mine;
	size_t *at = rank_rows(0, mine, size), total = at[size];
	if (total > *cap) {
		*cap = total + total / 4;
		*list = xrealloc(*list, (*cap + 1) * sizeof **list);
	}
	memmove(*list + at[rank], *list, mine * sizeof **list);
	gather_rows(*list, at, sizeof **list, size, ALL);
	free(at);
	return total;
#else
	(void)list, (void)cap;
	return mine;
#endif
}

void ranks_allgather_rows(const void *mine, size_t n, size_t row, void *all)
{
#ifdef DEM_MPI
	if (par_size() > 1) {
		size_t *at = rank_rows(0, n, par_size());
		gather_rows_from(mine, all, at, row, par_size(), ALL);
		free(at);
		return;
	}
#endif
	memcpy(all, mine, n * row);
}

void ranks_balance(const engine *e, double particles[2], double bonds[2])
{
	const rank_split *R = &e->ranks;
	const size_t *bfirst = e->pairs.split.bfirst;
	particles[0] = bonds[0] = 0;
	for (int q = 0; q < R->size; q++) {
		double np = (double)(R->pfirst[q + 1] - R->pfirst[q]);
		double nb =
		    (double)(bfirst[nblocks(R->pfirst[q + 1])] - bfirst[nblocks(R->pfirst[q])]);
		particles[0] = np > particles[0] ? np : particles[0];
		bonds[0] = nb > bonds[0] ? nb : bonds[0];
	}
	particles[1] = (double)e->p.n / R->size;
	bonds[1] = (double)e->pairs.nbonds / R->size;
}

void ranks_traffic_start(engine *e)
{
	rank_split *R = &e->ranks;
	R->recv_halo = R->recv_ghosts = R->recv_all = R->recv_forces = 0;
	memset(R->sec, 0, sizeof R->sec);
#ifdef DEM_MPI
	ngathers_ = 0;
#endif
	par_tally_reset();
}

void ranks_traffic(engine *e, double steps, const double memory[2])
{
	rank_split *R = &e->ranks;
	/* The run's own, before the reductions here. */
	par_tally red = par_reductions();
#ifdef DEM_MPI
	double ngathers = ngathers_;
#else
	double ngathers = 0;
#endif
	double own = (double)(R->p1 - R->p0), per = steps > 0 ? 1 / steps : 0;
	R->sec[RANKS_REDUCTIONS] = red.seconds;
	enum { NT = 9, NV = NT + RANKS_NX };
	double v[NV] = {R->recv_halo * per,
	                R->recv_ghosts * per,
	                (R->recv_halo + R->recv_ghosts + R->recv_all) * per,
	                R->size > 1 ? state_bytes(e->p.n) - state_bytes((size_t)own) : 0,
	                R->recv_forces * per,
	                memory[0],
	                memory[1],
	                (double)(e->p.hi - e->p.lo),
	                (double)e->p.held_peak};
	for (int k = 0; k < RANKS_NX; k++)
		v[NT + k] = R->sec[k];
	double top[NV];
	memcpy(top, v, sizeof top);
	par_max(top, NV);
	xsum s[NV];
	for (int k = 0; k < NV; k++) {
		xsum_clear(&s[k]);
		xsum_add(&s[k], v[k]);
	}
	par_sum(s, NV);
	double *out[NT] = {R->traffic_halo,      R->traffic_ghosts, R->traffic_state,
	                   R->traffic_allgather, R->traffic_forces, R->memory_state,
	                   R->memory_rss,        R->held,           R->held_peak};
	for (int k = 0; k < NV; k++) {
		double *o = k < NT ? out[k] : R->seconds[k - NT];
		o[0] = top[k];
		o[1] = xsum_round(&s[k]) / R->size;
	}
	R->reductions_per_step = red.calls * per;
	R->reduction_bytes_per_step = red.bytes * per;
	R->gathers_per_step = ngathers * per;
}

void ranks_free(rank_split *r)
{
	free(r->pfirst);
	links_free(&r->hsend);
	links_free(&r->hrecv);
	links_free(&r->bsend);
	links_free(&r->brecv);
	links_free(&r->csend);
	links_free(&r->crecv);
	memset(r, 0, sizeof *r);
}
