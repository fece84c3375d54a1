/* The results of a study's points in one table: runs.csv (a row per run),
 * study.csv (a row per point of the parameters: mean and standard
 * deviation over the packing seeds), response.png (the response against
 * the parameter) and curves.png (every stress-strain curve). A point
 * without summary.json is marked: failed, with the stage that failed,
 * when its stage.failed names one (workflows/study.mk), else missing (not
 * run yet, or interrupted). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lib/cfg.h"
#include "lib/err.h"
#include "post/output.h"
#include "post/plot.h"
#include "post/study.h"
#include "post/study_table.h"

/* The figures of summary.json in the table, with their columns' names. */
enum { NQ = 10 };
static const struct {
	const char *column; /* in the CSV files */
	const char *key[2]; /* summed from summary.json */
} quantities[NQ] = {
    {"peak_stress_Pa", {"peak_stress"}},
    {"strain_at_peak", {"strain_at_peak"}},
    {"young_modulus_Pa", {"young_modulus"}},
    {"poisson_ratio", {"poisson_ratio"}},
    {"bonds", {"bonds"}},
    {"bonds_broken", {"bonds_broken_tension", "bonds_broken_shear"}},
    {"spheres", {"spheres"}},
    {"solid_fraction", {"solid_fraction"}},
    {"wall_time_s", {"wall_time"}},
    {"bts_strength_Pa", {"bts_strength"}},
};

typedef enum { RUN_OK, RUN_FAILED, RUN_MISSING } run_status;
static const char *const status_word[] = {"ok", "failed", "missing"};

typedef struct {
	run_status status;
	char stage[32]; /* the stage that failed */
	double q[NQ];
} run_result;

static char *point_file(const char *dir, const study_point *pt, const char *name)
{
	size_t n = strlen(dir) + strlen(pt->name) + strlen(name) + 3;
	char *p = xmalloc(n);
	snprintf(p, n, "%s/%s/%s", dir, pt->name, name);
	return p;
}

/* A number of summary.json; NaN when null or absent. */
static double number(const cJSON *j, const char *key)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(j, key);
	return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

static int read_result(const char *dir, const study_point *pt, run_result *r)
{
	char *path = point_file(dir, pt, "summary.json");
	for (int q = 0; q < NQ; q++)
		r->q[q] = NAN;
	r->status = RUN_MISSING;
	if (access(path, F_OK) == 0) {
		cJSON *j = cfg_load_json(path);
		if (!j) {
			free(path);
			return -1;
		}
		for (int q = 0; q < NQ; q++) {
			r->q[q] = number(j, quantities[q].key[0]);
			if (quantities[q].key[1])
				r->q[q] += number(j, quantities[q].key[1]);
		}
		cJSON_Delete(j);
		r->status = RUN_OK;
	} else {
		char *failed = point_file(dir, pt, "stage.failed");
		FILE *f = fopen(failed, "r");
		if (f) {
			r->status = RUN_FAILED;
			if (!fgets(r->stage, sizeof r->stage, f))
				r->stage[0] = '\0';
			r->stage[strcspn(r->stage, "\r\n")] = '\0';
			fclose(f);
		}
		free(failed);
	}
	free(path);
	return 0;
}

/* The packing seed of point k: the study's, the varied one, or the
 * specimen's (pack's and tools/yade-pack's default is 1). */
static double point_seed(const study *s, int k)
{
	const study_point *pt = &s->point[k];
	if (pt->seed >= 0)
		return (double)pt->seed;
	for (int i = 0; i < s->np; i++)
		if (s->p[i].where == IN_SPECIMEN && !strcmp(s->p[i].path, "seed"))
			return s->p[i].value[pt->v[i]]->valuedouble;
	const cJSON *seed = cJSON_GetObjectItemCaseSensitive(s->specimen, "seed");
	return cJSON_IsNumber(seed) ? seed->valuedouble : 1;
}

static void value_field(FILE *f, const cJSON *v, const char *text)
{
	if (cJSON_IsNumber(v))
		out_csv_num(f, v->valuedouble);
	else
		out_csv_str(f, text);
}

static void write_runs(const study *s, const run_result *res, const char *dir)
{
	char *path = out_path(dir, "runs.csv");
	out_text o;
	out_text_open(&o, path);
	fputs("point", o.f);
	for (int i = 0; i < s->np; i++)
		fprintf(o.f, ",%s", s->p[i].name);
	fputs(",seed,status,failed_stage", o.f);
	for (int q = 0; q < NQ; q++)
		fprintf(o.f, ",%s", quantities[q].column);
	fputc('\n', o.f);
	for (int k = 0; k < s->npoints; k++) {
		const study_point *pt = &s->point[k];
		out_csv_str(o.f, pt->name);
		for (int i = 0; i < s->np; i++) {
			fputc(',', o.f);
			value_field(o.f, s->p[i].value[pt->v[i]], s->p[i].text[pt->v[i]]);
		}
		fprintf(o.f, ",%.0f,%s,", point_seed(s, k), status_word[res[k].status]);
		out_csv_str(o.f, res[k].stage);
		for (int q = 0; q < NQ; q++) {
			fputc(',', o.f);
			out_csv_num(o.f, res[k].q[q]);
		}
		fputc('\n', o.f);
	}
	out_text_commit(&o);
	free(path);
}

/* The runs of one point of the parameters (every seed): how many, how many
 * failed or are missing, and the mean and sample standard deviation of
 * each quantity over the runs that have it (sd NaN for fewer than two). */
typedef struct {
	int v[STUDY_MAX_PARAMS];
	int runs, failed;
	double mean[NQ], sd[NQ];
} group;

static int group_count(const study *s) { return s->p[0].n * (s->np > 1 ? s->p[1].n : 1); }

static void make_groups(const study *s, const run_result *res, group *g)
{
	int ng = group_count(s);
	for (int k = 0; k < ng; k++) {
		memset(&g[k], 0, sizeof g[k]);
		g[k].v[0] = s->np > 1 ? k / s->p[1].n : k;
		g[k].v[1] = s->np > 1 ? k % s->p[1].n : 0;
		for (int q = 0; q < NQ; q++) {
			double sum = 0, sum2 = 0;
			int n = 0;
			for (int j = 0; j < s->npoints; j++) {
				const study_point *pt = &s->point[j];
				if (pt->v[0] != g[k].v[0] || (s->np > 1 && pt->v[1] != g[k].v[1]))
					continue;
				if (q == 0) {
					g[k].runs++;
					g[k].failed += res[j].status != RUN_OK;
				}
				if (res[j].status != RUN_OK || !isfinite(res[j].q[q]))
					continue;
				sum += res[j].q[q];
				n++;
			}
			g[k].mean[q] = n ? sum / n : NAN;
			for (int j = 0; j < s->npoints; j++) {
				const study_point *pt = &s->point[j];
				if (pt->v[0] == g[k].v[0] &&
				    (s->np == 1 || pt->v[1] == g[k].v[1]) &&
				    res[j].status == RUN_OK && isfinite(res[j].q[q]))
					sum2 += (res[j].q[q] - g[k].mean[q]) *
					        (res[j].q[q] - g[k].mean[q]);
			}
			g[k].sd[q] = n > 1 ? sqrt(sum2 / (n - 1)) : NAN;
		}
	}
}

static void write_study(const study *s, const group *g, const char *dir)
{
	char *path = out_path(dir, "study.csv");
	out_text o;
	out_text_open(&o, path);
	for (int i = 0; i < s->np; i++)
		fprintf(o.f, "%s,", s->p[i].name);
	fputs("runs,failed", o.f);
	for (int q = 0; q < NQ; q++)
		fprintf(o.f, ",%s,%s_sd", quantities[q].column, quantities[q].column);
	fputc('\n', o.f);
	for (int k = 0; k < group_count(s); k++) {
		for (int i = 0; i < s->np; i++) {
			value_field(o.f, s->p[i].value[g[k].v[i]], s->p[i].text[g[k].v[i]]);
			fputc(',', o.f);
		}
		fprintf(o.f, "%d,%d", g[k].runs, g[k].failed);
		for (int q = 0; q < NQ; q++) {
			fputc(',', o.f);
			out_csv_num(o.f, g[k].mean[q]);
			fputc(',', o.f);
			out_csv_num(o.f, g[k].sd[q]);
		}
		fputc('\n', o.f);
	}
	out_text_commit(&o);
	free(path);
}

/* The panels of the response figure: quantity, factor to its unit, axis
 * label. A Brazilian test's show its strength and the broken bonds where
 * a compression test's show the peak stress and Young's modulus. */
typedef struct {
	int q;
	double factor;
	const char *label;
} panel;
static const panel compression_panels[4] = {{0, 1e-6, "peak stress (MPa)"},
                                            {1, 100, "strain at peak (%)"},
                                            {2, 1e-9, "Young's modulus (GPa)"},
                                            {7, 100, "solid fraction (%)"}};
static const panel bts_panels[4] = {{9, 1e-6, "Brazilian tensile strength (MPa)"},
                                    {1, 100, "strain at peak (%)"},
                                    {5, 1, "bonds broken"},
                                    {7, 100, "solid fraction (%)"}};

static double x_of(const study_param *p, int v)
{
	return p->numeric ? p->value[v]->valuedouble * p->scale : v;
}

/* "label = value" of value v of p, as the figures show it (the value
 * times the scale), appended to t (of size n). */
static void value_title(const study_param *p, int v, char *t, size_t n)
{
	size_t len = strlen(t);
	if (p->numeric)
		snprintf(t + len, n - len, "%s = %g", p->label, x_of(p, v));
	else
		snprintf(t + len, n - len, "%s = %s", p->label, p->text[v]);
}

static int draw_response(const study *s, const group *g, const char *dir)
{
	const study_param *p = &s->p[0];
	int ng = s->np > 1 ? s->p[1].n : 1, has_sd = s->nseeds > 1;
	const panel *panels = compression_panels;
	for (int k = 0; k < group_count(s); k++)
		if (isfinite(g[k].mean[9]))
			panels = bts_panels;
	plot_data d;
	plot_begin(&d);
	fputs("$study << EOD\n", d.f);
	for (int j = 0; j < ng; j++) {
		for (int k = 0; k < group_count(s); k++) {
			if (g[k].v[1] != j)
				continue;
			plot_num(d.f, x_of(p, g[k].v[0]));
			for (int c = 0; c < 4; c++) {
				double f = panels[c].factor, sd = g[k].sd[panels[c].q];
				fputc(' ', d.f);
				plot_num(d.f, f * g[k].mean[panels[c].q]);
				fputc(' ', d.f);
				plot_num(d.f, isfinite(sd) ? f * sd : 0);
			}
			fputc('\n', d.f);
		}
		fputs(j + 1 < ng ? "\n\n" : "", d.f);
	}
	fprintf(d.f, "EOD\nngroups = %d\nhas_sd = %d\narray group_title[%d]\n", ng, has_sd, ng);
	/* A panel whose values are all one gets a range about it (gnuplot
	 * would warn of an empty one); one without any is drawn empty. */
	fputs("array flat[4]\narray empty[4]\narray ylabel_text[4]\n", d.f);
	double xlo = INFINITY, xhi = -INFINITY;
	for (int c = 0; c < 4; c++) {
		double lo = INFINITY, hi = -INFINITY;
		for (int k = 0; k < group_count(s); k++) {
			double v = panels[c].factor * g[k].mean[panels[c].q],
			       x = x_of(p, g[k].v[0]);
			xlo = fmin(xlo, x), xhi = fmax(xhi, x);
			if (isfinite(v))
				lo = fmin(lo, v), hi = fmax(hi, v);
		}
		fprintf(d.f, "flat[%d] = ", c + 1);
		plot_num(d.f, lo == hi ? lo : NAN);
		fprintf(d.f, "\nempty[%d] = %d\nylabel_text[%d] = ", c + 1, lo > hi, c + 1);
		plot_quote(d.f, panels[c].label);
		fputc('\n', d.f);
	}
	fputs("xmin = ", d.f);
	plot_num(d.f, xlo < xhi ? xlo : xlo - 1);
	fputs("\nxmax = ", d.f);
	plot_num(d.f, xlo < xhi ? xhi : xhi + 1);
	fputc('\n', d.f);
	for (int j = 0; j < ng; j++) {
		char t[200] = "";
		if (s->np > 1)
			value_title(&s->p[1], j, t, sizeof t);
		fprintf(d.f, "group_title[%d] = ", j + 1);
		plot_quote(d.f, t);
		fputc('\n', d.f);
	}
	fputs("title_text = ", d.f);
	plot_quote(d.f, s->title);
	fputs("\nxlabel_text = ", d.f);
	plot_quote(d.f, p->label);
	fprintf(d.f, "\ncategorical = %d\nnx = %d\nxtics_cmd = \"set xtics (", !p->numeric, p->n);
	for (int k = 0; k < p->n; k++)
		fprintf(d.f, "%s'%s' %d", k ? ", " : "", p->text[k], k);
	fputs(")\"\n", d.f);
	char *png = plot_file(dir, "response");
	int rc = plot_draw(&d, "study_response", png, 1200, 900);
	free(png);
	return rc;
}

/* The columns strain_axial and stress_axial (stress_tensile, the
 * splitting tensile stress, for a Brazilian test's: *tensile set) of a
 * run's curve.csv, as ($curves) rows in % and MPa, at most about 1000 of
 * them, after a dataset separator when sep; 0 (and nothing written) when
 * the run has none. */
static int curve_rows(FILE *out, const char *path, int sep, int *tensile)
{
	FILE *f = fopen(path, "r");
	if (!f)
		return 0;
	char *line = NULL;
	size_t cap = 0;
	int ce = -1, cs = -1, ct = -1, n = 0;
	if (getline(&line, &cap, f) > 0) {
		int c = 0;
		for (char *save = NULL, *t = strtok_r(line, ",\n", &save); t;
		     t = strtok_r(NULL, ",\n", &save), c++) {
			ce = strcmp(t, "strain_axial") ? ce : c;
			cs = strcmp(t, "stress_axial") ? cs : c;
			ct = strcmp(t, "stress_tensile") ? ct : c;
		}
	}
	if (ct >= 0) {
		cs = ct;
		*tensile = 1;
	}
	long rows = 0;
	while (ce >= 0 && cs >= 0 && getline(&line, &cap, f) > 0)
		rows++;
	rewind(f);
	long every = rows / 1000 + 1, row = 0;
	if (getline(&line, &cap, f) > 0)
		while (ce >= 0 && cs >= 0 && getline(&line, &cap, f) > 0) {
			if (row++ % every)
				continue;
			if (sep && n == 0)
				fputs("\n\n", out);
			double e = NAN, sg = NAN;
			char *p = line;
			for (int c = 0; p; c++) {
				if (c == ce)
					e = strtod(p, NULL);
				if (c == cs)
					sg = strtod(p, NULL);
				p = strchr(p, ',');
				p = p ? p + 1 : NULL;
			}
			plot_num(out, 100 * e);
			fputc(' ', out);
			plot_num(out, 1e-6 * sg);
			fputc('\n', out);
			n++;
		}
	free(line);
	fclose(f);
	return n > 0;
}

static int draw_curves(const study *s, const char *dir)
{
	plot_data d;
	plot_begin(&d);
	int n = 0, tensile = 0, *lt = xmalloc((size_t)s->npoints * sizeof *lt + 1);
	char **title = xcalloc((size_t)s->npoints + 1, sizeof *title);
	fputs("$curves << EOD\n", d.f);
	for (int k = 0; k < s->npoints; k++) {
		const study_point *pt = &s->point[k];
		char *path = point_file(dir, pt, "curve.csv");
		int found = curve_rows(d.f, path, n > 0, &tensile);
		free(path);
		if (!found)
			continue;
		int combination = s->np > 1 ? pt->v[0] * s->p[1].n + pt->v[1] : pt->v[0];
		lt[n] = combination % 8 + 1;
		/* One key entry per point of the parameters, at its first run. */
		int first = 1;
		for (int j = 0; j < k; j++)
			first &= s->point[j].v[0] != pt->v[0] || s->point[j].v[1] != pt->v[1];
		char t[200] = "";
		if (first)
			for (int i = 0; i < s->np; i++) {
				if (i)
					snprintf(t + strlen(t), sizeof t - strlen(t), ", ");
				value_title(&s->p[i], pt->v[i], t, sizeof t);
			}
		title[n++] = xstrdup(t);
	}
	fprintf(d.f, "EOD\nncurves = %d\narray curve_lt[%d]\narray curve_title[%d]\n", n, n ? n : 1,
	        n ? n : 1);
	for (int k = 0; k < n; k++) {
		fprintf(d.f, "curve_lt[%d] = %d\ncurve_title[%d] = ", k + 1, lt[k], k + 1);
		plot_quote(d.f, title[k]);
		fputc('\n', d.f);
		free(title[k]);
	}
	free(title);
	free(lt);
	fputs("title_text = ", d.f);
	plot_quote(d.f, s->title);
	fprintf(d.f, "\ntensile = %d\n", tensile);
	if (!n) {
		plot_discard(&d);
		return 0;
	}
	char *png = plot_file(dir, "curves");
	int rc = plot_draw(&d, "study_curves", png, 1000, 700);
	free(png);
	return rc;
}

int study_table(const study *s, const char *dir, int figures, int *failed)
{
	run_result *res = xcalloc((size_t)s->npoints, sizeof *res);
	group *g = xcalloc((size_t)group_count(s), sizeof *g);
	int rc = 0;
	*failed = 0;
	for (int k = 0; k < s->npoints && !rc; k++) {
		rc = read_result(dir, &s->point[k], &res[k]);
		*failed += !rc && res[k].status != RUN_OK;
	}
	if (!rc) {
		make_groups(s, res, g);
		write_runs(s, res, dir);
		write_study(s, g, dir);
		plot_set_footer(s->source);
		rc = figures && (draw_response(s, g, dir) || draw_curves(s, dir));
	}
	free(g);
	free(res);
	return rc ? -1 : 0;
}
