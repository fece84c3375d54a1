/* The particles split among the ranks of a run (par.h), and what crosses
 * between them (ranks.c).
 *
 * Each rank takes a contiguous run of the thread shares of bonds.h (whole
 * particle blocks in Morton order, so a run of them is a compact piece of
 * the specimen): it computes the bonds and contacts whose first particle
 * (i < j) is its own, moves its own particles and sums its own blocks. A
 * pair that reaches into a later rank ("crossing") is computed by the rank
 * of i, which sends its force to the rank of j; there it is added where
 * pair order puts it, so every particle's force is the same sum, bit for
 * bit, on any number of ranks. After each step a rank receives the new
 * position and velocities of its halo only: the particles j of the
 * crossing pairs it computes, from their ranks, point to point.
 *
 * A neighbour rebuild searches each rank's own particles and its ghosts:
 * the other ranks' particles within the contact reach (2 r_max + skin) of
 * the box around its own, which their ranks send it point to point after
 * one gather of every rank's box. A rank lists the contacts of its own
 * particles i and, before them, those of earlier ranks' particles i with
 * its own j, whose forces it receives: every contact with an end of its
 * own, in the order one process lists them. Likewise the platen contacts
 * of its own particles.
 *
 * The other ranks' particles are stale between such exchanges: what reads
 * beyond the halo reads each rank's own particles and combines the ranks'
 * parts (the end layers, the lateral surface and the gauge, surface.c;
 * the diagnoses of a failing run, diagnose.c). Every rank writes its own
 * rows of every dataset into the run file they share (parallel HDF5;
 * ranks_rows_write, ranks_rows_put): no rank ever gathers the whole
 * specimen, the diagnosis of a non-finite state included (which shares
 * only the pairs with non-finite forces). With
 * DEM_RANKS_POISON=1 in the environment the stale particles' x, v and ω
 * are NaN instead, so that a read that misses an exchange shows.
 *
 * The bonds and contacts, with their histories, live with the rank of
 * their i: a rank holds the records of its own bonds only, and of the
 * crossing bonds it receives their ends (bonds.h). */
#ifndef DEM_RANKS_H
#define DEM_RANKS_H

#include <stddef.h>
#include <stdint.h>

#include "lib/h5.h"
#include "solve/pairlist.h"
#include "solve/platens.h"
#include "solve/window.h"

typedef struct engine engine;

/* The pair forces one rank sends to (receives from) another each step. */
typedef struct {
	int peer;
	size_t n, cap;
	size_t *idx; /* crossing-bond slots (bonds.h) or contact indices */
	double *buf; /* [n][6] */
} rank_link;

typedef struct {
	int n;
	rank_link *l;
} rank_links;

/* What a rank spends its exchanges on: the crossing pairs' forces and the
 * halo's state (point to point, every step), the ghosts (point to point,
 * at a neighbour rebuild, with the gather of the ranks' boxes), the
 * gathers (the output: the rows each rank writes and its writes; the
 * crack log's counts) and the reductions (par.h). */
enum { RANKS_FORCES, RANKS_HALO, RANKS_GHOSTS, RANKS_GATHERS, RANKS_REDUCTIONS, RANKS_NX };

typedef struct {
	int size, rank;
	size_t *pfirst;             /* [size + 1] first particle of each rank */
	int s0, s1;                 /* this rank's shares of pairs.split */
	size_t p0, p1;              /* its particles */
	size_t blk0, blk1;          /* its particle blocks */
	rank_links bsend, brecv;    /* crossing bonds' forces */
	rank_links csend, crecv;    /* crossing contacts' forces */
	rank_links hsend, hrecv;    /* the halo: particles whose x, v, ω go to
	                               (come from) each peer, in increasing order */
	int poison;                 /* DEM_RANKS_POISON: and NaN */
	double recv_halo, recv_all; /* bytes received so far by halo exchanges
	                               and by gathers (output, diagnosis) */
	double recv_ghosts;         /* and with the ghosts */
	double recv_forces;         /* bytes of crossing forces received so far */
	double ngathers;            /* collective gathers (MPI_Allgather(v)) so far */
	double sec[RANKS_NX];       /* wall seconds in each kind of exchange so far,
	                               waiting for the peers included */
	/* Bytes of state received per step of the run, the largest and the mean
	 * over the ranks (ranks_traffic): by halo exchanges, as ghosts, in all
	 * (with the full gathers), and what gathering every particle after
	 * every step would receive. */
	double traffic_halo[2], traffic_ghosts[2], traffic_state[2], traffic_allgather[2];
	/* Likewise, the bytes of crossing forces received per step; the wall
	 * seconds of the run in each kind of exchange; and, per step, the
	 * reductions (MPI_Allreduce calls), their payload in bytes, and the
	 * collective gathers, which every rank makes alike. */
	double traffic_forces[2], seconds[RANKS_NX][2];
	double reductions_per_step, reduction_bytes_per_step, gathers_per_step;
	/* Each rank's engine state and peak resident size in bytes, the
	 * largest and the mean over the ranks (ranks_traffic). */
	double memory_state[2], memory_rss[2];
	/* The particles each rank holds at the end (window.h), and the most it
	 * held at once (setup included), the largest and the mean over the
	 * ranks. */
	double held[2], held_peak[2];
} rank_split;

/* Lists of bonds, contacts and platen contacts: a rank's own
 * (ranks_own_pairs), as the checkpoint writes and checksums them. */
typedef struct {
	const pairlist *bonds, *contacts;
	size_t ncand[2];
	const platen_contact *pc[2];
	const int32_t *who[2];
} pairs_view;

/* This rank's part of the shares (after bonds_split), and the arrays of
 * its own particles made for them (their positions at the last rebuild,
 * zero until the next, and their sums of the bond forces). In setup with
 * several ranks, where each holds its share of the particles' order
 * (order.h), the particles first go to the ranks that own them. */
void ranks_split(engine *e);
/* Of this rank's crossing bond slots (bonds.h: its shares', found by
 * bonds_own), those whose j is another rank's sent to that rank; the
 * slots whose j is this rank's from the ranks of their i, in bond order,
 * as rows of (bond, i, j), indices in the whole specimen, into *in (the
 * caller's to free): their number. Collective. */
size_t ranks_incoming(const engine *e, int64_t **in);
/* Of the n pairs rec (ends given by their index in the whole specimen,
 * each i this rank's own), those whose j is another rank's sent to that
 * rank; the pairs other ranks send this rank, in the order of their
 * ranks, into *in (the caller's to free): their number. Collective. */
size_t ranks_share_pairs(const engine *e, const pair_rec *rec, size_t n, pair_rec **in);
/* The crossing contacts (after each contact rebuild). */
void ranks_contacts(engine *e);
/* Inside the step's parallel region, by one thread: the forces of the
 * crossing bonds and contacts sent to the ranks of their j. */
void ranks_exchange_forces(engine *e);
/* After the step (this rank's particles moved): their new position and
 * velocities to the ranks whose halo they are in. Collective. */
void ranks_share_state(engine *e);
/* Before a neighbour search: the other ranks' particles whose centres lie
 * within `reach` (per axis) of the box around this rank's own particles
 * (its ghosts), from their ranks, point to point: in increasing order of
 * their index in the whole specimen, each a row of *ghosts (the caller's
 * to free) of GHOST_COLS doubles, that index then its particle_row
 * (window.h); their number returned. Collective. */
enum { GHOST_COLS = 1 + PARTICLE_ROW };
size_t ranks_share_ghosts(engine *e, double reach, double **ghosts);
/* For each crossing contact (ranks_contacts), the value v[c] the rank of
 * its i holds sent to the rank of its j, into v[c] there. Collective. */
void ranks_share_contact_values(engine *e, double *v);
/* The same for each crossing bond's slot (bonds.h): the value the rank of
 * its i holds sent to the rank of its j. Collective. */
void ranks_share_bond_values(engine *e, double *v);
/* After the step: where the failures every rank found in it (each since
 * `first`, the length of its e->out.cracks before the step) go in the
 * crack log, in bond order, which is rank order: each rank keeps its own
 * and notes their run of rows, and counts those of all ranks
 * (e->out.cracks.all; crack_buf). Collective. */
void ranks_share_cracks(engine *e, size_t first);
/* This rank's own bond, contact and platen lists as a view (after a
 * checkpoint is read, before contacts_restore, the whole specimen's
 * contacts). */
void ranks_own_pairs(const engine *e, pairs_view *v);
/* This rank's particles [*p0, *p1), and 1: what the rank computes from its
 * own particles must be combined with the other ranks'. In setup with
 * several ranks, before ranks_split, its share of the order (order.h);
 * before ranks_split where every rank holds every particle (one process,
 * or engine_opts.whole), all of them, and 0. */
int ranks_own(const engine *e, size_t *p0, size_t *p1);
/* Particle g's (its index in the whole specimen) row (particle_row,
 * window.h), from its rank; x, v and ω only where finite. Collective once
 * the particles are split. */
void ranks_particle(const engine *e, size_t g, double row[PARTICLE_ROW]);
/* This rank's `mine` entries (*list)[0..mine), then every rank's, in rank
 * order, in *list (of room for *cap, grown to hold them all): their
 * number. Collective. */
size_t ranks_gather_list(int32_t **list, size_t *cap, size_t mine);
/* A dataset of the run file (rows x cols values of `size` bytes, open in
 * r on every rank) whose rows the ranks hold: this rank's `mine` items,
 * item k at row first + k, or dest[k] when dest is not NULL, their rows
 * [k0, k0 + m) written into buf by fill(ctx, k0, m, buf). Where the
 * dataset has several chunks (h5_chunk_rows), the rows go to the ranks
 * that write them, an even share of whole chunks each (HDF5 compresses a
 * chunk where it is written), in rounds of a few chunks a rank; else every
 * row goes to rank 0, which writes them. The chunks are those one process
 * writes. Collective. */
typedef void (*ranks_fill)(void *ctx, size_t k0, size_t m, void *buf);
int ranks_rows_write(engine *e, h5_rows *r, size_t rows, size_t cols, size_t size, size_t mine,
                     size_t first, const int32_t *dest, ranks_fill fill, void *ctx);
/* Rows the ranks hold in rank order (this rank's `mine` rows, from fill),
 * written into rows [0, their total) of the open dataset d (of type `type`
 * and cols columns, without filters), each rank its own a piece at a
 * time. -1 if a write of this rank failed (no message set). Collective. */
int ranks_rows_put(engine *e, hid_t d, hid_t type, size_t cols, size_t mine, ranks_fill fill,
                   void *ctx);
/* Every rank's n rows of `row` bytes (mine), in rank order, into all
 * (room for them all). Collective. */
void ranks_allgather_rows(const void *mine, size_t n, size_t row, void *all);
/* The sum of `mine` over the ranks. Collective. */
size_t ranks_total(size_t mine);
/* n values of each rank gathered in rank order into all ([size][n]) on
 * rank 0. Collective. */
void ranks_gather_u64(const uint64_t *mine, size_t n, uint64_t *all);
/* The load balance: the largest and the mean number of particles (and of
 * bonds, by their i) per rank. */
void ranks_balance(const engine *e, double particles[2], double bonds[2]);
/* Zero the counts of traffic and time above (where the run loop starts). */
void ranks_traffic_start(engine *e);
/* The traffic per step over the `steps` steps since ranks_traffic_start,
 * and the time in each exchange, into e->ranks.traffic_*, .seconds and the
 * counts per step; and this rank's memory (its engine state and peak
 * resident size, bytes) with the other ranks', into .memory_*.
 * Collective. */
void ranks_traffic(engine *e, double steps, const double memory[2]);
void ranks_free(rank_split *r);

#endif
