/* post ratios: the micro-macro compressive stress ratios of one or several
 * runs at a chosen instant (post/ratios.h for the definitions), as
 * ratios.csv and two figures: ratios.png (r against theta, one line per
 * run, as Fig. 11 of Onate et al. 2015) and ratios_groups.png (intact and
 * damaged contacts apart, and the shear stress). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "post/frame.h"
#include "post/instant.h"
#include "post/load.h"
#include "post/output.h"
#include "post/plot.h"
#include "post/post.h"
#include "post/ratios.h"
#include "post/summary.h"

enum { MAX_RUNS = 32 };

typedef struct {
	const char *path;
	char *label;
	size_t snap;
	int64_t step;
	double t, strain, stress; /* at the snapshot used */
	double sigma_ref;         /* Pa, the denominator of r */
	int plateau;              /* the "peak" is where a strain stop ended a rising curve */
	long ncontacts;
	ratio_stat *stat; /* [RATIO_NGROUPS][nbins] */
} run_ratios;

/* Split "a,b,c" into exactly n labels. */
static void split_labels(const char *list, char **labels, int n)
{
	char *copy = xstrdup(list), *save = NULL;
	int k = 0;
	for (char *tok = strtok_r(copy, ",", &save); tok; tok = strtok_r(NULL, ",", &save), k++)
		if (k < n)
			labels[k] = xstrdup(tok);
	free(copy);
	if (k != n)
		fatal("--labels %s: %d labels for %d run files (one per run, comma-separated)",
		      list, k, n);
}

/* A run file given twice would be counted twice: refused, whether by
 * the same name or by two names of one file (a link, ./run.h5). Files
 * that cannot be read are left to load_run's message. */
static void distinct_runs(char **pos, int n)
{
	struct stat st[MAX_RUNS];
	int ok[MAX_RUNS];
	for (int q = 0; q < n; q++)
		ok[q] = stat(pos[q], &st[q]) == 0;
	for (int q = 1; q < n; q++)
		for (int p = 0; p < q; p++) {
			if (strcmp(pos[p], pos[q]) == 0)
				fatal(
				    "%s: given twice (run files %d and %d): expected each run once "
				    "(it would be counted twice)",
				    pos[q], p + 1, q + 1);
			if (ok[p] && ok[q] && st[p].st_dev == st[q].st_dev &&
			    st[p].st_ino == st[q].st_ino)
				fatal(
				    "%s: the same file as %s (run files %d and %d): expected each "
				    "run once (it would be counted twice)",
				    pos[q], pos[p], p + 1, q + 1);
		}
}

static void compute_run(run_ratios *rr, const instant *in, const ratio_bins *bins, double sigma_ref)
{
	dem_run r;
	load_run("ratios", rr->path, &r);
	char desc[1024];
	if (instant_pick(rr->path, &r, in, &rr->snap, desc, sizeof desc))
		fatal(NULL);
	if (r.bonds.n == 0)
		fatal("%s: the run has no bonds (/bonds is missing or empty)", rr->path);
	printf("%s\n", desc);
	if (in->kind == AT_PEAK && summary_no_peak(&r)) {
		rr->plateau = 1;
		warn("%s: the axial stress has no peak before the run ended (%s): the instant is "
		     "the strain stop's plateau, not a limit stress",
		     rr->path, r.status);
	}
	dem_snapshot s;
	load_snapshot(rr->path, &r, rr->snap, &s);
	frame f;
	frame_of(&f, &r.assembly.geom);
	rr->step = s.step;
	rr->t = s.t;
	rr->strain = s.strain_axial;
	rr->stress = s.stress_axial;
	rr->sigma_ref = sigma_ref > 0 ? sigma_ref : s.stress_axial;
	rr->stat = xmalloc((size_t)(RATIO_NGROUPS * bins->n) * sizeof *rr->stat);
	rr->ncontacts = ratios_compute(&r.bonds, &s, &f, bins, rr->stat);
	if (rr->ncontacts < 0) {
		err_wrap("%s: snapshot %zu", rr->path, rr->snap);
		fatal(NULL);
	}
	if (!(rr->sigma_ref > 0)) {
		warn("%s: the axial stress at snapshot %zu is %g Pa, not positive: r is left empty "
		     "(give --sigma-ref)",
		     rr->path, rr->snap, rr->stress);
		rr->sigma_ref = NAN;
	}
	snapshot_free(&s);
	run_free(&r);
}

/* One line per run on stdout: how many contacts and the range of r. */
static void summarise(const run_ratios *rr, const ratio_bins *bins)
{
	const ratio_stat *all = rr->stat + RATIO_ALL * bins->n;
	double lo = INFINITY, hi = -INFINITY, sum = 0;
	for (int k = 0; k < bins->n; k++) {
		if (!all[k].count)
			continue;
		lo = fmin(lo, all[k].sn_mean / rr->sigma_ref);
		hi = fmax(hi, all[k].sn_mean / rr->sigma_ref);
		sum += all[k].sn_mean * (double)all[k].count;
	}
	if (rr->ncontacts == 0) {
		printf("%s: no bonded contact in compression at snapshot %zu\n", rr->label,
		       rr->snap);
		return;
	}
	printf("%s: %ld bonded contacts in compression; sigma_ref = %.4g MPa; r from %.3f to %.3f "
	       "over the bins, %.3f over all contacts\n",
	       rr->label, rr->ncontacts, 1e-6 * rr->sigma_ref, lo, hi,
	       sum / (double)rr->ncontacts / rr->sigma_ref);
}

static void write_csv(const char *path, const run_ratios *runs, int nruns, const ratio_bins *bins)
{
	out_text o;
	out_text_open(&o, path);
	fputs("run,snapshot,step,t_s,strain_axial,stress_axial_Pa,sigma_ref_Pa,group,"
	      "theta_min_deg,theta_max_deg,count,sigma_n_mean_Pa,sigma_n_std_Pa,r,r_std,"
	      "tau_mean_Pa,tau_std_Pa\n",
	      o.f);
	for (int q = 0; q < nruns; q++) {
		const run_ratios *rr = &runs[q];
		for (int g = 0; g < RATIO_NGROUPS; g++)
			for (int k = 0; k < bins->n; k++) {
				const ratio_stat *st = &rr->stat[g * bins->n + k];
				out_csv_str(o.f, rr->label);
				fprintf(o.f, ",%zu,%lld,%.10g,%.10g,%.10g,", rr->snap,
				        (long long)rr->step, rr->t, rr->strain, rr->stress);
				out_csv_num(o.f, rr->sigma_ref);
				fprintf(o.f, ",%s,%.10g,%.10g,%zu", ratio_group_name[g],
				        bins->edges[k], bins->edges[k + 1], st->count);
				double v[] = {st->sn_mean,
				              st->sn_std,
				              st->sn_mean / rr->sigma_ref,
				              st->sn_std / rr->sigma_ref,
				              st->tau_mean,
				              st->tau_std};
				for (size_t c = 0; c < sizeof v / sizeof v[0]; c++) {
					fputc(',', o.f);
					out_csv_num(o.f, v[c]);
				}
				fputc('\n', o.f);
			}
	}
	out_text_commit(&o);
}

/* Datablock $<group>: one index per run, rows theta_mid r r_std tau/ref
 * tau_std/ref count (NaN in empty bins, which gnuplot leaves out). */
static void data_group(FILE *f, int g, const run_ratios *runs, int nruns, const ratio_bins *bins,
                       long min_count)
{
	fprintf(f, "$%s << EOD\n", ratio_group_name[g]);
	for (int q = 0; q < nruns; q++) {
		if (q)
			fputs("\n\n", f);
		for (int k = 0; k < bins->n; k++) {
			const ratio_stat *st = &runs[q].stat[g * bins->n + k];
			/* Too few contacts to mean anything: not drawn. */
			double ref = (long)st->count >= min_count ? runs[q].sigma_ref : NAN;
			double v[] = {0.5 * (bins->edges[k] + bins->edges[k + 1]),
			              st->sn_mean / ref,
			              st->sn_std / ref,
			              st->tau_mean / ref,
			              st->tau_std / ref,
			              (double)st->count};
			for (size_t c = 0; c < sizeof v / sizeof v[0]; c++) {
				plot_num(f, v[c]);
				fputc(c + 1 < sizeof v / sizeof v[0] ? ' ' : '\n', f);
			}
		}
	}
	fputs("EOD\n", f);
}

/* sigma_given: the reference is --sigma-ref, one value for every run. */
static void plot(const char *dir, const run_ratios *runs, int nruns, const ratio_bins *bins,
                 long min_count, int sigma_given)
{
	const char *scripts[] = {"ratios", "ratios_groups"};
	for (int p = 0; p < 2; p++) {
		plot_data d;
		plot_begin(&d);
		for (int g = 0; g < RATIO_NGROUPS; g++)
			data_group(d.f, g, runs, nruns, bins, min_count);
		size_t ndamaged = 0; /* in the bins drawn */
		for (int q = 0; q < nruns; q++)
			for (int k = 0; k < bins->n; k++) {
				size_t c = runs[q].stat[RATIO_DAMAGED * bins->n + k].count;
				ndamaged += (long)c >= min_count ? c : 0;
			}
		/* The legend sits below the plot, a row per run and one for the
		 * band of the paper (ratios.png) or two for the line styles of
		 * intact and damaged contacts (ratios_groups.png, when there are
		 * damaged ones): the figure grows by its rows. */
		int key_rows = nruns + (p == 0 ? 1 : ndamaged > 0 ? 2 : 0);
		int height = 600 + 21 * key_rows;
		fprintf(d.f,
		        "nruns = %d\nndamaged = %zu\nmin_count = %ld\nkey_rows = %d\ncanvas_h = "
		        "%d\narray label[%d]\n",
		        nruns, ndamaged, min_count, key_rows, height, nruns);
		for (int q = 0; q < nruns; q++) {
			char text[512];
			/* The instant too: where on its curve each run was taken. */
			snprintf(
			    text, sizeof text,
			    "%s at ε_{a} = %.3g %%, σ_{a} = %.3g MPa (σ@_a^{ref} = %.3g MPa, %s%s)",
			    runs[q].label, 100 * runs[q].strain, 1e-6 * runs[q].stress,
			    1e-6 * runs[q].sigma_ref, sigma_given ? "common" : "own",
			    runs[q].plateau ? "; no peak: strain stop" : "");
			fprintf(d.f, "label[%d] = ", q + 1);
			plot_quote(d.f, text);
			fputc('\n', d.f);
		}
		char *fig = plot_file(dir, scripts[p]);
		if (plot_draw(&d, scripts[p], fig, p == 0 ? 900 : 1400, height))
			fatal(NULL);
		printf("wrote %s\n", fig);
		free(fig);
	}
}

int post_ratios(int argc, char **argv)
{
	const char *out = NULL, *at_snap = NULL, *at_time = NULL, *at_strain = NULL;
	const char *at_stress = NULL, *labels = NULL;
	double width = 10, sigma_ref = 0;
	int solid = 0, no_png = 0;
	long min_count = 20;
	const char *format = "png";
	const cli_opt opts[] = {
	    {"out", CLI_STR, &out, "DIR", "", "output directory (default: that of the first run)",
	     0, 0},
	    {"snapshot", CLI_STR, &at_snap, "K", "",
	     "at snapshot K (0 first, -1 last); with none of --snapshot, --time, --strain, "
	     "--stress: at the peak axial stress",
	     0, 0},
	    {"time", CLI_STR, &at_time, "T", "s", "at the snapshot nearest to time T", 0, 0},
	    {"strain", CLI_STR, &at_strain, "E", "",
	     "where the axial strain first reaches E, a fraction (0.005 is 0.5 %; compression "
	     "positive)",
	     0, 0},
	    {"stress", CLI_STR, &at_stress, "S", "Pa",
	     "where the axial stress first reaches S, e.g. the limit stress", 0, 0},
	    {"bin-width", CLI_NUM, &width, "DEG", "deg", "width of the angle bins", 0.1, 90},
	    {"equal-solid-angle", CLI_FLAG, &solid, NULL, "",
	     "bins of equal solid angle instead (as many as --bin-width gives)", 0, 0},
	    {"sigma-ref", CLI_NUM, &sigma_ref, "S", "Pa",
	     "reference stress of r; 0: each run's axial stress at the instant", 0, 1e15},
	    {"labels", CLI_STR, &labels, "LIST", "", "comma-separated run names for legends", 0, 0},
	    {"min-contacts", CLI_INT, &min_count, "N", "",
	     "figures: bins with fewer contacts are not drawn (the CSV has them all, with counts)",
	     1, 1e9},
	    {"no-png", CLI_FLAG, &no_png, NULL, "", "write the CSV only", 0, 0},
	    {"format", CLI_STR, &format, "png|pdf|svg", "",
	     "figure format (each figure's gnuplot script is left beside it as NAME.gp)", 0, 0},
	};
	const cli_spec spec = {
	    .usage = "post ratios [options] RUN.h5 [RUN.h5 ...]",
	    .summary =
	        "Micro-macro compressive stress ratios by contact orientation (Onate et al.\n"
	        "2015, sec. 9, Fig. 11): for every bonded contact in compression at one\n"
	        "instant (default: the peak axial stress), sigma_n = F_nc / A grouped by\n"
	        "the angle theta between the contact normal and the plane normal to the\n"
	        "loading axis; per bin the count, mean and standard deviation of sigma_n\n"
	        "and of the shear stress, r = mean sigma_n / sigma_ref, for all, intact\n"
	        "and damaged contacts. Several runs share one figure.\n"
	        "Writes ratios.csv, ratios.png, ratios_groups.png.",
	    .epilog = "Example: post ratios --stress 41e6 --labels UCS,5MPa ucs/run.h5 tx5/run.h5",
	    .opts = opts,
	    .nopts = sizeof opts / sizeof opts[0],
	    .min_pos = 1,
	    .max_pos = MAX_RUNS,
	};
	char *pos[MAX_RUNS];
	int nruns = cli_parse(&spec, argc, argv, pos);
	if (plot_set_format(format))
		fatal(NULL);
	instant in;
	if (instant_parse(&in, at_snap, at_time, at_strain, at_stress))
		cli_usage_error(&spec, "%s", err_msg());
	ratio_bins bins;
	if (solid)
		ratio_bins_solid_angle(&bins, (int)ceil(90.0 / width - 1e-9));
	else
		ratio_bins_width(&bins, width);
	distinct_runs(pos, nruns);
	run_ratios runs[MAX_RUNS] = {0};
	char *names[MAX_RUNS] = {0};
	if (labels)
		split_labels(labels, names, nruns);
	for (int q = 0; q < nruns; q++) {
		runs[q].path = pos[q];
		runs[q].label = names[q] ? names[q] : post_run_label(pos[q]);
		compute_run(&runs[q], &in, &bins, sigma_ref);
	}
	char *dir = out_dir(out, pos[0]);
	char *csv = out_path(dir, "ratios.csv");
	write_csv(csv, runs, nruns, &bins);
	printf("wrote %s\n", csv);
	for (int q = 0; q < nruns; q++)
		summarise(&runs[q], &bins);
	if (!no_png && nruns > 1) {
		/* Several runs: the footer names them all (one run: its caption). */
		char *text = NULL;
		size_t n = 0;
		FILE *f = open_memstream(&text, &n);
		if (!f)
			fatal("out of memory");
		fprintf(f, "%d runs:", nruns);
		for (int q = 0; q < nruns; q++)
			fprintf(f, "%s %s", q ? "," : "", runs[q].path);
		fclose(f);
		plot_set_footer(text);
		free(text);
	}
	/* A run whose every bin has fewer contacts than --min-contacts would
	 * have nothing drawn: draw all bins then, and say so. */
	for (int q = 0; q < nruns && !no_png; q++) {
		int drawn = 0;
		for (int k = 0; k < bins.n; k++)
			drawn |= (long)runs[q].stat[RATIO_ALL * bins.n + k].count >= min_count;
		if (!drawn && runs[q].ncontacts > 0) {
			warn("%s: no bin has %ld contacts (--min-contacts): the figures draw every "
			     "bin",
			     runs[q].label, min_count);
			min_count = 1;
		}
	}
	if (!no_png)
		plot(dir, runs, nruns, &bins, min_count, sigma_ref > 0);
	for (int q = 0; q < nruns; q++) {
		free(runs[q].label);
		free(runs[q].stat);
	}
	free(csv);
	free(dir);
	ratio_bins_free(&bins);
	return 0;
}
