/* The step's reductions (reduce.h). */
#include "solve/reduce.h"
#include "lib/err.h"
#include "solve/par.h"

void reduce_clear(reduction *r) { r->nsum = r->nmax = 0; }

/* nf new sums, cleared: the first of them. */
static xsum *new_sums(reduction *r, int nf)
{
	if (nf > REDUCE_SUMS - r->nsum)
		fatal("reduce: %d sums, at most %d", r->nsum + nf, REDUCE_SUMS);
	xsum *acc = r->sum + r->nsum;
	for (int f = 0; f < nf; f++)
		xsum_clear(&acc[f]);
	r->nsum += nf;
	return acc;
}

void reduce_part_add(xsum *acc, const double *blk, size_t nb, size_t stride, int nf)
{
	for (size_t k = 0; k < nb; k++)
		for (int f = 0; f < nf; f++)
			xsum_add(&acc[f], blk[k * stride + (size_t)f]);
}

int reduce_add_blocks(reduction *r, const double *blk, size_t nb, size_t stride, int nf)
{
	int k0 = r->nsum;
	reduce_part_add(new_sums(r, nf), blk, nb, stride, nf);
	return k0;
}

int reduce_add_parts(reduction *r, const xsum *first, int nparts, size_t bytes, int nf)
{
	int k0 = r->nsum;
	xsum *acc = new_sums(r, nf);
	for (int q = 0; q < nparts; q++) {
		const xsum *part = (const xsum *)(const void *)((const char *)first + q * bytes);
		for (int f = 0; f < nf; f++)
			xsum_merge(&acc[f], &part[f]);
	}
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
