/* post lammps on a synthetic run (tests/post/synth.h) and on its assembly:
 * the data file's header, box, Atoms, Velocities and Bonds sections and
 * the bond table hold the run file's values (positions, velocities and
 * radii to the bit, the bonds not broken at the snapshot, every bond's
 * reference length and state); the assembly's bonds are those the run
 * formed; bad input is one message, an exit status and no output.
 *
 * With --lmp, LAMMPS itself (lmp, or $DEM_LMP) reads the files with
 * read_data and reports what it read: skipped (exit status 77) where no
 * LAMMPS is installed (Debian: lammps, tools/deps --optional). */
#include <math.h>

#include "lib/runfile.h"
#include "lib/vec3.h"
#include "tests/check.h"
#include "tests/post/harness.h"
#include "tests/post/synth.h"

#define PI 3.14159265358979323846

static char dir[1024], run_path[1100], asm_path[1100];

/* The lines of section `name` of a data file ("Atoms", "Bonds", ...): a
 * pointer to its first line, NULL when absent. */
static const char *section(const char *text, const char *name)
{
	size_t n = strlen(name);
	for (const char *p = text; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL)
		if (strncmp(p, name, n) == 0 && (p[n] == '\n' || p[n] == ' ')) {
			p = strchr(p, '\n');
			return p ? p + 2 : NULL; /* past the blank line */
		}
	return NULL;
}

static const char *next_line(const char *p)
{
	const char *end = strchr(p, '\n');
	return end ? end + 1 : p + strlen(p);
}

static long header_count(const char *text, const char *what)
{
	char key[64];
	snprintf(key, sizeof key, " %s\n", what);
	const char *p = strstr(text, key);
	if (!p)
		return -1;
	while (p > text && p[-1] != '\n')
		p--;
	return strtol(p, NULL, 10);
}

static char *slurp_in(const char *sub, const char *name)
{
	char path[1300];
	snprintf(path, sizeof path, "%s/%s/%s", dir, sub, name);
	return harness_slurp(path);
}

/* Box, Atoms and Velocities of a data file against positions x, velocities
 * v and w (NULL: no Velocities section expected) and the assembly's radii. */
static void check_atoms(const char *text, const dem_assembly *a, const double *x, const double *v,
                        const double *w, int hybrid, double density)
{
	CHECK(header_count(text, "atoms") == (long)a->n);
	CHECK(header_count(text, "atom types") == 1);
	CHECK(header_count(text, "bond types") == 1);
	double dmax = 0;
	for (size_t i = 0; i < a->n; i++)
		dmax = fmax(dmax, 2 * a->r[i]);
	static const char *const lohi[3] = {"xlo xhi", "ylo yhi", "zlo zhi"};
	for (int k = 0; k < 3; k++) {
		const char *p = strstr(text, lohi[k]);
		CHECK(p != NULL);
		if (!p)
			continue;
		while (p > text && p[-1] != '\n')
			p--;
		double lo, hi, elo = INFINITY, ehi = -INFINITY;
		CHECK(sscanf(p, "%lf %lf", &lo, &hi) == 2);
		for (size_t i = 0; i < a->n; i++) {
			elo = fmin(elo, x[3 * i + k] - a->r[i]);
			ehi = fmax(ehi, x[3 * i + k] + a->r[i]);
		}
		/* every sphere inside, one largest diameter from the faces */
		CHECK_NEAR(lo, elo - dmax, 1e-15);
		CHECK_NEAR(hi, ehi + dmax, 1e-15);
	}
	const char *p = section(text, "Atoms");
	CHECK(p != NULL);
	CHECK(strstr(text, hybrid ? "\nAtoms # hybrid\n" : "\nAtoms # bpm/sphere\n") != NULL);
	int bad = 0;
	for (size_t i = 0; p && i < a->n; i++, p = next_line(p)) {
		long id, mol, type;
		double diam, rho, y[3];
		int got = hybrid ? sscanf(p, "%ld %ld %lf %lf %lf %lf %lf %ld", &id, &type, &y[0],
		                          &y[1], &y[2], &diam, &rho, &mol)
		                 : sscanf(p, "%ld %ld %ld %lf %lf %lf %lf %lf", &id, &mol, &type,
		                          &diam, &rho, &y[0], &y[1], &y[2]);
		bad += got != 8 || id != (long)i + 1 || mol != 1 || type != 1 ||
		       diam != 2 * a->r[i] || rho != density;
		for (int k = 0; k < 3; k++)
			bad += y[k] != x[3 * i + k];
	}
	CHECK(bad == 0);
	p = section(text, "Velocities");
	CHECK((p != NULL) == (v != NULL));
	bad = 0;
	for (size_t i = 0; p && v && i < a->n; i++, p = next_line(p)) {
		long id;
		double u[6];
		bad += sscanf(p, "%ld %lf %lf %lf %lf %lf %lf", &id, &u[0], &u[1], &u[2], &u[3],
		              &u[4], &u[5]) != 7 ||
		       id != (long)i + 1;
		for (int k = 0; k < 3; k++)
			bad += u[k] != v[3 * i + k] || u[3 + k] != w[3 * i + k];
	}
	CHECK(bad == 0);
}

/* The Bonds section and the table: the bonds with state < broken (all
 * when state is NULL), in order; every bond in the table. */
static void check_bonds(const char *text, const char *csv, const dem_bonds *b, const uint8_t *state,
                        const double *x, size_t expect_bonded)
{
	static const char *const names[] = {"intact", "damaged", "broken_tension", "broken_shear"};
	CHECK(header_count(text, "bonds") == (long)expect_bonded);
	const char *p = section(text, "Bonds");
	CHECK((p != NULL) == (expect_bonded > 0));
	const char *head = "bond,atom_i,atom_j,lammps_bond,reference_length_m,length_m,state\n";
	CHECK(strncmp(csv, head, strlen(head)) == 0);
	const char *q = strchr(csv, '\n');
	size_t id = 0;
	int bad = 0;
	for (size_t k = 0; k < b->n; k++) {
		int live = !state || state[k] < BOND_BROKEN_TENSION;
		if (live && p) {
			long bid, type, ai, aj;
			bad += sscanf(p, "%ld %ld %ld %ld", &bid, &type, &ai, &aj) != 4 ||
			       bid != (long)id + 1 || type != 1 || ai != b->i[k] + 1 ||
			       aj != b->j[k] + 1;
			p = next_line(p);
		}
		id += (size_t)live;
		/* bond,atom_i,atom_j,lammps_bond,reference_length_m,length_m,state */
		q = q ? q + 1 : q;
		char f[7][64];
		for (int c = 0; q && c < 7; c++)
			harness_field(q, c, f[c], sizeof f[c]);
		double d[3];
		v3_sub(d, x + 3 * (size_t)b->j[k], x + 3 * (size_t)b->i[k]);
		char want_id[32] = "";
		if (live)
			snprintf(want_id, sizeof want_id, "%zu", id);
		bad += !q || strtol(f[0], NULL, 10) != (long)k || atol(f[1]) != b->i[k] + 1 ||
		       atol(f[2]) != b->j[k] + 1 || strcmp(f[3], want_id) != 0 ||
		       strtod(f[4], NULL) != b->d0[k] ||
		       fabs(strtod(f[5], NULL) - v3_norm(d)) > 1e-15 ||
		       strcmp(f[6], names[state ? state[k] : 0]) != 0;
		q = q ? strchr(q, '\n') : q;
	}
	CHECK(bad == 0);
	CHECK(id == expect_bonded);
	CHECK(q && q[1] == '\0'); /* no more rows */
}

static size_t count_bonded(const dem_bonds *b, const uint8_t *state)
{
	size_t n = 0;
	for (size_t k = 0; k < b->n; k++)
		n += state[k] < BOND_BROKEN_TENSION;
	return n;
}

static void check_run(const dem_run *r)
{
	post_result res = harness_post("lammps --out %s/last %s", dir, run_path);
	CHECK(res.status == 0);
	CHECK_CONTAINS(res.out, "snapshot 4 (step");
	CHECK_CONTAINS(res.out, "atom_style bpm/sphere, units si");
	harness_free(&res);
	dem_snapshot s;
	CHECK(run_read_snapshot(run_path, r, r->nsnap - 1, &s) == 0);
	size_t live = count_bonded(&r->bonds, s.state);
	CHECK(live > 0 && live < r->bonds.n); /* some broken, some not: the test means something */
	char *text = slurp_in("last", "lammps.data"), *csv = slurp_in("last", "lammps_bonds.csv");
	CHECK_CONTAINS(text, "LAMMPS data file (units si, atom_style bpm/sphere): the run ");
	check_atoms(text, &r->assembly, s.x, s.v, s.w, 0, SYNTH_DENSITY);
	check_bonds(text, csv, &r->bonds, s.state, s.x, live);
	free(text), free(csv);
	snapshot_free(&s);

	/* the first snapshot, for older LAMMPS, at another density */
	res =
	    harness_post("lammps --atom-style hybrid --snapshot 0 --density 2650 --out %s/first %s",
	                 dir, run_path);
	CHECK(res.status == 0);
	harness_free(&res);
	CHECK(run_read_snapshot(run_path, r, 0, &s) == 0);
	text = slurp_in("first", "lammps.data"), csv = slurp_in("first", "lammps_bonds.csv");
	check_atoms(text, &r->assembly, s.x, s.v, s.w, 1, 2650);
	check_bonds(text, csv, &r->bonds, s.state, s.x, count_bonded(&r->bonds, s.state));
	free(text), free(csv);
	snapshot_free(&s);
}

/* The run's assembly: the bonds post forms are the run's (synth bonds
 * within (1 + 0.7)(r_i + r_j), the beta of its report); a smaller --beta
 * forms fewer, each within its range. */
static void check_assembly(const dem_run *r)
{
	CHECK(assembly_write(asm_path, &r->assembly) == 0);
	post_result res =
	    harness_post("lammps --density 2500 --margin 0 --out %s/asm %s", dir, asm_path);
	CHECK(res.status == 0);
	harness_free(&res);
	char *text = slurp_in("asm", "lammps.data"), *csv = slurp_in("asm", "lammps_bonds.csv");
	CHECK_CONTAINS(text, "bonded for d <= (1 + 0.7)(r_i + r_j)");
	CHECK(section(text, "Velocities") == NULL);
	check_bonds(text, csv, &r->bonds, NULL, r->assembly.x, r->bonds.n);
	const char *p = strstr(text, "xlo xhi");
	while (p > text && p[-1] != '\n')
		p--;
	double lo = 0, elo = INFINITY;
	CHECK(sscanf(p, "%lf", &lo) == 1);
	for (size_t i = 0; i < r->assembly.n; i++)
		elo = fmin(elo, r->assembly.x[3 * i] - r->assembly.r[i]);
	CHECK(lo == elo); /* --margin 0: the box touches the spheres */
	free(text), free(csv);

	res = harness_post("lammps --density 2500 --beta 0.05 --out %s/asm05 %s", dir, asm_path);
	CHECK(res.status == 0);
	harness_free(&res);
	text = slurp_in("asm05", "lammps.data");
	size_t want = 0;
	const dem_assembly *a = &r->assembly;
	for (size_t i = 0; i < a->n; i++)
		for (size_t j = i + 1; j < a->n; j++) {
			double d[3];
			v3_sub(d, a->x + 3 * j, a->x + 3 * i);
			want += v3_norm(d) <= 1.05 * (a->r[i] + a->r[j]);
		}
	CHECK(want > 0 && want < r->bonds.n);
	CHECK(header_count(text, "bonds") == (long)want);
	free(text);
}

/* post lammps <args> fails with status and exactly message, writing nothing. */
static void expect(int status, const char *message, const char *args)
{
	char out[1100];
	snprintf(out, sizeof out, "%s/bad", dir);
	post_result r = harness_post("lammps --out %s %s", out, args);
	if (r.status != status)
		fprintf(stderr, "post lammps %s: status %d\n", args, r.status);
	CHECK(r.status == status);
	CHECK_STR(r.err, message);
	CHECK(!harness_exists(out));
	harness_free(&r);
}

static void check_errors(void)
{
	const char *usage = " (usage: post lammps [options] RUN.h5|ASSEMBLY.h5; see --help)\n";
	char msg[4096], args[2400], tiny[1100], empty[1100];
	snprintf(msg, sizeof msg,
	         "post: %s: an assembly holds no density: give --density RHO (kg/m^3)%s", asm_path,
	         usage);
	expect(2, msg, asm_path);
	snprintf(args, sizeof args, "--density 2500 --snapshot 0 %s", asm_path);
	snprintf(msg, sizeof msg,
	         "post: %s: an assembly has one state: --snapshot, --time, --strain and --stress "
	         "choose a run's%s",
	         asm_path, usage);
	expect(2, msg, args);
	snprintf(args, sizeof args, "--beta 0.1 %s", run_path);
	snprintf(msg, sizeof msg,
	         "post: %s: --beta is for an assembly: a run's bonds are those solve formed%s",
	         run_path, usage);
	expect(2, msg, args);
	snprintf(args, sizeof args, "--beta 2 %s", asm_path);
	snprintf(msg, sizeof msg, "post: --beta 2: expected a number in [0, 1]%s", usage);
	expect(2, msg, args);
	snprintf(args, sizeof args, "--atom-style sphere %s", run_path);
	snprintf(msg, sizeof msg, "post: --atom-style sphere: expected bpm/sphere or hybrid%s",
	         usage);
	expect(2, msg, args);
	snprintf(args, sizeof args, "--snapshot 5 %s", run_path);
	snprintf(msg, sizeof msg,
	         "post: %s: --snapshot 5: out of range (the run has 5 snapshots: 0 to 4, or -1 "
	         "for the last)\n",
	         run_path);
	expect(1, msg, args);
	snprintf(args, sizeof args, "--density -1 %s", run_path);
	expect(2, "post: --density -1: expected a number in [0, 1e+09] (kg/m^3)\n", args);
	/* a run whose configuration names no material */
	snprintf(tiny, sizeof tiny, "%s/tiny.h5", dir);
	snprintf(empty, sizeof empty, "%s/empty.h5", dir);
	const double t[2] = {0, 1e-3}, s[2] = {0, 5e6};
	CHECK(synth_tiny(tiny, 2, t, s, 2, t, s, 1) == 0);
	CHECK(synth_tiny(empty, 0, NULL, NULL, 0, NULL, NULL, 1) == 0);
	snprintf(msg, sizeof msg,
	         "post: %s: its configuration has no material density: give --density RHO "
	         "(kg/m^3)\n",
	         tiny);
	expect(1, msg, tiny);
	snprintf(args, sizeof args, "--density 1000 %s", empty);
	snprintf(msg, sizeof msg,
	         "post: %s: the run has no snapshots (it stopped before writing one)\n", empty);
	expect(1, msg, args);
	post_result r = harness_post("lammps --density 1000 --out %s/tiny %s", dir, tiny);
	CHECK(r.status == 0);
	CHECK_CONTAINS(r.out, "(4 spheres, 2 bonds of 2,");
	harness_free(&r);
	/* nothing left under a temporary name */
	char cmd[1300];
	snprintf(cmd, sizeof cmd, "ls %s/*/*.tmp* >/dev/null 2>&1", dir);
	CHECK(system(cmd) != 0);
}

/* LAMMPS reads the files: what read_data reports matches the run. */
static int lmp_read(const char *lmp, const char *sub, const char *style, const dem_assembly *a,
                    const double *x, long bonds)
{
	char in[1300], out[1300], cmd[4000];
	snprintf(in, sizeof in, "%s/%s/in.lmp", dir, sub);
	snprintf(out, sizeof out, "%s/%s/lmp.out", dir, sub);
	FILE *f = fopen(in, "w");
	if (!f)
		return -1;
	fprintf(f,
	        "units si\natom_style %s\nboundary f f f\nread_data lammps.data\n"
	        "print \"CHECK $(atoms) $(bonds) $(mass(all):%%.17g) $(xlo:%%.17g) "
	        "$(zhi:%%.17g)\"\n"
	        "print \"CHECK $(x[1]:%%.17g) $(y[1]:%%.17g) $(z[1]:%%.17g) $(mass[1]:%%.17g)\"\n",
	        style);
	fclose(f);
	snprintf(cmd, sizeof cmd, "cd %s/%s && %s -in in.lmp -log none -echo none >lmp.out 2>&1",
	         dir, sub, lmp);
	int rc = system(cmd);
	char *text = harness_slurp(out);
	const char *p = strstr(text, "CHECK ");
	long natoms = -1, nbonds = -1;
	double mass = 0, xlo = 0, zhi = 0, y[3] = {0}, m1 = 0;
	CHECK(rc == 0 && p != NULL);
	if (rc != 0 || !p) {
		fprintf(stderr, "%s", text);
		free(text);
		return -1;
	}
	CHECK(sscanf(p, "CHECK %ld %ld %lf %lf %lf", &natoms, &nbonds, &mass, &xlo, &zhi) == 5);
	p = strstr(p + 1, "CHECK ");
	CHECK(p && sscanf(p, "CHECK %lf %lf %lf %lf", &y[0], &y[1], &y[2], &m1) == 4);
	double want = 0, dmax = 0, lo = INFINITY, hi = -INFINITY;
	for (size_t i = 0; i < a->n; i++) {
		want += SYNTH_DENSITY * 4.0 / 3.0 * PI * pow(a->r[i], 3);
		dmax = fmax(dmax, 2 * a->r[i]);
		lo = fmin(lo, x[3 * i] - a->r[i]);
		hi = fmax(hi, x[3 * i + 2] + a->r[i]);
	}
	CHECK(natoms == (long)a->n);
	CHECK(nbonds == bonds);
	CHECK_REL(mass, want, 1e-12);
	CHECK_REL(m1, SYNTH_DENSITY * 4.0 / 3.0 * PI * pow(a->r[0], 3), 1e-12);
	CHECK_NEAR(xlo, lo - dmax, 1e-15);
	CHECK_NEAR(zhi, hi + dmax, 1e-15);
	for (int k = 0; k < 3; k++)
		CHECK(y[k] == x[k]);
	printf("LAMMPS (%s) read %ld atoms, %ld bonds, mass %.6g kg\n", style, natoms, nbonds,
	       mass);
	free(text);
	return 0;
}

static int has_style(const char *lmp, const char *style)
{
	char cmd[1200];
	snprintf(cmd, sizeof cmd, "%s -h 2>/dev/null | grep -qw '%s'", lmp, style);
	return system(cmd) == 0;
}

static int check_lammps(const dem_run *r)
{
	const char *lmp = getenv("DEM_LMP");
	if (!lmp || !lmp[0])
		lmp = "lmp";
	char cmd[1200];
	snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", lmp);
	if (system(cmd) != 0 || !has_style(lmp, "hybrid")) {
		printf("SKIPPED: no LAMMPS (%s) to read the data files (Debian: lammps; tools/deps "
		       "--optional)\n",
		       lmp);
		return 77;
	}
	dem_snapshot s;
	CHECK(run_read_snapshot(run_path, r, r->nsnap - 1, &s) == 0);
	long live = (long)count_bonded(&r->bonds, s.state);
	static const char *const dirs[2] = {"lmp_hybrid", "lmp_bpm"};
	for (int k = 0; k < 2; k++) {
		if (k == 1 && !has_style(lmp, "bpm/sphere")) {
			printf("note: %s has no atom style bpm/sphere (a LAMMPS without the BPM "
			       "package): only hybrid sphere bond read\n",
			       lmp);
			continue;
		}
		post_result res = harness_post("lammps --atom-style %s --out %s/%s %s",
		                               k ? "bpm/sphere" : "hybrid", dir, dirs[k], run_path);
		CHECK(res.status == 0);
		harness_free(&res);
		char style[64];
		snprintf(style, sizeof style, "%s", k ? "bpm/sphere" : "hybrid sphere bond");
		lmp_read(lmp, dirs[k], style, &r->assembly, s.x, live);
	}
	snapshot_free(&s);
	return check_done();
}

int main(int argc, char **argv)
{
	int lmp = argc > 1 && strcmp(argv[1], "--lmp") == 0;
	harness_dir(dir, sizeof dir, lmp ? "lammps_lmp" : "lammps");
	snprintf(run_path, sizeof run_path, "%s/run.h5", dir);
	snprintf(asm_path, sizeof asm_path, "%s/assembly.h5", dir);
	synth_opts o = synth_defaults();
	CHECK(synth_run(run_path, &o) == 0);
	dem_run r;
	CHECK(run_read(run_path, &r) == 0);
	if (lmp) {
		int rc = check_lammps(&r);
		run_free(&r);
		return rc;
	}
	check_run(&r);
	check_assembly(&r);
	check_errors();
	run_free(&r);
	return check_done();
}
