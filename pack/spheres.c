#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "pack/spheres.h"

void spheres_push(spheres *S, const double x[3], double r, double lo, double hi)
{
	if (S->n == S->cap) {
		S->cap = S->cap ? 2 * S->cap : 1024;
		S->x = xrealloc(S->x, 3 * S->cap * sizeof *S->x);
		S->r = xrealloc(S->r, S->cap * sizeof *S->r);
		S->r0 = xrealloc(S->r0, S->cap * sizeof *S->r0);
		S->lo = xrealloc(S->lo, S->cap * sizeof *S->lo);
		S->hi = xrealloc(S->hi, S->cap * sizeof *S->hi);
	}
	memcpy(S->x + 3 * S->n, x, 3 * sizeof *x);
	S->r[S->n] = r;
	S->r0[S->n] = r;
	S->lo[S->n] = lo;
	S->hi[S->n] = hi;
	S->n++;
}

void spheres_compact(spheres *S, const unsigned char *keep)
{
	size_t m = 0;
	for (size_t i = 0; i < S->n; i++) {
		if (!keep[i])
			continue;
		memmove(S->x + 3 * m, S->x + 3 * i, 3 * sizeof *S->x);
		S->r[m] = S->r[i];
		S->r0[m] = S->r0[i];
		S->lo[m] = S->lo[i];
		S->hi[m] = S->hi[i];
		m++;
	}
	S->n = m;
}

void spheres_free(spheres *S)
{
	free(S->x);
	free(S->r);
	free(S->r0);
	free(S->lo);
	free(S->hi);
	memset(S, 0, sizeof *S);
}

double sphere_volume(const double *r, size_t n)
{
	double v = 0;
	for (size_t i = 0; i < n; i++)
		v += 4.0 / 3.0 * M_PI * r[i] * r[i] * r[i];
	return v;
}
