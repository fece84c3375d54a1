/* post ratios on a synthetic snapshot with known forces.
 *
 * Each bond is built at a chosen angle theta to the plane normal to the
 * loading axis, well inside one 10-degree bin, with a chosen compressive
 * force, area and shear force; the expected count, mean and (population)
 * standard deviation of sigma_n = -fn / A and tau = |fs| / A of every bin
 * and group are computed here from those choices, not from positions.
 * Bonds that must not count (broken, in tension, unloaded) are spread over
 * the bins, and bin 60-70 receives only those, so it must come out empty.
 * The same specimen is built about the z axis and about a tilted axis:
 * the statistics must not change. */
#include <math.h>
#include <stdint.h>

#include "lib/runfile.h"
#include "lib/vec3.h"
#include "tests/check.h"
#include "tests/post/harness.h"
#include "tests/post/vtkread.h"

#define PI 3.14159265358979323846
enum { NBINS = 9, EMPTY_BIN = 6, MAXB = 512 };
enum { ALL, INTACT, DAMAGED };

/* What the test expects of one group and bin. */
typedef struct {
	int n;
	double sn[64], tau[64];
} bucket;

typedef struct {
	size_t nb;
	int32_t i[MAXB], j[MAXB];
	double x[2 * MAXB][3], area[MAXB], fn[MAXB], fs[MAXB][3];
	uint8_t state[MAXB];
	double theta[MAXB]; /* the angle each valid bond was built at */
	int valid[MAXB];    /* counted: bonded and in compression */
} design;

static bucket expect[3][NBINS];

static void unit_frame(const double a[3], double e1[3], double e2[3])
{
	double u[3] = {1, 0, 0};
	if (fabs(a[0]) > 0.9)
		u[0] = 0, u[1] = 1;
	v3_reject(e1, u, a);
	v3_scale(e1, e1, 1 / v3_norm(e1));
	v3_cross(e2, a, e1);
}

/* Add a bond of direction angle theta (deg), azimuth phi (deg). */
static size_t add_bond(design *d, const double a[3], double theta, double phi, int flip)
{
	double e1[3], e2[3], n[3] = {0, 0, 0};
	unit_frame(a, e1, e2);
	double t = theta * PI / 180, p = phi * PI / 180;
	v3_axpy(n, e1, cos(t) * cos(p));
	v3_axpy(n, e2, cos(t) * sin(p));
	v3_axpy(n, a, sin(t));
	if (flip)
		v3_scale(n, n, -1);
	size_t b = d->nb++;
	double base[3] = {0.01 * (double)b, 0.013 * (double)(b % 7), 0.007 * (double)(b % 5)};
	v3_copy(d->x[2 * b], base);
	v3_copy(d->x[2 * b + 1], base);
	v3_axpy(d->x[2 * b + 1], n, 2.1e-3 * (1 + 0.05 * (double)(b % 4)));
	d->i[b] = (int32_t)(2 * b);
	d->j[b] = (int32_t)(2 * b + 1);
	d->theta[b] = theta;
	/* the shear force is normal to the bond */
	double s[3];
	v3_cross(s, n, a);
	if (v3_norm(s) < 1e-6)
		v3_copy(s, e1);
	v3_scale(d->fs[b], s, 1 / v3_norm(s));
	return b;
}

static void valid_bond(design *d, const double a[3], int k, int q, double theta)
{
	size_t b = add_bond(d, a, theta, 37.0 * q + 11.0 * k, q % 2);
	d->state[b] = q % 3 == 1 ? BOND_DAMAGED : BOND_INTACT;
	d->area[b] = 1e-6 * (1 + 0.1 * q + 0.01 * k);
	d->fn[b] = -(1000.0 * (k + 1) + 137.0 * q * q + 50.0 * q);
	double shear = 200 + 31.0 * q + 7.0 * k;
	v3_scale(d->fs[b], d->fs[b], shear);
	d->valid[b] = 1;
	double sn = -d->fn[b] / d->area[b], tau = shear / d->area[b];
	int groups[2] = {ALL, d->state[b] == BOND_INTACT ? INTACT : DAMAGED};
	for (int g = 0; g < 2; g++) {
		bucket *e = &expect[groups[g]][k];
		e->sn[e->n] = sn;
		e->tau[e->n] = tau;
		e->n++;
	}
}

/* Bonds that must be left out, in bin k. */
static void excluded_bonds(design *d, const double a[3], int k)
{
	const uint8_t state[4] = {BOND_BROKEN_TENSION, BOND_BROKEN_SHEAR, BOND_INTACT,
	                          BOND_DAMAGED};
	const double fn[4] = {-5000, -7000, 800, 0};
	for (int q = 0; q < 4; q++) {
		size_t b = add_bond(d, a, 10.0 * k + 2.5 * q + 1, 50.0 * q, 0);
		d->state[b] = state[q];
		d->fn[b] = fn[q];
		d->area[b] = 1e-6;
		v3_scale(d->fs[b], d->fs[b], 300);
	}
}

static void build(design *d, const double a[3])
{
	memset(d, 0, sizeof *d);
	memset(expect, 0, sizeof expect);
	for (int k = 0; k < NBINS; k++) {
		excluded_bonds(d, a, k);
		if (k == EMPTY_BIN)
			continue;
		int m = 3 + k;
		for (int q = 0; q < m; q++)
			valid_bond(d, a, k, q, 10.0 * k + 10.0 * (q + 0.5) / m);
	}
	/* the ends of the range: a horizontal bond and one along the axis */
	valid_bond(d, a, 0, 3, 0);
	valid_bond(d, a, NBINS - 1, 7, 90);
}

static const run_column columns[] = {{"t", "s"}, {"strain_axial", ""}, {"stress_axial", "Pa"}};

/* The run: three history rows of stress 0, stress / 2, stress (or, when
 * falling, 0, stress, stress / 2) and one snapshot at the last, ended with
 * the given status. */
static void write_run_as(const char *path, const design *d, const double a[3], double stress,
                         const char *status, int falling)
{
	size_t n = 2 * d->nb;
	dem_assembly as;
	memset(&as, 0, sizeof as);
	prov_init(&as.prov, "pack", "{}", 0);
	as.n = n;
	as.x = malloc(3 * n * sizeof *as.x);
	memcpy(as.x, d->x, 3 * n * sizeof *as.x);
	as.r = malloc(n * sizeof *as.r);
	as.material = calloc(n, sizeof *as.material);
	for (size_t k = 0; k < n; k++)
		as.r[k] = 1e-3;
	strcpy(as.geom.shape, "cylinder");
	v3_copy(as.geom.axis, a);
	as.geom.center[0] = 0.05;
	as.geom.diameter = 0.05;
	as.geom.height = 0.1;
	dem_provenance prov;
	prov_init(&prov, "solve", "{}", 0);
	run_writer *w = run_create(path, &prov, &as, columns, 3);
	dem_bonds b = {.n = d->nb,
	               .i = (int32_t *)d->i,
	               .j = (int32_t *)d->j,
	               .d0 = calloc(d->nb, sizeof(double)),
	               .area = (double *)d->area,
	               .kn = calloc(d->nb, sizeof(double)),
	               .ks = calloc(d->nb, sizeof(double))};
	CHECK(run_write_bonds(w, &b) == 0);
	for (int r = 0; r < 3; r++) {
		double row[3] = {1e-3 * r, 1e-3 * r, stress * (falling && r == 2 ? 1 : r) / 2};
		if (falling && r == 1)
			row[2] = stress;
		CHECK(run_history(w, row) == 0);
	}
	double *zero = calloc(3 * n, sizeof *zero), *dmg = calloc(d->nb, sizeof *dmg);
	dem_snapshot s = {.step = 200,
	                  .t = 2e-3,
	                  .strain_axial = 2e-3,
	                  .stress_axial = stress,
	                  .n = n,
	                  .x = as.x,
	                  .v = zero,
	                  .w = zero,
	                  .nbonds = d->nb,
	                  .state = (uint8_t *)d->state,
	                  .damage_n = dmg,
	                  .damage_s = dmg,
	                  .fn = (double *)d->fn,
	                  .fs = (double *)d->fs};
	CHECK(run_snapshot(w, &s) == 0);
	CHECK(run_finish(w, status) == 0);
	free(zero), free(dmg), free(b.d0), free(b.kn), free(b.ks);
	prov_free(&prov);
	assembly_free(&as);
}

static void write_run(const char *path, const design *d, const double a[3], double stress)
{
	write_run_as(path, d, a, stress, "complete", 0);
}

/* Fig. 11 at the peak of a run that a strain stop ended while its stress
 * still rose: the "peak" is flagged as the stop's plateau, in a warning and
 * in the legend; not when the stress fell before the stop, nor when
 * another rule ended the run. */
static void check_plateau(const design *d, const double a[3])
{
	static const struct {
		const char *status;
		int falling, flagged;
	} runs[] = {{"stopped: axial strain reached 0.002", 0, 1},
	            {"stopped: axial strain reached 0.002", 1, 0},
	            {"complete", 0, 0}};
	for (int k = 0; k < 3; k++) {
		char dir[1024], run[1100], gp[1100];
		harness_dir(dir, sizeof dir, "ratios_plateau");
		snprintf(run, sizeof run, "%s/run%d.h5", dir, k);
		snprintf(gp, sizeof gp, "%s/ratios.gp", dir);
		write_run_as(run, d, a, 2.5e6, runs[k].status, runs[k].falling);
		post_result r = harness_post("ratios --out %s %s", dir, run);
		CHECK(r.status == 0);
		CHECK(!!strstr(r.err, "the strain stop's plateau, not a limit stress") ==
		      runs[k].flagged);
		harness_free(&r);
		char *text = harness_slurp(gp);
		CHECK(text && !!strstr(text, "no peak: strain stop") == runs[k].flagged);
		free(text);
	}
}

static void mean_std(const double *v, int n, double *mean, double *sd)
{
	double s = 0, q = 0;
	for (int k = 0; k < n; k++)
		s += v[k];
	*mean = s / n;
	for (int k = 0; k < n; k++)
		q += (v[k] - *mean) * (v[k] - *mean);
	*sd = sqrt(q / n);
}

static double num(const char *line, int k)
{
	char buf[64];
	harness_field(line, k, buf, sizeof buf);
	return buf[0] ? strtod(buf, NULL) : NAN;
}

/* Compare ratios.csv with the expectations, for reference stress ref. */
static void check_csv(const char *csv, double ref)
{
	char *text = harness_slurp(csv), *save = NULL;
	const char *groups[3] = {"all", "intact", "damaged"};
	int rows = 0;
	for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
		if (rows++ == 0) {
			CHECK_STR(line,
			          "run,snapshot,step,t_s,strain_axial,stress_axial_Pa,sigma_ref_Pa,"
			          "group,theta_min_deg,theta_max_deg,count,sigma_n_mean_Pa,"
			          "sigma_n_std_Pa,r,r_std,tau_mean_Pa,tau_std_Pa");
			continue;
		}
		char g[32];
		harness_field(line, 7, g, sizeof g);
		int grp = strcmp(g, groups[1]) == 0   ? INTACT
		          : strcmp(g, groups[2]) == 0 ? DAMAGED
		                                      : ALL;
		int k = (int)lround(num(line, 8) / 10);
		CHECK(k >= 0 && k < NBINS);
		if (k < 0 || k >= NBINS)
			continue;
		CHECK(num(line, 9) == 10.0 * (k + 1));
		CHECK_REL(num(line, 6), ref, 1e-9);
		const bucket *e = &expect[grp][k];
		CHECK(num(line, 10) == e->n);
		if (e->n == 0) {
			CHECK(isnan(num(line, 11)) && isnan(num(line, 12)) && isnan(num(line, 13)));
			continue;
		}
		double m, sd, tm, tsd;
		mean_std(e->sn, e->n, &m, &sd);
		mean_std(e->tau, e->n, &tm, &tsd);
		CHECK_REL(num(line, 11), m, 1e-9);
		CHECK_NEAR(num(line, 12), sd, 1e-9 * m);
		CHECK_REL(num(line, 13), m / ref, 1e-9);
		CHECK_NEAR(num(line, 14), sd / ref, 1e-9 * m / ref);
		CHECK_REL(num(line, 15), tm, 1e-9);
		CHECK_NEAR(num(line, 16), tsd, 1e-9 * tm);
	}
	CHECK(rows == 1 + 3 * NBINS);
	CHECK(expect[ALL][EMPTY_BIN].n == 0 && expect[ALL][0].n > 0);
	free(text);
}

/* Equal-solid-angle bins: edges asin(k/3); counts classified here by
 * sin(theta) of the angles the bonds were built at. */
static void check_solid_angle(const char *csv, const design *d)
{
	int count[3] = {0, 0, 0};
	for (size_t b = 0; b < d->nb; b++)
		if (d->valid[b]) {
			int k = (int)floor(3 * sin(d->theta[b] * PI / 180));
			count[k < 3 ? k : 2]++;
		}
	char *text = harness_slurp(csv), *save = NULL;
	int row = 0;
	for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
		if (row++ == 0 || !strstr(line, ",all,"))
			continue;
		int k = row - 2;
		CHECK_NEAR(num(line, 8), asin(k / 3.0) * 180 / PI, 1e-8);
		CHECK_NEAR(num(line, 9), asin((k + 1) / 3.0) * 180 / PI, 1e-8);
		CHECK(num(line, 10) == count[k]);
	}
	CHECK(row == 1 + 3 * 3);
	free(text);
}

/* ratios.png: a real image, with the first run's colour (style.gp), its
 * height grown by its legend's two rows (the run and the paper's band). */
static void check_png(const char *png)
{
	int w = 0, h = 0;
	long colours = 0, count[1];
	unsigned blue = 0x0072B2;
	CHECK(vtkr_png(png, &w, &h, &colours, &blue, count, 1) == 0);
	CHECK(w == 900 && h == 600 + 21 * 2);
	CHECK(colours > 20);   /* text, grid, lines: not a blank frame */
	CHECK(count[0] > 300); /* the line of the run */
}

/* Two runs in one table and figure: 27 rows each under their labels, and
 * both runs' colours (style.gp) in the picture. */
static void check_two_runs(const char *dir, const char *run1, const char *run2)
{
	post_result r = harness_post("ratios --snapshot 0 --labels UCS,confined --out %s %s %s",
	                             dir, run1, run2);
	CHECK(r.status == 0);
	CHECK_CONTAINS(r.out, "UCS: ");
	CHECK_CONTAINS(r.out, "confined: ");
	harness_free(&r);
	char path[1200];
	snprintf(path, sizeof path, "%s/ratios.csv", dir);
	char *text = harness_slurp(path);
	int ucs = 0, confined = 0;
	for (const char *p = text; (p = strchr(p, '\n')) != NULL;) {
		p++;
		ucs += strncmp(p, "UCS,", 4) == 0;
		confined += strncmp(p, "confined,", 9) == 0;
	}
	CHECK(ucs == 3 * NBINS && confined == 3 * NBINS);
	free(text);
	snprintf(path, sizeof path, "%s/ratios.png", dir);
	const unsigned colours[2] = {0x0072B2, 0xD55E00};
	long count[2] = {0, 0}, distinct = 0;
	int w, h;
	CHECK(vtkr_png(path, &w, &h, &distinct, colours, count, 2) == 0);
	CHECK(count[0] > 300 && count[1] > 300);
}

int main(void)
{
	static design d;
	const double axes[2][3] = {{0, 0, 1}, {1 / 3.0, 2 / 3.0, 2 / 3.0}};
	const double stress = 2.5e6;
	char runs[2][1100];
	for (int c = 0; c < 2; c++) {
		char dir[1024], run[1100], csv[1100];
		harness_dir(dir, sizeof dir, c ? "ratios_tilted" : "ratios_z");
		snprintf(run, sizeof run, "%s/run.h5", dir);
		snprintf(csv, sizeof csv, "%s/ratios.csv", dir);
		build(&d, axes[c]);
		write_run(run, &d, axes[c], c ? 2 * stress : stress);
		snprintf(runs[c], sizeof runs[c], "%s", run);
		post_result r = harness_post("ratios --snapshot 0 --no-png %s", run);
		CHECK(r.status == 0);
		CHECK_CONTAINS(r.out, c ? "snapshot 0 (step 200, t = 0.002 s, axial strain 0.2 %, "
		                          "axial stress 5 MPa)"
		                        : "snapshot 0 (step 200, t = 0.002 s, axial strain 0.2 %, "
		                          "axial stress 2.5 MPa)");
		harness_free(&r);
		check_csv(csv, c ? 2 * stress : stress);
		r = harness_post("ratios --snapshot 0 --sigma-ref 1e7 --no-png --out %s %s", dir,
		                 run);
		CHECK(r.status == 0);
		harness_free(&r);
		check_csv(csv, 1e7);
		r = harness_post(
		    "ratios --snapshot 0 --equal-solid-angle --bin-width 30 --no-png %s", run);
		CHECK(r.status == 0);
		harness_free(&r);
		check_solid_angle(csv, &d);
		if (c == 0) {
			char png[1100];
			r = harness_post("ratios --snapshot 0 %s", run);
			CHECK(r.status == 0);
			harness_free(&r);
			snprintf(png, sizeof png, "%s/ratios.png", dir);
			check_png(png);
			snprintf(png, sizeof png, "%s/ratios_groups.png", dir);
			CHECK(harness_exists(png));
			/* The legend says which reference r is of; bins of too few
			 * contacts are left out, or all drawn when none has enough. */
			r = harness_post("ratios --snapshot 0 --min-contacts 5 %s", run);
			CHECK(r.status == 0 && !strstr(r.err, "no bin has"));
			harness_free(&r);
			snprintf(png, sizeof png, "%s/ratios.gp", dir);
			char *gp = harness_slurp(png);
			CHECK(gp && strstr(gp, "MPa, own)") && strstr(gp, "min_count = 5\n"));
			free(gp);
			r = harness_post(
			    "ratios --snapshot 0 --sigma-ref 1e7 --min-contacts 100000 %s", run);
			CHECK(r.status == 0);
			CHECK_CONTAINS(r.err, "no bin has 100000 contacts (--min-contacts)");
			harness_free(&r);
			gp = harness_slurp(png);
			CHECK(gp && strstr(gp, "10 MPa, common") && strstr(gp, "min_count = 1\n"));
			free(gp);
		}
	}
	char dir[1024];
	harness_dir(dir, sizeof dir, "ratios_two");
	check_two_runs(dir, runs[0], runs[1]);
	build(&d, axes[0]);
	check_plateau(&d, axes[0]);
	return check_done();
}
