/* The step's reductions (reduce.h). */
#include "solve/reduce.h"
#include "lib/err.h"
#include "lib/xsum.h"
#include "solve/par.h"

void reduce_blocks(const double *blk, size_t nb, size_t stride, int nf, double *out)
{
	enum { MAXF = 32 };
	if (nf > MAXF)
		fatal("reduce_blocks: %d sums, at most %d", nf, MAXF);
	xsum acc[MAXF];
	for (int f = 0; f < nf; f++)
		xsum_clear(&acc[f]);
	for (size_t k = 0; k < nb; k++)
		for (int f = 0; f < nf; f++)
			xsum_add(&acc[f], blk[k * stride + (size_t)f]);
	par_sum(acc, nf);
	for (int f = 0; f < nf; f++)
		out[f] = xsum_round(&acc[f]);
}
