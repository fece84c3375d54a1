/* The reductions over ranks (solve/par.h, solve/reduce.h): blocks of
 * partial sums shared among however many ranks run this test (one, or
 * several under mpirun) give totals identical to the bit to the exact sum
 * of all blocks on one process; maxima and minima likewise. Every rank
 * checks its own result. Usage: test_par [RANKS expected]. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/rng.h"
#include "lib/xsum.h"
#include "solve/par.h"
#include "solve/reduce.h"
#include "tests/check.h"

enum { NB = 1001, NF = 5 };

int main(int argc, char **argv)
{
	if (par_init(&argc, &argv)) {
		fprintf(stderr, "test_par: %s\n", err_msg());
		return 1;
	}
	int rank = par_rank(), size = par_size();
	/* The number of ranks the test was started on, when given. */
	CHECK(argc < 2 || size == atoi(argv[1]));
	/* The same blocks on every rank, over a wide range of magnitudes and
	 * signs; each rank reduces its own contiguous share. */
	static double blk[NB][NF];
	rng r;
	rng_seed(&r, 11);
	for (int k = 0; k < NB; k++)
		for (int f = 0; f < NF; f++)
			blk[k][f] =
			    (rng_uniform(&r) - 0.3) * ldexp(1, (int)(rng_uniform(&r) * 80) - 40);
	double want[NF];
	for (int f = 0; f < NF; f++) {
		xsum s;
		xsum_clear(&s);
		for (int k = 0; k < NB; k++)
			xsum_add(&s, blk[k][f]);
		want[f] = xsum_round(&s);
	}
	int k0 = rank * NB / size, k1 = (rank + 1) * NB / size;
	double got[NF];
	reduce_blocks(&blk[k0][0], (size_t)(k1 - k0), NF, NF, got);
	CHECK(memcmp(got, want, sizeof got) == 0);

	double mx[2] = {rank, -rank}, mn[1] = {rank + 0.5};
	par_max(mx, 2);
	par_min(mn, 1);
	CHECK(mx[0] == size - 1 && mx[1] == 0 && mn[0] == 0.5);
	int flags[2] = {rank == size - 1, 0};
	par_max_int(flags, 2);
	CHECK(flags[0] == 1 && flags[1] == 0);
	/* A step's reduction: as many sums as it holds (some 35 kB, which an
	 * MPI library may reduce in pieces) and maxima, in one collective,
	 * the same as on one process. */
	static double wide[NB][REDUCE_SUMS];
	for (int k = 0; k < NB; k++)
		for (int f = 0; f < REDUCE_SUMS; f++)
			wide[k][f] = blk[k][f % NF] * (1 + f);
	static reduction red, one;
	reduce_clear(&red);
	reduce_clear(&one);
	int kw = reduce_add_blocks(&red, &wide[k0][0], (size_t)(k1 - k0), REDUCE_SUMS, 20);
	reduce_add_blocks(&red, &wide[k0][20], (size_t)(k1 - k0), REDUCE_SUMS, REDUCE_SUMS - 20);
	reduce_add_blocks(&one, &wide[0][0], NB, REDUCE_SUMS, REDUCE_SUMS);
	int km = reduce_add_max(&red, rank);
	reduce_add_max(&red, -rank - 1.5);
	reduce_add_max(&red, rank == 1 ? 7 : 0);
	reduce_finish(&red);
	double all[REDUCE_SUMS], ref[REDUCE_SUMS];
	reduce_sums(&red, kw, REDUCE_SUMS, all);
	reduce_sums(&one, 0, REDUCE_SUMS, ref);
	CHECK(memcmp(all, ref, sizeof all) == 0);
	CHECK(red.max[km] == size - 1 && red.max[km + 1] == -1.5 &&
	      red.max[km + 2] == (size > 1 ? 7 : 0));
	/* The outermost of each bin and, among equals, the lowest index. */
	double v[3] = {rank, 1, -INFINITY};
	int32_t at[3] = {10 + rank, 100 - rank, -1};
	par_maxloc(v, at, 3);
	CHECK(v[0] == size - 1 && at[0] == 10 + size - 1);
	CHECK(v[1] == 1 && at[1] == 100 - (size - 1));
	CHECK(v[2] == -INFINITY && at[2] == -1);
	/* Each of the six reductions counted, with its payload (an exact
	 * accumulator is DEM_XSUM_WORDS int64 words, led by a count word);
	 * none on one rank. */
	par_tally t = par_reductions();
	if (size == 1) {
		CHECK(t.calls == 0 && t.bytes == 0 && t.seconds == 0);
	} else {
		CHECK(t.calls == 6);
		CHECK(t.bytes == (1 + NF * DEM_XSUM_WORDS) * 8 + 3 * 8 + 2 * sizeof(int) +
		                     (1 + REDUCE_SUMS * DEM_XSUM_WORDS + 3) * 8 +
		                     3 * (sizeof(double) + sizeof(int)));
		CHECK(t.seconds >= 0);
	}
	par_tally_reset();
	t = par_reductions();
	CHECK(t.calls == 0 && t.bytes == 0);
	int failed = check_done();
	par_finalize();
	return failed;
}
