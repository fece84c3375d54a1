/* post study: the points a study file makes (their names and files; a
 * file is rewritten only when its content changes), the table of their
 * results against hand-made summary.json files (means and sample standard
 * deviations over the seeds, a failed and a missing point marked, the
 * figures drawn, a Brazilian test's strength), and bad study files: one message naming the file,
 * the key, the value and what was expected, exit status 1, and the points already written left as
 * they were. */
#include <math.h>
#include <sys/stat.h>

#include "lib/cfg.h"
#include "tests/harness.h"

static char study_path[1024], out[1024], share[1024];

static void write_text(const char *path, const char *text)
{
	FILE *f = fopen(path, "w");
	fputs(text, f);
	fclose(f);
}

/* A study of the JCFPM concrete case on a small packed cylinder, with the
 * vary block given. */
static void write_study(const char *vary)
{
	char text[4096];
	snprintf(text, sizeof text,
	         "{\"title\": \"test\", \"case\": \"%s/cases/jcfpm-concrete-ucs.json\",\n"
	         " \"specimen\": {\"shape\": \"cylinder\", \"diameter\": 0.012, \"height\": "
	         "0.024, \"dist\": \"fuzz\", \"radius\": 0.001, \"fuzz\": 0},\n"
	         " \"set\": {\"case.stop.strain_axial\": 0.004},\n %s}\n",
	         share, vary);
	write_text(study_path, text);
}

static harness_result plan(const char *extra)
{
	return harness_run("post", "study %s --out %s %s", extra, out, study_path);
}

static char *point_path(const char *point, const char *file)
{
	static char p[2048];
	snprintf(p, sizeof p, "%s/%s/%s", out, point, file);
	return p;
}

/* A file of the study's directory. */
static char *study_file(const char *file)
{
	static char p[2048];
	snprintf(p, sizeof p, "%s/%s", out, file);
	return p;
}

static ino_t inode(const char *path)
{
	struct stat st;
	return stat(path, &st) == 0 ? st.st_ino : 0;
}

static double json_number(const char *path, const char *key)
{
	cfg *c = cfg_load(path);
	double v = NAN;
	if (c && cfg_number(c, key, &v, "", -INFINITY, INFINITY))
		v = NAN;
	cfg_free(c);
	return v;
}

static const char *const SEEDED = "\"vary\": [{\"key\": \"material.interaction_range\", "
                                  "\"values\": [1.2, 1.4]}], \"seeds\": [1, 2]";

static void test_points(void)
{
	write_study(SEEDED);
	harness_result r = plan("");
	CHECK(r.status == 0);
	CHECK_CONTAINS(r.out, "4 points");
	harness_free(&r);
	static const char *const names[] = {
	    "interaction_range-1.2_seed-1", "interaction_range-1.2_seed-2",
	    "interaction_range-1.4_seed-1", "interaction_range-1.4_seed-2"};
	char *mk = harness_slurp(study_file("points.mk"));
	CHECK_CONTAINS(mk, "STUDY_POINTS := interaction_range-1.2_seed-1 "
	                   "interaction_range-1.2_seed-2 interaction_range-1.4_seed-1 "
	                   "interaction_range-1.4_seed-2\n");
	free(mk);
	CHECK_NEAR(json_number(point_path(names[3], "material.json"), "interaction_range"), 1.4, 0);
	CHECK_NEAR(json_number(point_path(names[3], "material.json"), "cohesion"), 9e6, 0);
	CHECK_NEAR(json_number(point_path(names[3], "specimen.json"), "seed"), 2, 0);
	CHECK_NEAR(json_number(point_path(names[2], "specimen.json"), "seed"), 1, 0);
	char *kase = harness_slurp(point_path(names[0], "case.json"));
	CHECK_CONTAINS(kase, "\"material\":\t\"material.json\"");
	CHECK_CONTAINS(kase, "\"strain_axial\":\t0.004");
	free(kase);
	CHECK(!harness_exists(point_path(names[0], "yade.args")));

	/* Again, and with one value changed: only what changed is written. */
	ino_t before[4][3];
	static const char *const files[] = {"material.json", "case.json", "specimen.json"};
	for (int k = 0; k < 4; k++)
		for (int f = 0; f < 3; f++)
			before[k][f] = inode(point_path(names[k], files[f]));
	r = plan("");
	CHECK_CONTAINS(r.out, "(0 new or changed)");
	harness_free(&r);
	for (int k = 0; k < 4; k++)
		for (int f = 0; f < 3; f++)
			CHECK(inode(point_path(names[k], files[f])) == before[k][f]);
	write_study("\"vary\": [{\"key\": \"material.interaction_range\", \"values\": [1.2, "
	            "1.5]}], \"seeds\": [1, 2]");
	r = plan("");
	CHECK_CONTAINS(r.out, "(2 new or changed)");
	harness_free(&r);
	for (int f = 0; f < 3; f++)
		CHECK(inode(point_path(names[0], files[f])) == before[0][f]);
	CHECK(harness_exists(point_path("interaction_range-1.5_seed-2", "material.json")));

	/* Yade's packing: the options of tools/yade-pack, and pack imports. */
	char text[2048];
	snprintf(text, sizeof text,
	         "{\"case\": \"%s/cases/jcfpm-concrete-ucs.json\", \"specimen\": "
	         "{\"arrangement\": \"yade\", \"diameter\": 0.05, \"height\": 0.1, \"radius\": "
	         "0.00125, \"seed\": 3}, \"vary\": [{\"key\": \"specimen.fuzz\", \"values\": [0.2, "
	         "0.4]}]}",
	         share);
	write_text(study_path, text);
	r = plan("");
	CHECK(r.status == 0);
	harness_free(&r);
	char *args = harness_slurp(point_path("fuzz-0.4", "yade.args"));
	CHECK_STR(args, "--diameter 0.05 --height 0.1 --radius 0.00125 --fuzz 0.4 --seed 3\n");
	free(args);
	char *sp = harness_slurp(point_path("fuzz-0.4", "specimen.json"));
	CHECK_CONTAINS(sp, "\"import\":\t\"spheres.txt\"");
	free(sp);
	mk = harness_slurp(study_file("points.mk"));
	CHECK_CONTAINS(mk, "/fuzz-0.4/assembly.h5: ");
	free(mk);
}

/* A summary.json of the keys the table reads: a compression test's, with
 * bts > 0 a Brazilian test's (no modulus, that strength), with bts < 0
 * one with neither. */
static void write_summary_of(const char *point, double peak, double strain, double broken,
                             double bts)
{
	char text[1024], e[32] = "1e10", t[32] = "null";
	if (bts != 0)
		snprintf(e, sizeof e, "null");
	if (bts > 0)
		snprintf(t, sizeof t, "%.10g", bts);
	snprintf(text, sizeof text,
	         "{\"peak_stress\": %.10g, \"strain_at_peak\": %.10g, \"young_modulus\": %s, "
	         "\"poisson_ratio\": null, \"bonds\": 1000, \"bonds_broken_tension\": %.10g, "
	         "\"bonds_broken_shear\": 5, \"spheres\": 300, \"solid_fraction\": 0.5, "
	         "\"wall_time\": 2, \"bts_strength\": %s}\n",
	         peak, strain, e, broken, t);
	write_text(point_path(point, "summary.json"), text);
}

static void write_summary(const char *point, double peak, double strain, double broken)
{
	write_summary_of(point, peak, strain, broken, 0);
}

/* The field of a CSV text in the row whose first field is row, under
 * column; NULL when absent (a static copy). */
static const char *csv_field(const char *text, const char *row, const char *column)
{
	static char field[256];
	const char *end = strchr(text, '\n');
	int col = -1, c = 0;
	for (const char *p = text; p && p < end; c++) {
		size_t n = strcspn(p, ",\n");
		if (n == strlen(column) && !strncmp(p, column, n))
			col = c;
		p = p[n] == ',' ? p + n + 1 : NULL;
	}
	size_t rl = strlen(row);
	for (const char *line = end + 1; col >= 0 && *line; line = strchr(line, '\n') + 1) {
		if (strncmp(line, row, rl) || line[rl] != ',')
			continue;
		const char *p = line;
		for (int k = 0; k < col; k++)
			p = strchr(p, ',') + 1;
		size_t n = strcspn(p, ",\n");
		snprintf(field, sizeof field, "%.*s", (int)n, p);
		return field;
	}
	return NULL;
}

static double csv_number(const char *text, const char *row, const char *column)
{
	const char *f = csv_field(text, row, column);
	return f && *f ? strtod(f, NULL) : NAN;
}

static void test_table(void)
{
	write_study(SEEDED);
	harness_result r = plan("");
	harness_free(&r);
	/* before any point has run: the table, and a warning saying so */
	r = plan("--table --no-png");
	CHECK(r.status == 0);
	CHECK_CONTAINS(r.out, "4 runs, 4 without results");
	CHECK_CONTAINS(r.err, "post study: warning: no run of ");
	CHECK_CONTAINS(r.err, " has results in ");
	harness_free(&r);
	write_summary("interaction_range-1.2_seed-1", 10e6, 0.002, 100);
	write_summary("interaction_range-1.2_seed-2", 12e6, 0.003, 110);
	write_summary("interaction_range-1.4_seed-1", 14e6, 0.0025, 120);
	write_text(point_path("interaction_range-1.4_seed-2", "stage.failed"), "solve\n");
	r = plan("--table --no-png");
	CHECK(r.status == 0);
	CHECK_CONTAINS(r.out, "4 runs, 1 without results");
	CHECK(!strstr(r.err, "warning"));
	harness_free(&r);
	char *study = harness_slurp(study_file("study.csv"));
	char *runs = harness_slurp(study_file("runs.csv"));
	printf("%s\n%s", study, runs);
	CHECK_NEAR(csv_number(study, "1.2", "runs"), 2, 0);
	CHECK_NEAR(csv_number(study, "1.2", "failed"), 0, 0);
	CHECK_REL(csv_number(study, "1.2", "peak_stress_Pa"), 11e6, 1e-9);
	CHECK_REL(csv_number(study, "1.2", "peak_stress_Pa_sd"), sqrt(2.0) * 1e6, 1e-9);
	CHECK_REL(csv_number(study, "1.2", "strain_at_peak"), 0.0025, 1e-9);
	CHECK_REL(csv_number(study, "1.2", "bonds_broken"), 110, 1e-9);
	CHECK_NEAR(csv_number(study, "1.4", "failed"), 1, 0);
	CHECK_REL(csv_number(study, "1.4", "peak_stress_Pa"), 14e6, 1e-9);
	CHECK(isnan(csv_number(study, "1.4", "peak_stress_Pa_sd")));
	CHECK(isnan(csv_number(study, "1.4", "poisson_ratio")));
	CHECK_STR(csv_field(runs, "interaction_range-1.4_seed-2", "status"), "failed");
	CHECK_STR(csv_field(runs, "interaction_range-1.4_seed-2", "failed_stage"), "solve");
	CHECK_STR(csv_field(runs, "interaction_range-1.4_seed-1", "status"), "ok");
	CHECK_NEAR(csv_number(runs, "interaction_range-1.4_seed-1", "seed"), 1, 0);
	CHECK_REL(csv_number(runs, "interaction_range-1.4_seed-1", "bonds_broken"), 125, 1e-12);
	CHECK_REL(csv_number(runs, "interaction_range-1.4_seed-1", "interaction_range"), 1.4, 0);
	free(study);
	free(runs);

	/* The figures, with a curve for one run; a point never run is missing. */
	unlink(point_path("interaction_range-1.4_seed-2", "stage.failed"));
	write_text(point_path("interaction_range-1.2_seed-1", "curve.csv"),
	           "t,strain_axial,stress_axial\n0,0,0\n1,0.001,5e6\n2,0.002,10e6\n");
	r = plan("--table");
	CHECK(r.status == 0);
	harness_free(&r);
	runs = harness_slurp(study_file("runs.csv"));
	CHECK_STR(csv_field(runs, "interaction_range-1.4_seed-2", "status"), "missing");
	free(runs);
	static const char png[] = "\x89PNG";
	for (int k = 0; k < 2; k++) {
		char *fig = harness_slurp(study_file(k ? "curves.png" : "response.png"));
		CHECK(!strncmp(fig, png, 4));
		free(fig);
	}

	/* A Brazilian test's results: its strength in the table and the
	 * figure, which draws without a modulus. */
	unlink(study_file("response.png"));
	write_summary_of("interaction_range-1.2_seed-1", 4e6, 0.02, 100, 2.5e6);
	write_summary_of("interaction_range-1.2_seed-2", 4e6, 0.02, 100, 2.7e6);
	write_summary_of("interaction_range-1.4_seed-1", 5e6, 0.02, 100, 3.1e6);
	r = plan("--table");
	CHECK(r.status == 0);
	harness_free(&r);
	study = harness_slurp(study_file("study.csv"));
	CHECK_REL(csv_number(study, "1.2", "bts_strength_Pa"), 2.6e6, 1e-9);
	CHECK(isnan(csv_number(study, "1.2", "young_modulus_Pa")));
	free(study);
	char *fig = harness_slurp(study_file("response.png"));
	CHECK(fig && !strncmp(fig, png, 4));
	free(fig);
	/* Its curves are the splitting tensile stress (curve.csv's
	 * stress_tensile), so labelled. */
	write_text(point_path("interaction_range-1.2_seed-1", "curve.csv"),
	           "t,strain_axial,stress_axial,stress_tensile\n0,0,0,0\n1,0.001,5e6,2.2e6\n"
	           "2,0.002,10e6,4.4e6\n");
	r = plan("--table");
	CHECK(r.status == 0);
	harness_free(&r);
	char *script = harness_slurp(study_file("curves.gp"));
	CHECK(script && strstr(script, "\ntensile = 1\n") && strstr(script, "\n0.2 4.4\n"));
	free(script);
	/* No modulus at all: that panel is drawn empty. */
	unlink(study_file("response.png"));
	for (int k = 0; k < 3; k++)
		write_summary_of(
		    k < 2 ? (k ? "interaction_range-1.2_seed-2" : "interaction_range-1.2_seed-1")
		          : "interaction_range-1.4_seed-1",
		    4e6, 0.02, 100, -1);
	r = plan("--table");
	CHECK(r.status == 0);
	harness_free(&r);
	fig = harness_slurp(study_file("response.png"));
	CHECK(fig && !strncmp(fig, png, 4));
	free(fig);
}

static void test_errors(void)
{
	write_study(SEEDED);
	harness_result r = plan("");
	harness_free(&r);
	ino_t kept = inode(point_path("interaction_range-1.2_seed-1", "material.json"));
	static const struct {
		const char *vary, *message;
	} bad[] = {
	    {"\"vary\": [{\"key\": \"interaction_range\", \"values\": [1.2]}]",
	     "key 'vary[0].key': value \"interaction_range\": expected material.<key>, "
	     "case.<key> or specimen.<key>"},
	    {"\"vary\": [{\"key\": \"material.interaction_range\", \"values\": [1.2, 3]}]",
	     "point interaction_range-3: case: key 'material.interaction_range': value 3: "
	     "expected a number in [1, 2]"},
	    {"\"vary\": [{\"key\": \"material.interaction_rang\", \"values\": [1.2]}]",
	     "key 'material.interaction_rang': unknown key"},
	    {"\"vary\": [{\"key\": \"material.interaction_range\", \"values\": [1.2, 1.2000001]}]",
	     "key 'vary[0].values': values 1.2 and 1.2000001 would both be point "
	     "'interaction_range-1.2': expected values distinct"},
	    {"\"vary\": [{\"key\": \"specimen.fuzz\", \"values\": [0.2, 1.5]}]",
	     "point fuzz-1.5: specimen: key 'fuzz': value 1.5: expected a number in [0, 0.99]"},
	    {"\"vary\": [{\"key\": \"specimen.arrangement\", \"values\": [\"hexagonal\"]}]",
	     "key 'arrangement': value \"hexagonal\": expected random or hcp (pack's) or yade"},
	    {"\"vary\": [{\"key\": \"specimen.seed\", \"values\": [1, 2]}], \"seeds\": [3]",
	     "key 'vary[0].key': value \"specimen.seed\": the study's \"seeds\" set it"},
	    {"\"vary\": [{\"key\": \"material.E\", \"range\": {\"from\": 1e9, \"to\": 2e9, "
	     "\"step\": -1e8}}]",
	     "key 'vary[0].range.step': value -1e+08: expected a step from 1e+09 towards 2e+09"},
	    {"\"vary\": [{\"key\": \"case.dampin.translational\", \"values\": [0.1]}]",
	     "point translational-0.1: case: key 'dampin': unknown key"},
	    {"\"vary\": [{\"key\": \"material.E\", \"values\": [1e9]}], \"extra\": 1",
	     "key 'extra': unknown key"},
	    {"\"vary\": [{\"key\": \"material.E\", \"values\": [1e9, 1e400]}]",
	     "key 'vary[0].values': value null (or a number beyond the range of a double): "
	     "expected a number"},
	    {"\"vary\": [{\"key\": \"material.E\", \"range\": {\"from\": 1, \"to\": 1e300, "
	     "\"step\": 1e-10}}]",
	     "key 'vary[0].range.step': value 1e-10: 1.8e+308 values from 1 to 1e+300: "
	     "expected at most 64"},
	};
	for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
		write_study(bad[k].vary);
		r = plan("");
		printf("%s", r.err);
		CHECK(r.status == 1);
		CHECK_CONTAINS(r.err, study_path);
		CHECK_CONTAINS(r.err, bad[k].message);
		CHECK(strchr(r.err, '\n') == r.err + strlen(r.err) - 1);
		harness_free(&r);
	}
	CHECK(inode(point_path("interaction_range-1.2_seed-1", "material.json")) == kept);
}

int main(void)
{
	snprintf(study_path, sizeof study_path, "%s", check_tmp("study_test.json"));
	snprintf(out, sizeof out, "%s", check_tmp("study_test"));
	if (!getcwd(share, sizeof share - 8))
		return 1;
	strcat(share, "/share");
	char rm[1200];
	snprintf(rm, sizeof rm, "rm -rf %s", out);
	if (system(rm))
		return 1;
	test_points();
	test_table();
	test_errors();
	return check_done();
}
