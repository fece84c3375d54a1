#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/path.h"
#include "lib/vec3.h"
#include "solve/case.h"

static const char *const axial_words[] = {"none",   "hold",  "velocity", "strain_rate",
                                          "stress", "force", "layers",   NULL};
static const char *const lateral_words[] = {"free", "pressure", "constraint", NULL};
static const char *const method_words[] = {"tributary", "paper", NULL};
static const char *const move_words[] = {"both", "top", NULL};
static const char *const damping_words[] = {"vector", "components", NULL};

static int parse_stop(cfg *c, stop_rule *s, int with_stress)
{
	*s = (stop_rule){.strain_axial = NAN, .stress_axial = NAN, .stress_drop = NAN, .time = NAN};
	if (!c)
		return 0;
	if (cfg_has(c, "strain_axial") &&
	    cfg_number(c, "strain_axial", &s->strain_axial, "", -1, 1))
		return -1;
	if (with_stress && cfg_has(c, "stress_axial") &&
	    cfg_number(c, "stress_axial", &s->stress_axial, "Pa", -INFINITY, INFINITY))
		return -1;
	if (cfg_has(c, "stress_drop") && cfg_number(c, "stress_drop", &s->stress_drop, "", 0, 1))
		return -1;
	if (cfg_has(c, "time") && cfg_number(c, "time", &s->time, "s", CFG_POS, INFINITY))
		return -1;
	return cfg_integer_or(c, "steps", &s->steps, 0, 1, 1L << 62);
}

static int stop_empty(const stop_rule *s)
{
	return isnan(s->strain_axial) && isnan(s->stress_axial) && isnan(s->stress_drop) &&
	       isnan(s->time) && s->steps == 0;
}

static int parse_axial(cfg *a, stage *s)
{
	int move = 0;
	if (cfg_choice_or(a, "mode", &s->axial, axial_words, AXIAL_NONE))
		return -1;
	switch (s->axial) {
	case AXIAL_VELOCITY:
		if (cfg_number(a, "velocity", &s->velocity, "m/s", -INFINITY, INFINITY))
			return -1;
		break;
	case AXIAL_STRAIN_RATE:
		if (cfg_number(a, "rate", &s->rate, "1/s", -INFINITY, INFINITY))
			return -1;
		break;
	case AXIAL_STRESS:
	case AXIAL_FORCE:
		if (cfg_number(a, s->axial == AXIAL_STRESS ? "stress" : "force", &s->target,
		               s->axial == AXIAL_STRESS ? "Pa" : "N", 0, INFINITY) ||
		    cfg_number_or(a, "rate", &s->rate, 1.0, "1/s", CFG_POS, INFINITY))
			return -1;
		break;
	case AXIAL_LAYERS:
		if (cfg_number(a, "rate", &s->rate, "1/s", -INFINITY, INFINITY) ||
		    cfg_number_or(a, "thickness", &s->thickness, 0, "m", CFG_POS, INFINITY))
			return -1;
		break;
	}
	if (s->axial != AXIAL_NONE && s->axial != AXIAL_HOLD &&
	    cfg_choice_or(a, "move", &move, move_words, 0))
		return -1;
	s->top_only = move == 1;
	return 0;
}

static int parse_lateral(cfg *l, stage *s)
{
	if (cfg_choice_or(l, "mode", &s->lateral, lateral_words, LATERAL_FREE))
		return -1;
	if (s->lateral == LATERAL_PRESSURE &&
	    (cfg_number(l, "pressure", &s->pressure, "Pa", 0, INFINITY) ||
	     cfg_choice_or(l, "method", &s->method, method_words, PRESSURE_PAPER)))
		return -1;
	return 0;
}

static int parse_stage(cfg *c, stage *s)
{
	memset(s, 0, sizeof *s);
	cfg *a = cfg_object_opt(c, "axial");
	if (!a && err_msg()[0])
		return -1;
	cfg *l = cfg_object_opt(c, "lateral");
	if (!l && err_msg()[0])
		return -1;
	cfg *u = cfg_object_opt(c, "until");
	if (!u && err_msg()[0])
		return -1;
	const char *name;
	if (cfg_string_or(c, "name", &name, "") ||
	    cfg_number_or(c, "ramp", &s->ramp, 0, "s", 0, INFINITY))
		return -1;
	snprintf(s->name, sizeof s->name, "%s", name);
	if (a && parse_axial(a, s))
		return -1;
	if (l && parse_lateral(l, s))
		return -1;
	return parse_stop(u, &s->until, 1);
}

static int parse_output(cfg *c, dem_case *k)
{
	cfg *o = cfg_object_opt(c, "output");
	if (!o && err_msg()[0])
		return -1;
	k->history_every = 100;
	k->checkpoint_wall = 600;
	if (!o)
		return 0;
	if (cfg_integer_or(o, "history_every", &k->history_every, 100, 1, 1L << 40) ||
	    cfg_integer_or(o, "snapshot_every", &k->snapshot_every, 0, 0, 1L << 40) ||
	    cfg_number_or(o, "snapshot_every_strain", &k->snapshot_every_strain, 0, "", 0, 1) ||
	    cfg_integer_or(o, "checkpoint_every", &k->checkpoint_every, 0, 0, 1L << 40) ||
	    cfg_number_or(o, "checkpoint_wall", &k->checkpoint_wall, 600, "s", 0, INFINITY))
		return -1;
	if (cfg_has(o, "snapshot_strains") &&
	    cfg_numbers(o, "snapshot_strains", &k->snapshot_strains, &k->nsnapshot_strains, 0, "",
	                -1, 1))
		return -1;
	return 0;
}

/* An optional object's optional number. */
static int sub_number(cfg *c, const char *obj, const char *key, double *out, double def,
                      const char *unit, double lo, double hi)
{
	cfg *o = cfg_object_opt(c, obj);
	if (!o && err_msg()[0])
		return -1;
	*out = def;
	return o ? cfg_number_or(o, key, out, def, unit, lo, hi) : 0;
}

static int parse_numerics(cfg *c, dem_case *k)
{
	double every;
	if (sub_number(c, "time_step", "safety", &k->safety, 0.8, "", CFG_POS, 1) ||
	    sub_number(c, "time_step", "dt", &k->dt, 0, "s", CFG_POS, INFINITY) ||
	    sub_number(c, "damping", "translational", &k->alpha_t, 0.1, "", 0, 1) ||
	    sub_number(c, "damping", "rotational", &k->alpha_r, 0.1, "", 0, 1) ||
	    sub_number(c, "neighbours", "skin", &k->skin, 0, "m", CFG_POS, INFINITY) ||
	    sub_number(c, "servo", "gain", &k->servo_gain, 0.05, "", CFG_POS, 1) ||
	    sub_number(c, "surface", "update_every", &every, 100, "steps", 1, 1e12) ||
	    sub_number(c, "surface", "bin", &k->surface_bin, 0, "m", CFG_POS, INFINITY))
		return -1;
	if (every != floor(every))
		return cfg_error(c, "surface.update_every",
		                 "value %g: expected a whole number of steps", every);
	k->surface_every = (long)every;
	cfg *d = cfg_object_opt(c, "damping");
	if (!d && err_msg()[0])
		return -1;
	k->damping_form = DAMPING_VECTOR;
	if (d && cfg_choice_or(d, "form", &k->damping_form, damping_words, DAMPING_VECTOR))
		return -1;
	long threads;
	if (cfg_integer_or(c, "threads", &threads, 0, 0, 1024))
		return -1;
	k->threads = (int)threads;
	if (cfg_has(c, "axis")) {
		double *a;
		if (cfg_numbers(c, "axis", &a, NULL, 3, "", -INFINITY, INFINITY))
			return -1;
		memcpy(k->axis, a, sizeof k->axis);
		free(a);
		double unit[3];
		if (v3_unit(unit, k->axis))
			return cfg_error(c, "axis",
			                 "value [%g, %g, %g]: expected a non-zero direction",
			                 k->axis[0], k->axis[1], k->axis[2]);
	}
	return 0;
}

static int parse_loading(cfg *c, dem_case *k)
{
	long n = cfg_list(c, "loading");
	if (n <= 0)
		return cfg_error(c, "loading", "%s: expected a non-empty array of stage objects",
		                 n < 0 ? "not an array of objects" : "missing");
	k->nstages = (int)n;
	k->stages = xcalloc((size_t)n, sizeof *k->stages);
	for (long s = 0; s < n; s++) {
		cfg *item = cfg_item(c, "loading", (size_t)s);
		if (parse_stage(item, &k->stages[s]))
			return -1;
		if (s + 1 < n && stop_empty(&k->stages[s].until))
			return cfg_error(c, "loading",
			                 "stage %ld: no condition in 'until': every stage but the "
			                 "last needs a condition that ends it",
			                 s + 1);
	}
	cfg *st = cfg_object_opt(c, "stop");
	if (!st && err_msg()[0])
		return -1;
	if (parse_stop(st, &k->stop, 0))
		return -1;
	if (stop_empty(&k->stop) && stop_empty(&k->stages[n - 1].until))
		return cfg_error(
		    c, "stop",
		    st ? "no rule: expected strain_axial, stress_drop, time or steps (a "
		         "stress to reach is a stage's 'until' rule)"
		       : "missing: the run never ends (give 'stop' or an 'until' "
		         "in the last stage)");
	return 0;
}

/* Everything but the material and the assembly. */
static int parse_body(cfg *c, dem_case *k)
{
	const char *test;
	if (cfg_string_or(c, "test", &test, "custom"))
		return -1;
	k->test = xstrdup(test);
	return parse_numerics(c, k) || parse_output(c, k) || parse_loading(c, k);
}

/* The material: a file name (relative to the case) or an inline object.
 * Sets *json to the material object as JSON text. */
static int parse_material(cfg *c, const char *source, dem_case *k, char **json)
{
	cfg *m = cfg_object_opt(c, "material");
	if (m) {
		*json = cfg_text(m);
		return material_parse(m, &k->mat);
	}
	if (!cfg_has(c, "material"))
		return cfg_error(c, "material",
		                 "missing: expected a material file name or an object");
	err_clear();
	const char *name;
	if (cfg_string_or(c, "material", &name, NULL) || !name || !name[0])
		return cfg_error(c, "material", "expected a material file name or an object");
	k->material_file = path_beside(source, name);
	cfg *mf = cfg_load(k->material_file);
	if (!mf)
		return cfg_error(c, "material", "%s", err_msg());
	int rc = material_parse(mf, &k->mat) || cfg_check_unused(mf);
	if (!rc)
		*json = cfg_text(mf);
	cfg_free(mf);
	return rc;
}

/* The case text with the material object in place of its file name and the
 * assembly path as used. */
static char *resolved_config(const char *text, const char *material_json, const char *assembly)
{
	cJSON *root = cJSON_Parse(text);
	cJSON *mat = cJSON_Parse(material_json);
	cJSON_ReplaceItemInObjectCaseSensitive(root, "material", mat);
	if (assembly) {
		cJSON *a = cJSON_CreateString(assembly);
		if (cJSON_GetObjectItemCaseSensitive(root, "assembly"))
			cJSON_ReplaceItemInObjectCaseSensitive(root, "assembly", a);
		else
			cJSON_AddItemToObject(root, "assembly", a);
	}
	char *out = cJSON_Print(root);
	cJSON_Delete(root);
	char *copy = xstrdup(out);
	free(out);
	return copy;
}

static int load(cfg *c, const char *source, const char *assembly, dem_case *k)
{
	char *mjson = NULL;
	const char *apath = NULL;
	int rc = parse_material(c, source, k, &mjson);
	if (!rc && !assembly)
		rc = cfg_string(c, "assembly", &apath);
	else if (!rc && cfg_has(c, "assembly"))
		rc = cfg_string(c, "assembly", &apath);
	if (!rc && apath && !apath[0])
		rc = cfg_error(c, "assembly", "empty: expected the assembly file's name");
	rc = rc || parse_body(c, k) || cfg_check_unused(c);
	if (!rc) {
		k->assembly = assembly ? xstrdup(assembly) : path_beside(source, apath);
		char *text = cfg_text(c);
		k->config = resolved_config(text, mjson, k->assembly);
		free(text);
	}
	free(mjson);
	return rc;
}

double case_checkpoint_interval(const dem_case *c, int done)
{
	double w = c->checkpoint_wall, first = w / 10 < 60 ? w / 10 : 60;
	for (int k = 0; k < done && first < w; k++)
		first *= 2;
	return first < w ? first : w;
}

int case_load(const char *path, const char *assembly, dem_case *k)
{
	memset(k, 0, sizeof *k);
	cfg *c = cfg_load(path);
	if (!c)
		return -1;
	k->source = xstrdup(path);
	int rc = load(c, path, assembly, k);
	cfg_free(c);
	if (rc)
		case_free(k);
	return rc;
}

int case_parse_text(const char *text, const char *source, dem_case *k)
{
	memset(k, 0, sizeof *k);
	cfg *c = cfg_parse(text, source);
	if (!c)
		return -1;
	k->source = xstrdup(source);
	int rc = load(c, "./", NULL, k);
	cfg_free(c);
	if (rc)
		case_free(k);
	return rc;
}

void case_free(dem_case *k)
{
	material_free(&k->mat);
	free(k->source), free(k->material_file), free(k->assembly), free(k->config), free(k->test);
	free(k->snapshot_strains), free(k->stages);
	memset(k, 0, sizeof *k);
}
