/* Bonds: formed once at start, computed once per step by the law, their
 * failures collected as cracks (bonds.c). */
#ifndef DEM_BONDS_H
#define DEM_BONDS_H

#include <stddef.h>
#include <stdint.h>

#include "lib/rng.h"
#include "lib/runfile.h"
#include "solve/cells.h"
#include "solve/law.h"
#include "solve/pairlist.h"

typedef struct engine engine;

/* Bond failures waiting to be written to /cracks. */
typedef struct {
	size_t n, cap;
	dem_crack *c;
	int64_t *bond; /* the failed bond of each in the whole specimen's bond
	                  order (which may pass 2^31 over many ranks), for sorting */
	/* On several ranks (ranks_share_cracks): the rows of all ranks, and
	 * where this rank's go among them, a run each step it found some:
	 * rows [run_at[k], run_at[k] + run_n[k]). */
	size_t all, nruns, runcap;
	size_t *run_at, *run_n;
	/* The most rows not yet written that one rank holds (all, on one
	 * rank), and each rank's ([ranks], on several): what decides when
	 * they are written, so that neither a rank's memory nor how often
	 * the ranks write grows with the rank count. */
	size_t most, *held;
	/* Bonds (this rank's indices) whose force a step found not finite,
	 * for the diagnosis (diagnose.c): the step ends the run. */
	size_t nbad, badcap;
	int32_t *bad;
} crack_buf;

/* What a bond computed in this step adds to its block's sums and to its two
 * particles, kept until it is added in bond order. */
typedef struct {
	double f[6]; /* force on i, torque per unit radius (pairlist.h) */
	double e_damage, e_friction, e_viscous, e_elastic;
	double love[9];
	int state;
} bond_part;

/* The particles split into shares, one per thread of a step: contiguous
 * ranges of whole particle blocks, each with the bonds whose first particle
 * (i < j) lies in it. Every particle's force is the sum of its bonds' forces
 * in bond order, whatever the shares: a share computes its bonds in order
 * and adds each force to both ends; the bonds that reach into a later share
 * ("crossing") are computed first, before any share adds, and kept, so the
 * later share adds them before its own, where bond order puts them.
 *
 * The crossing bonds have slots: first those of this rank's shares (all of
 * them with one rank), share by share from cfirst[s0] = 0 to cfirst[s1] =
 * cfirst[n] (ranks.h), then those of earlier ranks' shares whose j is this
 * rank's ("incoming": their forces come from the rank of i), in bond order,
 * up to ncross. */
typedef struct {
	int n;            /* shares */
	size_t *pfirst;   /* [n + 1] first particle of each share */
	size_t *cfirst;   /* [n + 1] first slot of each share (this rank's) */
	size_t ncross;    /* slots */
	int32_t *cross;   /* [ncross] the bond of each slot in pairs.bonds, or -1
	                     (incoming) */
	int32_t *ci, *cj; /* [ncross] the particles of each slot's bond */
	size_t *infirst;  /* [n + 1] first of each share's in */
	int32_t *in;      /* slots of the bonds whose j each share holds, in bond
	                     order */
	bond_part *part;  /* what each slot's bond adds, this step */
	size_t *bfirst;   /* [particle blocks + 1] first bond of each particle
	                     block, in the whole specimen's bond order */
	/* [bonds] at the first bond of each batch of bonds_share: 0 when the
	 * batch goes through the law's force_pairs, else the steps left that
	 * it goes the staged way (more than a quarter of its lanes were off
	 * the law's elastic branch). Only the speed depends on it. Kept when
	 * the bonds are split again: it goes by the bond. */
	uint8_t *staged;
	double *work; /* [n] each share's work as the split estimated it */
} bond_split;

/* The balance of one rank's threads: a share's work is its particles and
 * bonds, but the threads that take them need not run alike (the cores of
 * one machine differ, and change, when other work shares them), so the
 * shares' times are measured and, when that pays, their ends moved
 * (bonds_balance). The forces do not depend on the ends. */
typedef struct {
	int n;            /* shares */
	double *busy;     /* [n] seconds each share took after the barrier of
	                     the step (bonds_share and the particles), since the
	                     shares were last looked at */
	double *busy_run; /* [n] the same over the run, up to that look */
	int steps;        /* steps since the shares were last looked at */
	int resplits;     /* times their ends moved */
	int test;         /* DEM_BALANCE_TEST: moved every few steps, at
	                     random (the forces must not change) */
	rng gen;
} share_balance;

/* Whether the bond loop prefetches the records and far particles of the
 * batches ahead (bonds_prefetch): it pays where a rank's specimen
 * outgrows the caches (a tenth less time a bond update at 70 000 spheres)
 * and costs where it fits (a tenth more at 13 000), and where the caches
 * end depends on the machine and on what else runs there. So the engine
 * times steps with it and without, in alternate windows, and keeps the
 * way of the quickest (bonds_tune_prefetch); again every few thousand
 * steps. Only the speed depends on it. DEM_PREFETCH=on or off fixes it. */
typedef struct {
	int off;        /* 1 while the loop does not prefetch */
	int fixed;      /* set by DEM_PREFETCH: never timed */
	int window;     /* windows timed so far in this trial; 0: no trial */
	int steps;      /* steps into the window, or since the last trial */
	int trials;     /* trials so far */
	double now;     /* seconds of this window so far */
	double best[2]; /* seconds of this trial's quickest window with,
	                   without (0: none yet) */
} prefetch_tune;

/* Bonds between the particles within the law's range (Eq. 16), as
 * e->pairs.formed until bonds_own makes a rank's records: a cell grid over
 * the particles the rank holds (with several ranks its own and the others'
 * within the bond range), from which the bonds of its particles are found
 * again in bond order, and the first bond of each particle block of the
 * whole specimen (each rank counts its own, bonds_form). No rank holds
 * every bond. */
typedef struct {
	cells grid; /* over the particles held from lo on */
	size_t lo;
	double range;   /* Eq. 16, times r_i + r_j */
	size_t *bfirst; /* [particle blocks + 1] */
} bond_search;
int bonds_form(engine *e);
/* The search's grid (again) over the particles this rank holds: with
 * several ranks, its own and, first fetched, the others' within the bond
 * range of them (window_ghosts). Collective. */
void bonds_search_grid(engine *e);
void bonds_search_free(bond_search *f);
/* The history of this rank's bonds at the start, and the largest fraction
 * of critical damping of any bond (Eq. 13) into e->clock.xi_max.
 * Collective. */
void bonds_init_history(engine *e);
/* What this rank's bonds keep of their pair's constants (law.restore),
 * after a checkpoint gave their histories. */
void bonds_restore(engine *e);
/* Split the particles into shares for the step's threads (after the bonds
 * have formed; again later only with one rank). */
void bonds_split(engine *e, int shares);
/* Keep this rank's part of the split, the shares [s0, s1) (ranks_split):
 * the records of their bonds, their crossing bonds' slots and the incoming
 * ones. */
void bonds_own(engine *e, int s0, int s1);
void bonds_split_free(bond_split *s);
/* Every so many steps, with one rank and several shares: whether the
 * shares' measured times (e->pairs.balance) say that moving their ends
 * would shorten the step by a few percent, and if so, the split again with
 * each share's work in proportion to its measured speed. Outside the
 * step's parallel region. */
void bonds_balance(engine *e);
void share_balance_free(share_balance *b);
/* The prefetch_tune at the start of a run (DEM_PREFETCH read: -1 and a
 * message when it is neither on nor off); then after
 * each step, with the seconds its threads took (the bonds, the contacts
 * and the particles), its trial goes on. */
int bonds_prefetch_setup(engine *e);
void bonds_tune_prefetch(engine *e, double seconds);
/* This step's forces of the crossing bonds of share k, inside the step's
 * parallel region (before a barrier). */
void bonds_cross(engine *e, int k, int measure);
/* This step's forces of share k's other bonds, and every bond force on
 * share k's particles summed into e->scratch.acc (after the barrier).
 * After the bonds of each particle block blk (those whose i is in it),
 * done(e, blk, ctx): the block's sums are then whole (every bond of one of
 * its particles has its i there or before), and no later bond of the
 * share reads its particles (their j lie beyond). The block's sums are
 * zeroed after done returns: they are zero between steps. */
typedef void (*block_done)(engine *e, size_t blk, void *ctx);
void bonds_share(engine *e, int k, int measure, block_done done, void *ctx);
/* The force on i of each of this rank's bonds at the state as it is now
 * (between steps: the force the next step gives it), computed by the law
 * without changing any bond, into e->pairs.bonds.fb, for the output
 * (snapshots, checkpoints): a step does not keep its bonds' forces.
 * Outside a parallel region. */
void bonds_output_forces(engine *e);
/* Move this step's failures to e->out.cracks, in bond order. */
void bonds_collect_cracks(engine *e);
/* Bond b of L (this rank's bonds, whose ends it holds): its ends in the
 * assembly's numbering (ends[0] < ends[1]) and, when c is not NULL, its
 * elastic constants. */
void engine_bond_entry(const engine *e, const pairlist *L, size_t b, int32_t ends[2], law_const *c);

#endif
