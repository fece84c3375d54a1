/* post curve: the history table of a run as curve.csv and figures:
 * stress_strain.png (axial stress against axial and radial strain),
 * volumetric.png (volumetric against axial strain), bonds.png (broken
 * bonds by mode against axial strain, with the stress) and energy.png
 * (every energy_* column). Experimental points can be overlaid
 * (post/experiment.h). History columns used: strain_axial, stress_axial
 * (required), strain_radial, strain_volumetric (else eps_a + 2 eps_r
 * when the radial strain is there), pressure, energy_*.
 * A Brazilian test (the case's test "bts") is judged by its splitting
 * tensile stress sigma_t = 2P/(pi D t), P the history's force_axial, D
 * and t the disc's diameter and thickness (/geometry diameter, height):
 * curve.csv gets it as a last column, stress_tensile, and the figures draw
 * it in place of the axial stress (the load over the disc's face area),
 * without the radial and volumetric strains, which mean nothing for a
 * disc loaded across a diameter. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "post/crackmap.h"
#include "post/experiment.h"
#include "post/frame.h"
#include "post/load.h"
#include "post/output.h"
#include "post/plot.h"
#include "post/post.h"
#include "post/summary.h"

/* What the figures draw as the stress: the axial stress, or a Brazilian
 * test's splitting tensile stress (Pa, one per history row). */
typedef struct {
	int bts;              /* a Brazilian test: no radial or volumetric strain drawn */
	const double *stress; /* Pa */
	double *tensile;      /* sigma_t (malloc'd), NULL when not a Brazilian test */
} curve_stress;

static void stress_of(curve_stress *cs, const char *path, const dem_run *r)
{
	cs->bts = load_is_bts(r);
	cs->stress = run_column_data(r, "stress_axial");
	cs->tensile = NULL;
	if (!cs->bts)
		return;
	const double *fa = run_column_data(r, "force_axial");
	double D = r->assembly.geom.diameter, t = r->assembly.geom.height;
	if (!fa || !(D > 0) || !(t > 0)) {
		printf("%s: a Brazilian test without %s: the figures draw the axial stress, not "
		       "the splitting tensile stress 2P/(pi D t)\n",
		       path,
		       fa ? "the disc's diameter and thickness (/geometry)"
		          : "a force_axial column in the history");
		return;
	}
	cs->tensile = xmalloc((r->nrows ? r->nrows : 1) * sizeof *cs->tensile);
	for (size_t k = 0; k < r->nrows; k++)
		cs->tensile[k] = summary_splitting_stress(fa[k], D, t);
	cs->stress = cs->tensile;
}

/* Every history column, then stress_tensile for a Brazilian test. */
static void write_csv(const char *path, const dem_run *r, const curve_stress *cs)
{
	out_text o;
	out_text_open(&o, path);
	int n = r->ncols + (cs->tensile != NULL);
	for (int c = 0; c < n; c++) {
		out_csv_str(o.f, c < r->ncols ? r->col_name[c] : "stress_tensile");
		fputc(c + 1 < n ? ',' : '\n', o.f);
	}
	for (size_t k = 0; k < r->nrows; k++)
		for (int c = 0; c < n; c++) {
			out_csv_num(o.f, c < r->ncols ? r->col[c][k] : cs->tensile[k]);
			fputc(c + 1 < n ? ',' : '\n', o.f);
		}
	out_text_commit(&o);
}

static const double *required(const char *path, const dem_run *r, const char *name)
{
	const double *v = run_column_data(r, name);
	if (!v)
		fatal("%s: the history has no column '%s' (post curve needs strain_axial and "
		      "stress_axial)",
		      path, name);
	return v;
}

/* Row k of a curve: eps_a(%) sigma_a(MPa) eps_r(%) eps_v(%), the radial
 * and volumetric strains NaN when absent, eps_v from eps_a + 2 eps_r when
 * only the radial strain is there. */
static void curve_row(FILE *f, const double *ea, const double *sa, const double *er,
                      const double *ev, size_t k)
{
	double v[4] = {100 * ea[k], 1e-6 * sa[k], er ? 100 * er[k] : NAN,
	               ev   ? 100 * ev[k]
	               : er ? 100 * (ea[k] + 2 * er[k])
	                    : NAN};
	for (int c = 0; c < 4; c++) {
		plot_num(f, v[c]);
		fputc(c < 3 ? ' ' : '\n', f);
	}
}

/* $curve rows (curve_row), the stress that of cs;
 * and has_radial, has_volumetric, pc (MPa, the largest confining
 * pressure, 0 without a pressure column), bts (1: the stress is a
 * Brazilian test's splitting tensile stress). */
static void curve_data(FILE *f, const char *path, const dem_run *r, const curve_stress *cs)
{
	const double *ea = required(path, r, "strain_axial");
	const double *sa = cs->stress;
	const double *er = cs->bts ? NULL : run_column_data(r, "strain_radial");
	const double *ev = cs->bts ? NULL : run_column_data(r, "strain_volumetric");
	const double *pc = run_column_data(r, "pressure");
	double pmax = 0;
	fputs("$curve << EOD\n", f);
	for (size_t k = 0; k < r->nrows; k++) {
		curve_row(f, ea, sa, er, ev, k);
		if (pc)
			pmax = fmax(pmax, pc[k]);
	}
	fprintf(f, "EOD\nhas_radial = %d\nhas_volumetric = %d\npc = %.6g\nbts = %d\n", er != NULL,
	        er || ev, 1e-6 * pmax, cs->tensile != NULL);
}

/* $exp rows as $curve, has_exp and exp_label; of a Brazilian test, the
 * axial strain and the stress only. */
static void experiment_data(FILE *f, const experiment *e, const char *label, const curve_stress *cs)
{
	fputs("$exp << EOD\n", f);
	for (size_t k = 0; e && k < e->n; k++)
		curve_row(f, e->col[EXP_STRAIN_AXIAL], e->col[EXP_STRESS_AXIAL],
		          cs->bts ? NULL : e->col[EXP_STRAIN_RADIAL],
		          cs->bts ? NULL : e->col[EXP_STRAIN_VOLUMETRIC], k);
	fprintf(f, "EOD\nhas_exp = %d\nexp_label = ", e != NULL);
	plot_quote(f, label);
	fputc('\n', f);
}

/* $energy rows: eps_a(%) and each energy_* column (J); nenergy, ename[k]. */
static int energy_data(FILE *f, const dem_run *r)
{
	const double *ea = run_column_data(r, "strain_axial");
	int idx[64], n = 0;
	for (int c = 0; c < r->ncols && n < 64; c++)
		if (strncmp(r->col_name[c], "energy_", 7) == 0)
			idx[n++] = c;
	if (!n)
		return 0;
	fputs("$energy << EOD\n", f);
	for (size_t k = 0; k < r->nrows; k++) {
		plot_num(f, 100 * ea[k]);
		for (int c = 0; c < n; c++) {
			fputc(' ', f);
			plot_num(f, r->col[idx[c]][k]);
		}
		fputc('\n', f);
	}
	fprintf(f, "EOD\nnenergy = %d\narray ename[%d]\n", n, n);
	for (int c = 0; c < n; c++) {
		fprintf(f, "ename[%d] = ", c + 1);
		plot_quote(f, r->col_name[idx[c]] + 7);
		fputc('\n', f);
	}
	return n;
}

static void draw(const char *dir, const char *name, const char *script, plot_data *d)
{
	char *fig = plot_file(dir, name);
	if (plot_draw(d, script, fig, 900, 650))
		fatal(NULL);
	printf("wrote %s\n", fig);
	free(fig);
}

static void plot_curves(const char *dir, const char *path, const dem_run *r, const experiment *e,
                        const char *label, const curve_stress *cs)
{
	const char *scripts[] = {"stress_strain", "volumetric"};
	for (int p = 0; p < 2; p++) {
		if (p == 1 && cs->bts) {
			printf(
			    "%s: a Brazilian test: volumetric.png not drawn (a disc loaded "
			    "across a diameter has no radial or volumetric strain to speak of)\n",
			    path);
			continue;
		}
		if (p == 1 && !run_column_data(r, "strain_radial") &&
		    !run_column_data(r, "strain_volumetric")) {
			printf(
			    "%s: no radial or volumetric strain in the history: volumetric.png not "
			    "drawn\n",
			    path);
			continue;
		}
		plot_data d;
		plot_begin(&d);
		curve_data(d.f, path, r, cs);
		experiment_data(d.f, e, label, cs);
		draw(dir, scripts[p], scripts[p], &d);
	}
	plot_data d;
	plot_begin(&d);
	crackmap_count_data(d.f, r);
	const double *ea = run_column_data(r, "strain_axial");
	fputs("$stress << EOD\n", d.f);
	for (size_t k = 0; k < r->nrows; k++)
		fprintf(d.f, "%.10g %.10g\n", 100 * ea[k], 1e-6 * cs->stress[k]);
	fprintf(d.f, "EOD\nwith_stress = 1\nbts = %d\n", cs->tensile != NULL);
	draw(dir, "bonds", "cracks_count", &d);
	plot_begin(&d);
	if (energy_data(d.f, r)) {
		draw(dir, "energy", "energy", &d);
	} else {
		plot_discard(&d);
		printf("%s: no energy_* columns in the history: energy.png not drawn\n", path);
	}
}

int post_curve(int argc, char **argv)
{
	const char *out = NULL, *exp_path = NULL, *exp_label = "experiment", *format = "png";
	int no_png = 0;
	const cli_opt opts[] = {
	    {"out", CLI_STR, &out, "DIR", "", "output directory (default: that of the run)", 0, 0},
	    {"experiment", CLI_STR, &exp_path, "FILE", "",
	     "CSV of experimental points to overlay (share/doc/post.md)", 0, 0},
	    {"experiment-label", CLI_STR, &exp_label, "TEXT", "", "legend of those points", 0, 0},
	    {"no-png", CLI_FLAG, &no_png, NULL, "", "write the CSV only", 0, 0},
	    {"format", CLI_STR, &format, "png|pdf|svg", "",
	     "figure format (each figure's gnuplot script is left beside it as NAME.gp)", 0, 0},
	};
	const char *file =
	    post_one_file("post curve [options] RUN.h5",
	                  "The history of a run: curve.csv (every history column) and figures:\n"
	                  "stress_strain.png (axial stress against axial and radial strain),\n"
	                  "volumetric.png, bonds.png (broken bonds by mode against axial strain)\n"
	                  "and energy.png, with experimental points overlaid if given. A\n"
	                  "Brazilian test (test bts) adds stress_tensile = 2P/(pi D t) to the\n"
	                  "CSV and draws it in place of the axial stress.",
	                  opts, (int)(sizeof opts / sizeof opts[0]), argc, argv);
	if (plot_set_format(format))
		fatal(NULL);
	dem_run r;
	load_run("curve", file, &r);
	if (r.nrows == 0)
		fatal("%s: the history table is empty (the run stopped before its first row)",
		      file);
	required(file, &r, "strain_axial");
	required(file, &r, "stress_axial");
	experiment e, *ep = NULL;
	if (exp_path) {
		if (experiment_read(exp_path, &e))
			fatal(NULL);
		ep = &e;
	}
	curve_stress cs;
	stress_of(&cs, file, &r);
	char *dir = out_dir(out, file);
	char *csv = out_path(dir, "curve.csv");
	write_csv(csv, &r, &cs);
	printf("wrote %s (%zu rows, %d columns)\n", csv, r.nrows, r.ncols + (cs.tensile != NULL));
	if (!no_png)
		plot_curves(dir, file, &r, ep, exp_label, &cs);
	if (ep)
		experiment_free(ep);
	free(cs.tensile);
	free(csv), free(dir);
	run_free(&r);
	return 0;
}
