/* The step's reductions (reduce.h). */
#include "solve/reduce.h"
#include "lib/err.h"
#include "solve/par.h"

void reduce_clear(reduction *r) { r->nsum = r->nmax = 0; }

int reduce_add_blocks(reduction *r, const double *blk, size_t nb, size_t stride, int nf)
{
	int k0 = r->nsum;
	if (nf > REDUCE_SUMS - k0)
		fatal("reduce_add_blocks: %d sums, at most %d", k0 + nf, REDUCE_SUMS);
	xsum *acc = r->sum + k0;
	for (int f = 0; f < nf; f++)
		xsum_clear(&acc[f]);
	for (size_t k = 0; k < nb; k++)
		for (int f = 0; f < nf; f++)
			xsum_add(&acc[f], blk[k * stride + (size_t)f]);
	r->nsum += nf;
	return k0;
}

int reduce_add_max(reduction *r, double v)
{
	if (r->nmax == REDUCE_MAXIMA)
		fatal("reduce_add_max: at most %d maxima", REDUCE_MAXIMA);
	r->max[r->nmax] = v;
	return r->nmax++;
}

void reduce_finish(reduction *r) { par_sum_max(r->sum, r->nsum, r->max, r->nmax); }

void reduce_sums(const reduction *r, int k, int nf, double *out)
{
	for (int f = 0; f < nf; f++)
		out[f] = xsum_round(&r->sum[k + f]);
}

void reduce_blocks(const double *blk, size_t nb, size_t stride, int nf, double *out)
{
	reduction r;
	reduce_clear(&r);
	int k = reduce_add_blocks(&r, blk, nb, stride, nf);
	reduce_finish(&r);
	reduce_sums(&r, k, nf, out);
}
