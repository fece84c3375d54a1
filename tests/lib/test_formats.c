/* assembly.h5 and run.h5: every field survives a write/read round trip, and
 * a truncated, foreign or mismatched file gives a clear error, not a crash. */
#include <math.h>
#include <stdint.h>
#include <sys/stat.h>
#include <unistd.h>

#include <hdf5_hl.h>

#include "lib/assembly.h"
#include "lib/err.h"
#include "lib/h5.h"
#include "lib/runfile.h"
#include "tests/check.h"

static double *seq(size_t n, double start)
{
	double *v = malloc(n * sizeof *v);
	for (size_t k = 0; k < n; k++)
		v[k] = start + 0.5 * (double)k;
	return v;
}

static void make_assembly(dem_assembly *a, size_t n)
{
	memset(a, 0, sizeof *a);
	prov_init(&a->prov, "pack", "{\"shape\":\"cylinder\"}", 1234);
	a->n = n;
	a->x = seq(3 * n, 0.001);
	a->r = seq(n, 0.0005);
	a->material = malloc(n * sizeof *a->material);
	for (size_t i = 0; i < n; i++)
		a->material[i] = (int32_t)(i % 3);
	dem_geometry *g = &a->geom;
	strcpy(g->shape, "cylinder");
	strcpy(g->source, "share/geometry/x.geo");
	for (int k = 0; k < 3; k++) {
		g->center[k] = 0.1 * k;
		g->axis[k] = k == 2;
		g->size[k] = 0.01 * k;
		g->bbox_min[k] = -0.025 - k;
		g->bbox_max[k] = 1e4 + k; /* around every sphere of seq() */
	}
	g->diameter = 0.05;
	g->height = 0.1;
	g->volume = 1.9635e-4;
	g->area = 0.0196;
	g->nvert = 5;
	g->vert = seq(15, -1);
	g->ntri = 2;
	g->tri = malloc(6 * sizeof *g->tri);
	for (int k = 0; k < 6; k++)
		g->tri[k] = k % 5;
	dem_report *r = &a->report;
	r->solid_fraction = 0.63;
	r->solid_fraction_core = 0.645;
	r->wall_deficit = 0.12;
	r->mean_radius = 0.001;
	r->beta = 0.1;
	r->coordination = 11.5;
	r->alpha = 40 * 0.37 / 11.5;
	r->coordination_core = 12.25;
	r->coordination_boundary = 5.5;
	r->unbonded = 3;
	r->fabric_anisotropy = 0.01;
	r->overlap_max = 0.008;
	r->overlap_mean = 0.001;
	r->wall_overlap_max = 0.002;
	r->time = 2.5;
	r->time_geometry = 0.1;
	r->time_cell = 0.7;
	r->time_fill = 1.2;
	r->time_report = 0.3;
	r->nprofile = 4;
	r->profile_w = seq(4, 0);
	r->profile_phi = seq(4, 0.3);
	r->npsd = 3;
	r->psd_size = seq(3, 0.001);
	r->psd_target_number = seq(3, 0.1);
	r->psd_target_volume = seq(3, 0.2);
	r->psd_number = seq(3, 0.3);
	r->psd_volume = seq(3, 0.4);
}

#define SAME_ARRAY(a, b, n) CHECK(memcmp((a), (b), (n) * sizeof *(a)) == 0)

static void compare_assembly(const dem_assembly *a, const dem_assembly *b)
{
	CHECK_STR(a->prov.program, b->prov.program);
	CHECK_STR(a->prov.version, b->prov.version);
	CHECK_STR(a->prov.created, b->prov.created);
	CHECK_STR(a->prov.config, b->prov.config);
	CHECK(a->prov.seed == b->prov.seed);
	CHECK(a->n == b->n);
	SAME_ARRAY(a->x, b->x, 3 * a->n);
	SAME_ARRAY(a->r, b->r, a->n);
	SAME_ARRAY(a->material, b->material, a->n);
	const dem_geometry *g = &a->geom, *h = &b->geom;
	CHECK_STR(g->shape, h->shape);
	CHECK_STR(g->source, h->source);
	SAME_ARRAY(g->center, h->center, 3);
	SAME_ARRAY(g->axis, h->axis, 3);
	SAME_ARRAY(g->size, h->size, 3);
	SAME_ARRAY(g->bbox_min, h->bbox_min, 3);
	SAME_ARRAY(g->bbox_max, h->bbox_max, 3);
	CHECK(g->diameter == h->diameter && g->height == h->height);
	CHECK(g->volume == h->volume && g->area == h->area);
	CHECK(g->nvert == h->nvert && g->ntri == h->ntri);
	SAME_ARRAY(g->vert, h->vert, 3 * g->nvert);
	SAME_ARRAY(g->tri, h->tri, 3 * g->ntri);
	const dem_report *r = &a->report, *s = &b->report;
	CHECK(r->solid_fraction == s->solid_fraction);
	CHECK(r->solid_fraction_core == s->solid_fraction_core);
	CHECK(r->wall_deficit == s->wall_deficit);
	CHECK(r->mean_radius == s->mean_radius);
	CHECK(r->beta == s->beta && r->coordination == s->coordination && r->alpha == s->alpha);
	CHECK(r->coordination_core == s->coordination_core);
	CHECK(r->coordination_boundary == s->coordination_boundary);
	CHECK(r->unbonded == s->unbonded);
	CHECK(r->fabric_anisotropy == s->fabric_anisotropy);
	CHECK(r->overlap_max == s->overlap_max && r->overlap_mean == s->overlap_mean);
	CHECK(r->wall_overlap_max == s->wall_overlap_max);
	CHECK(r->time == s->time);
	CHECK(r->time_geometry == s->time_geometry && r->time_cell == s->time_cell);
	CHECK(r->time_fill == s->time_fill && r->time_report == s->time_report);
	CHECK(r->nprofile == s->nprofile && r->npsd == s->npsd);
	SAME_ARRAY(r->profile_w, s->profile_w, r->nprofile);
	SAME_ARRAY(r->profile_phi, s->profile_phi, r->nprofile);
	SAME_ARRAY(r->psd_size, s->psd_size, r->npsd);
	SAME_ARRAY(r->psd_target_number, s->psd_target_number, r->npsd);
	SAME_ARRAY(r->psd_target_volume, s->psd_target_volume, r->npsd);
	SAME_ARRAY(r->psd_number, s->psd_number, r->npsd);
	SAME_ARRAY(r->psd_volume, s->psd_volume, r->npsd);
}

static void test_assembly_roundtrip(const char *path)
{
	dem_assembly a, b;
	make_assembly(&a, 5000); /* large enough to be chunked and compressed */
	CHECK(assembly_write(path, &a) == 0);
	CHECK(assembly_read(path, &b) == 0);
	compare_assembly(&a, &b);
	assembly_free(&b);

	/* A sphere that does not fit the geometry's box (a damaged file). */
	const char *far = check_tmp("far_assembly.h5");
	a.x[3 * 7] = 3e4;
	CHECK(assembly_write(far, &a) == 0);
	CHECK(assembly_read(far, &b) == -1);
	CHECK_CONTAINS(err_msg(), "far_assembly.h5: particle 7 (radius 3.5005 m at (30000, ");
	CHECK_CONTAINS(err_msg(),
	               ") m) does not fit the geometry's bounding box [-0.025, 10000] x ");
	a.x[3 * 7] = 0.001 + 0.5 * 21;

	/* A file from before the report had its coordination by layer reads,
	 * with those figures unknown (NaN) and the rest as written. */
	const char *old = check_tmp("old_assembly.h5");
	CHECK(assembly_write(old, &a) == 0);
	hid_t f = H5Fopen(old, H5F_ACC_RDWR, H5P_DEFAULT);
	static const char *later[] = {"coordination_core", "coordination_boundary", "unbonded"};
	for (size_t k = 0; k < sizeof later / sizeof *later; k++)
		CHECK(H5Adelete_by_name(f, "report", later[k], H5P_DEFAULT) >= 0);
	H5Fclose(f);
	CHECK(assembly_read(old, &b) == 0);
	CHECK(isnan(b.report.coordination_core) && isnan(b.report.coordination_boundary));
	CHECK(isnan(b.report.unbonded));
	CHECK(a.report.coordination == b.report.coordination && a.n == b.n);
	unlink(old);
	assembly_free(&a);
	assembly_free(&b);
}

static const run_column columns[] = {{"t", "s"}, {"strain_axial", ""}, {"stress_axial", "Pa"}};

static void make_snapshot(dem_snapshot *s, size_t n, size_t nb, int64_t step)
{
	s->step = step;
	s->t = 1e-6 * (double)step;
	s->strain_axial = 1e-5 * (double)step;
	s->stress_axial = 1e3 * (double)step;
	s->n = n;
	s->x = seq(3 * n, (double)step);
	s->v = seq(3 * n, 2);
	s->w = seq(3 * n, 3);
	s->nbonds = nb;
	s->state = malloc(nb);
	for (size_t k = 0; k < nb; k++)
		s->state[k] = (uint8_t)(k % 4);
	s->damage_n = seq(nb, 0);
	s->damage_s = seq(nb, 0.1);
	s->fn = seq(nb, -5);
	s->fs = seq(3 * nb, 7);
}

static void test_run_roundtrip(const char *path)
{
	dem_assembly a;
	make_assembly(&a, 40);
	dem_provenance prov;
	prov_init(&prov, "solve", "{\"test\":\"ucs\"}", 99);
	run_writer *w = run_create(path, &prov, &a, columns, 3);
	CHECK(w != NULL);
	if (!w)
		return;
	size_t nb = 25;
	dem_bonds b = {.n = nb};
	b.i = malloc(nb * sizeof *b.i);
	b.j = malloc(nb * sizeof *b.j);
	for (size_t k = 0; k < nb; k++)
		b.i[k] = (int32_t)k, b.j[k] = (int32_t)(k + 1);
	b.d0 = seq(nb, 0.002);
	b.area = seq(nb, 1e-6);
	b.kn = seq(nb, 1e6);
	b.ks = seq(nb, 4e5);
	CHECK(run_write_bonds(w, &b) == 0);
	const size_t nrows = 700; /* several history buffer flushes */
	for (size_t k = 0; k < nrows; k++) {
		double row[3] = {1e-6 * (double)k, 1e-5 * (double)k, 2e4 * (double)k};
		CHECK(run_history(w, row) == 0);
	}
	dem_snapshot s1, s2;
	make_snapshot(&s1, a.n, nb, 100);
	make_snapshot(&s2, a.n, nb, 20);
	CHECK(run_snapshot(w, &s1) == 0);
	CHECK(run_snapshot(w, &s2) == 0);
	dem_crack c[3];
	memset(c, 0, sizeof c);
	for (int k = 0; k < 3; k++) {
		c[k] = (dem_crack){.t = k,
		                   .strain_axial = 0.1 * k,
		                   .step = 10 * k,
		                   .i = k,
		                   .j = k + 1,
		                   .mode = k % 2 ? CRACK_SHEAR : CRACK_TENSION,
		                   .x = {k, 1, 2},
		                   .normal = {0, 0, 1},
		                   .radius = 1e-3,
		                   .fn = 5.0 * k,
		                   .fs = 2.0 * k};
	}
	CHECK(run_cracks(w, c, 2) == 0);
	CHECK(run_cracks(w, c + 2, 1) == 0);
	CHECK(run_finish(w, "complete") == 0);

	dem_run r;
	CHECK(run_read(path, &r) == 0);
	CHECK_STR(r.status, "complete");
	CHECK_STR(r.prov.program, "solve");
	CHECK_STR(r.prov.config, "{\"test\":\"ucs\"}");
	CHECK(r.prov.seed == 99);
	compare_assembly(&a, &r.assembly);
	CHECK(r.bonds.n == nb);
	SAME_ARRAY(r.bonds.i, b.i, nb);
	SAME_ARRAY(r.bonds.j, b.j, nb);
	SAME_ARRAY(r.bonds.d0, b.d0, nb);
	SAME_ARRAY(r.bonds.area, b.area, nb);
	SAME_ARRAY(r.bonds.kn, b.kn, nb);
	SAME_ARRAY(r.bonds.ks, b.ks, nb);
	CHECK(r.ncols == 3 && r.nrows == nrows);
	CHECK_STR(r.col_name[2], "stress_axial");
	CHECK_STR(r.col_unit[2], "Pa");
	CHECK_STR(r.col_unit[1], "");
	const double *stress = run_column_data(&r, "stress_axial");
	CHECK(stress && stress[nrows - 1] == 2e4 * (double)(nrows - 1));
	CHECK(run_column_data(&r, "nope") == NULL);
	CHECK(r.nsnap == 2 && r.snap_step[0] == 20 && r.snap_step[1] == 100);
	CHECK(r.snap_t[1] == s1.t && r.snap_strain[0] == s2.strain_axial);
	CHECK(r.snap_stress[1] == s1.stress_axial && r.snap_stress[0] == s2.stress_axial);
	dem_snapshot t;
	CHECK(run_read_snapshot(path, &r, 1, &t) == 0);
	CHECK(t.step == 100 && t.t == s1.t && t.strain_axial == s1.strain_axial);
	CHECK(t.stress_axial == s1.stress_axial);
	CHECK(t.n == a.n && t.nbonds == nb);
	SAME_ARRAY(t.x, s1.x, 3 * a.n);
	SAME_ARRAY(t.v, s1.v, 3 * a.n);
	SAME_ARRAY(t.w, s1.w, 3 * a.n);
	SAME_ARRAY(t.state, s1.state, nb);
	SAME_ARRAY(t.damage_n, s1.damage_n, nb);
	SAME_ARRAY(t.damage_s, s1.damage_s, nb);
	SAME_ARRAY(t.fn, s1.fn, nb);
	SAME_ARRAY(t.fs, s1.fs, 3 * nb);
	snapshot_free(&t);
	CHECK(run_read_snapshot(path, &r, 2, &t) == -1);
	CHECK_CONTAINS(err_msg(), "snapshot 2: out of range");
	CHECK(r.ncracks == 3);
	for (size_t k = 0; k < 3 && r.ncracks == 3; k++)
		CHECK(memcmp(&r.cracks[k], &c[k], sizeof c[k]) == 0);
	run_free(&r);

	/* Format 3: CF's `units`, dimension scales, and the snapshots over
	 * time (virtual datasets over each snapshot's), in step order. */
	hid_t f = h5_open(path, RUN_FORMAT, 0);
	CHECK(f >= 0);
	hid_t h = H5Dopen2(f, "history/stress_axial", H5P_DEFAULT);
	CHECK(H5Aexists(h, "units") > 0 && H5Aexists(h, "unit") == 0);
	hid_t ht = H5Dopen2(f, "history/t", H5P_DEFAULT);
	CHECK(H5DSis_attached(h, ht, 0) > 0);
	H5Dclose(ht);
	H5Dclose(h);
	CHECK(h5_rows_of(f, "cracks/crack") == 3 && h5_rows_of(f, "snapshots/t") == 2);
	hid_t d = H5Dopen2(f, "snapshots/x", H5P_DEFAULT);
	hid_t sp = H5Dget_space(d);
	hsize_t dims[3] = {0, 0, 0};
	CHECK(H5Sget_simple_extent_ndims(sp) == 3);
	H5Sget_simple_extent_dims(sp, dims, NULL);
	CHECK(dims[0] == 2 && dims[1] == a.n && dims[2] == 3);
	double *series = malloc(2 * 3 * a.n * sizeof *series);
	CHECK(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, series) >= 0);
	SAME_ARRAY(series, s2.x, 3 * a.n);
	SAME_ARRAY(series + 3 * a.n, s1.x, 3 * a.n);
	free(series);
	H5Sclose(sp);
	H5Dclose(d);
	int64_t *steps = NULL;
	size_t ns = 0;
	CHECK(h5_read(f, "snapshots/step", H5T_NATIVE_INT64, (void **)&steps, &ns, 0) == 0);
	CHECK(ns == 2 && steps[0] == 20 && steps[1] == 100);
	free(steps);
	H5Fclose(f);
	snapshot_free(&s1);
	snapshot_free(&s2);
	bonds_free(&b);
	prov_free(&prov);
	assembly_free(&a);
}

/* The history's integer columns are stored as integers (format 3) and read
 * back as numbers like the others. */
static void test_integer_columns(const char *path)
{
	static const run_column cols[] = {
	    {"t", "s"}, {"step", ""}, {"stage", ""}, {"bonds_intact", ""}, {"force_axial", "N"}};
	dem_assembly a;
	make_assembly(&a, 10);
	dem_provenance prov;
	prov_init(&prov, "solve", "{}", 1);
	run_writer *w = run_create(path, &prov, &a, cols, 5);
	CHECK(w != NULL);
	for (int k = 0; w && k < 300; k++) {
		double row[5] = {1e-6 * k, 100.0 * k, 1 + k / 200, 5000 - k, 0.5 * k};
		CHECK(run_history(w, row) == 0);
	}
	CHECK(w && run_finish(w, "complete") == 0);
	hid_t f = h5_open(path, RUN_FORMAT, 0);
	hid_t d = H5Dopen2(f, "history/step", H5P_DEFAULT), t = H5Dget_type(d);
	CHECK(H5Tget_class(t) == H5T_INTEGER && H5Tget_size(t) == 8);
	H5Tclose(t), H5Dclose(d);
	d = H5Dopen2(f, "history/stage", H5P_DEFAULT), t = H5Dget_type(d);
	CHECK(H5Tget_class(t) == H5T_INTEGER && H5Tget_size(t) == 4);
	H5Tclose(t), H5Dclose(d);
	d = H5Dopen2(f, "history/bonds_intact", H5P_DEFAULT), t = H5Dget_type(d);
	CHECK(H5Tget_class(t) == H5T_INTEGER && H5Tget_size(t) == 8);
	H5Tclose(t), H5Dclose(d);
	d = H5Dopen2(f, "history/force_axial", H5P_DEFAULT), t = H5Dget_type(d);
	CHECK(H5Tget_class(t) == H5T_FLOAT);
	H5Tclose(t), H5Dclose(d);
	H5Fclose(f);
	dem_run r;
	CHECK(run_read(path, &r) == 0);
	const double *step = run_column_data(&r, "step"), *stage = run_column_data(&r, "stage");
	CHECK(r.nrows == 300 && step && stage);
	CHECK(step && step[299] == 29900 && stage && stage[199] == 1 && stage[200] == 2);
	const double *intact = run_column_data(&r, "bonds_intact");
	const double *force = run_column_data(&r, "force_axial");
	CHECK(intact && intact[299] == 4701 && force && force[299] == 149.5);
	run_free(&r);
	prov_free(&prov);
	assembly_free(&a);
	unlink(path);
}

/* Files of format 2 (units named `unit`, float64 history, no dimension
 * scales nor series) still read, as written. */
static void test_format_2(void)
{
	const char *path = "tests/fuzz/corpus/run/ucs-complete.h5";
	hid_t f = h5_open(path, RUN_FORMAT, 0);
	int64_t version = 0;
	CHECK(f >= 0 && h5_read_attr_i64(f, "format_version", &version) == 0 && version == 2);
	if (f >= 0)
		H5Fclose(f);
	dem_run r;
	CHECK(run_read(path, &r) == 0);
	int pa = 0;
	for (int c = 0; c < r.ncols; c++)
		if (strcmp(r.col_name[c], "stress_axial") == 0)
			pa = strcmp(r.col_unit[c], "Pa") == 0;
	CHECK(pa);
	const double *step = run_column_data(&r, "step");
	CHECK(step && r.nrows > 1 && step[0] == 0 && step[r.nrows - 1] > 0);
	CHECK(r.nsnap >= 1);
	dem_snapshot s;
	CHECK(r.nsnap >= 1 && run_read_snapshot(path, &r, r.nsnap - 1, &s) == 0);
	CHECK(s.n == r.assembly.n && s.nbonds == r.bonds.n);
	snapshot_free(&s);
	run_free(&r);
	dem_assembly a;
	CHECK(assembly_read("tests/fuzz/corpus/assembly/lattice-12.h5", &a) == 0);
	CHECK(a.n == 12);
	assembly_free(&a);
}

/* The whole file at path (caller frees); *n gets its size. */
static void *slurp(const char *path, size_t *n)
{
	FILE *in = fopen(path, "rb");
	fseek(in, 0, SEEK_END);
	*n = (size_t)ftell(in);
	fseek(in, 0, SEEK_SET);
	void *buf = malloc(*n);
	CHECK(fread(buf, 1, *n, in) == *n);
	fclose(in);
	return buf;
}

/* The same files read from memory (h5_open_image, what the fuzz targets
 * do) read the same, and an image of another format or of garbage is
 * refused with a message. */
static void test_images(const char *apath, const char *rpath)
{
	size_t n;
	void *img = slurp(apath, &n);
	dem_assembly a, b;
	CHECK(assembly_read(apath, &a) == 0);
	hid_t f = h5_open_image(img, n, ASSEMBLY_FORMAT);
	CHECK(f >= 0 && assembly_read_file(f, &b) == 0);
	if (f >= 0) {
		compare_assembly(&a, &b);
		assembly_free(&b);
		H5Fclose(f);
	}
	CHECK(h5_open_image(img, n, RUN_FORMAT) < 0);
	CHECK_CONTAINS(err_msg(), "(file image): attribute 'format': value \"dem-assembly\"");
	CHECK(h5_open_image(img, n / 3, ASSEMBLY_FORMAT) < 0);
	CHECK(h5_open_image("not hdf5", 8, ASSEMBLY_FORMAT) < 0);
	CHECK_CONTAINS(err_msg(), "(file image): not a readable HDF5 file image");
	free(img);
	assembly_free(&a);

	img = slurp(rpath, &n);
	dem_run r, q;
	CHECK(run_read(rpath, &r) == 0);
	f = h5_open_image(img, n, RUN_FORMAT);
	CHECK(f >= 0 && run_read_file(f, &q) == 0);
	if (f >= 0) {
		CHECK(q.nrows == r.nrows && q.nsnap == r.nsnap && q.ncracks == r.ncracks);
		compare_assembly(&r.assembly, &q.assembly);
		dem_snapshot s, t;
		CHECK(run_read_snapshot(rpath, &r, 1, &s) == 0);
		CHECK(run_read_snapshot_file(f, &q, 1, &t) == 0);
		CHECK(s.step == t.step && s.n == t.n && s.nbonds == t.nbonds);
		SAME_ARRAY(s.x, t.x, 3 * s.n);
		SAME_ARRAY(s.fs, t.fs, 3 * s.nbonds);
		snapshot_free(&s);
		snapshot_free(&t);
		run_free(&q);
		H5Fclose(f);
	}
	run_free(&r);
	free(img);
}

static void copy_truncated(const char *from, const char *to, double fraction)
{
	FILE *in = fopen(from, "rb"), *out = fopen(to, "wb");
	fseek(in, 0, SEEK_END);
	long size = ftell(in), keep = (long)(fraction * (double)size);
	fseek(in, 0, SEEK_SET);
	char buf[4096];
	while (keep > 0) {
		size_t got = fread(buf, 1, keep < 4096 ? (size_t)keep : 4096, in);
		if (!got)
			break;
		fwrite(buf, 1, got, out);
		keep -= (long)got;
	}
	fclose(in);
	fclose(out);
}

static void test_bad_files(const char *assembly_path, const char *run_path)
{
	dem_assembly a;
	dem_run r;
	const char *bad = check_tmp("bad.h5");
	static const double fractions[] = {0, 0.01, 0.3, 0.6, 0.9, 0.99};
	for (size_t k = 0; k < sizeof fractions / sizeof *fractions; k++) {
		copy_truncated(assembly_path, bad, fractions[k]);
		CHECK(assembly_read(bad, &a) == -1);
		CHECK_CONTAINS(err_msg(), bad);
		copy_truncated(run_path, bad, fractions[k]);
		CHECK(run_read(bad, &r) == -1);
		CHECK_CONTAINS(err_msg(), bad);
	}

	FILE *f = fopen(bad, "w");
	fputs("x y z r\n0 0 0 1\n", f);
	fclose(f);
	CHECK(assembly_read(bad, &a) == -1);
	CHECK_CONTAINS(err_msg(), "not a readable HDF5 file");

	/* A foreign HDF5 file: no format attribute. */
	hid_t h = H5Fcreate(bad, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
	H5Fclose(h);
	CHECK(assembly_read(bad, &a) == -1);
	CHECK_CONTAINS(err_msg(), "attribute 'format': missing: expected \"dem-assembly\"");

	/* The wrong kind of file of ours. */
	CHECK(run_read(assembly_path, &r) == -1);
	CHECK_CONTAINS(err_msg(), "value \"dem-assembly\": expected \"dem-run\"");
	CHECK(assembly_read("/nonexistent/a.h5", &a) == -1);
	CHECK_CONTAINS(err_msg(), "/nonexistent/a.h5: cannot read: No such file or directory");
	unlink(bad);
}

/* A dataset written in pieces (h5_rows) reads back as written, across
 * several pieces; missing or extra rows are errors. */
/* A dataset whose dataspace claims more rows than its storage and the file
 * hold (a damaged header) is refused before anything is allocated: reading
 * it used to end the program out of memory. */
static void test_claimed_rows(const char *path)
{
	char tmp[4096];
	hid_t f = h5_create(path, tmp, sizeof tmp);
	CHECK(f >= 0);
	if (f < 0)
		return;
	hsize_t dims[1] = {(hsize_t)1 << 40}, chunk[1] = {1024};
	hid_t space = H5Screate_simple(1, dims, NULL);
	hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
	H5Pset_chunk(dcpl, 1, chunk);
	hid_t d = H5Dcreate2(f, "huge", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
	CHECK(d >= 0);
	H5Dclose(d);
	H5Pclose(dcpl);
	H5Sclose(space);
	double one = 1;
	CHECK(h5_write(f, "one", H5T_NATIVE_DOUBLE, &one, 1, 0, NULL) == 0);
	void *data = NULL;
	size_t rows = 0;
	CHECK(h5_read(f, "huge", H5T_NATIVE_DOUBLE, &data, &rows, 0) == -1 && !data);
	CHECK_CONTAINS(err_msg(), "dataset 'huge': 1099511627776 rows, more than the file holds");
	CHECK(h5_read(f, "one", H5T_NATIVE_DOUBLE, &data, &rows, 0) == 0 && rows == 1);
	free(data);
	h5_discard(f, tmp);
}

static void test_rows(const char *path)
{
	char tmp[4096];
	hid_t f = h5_create(path, tmp, sizeof tmp);
	CHECK(f >= 0);
	if (f < 0)
		return;
	size_t cols[2] = {0, 3}, rows[2] = {150000, 50000};
	const char *names[2] = {"flat", "xyz"};
	for (int k = 0; k < 2; k++) {
		size_t width = cols[k] ? cols[k] : 1, pieces = 0;
		double *buf = malloc(H5_PIECE_ELEMENTS * sizeof *buf);
		h5_rows r;
		CHECK(h5_rows_open(&r, f, names[k], H5T_NATIVE_DOUBLE, rows[k], cols[k], "m") == 0);
		for (size_t m; (m = h5_rows_piece(&r)) > 0; pieces++) {
			CHECK(m * width <= H5_PIECE_ELEMENTS);
			for (size_t q = 0; q < m * width; q++)
				buf[q] = 0.25 * (double)(r.at * width + q);
			CHECK(h5_rows_put(&r, buf, m) == 0);
		}
		CHECK(h5_rows_close(&r) == 0);
		CHECK(pieces >= 3);
		free(buf);
		double *back = NULL;
		CHECK(h5_read_n(f, names[k], H5T_NATIVE_DOUBLE, (void **)&back, rows[k], cols[k]) ==
		      0);
		size_t bad = 0;
		for (size_t q = 0; back && q < rows[k] * width; q++)
			bad += back[q] != 0.25 * (double)q;
		CHECK(back && bad == 0);
		free(back);
	}
	double one[4] = {1, 2, 3, 4};
	h5_rows r;
	CHECK(h5_rows_open(&r, f, "short", H5T_NATIVE_DOUBLE, 3, 0, NULL) == 0);
	CHECK(h5_rows_put(&r, one, 2) == 0);
	CHECK(h5_rows_put(&r, one, 2) != 0 && strstr(err_msg(), "more rows"));
	CHECK(h5_rows_close(&r) != 0);
	CHECK(h5_rows_open(&r, f, "missing", H5T_NATIVE_DOUBLE, 3, 0, NULL) == 0);
	CHECK(h5_rows_put(&r, one, 2) == 0);
	CHECK(h5_rows_close(&r) != 0 && strstr(err_msg(), "2 of 3 rows"));
	h5_discard(f, tmp);
}

int main(void)
{
	const char *ap = check_tmp("formats-assembly.h5");
	const char *rp = check_tmp("formats-run.h5");
	test_assembly_roundtrip(ap);
	test_run_roundtrip(rp);
	test_integer_columns(check_tmp("formats-integers.h5"));
	test_format_2();
	test_images(ap, rp);
	test_rows(check_tmp("formats-rows.h5"));
	test_claimed_rows(check_tmp("formats-claimed.h5"));
	test_bad_files(ap, rp);
	return check_done();
}
