/* post summary: summary.json, the figures a laboratory test is judged by
 * (post/summary.h), with the run's test, material and sizes, and a warning
 * when the loading was too fast to be quasi-static. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/cfg.h"
#include "lib/cli.h"
#include "lib/err.h"
#include "lib/json.h"
#include "post/load.h"
#include "post/output.h"
#include "post/post.h"
#include "post/summary.h"

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
	cJSON *j = cJSON_CreateObject();
	json_str(j, "case", label);
	json_str(j, "test", nm->test);
	json_str(j, "material", nm->material);
	json_str(j, "law", nm->law);
	json_str(j, "status", r->status);
	json_num(j, "spheres", (double)r->assembly.n);
	json_num(j, "bonds", (double)r->bonds.n);
	json_num(j, "solid_fraction", r->assembly.report.solid_fraction);
	json_num(j, "peak_stress", s->peak_stress);
	json_num(j, "strain_at_peak", s->strain_at_peak);
	json_num(j, "peak_deviator", s->peak_deviator);
	json_num(j, "strain_at_peak_deviator", s->strain_at_peak_deviator);
	json_num(j, "confining_pressure", s->pressure_at_peak);
	json_num(j, "young_modulus", s->young_modulus);
	json_num(j, "poisson_ratio", s->poisson_ratio);
	json_num(j, "peak_force", s->peak_force);
	json_num(j, "bts_strength", s->bts_strength);
	json_num(j, "bulk_modulus", s->bulk_modulus);
	json_num(j, "residual_stress", s->residual_stress);
	json_num(j, "residual_deviator", s->residual_deviator);
	json_num(j, "pressure_final", s->pressure_final);
	json_num(j, "strain_axial_final", s->strain_axial_final);
	json_num(j, "strain_volumetric_final", s->strain_volumetric_final);
	json_num(j, "bonds_intact", s->bonds_intact);
	json_num(j, "bonds_damaged", s->bonds_damaged);
	json_num(j, "bonds_broken_tension", s->bonds_broken_tension);
	json_num(j, "bonds_broken_shear", s->bonds_broken_shear);
	json_num(j, "steps", s->steps);
	json_num(j, "time", s->time);
	json_num(j, "wall_time", s->wall_time);
	json_num(j, "particle_steps_per_second",
	         s->wall_time > 0 ? (double)r->assembly.n * s->steps / s->wall_time : NAN);
	json_num(j, "kinetic_elastic_ratio", s->ke_ratio_max);
	json_bool(j, "quasi_static", !isnan(s->ke_ratio_max),
	          s->ke_ratio_max <= SUMMARY_KE_RATIO_MAX);
	if (warning)
		json_str(j, "warning", warning);
	else
		cJSON_AddNullToObject(j, "warning");
	if (json_write(path, j))
		fatal(NULL);
}

/* The warning fmt added to the list w (of size n), after a "; " when it
 * holds one already. */
__attribute__((format(printf, 3, 4))) static void add_warning(char *w, size_t n, const char *fmt,
                                                              ...)
{
	size_t len = strlen(w);
	if (len && len + 2 < n)
		strcpy(w + len, "; "), len += 2;
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(w + len, n - len, fmt, ap);
	va_end(ap);
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
	char warning[600] = "", *label = post_run_label(file);
	if (s.ke_ratio_max > SUMMARY_KE_RATIO_MAX)
		add_warning(
		    warning, sizeof warning,
		    "kinetic/elastic energy ratio %.3g on the loading branch (above %g): the "
		    "loading is too fast to be quasi-static",
		    s.ke_ratio_max, SUMMARY_KE_RATIO_MAX);
	if (kind_of(nm.test) != TEST_HYDROSTATIC && summary_no_peak(&r))
		add_warning(
		    warning, sizeof warning,
		    "no peak: the axial-strain stop ended the run with the stress within 1 %% of "
		    "its highest, so the peak and strength figures are the stop's (the specimen "
		    "had not failed: raise stop.strain_axial)");
	if (!summary_finished(&r))
		add_warning(
		    warning, sizeof warning,
		    "the run did not reach its stop rule (status '%s'): the peak and the other "
		    "figures are those of its history so far%s",
		    r.status ? r.status : "none",
		    r.status && !strcmp(r.status, "interrupted") ? " (solve --restart continues it)"
		                                                 : "");
	if (warning[0])
		fprintf(stderr, "%s: warning: %s: %s\n", err_program_name(), file, warning);
	char *dir = out_dir(out, file);
	char *path = out_path(dir, "summary.json");
	write_json(path, label, &r, &nm, &s, warning[0] ? warning : NULL);
	printf("wrote %s\n", path);
	free(path), free(dir), free(label);
	run_free(&r);
	return 0;
}
