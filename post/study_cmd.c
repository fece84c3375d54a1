/* post study: a parametric study's points (share/doc/studies.md). Without
 * --table, it checks the study file and writes, under the output
 * directory, each point's material.json, case.json, specimen.json (and
 * yade.args for Yade's packing), rewriting a file only when its content
 * changes, so that make re-runs exactly the points and stages a change
 * touches; and points.mk, the points for workflows/study.mk. With
 * --table, it collects the points' results (study_table.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "post/output.h"
#include "post/plot.h"
#include "post/post.h"
#include "post/study.h"
#include "post/study_table.h"

/* Write text to path unless the file already holds it; 1 when written. */
static int write_if_changed(const char *path, const char *text)
{
	FILE *f = fopen(path, "rb");
	if (f) {
		size_t n = strlen(text), same = 1;
		char buf[4096];
		size_t got, at = 0;
		while (same && (got = fread(buf, 1, sizeof buf, f)) > 0) {
			same = at + got <= n && memcmp(buf, text + at, got) == 0;
			at += got;
		}
		fclose(f);
		if (same && at == n)
			return 0;
	}
	out_text o;
	out_text_open(&o, path);
	fputs(text, o.f);
	out_text_commit(&o);
	return 1;
}

static int write_json_if_changed(const char *path, const cJSON *j)
{
	char *text = cJSON_Print(j);
	size_t n = strlen(text);
	text = xrealloc(text, n + 2);
	strcpy(text + n, "\n");
	int rc = write_if_changed(path, text);
	free(text);
	return rc;
}

/* Point k's files in dir/<point>/; the number of files changed. */
static int write_point(const study *s, int k, const char *dir)
{
	study_files f;
	if (study_point_files(s, k, &f))
		fatal(NULL);
	char *pdir = out_path(dir, s->point[k].name);
	out_mkdir(pdir);
	static const char *const names[] = {"material.json", "case.json", "specimen.json"};
	const cJSON *json[] = {f.material, f.kase, f.specimen};
	int changed = 0;
	for (int i = 0; i < 3; i++) {
		char *path = out_path(pdir, names[i]);
		changed += write_json_if_changed(path, json[i]);
		free(path);
	}
	char *args = out_path(pdir, "yade.args");
	if (f.yade_args) {
		char line[600];
		snprintf(line, sizeof line, "%s\n", f.yade_args);
		changed += write_if_changed(args, line);
	} else if (unlink(args) == 0) {
		changed++;
	}
	free(args);
	free(pdir);
	study_files_free(&f);
	return changed;
}

/* points.mk: the points, the Yade sphere lists their assemblies import,
 * and the files this one is made from. */
static void write_points_mk(const study *s, const char *dir)
{
	char *path = out_path(dir, "points.mk");
	out_text o;
	out_text_open(&o, path);
	fprintf(o.f,
	        "# The points of the study %s, written by post study\n"
	        "# (share/doc/studies.md, workflows/study.mk): do not edit.\nSTUDY_POINTS :=",
	        s->source);
	for (int k = 0; k < s->npoints; k++)
		fprintf(o.f, " %s", s->point[k].name);
	fputc('\n', o.f);
	for (int k = 0; k < s->npoints; k++) {
		study_files f;
		if (study_point_files(s, k, &f))
			fatal(NULL);
		if (f.yade_args)
			fprintf(o.f, "%s/%s/assembly.h5: %s/%s/spheres.txt\n", dir,
			        s->point[k].name, dir, s->point[k].name);
		study_files_free(&f);
	}
	fprintf(o.f, "%s: %s %s", path, s->source, s->case_file);
	if (s->material_file)
		fprintf(o.f, " %s", s->material_file);
	if (s->specimen_file)
		fprintf(o.f, " %s", s->specimen_file);
	fputc('\n', o.f);
	out_text_commit(&o);
	free(path);
}

int post_study(int argc, char **argv)
{
	const char *out = NULL, *format = "png";
	int table = 0, no_png = 0;
	const cli_opt opts[] = {
	    {"out", CLI_STR, &out, "DIR", "",
	     "the study's directory (default: the study file's name, without .json, here)", 0, 0},
	    {"table", CLI_FLAG, &table, NULL, "",
	     "collect the points' results: runs.csv, study.csv, response.png, curves.png", 0, 0},
	    {"no-png", CLI_FLAG, &no_png, NULL, "", "with --table: write the CSV files only", 0, 0},
	    {"format", CLI_STR, &format, "png|pdf|svg", "", "figure format", 0, 0},
	};
	const char *file = post_one_file(
	    "post study [options] STUDY.json",
	    "A parametric study (share/doc/studies.md): check the study file and write\n"
	    "each point's material, case and specimen files (only those that change) and\n"
	    "points.mk for workflows/study.mk; with --table, collect the points'\n"
	    "summary.json and curve.csv into runs.csv, study.csv and figures.",
	    opts, (int)(sizeof opts / sizeof opts[0]), argc, argv);
	if (plot_set_format(format))
		fatal(NULL);
	study s;
	if (study_load(file, &s))
		fatal(NULL);
	char name[256];
	const char *base = strrchr(file, '/') ? strrchr(file, '/') + 1 : file;
	snprintf(name, sizeof name, "%s", base);
	if (strlen(name) > 5 && !strcmp(name + strlen(name) - 5, ".json"))
		name[strlen(name) - 5] = '\0';
	char *dir = out_dir(out ? out : name, file);
	if (table) {
		int failed;
		if (study_table(&s, dir, !no_png, &failed))
			fatal(NULL);
		printf("post study: %s/study.csv: %d points, %d runs, %d without results%s\n", dir,
		       s.p[0].n * (s.np > 1 ? s.p[1].n : 1), s.npoints, failed,
		       failed ? " (marked failed or missing in runs.csv)" : "");
		if (failed == s.npoints)
			fprintf(
			    stderr,
			    "post study: warning: no run of %s has results in %s: run the study "
			    "first (make -C workflows study STUDY=%s, share/doc/studies.md)\n",
			    file, dir, name);
	} else {
		int changed = 0;
		for (int k = 0; k < s.npoints; k++)
			changed += write_point(&s, k, dir) > 0;
		write_points_mk(&s, dir);
		printf("post study: %d points of %s in %s (%d new or changed)\n", s.npoints, file,
		       dir, changed);
	}
	free(dir);
	study_free(&s);
	return 0;
}
