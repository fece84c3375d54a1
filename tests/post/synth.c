#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/rng.h"
#include "lib/runfile.h"
#include "lib/vec3.h"
#include "tests/post/synth.h"

#define PI 3.14159265358979323846

/* Model constants (SI): micro modulus, Poisson's ratio, strengths. */
static const double E_MICRO = 10e9, NU = 0.25, SIGMA_T = 12e6, TAU = 9e6, MU = 0.5;
static const double BETA = 0.7, RATE = 1.0 /* 1/s */, DT = 1e-8 /* s per step */;

synth_opts synth_defaults(void)
{
	return (synth_opts){.nparticles = 400,
	                    .radius = 0.5e-3,
	                    .diameter = 10e-3,
	                    .height = 20e-3,
	                    .axis = {0, 0, 1},
	                    .center = {0, 0, 10e-3},
	                    .nsnap = 5,
	                    .nrows = 200,
	                    .peak_strain = 3e-3,
	                    .peak_stress = 40e6,
	                    .end_strain = 4.5e-3,
	                    .seed = 1};
}

typedef struct {
	double a[3], e1[3], e2[3], c[3];
} sframe;

static void frame_from(sframe *f, const double axis[3], const synth_opts *o)
{
	v3_scale(f->a, axis, 1 / v3_norm(axis));
	v3_copy(f->c, o->center);
	int least = 0;
	for (int k = 1; k < 3; k++)
		if (fabs(f->a[k]) < fabs(f->a[least]))
			least = k;
	double u[3] = {0, 0, 0};
	u[least] = 1;
	v3_reject(f->e1, u, f->a);
	v3_scale(f->e1, f->e1, 1 / v3_norm(f->e1));
	v3_cross(f->e2, f->a, f->e1);
}

static void to_global(const sframe *f, const double l[3], double x[3])
{
	v3_copy(x, f->c);
	v3_axpy(x, f->e1, l[0]);
	v3_axpy(x, f->e2, l[1]);
	v3_axpy(x, f->a, l[2]);
}

/* eps . d for axial strain e (compression positive). */
static void strain_apply(const sframe *f, double e, const double d[3], double out[3])
{
	double da = v3_dot(d, f->a);
	v3_scale(out, d, NU * e);
	v3_axpy(out, f->a, -(1 + NU) * e * da);
}

/* Random sequential addition on a cell grid (local coordinates). */
static size_t place(const synth_opts *o, rng *g, double *l, double *r)
{
	double rmax = 1.2 * o->radius, h = 2 * rmax, R = 0.5 * o->diameter;
	int nx = (int)ceil(o->diameter / h) + 1, nz = (int)ceil(o->height / h) + 1;
	int *head = malloc((size_t)nx * nx * nz * sizeof *head);
	int *next = malloc((size_t)o->nparticles * sizeof *next);
	for (int k = 0; k < nx * nx * nz; k++)
		head[k] = -1;
	size_t n = 0;
	for (long tries = 0; n < (size_t)o->nparticles && tries < 200L * o->nparticles; tries++) {
		double ri = o->radius * rng_range(g, 0.8, 1.2);
		double p[3] = {rng_range(g, -R + ri, R - ri), rng_range(g, -R + ri, R - ri),
		               rng_range(g, -0.5 * o->height + ri, 0.5 * o->height - ri)};
		if (hypot(p[0], p[1]) > R - ri)
			continue;
		int cx = (int)((p[0] + R) / h), cy = (int)((p[1] + R) / h);
		int cz = (int)((p[2] + 0.5 * o->height) / h), ok = 1;
		for (int dx = -1; dx <= 1 && ok; dx++)
			for (int dy = -1; dy <= 1 && ok; dy++)
				for (int dz = -1; dz <= 1 && ok; dz++) {
					int x = cx + dx, y = cy + dy, z = cz + dz;
					if (x < 0 || y < 0 || z < 0 || x >= nx || y >= nx ||
					    z >= nz)
						continue;
					for (int q = head[(z * nx + y) * nx + x]; q >= 0 && ok;
					     q = next[q]) {
						double d[3];
						v3_sub(d, p, l + 3 * q);
						ok = v3_norm(d) >= ri + r[q];
					}
				}
		if (!ok)
			continue;
		v3_copy(l + 3 * n, p);
		r[n] = ri;
		int cell = (cz * nx + cy) * nx + cx;
		next[n] = head[cell];
		head[cell] = (int)n;
		n++;
	}
	free(head);
	free(next);
	return n;
}

static void cylinder_mesh(dem_geometry *gm, const sframe *f, const synth_opts *o)
{
	enum { SEG = 32 };
	gm->nvert = 2 * SEG + 2;
	gm->vert = malloc(3 * gm->nvert * sizeof *gm->vert);
	gm->ntri = 4 * SEG;
	gm->tri = malloc(3 * gm->ntri * sizeof *gm->tri);
	double R = 0.5 * o->diameter, H = o->height;
	for (int s = 0; s < SEG; s++)
		for (int z = 0; z < 2; z++) {
			double l[3] = {R * cos(2 * PI * s / SEG), R * sin(2 * PI * s / SEG),
			               (z - 0.5) * H};
			to_global(f, l, gm->vert + 3 * (2 * s + z));
		}
	for (int z = 0; z < 2; z++) {
		double l[3] = {0, 0, (z - 0.5) * H};
		to_global(f, l, gm->vert + 3 * (2 * SEG + z));
	}
	int32_t *t = gm->tri;
	for (int s = 0; s < SEG; s++) {
		int a0 = 2 * s, a1 = 2 * s + 1, b0 = 2 * ((s + 1) % SEG), b1 = b0 + 1;
		int32_t tris[4][3] = {
		    {a0, b0, b1}, {a0, b1, a1}, {2 * SEG, b0, a0}, {2 * SEG + 1, a1, b1}};
		memcpy(t + 12 * s, tris, sizeof tris);
	}
	gm->volume = PI * R * R * H;
	gm->area = 2 * PI * R * (R + H);
}

static void make_assembly(dem_assembly *a, const synth_opts *o, const sframe *f, rng *g)
{
	memset(a, 0, sizeof *a);
	prov_init(&a->prov, "pack", "{\"synthetic\":true}", o->seed);
	double *l = malloc(3 * (size_t)o->nparticles * sizeof *l);
	a->r = malloc((size_t)o->nparticles * sizeof *a->r);
	a->n = place(o, g, l, a->r);
	a->x = malloc(3 * a->n * sizeof *a->x);
	a->material = calloc(a->n, sizeof *a->material);
	for (size_t k = 0; k < a->n; k++)
		to_global(f, l + 3 * k, a->x + 3 * k);
	free(l);
	dem_geometry *gm = &a->geom;
	strcpy(gm->shape, "cylinder");
	v3_copy(gm->center, o->center);
	v3_copy(gm->axis, f->a);
	gm->diameter = o->diameter;
	gm->height = o->height;
	for (int k = 0; k < 3; k++) {
		double ext = 0.5 * o->height * fabs(f->a[k]) +
		             0.5 * o->diameter * sqrt(fmax(0, 1 - f->a[k] * f->a[k]));
		gm->bbox_min[k] = o->center[k] - ext;
		gm->bbox_max[k] = o->center[k] + ext;
	}
	cylinder_mesh(gm, f, o);
	a->report.mean_radius = o->radius;
	a->report.beta = BETA;
}

/* What the model says of one bond: per unit axial strain, and its fate. */
typedef struct {
	double fn1;     /* N, normal force per unit strain */
	double fs1[3];  /* N, shear force per unit strain */
	double e_fail;  /* strain of failure (INFINITY if none) */
	int mode;       /* CRACK_* at failure */
	double ft, tau; /* N, strengths */
} bond_law;

static void bond_model(const dem_assembly *a, const dem_bonds *b, size_t k, const sframe *f,
                       const synth_opts *o, rng *g, bond_law *m)
{
	const double *xi = a->x + 3 * (size_t)b->i[k], *xj = a->x + 3 * (size_t)b->j[k];
	double d[3], n[3], ed[3], mid[3];
	v3_sub(d, xj, xi);
	v3_scale(n, d, 1 / v3_norm(d));
	strain_apply(f, 1, d, ed);
	double dn = v3_dot(n, ed);
	m->fn1 = b->kn[k] * dn * (1 + rng_range(g, -0.3, 0.3));
	for (int c = 0; c < 3; c++)
		m->fs1[c] = b->ks[k] * (ed[c] - dn * n[c]);
	/* weaker in a band inclined at 60 degrees through the centre */
	double band[3], weak = 1;
	v3_scale(band, f->a, cos(PI / 3));
	v3_axpy(band, f->e1, sin(PI / 3));
	v3_add(mid, xi, xj);
	v3_scale(mid, mid, 0.5);
	v3_sub(mid, mid, f->c);
	if (fabs(v3_dot(mid, band)) < o->diameter / 6)
		weak = 0.6;
	double scale = weak * rng_range(g, 0.6, 1.4);
	m->ft = SIGMA_T * b->area[k] * scale;
	m->tau = TAU * b->area[k] * scale;
	double fs = v3_norm(m->fs1);
	double e_t = m->fn1 > 0 ? m->ft / m->fn1 : INFINITY;
	double shear = fs - (m->fn1 < 0 ? MU * -m->fn1 : 0);
	double e_s = shear > 0 ? m->tau / shear : INFINITY;
	m->e_fail = fmin(e_t, e_s);
	m->mode = e_t <= e_s ? CRACK_TENSION : CRACK_SHEAR;
}

static size_t find_bonds(const dem_assembly *a, dem_bonds *b)
{
	size_t cap = 16 * a->n, n = 0;
	b->i = malloc(cap * sizeof *b->i);
	b->j = malloc(cap * sizeof *b->j);
	for (size_t i = 0; i < a->n; i++)
		for (size_t j = i + 1; j < a->n; j++) {
			double d[3];
			v3_sub(d, a->x + 3 * j, a->x + 3 * i);
			if (v3_norm(d) > (1 + BETA) * (a->r[i] + a->r[j]))
				continue;
			if (n == cap) {
				cap *= 2;
				b->i = realloc(b->i, cap * sizeof *b->i);
				b->j = realloc(b->j, cap * sizeof *b->j);
			}
			b->i[n] = (int32_t)i;
			b->j[n] = (int32_t)j;
			n++;
		}
	b->n = n;
	b->d0 = malloc(n * sizeof *b->d0);
	b->area = malloc(n * sizeof *b->area);
	b->kn = malloc(n * sizeof *b->kn);
	b->ks = malloc(n * sizeof *b->ks);
	for (size_t k = 0; k < n; k++) {
		double d[3], rc = fmin(a->r[b->i[k]], a->r[b->j[k]]);
		v3_sub(d, a->x + 3 * (size_t)b->j[k], a->x + 3 * (size_t)b->i[k]);
		b->d0[k] = v3_norm(d);
		b->area[k] = PI * rc * rc;
		b->kn[k] = E_MICRO * b->area[k] / b->d0[k];
		b->ks[k] = b->kn[k] / 2.5;
	}
	return n;
}

static double stress_at(const synth_opts *o, double e)
{
	return o->peak_stress * (e / o->peak_strain) * exp(1 - e / o->peak_strain);
}

static void positions(const dem_assembly *a, const sframe *f, double e, double *x)
{
	for (size_t k = 0; k < a->n; k++) {
		double d[3], u[3];
		v3_sub(d, a->x + 3 * k, f->c);
		strain_apply(f, e, d, u);
		v3_add(x + 3 * k, a->x + 3 * k, u);
	}
}

static int write_snapshot(run_writer *w, const dem_assembly *a, const dem_bonds *b,
                          const bond_law *m, const sframe *f, const synth_opts *o, double e)
{
	size_t n = a->n, nb = b->n;
	dem_snapshot s = {.step = (int64_t)llround(e / RATE / DT),
	                  .t = e / RATE,
	                  .strain_axial = e,
	                  .stress_axial = stress_at(o, e),
	                  .n = n,
	                  .nbonds = nb};
	s.x = malloc(3 * n * sizeof *s.x);
	s.v = malloc(3 * n * sizeof *s.v);
	s.w = calloc(3 * n, sizeof *s.w);
	positions(a, f, e, s.x);
	for (size_t k = 0; k < n; k++) {
		double d[3];
		v3_sub(d, a->x + 3 * k, f->c);
		strain_apply(f, RATE, d, s.v + 3 * k);
	}
	s.state = malloc(nb);
	s.damage_n = malloc(nb * sizeof *s.damage_n);
	s.damage_s = malloc(nb * sizeof *s.damage_s);
	s.fn = malloc(nb * sizeof *s.fn);
	s.fs = malloc(3 * nb * sizeof *s.fs);
	for (size_t k = 0; k < nb; k++) {
		int broken = m[k].e_fail <= e;
		s.state[k] = broken ? (uint8_t)(m[k].mode == CRACK_TENSION ? BOND_BROKEN_TENSION
		                                                           : BOND_BROKEN_SHEAR)
		                    : BOND_INTACT;
		double fn = broken ? 0 : m[k].fn1 * e, scale = broken ? 0 : e;
		s.fn[k] = fn;
		v3_scale(s.fs + 3 * k, m[k].fs1, scale);
		s.damage_n[k] = broken ? 1 : fmin(1, fmax(0, (fn / m[k].ft - 0.7) / 0.3));
		s.damage_s[k] =
		    broken ? 1 : fmin(1, fmax(0, (v3_norm(s.fs + 3 * k) / m[k].tau - 0.7) / 0.3));
		if (!broken && (s.damage_n[k] > 0 || s.damage_s[k] > 0))
			s.state[k] = BOND_DAMAGED;
	}
	int rc = run_snapshot(w, &s);
	snapshot_free(&s);
	return rc;
}

static const bond_law *sort_ctx;
static int by_failure(const void *pa, const void *pb)
{
	double a = sort_ctx[*(const size_t *)pa].e_fail, b = sort_ctx[*(const size_t *)pb].e_fail;
	return (a > b) - (a < b);
}

static int write_cracks(run_writer *w, const dem_assembly *a, const dem_bonds *b, const bond_law *m,
                        const sframe *f, const synth_opts *o)
{
	size_t *order = malloc((b->n ? b->n : 1) * sizeof *order), nc = 0;
	for (size_t k = 0; k < b->n; k++)
		if (m[k].e_fail <= o->end_strain)
			order[nc++] = k;
	sort_ctx = m;
	qsort(order, nc, sizeof *order, by_failure);
	dem_crack *c = calloc(nc ? nc : 1, sizeof *c);
	for (size_t q = 0; q < nc; q++) {
		size_t k = order[q];
		double e = m[k].e_fail, xi[3], xj[3], d[3], u[3];
		int32_t i = b->i[k], j = b->j[k];
		v3_sub(d, a->x + 3 * (size_t)i, f->c);
		strain_apply(f, e, d, u);
		v3_add(xi, a->x + 3 * (size_t)i, u);
		v3_sub(d, a->x + 3 * (size_t)j, f->c);
		strain_apply(f, e, d, u);
		v3_add(xj, a->x + 3 * (size_t)j, u);
		v3_sub(d, xj, xi);
		double len = v3_norm(d), fi = a->r[i] / (a->r[i] + a->r[j]);
		c[q] = (dem_crack){.t = e / RATE,
		                   .strain_axial = e,
		                   .step = (int64_t)llround(e / RATE / DT),
		                   .i = i,
		                   .j = j,
		                   .mode = m[k].mode,
		                   .radius = fmin(a->r[i], a->r[j]),
		                   .fn = m[k].fn1 * e,
		                   .fs = v3_norm(m[k].fs1) * e};
		v3_copy(c[q].x, xi);
		v3_axpy(c[q].x, d, fi);
		v3_scale(c[q].normal, d, 1 / len);
	}
	int rc = run_cracks(w, c, nc);
	free(c);
	free(order);
	return rc;
}

static int is_bts(const synth_opts *o) { return v3_norm(o->load) > 0; }

static const run_column columns[] = {
    {"t", "s"},
    {"step", ""},
    {"strain_axial", ""},
    {"stress_axial", "Pa"},
    {"strain_radial", ""},
    {"strain_volumetric", ""},
    {"pressure", "Pa"},
    {"energy_elastic", "J"},
    {"energy_kinetic", "J"},
    {"energy_fracture", "J"},
    {"bonds_broken_tension", ""},
    {"bonds_broken_shear", ""},
    {"force_axial", "N"}, /* Brazilian tests only: the last */
};
enum { NCOLS = sizeof columns / sizeof columns[0] };

static int write_history(run_writer *w, const dem_bonds *b, const bond_law *m, const synth_opts *o)
{
	double volume = PI * 0.25 * o->diameter * o->diameter * o->height;
	for (int k = 0; k < o->nrows; k++) {
		double e = o->end_strain * k / (o->nrows - 1), nt = 0, ns = 0;
		for (size_t q = 0; q < b->n; q++)
			if (m[q].e_fail <= e) {
				nt += m[q].mode == CRACK_TENSION;
				ns += m[q].mode == CRACK_SHEAR;
			}
		double s = stress_at(o, e);
		double row[NCOLS] = {e / RATE,
		                     llround(e / RATE / DT),
		                     e,
		                     s,
		                     -NU * e,
		                     (1 - 2 * NU) * e,
		                     0,
		                     0.5 * s * e * volume,
		                     1e-3 * s * e * volume,
		                     2e-4 * (nt + ns),
		                     nt,
		                     ns,
		                     s * PI * 0.25 * o->diameter * o->diameter};
		if (run_history(w, row))
			return -1;
	}
	return 0;
}

int synth_run(const char *path, const synth_opts *o)
{
	rng g;
	rng_seed(&g, o->seed);
	/* f: the loading; shape: the specimen (the same but for a disc). */
	sframe f, shape;
	frame_from(&shape, o->axis, o);
	frame_from(&f, is_bts(o) ? o->load : o->axis, o);
	dem_assembly a;
	make_assembly(&a, o, &shape, &g);
	if (is_bts(o))
		strcpy(a.geom.shape, "disc");
	dem_bonds b;
	find_bonds(&a, &b);
	bond_law *m = malloc((b.n ? b.n : 1) * sizeof *m);
	for (size_t k = 0; k < b.n; k++)
		bond_model(&a, &b, k, &f, o, &g, &m[k]);
	dem_provenance prov;
	char config[400], load[120] = "";
	if (is_bts(o))
		snprintf(load, sizeof load, ",\"axis\":[%.17g,%.17g,%.17g]", f.a[0], f.a[1],
		         f.a[2]);
	snprintf(config, sizeof config,
	         "{\"test\":\"%s\",\"synthetic\":true,\"material\":{\"name\":\"synthetic\","
	         "\"density\":%.17g}%s}",
	         is_bts(o) ? "bts" : "ucs", SYNTH_DENSITY, load);
	prov_init(&prov, "solve", config, o->seed);
	run_writer *w = run_create(path, &prov, &a, columns, NCOLS - !is_bts(o));
	int rc = !w || run_write_bonds(w, &b) || write_history(w, &b, m, o);
	for (int s = 0; !rc && s < o->nsnap; s++)
		rc = write_snapshot(w, &a, &b, m, &f, o,
		                    o->nsnap > 1 ? o->end_strain * s / (o->nsnap - 1)
		                                 : o->end_strain);
	rc = rc || write_cracks(w, &a, &b, m, &f, o);
	if (w && rc)
		run_abort(w);
	else if (w)
		rc = run_finish(w, "complete");
	prov_free(&prov);
	free(m);
	bonds_free(&b);
	assembly_free(&a);
	return rc ? -1 : 0;
}

int synth_tiny(const char *path, int nsnap, const double *snap_t, const double *snap_stress,
               int nrows, const double *row_t, const double *row_stress, int with_stress)
{
	enum { N = 4, NB = 2 };
	double x[3 * N] = {0, 0, 0, 0, 0, 2e-3, 0, 0, 4e-3, 0, 0, 6e-3},
	             r[N] = {1e-3, 1e-3, 1e-3, 1e-3};
	int32_t mat[N] = {0, 0, 0, 0};
	dem_assembly a = {.n = N, .x = x, .r = r, .material = mat};
	prov_init(&a.prov, "pack", "{}", 0);
	strcpy(a.geom.shape, "cylinder");
	a.geom.axis[2] = 1;
	a.geom.diameter = 2e-3;
	a.geom.height = 8e-3;
	dem_provenance prov;
	prov_init(&prov, "solve", "{}", 0);
	const run_column cols[] = {{"t", "s"}, {"strain_axial", ""}, {"stress_axial", "Pa"}};
	run_writer *w = run_create(path, &prov, &a, cols, with_stress ? 3 : 2);
	int32_t bi[NB] = {0, 2}, bj[NB] = {1, 3};
	double d0[NB] = {2e-3, 2e-3}, area[NB] = {1e-6, 2e-6}, k[NB] = {1e6, 1e6};
	dem_bonds b = {.n = NB, .i = bi, .j = bj, .d0 = d0, .area = area, .kn = k, .ks = k};
	int rc = !w || (nsnap + nrows > 0 && run_write_bonds(w, &b));
	for (int q = 0; !rc && q < nrows; q++) {
		double row[3] = {row_t[q], row_t[q] * RATE, row_stress ? row_stress[q] : 0};
		rc = run_history(w, row);
	}
	double v[3 * N] = {0}, dmg[NB] = {0}, fn[NB] = {-10, -30}, fs[3 * NB] = {0};
	uint8_t state[NB] = {BOND_INTACT, BOND_DAMAGED};
	for (int q = 0; !rc && q < nsnap; q++) {
		dem_snapshot s = {.step = (int64_t)llround(snap_t[q] / DT),
		                  .t = snap_t[q],
		                  .strain_axial = snap_t[q] * RATE,
		                  .stress_axial = snap_stress[q],
		                  .n = N,
		                  .x = x,
		                  .v = v,
		                  .w = v,
		                  .nbonds = NB,
		                  .state = state,
		                  .damage_n = dmg,
		                  .damage_s = dmg,
		                  .fn = fn,
		                  .fs = fs};
		rc = run_snapshot(w, &s);
	}
	if (w && rc)
		run_abort(w);
	else if (w)
		rc = run_finish(w, "complete");
	prov_free(&prov);
	prov_free(&a.prov);
	return rc ? -1 : 0;
}
