/* post summary: summary.json, the figures a laboratory test is judged by
 * (post/summary.h), with the run's test, material and sizes, and a warning
 * when the loading was too fast to be quasi-static. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/cfg.h"
#include "lib/cli.h"
#include "lib/err.h"
#include "post/load.h"
#include "post/output.h"
#include "post/post.h"
#include "post/summary.h"

static void json_str(FILE *f, const char *s)
{
	fputc('"', f);
	for (; *s; s++) {
		if (*s == '"' || *s == '\\')
			fprintf(f, "\\%c", *s);
		else if ((unsigned char)*s < 0x20)
			fprintf(f, "\\u%04x", (unsigned char)*s);
		else
			fputc(*s, f);
	}
	fputc('"', f);
}

static void json_num(FILE *f, const char *key, double v, int last)
{
	fprintf(f, "  \"%s\": ", key);
	if (isfinite(v))
		fprintf(f, "%.12g", v);
	else
		fputs("null", f);
	fputs(last ? "\n" : ",\n", f);
}

static void json_text(FILE *f, const char *key, const char *v)
{
	fprintf(f, "  \"%s\": ", key);
	json_str(f, v);
	fputs(",\n", f);
}

/* The test and material named in the run's configuration ("" when absent). */
typedef struct {
	char test[64], material[256], law[64];
} run_names;

static void copy(char *dst, size_t n, const char *src) { snprintf(dst, n, "%s", src ? src : ""); }

static run_names names_of(const dem_run *r)
{
	run_names nm = {"", "", ""};
	cfg *c = cfg_parse(r->prov.config ? r->prov.config : "{}", "run configuration");
	if (!c)
		return nm;
	const char *s = NULL;
	if (cfg_string_or(c, "test", &s, "") == 0)
		copy(nm.test, sizeof nm.test, s);
	cfg *m = cfg_has(c, "material") ? cfg_object_opt(c, "material") : NULL;
	if (m && cfg_string_or(m, "name", &s, "") == 0)
		copy(nm.material, sizeof nm.material, s);
	if (m && cfg_string_or(m, "law", &s, "") == 0)
		copy(nm.law, sizeof nm.law, s);
	cfg_free(c);
	err_clear();
	return nm;
}

static summary_kind kind_of(const char *test)
{
	if (strcmp(test, "bts") == 0)
		return TEST_BTS;
	if (strcmp(test, "hydrostatic") == 0)
		return TEST_HYDROSTATIC;
	return TEST_COMPRESSION;
}

static void write_json(const char *path, const char *label, const dem_run *r, const run_names *nm,
                       const summary *s, const char *warning)
{
	out_text o;
	out_text_open(&o, path);
	FILE *f = o.f;
	fputs("{\n", f);
	json_text(f, "case", label);
	json_text(f, "test", nm->test);
	json_text(f, "material", nm->material);
	json_text(f, "law", nm->law);
	json_text(f, "status", r->status ? r->status : "");
	json_num(f, "spheres", (double)r->assembly.n, 0);
	json_num(f, "bonds", (double)r->bonds.n, 0);
	json_num(f, "peak_stress", s->peak_stress, 0);
	json_num(f, "strain_at_peak", s->strain_at_peak, 0);
	json_num(f, "peak_deviator", s->peak_deviator, 0);
	json_num(f, "strain_at_peak_deviator", s->strain_at_peak_deviator, 0);
	json_num(f, "confining_pressure", s->pressure_at_peak, 0);
	json_num(f, "young_modulus", s->young_modulus, 0);
	json_num(f, "poisson_ratio", s->poisson_ratio, 0);
	json_num(f, "peak_force", s->peak_force, 0);
	json_num(f, "bts_strength", s->bts_strength, 0);
	json_num(f, "bulk_modulus", s->bulk_modulus, 0);
	json_num(f, "residual_stress", s->residual_stress, 0);
	json_num(f, "residual_deviator", s->residual_deviator, 0);
	json_num(f, "pressure_final", s->pressure_final, 0);
	json_num(f, "strain_axial_final", s->strain_axial_final, 0);
	json_num(f, "strain_volumetric_final", s->strain_volumetric_final, 0);
	json_num(f, "bonds_intact", s->bonds_intact, 0);
	json_num(f, "bonds_damaged", s->bonds_damaged, 0);
	json_num(f, "bonds_broken_tension", s->bonds_broken_tension, 0);
	json_num(f, "bonds_broken_shear", s->bonds_broken_shear, 0);
	json_num(f, "steps", s->steps, 0);
	json_num(f, "time", s->time, 0);
	json_num(f, "wall_time", s->wall_time, 0);
	json_num(f, "particle_steps_per_second",
	         s->wall_time > 0 ? (double)r->assembly.n * s->steps / s->wall_time : NAN, 0);
	json_num(f, "kinetic_elastic_ratio", s->ke_ratio_max, 0);
	fprintf(f, "  \"quasi_static\": %s,\n",
	        isnan(s->ke_ratio_max)                    ? "null"
	        : s->ke_ratio_max <= SUMMARY_KE_RATIO_MAX ? "true"
	                                                  : "false");
	fputs("  \"warning\": ", f);
	if (warning)
		json_str(f, warning);
	else
		fputs("null", f);
	fputs("\n}\n", f);
	out_text_commit(&o);
}

int post_summary(int argc, char **argv)
{
	const char *out = NULL;
	const cli_opt opts[] = {
	    {"out", CLI_STR, &out, "DIR", "", "output directory (default: that of the run)", 0, 0},
	};
	const char *file =
	    post_one_file("post summary [options] RUN.h5",
	                  "summary.json: the test, material, spheres and bonds, peak stress and\n"
	                  "strain, Young's modulus (tangent at 50 % of the peak) and Poisson's\n"
	                  "ratio, the Brazilian strength, the residual stress, bonds broken by\n"
	                  "mode, wall time and particle-steps per second, and the kinetic/elastic\n"
	                  "energy ratio on the loading branch (a warning when it is too high).",
	                  opts, (int)(sizeof opts / sizeof opts[0]), argc, argv);
	dem_run r;
	load_run("summary", file, &r);
	run_names nm = names_of(&r);
	summary s;
	if (summary_compute(&r, kind_of(nm.test), r.assembly.geom.diameter, r.assembly.geom.height,
	                    &s))
		fatal("%s: %s", file, err_msg());
	char warning[256], *label = post_run_label(file);
	int slow = s.ke_ratio_max > SUMMARY_KE_RATIO_MAX;
	if (slow) {
		snprintf(warning, sizeof warning,
		         "kinetic/elastic energy ratio %.3g on the loading branch (above %g): the "
		         "loading is too fast to be quasi-static",
		         s.ke_ratio_max, SUMMARY_KE_RATIO_MAX);
		fprintf(stderr, "%s: warning: %s: %s\n", err_program_name(), file, warning);
	}
	char *dir = out_dir(out, file);
	char *path = out_path(dir, "summary.json");
	write_json(path, label, &r, &nm, &s, slow ? warning : NULL);
	printf("wrote %s\n", path);
	free(path), free(dir), free(label);
	run_free(&r);
	return 0;
}
