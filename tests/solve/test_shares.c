/* The bond forces reach the particles the same, bit for bit, however the
 * particles are split into shares (bonds.h): one share, seven shares on the
 * threads of the run (crossing bonds, several shares a thread), and more
 * shares than particle blocks (cut down to one a block). The runs load a
 * cylinder until bonds break, so failures, crossing bonds and the bonds'
 * block sums are all compared. Also: a step's failures sorted by bond
 * index beyond 32 bits, and the split's balance on a larger specimen. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "lib/err.h"
#include "solve/engine.h"
#include "solve/ranks.h"
#include "tests/check.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

static const char *case_text =
    "{\"assembly\": \"-\", \"material\": {\"name\": \"m\", \"law\": \"linear\", "
    "\"density\": 2500, \"E\": 1e10, \"nu\": 0.2, \"tensile_strength\": 2e6, "
    "\"shear_strength\": 4e6}, \"loading\": [{\"axial\": {\"mode\": \"strain_rate\", "
    "\"rate\": 40}}], \"stop\": {\"steps\": 400}}";

enum { STEPS = 400 };

/* Run STEPS steps of e with its particles in the given number of shares. */
static void run(engine *e, const dem_case *c, const dem_assembly *a, int shares)
{
	harness_engine(e, c, a);
	bonds_split(e, shares);
	ranks_split(e);
	for (int s = 0; s < STEPS; s++)
		engine_step(e, s % 50 == 0);
}

/* Split e into shares of a larger specimen: each non-empty, and the work
 * bonds_split takes each share to have (particles, bonds, crossing bonds
 * once more) within one particle block's of the mean. */
static void check_balance(engine *e, int shares)
{
	bonds_split(e, shares);
	const bond_split *S = &e->pairs.split;
	CHECK(S->n == shares);
	size_t nblk = nblocks(e->p.n), most = 0, total = 0;
	for (size_t b = 0; b < nblk; b++) {
		size_t w = S->bfirst[b + 1] - S->bfirst[b] + BLOCK;
		most = w > most ? w : most;
	}
	double work[16];
	for (int k = 0; k < shares; k++) {
		size_t p0 = S->pfirst[k], p1 = S->pfirst[k + 1];
		CHECK(p1 > p0);
		size_t cross = S->cfirst[k + 1] - S->cfirst[k];
		most = cross > most ? cross : most;
		work[k] =
		    (double)(p1 - p0 + S->bfirst[nblocks(p1)] - S->bfirst[p0 / BLOCK] + cross);
		total += (size_t)work[k];
	}
	for (int k = 0; k < shares; k++)
		CHECK(fabs(work[k] - (double)total / shares) <= (double)most);
}

static int same(const void *x, const void *y, size_t n) { return memcmp(x, y, n) == 0; }

/* A step's failures go to e's crack list in the order of their bonds in
 * the whole specimen, whose indices pass 2^31 over many ranks: one found
 * at bond 2^31 + 5, then one at bond 7. */
static void check_crack_order(engine *e)
{
	crack_buf *tc = &e->out.thread_cracks[0], *cb = &e->out.cracks;
	int64_t far = (int64_t)INT32_MAX + 6, near = 7;
	tc->cap = tc->n + 2;
	tc->c = xrealloc(tc->c, tc->cap * sizeof *tc->c);
	tc->bond = xrealloc(tc->bond, tc->cap * sizeof *tc->bond);
	size_t first = cb->n;
	tc->c[tc->n] = (dem_crack){.step = 1};
	tc->bond[tc->n++] = far;
	tc->c[tc->n] = (dem_crack){.step = 2};
	tc->bond[tc->n++] = near;
	bonds_collect_cracks(e);
	CHECK(cb->n == first + 2);
	CHECK(cb->bond[first] == near && cb->bond[first + 1] == far);
	CHECK(cb->c[first].step == 2 && cb->c[first + 1].step == 1);
}

int main(void)
{
	dem_assembly a;
	fixture_cylinder(&a, 3);
	dem_case c;
	harness_case(&c, case_text);
	engine one, many, most;
	run(&one, &c, &a, 1);
	run(&many, &c, &a, 7);
	run(&most, &c, &a, 100000);
	CHECK(one.pairs.split.n == 1 && many.pairs.split.n == 7);
	CHECK(most.pairs.split.n == (int)nblocks(most.p.n));
	/* Bonds reached into later shares, and some broke. */
	CHECK(many.pairs.split.cfirst[7] > 0);
	size_t broken = 0;
	for (size_t b = 0; b < one.pairs.bonds.n; b++)
		broken += one.pairs.bonds.state[b] >= BOND_BROKEN_TENSION;
	CHECK(broken > 0);
	const engine *other[2] = {&many, &most};
	size_t n = one.p.n, nb = one.pairs.bonds.n;
	for (int k = 0; k < 2; k++) {
		const engine *e = other[k];
		CHECK(same(one.p.x, e->p.x, 3 * n * sizeof *one.p.x));
		CHECK(same(one.p.v, e->p.v, 3 * n * sizeof *one.p.v));
		CHECK(same(one.p.w, e->p.w, 3 * n * sizeof *one.p.w));
		CHECK(same(one.pairs.bonds.fb, e->pairs.bonds.fb,
		           3 * nb * sizeof *one.pairs.bonds.fb));
		int records = 1;
		for (size_t b = 0; b < nb; b++) {
			bond p = pairlist_bond(&one.pairs.bonds, b),
			     q = pairlist_bond(&e->pairs.bonds, b);
			records &= same(p.t, q.t, sizeof p.t) && same(p.h, q.h, sizeof p.h) &&
			           same(&p.k, &q.k, sizeof p.k) && p.state == q.state;
		}
		CHECK(records);
		CHECK(same(&one.sums.bonds, &e->sums.bonds, sizeof one.sums.bonds));
		CHECK(same(&one.energy, &e->energy, sizeof one.energy));
		CHECK(one.out.cracks.n == e->out.cracks.n &&
		      same(one.out.cracks.bond, e->out.cracks.bond,
		           one.out.cracks.n * sizeof *one.out.cracks.bond));
	}
	check_crack_order(&one);
	engine_free(&one), engine_free(&many), engine_free(&most);
	/* About 11 000 spheres, 43 blocks. */
	lattice l = {.kind = LATTICE_FCC,
	             .nx = 14,
	             .ny = 14,
	             .nz = 14,
	             .r = 1e-3,
	             .jitter = 0.02,
	             .polydisp = 0.02,
	             .seed = 7};
	dem_assembly big;
	fixture_lattice(&big, &l);
	engine e;
	harness_engine(&e, &c, &big);
	CHECK(nblocks(e.p.n) > 40);
	for (int shares = 2; shares <= 16; shares *= 2)
		check_balance(&e, shares);
	engine_free(&e);
	assembly_free(&big);
	case_free(&c);
	assembly_free(&a);
	return check_done();
}
