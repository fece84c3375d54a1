/* post vtk on a synthetic run (tests/post/synth.h), read back through the
 * VTK library: every particle, bond, crack disc and platen is compared
 * with the run file as lib/runfile.h reads it, and the files must be
 * binary, compressed XML indexed by .pvd series, the same files whatever
 * the threads that write the frames; a series written over another
 * replaces it as a whole. Also the packing of an assembly file. */
#include <math.h>
#include <sys/stat.h>

#include "lib/runfile.h"
#include "lib/vec3.h"
#include "tests/check.h"
#include "tests/post/harness.h"
#include "tests/post/synth.h"
#include "tests/post/vtkread.h"

static char dir[1024], vdir[1100];

static vtkr *open_file(const char *name)
{
	char path[1300];
	snprintf(path, sizeof path, "%s/%s", vdir, name);
	vtkr *r = vtkr_open(path);
	CHECK(r != NULL);
	return r;
}

static int count_str(const char *text, const char *sub)
{
	int n = 0;
	for (const char *p = strstr(text, sub); p; p = strstr(p + 1, sub))
		n++;
	return n;
}

/* The array exists on the right entity with ncomp components, one tuple
 * per point or cell. */
static void check_array(const vtkr *r, char where, const char *name, int ncomp, long n)
{
	long nt = -1;
	int nc = vtkr_array(r, where, name, &nt);
	if (nc != ncomp || nt != n)
		fprintf(stderr, "array %s: %d components, %ld tuples\n", name, nc, nt);
	CHECK(nc == ncomp && nt == n);
}

static void check_particles(const dem_run *run, const dem_snapshot *s)
{
	vtkr *r = open_file("particles_000002.vtu");
	if (!r)
		return;
	long n = (long)run->assembly.n;
	CHECK(vtkr_npoints(r) == n && vtkr_ncells(r) == n);
	CHECK(vtkr_cell_type(r, n / 2) == 1 && vtkr_cell_size(r, n / 2) == 1);
	const char *scalars[] = {"id", "radius", "material", "damage", "broken_bonds"};
	for (int k = 0; k < 5; k++)
		check_array(r, 'p', scalars[k], 1, n);
	const char *vectors[] = {"displacement", "velocity", "angular_velocity"};
	for (int k = 0; k < 3; k++)
		check_array(r, 'p', vectors[k], 3, n);
	/* damage: mean over the particle's bonds of 1 (broken) or max(dn, ds) */
	double *sum = calloc((size_t)n, sizeof *sum);
	int *nb = calloc((size_t)n, sizeof *nb), *broken = calloc((size_t)n, sizeof *broken);
	for (size_t b = 0; b < run->bonds.n; b++) {
		int gone = s->state[b] >= BOND_BROKEN_TENSION;
		double d = gone ? 1 : fmax(s->damage_n[b], s->damage_s[b]);
		int ends[2] = {run->bonds.i[b], run->bonds.j[b]};
		for (int e = 0; e < 2; e++)
			sum[ends[e]] += d, nb[ends[e]]++, broken[ends[e]] += gone;
	}
	int bad = 0, damaged = 0;
	for (long k = 0; k < n; k++) {
		double x[3];
		vtkr_point(r, k, x);
		for (int c = 0; c < 3; c++) {
			bad += x[c] != s->x[3 * k + c];
			bad += vtkr_value(r, 'p', "displacement", k, c) !=
			       s->x[3 * k + c] - run->assembly.x[3 * k + c];
			bad += vtkr_value(r, 'p', "velocity", k, c) != s->v[3 * k + c];
		}
		bad += vtkr_value(r, 'p', "radius", k, 0) != run->assembly.r[k];
		bad += vtkr_value(r, 'p', "id", k, 0) != k;
		double dmg = nb[k] ? sum[k] / nb[k] : 0;
		bad += fabs(vtkr_value(r, 'p', "damage", k, 0) - dmg) > 1e-12;
		bad += vtkr_value(r, 'p', "broken_bonds", k, 0) != broken[k];
		damaged += dmg > 0;
	}
	CHECK(bad == 0);
	CHECK(damaged > 0); /* the test means something */
	free(sum), free(nb), free(broken);

	/* Stress: Σ_p V_p σ_p is the Love–Weber sum Σ_b d n ⊗ f over the bonds
	 * (tension positive: f = fn n + fs on i); the invariants match the
	 * tensor. */
	check_array(r, 'p', "stress", 9, n);
	check_array(r, 'p', "stress_mean", 1, n);
	check_array(r, 'p', "stress_von_mises", 1, n);
	double love[9] = {0}, got[9] = {0}, scale = 0;
	for (size_t b = 0; b < run->bonds.n; b++) {
		double nv[3], f[3];
		v3_sub(nv, s->x + 3 * run->bonds.j[b], s->x + 3 * run->bonds.i[b]);
		for (int c = 0; c < 3; c++)
			f[c] = s->fn[b] * nv[c] / v3_norm(nv) + s->fs[3 * b + c];
		for (int c = 0; c < 9; c++)
			love[c] += nv[c / 3] * f[c % 3];
	}
	bad = 0;
	for (long k = 0; k < n; k++) {
		double rr = run->assembly.r[k],
		       v = 4.0 / 3.0 * 3.14159265358979323846 * rr * rr * rr, t[9];
		for (int c = 0; c < 9; c++) {
			t[c] = vtkr_value(r, 'p', "stress", k, c);
			got[c] += v * t[c];
		}
		double p = (t[0] + t[4] + t[8]) / 3, s2 = 0;
		for (int c = 0; c < 9; c++) {
			double sym = 0.5 * (t[c] + t[3 * (c % 3) + c / 3]) - (c % 4 == 0 ? p : 0);
			s2 += sym * sym;
		}
		bad += fabs(vtkr_value(r, 'p', "stress_mean", k, 0) - p) > 1e-9 * fabs(p) + 1e-6;
		double q = vtkr_value(r, 'p', "stress_von_mises", k, 0);
		bad += fabs(q - sqrt(1.5 * s2)) > 1e-9 * q + 1e-6;
	}
	for (int c = 0; c < 9; c++)
		scale = fmax(scale, fabs(love[c]));
	for (int c = 0; c < 9; c++)
		bad += fabs(got[c] - love[c]) > 1e-9 * scale;
	CHECK(bad == 0 && scale > 0);

	/* The frame's state as field data. */
	long one = 0;
	CHECK(vtkr_array(r, 'f', "time", &one) == 1 && one == 1);
	CHECK(vtkr_value(r, 'f', "time", 0, 0) == run->snap_t[2]);
	CHECK(vtkr_value(r, 'f', "step", 0, 0) == run->snap_step[2]);
	CHECK(vtkr_value(r, 'f', "strain_axial", 0, 0) == run->snap_strain[2]);
	CHECK(vtkr_value(r, 'f', "stress_axial", 0, 0) == run->snap_stress[2]);
	CHECK(vtkr_array(r, 'f', "confining_pressure", &one) == 1);
	vtkr_close(r);
}

static void check_bonds(const dem_run *run, const dem_snapshot *s)
{
	vtkr *r = open_file("bonds_000002.vtp");
	if (!r)
		return;
	long nb = (long)run->bonds.n;
	CHECK(vtkr_ncells(r) == nb && vtkr_npoints(r) == (long)run->assembly.n);
	const char *scalars[] = {"id",       "state",    "fn",     "fs_magnitude",
	                         "damage_n", "damage_s", "damage", "area"};
	for (int k = 0; k < 8; k++)
		check_array(r, 'c', scalars[k], 1, nb);
	check_array(r, 'c', "fs", 3, nb);
	int bad = 0, states[4] = {0, 0, 0, 0};
	for (long b = 0; b < nb; b++) {
		bad += vtkr_cell_type(r, b) != 3 || vtkr_cell_size(r, b) != 2;
		bad += vtkr_cell_point(r, b, 0) != run->bonds.i[b];
		bad += vtkr_cell_point(r, b, 1) != run->bonds.j[b];
		bad += vtkr_value(r, 'c', "state", b, 0) != s->state[b];
		bad += vtkr_value(r, 'c', "fn", b, 0) != s->fn[b];
		bad += vtkr_value(r, 'c', "damage_n", b, 0) != s->damage_n[b];
		bad += vtkr_value(r, 'c', "damage_s", b, 0) != s->damage_s[b];
		for (int c = 0; c < 3; c++)
			bad += vtkr_value(r, 'c', "fs", b, c) != s->fs[3 * b + c];
		states[s->state[b]]++;
	}
	CHECK(bad == 0);
	CHECK(states[BOND_INTACT] > 0 && states[BOND_BROKEN_TENSION] > 0 &&
	      states[BOND_BROKEN_SHEAR] > 0);
	vtkr_close(r);
}

/* Frame k shows the cracks of time <= the snapshot's time, each a disc. */
static void check_cracks(const dem_run *run, const dem_snapshot *last)
{
	CHECK(run->ncracks > 10);
	long broken = 0;
	for (size_t b = 0; b < run->bonds.n; b++)
		broken += last->state[b] >= BOND_BROKEN_TENSION;
	for (size_t k = 0; k < 3; k++) {
		char name[64];
		snprintf(name, sizeof name, "cracks_%06zu.vtp", k);
		vtkr *r = open_file(name);
		if (!r)
			return;
		long expect = 0;
		for (size_t c = 0; c < run->ncracks; c++)
			expect += run->cracks[c].t <= run->snap_t[k];
		CHECK(vtkr_ncells(r) == expect);
		if (k == 2) {
			/* one disc per crack row of run.h5, that is per broken bond */
			CHECK(vtkr_ncells(r) == (long)run->ncracks);
			CHECK(vtkr_ncells(r) == broken);
			int bad = 0;
			for (long c = 0; c < vtkr_ncells(r); c++) {
				long row = (long)vtkr_value(r, 'c', "crack", c, 0);
				const dem_crack *q = &run->cracks[row];
				int m = vtkr_cell_size(r, c);
				double centre[3] = {0, 0, 0}, p[3], d[3];
				for (int v = 0; v < m; v++) {
					vtkr_point(r, vtkr_cell_point(r, c, v), p);
					v3_axpy(centre, p, 1.0 / m);
				}
				for (int v = 0; v < m; v++) {
					vtkr_point(r, vtkr_cell_point(r, c, v), p);
					v3_sub(d, p, q->x);
					bad += fabs(v3_norm(d) - q->radius) > 1e-9 * q->radius;
					bad += fabs(v3_dot(d, q->normal)) > 1e-9 * q->radius;
				}
				v3_sub(d, centre, q->x);
				bad += m != 16 || v3_norm(d) > 1e-9 * q->radius;
				bad += vtkr_value(r, 'c', "mode", c, 0) != q->mode;
				bad += vtkr_value(r, 'c', "t", c, 0) != q->t;
				bad += vtkr_value(r, 'c', "strain_axial", c, 0) != q->strain_axial;
				bad += vtkr_value(r, 'c', "fn", c, 0) != q->fn;
				bad += vtkr_value(r, 'c', "fs_magnitude", c, 0) != q->fs;
				bad += vtkr_value(r, 'c', "i", c, 0) != q->i;
				bad += vtkr_value(r, 'c', "radius", c, 0) != q->radius;
			}
			CHECK(bad == 0);
		}
		vtkr_close(r);
	}
}

/* The platens are normal to the axis at the particle extents. */
static void check_platens(const dem_run *run, const dem_snapshot *s)
{
	vtkr *r = open_file("platens_000002.vtp");
	if (!r)
		return;
	const double *a = run->assembly.geom.axis, *o = run->assembly.geom.center;
	double lo = INFINITY, hi = -INFINITY, d[3];
	for (size_t k = 0; k < run->assembly.n; k++) {
		v3_sub(d, s->x + 3 * k, o);
		lo = fmin(lo, v3_dot(d, a) - run->assembly.r[k]);
		hi = fmax(hi, v3_dot(d, a) + run->assembly.r[k]);
	}
	CHECK(vtkr_ncells(r) == 2);
	int bad = 0;
	for (int c = 0; c < 2; c++) {
		int which = (int)vtkr_value(r, 'c', "platen", c, 0);
		for (int v = 0; v < vtkr_cell_size(r, c); v++) {
			double p[3];
			vtkr_point(r, vtkr_cell_point(r, c, v), p);
			v3_sub(d, p, o);
			bad += fabs(v3_dot(d, a) - (which ? hi : lo)) > 1e-12;
		}
		bad += vtkr_value(r, 'c', "stress_axial", c, 0) != s->stress_axial;
	}
	CHECK(bad == 0);
	vtkr_close(r);
}

static void check_files(const dem_run *run)
{
	char path[1300];
	snprintf(path, sizeof path, "%s/particles_000001.vtu", vdir);
	char *text = harness_slurp(path);
	CHECK_CONTAINS(text, "format=\"appended\"");
	CHECK_CONTAINS(text, "compressor=\"vtkZLibDataCompressor\"");
	CHECK_CONTAINS(text, "<AppendedData encoding=\"raw\">");
	free(text);
	snprintf(path, sizeof path, "%s/run.pvd", vdir);
	text = harness_slurp(path);
	CHECK(count_str(text, "<DataSet ") == 12);
	free(text);
	snprintf(path, sizeof path, "%s/particles.pvd", vdir);
	text = harness_slurp(path);
	CHECK(count_str(text, "<DataSet ") == 3);
	char entry[256];
	snprintf(entry, sizeof entry, "timestep=\"%.10g\" part=\"0\" file=\"particles_000002.vtu\"",
	         run->snap_t[2]);
	CHECK_CONTAINS(text, entry);
	free(text);
	vtkr *g = open_file("geometry.vtp");
	if (g) {
		CHECK(vtkr_ncells(g) == (long)run->assembly.geom.ntri);
		vtkr_close(g);
	}
}

static void check_assembly(const dem_run *run)
{
	char apath[1100], adir[1100];
	snprintf(apath, sizeof apath, "%s/assembly.h5", dir);
	snprintf(adir, sizeof adir, "%s/packing", dir);
	CHECK(assembly_write(apath, &run->assembly) == 0);
	post_result res = harness_post("vtk --out %s %s", adir, apath);
	CHECK(res.status == 0);
	harness_free(&res);
	snprintf(vdir, sizeof vdir, "%s", adir);
	vtkr *r = open_file("particles.vtu");
	if (!r)
		return;
	long n = (long)run->assembly.n, nt;
	CHECK(vtkr_npoints(r) == n);
	check_array(r, 'p', "radius", 1, n);
	check_array(r, 'p', "material", 1, n);
	CHECK(vtkr_array(r, 'p', "displacement", &nt) == -1);
	CHECK(vtkr_value(r, 'p', "radius", n - 1, 0) == run->assembly.r[n - 1]);
	vtkr_close(r);
	char gpath[1300];
	snprintf(gpath, sizeof gpath, "%s/geometry.vtp", adir);
	CHECK(harness_exists(gpath));
}

/* The files in d whose names start with prefix. */
static int count_files(const char *d, const char *prefix)
{
	char cmd[1400];
	snprintf(cmd, sizeof cmd, "ls -A '%s' | grep -c '^%s' > '%s/count.txt'", d, prefix, dir);
	if (system(cmd) < 0)
		return -1;
	snprintf(cmd, sizeof cmd, "%s/count.txt", dir);
	char *text = harness_slurp(cmd);
	int n = text ? atoi(text) : -1;
	free(text);
	return n;
}

/* A series written over another run's replaces it as a whole: the older
 * frames beyond the new ones removed, the other files of the directory
 * kept, what a killed post left in its staging directory cleared. */
static void check_replaced(const char *run_path)
{
	char d[1200], path[1300];
	snprintf(d, sizeof d, "%s/replaced", dir);
	post_result res = harness_post("vtk --out %s %s", d, run_path);
	CHECK(res.status == 0);
	harness_free(&res);
	CHECK(count_files(d, "particles_") == 3 && count_files(d, "cracks_") >= 3);
	snprintf(path, sizeof path, "%s/notes.txt", d);
	FILE *f = fopen(path, "w");
	CHECK(f && fputs("mine\n", f) >= 0 && fclose(f) == 0);
	snprintf(path, sizeof path, "%s/.vtk.new", d);
	CHECK(mkdir(path, 0777) == 0);
	snprintf(path, sizeof path, "%s/.vtk.new/particles_000007.vtu", d);
	f = fopen(path, "w");
	CHECK(f && fclose(f) == 0);
	res = harness_post("vtk --every 2 --out %s %s", d, run_path);
	CHECK(res.status == 0);
	harness_free(&res);
	CHECK(count_files(d, "particles_") == 2 && count_files(d, "bonds_") == 2);
	CHECK(count_files(d, "particles_000002") == 0);
	CHECK(count_files(d, "notes.txt") == 1);
	CHECK(count_files(d, ".vtk.new") == 0);
	snprintf(path, sizeof path, "%s/every", dir);
	char cmd[4000];
	snprintf(cmd, sizeof cmd, "rm '%s/notes.txt' && diff -r '%s' '%s'", d, path, d);
	CHECK(system(cmd) == 0);
}

int main(void)
{
	harness_dir(dir, sizeof dir, "vtk");
	char run_path[1100];
	snprintf(run_path, sizeof run_path, "%s/run.h5", dir);
	snprintf(vdir, sizeof vdir, "%s/vtk", dir);
	synth_opts o = synth_defaults();
	o.nparticles = 150;
	o.nsnap = 3;
	o.axis[0] = 0.5; /* a tilted loading axis */
	CHECK(synth_run(run_path, &o) == 0);
	post_result res = harness_post("vtk %s", run_path);
	CHECK(res.status == 0);
	CHECK_CONTAINS(res.out, "wrote 3 snapshots");
	harness_free(&res);
	dem_run run;
	dem_snapshot s;
	CHECK(run_read(run_path, &run) == 0);
	CHECK(run_read_snapshot(run_path, &run, 2, &s) == 0);
	check_particles(&run, &s);
	check_bonds(&run, &s);
	check_cracks(&run, &s);
	check_platens(&run, &s);
	check_files(&run);
	/* --every 2 keeps snapshots 0 and 2 */
	res = harness_post("vtk --every 2 --out %s/every %s", dir, run_path);
	CHECK(res.status == 0);
	harness_free(&res);
	char path[1200];
	snprintf(path, sizeof path, "%s/every/particles.pvd", dir);
	char *text = harness_slurp(path);
	CHECK(count_str(text, "<DataSet ") == 2);
	free(text);
	/* The frames go to the threads (--threads): the same files on 1 and 3
	 * as on all cores, above. */
	for (int t = 1; t <= 3; t += 2) {
		res = harness_post("vtk --threads %d --out %s/threads%d %s", t, dir, t, run_path);
		CHECK(res.status == 0);
		harness_free(&res);
		char cmd[2600];
		snprintf(cmd, sizeof cmd, "diff -r '%s' '%s/threads%d'", vdir, dir, t);
		CHECK(system(cmd) == 0);
	}
	check_replaced(run_path);
	check_assembly(&run);
	snapshot_free(&s);
	run_free(&run);
	return check_done();
}
