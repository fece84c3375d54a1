/* The reductions over ranks (solve/par.h, solve/reduce.h): blocks of
 * partial sums shared among however many ranks run this test (one, or
 * several under mpirun) give totals identical to the bit to the exact sum
 * of all blocks on one process; maxima and minima likewise. Every rank
 * checks its own result. Usage: test_par [RANKS expected]. */
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
	/* Each of the four reductions counted, with its payload (an exact
	 * accumulator is DEM_XSUM_WORDS int64 words); none on one rank. */
	par_tally t = par_reductions();
	if (size == 1) {
		CHECK(t.calls == 0 && t.bytes == 0 && t.seconds == 0);
	} else {
		CHECK(t.calls == 4);
		CHECK(t.bytes == NF * DEM_XSUM_WORDS * 8 + 3 * 8 + 2 * sizeof(int));
		CHECK(t.seconds >= 0);
	}
	par_tally_reset();
	t = par_reductions();
	CHECK(t.calls == 0 && t.bytes == 0);
	int failed = check_done();
	par_finalize();
	return failed;
}
