/* Neighbour lists and forces of the soft-sphere system (pack/soft.h):
 * every pair within r_i + r_j + skin is listed, twice in a full list (once
 * from each sphere) and once in a half list, as a brute-force search over
 * all pairs finds them, in a periodic box (cells of the reach, and one too
 * short for three cells a side, where pairs take their minimum image) and
 * in an open one with fixed spheres; and the half list's forces are the
 * full list's, summed in another order. */
#include "tests/check.h"

#include "lib/rng.h"
#include "lib/vec3.h"
#include "pack/soft.h"

enum { NMAX = 800 };

/* n spheres, radii uniform in [0.5, 1.5], uniform in [0, edge)^3. */
static void scatter(double *x, double *r, size_t n, double edge, uint64_t seed)
{
	rng g;
	rng_seed(&g, seed);
	for (size_t i = 0; i < n; i++) {
		for (int k = 0; k < 3; k++)
			x[3 * i + k] = edge * rng_uniform(&g);
		r[i] = rng_range(&g, 0.5, 1.5);
	}
}

/* Separation of j from i, minimum image when box > 0. */
static double separation(const double *x, size_t i, size_t j, double box)
{
	double dd = 0;
	for (int k = 0; k < 3; k++) {
		double d = x[3 * j + k] - x[3 * i + k];
		if (box > 0)
			d -= box * nearbyint(d / box);
		dd += d * d;
	}
	return sqrt(dd);
}

/* The list of s (built) against brute force: each pair within reach with
 * a mobile sphere listed `times` times in all (listings from i of j and
 * from j of i), through the image at minimum distance, and no other. */
static void check_list(soft_system *s, double box, int times)
{
	static unsigned char seen[NMAX][NMAX];
	memset(seen, 0, sizeof seen);
	int wrong_image = 0;
	for (size_t i = 0; i < s->nmobile; i++)
		for (size_t q = s->nb_start[i]; q < s->nb_start[i + 1]; q++) {
			size_t j = (size_t)s->nb[q];
			double d[3];
			for (int k = 0; k < 3; k++)
				d[k] =
				    s->x[3 * j + k] - s->x[3 * i + k] + s->shift[s->nb_shift[q]][k];
			wrong_image |=
			    fabs(sqrt(v3_dot(d, d)) - separation(s->x, i, j, box)) > 1e-9;
			seen[i < j ? i : j][i < j ? j : i]++;
		}
	CHECK(!wrong_image);
	size_t pairs = 0, bad = 0;
	for (size_t i = 0; i < s->n; i++)
		for (size_t j = i + 1; j < s->n; j++) {
			int near = separation(s->x, i, j, box) < s->r[i] + s->r[j] + s->skin;
			int want = !near ? 0 : times == 1 ? 1 : (i < s->nmobile) + (j < s->nmobile);
			pairs += near;
			bad += seen[i][j] != want;
		}
	CHECK(pairs > 0);
	CHECK(bad == 0);
}

static void periodic(size_t n, double edge, uint64_t seed)
{
	static double x[3 * NMAX], r[NMAX], xh[3 * NMAX], f[3 * NMAX], fh[3 * NMAX];
	scatter(x, r, n, edge, seed);
	memcpy(xh, x, sizeof x);
	soft_system full, half;
	soft_init(&full, n, n, x, r);
	soft_init(&half, n, n, xh, r);
	for (int k = 0; k < 3; k++)
		full.box[k] = half.box[k] = edge;
	full.skin = half.skin = 0.4;
	half.half = 1;
	soft_rebuild(&full);
	soft_rebuild(&half);
	check_list(&full, edge, 2);
	check_list(&half, edge, 1);
	soft_stats a, b;
	soft_update(&full, 0);
	soft_forces(&full, f, &a);
	soft_forces(&half, fh, &b);
	double err = 0, big = 0;
	for (size_t k = 0; k < 3 * n; k++) {
		err = fmax(err, fabs(f[k] - fh[k]));
		big = fmax(big, fabs(f[k]));
	}
	CHECK(big > 0);
	CHECK(err <= 1e-12 * big);
	CHECK(a.overlap_max == b.overlap_max);
	CHECK(a.contacts == b.contacts);
	CHECK_REL(a.overlap_mean, b.overlap_mean, 1e-12);
	CHECK_REL(a.fmax, b.fmax, 1e-12);
	soft_free(&full);
	soft_free(&half);
}

int main(void)
{
	/* 800 spheres in a box of 10 cells of the reach a side (3.4), then
	 * 30 in a box of 2.4 reaches: one cell along each axis. */
	periodic(800, 34, 1);
	periodic(30, 8, 2);

	/* Open box: the first 300 of 600 spheres move, the others are fixed
	 * and listed only as neighbours. */
	static double x[3 * NMAX], r[NMAX];
	scatter(x, r, 600, 24, 3);
	soft_system s;
	soft_init(&s, 600, 300, x, r);
	s.skin = 0.4;
	soft_rebuild(&s);
	check_list(&s, 0, 2);
	soft_free(&s);
	return check_done();
}
