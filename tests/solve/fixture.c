#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/rng.h"
#include "lib/vec3.h"
#include "tests/solve/fixture.h"

void fixture_cylinder(dem_assembly *a, uint64_t seed)
{
	lattice l = {.kind = LATTICE_FCC,
	             .nx = 9,
	             .ny = 9,
	             .nz = 14,
	             .r = 1e-3,
	             .jitter = 0.02,
	             .polydisp = 0.02,
	             .diameter = 0.0235,
	             .seed = seed};
	fixture_lattice(a, &l);
}

void fixture_spheres(dem_assembly *a, size_t n)
{
	memset(a, 0, sizeof *a);
	prov_init(&a->prov, "test", "{}", 0);
	a->n = n;
	a->x = xcalloc(3 * n, sizeof *a->x);
	a->r = xcalloc(n, sizeof *a->r);
	a->material = xcalloc(n, sizeof *a->material);
}

void fixture_lattice(dem_assembly *a, const lattice *l)
{
	memset(a, 0, sizeof *a);
	prov_init(&a->prov, "test", "{\"fixture\":\"lattice\"}", l->seed);
	/* Cell edge: SC spacing 2r; FCC cube edge 2 sqrt(2) r (neighbours at 2r). */
	double edge = l->kind == LATTICE_SC ? 2 * l->r : 2 * sqrt(2) * l->r;
	static const double fcc[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
	int per = l->kind == LATTICE_SC ? 1 : 4;
	size_t cap = (size_t)l->nx * l->ny * l->nz * per;
	a->x = xmalloc(3 * cap * sizeof *a->x);
	a->r = xmalloc(cap * sizeof *a->r);
	a->material = xcalloc(cap, sizeof *a->material);
	double half[3] = {0.5 * (l->nx - 1) * edge, 0.5 * (l->ny - 1) * edge,
	                  0.5 * (l->nz - 1) * edge};
	if (l->kind == LATTICE_FCC)
		for (int k = 0; k < 3; k++)
			half[k] += 0.25 * edge;
	rng g;
	rng_seed(&g, l->seed);
	size_t n = 0;
	for (int z = 0; z < l->nz; z++)
		for (int y = 0; y < l->ny; y++)
			for (int x = 0; x < l->nx; x++)
				for (int b = 0; b < per; b++) {
					double p[3] = {(x + fcc[b][0]) * edge - half[0],
					               (y + fcc[b][1]) * edge - half[1],
					               (z + fcc[b][2]) * edge - half[2]};
					double j[3], dr;
					for (int k = 0; k < 3; k++)
						j[k] = rng_range(&g, -1, 1) * l->jitter * l->r;
					dr = rng_range(&g, -1, 1) * l->polydisp * l->r;
					if (l->diameter > 0 &&
					    sqrt(p[0] * p[0] + p[1] * p[1]) + l->r >
					        0.5 * l->diameter)
						continue;
					for (int k = 0; k < 3; k++)
						a->x[3 * n + k] = p[k] + j[k];
					a->r[n++] = l->r + dr;
				}
	a->n = n;
	double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	for (size_t i = 0; i < n; i++)
		for (int k = 0; k < 3; k++) {
			lo[k] = fmin(lo[k], a->x[3 * i + k] - a->r[i]);
			hi[k] = fmax(hi[k], a->x[3 * i + k] + a->r[i]);
		}
	dem_geometry *gm = &a->geom;
	gm->axis[2] = 1;
	for (int k = 0; k < 3; k++) {
		gm->center[k] = 0.5 * (lo[k] + hi[k]);
		gm->bbox_min[k] = lo[k];
		gm->bbox_max[k] = hi[k];
	}
	gm->height = hi[2] - lo[2];
	if (l->diameter > 0) {
		strcpy(gm->shape, "cylinder");
		gm->diameter = l->diameter;
		gm->volume = DEM_PI / 4 * l->diameter * l->diameter * gm->height;
	} else {
		strcpy(gm->shape, "box");
		for (int k = 0; k < 3; k++)
			gm->size[k] = hi[k] - lo[k];
		gm->volume = gm->size[0] * gm->size[1] * gm->size[2];
	}
	double vs = 0;
	for (size_t i = 0; i < n; i++)
		vs += 4.0 / 3.0 * DEM_PI * a->r[i] * a->r[i] * a->r[i];
	a->report.solid_fraction = vs / gm->volume;
	a->report.mean_radius = l->r;
}

void fixture_rotation(const double axis[3], double angle, double R[9])
{
	double u[3];
	v3_scale(u, axis, 1 / v3_norm(axis));
	double c = cos(angle), s = sin(angle), t = 1 - c;
	double m[9] = {
	    t * u[0] * u[0] + c,        t * u[0] * u[1] - s * u[2], t * u[0] * u[2] + s * u[1],
	    t * u[0] * u[1] + s * u[2], t * u[1] * u[1] + c,        t * u[1] * u[2] - s * u[0],
	    t * u[0] * u[2] - s * u[1], t * u[1] * u[2] + s * u[0], t * u[2] * u[2] + c};
	memcpy(R, m, sizeof m);
}

static void rotate(const double R[9], double v[3])
{
	double o[3];
	for (int k = 0; k < 3; k++)
		o[k] = R[3 * k] * v[0] + R[3 * k + 1] * v[1] + R[3 * k + 2] * v[2];
	v3_copy(v, o);
}

void fixture_rotate(dem_assembly *a, const double R[9])
{
	for (size_t i = 0; i < a->n; i++)
		rotate(R, a->x + 3 * i);
	rotate(R, a->geom.center);
	rotate(R, a->geom.axis);
	/* The box around the turned box's corners. */
	dem_geometry *g = &a->geom;
	double lo[3], hi[3];
	for (int k = 0; k < 3; k++)
		lo[k] = INFINITY, hi[k] = -INFINITY;
	for (int c = 0; c < 8; c++) {
		double x[3];
		for (int k = 0; k < 3; k++)
			x[k] = c >> k & 1 ? g->bbox_max[k] : g->bbox_min[k];
		rotate(R, x);
		for (int k = 0; k < 3; k++)
			lo[k] = fmin(lo[k], x[k]), hi[k] = fmax(hi[k], x[k]);
	}
	memcpy(g->bbox_min, lo, sizeof lo);
	memcpy(g->bbox_max, hi, sizeof hi);
}

void fixture_write(const dem_assembly *a, const char *path)
{
	if (assembly_write(path, a)) {
		fprintf(stderr, "fixture: %s\n", err_msg());
		exit(1);
	}
}
