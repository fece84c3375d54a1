/* The contact-law interface.
 *
 * A law turns the relative motion of two spheres joined by a bond (or
 * touching) into forces. The engine never knows which law runs: it holds a
 * `law` table found by name (law_find) from the material file's "law" key,
 * in the spirit of CoMD's BasePotential and of the Kratos constitutive-law
 * base class (seeds/001 §3.2: contact area, elastic constants, normal force,
 * tangential force, damping).
 *
 * Conventions (equation numbers from Oñate et al. 2015, seeds/000):
 *   n      unit vector from the centre of i to the centre of j
 *   u_n    |x_j - x_i| - d0, opening positive, compression negative (Eq. 26)
 *   fn     normal force, TENSION POSITIVE: the force on i is +fn n (towards j
 *          in tension), on j it is -fn n
 *   fs     shear force on i (on j: -fs), in the contact plane (Eq. 18b-19)
 *   dus    tangential displacement increment of j relative to i at the
 *          contact point during this step, in the current contact plane
 *          (Eq. 34); a shear force on i acts along +dus when elastic.
 * A law keeps its tangential history in bond.t, a vector in the contact
 * plane (accumulated shear displacement for total-displacement laws, shear
 * force for incremental ones). Before every call the engine rotates t into
 * the current contact plane, so laws never deal with rigid rotations.
 *
 * SI units throughout. Laws are pure: no globals, no allocation in force(),
 * no I/O; so a single bond can be driven by prescribed displacements in
 * tests exactly as the engine drives it.
 */
#ifndef DEM_LAW_H
#define DEM_LAW_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "lib/cfg.h"
#include "solve/clones.h"

enum { LAW_NHIST = 3 };

/* A bond (or contact) as a law sees it. The engine stores the fields
 * from i to h as a pair_rec (below), and the state and k in arrays of
 * their own. */
typedef struct {
	int32_t i, j; /* particle indices */
	double d0;    /* m, reference length: centre distance at bonding */
	/* A constant of the bond that the law keeps so that a step need not
	 * compute it (law-defined, set by init and restore; 0 when the law
	 * keeps none). Not history: checkpoints do not hold it. */
	double k;
	double t[3];         /* tangential history (law-defined), contact plane */
	double h[LAW_NHIST]; /* law-defined history: damage, plastic state, ... */
	uint8_t state;       /* BOND_INTACT, BOND_DAMAGED, BOND_BROKEN_* (lib/states.h) */
} bond;

/* A bond or contact as the engine stores it: 64 bytes, one cache line in
 * the engine's arrays (pairlist.h), which is what a step reads and writes
 * of every bond. A bond's state and the law's constant k are arrays of
 * their own beside the records (pairlist.state, pairlist.k): k is kept
 * only for a law that has one (law.keeps_k), and a contact has neither. */
typedef struct {
	int32_t i, j;
	double d0;
	double t[3];
	double h[LAW_NHIST];
} pair_rec;
_Static_assert(sizeof(pair_rec) == 64, "pair_rec: one cache line");

/* The law's view of record r, with its state and constant k. */
static inline bond pair_bond(const pair_rec *r, int state, double k)
{
	bond b = {.i = r->i, .j = r->j, .d0 = r->d0, .k = k, .state = (uint8_t)state};
	memcpy(b.t, r->t, sizeof b.t);
	memcpy(b.h, r->h, sizeof b.h);
	return b;
}

/* The two spheres of a bond. */
typedef struct {
	double ri, rj; /* m */
	double mi, mj; /* kg */
	double d0;     /* m */
} law_pair;

/* Relative motion in this step. */
typedef struct {
	double un;     /* m, normal displacement, opening positive */
	double vn;     /* m/s, normal relative velocity, opening positive */
	double dus[3]; /* m, tangential displacement increment (contact plane) */
} law_kin;

typedef struct {
	double fn;    /* N, tension positive */
	double fs[3]; /* N, on particle i */
	int failed;   /* 0, or CRACK_TENSION / CRACK_SHEAR if the bond broke in this call */
	/* Energy bookkeeping for the run's history (energy_damped, _fracture,
	 * _friction). The engine sets these three to 0 before every call, so a
	 * law that does not track them simply leaves them. */
	double fn_viscous; /* N, the viscous part of fn (included in fn), tension positive */
	double e_damage;   /* J, dissipated by damage, plastic flow or failure in this call */
	double e_friction; /* J, dissipated by sliding in this call */
	/* Set with failed: the forces the failure criterion judged in this
	 * call, before the failure took them away (the crack record's): the
	 * normal force of the bond's spring (N, tension positive, without the
	 * viscous part) and the size of its shear force (N). A damage law
	 * gives them with the damage the bond had before the call. */
	double fn_failed, fs_failed;
} law_out;

/* Elastic constants of a bond, for the time step estimate and output. */
typedef struct {
	double kn, ks; /* N/m, initial (largest) normal and shear stiffness */
	double cn;     /* N s/m, normal viscous damping coefficient */
	double area;   /* m^2, effective contact area A-bar */
	double rc;     /* m, contact radius */
} law_const;

/* What the engine knows of the packing when bonds have formed. */
typedef struct {
	double porosity;     /* 1 - solid fraction of the specimen */
	double coordination; /* mean bonds per sphere */
} law_packing;

/* A batch of up to LAW_LANES bonds as force_batch sees them: the fields of
 * law_pair, law_kin, bond (history) and law_out as arrays over the lanes
 * q = 0 .. n - 1, so a law can compute many bonds at once in the vector
 * units. force_batch reads the pair, kinematics and history, and writes
 * the history and every output (the energies from zero). */
enum { LAW_LANES = 32 };
typedef struct {
	int n;
	double ri[LAW_LANES], rj[LAW_LANES], mi[LAW_LANES], mj[LAW_LANES], d0[LAW_LANES];
	double un[LAW_LANES], vn[LAW_LANES], dus[3][LAW_LANES];
	double t[3][LAW_LANES], h[LAW_NHIST][LAW_LANES];
	double k[LAW_LANES];      /* bond.k, read only */
	int32_t state[LAW_LANES]; /* lib/states.h */
	double fn[LAW_LANES], fs[3][LAW_LANES], fn_viscous[LAW_LANES];
	double e_damage[LAW_LANES], e_friction[LAW_LANES];
	int failed[LAW_LANES];
	double fn_failed[LAW_LANES], fs_failed[LAW_LANES]; /* where failed */
} law_batch;

typedef struct law_params law_params; /* each law's own, opaque */
typedef struct law_pairs law_pairs;   /* kinematics.h */
typedef struct law_lanes law_lanes;   /* kinematics.h */
typedef struct law_fused law_fused;   /* kinematics.h */

typedef struct law {
	const char *name;    /* as in the material file: "onate", "jcfpm", ... */
	const char *summary; /* one line for help and documentation */
	/* Read the law's keys from the material object (required ones are an
	 * error when missing, every value range-checked). NULL and err on error. */
	law_params *(*parse)(cfg *material);
	void (*free)(law_params *p);
	/* A copy of p that the caller owns and releases with this table's free.
	 * The engine runs on its own copy, so setup never writes into the
	 * material it was given. */
	law_params *(*copy)(const law_params *p);
	/* Bonds form at start between spheres with d <= range * (ri + rj). */
	double (*bond_range)(const law_params *p);
	/* Called once after bonds form, on the engine's copy (e.g. alpha =
	 * 40 P / N_c, Eq. 22); before it only bond_range may be called. */
	void (*setup)(law_params *p, const law_packing *packing);
	void (*constants)(const law_params *p, const law_pair *pair, law_const *out);
	/* Initialise the history of a new bond. */
	void (*init)(const law_params *p, const law_pair *pair, bond *b);
	/* Optional (NULL when the law has none): set again what init keeps
	 * that depends on the pair alone (bond.k, or a constant kept in the
	 * history), after a checkpoint gave the rest: a checkpoint does not
	 * hold bond.k, and one of an earlier version may not hold the other. */
	void (*restore)(const law_params *p, const law_pair *pair, bond *b);
	/* Forces for this step's kinematics; updates b->t, b->h and b->state. */
	void (*force)(const law_params *p, const law_pair *pair, bond *b, const law_kin *k,
	              law_out *out);
	/* The same over a batch, exactly (bit for bit) as force bond by bond. */
	void (*force_batch)(const law_params *p, law_batch *b);
	/* Optional (NULL when the law has none): the n lanes of a batch of
	 * bonds (L, from law_pairs_load) to the forces on them in one loop,
	 * for the lanes that stay on the law's elastic branch, and any
	 * others it chooses to compute (broken bonds; out->elastic[q] != 0
	 * for all those), to the bit what batch_kinematics,
	 * force_batch and batch_force give (kinematics.h); the other lanes are
	 * left to those, and their bonds as they were. Returns the count of
	 * lanes it computed. */
	int (*force_pairs)(const law_params *p, const law_lanes *L, int n, double dt,
	                   law_fused *out);
	/* Elastic energy stored in the bond (J) after the force() call whose
	 * normal displacement was un (m). */
	double (*energy)(const law_params *p, const law_pair *pair, const bond *b, double un);
	/* Damage in tension and in shear, each in [0, 1]. */
	void (*damage)(const law_params *p, const bond *b, double *dn, double *ds);
	/* Whether init sets bond.k (a constant the engine then keeps per
	 * bond); when 0, k is 0 in every call. */
	int keeps_k;
	/* The slot of h in which checkpoints written before h had LAW_NHIST
	 * slots kept the last u_n: the rest are this layout's, in order. */
	int h_dropped;
} law;

/* Lane q of a batch as force() takes it, and back. */
static inline law_pair law_lane_pair(const law_batch *B, int q)
{
	return (law_pair){
	    .ri = B->ri[q], .rj = B->rj[q], .mi = B->mi[q], .mj = B->mj[q], .d0 = B->d0[q]};
}
static inline law_kin law_lane_kin(const law_batch *B, int q)
{
	return (law_kin){
	    .un = B->un[q], .vn = B->vn[q], .dus = {B->dus[0][q], B->dus[1][q], B->dus[2][q]}};
}
static inline bond law_lane_bond(const law_batch *B, int q)
{
	bond b = {.d0 = B->d0[q], .k = B->k[q], .state = B->state[q]};
	for (int c = 0; c < 3; c++)
		b.t[c] = B->t[c][q];
	for (int c = 0; c < LAW_NHIST; c++)
		b.h[c] = B->h[c][q];
	return b;
}
static inline void law_lane_put(law_batch *B, int q, const bond *b, const law_out *o)
{
	for (int c = 0; c < 3; c++) {
		B->t[c][q] = b->t[c];
		B->fs[c][q] = o->fs[c];
	}
	for (int c = 0; c < LAW_NHIST; c++)
		B->h[c][q] = b->h[c];
	B->state[q] = b->state;
	B->fn[q] = o->fn;
	B->fn_viscous[q] = o->fn_viscous;
	B->e_damage[q] = o->e_damage;
	B->e_friction[q] = o->e_friction;
	B->failed[q] = o->failed;
	B->fn_failed[q] = o->fn_failed;
	B->fs_failed[q] = o->fs_failed;
}

/* Lane q of a batch computed by FORCE (a function with the signature of
 * law.force), as the engine would call it for that bond alone. */
#define LAW_LANE(FORCE, p, B, q)                                            \
	do {                                                                \
		law_pair lane_pair_ = law_lane_pair(B, q);                  \
		law_kin lane_kin_ = law_lane_kin(B, q);                     \
		bond lane_bond_ = law_lane_bond(B, q);                      \
		law_out lane_out_ = {0};                                    \
		FORCE(p, &lane_pair_, &lane_bond_, &lane_kin_, &lane_out_); \
		law_lane_put(B, q, &lane_bond_, &lane_out_);                \
	} while (0)

/* The end of a force_batch whose vector loop computed the lanes with
 * elastic[q] != 0: those dissipate nothing and do not fail, and every other
 * lane is computed by FORCE, as force() would. */
#define LAW_BATCH_REST(FORCE, p, B, elastic)               \
	do {                                               \
		for (int q_ = 0; q_ < (B)->n; q_++) {      \
			(B)->e_damage[q_] = 0;             \
			(B)->e_friction[q_] = 0;           \
			(B)->failed[q_] = 0;               \
		}                                          \
		for (int q_ = 0; q_ < (B)->n; q_++)        \
			if (!(elastic)[q_])                \
				LAW_LANE(FORCE, p, B, q_); \
	} while (0)

/* Defines `static void NAME_batch(const law_params *, law_batch *)` computing
 * every lane with FORCE, a function with the signature of law.force.
 * Everything FORCE calls is inlined into the loop (flatten), so a law's
 * helpers cost no calls. */
#define LAW_BATCH(NAME, FORCE)                                                               \
	DEM_VECTOR_CLONES                                                                    \
	__attribute__((flatten)) static void NAME##_batch(const law_params *p, law_batch *B) \
	{                                                                                    \
		for (int q = 0; q < B->n; q++)                                               \
			LAW_LANE(FORCE, p, B, q);                                            \
	}

/* k ? a : b chosen on the bits, both computed first: the compiler keeps it
 * a select, where ?: on two computed values may become a branch around
 * one of them, and a loop with a floating-point operation in a branch is
 * not vectorised under strict floating point (the operation could trap).
 * The same value as ?:. */
static inline double law_sel(int64_t k, double a, double b)
{
	uint64_t x, y, m = (uint64_t)0 - (uint64_t)(k != 0);
	memcpy(&x, &a, sizeof x);
	memcpy(&y, &b, sizeof y);
	x = (x & m) | (y & ~m);
	double r;
	memcpy(&r, &x, sizeof r);
	return r;
}

/* The smaller and the larger of two numbers, inline: the compiler calls the
 * C library for fmin and fmax unless it may ignore NaNs, which it may not
 * here. (A NaN stops the run anyway; it is diagnosed after the step.) */
static inline double law_min(double a, double b) { return a < b ? a : b; }
static inline double law_max(double a, double b) { return a > b ? a : b; }

/* A test that only chooses whether a lane takes its law's vector branch
 * (a lane turned away is computed as force() would, to the same bits) may
 * say "not sure" near its limit. These leave out the exact tests'
 * divisions and square roots, with a margin of 1e-12 of the limit, far
 * above the rounding; a NaN is never sure.
 *   law_surely_below(a * k, b * k): a <= b / k, for k > 0 and b >= 0;
 *   law_surely_within(k * k * tt, lim): k sqrt(tt) <= lim, for k > 0. */
static inline int32_t law_surely_below(double x, double y) { return x <= (1 - 1e-12) * y; }
static inline int32_t law_surely_within(double ff, double lim)
{
	return (lim > 0) & (ff <= (1 - 1e-12) * lim * lim);
}

/* Whether a trial shear t of |t|² = tt stays within lim, k |t| <= lim, as
 * a vector branch tests it: exactly, with *f = k |t|, where the batch holds
 * broken bonds (whose friction needs |t| itself); else law_surely_within,
 * without the root (*f left as it was). */
static inline int32_t law_shear_within(int broken, double k, double tt, double lim, double *f)
{
	if (broken) {
		*f = k * sqrt(tt);
		return *f <= lim;
	}
	return law_surely_within(k * k * tt, lim);
}

/* law.copy of a law whose parameters are one struct of size bytes with no
 * pointers inside. */
law_params *law_params_dup(const law_params *p, size_t size);

/* The law registered under name, or NULL (err_msg lists the known ones). */
const law *law_find(const char *name);
/* All registered laws, NULL-terminated. */
const law *const *law_all(void);

#endif
