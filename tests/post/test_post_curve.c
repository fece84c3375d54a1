/* post curve on a synthetic run: curve.csv is the history table, and the
 * four figures are real images with the curves in their colours;
 * experimental points add black markers. A Brazilian test's figures draw
 * its splitting tensile stress, which curve.csv adds as a last column. Each figure's gnuplot script
 * is left beside it and draws it again; --format pdf and svg draw vector figures, an unknown format
 * is refused. A gnuplot that fails, or draws nothing, is one message, and no figure, script or
 * temporary is left. */
#include <dirent.h>
#include <math.h>
#include <sys/stat.h>

#include "lib/runfile.h"
#include "tests/check.h"
#include "tests/post/harness.h"
#include "tests/post/synth.h"
#include "tests/post/vtkread.h"

/* Pixels near colour rgb in dir/name (-1 if it is no 900x650 PNG). */
static long pixels(const char *dir, const char *name, unsigned rgb)
{
	char path[1200];
	snprintf(path, sizeof path, "%s/%s", dir, name);
	long count = 0, distinct = 0;
	int w = 0, h = 0;
	if (vtkr_png(path, &w, &h, &distinct, &rgb, &count, 1) || w != 900 || h != 650 ||
	    distinct < 20)
		return -1;
	return count;
}

/* post curve with the program gnuplot of a fresh directory first on the
 * PATH: a shell script of body. Expects status 1, the message
 * "figure: gnuplot failed to draw the figure", also says, and no file
 * in the output directory. */
static void failing_gnuplot(const char *dir, const char *run, const char *body, const char *says)
{
	char bin[1100], prog[1200], out[1100], cmd[4000], path[8192];
	snprintf(bin, sizeof bin, "%s/fake", dir);
	snprintf(out, sizeof out, "%s/failed", dir);
	snprintf(prog, sizeof prog, "%s/gnuplot", bin);
	snprintf(cmd, sizeof cmd, "rm -rf '%s' '%s' && mkdir -p '%s'", bin, out, bin);
	CHECK(system(cmd) == 0);
	FILE *f = fopen(prog, "w");
	CHECK(f != NULL);
	if (!f)
		return;
	fprintf(f, "#!/bin/sh\n%s\n", body);
	fclose(f);
	CHECK(chmod(prog, 0755) == 0);
	char *old = strdup(getenv("PATH") ? getenv("PATH") : "/usr/bin:/bin");
	snprintf(path, sizeof path, "%s:%s", bin, old);
	setenv("PATH", path, 1);
	post_result res = harness_post("curve --out %s %s", out, run);
	setenv("PATH", old, 1);
	free(old);
	CHECK(res.status == 1);
	CHECK(strstr(res.err, "gnuplot failed to draw the figure") != NULL);
	CHECK(strstr(res.err, says) != NULL);
	if (res.status != 1 || !strstr(res.err, says))
		fprintf(stderr, "post curve with a failing gnuplot: status %d: %s\n", res.status,
		        res.err);
	harness_free(&res);
	/* Only curve.csv, written before any figure. */
	DIR *d = opendir(out);
	int left = 0;
	for (struct dirent *e; d && (e = readdir(d));)
		if (e->d_name[0] != '.' || strlen(e->d_name) > 2)
			if (strcmp(e->d_name, "curve.csv")) {
				fprintf(stderr, "left behind: %s\n", e->d_name);
				left++;
			}
	if (d)
		closedir(d);
	CHECK(d != NULL && left == 0);
}

/* Rows of datablock `name` of a gnuplot input text: the largest value of
 * its column col (1-based) and the number of rows. */
static size_t datablock_max(const char *text, const char *name, int col, double *max)
{
	size_t rows = harness_datablock(text, name, col, NULL, 0);
	double *v = malloc((rows * (size_t)col + 1) * sizeof *v);
	harness_datablock(text, name, col, v, rows);
	*max = -INFINITY;
	for (size_t k = 0; k < rows; k++)
		*max = fmax(*max, v[k * (size_t)col + (size_t)col - 1]);
	free(v);
	return rows;
}

/* A Brazilian test: curve.csv keeps every history column and adds
 * stress_tensile = 2P/(pi D t); stress_strain.png draws that stress alone
 * (no radial strain), bonds.png too, and volumetric.png is not drawn. */
static void check_bts(const char *parent)
{
	char dir[1100], run[1200], path[1300];
	snprintf(dir, sizeof dir, "%s/bts", parent);
	snprintf(run, sizeof run, "%s/run.h5", dir);
	char cmd[2400];
	snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", dir, dir);
	CHECK(system(cmd) == 0);
	synth_opts o = synth_defaults();
	o.nparticles = 150;
	o.diameter = 12e-3, o.height = 5e-3;
	o.center[2] = 0;
	o.load[0] = 1; /* across a diameter of a disc of axis z */
	CHECK(synth_run(run, &o) == 0);
	dem_run r;
	CHECK(run_read(run, &r) == 0);
	post_result res = harness_post("curve %s", run);
	CHECK(res.status == 0);
	CHECK_CONTAINS(res.out, "a Brazilian test: volumetric.png not drawn");
	harness_free(&res);
	snprintf(path, sizeof path, "%s/volumetric.png", dir);
	CHECK(!harness_exists(path));

	const double *fa = run_column_data(&r, "force_axial");
	CHECK(fa != NULL);
	double D = r.assembly.geom.diameter, t = r.assembly.geom.height, peak = 0;
	snprintf(path, sizeof path, "%s/curve.csv", dir);
	char *text = harness_slurp(path), *save = NULL, buf[64];
	size_t row = 0;
	int bad = 0;
	for (char *line = strtok_r(text, "\n", &save); fa && line;
	     line = strtok_r(NULL, "\n", &save)) {
		if (row++ == 0) {
			for (int c = 0; c < r.ncols; c++)
				bad += strcmp(harness_field(line, c, buf, sizeof buf),
				              r.col_name[c]) != 0;
			bad += strcmp(harness_field(line, r.ncols, buf, sizeof buf),
			              "stress_tensile") != 0;
			continue;
		}
		for (int c = 0; c < r.ncols; c++) {
			double want = r.col[c][row - 2];
			double got = strtod(harness_field(line, c, buf, sizeof buf), NULL);
			bad += fabs(got - want) > 1e-9 * fabs(want);
		}
		double want = 2 * fa[row - 2] / (3.14159265358979323846 * D * t);
		double got = strtod(harness_field(line, r.ncols, buf, sizeof buf), NULL);
		bad += fabs(got - want) > 1e-9 * fabs(want);
		peak = fmax(peak, want);
	}
	CHECK(row == r.nrows + 1);
	CHECK(bad == 0);
	free(text);

	/* The figures' stress is sigma_t (MPa), under its name. */
	double max;
	snprintf(path, sizeof path, "%s/stress_strain.gp", dir);
	text = harness_slurp(path);
	CHECK(datablock_max(text, "$curve", 2, &max) == r.nrows);
	CHECK(fabs(max - 1e-6 * peak) < 1e-6 * max);
	CHECK(text && strstr(text, "bts = 1"));
	free(text);
	snprintf(path, sizeof path, "%s/bonds.gp", dir);
	text = harness_slurp(path);
	CHECK(datablock_max(text, "$stress", 2, &max) == r.nrows);
	CHECK(fabs(max - 1e-6 * peak) < 1e-6 * max);
	free(text);
	CHECK(pixels(dir, "stress_strain.png", 0x0072B2) > 300); /* sigma_t */
	CHECK(pixels(dir, "stress_strain.png", 0xD55E00) == 0);  /* no radial strain */
	run_free(&r);
}

int main(void)
{
	char dir[1024], run[1100], path[1200], exp[1100];
	harness_dir(dir, sizeof dir, "curve");
	snprintf(run, sizeof run, "%s/run.h5", dir);
	synth_opts o = synth_defaults();
	o.nparticles = 150;
	CHECK(synth_run(run, &o) == 0);
	dem_run r;
	CHECK(run_read(run, &r) == 0);
	post_result res = harness_post("curve %s", run);
	CHECK(res.status == 0);
	harness_free(&res);

	snprintf(path, sizeof path, "%s/curve.csv", dir);
	char *text = harness_slurp(path), *save = NULL, buf[64];
	size_t row = 0;
	int bad = 0;
	for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
		if (row++ == 0) {
			for (int c = 0; c < r.ncols; c++)
				bad += strcmp(harness_field(line, c, buf, sizeof buf),
				              r.col_name[c]) != 0;
			continue;
		}
		for (int c = 0; c < r.ncols; c++) {
			double want = r.col[c][row - 2];
			double got = strtod(harness_field(line, c, buf, sizeof buf), NULL);
			bad += fabs(got - want) > 1e-9 * fabs(want);
		}
	}
	CHECK(row == r.nrows + 1);
	CHECK(bad == 0);
	free(text);

	CHECK(pixels(dir, "stress_strain.png", 0x0072B2) > 300); /* axial */
	CHECK(pixels(dir, "stress_strain.png", 0xD55E00) > 300); /* radial */
	CHECK(pixels(dir, "volumetric.png", 0x0072B2) > 300);
	CHECK(pixels(dir, "bonds.png", 0xD62728) > 100 && pixels(dir, "bonds.png", 0x1F4E9E) > 100);
	CHECK(pixels(dir, "energy.png", 0x0072B2) > 300);
	long black = pixels(dir, "stress_strain.png", 0x000000);

	snprintf(exp, sizeof exp, "%s/exp.csv", dir);
	FILE *f = fopen(exp, "w");
	fputs("# synthetic experiment\nstrain_axial,strain_radial,stress_axial_MPa\n", f);
	for (int k = 1; k <= 12; k++)
		fprintf(f, "%g,%g,%g\n", 3e-4 * k, -0.8e-4 * k, 3.0 * k);
	fclose(f);
	res = harness_post("curve --experiment %s --experiment-label lab %s", exp, run);
	CHECK(res.status == 0);
	harness_free(&res);
	long marks = pixels(dir, "stress_strain.png", 0x000000);
	CHECK(marks > black + 200);

	/* The script beside the figure draws the same figure again. */
	snprintf(path, sizeof path, "%s/stress_strain.gp", dir);
	text = harness_slurp(path);
	CHECK(text && strstr(text, "set output 'stress_strain.png'"));
	CHECK(text && strstr(text, "run.h5 · ucs"));
	free(text);
	snprintf(path, sizeof path, "%s/stress_strain.png", dir);
	remove(path);
	char cmd[1300];
	snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot stress_strain.gp", dir);
	CHECK(system(cmd) == 0);
	CHECK(pixels(dir, "stress_strain.png", 0x000000) == marks);

	/* Vector figures. */
	const char *vec[][2] = {{"pdf", "%PDF-"}, {"svg", "<svg"}};
	for (int k = 0; k < 2; k++) {
		res = harness_post("curve --format %s %s", vec[k][0], run);
		CHECK(res.status == 0);
		harness_free(&res);
		snprintf(path, sizeof path, "%s/stress_strain.%s", dir, vec[k][0]);
		text = harness_slurp(path);
		struct stat st;
		CHECK(text && strstr(text, vec[k][1]) && stat(path, &st) == 0 && st.st_size > 5000);
		free(text);
	}
	res = harness_post("curve --format eps %s", run);
	CHECK(res.status == 1 && strstr(res.err, "--format eps: expected png, pdf or svg"));
	harness_free(&res);

	/* gnuplot fails with a message of its own; draws nothing; is killed. */
	failing_gnuplot(dir, run, "echo \"gnuplot: cannot open terminal\" >&2; exit 1",
	                "gnuplot: cannot open terminal");
	failing_gnuplot(dir, run, "exit 0", ".png: gnuplot failed");
	failing_gnuplot(dir, run, "kill -9 $$", ".png: gnuplot failed");
	run_free(&r);
	check_bts(dir);
	return check_done();
}
