/* Packing report (see report.h).
 *
 * Solid fraction profile: with s_i the depth of centre i below the boundary
 * (its signed distance), sphere i puts the volume
 *     V_i[a, b] = pi [r^2 t - t^3/3] from t = max(a - s_i, -r) to min(b - s_i, r)
 * at depths between a and b (the boundary is taken as flat over one sphere,
 * exact for faces and off by O(r/R) on a surface of curvature radius R).
 * phi(w) in a bin [a, b] is sum_i V_i[a, b] over the volume of the specimen
 * at those depths, V_in(a) - V_in(b), V_in(w) being the volume deeper than
 * w: exact for the built-in shapes, for files measured by stratified
 * random points (27 per zone cell near the boundary, about 1.4 per
 * sphere volume).
 *     phi_core = sum_i V_i[w_c, inf) / V_in(w_c),  w_c = 2 mean diameters,
 *     delta*   = integral_0^{w_c} (phi_core - phi(w)) dw   (in mean diameters).
 * Contacts: pairs with d_ij <= (1 + beta)(r_i + r_j) (Eq. 16 of Onate et al.
 * 2015) give the coordination N_c = 2 B / N and alpha = 40 P / N_c with P
 * = 1 - phi the porosity (Eq. 22); the same count over the core spheres and
 * over the boundary layer (centres less than REPORT_LAYER_DEPTH deep), and
 * the spheres left without any bond. Fabric F = <n n> over such pairs with
 * both spheres in the core; anisotropy sqrt(3/2 D:D) with D = F - I/3,
 * which is the difference of principal values for an axisymmetric fabric
 * (0 isotropic, 1 all contacts along one axis). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/rng.h"
#include "lib/vec3.h"
#include "pack/cells.h"
#include "pack/geometry.h"
#include "pack/report.h"
#include "pack/spheres.h"

static double cap_volume(double r, double t0, double t1)
{
	t0 = fmax(t0, -r);
	t1 = fmin(t1, r);
	if (t1 <= t0)
		return 0;
	return M_PI * (r * r * (t1 - t0) - (t1 * t1 * t1 - t0 * t0 * t0) / 3);
}

/* Depth of every centre: exact where it matters (shallower than `limit`
 * plus its radius), else the zone's lower bound. The exact ones are taken
 * zone cell by zone cell among the triangles near the cell. */
static double *depths(const dem_assembly *a, const surface *surf, const zones *z, double limit)
{
	size_t n = a->n, ncell = (size_t)z->dim[0] * (size_t)z->dim[1] * (size_t)z->dim[2];
	double *s = xmalloc(n * sizeof *s + 1), rmax = 0;
	size_t *cell = xmalloc(n * sizeof *cell + 1), *start = xcalloc(ncell + 1, sizeof *start);
	size_t *item = xmalloc(n * sizeof *item + 1);
	for (size_t i = 0; i < n; i++) {
		cell[i] = zones_cell(z, a->x + 3 * i);
		start[cell[i] + 1]++;
		rmax = fmax(rmax, a->r[i]);
	}
	for (size_t c = 0; c < ncell; c++)
		start[c + 1] += start[c];
	size_t *fill = xmalloc(ncell * sizeof *fill + 1);
	memcpy(fill, start, ncell * sizeof *fill);
	for (size_t i = 0; i < n; i++)
		item[fill[cell[i]]++] = i;
	free(fill);
	enum { NEAR_MAX = 256 };
#pragma omp parallel for schedule(dynamic, 64)
	for (size_t c = 0; c < ncell; c++) {
		if (start[c] == start[c + 1])
			continue;
		if (z->lb[c] >= limit + rmax) {
			for (size_t q = start[c]; q < start[c + 1]; q++)
				s[item[q]] = z->lb[c];
			continue;
		}
		double centre[3];
		zones_centre(z, c, centre);
		int32_t near[NEAR_MAX];
		size_t nnear =
		    surface_near(surf, centre, sqrt(3.0) * z->edge + limit + rmax, near, NEAR_MAX);
		for (size_t q = start[c]; q < start[c + 1]; q++) {
			size_t i = item[q];
			int32_t hint = z->hint[c];
			if (z->lb[c] >= limit + a->r[i])
				s[i] = z->lb[c];
			else if (nnear <= NEAR_MAX)
				s[i] = surface_distance_among(surf, a->x + 3 * i, near, nnear);
			else
				s[i] = surface_distance(surf, a->x + 3 * i, NULL, &hint);
		}
	}
	free(cell);
	free(start);
	free(item);
	return s;
}

/* V_in at the bin edges edge[0..nb] (edge[0] = 0). */
static void inner_volumes(const dem_geometry *g, const surface *surf, const zones *z,
                          const double *edge, size_t nb, double *vin)
{
	if (geometry_inner_volume(g, 0) >= 0) {
		for (size_t k = 0; k <= nb; k++)
			vin[k] = geometry_inner_volume(g, edge[k]);
		return;
	}
	/* Stratified sampling: one point at a random place in each of the
	 * PROBES^3 sub-cells of every zone cell near the boundary (random, so
	 * the points do not alias with faces parallel to the grid), its depth
	 * taken among the triangles near the cell. */
	enum { PROBES = 3, NEAR_MAX = 256 };
	size_t ncell = (size_t)z->dim[0] * (size_t)z->dim[1] * (size_t)z->dim[2];
	double h = z->edge / PROBES, dv = h * h * h, wmax = edge[nb], dw = wmax / (double)nb;
	double *hist = xcalloc(nb + 1, sizeof *hist);
	size_t nblock = (ncell + 255) / 256;
	double *part = xcalloc(nblock * nb + 1, sizeof *part);
#pragma omp parallel for schedule(dynamic, 1)
	for (size_t blk = 0; blk < nblock; blk++) {
		double *ph = part + blk * nb;
		size_t end = (blk + 1) * 256 < ncell ? (blk + 1) * 256 : ncell;
		for (size_t c = blk * 256; c < end; c++) {
			if (z->ub[c] < 0 || z->lb[c] >= wmax)
				continue;
			double centre[3];
			zones_centre(z, c, centre);
			int32_t near[NEAR_MAX];
			size_t nnear =
			    surface_near(surf, centre, sqrt(3.0) * z->edge + wmax, near, NEAR_MAX);
			rng g;
			rng_seed_stream(&g, 0x70726f6265ULL, c);
			for (int q = 0; q < PROBES * PROBES * PROBES; q++) {
				int o[3] = {q % PROBES, q / PROBES % PROBES, q / (PROBES * PROBES)};
				double p[3];
				for (int d = 0; d < 3; d++)
					p[d] =
					    centre[d] + (o[d] + rng_uniform(&g) - 0.5 * PROBES) * h;
				int32_t hint = z->hint[c];
				double s = nnear <= NEAR_MAX
				               ? surface_distance_among(surf, p, near, nnear)
				               : surface_distance(surf, p, NULL, &hint);
				if (s < 0 || s >= wmax)
					continue;
				size_t b = (size_t)(s / dw);
				ph[b < nb ? b : nb - 1] += dv;
			}
		}
	}
	for (size_t blk = 0; blk < nblock; blk++)
		for (size_t k = 0; k < nb; k++)
			hist[k] += part[blk * nb + k];
	free(part);
	vin[0] = g->volume;
	for (size_t k = 0; k < nb; k++)
		vin[k + 1] = vin[k] - hist[k];
	free(hist);
}

static void profile(dem_assembly *a, const double *s, const surface *surf, const zones *z)
{
	dem_report *rep = &a->report;
	double dmean = 2 * rep->mean_radius, wc = REPORT_CORE_DEPTH * dmean;
	size_t nb = REPORT_PROFILE_BINS,
	       ncore = (size_t)lround(nb * REPORT_CORE_DEPTH / REPORT_PROFILE_DEPTH);
	double dw = REPORT_PROFILE_DEPTH * dmean / (double)nb;
	double edge[REPORT_PROFILE_BINS + 1], vin[REPORT_PROFILE_BINS + 1];
	double mass[REPORT_PROFILE_BINS] = {0}, core = 0;
	for (size_t k = 0; k <= nb; k++)
		edge[k] = dw * (double)k;
	for (size_t i = 0; i < a->n; i++) {
		double r = a->r[i];
		if (s[i] - r >= edge[nb] && s[i] - r >= wc) {
			core += 4.0 / 3.0 * M_PI * r * r * r;
			continue;
		}
		for (size_t k = 0; k < nb; k++)
			mass[k] += cap_volume(r, edge[k] - s[i], edge[k + 1] - s[i]);
		core += cap_volume(r, wc - s[i], r);
	}
	inner_volumes(&a->geom, surf, z, edge, nb, vin);
	rep->nprofile = nb;
	rep->profile_w = xmalloc(nb * sizeof *rep->profile_w);
	rep->profile_phi = xmalloc(nb * sizeof *rep->profile_phi);
	double vcore = vin[ncore];
	rep->solid_fraction_core = vcore > 0 ? core / vcore : 0;
	double deficit = 0;
	for (size_t k = 0; k < nb; k++) {
		double shell = vin[k] - vin[k + 1];
		rep->profile_w[k] = 0.5 * (edge[k] + edge[k + 1]);
		rep->profile_phi[k] = shell > 0 ? mass[k] / shell : 0;
		if (k < ncore)
			deficit += (rep->solid_fraction_core - rep->profile_phi[k]) * dw;
	}
	rep->wall_deficit = dmean > 0 ? deficit / dmean : 0;
}

/* What the pair loop sums over one block of spheres. The blocks are fixed,
 * and their sums added in block order, so that the totals do not depend on
 * the number of threads; the maxima are exact in any order. */
typedef struct {
	double bonds;                     /* pairs within (1 + beta)(r_i + r_j) */
	double fabric[6];                 /* sum of n n over core pairs: xx yy zz xy xz yz */
	double ncore;                     /* core pairs */
	double ov_sum, ov_n, ov_max;      /* overlaps relative to the smaller radius */
	double wall_max;                  /* overlap with the boundary relative to the radius */
	double core_spheres, core_ends;   /* spheres in the core, bond ends there */
	double layer_spheres, layer_ends; /* the same in the boundary layer */
} contact_sums;

/* What every block reads: the spheres, the depth of each centre (s), where
 * it lies ('c' core, 'l' boundary layer, 0 between) and the grid. */
typedef struct {
	const dem_assembly *a;
	const double *s;
	const char *where;
	double beta;
	pack_cells g;
	char *bonded; /* set for each sphere in a bond, from any thread */
} contact_scan;

/* Add the pair (i, j) if it is a bond: within (1 + beta) (r_i + r_j). */
static void add_pair(contact_sums *p, const contact_scan *cs, size_t i, size_t j)
{
	const dem_assembly *a = cs->a;
	double ri = a->r[i], beta = cs->beta, d[3];
	v3_sub(d, a->x + 3 * j, a->x + 3 * i);
	double sum = ri + a->r[j], dd = v3_dot(d, d);
	if (dd > (1 + beta) * (1 + beta) * sum * sum)
		return;
	double dist = sqrt(dd);
	p->bonds += 1;
	p->core_ends += (cs->where[i] == 'c') + (cs->where[j] == 'c');
	p->layer_ends += (cs->where[i] == 'l') + (cs->where[j] == 'l');
#pragma omp atomic write
	cs->bonded[i] = 1;
#pragma omp atomic write
	cs->bonded[j] = 1;
	if (dist < sum) {
		double rel = (sum - dist) / fmin(ri, a->r[j]);
		p->ov_sum += rel;
		p->ov_n += 1;
		p->ov_max = fmax(p->ov_max, rel);
	}
	if (cs->where[i] == 'c' && cs->where[j] == 'c' && dist > 0) {
		double u[3];
		v3_scale(u, d, 1 / dist);
		p->fabric[0] += u[0] * u[0];
		p->fabric[1] += u[1] * u[1];
		p->fabric[2] += u[2] * u[2];
		p->fabric[3] += u[0] * u[1];
		p->fabric[4] += u[0] * u[2];
		p->fabric[5] += u[1] * u[2];
		p->ncore += 1;
	}
}

/* The pairs that sphere i counts, so that each is counted once: with the
 * offset o = (dx + 1) + 3 (dy + 1) + 9 (dz + 1) of a cell around i's, the
 * later spheres of its own cell (13) and those of the cells after it in
 * (z, y, x) order (14 to 26). */
static void scan_sphere(contact_sums *p, const contact_scan *cs, size_t i)
{
	const pack_cells *g = &cs->g;
	int c0[3];
	pack_cells_coord(g, cs->a->x + 3 * i, c0);
	for (int o = 13; o < 27; o++) {
		int c[3];
		if (!pack_cells_near(g->dim, c0, o, c))
			continue;
		size_t id = pack_cells_index(g, c);
		for (size_t q = g->start[id]; q < g->start[id + 1]; q++) {
			size_t j = (size_t)g->item[q];
			if (o != 13 || j > i)
				add_pair(p, cs, i, j);
		}
	}
}

/* The sums of spheres [first, end). */
static void scan_block(contact_sums *p, const contact_scan *cs, size_t first, size_t end)
{
	for (size_t i = first; i < end; i++) {
		double ri = cs->a->r[i], si = cs->s[i];
		if (si < ri)
			p->wall_max = fmax(p->wall_max, (ri - si) / ri);
		p->core_spheres += cs->where[i] == 'c';
		p->layer_spheres += cs->where[i] == 'l';
		scan_sphere(p, cs, i);
	}
}

static void add_sums(contact_sums *t, const contact_sums *p)
{
	t->bonds += p->bonds;
	for (int k = 0; k < 6; k++)
		t->fabric[k] += p->fabric[k];
	t->ncore += p->ncore;
	t->ov_sum += p->ov_sum;
	t->ov_n += p->ov_n;
	t->ov_max = fmax(t->ov_max, p->ov_max);
	t->wall_max = fmax(t->wall_max, p->wall_max);
	t->core_spheres += p->core_spheres;
	t->core_ends += p->core_ends;
	t->layer_spheres += p->layer_spheres;
	t->layer_ends += p->layer_ends;
}

/* sqrt(3/2 D:D) of the mean fabric f = F / count, D = F - I/3. */
static double anisotropy(const double fabric[6], double count)
{
	double f[6];
	for (int k = 0; k < 6; k++)
		f[k] = fabric[k] / count;
	double tr = (f[0] + f[1] + f[2]) / 3;
	double dd = (f[0] - tr) * (f[0] - tr) + (f[1] - tr) * (f[1] - tr) +
	            (f[2] - tr) * (f[2] - tr) + 2 * (f[3] * f[3] + f[4] * f[4] + f[5] * f[5]);
	return sqrt(1.5 * dd);
}

/* The report's coordination, overlap and fabric fields from the totals. */
static void store_contacts(dem_report *rep, const contact_sums *t, size_t n, double beta)
{
	rep->beta = beta;
	rep->coordination = n ? 2 * t->bonds / (double)n : 0;
	rep->alpha = rep->coordination > 0 ? 40 * (1 - rep->solid_fraction) / rep->coordination : 0;
	rep->coordination_core = t->core_spheres > 0 ? t->core_ends / t->core_spheres : 0;
	rep->coordination_boundary = t->layer_spheres > 0 ? t->layer_ends / t->layer_spheres : NAN;
	rep->overlap_max = t->ov_max;
	rep->overlap_mean = t->ov_n > 0 ? t->ov_sum / t->ov_n : 0;
	rep->wall_overlap_max = t->wall_max;
	rep->fabric_anisotropy = t->ncore > 0 ? anisotropy(t->fabric, t->ncore) : 0;
}

/* Coordination, fabric and overlaps: every pair once, found through a
 * cell grid, summed by fixed blocks of spheres (contact_sums). */
static void contacts(dem_assembly *a, const double *s, double beta)
{
	dem_report *rep = &a->report;
	size_t n = a->n;
	double rmax = 0, wc = REPORT_CORE_DEPTH * 2 * rep->mean_radius,
	       we = REPORT_LAYER_DEPTH * 2 * rep->mean_radius;
	for (size_t i = 0; i < n; i++)
		rmax = fmax(rmax, a->r[i]);
	char *where = xmalloc(n + 1);
	for (size_t i = 0; i < n; i++)
		where[i] = s[i] >= wc ? 'c' : s[i] < we ? 'l' : 0;
	contact_scan cs = {
	    .a = a, .s = s, .where = where, .beta = beta, .bonded = xcalloc(n + 1, 1)};
	pack_cells_build(&cs.g, a->x, n, 2 * (1 + beta) * rmax, NULL);
	enum { BLOCK = 1024 };
	size_t nblock = (n + BLOCK - 1) / BLOCK;
	contact_sums *part = xcalloc(nblock + 1, sizeof *part);
#pragma omp parallel for schedule(dynamic, 4)
	for (size_t b = 0; b < nblock; b++)
		scan_block(&part[b], &cs, b * BLOCK, (b + 1) * BLOCK < n ? (b + 1) * BLOCK : n);
	contact_sums tot = {0};
	for (size_t b = 0; b < nblock; b++)
		add_sums(&tot, &part[b]);
	store_contacts(rep, &tot, n, beta);
	rep->unbonded = 0;
	for (size_t i = 0; i < n; i++)
		rep->unbonded += !cs.bonded[i];
	pack_cells_free(&cs.g);
	free(part);
	free(cs.bonded);
	free(where);
}

static int cmp_double(const void *x, const void *y)
{
	double a = *(const double *)x, b = *(const double *)y;
	return (a > b) - (a < b);
}

static void size_distribution(dem_assembly *a, const psd *target)
{
	dem_report *rep = &a->report;
	size_t n = a->n, m = REPORT_PSD_POINTS;
	double *r = xmalloc(n * sizeof *r + 1), *cumv = xmalloc((n + 1) * sizeof *cumv);
	if (n)
		memcpy(r, a->r, n * sizeof *r);
	qsort(r, n, sizeof *r, cmp_double);
	cumv[0] = 0;
	for (size_t i = 0; i < n; i++)
		cumv[i + 1] = cumv[i] + r[i] * r[i] * r[i];
	double lo = n ? r[0] : 0, hi = n ? r[n - 1] : 0;
	if (target) {
		lo = fmin(lo, target->rmin);
		hi = fmax(hi, target->rmax);
	}
	rep->npsd = m;
	rep->psd_size = xmalloc(m * sizeof *rep->psd_size);
	rep->psd_number = xmalloc(m * sizeof *rep->psd_number);
	rep->psd_volume = xmalloc(m * sizeof *rep->psd_volume);
	rep->psd_target_number = xmalloc(m * sizeof *rep->psd_target_number);
	rep->psd_target_volume = xmalloc(m * sizeof *rep->psd_target_volume);
	size_t below = 0;
	for (size_t k = 0; k < m; k++) {
		double rk = lo + (hi - lo) * (double)k / (double)(m - 1);
		while (below < n && r[below] <= rk)
			below++;
		rep->psd_size[k] = 2 * rk;
		rep->psd_number[k] = n ? (double)below / (double)n : 0;
		rep->psd_volume[k] = cumv[n] > 0 ? cumv[below] / cumv[n] : 0;
		rep->psd_target_number[k] =
		    target ? psd_cdf_number(target, rk) : rep->psd_number[k];
		rep->psd_target_volume[k] =
		    target ? psd_cdf_volume(target, rk) : rep->psd_volume[k];
	}
	free(r);
	free(cumv);
}

void pack_report_compute(dem_assembly *a, const surface *surf, const zones *z, const psd *target,
                         double beta)
{
	dem_report *rep = &a->report;
	double rsum = 0;
	for (size_t i = 0; i < a->n; i++)
		rsum += a->r[i];
	rep->solid_fraction = sphere_volume(a->r, a->n) / a->geom.volume;
	rep->mean_radius = a->n ? rsum / (double)a->n : 0;
	double dmean = 2 * rep->mean_radius;
	double *s = depths(a, surf, z, fmax(REPORT_PROFILE_DEPTH, REPORT_CORE_DEPTH) * dmean);
	profile(a, s, surf, z);
	contacts(a, s, beta);
	size_distribution(a, target);
	free(s);
}

/* The diameter below which a fraction f of the spheres (by number or
 * volume) lies, interpolated in the reported distribution. */
static double percentile(const dem_report *r, const double *cum, double f)
{
	for (size_t k = 1; k < r->npsd; k++)
		if (cum[k] >= f) {
			double t =
			    cum[k] > cum[k - 1] ? (f - cum[k - 1]) / (cum[k] - cum[k - 1]) : 1;
			return r->psd_size[k - 1] + t * (r->psd_size[k] - r->psd_size[k - 1]);
		}
	return r->npsd ? r->psd_size[r->npsd - 1] : 0;
}

/* d10, d50 and d90 achieved and targeted, by number or by volume. */
static void print_diameters(FILE *out, const char *head, const dem_report *r, const double *cum,
                            const double *target, const char *by)
{
	fprintf(out, "%sd10 %.3f  d50 %.3f  d90 %.3f by %s (target %.3f %.3f %.3f)\n", head,
	        1e3 * percentile(r, cum, 0.1), 1e3 * percentile(r, cum, 0.5),
	        1e3 * percentile(r, cum, 0.9), by, 1e3 * percentile(r, target, 0.1),
	        1e3 * percentile(r, target, 0.5), 1e3 * percentile(r, target, 0.9));
}

void pack_report_print(const dem_assembly *a, FILE *out)
{
	const dem_report *r = &a->report;
	const dem_geometry *g = &a->geom;
	fprintf(out, "pack: %zu spheres in ", a->n);
	if (strcmp(g->shape, "box") == 0)
		fprintf(out, "box %g x %g x %g mm", 1e3 * g->size[0], 1e3 * g->size[1],
		        1e3 * g->size[2]);
	else if (strcmp(g->shape, "file") == 0)
		fprintf(out, "%s", g->source);
	else
		fprintf(out, "%s %g x %g mm", g->shape, 1e3 * g->diameter, 1e3 * g->height);
	fprintf(out, " (volume %.4g m^3)\n", g->volume);
	fprintf(out, "  solid fraction   %.4f total, %.4f core (deeper than %g mean diameters)\n",
	        r->solid_fraction, r->solid_fraction_core, REPORT_CORE_DEPTH);
	fprintf(out, "  wall deficit     delta* = %.3f mean diameters\n", r->wall_deficit);
	fprintf(out, "  profile phi(w)  ");
	for (size_t k = 1; k < r->nprofile; k += r->nprofile / 6)
		fprintf(out, " %.2fd:%.3f", r->profile_w[k] / (2 * r->mean_radius),
		        r->profile_phi[k]);
	fprintf(out, "\n");
	fprintf(out,
	        "  mean radius      %.4f mm over all spheres (those filling the wall band "
	        "are smaller)\n",
	        1e3 * r->mean_radius);
	print_diameters(out, "  diameters (mm)   ", r, r->psd_number, r->psd_target_number,
	                "number");
	print_diameters(out, "                   ", r, r->psd_volume, r->psd_target_volume,
	                "volume");
	fprintf(out,
	        "  coordination     %.2f bonds per sphere at beta = %.2f; alpha = 40 P/N_c = "
	        "%.3f\n",
	        r->coordination, r->beta, r->alpha);
	char layer[64] = "no sphere in the boundary layer";
	if (!isnan(r->coordination_boundary))
		snprintf(layer, sizeof layer, "%.2f in the boundary layer",
		         r->coordination_boundary);
	fprintf(out, "                   %.2f in the core, %s; %.0f spheres without a bond\n",
	        r->coordination_core, layer, r->unbonded);
	fprintf(out, "  fabric           anisotropy %.4f in the core\n", r->fabric_anisotropy);
	fprintf(out,
	        "  overlaps         max %.3f %%, mean %.3f %% of the smaller radius; "
	        "boundary max %.3f %% of the radius\n",
	        100 * r->overlap_max, 100 * r->overlap_mean, 100 * r->wall_overlap_max);
	fprintf(out,
	        "  seed %llu; time %.3f s (geometry %.3f, cell %.3f, fill %.3f, report %.3f)\n",
	        (unsigned long long)a->prov.seed, r->time, r->time_geometry, r->time_cell,
	        r->time_fill, r->time_report);
}
