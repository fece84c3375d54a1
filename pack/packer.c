/* The packing pipeline (see packer.h).
 *
 * The periodic cell holds half as many spheres as the specimen, at least
 * CELL_MIN and at most cell_max (its cost grows with its size; a large
 * specimen repeats it, which periodicity makes seamless); when the
 * specimen's bounding box holds fewer, the cell is that box. An edge is
 * never shorter than 8 r_max, so no sphere meets two images of another.
 * Tolerances: the cell and the band stop at a largest overlap of 0.5 % of
 * the smaller radius; pruning removes what still exceeds 0.9 %, so the
 * assembly stays below the 1 % a bond's reference length tolerates. Voids
 * are filled only against the boundary, where the cut left them: deeper,
 * the room a sphere of r_min finds is the cage of a rattler of the jammed
 * cell, and filling it would add small spheres the size distribution does
 * not have. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/timer.h"
#include "pack/band.h"
#include "pack/jam.h"
#include "pack/packer.h"
#include "pack/prune.h"
#include "pack/tile.h"
#include "pack/voids.h"

static const double PHI_RCP = 0.64, CELL_OTOL = 0.005, BAND_OTOL = 0.005, PRUNE_LIMIT = 0.009;
static const long BAND_ITER = 300, REFILL_ITER = 60, SHRINK_AFTER = 50;
static const double CELL_MIN = 1000;
static const double COUNT_TOL = 0.003; /* on the size scale: 1 % on the count */
static const int COUNT_PASSES = 3;

/* The mean volume of a sphere of d. */
static double mean_volume(const psd *d) { return 4.0 / 3.0 * M_PI * psd_moment(d, 3); }

double packer_count_estimate(const psd *d, double volume)
{
	return PHI_RCP * volume / mean_volume(d);
}

double packer_count_scale(const psd *d, double volume, long count)
{
	return cbrt(PHI_RCP * volume / ((double)count * mean_volume(d)));
}

static void cell_shape(const psd *d, const dem_geometry *g, long cell_max, double shape[3],
                       size_t *n)
{
	double v = 4.0 / 3.0 * M_PI * psd_moment(d, 3), vb = 1, edge_min = 8 * d->rmax;
	for (int k = 0; k < 3; k++) {
		shape[k] = fmax(g->bbox_max[k] - g->bbox_min[k], edge_min);
		vb *= shape[k];
	}
	double nb = PHI_RCP * vb / v,
	       want = fmin(fmax(0.5 * PHI_RCP * g->volume / v, CELL_MIN), (double)cell_max);
	want = fmax(want, PHI_RCP * pow(edge_min, 3) / v);
	if (nb <= want) {
		*n = (size_t)ceil(nb);
		return;
	}
	shape[0] = shape[1] = shape[2] = 1;
	*n = (size_t)ceil(want);
}

/* Multiply the cell's lengths, and the distribution's sizes, by s. */
static void scale_cell(jam_cell *c, psd *d, double s)
{
	for (size_t i = 0; i < 3 * c->n; i++)
		c->x[i] *= s;
	for (size_t i = 0; i < c->n; i++)
		c->r[i] *= s;
	for (int k = 0; k < 3; k++)
		c->box[k] *= s;
	psd_scale(d, s);
}

/* Tile the cell over the specimen and repair the wall band. */
static void fill(spheres *S, const jam_cell *c, const psd *d, const dem_geometry *g,
                 const surface *surf, const zones *z, const packer_params *params, packer_stats *st)
{
	double t0 = timer_now();
	S->n = 0;
	tile_fill(S, c, surf, z, g->bbox_min, g->bbox_max, params->keep);
	st->tiled = S->n;
	double t1 = timer_now();
	st->time_tile += t1 - t0;
	double rmean = 0, rmax = 0;
	for (size_t i = 0; i < c->n; i++) {
		rmean += c->r[i] / (double)c->n;
		rmax = fmax(rmax, c->r[i]);
	}
	progress prog;
	progress_start(&prog, "iterations", BAND_ITER + REFILL_ITER);
	band_params bp = {
	    params->band * 2 * rmean, BAND_OTOL, BAND_ITER, SHRINK_AFTER, 0.2 * rmean, &prog};
	band_result br;
	band_relax(S, surf, g, &bp, &br);
	st->band_mobile = br.mobile;
	st->band_iter = br.iter;
	double t2 = timer_now();
	st->time_band += t2 - t1;
	st->inserted = voids_fill(S, surf, g, d, params->seed);
	double t3 = timer_now();
	st->time_voids += t3 - t2;
	bp.max_iter = REFILL_ITER;
	bp.shrink_after = 0;
	band_relax(S, surf, g, &bp, &br);
	st->band_iter += br.iter;
	st->shrunk = br.shrunk;
	st->shrink_mean = br.shrink_mean;
	st->shrink_max = br.shrink_max;
	double t4 = timer_now();
	st->time_refill += t4 - t3;
	st->pruned = prune_overlaps(S, surf, bp.width + 2 * rmax + bp.skin, PRUNE_LIMIT);
	st->time_prune += timer_now() - t4;
	progress_end(&prog);
}

void packer_cell(jam_cell *c, psd *d, const dem_geometry *g, const packer_params *params,
                 packer_stats *st)
{
	double t0 = timer_now();
	double shape[3];
	size_t n;
	cell_shape(d, g, params->cell_max, shape, &n);
	progress prog;
	progress_start(&prog, "iterations", 0);
	int threads = omp_get_max_threads();
	omp_set_num_threads(1);
	jam_make(c, d, n, shape, params->seed, CELL_OTOL, &prog);
	omp_set_num_threads(threads);
	progress_end(&prog);
	st->cell_n = c->n;
	st->cell_phi = c->phi;
	st->cell_iter = c->iter;
	double vs = sphere_volume(c->r, c->n);
	if (params->count > 0) /* the cell's own solid fraction refines the scale */
		scale_cell(c, d,
		           cbrt(c->phi * g->volume / (vs / (double)c->n) / (double)params->count));
	st->time_cell = timer_now() - t0;
}

void packer_fill(spheres *S, jam_cell *c, psd *d, const dem_geometry *g, const surface *surf,
                 const zones *z, const packer_params *params, packer_stats *st)
{
	double t1 = timer_now();
	fill(S, c, d, g, surf, z, params, st);
	/* The wall band loses and gains spheres: up to COUNT_PASSES - 1 more
	 * passes, each at the scale that corrects the last count. */
	for (int pass = 1; params->count > 0 && pass < COUNT_PASSES; pass++) {
		double s = cbrt((double)S->n / (double)params->count);
		if (fabs(s - 1) <= COUNT_TOL)
			break;
		scale_cell(c, d, s);
		fill(S, c, d, g, surf, z, params, st);
	}
	st->time_fill = timer_now() - t1;
}

void packer_print(const packer_stats *st, FILE *out)
{
	fprintf(out,
	        "  packing          periodic cell of %zu spheres at %.4f (%ld iterations), %zu "
	        "tiled\n",
	        st->cell_n, st->cell_phi, st->cell_iter, st->tiled);
	fprintf(out, "  wall band        %zu moved (%ld iterations), %zu inserted, %zu removed;\n",
	        st->band_mobile, st->band_iter, st->inserted, st->pruned);
	fprintf(out,
	        "                   %zu left smaller than drawn, by %.2f %% on average, %.1f "
	        "%% at most\n",
	        st->shrunk, 100 * st->shrink_mean, 100 * st->shrink_max);
	fprintf(out,
	        "  fill time        tile %.3f, wall band %.3f, voids %.3f, settling %.3f, "
	        "pruning %.3f s\n",
	        st->time_tile, st->time_band, st->time_voids, st->time_refill, st->time_prune);
}
