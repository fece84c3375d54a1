/* force_batch gives exactly what force gives bond by bond: the same forces,
 * failures and histories, bit for bit, for every law along random paths that
 * visit every branch. And force_pairs, where a law has it, gives for the
 * lanes it computes exactly what the engine's staged path gives
 * (batch_kinematics, force_batch, batch_force), and leaves the other bonds
 * as they were. And law_pairs_load, which feeds force_pairs, gives what
 * its scalar loop gives. */
#include "tests/laws/drive.h"

#include <math.h>
#include <stdio.h>

#include "lib/rng.h"
#include "solve/kinematics.h"
#include "solve/pairlist.h"

enum { NB = 64, NSTEP = 300 };

static const char *materials[][2] = {
    {"onate", "{\"name\": \"m\", \"law\": \"onate\", \"density\": 2500,"
              " \"E0\": 3.8e9, \"nu\": 0.2, \"tensile_strength\": 4.8e6,"
              " \"shear_strength\": 8.5e6, \"mu1\": 0.3, \"mu2\": 0.4, \"LCS1\": 8.5e6,"
              " \"LCS2\": 9e6, \"LCS3\": 11e6, \"YRC1\": 3, \"YRC2\": 9, \"YRC3\": 24,"
              " \"delta_n\": 0.2, \"delta_s\": 0.2, \"alpha\": 1}"},
    {"onate", "{\"name\": \"m\", \"law\": \"onate\", \"density\": 2500,"
              " \"E0\": 3.8e9, \"nu\": 0.2, \"tensile_strength\": 4.8e6,"
              " \"shear_strength\": 8.5e6, \"mu1\": 0.3, \"mu2\": 0.4, \"LCS1\": 8.5e6,"
              " \"LCS2\": 9e6, \"LCS3\": 11e6, \"YRC1\": 3, \"YRC2\": 9, \"YRC3\": 24,"
              " \"delta_n\": 0, \"delta_s\": 0.5, \"criterion\": \"coupled\"}"},
    {"linear", "{\"name\": \"m\", \"law\": \"linear\", \"density\": 2500,"
               " \"E\": 10e9, \"nu\": 0.2, \"tensile_strength\": 5e6,"
               " \"shear_strength\": 10e6, \"mu1\": 0.3, \"mu2\": 0.5, \"xi\": 0.05,"
               " \"alpha\": 1}"},
    {"jcfpm", "{\"name\": \"m\", \"law\": \"jcfpm\", \"density\": 2500,"
              " \"E\": 17e9, \"ks_ratio\": 0.15, \"tensile_strength\": 3.163e6,"
              " \"cohesion\": 9e6, \"friction_angle_deg\": 34.25, \"interaction_range\": 1.4}"},
    {"jcfpm", "{\"name\": \"m\", \"law\": \"jcfpm\", \"density\": 2500,"
              " \"E\": 17e9, \"ks_ratio\": 0.15, \"tensile_strength\": 3.163e6,"
              " \"cohesion\": 9e6, \"friction_angle_deg\": 34.25, \"interaction_range\": 1.4,"
              " \"contact\": {\"conventions\": \"yade\"}}"},
    {"exponential", "{\"name\": \"m\", \"law\": \"exponential\", \"density\": 2500,"
                    " \"E0\": 28e9, \"nu\": 0.2, \"tensile_strength\": 10e6,"
                    " \"delta_n\": 0.2, \"cohesion\": 13e6, \"friction_angle_deg\": 30,"
                    " \"contact_friction_angle_deg\": 30, \"interaction_range\": 1.1}"},
};

/* Field by field (padding bytes are not compared), bit for bit. */
static int same_out(const law_out *a, const law_out *b)
{
	return memcmp(&a->fn, &b->fn, sizeof a->fn) == 0 &&
	       memcmp(a->fs, b->fs, sizeof a->fs) == 0 && a->failed == b->failed &&
	       memcmp(&a->fn_viscous, &b->fn_viscous, sizeof a->fn_viscous) == 0 &&
	       memcmp(&a->e_damage, &b->e_damage, sizeof a->e_damage) == 0 &&
	       memcmp(&a->e_friction, &b->e_friction, sizeof a->e_friction) == 0;
}

static int same_bond(const bond *a, const bond *b)
{
	return a->i == b->i && a->j == b->j && memcmp(&a->d0, &b->d0, sizeof a->d0) == 0 &&
	       memcmp(&a->k, &b->k, sizeof a->k) == 0 && memcmp(a->t, b->t, sizeof a->t) == 0 &&
	       memcmp(a->h, b->h, sizeof a->h) == 0 && a->state == b->state;
}

/* One bond into lane q of a batch, and back (every field of the lane). */
static void to_lane(law_batch *B, int q, const law_pair *pr, const bond *b, const law_kin *k)
{
	B->ri[q] = pr->ri;
	B->rj[q] = pr->rj;
	B->mi[q] = pr->mi;
	B->mj[q] = pr->mj;
	B->d0[q] = pr->d0;
	B->un[q] = k->un;
	B->vn[q] = k->vn;
	for (int c = 0; c < 3; c++) {
		B->dus[c][q] = k->dus[c];
		B->t[c][q] = b->t[c];
	}
	for (int c = 0; c < LAW_NHIST; c++)
		B->h[c][q] = b->h[c];
	B->k[q] = b->k;
	B->state[q] = b->state;
}

static void from_lane(const law_batch *B, int q, bond *b, law_out *o)
{
	for (int c = 0; c < 3; c++) {
		b->t[c] = B->t[c][q];
		o->fs[c] = B->fs[c][q];
	}
	for (int c = 0; c < LAW_NHIST; c++)
		b->h[c] = B->h[c][q];
	b->state = B->state[q];
	o->fn = B->fn[q];
	o->fn_viscous = B->fn_viscous[q];
	o->e_damage = B->e_damage[q];
	o->e_friction = B->e_friction[q];
	o->failed = B->failed[q];
}

/* The law's parameters from json, set up for a packing (NULL, and a failed
 * check, when they do not parse). */
static law_params *law_ready(const law *L, const char *json, const char *name)
{
	law_params *p = drive_parse(L, json, name);
	CHECK(p != NULL);
	if (p) {
		law_packing pk = {.porosity = 0.15, .coordination = 7};
		L->setup(p, &pk);
	}
	return p;
}

static void run(const char *name, const char *json)
{
	const law *L = law_find(name);
	law_params *p = law_ready(L, json, name);
	if (!p)
		return;
	rng g;
	rng_seed(&g, 42);
	static law_pair pair[NB];
	static bond one[NB], many[NB];
	static law_kin kin[NB];
	static law_out o1[NB], on[NB];
	double scale[NB];
	for (int q = 0; q < NB; q++) {
		pair[q].ri = rng_range(&g, 0.5e-3, 2e-3);
		pair[q].rj = rng_range(&g, 0.5e-3, 2e-3);
		pair[q].d0 = (pair[q].ri + pair[q].rj) * rng_range(&g, 0.92, 1.08);
		pair[q].mi = 2e3 * pair[q].ri * pair[q].ri * pair[q].ri;
		pair[q].mj = 2e3 * pair[q].rj * pair[q].rj * pair[q].rj;
		one[q] = drive_bond(L, p, &pair[q]);
		many[q] = one[q];
		scale[q] = pair[q].d0 * rng_range(&g, 1e-5, 3e-3);
		kin[q].un = 0;
	}
	int states[4] = {0};
	for (int s = 0; s < NSTEP; s++) {
		for (int q = 0; q < NB; q++) {
			kin[q].un += scale[q] * rng_range(&g, -1.0, 0.9);
			kin[q].vn = rng_range(&g, -1e-3, 1e-3);
			for (int k = 0; k < 3; k++)
				kin[q].dus[k] = scale[q] * rng_range(&g, -0.5, 0.5);
		}
		for (int q = 0; q < NB; q++) /* as the engine does */
			o1[q].fn_viscous = o1[q].e_damage = o1[q].e_friction = 0;
		for (int q = 0; q < NB; q++)
			L->force(p, &pair[q], &one[q], &kin[q], &o1[q]);
		for (int q0 = 0; q0 < NB; q0 += LAW_LANES) {
			law_batch B;
			B.n = NB - q0 < LAW_LANES ? NB - q0 : LAW_LANES;
			for (int q = 0; q < B.n; q++)
				to_lane(&B, q, &pair[q0 + q], &many[q0 + q], &kin[q0 + q]);
			L->force_batch(p, &B);
			for (int q = 0; q < B.n; q++)
				from_lane(&B, q, &many[q0 + q], &on[q0 + q]);
		}
		int same = 1;
		for (int q = 0; q < NB; q++)
			same &= same_out(&o1[q], &on[q]) && same_bond(&one[q], &many[q]);
		CHECK(same);
	}
	for (int q = 0; q < NB; q++)
		states[one[q].state]++;
	/* The paths reached broken bonds and kept some intact or damaged. */
	CHECK(states[BOND_BROKEN_TENSION] + states[BOND_BROKEN_SHEAR] > 0);
	CHECK(states[BOND_INTACT] + states[BOND_DAMAGED] > 0);
	L->free(p);
}

/* Bonds b[0..n) as the engine stores them: records, states, constants
 * (one record more, which law_pairs_load may read). */
typedef struct {
	pair_rec rec[NB + 1];
	uint8_t state[NB];
	double k[NB];
} stored;

/* s as the engine's bond list, for pairlist_put and pairlist_bond. */
static pairlist stored_list(stored *s)
{
	return (pairlist){.rec = s->rec, .state = s->state, .k = s->k};
}

static void store(const bond *b, int n, stored *s)
{
	pairlist l = stored_list(s);
	for (int q = 0; q < n; q++)
		pairlist_put(&l, (size_t)q, &b[q]);
}

/* force_pairs against the staged path along random motions of NB pairs of
 * spheres (sphere 2q and 2q + 1 for bond q), the bonds carried on by the
 * staged path. The first LAW_LANES bonds, one batch, move a thousand times
 * less and stay undamaged: the variant of a loop for batches without
 * damage (onate's plain) is run too, and all their lanes elastic. */
static void run_pairs(const char *name, const char *json)
{
	const law *L = law_find(name);
	if (!L->force_pairs)
		return;
	law_params *p = law_ready(L, json, name);
	if (!p)
		return;
	rng g;
	rng_seed(&g, 7);
	enum { NP = 2 * NB };
	/* One spare item in x, v and w, as force_pairs needs (law_pairs). */
	static double x[3 * (NP + 1)], v[3 * (NP + 1)], w[3 * (NP + 1)], r[NP], m[NP];
	static bond rec[NB], fused[NB];
	static stored staged, loaded_from;
	double un[NB], scale[NB], dt = 1e-6;
	for (int q = 0; q < NB; q++) {
		for (int k = 0; k < 2; k++) {
			r[2 * q + k] = rng_range(&g, 0.5e-3, 2e-3);
			m[2 * q + k] = 2e3 * r[2 * q + k] * r[2 * q + k] * r[2 * q + k];
		}
		law_pair pair = {.ri = r[2 * q],
		                 .rj = r[2 * q + 1],
		                 .mi = m[2 * q],
		                 .mj = m[2 * q + 1],
		                 .d0 = (r[2 * q] + r[2 * q + 1]) * rng_range(&g, 0.92, 1.08)};
		rec[q] = drive_bond(L, p, &pair);
		rec[q].i = 2 * q;
		rec[q].j = 2 * q + 1;
		rec[q].d0 = pair.d0;
		scale[q] = pair.d0 * rng_range(&g, 1e-5, 3e-3) * (q < LAW_LANES ? 1e-3 : 1);
		un[q] = 0;
	}
	int32_t idx[NB];
	for (int q = 0; q < NB; q++)
		idx[q] = NB - 1 - q; /* not in order */
	int lanes[2] = {0, 0}, quiet = 0, plastic = 0, friction = 0, sliding = 0, moved = 0;
	for (int s = 0; s < NSTEP; s++) {
		for (int q = 0; q < NB; q++) {
			un[q] += scale[q] * rng_range(&g, -1.0, 0.9);
			double u[3], l = 0;
			for (int c = 0; c < 3; c++) {
				u[c] = rng_range(&g, -1.0, 1.0);
				l += u[c] * u[c];
			}
			l = sqrt(l);
			for (int c = 0; c < 3; c++) {
				x[6 * q + c] = rng_range(&g, -0.1, 0.1);
				x[6 * q + 3 + c] = x[6 * q + c] + (rec[q].d0 + un[q]) * u[c] / l;
				for (int k = 0; k < 2; k++) {
					v[6 * q + 3 * k + c] =
					    0.5 * scale[q] / dt * rng_range(&g, -1.0, 1.0);
					w[6 * q + 3 * k + c] = 0.5 * scale[q] / dt / r[2 * q + k] *
					                       rng_range(&g, -1.0, 1.0);
				}
			}
		}
		memcpy(fused, rec, sizeof rec);
		store(rec, NB, &staged);
		store(fused, NB, &loaded_from);
		int same = 1;
		for (int q0 = 0; q0 < NB; q0 += LAW_LANES) {
			int nq = NB - q0 < LAW_LANES ? NB - q0 : LAW_LANES;
			const int32_t *ix = idx + q0;
			law_batch B;
			batch_geom geo;
			batch_kinematics(x, v, w, r, m, staged.rec, staged.state, staged.k, ix, nq,
			                 dt, &B, &geo);
			L->force_batch(p, &B);
			batch_history_store(staged.rec, staged.state, ix, &B);
			pairlist back = stored_list(&staged);
			for (int q = 0; q < nq; q++)
				rec[ix[q]] = pairlist_bond(&back, (size_t)ix[q]);
			law_pairs in = {.x = x,
			                .v = v,
			                .w = w,
			                .r = r,
			                .rec = loaded_from.rec,
			                .state = loaded_from.state,
			                .k = loaded_from.k,
			                .idx = ix,
			                .n = nq};
			law_lanes loaded;
			law_pairs_load(&in, &loaded);
			law_fused o;
			o.damage = o.friction = 0; /* as the engine does (bonds.c) */
			int count = L->force_pairs(p, &loaded, nq, dt, &o), elastic = 0;
			for (int q = 0; q < nq; q++) {
				bond *b = &fused[ix[q]];
				lanes[!o.elastic[q]]++;
				if (!o.elastic[q])
					continue;
				elastic++;
				quiet += ix[q] < LAW_LANES;
				double f[6], ev = B.fn_viscous[q] * B.vn[q] * dt;
				batch_force(&B, &geo, q, f);
				for (int c = 0; c < 6; c++)
					same &= memcmp(&f[c], &o.f[c][q], sizeof f[c]) == 0;
				same &= memcmp(&ev, &o.e_viscous[q], sizeof ev) == 0;
				/* Plastic work only where the law gives it. */
				double ed = o.damage ? o.e_damage[q] : 0;
				same &= memcmp(&B.e_damage[q], &ed, sizeof ed) == 0;
				/* Work of sliding only where the law gives it. */
				double ef = o.friction ? o.e_friction[q] : 0;
				same &=
				    memcmp(&B.e_friction[q], &ef, sizeof ef) == 0 && !B.failed[q];
				plastic += ed > 0;
				sliding += ef > 0;
				if (B.state[q] >= BOND_BROKEN_TENSION) {
					friction++;
					for (int c = 0; o.history && c < LAW_NHIST; c++)
						moved += o.h[c][q] != loaded.h[c][q];
				}
				for (int c = 0; c < 3; c++)
					b->t[c] = o.t[c][q];
				if (o.history) { /* as the engine does (bonds.c) */
					for (int c = 0; c < LAW_NHIST; c++)
						b->h[c] = o.h[c][q];
					b->state = (uint8_t)o.state[q];
				}
				same &= same_bond(b, &rec[ix[q]]);
			}
			same &= count == elastic;
		}
		CHECK(same);
	}
	/* Both kinds of lanes were met, and with a hardening curve lanes that
	 * flow plastically in the loop. */
	printf("%s: force_pairs lanes %d elastic (%d of the quiet batch), %d not; %d plastic, "
	       "%d broken (%d sliding, %d history values moved)\n",
	       name, lanes[0], quiet, lanes[1], plastic, friction, sliding, moved);
	CHECK(lanes[0] > 0 && lanes[1] > 0 && quiet == LAW_LANES * NSTEP);
	CHECK(strcmp(L->name, "onate") != 0 || plastic > 0);
	/* And broken bonds' lanes, some of them sliding, and (but for linear,
	 * whose history is only t) some with their history moved (loading
	 * past the largest compression; apart, ended, starting again). */
	CHECK(friction > 0 && sliding > 0);
	CHECK(strcmp(L->name, "linear") == 0 || moved > 0);
	L->free(p);
}

/* law_pairs_load (vectors and transposes, where the CPU has AVX2) gives
 * what its scalar loop gives, and that loop the lanes' definition, bit for
 * bit: every batch size from 1 to LAW_LANES (groups of four and the lanes
 * after them), the lanes out of order or without indices, the last
 * particle among them (its three values read as four: the spare item). */
static void check_load(void)
{
	enum { NP = 40, NR = 2 * LAW_LANES };
	static double x[3 * (NP + 1)], v[3 * (NP + 1)], w[3 * (NP + 1)], r[NP];
	static pair_rec rec[NR + 1];
	static uint8_t state[NR];
	static double kk[NR];
	rng g;
	rng_seed(&g, 11);
	for (int k = 0; k < 3 * NP; k++) {
		x[k] = rng_range(&g, -0.1, 0.1);
		v[k] = rng_range(&g, -1.0, 1.0);
		w[k] = rng_range(&g, -100.0, 100.0);
	}
	for (int k = 0; k < NP; k++)
		r[k] = rng_range(&g, 1e-3, 2e-3);
	for (int b = 0; b < NR; b++) {
		rec[b].i = (int32_t)(rng_u64(&g) % NP);
		rec[b].j = b % 3 ? (int32_t)(rng_u64(&g) % NP) : NP - 1;
		rec[b].d0 = rng_range(&g, 2e-3, 4e-3);
		kk[b] = rng_range(&g, 0.0, 1.0);
		for (int c = 0; c < 3; c++)
			rec[b].t[c] = rng_range(&g, -1e-6, 1e-6);
		for (int c = 0; c < LAW_NHIST; c++)
			rec[b].h[c] = rng_range(&g, 0.0, 1.0);
		state[b] = (uint8_t)(b % 4);
	}
	int32_t order[LAW_LANES];
	for (int q = 0; q < LAW_LANES; q++)
		order[q] = q;
	for (int n = 1; n <= LAW_LANES; n++) {
		int32_t idx[LAW_LANES];
		for (int q = 0; q < n; q++)
			idx[q] = (int32_t)((7 * q + n) % NR);
		law_pairs in = {.x = x,
		                .v = v,
		                .w = w,
		                .r = r,
		                .rec = rec,
		                .state = state,
		                .k = kk,
		                .idx = idx,
		                .n = n};
		law_lanes a, d;
		memset(&a, 0, sizeof a);
		memset(&d, 0, sizeof d);
		law_pairs_load(&in, &a);
		law_pairs_load_lanes(&in, &d, 0);
		CHECK(memcmp(&a, &d, sizeof a) == 0);
		for (int q = 0; q < n; q++) {
			const pair_rec *b = &rec[idx[q]];
			int32_t i = b->i, j = b->j;
			int same = d.ri[q] == r[i] && d.rj[q] == r[j] && d.d0[q] == b->d0 &&
			           d.k[q] == kk[idx[q]] && d.state[q] == state[idx[q]];
			for (int c = 0; c < 3; c++)
				same &= d.dx[c][q] == x[3 * j + c] - x[3 * i + c] &&
				        d.dv[c][q] == v[3 * j + c] - v[3 * i + c] &&
				        d.wi[c][q] == w[3 * i + c] && d.wj[c][q] == w[3 * j + c] &&
				        d.t[c][q] == b->t[c] && d.h[c][q] == b->h[c];
			CHECK(same);
		}
		/* Without indices: the records rec[0..n). */
		law_pairs in0 = in, in1 = in;
		in0.idx = NULL;
		in1.idx = order;
		memset(&a, 0, sizeof a);
		memset(&d, 0, sizeof d);
		law_pairs_load(&in0, &a);
		law_pairs_load_lanes(&in1, &d, 0);
		CHECK(memcmp(&a, &d, sizeof a) == 0);
		/* Without states and constants (contacts): BOND_BROKEN_TENSION, 0;
		 * the records up to the last, the spare one read past it. */
		law_pairs in2 = {.x = x, .v = v, .w = w, .r = r, .rec = rec + NR - n, .n = n};
		memset(&a, 0, sizeof a);
		law_pairs_load(&in2, &a);
		int none = 1;
		for (int q = 0; q < n; q++)
			none &= a.state[q] == BOND_BROKEN_TENSION && a.k[q] == 0 &&
			        a.h[2][q] == rec[NR - n + q].h[2];
		CHECK(none);
	}
}

int main(void)
{
	check_load();
	for (size_t k = 0; k < sizeof materials / sizeof materials[0]; k++)
		run(materials[k][0], materials[k][1]);
	for (size_t k = 0; k < sizeof materials / sizeof materials[0]; k++)
		run_pairs(materials[k][0], materials[k][1]);
	return check_done();
}
