#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "calibrate/quantity.h"
#include "calibrate/spec.h"
#include "lib/cfg.h"
#include "lib/err.h"
#include "lib/path.h"
#include "solve/case.h"
#include "solve/laws/material.h"

cJSON *spec_material_number(cJSON *m, const char *key)
{
	const char *dot = strchr(key, '.');
	if (dot) {
		char head[64];
		size_t n = (size_t)(dot - key);
		if (n >= sizeof head)
			return NULL;
		memcpy(head, key, n);
		head[n] = '\0';
		cJSON *o = cJSON_GetObjectItemCaseSensitive(m, head);
		return cJSON_IsObject(o) ? spec_material_number(o, dot + 1) : NULL;
	}
	cJSON *v = cJSON_GetObjectItemCaseSensitive(m, key);
	return cJSON_IsNumber(v) ? v : NULL;
}

int spec_check_material(const cJSON *m, const char *what)
{
	char *text = cJSON_PrintUnformatted(m);
	cfg *c = cfg_parse(text, what);
	free(text);
	if (!c)
		return -1;
	material mat;
	int rc = material_parse(c, &mat);
	if (rc == 0) {
		rc = cfg_check_unused(c);
		material_free(&mat);
	}
	cfg_free(c);
	return rc;
}

/* The number keys of a material, for a message: "E0, nu, ..., contact.E". */
static void number_keys(const cJSON *m, const char *prefix, char *buf, size_t n)
{
	for (const cJSON *v = m->child; v; v = v->next) {
		size_t len = strlen(buf);
		if (cJSON_IsNumber(v))
			snprintf(buf + len, n - len, "%s%s%s", len ? ", " : "", prefix, v->string);
		else if (cJSON_IsObject(v) && !prefix[0]) {
			char p[80];
			snprintf(p, sizeof p, "%s.", v->string);
			number_keys(v, p, buf, n);
		}
	}
}

/* A material given as a file name or inline under key; NULL (and no
 * error) when absent and not required. */
static int load_object(cfg *c, const char *key, int required, cJSON **out, char *what, size_t n)
{
	*out = NULL;
	char *text = cfg_member_text(c, key);
	if (!text)
		return required ? cfg_error(c, key,
		                            "missing: expected a material file name or a material "
		                            "object")
		                : 0;
	cJSON *v = cJSON_Parse(text);
	free(text);
	if (cJSON_IsString(v)) {
		char *path = path_beside(cfg_source(c), v->valuestring);
		if (access(path, R_OK) != 0) {
			char *full = path_absolute(path);
			cfg_error(c, key,
			          "value \"%s\": no readable file %s: expected a material file "
			          "(its name relative to the calibration file's directory) or a "
			          "material object",
			          v->valuestring, full);
			free(full), free(path);
			cJSON_Delete(v);
			return -1;
		}
		cfg *m = cfg_load(path);
		snprintf(what, n, "%s", path);
		free(path);
		if (!m) {
			cfg_error(c, key, "value \"%s\": %s", v->valuestring, err_msg());
			cJSON_Delete(v);
			return -1;
		}
		cJSON_Delete(v);
		char *t = cfg_text(m);
		cfg_free(m);
		*out = cJSON_Parse(t);
		free(t);
	} else if (cJSON_IsObject(v)) {
		*out = v;
		snprintf(what, n, "%s: %s", cfg_source(c), key);
	} else {
		cJSON_Delete(v);
		return cfg_error(c, key, "expected a material file name or a material object");
	}
	return spec_check_material(*out, what);
}

static int load_material(cfg *c, cal_spec *s)
{
	char what[4200];
	if (load_object(c, "material", 1, &s->material, what, sizeof what))
		return -1;
	cJSON *law = cJSON_GetObjectItemCaseSensitive(s->material, "law");
	cJSON *name = cJSON_GetObjectItemCaseSensitive(s->material, "name");
	s->law = xstrdup(law->valuestring);
	s->material_name = xstrdup(name->valuestring);
	return 0;
}

/* A blind recovery's truth: the template but for the keys calibrated. */
static int load_truth(cfg *c, cal_spec *s)
{
	char what[4200];
	if (load_object(c, "truth", 0, &s->truth, what, sizeof what))
		return -1;
	if (!s->truth)
		return 0;
	cJSON *a = cJSON_Duplicate(s->material, 1), *b = cJSON_Duplicate(s->truth, 1);
	for (int k = 0; k < s->nkey; k++) {
		cJSON *v = spec_material_number(b, s->key[k].name);
		if (!v) {
			cJSON_Delete(a), cJSON_Delete(b);
			return cfg_error(c, "truth",
			                 "%s has no number '%s', which the calibration "
			                 "changes",
			                 what, s->key[k].name);
		}
		cJSON_SetNumberValue(v, 0);
		cJSON_SetNumberValue(spec_material_number(a, s->key[k].name), 0);
	}
	cJSON_DeleteItemFromObjectCaseSensitive(a, "name");
	cJSON_DeleteItemFromObjectCaseSensitive(b, "name");
	int same = cJSON_Compare(a, b, 1);
	cJSON_Delete(a), cJSON_Delete(b);
	if (!same)
		return cfg_error(c, "truth",
		                 "%s differs from the template in a key the calibration does not "
		                 "change: a blind recovery changes only those",
		                 what);
	return 0;
}

static int parse_free(cfg *c, cal_spec *s)
{
	long n = cfg_list(c, "free");
	if (n < 0)
		return -1;
	if (n == 0 || n > CAL_MAX_FREE)
		return cfg_error(c, "free",
		                 "%s: expected an array of 1 to %d parameters {key, min, max}",
		                 n ? "too many" : "missing or empty", CAL_MAX_FREE);
	for (long k = 0; k < n; k++) {
		cfg *f = cfg_item(c, "free", (size_t)k);
		cal_key *p = &s->key[s->nkey];
		const char *name;
		if (cfg_string(f, "key", &name))
			return -1;
		cJSON *tv = spec_material_number(s->material, name);
		if (!tv) {
			char keys[1024] = "";
			number_keys(s->material, "", keys, sizeof keys);
			return cfg_error(f, "key",
			                 "value \"%s\": not a number of the material template (law "
			                 "%s): expected one of %s",
			                 name, s->law, keys);
		}
		for (int j = 0; j < s->nkey; j++)
			if (strcmp(s->key[j].name, name) == 0)
				return cfg_error(f, "key", "value \"%s\": free twice", name);
		p->name = xstrdup(name);
		p->free = 1;
		p->tmpl = tv->valuedouble;
		s->nkey++, s->nfree++;
		if (cfg_number(f, "min", &p->lo, "", -INFINITY, INFINITY) ||
		    cfg_number(f, "max", &p->hi, "", -INFINITY, INFINITY) ||
		    cfg_bool_or(f, "log", &p->log, 0))
			return -1;
		if (!(p->hi > p->lo))
			return cfg_error(f, "max",
			                 "value %g: expected a number greater than min = %g", p->hi,
			                 p->lo);
		if (p->log && p->lo <= 0)
			return cfg_error(f, "min",
			                 "value %g: expected a positive number (log scale)", p->lo);
		int given = cfg_has(f, "start");
		if (cfg_number_or(f, "start", &p->start, p->tmpl, "", -INFINITY, INFINITY))
			return -1;
		if (p->start < p->lo || p->start > p->hi) {
			if (given)
				return cfg_error(
				    f, "start",
				    "value %g: the bounds [%g, %g] exclude it: expected a "
				    "start within them",
				    p->start, p->lo, p->hi);
			return cfg_error(
			    f, "min",
			    "the bounds [%g, %g] exclude the start, the template's %s = "
			    "%g: widen them or give a \"start\" within them",
			    p->lo, p->hi, name, p->tmpl);
		}
	}
	return 0;
}

static int parse_specimen(cfg *o, cal_specimen *sp)
{
	const char *config = NULL, *assembly = NULL;
	if (cfg_string_or(o, "specimen", &config, NULL) ||
	    cfg_string_or(o, "assembly", &assembly, NULL) ||
	    cfg_integer_or(o, "count", &sp->count, 0, 0, 100000000) ||
	    cfg_integer_or(o, "seed", &sp->seed, 0, 0, 2147483647))
		return -1;
	if (!config == !assembly)
		return cfg_error(o, config ? "assembly" : "specimen",
		                 "expected either \"specimen\" (a pack configuration, "
		                 "share/specimens/) or \"assembly\" (an assembly file), not %s",
		                 config ? "both" : "neither");
	if (assembly && (sp->count || sp->seed))
		return cfg_error(o, sp->count ? "count" : "seed",
		                 "applies to a \"specimen\" that pack makes, not to an assembly");
	const char *key = config ? "specimen" : "assembly";
	char *path = path_beside(cfg_source(o), config ? config : assembly);
	if (access(path, R_OK) != 0) {
		cfg_error(o, key, "value \"%s\": no readable file %s", config ? config : assembly,
		          path);
		free(path);
		return -1;
	}
	if (config)
		sp->config = path;
	else
		sp->assembly = path;
	return 0;
}

static int valid_name(const char *s)
{
	if (!s[0] || strlen(s) > 40)
		return 0;
	for (; *s; s++)
		if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') ||
		      (*s >= '0' && *s <= '9') || *s == '-' || *s == '_' || *s == '.'))
			return 0;
	return 1;
}

static int parse_tests(cfg *c, cal_spec *s)
{
	long n = cfg_list(c, "tests");
	if (n < 0)
		return -1;
	if (n == 0 || n > CAL_MAX_TESTS)
		return cfg_error(c, "tests",
		                 "%s: expected an array of 1 to %d tests {name, case, search}",
		                 n ? "too many" : "missing or empty", CAL_MAX_TESTS);
	for (long k = 0; k < n; k++) {
		cfg *t = cfg_item(c, "tests", (size_t)k);
		cal_test *ts = &s->test[k];
		const char *name, *cs, *word;
		if (cfg_string(t, "name", &name) || cfg_string(t, "case", &cs))
			return -1;
		if (!valid_name(name))
			return cfg_error(
			    t, "name",
			    "value \"%s\": expected a short name of letters, digits, '-', "
			    "'_' and '.'",
			    name);
		for (int j = 0; j < k; j++)
			if (strcmp(s->test[j].name, name) == 0)
				return cfg_error(t, "name", "value \"%s\": two tests of that name",
				                 name);
		ts->name = xstrdup(name);
		s->ntest++;
		ts->case_file = path_beside(s->source, cs);
		cfg *cc = cfg_load(ts->case_file);
		if (!cc)
			return cfg_error(t, "case", "%s", err_msg());
		int rc = cfg_string_or(cc, "test", &word, "custom");
		if (rc == 0)
			ts->test = xstrdup(word);
		cfg_free(cc);
		if (rc)
			return -1;
		cfg *o = cfg_object(t, "search");
		if (!o || parse_specimen(o, &ts->search))
			return -1;
		o = cfg_object_opt(t, "confirm");
		if (!o && err_msg()[0])
			return -1;
		if (o) {
			if (parse_specimen(o, &ts->confirm))
				return -1;
			ts->has_confirm = 1;
		}
	}
	return 0;
}

cJSON *spec_case_as_run(const cal_test *t)
{
	cJSON *j = cfg_load_json(t->case_file);
	if (!j)
		return NULL;
	cJSON_DeleteItemFromObjectCaseSensitive(j, "material");
	cJSON *out = cJSON_GetObjectItemCaseSensitive(j, "output");
	if (cJSON_IsObject(out)) {
		cJSON_DeleteItemFromObjectCaseSensitive(out, "snapshot_every");
		cJSON_DeleteItemFromObjectCaseSensitive(out, "snapshot_every_strain");
		cJSON_DeleteItemFromObjectCaseSensitive(out, "snapshot_strains");
	}
	return j;
}

/* Each test's case as solve reads it, with the template as its material
 * (its bounds are checked apart): a bad key is found before anything is
 * packed or run, and named with the calibration file and the test. */
static int check_cases(cfg *c, const cal_spec *s)
{
	for (int k = 0; k < s->ntest; k++) {
		const cal_test *t = &s->test[k];
		cJSON *j = spec_case_as_run(t);
		if (!j)
			return cfg_error(cfg_item(c, "tests", (size_t)k), "case", "%s", err_msg());
		cJSON_AddItemToObject(j, "material", cJSON_Duplicate(s->material, 1));
		/* solve is given the specimen's assembly on its command line. */
		cJSON_DeleteItemFromObjectCaseSensitive(j, "assembly");
		cJSON_AddStringToObject(j, "assembly", "the search specimen");
		char *text = cJSON_PrintUnformatted(j);
		cJSON_Delete(j);
		char what[8400];
		snprintf(what, sizeof what, "%s: test '%s': case %s", s->source, t->name,
		         t->case_file);
		dem_case dc;
		int rc = case_parse_text(text, what, &dc);
		free(text);
		if (rc)
			return -1;
		case_free(&dc);
	}
	return 0;
}

static int parse_targets(cfg *c, cal_spec *s)
{
	long n = cfg_list(c, "targets");
	if (n < 0)
		return -1;
	if (n == 0 || n > CAL_MAX_TARGETS)
		return cfg_error(c, "targets",
		                 "%s: expected an array of 1 to %d targets {test, quantity, value}",
		                 n ? "too many" : "missing or empty", CAL_MAX_TARGETS);
	for (long k = 0; k < n; k++) {
		cfg *t = cfg_item(c, "targets", (size_t)k);
		cal_target *tg = &s->target[k];
		const char *test, *qty;
		if (cfg_string(t, "test", &test) || cfg_string(t, "quantity", &qty))
			return -1;
		tg->test = -1;
		for (int j = 0; j < s->ntest; j++)
			if (strcmp(s->test[j].name, test) == 0)
				tg->test = j;
		if (tg->test < 0) {
			char names[1024] = "";
			for (int j = 0; j < s->ntest; j++) {
				size_t len = strlen(names);
				snprintf(names + len, sizeof names - len, "%s'%s'", j ? ", " : "",
				         s->test[j].name);
			}
			return cfg_error(t, "test",
			                 "value \"%s\": no such test: expected one of %s", test,
			                 names);
		}
		tg->quantity = quantity_find(qty);
		if (tg->quantity < 0)
			return cfg_error(t, "quantity", "value \"%s\": expected one of %s", qty,
			                 quantity_list());
		const quantity *q = &quantities[tg->quantity];
		const cal_test *ts = &s->test[tg->test];
		if (!(q->needs & quantity_test_kind(ts->test)))
			return cfg_error(
			    t, "quantity",
			    "value \"%s\": not measured by a \"%s\" test (case %s): %s", qty,
			    ts->test, ts->case_file,
			    q->needs == QTY_BTS ? "expected a Brazilian test (\"bts\")"
			    : q->needs == QTY_HYDROSTATIC
			        ? "expected a hydrostatic test"
			        : "expected a compression test (UCS, triaxial, ...)");
		tg->from_truth = s->truth && !cfg_has(t, "value");
		if ((!tg->from_truth &&
		     cfg_number(t, "value", &tg->value, q->unit,
		                quantity_positive(q) ? CFG_POS : -INFINITY, INFINITY)) ||
		    cfg_number_or(t, "tolerance", &tg->tol, 0.02, "relative", CFG_POS, 1) ||
		    cfg_number_or(t, "weight", &tg->weight, 1, "", CFG_POS, INFINITY))
			return -1;
		if (!tg->from_truth && tg->value == 0)
			return cfg_error(t, "value",
			                 "value 0: expected a non-zero number (the "
			                 "tolerance is relative to it)");
		char why[512];
		if (!tg->from_truth && quantity_plausible(q, tg->value, why, sizeof why))
			return cfg_error(t, "value", "value %g (test '%s', %s): %s", tg->value,
			                 ts->name, q->name, why);
		s->ntarget++;
	}
	for (int j = 0; j < s->ntest; j++) {
		int used = 0;
		for (int k = 0; k < s->ntarget; k++)
			used |= s->target[k].test == j;
		if (!used)
			return cfg_error(cfg_item(c, "tests", (size_t)j), "name",
			                 "value \"%s\": no target names this test",
			                 s->test[j].name);
	}
	return 0;
}

/* The search's defaults (share/doc/calibrate.md): a first step large
 * enough that its effect stands out of the noise of a few thousand spheres
 * (a percent or two on a peak), rounds that end before the steps sink into
 * it, a global stage for a start more than 10 % off once scaled, and four
 * tries of a scaled copy before the search gives up. */
#define STEP 0.5
#define XTOL 0.02
#define GLOBAL_ABOVE 0.1
#define PATIENCE 4

static int parse_search(cfg *c, cal_spec *s)
{
	static const char *const local[] = {"bobyqa", "cobyla", "sbplx", NULL};
	static const char *const global[] = {"auto", "never", "always", NULL};
	cfg *b = cfg_object_opt(c, "budget");
	if (!b && err_msg()[0])
		return -1;
	if (b ? cfg_integer_or(b, "runs", &s->runs, 200, 1, 1000000) ||
	            cfg_number_or(b, "wall", &s->wall, 0, "s", 0, INFINITY)
	      : (s->runs = 200, s->wall = 0, 0))
		return -1;
	cfg *o = cfg_object_opt(c, "search");
	if (!o && err_msg()[0])
		return -1;
	int scale_default = scaling_law(s->law);
	if (o) {
		if (cfg_choice_or(o, "method", &s->local, local, LOCAL_BOBYQA) ||
		    cfg_choice_or(o, "global", &s->global, global, GLOBAL_AUTO) ||
		    cfg_integer_or(o, "global_points", &s->global_points, 0, 0, 100000) ||
		    cfg_number_or(o, "global_above", &s->global_above, GLOBAL_ABOVE, "relative",
		                  CFG_POS, INFINITY) ||
		    cfg_bool_or(o, "scaling", &s->scaling, scale_default) ||
		    cfg_number_or(o, "step", &s->step, STEP, "relative", CFG_POS, 1) ||
		    cfg_number_or(o, "xtol", &s->xtol, XTOL, "relative", CFG_POS, 0.5) ||
		    cfg_integer_or(o, "patience", &s->patience, PATIENCE, 1, 12) ||
		    cfg_integer_or(o, "seed", &s->seed, 1, 0, 2147483647))
			return -1;
		if (s->scaling && !scale_default)
			return cfg_error(o, "scaling",
			                 "value true: the law '%s' has no exact scaling (laws with "
			                 "it: onate, jcfpm, linear)",
			                 s->law);
	} else {
		s->local = LOCAL_BOBYQA, s->global = GLOBAL_AUTO, s->global_points = 0;
		s->global_above = GLOBAL_ABOVE;
		s->patience = PATIENCE;
		s->scaling = scale_default, s->step = STEP, s->xtol = XTOL, s->seed = 1;
	}
	cfg *sn = cfg_object_opt(c, "sensitivity");
	if (!sn && err_msg()[0])
		return -1;
	s->sens_step = 0.05;
	return sn ? cfg_number_or(sn, "step", &s->sens_step, 0.05, "relative", CFG_POS, 0.5) : 0;
}

/* With the scaling: the class of each free key; the law's other scaling
 * keys in the template follow their class's scale (tied). */
static int assign_classes(cfg *c, cal_spec *s)
{
	if (!s->scaling)
		return 0;
	int active[3] = {0, 0, 0};
	for (int k = 0; k < s->nfree; k++) {
		cal_key *p = &s->key[k];
		p->cls = scaling_class(s->law, p->name);
		if (p->cls == CLS_NONE)
			continue;
		active[p->cls] = 1;
		if (p->lo <= 0 || p->tmpl <= 0)
			return cfg_error(
			    cfg_item(c, "free", (size_t)k), p->lo <= 0 ? "min" : "key",
			    "%s of %s: expected positive (with the scaling, stresses and "
			    "stiffnesses are searched on a log scale; or set "
			    "\"search\": {\"scaling\": false})",
			    p->lo <= 0 ? "the lower bound" : "the template's value", p->name);
		p->log = 1;
	}
	const char *const *keys = scaling_keys(s->law);
	for (int j = 0; keys[j]; j++) {
		scale_class cls = scaling_class(s->law, keys[j]);
		cJSON *v = spec_material_number(s->material, keys[j]);
		int is_free = 0;
		for (int k = 0; k < s->nfree; k++)
			is_free |= strcmp(s->key[k].name, keys[j]) == 0;
		if (!v || is_free || !active[cls])
			continue;
		cal_key *t = &s->key[s->nkey++];
		t->name = xstrdup(keys[j]);
		t->cls = cls;
		t->tmpl = t->start = v->valuedouble;
		t->log = 1;
	}
	return 0;
}

/* The material at each bound of each free key (the others at their
 * start) is one solve accepts. */
static int check_bounds(cfg *c, cal_spec *s)
{
	for (int k = 0; k < s->nfree; k++)
		for (int side = 0; side < 2; side++) {
			cJSON *m = cJSON_Duplicate(s->material, 1);
			for (int j = 0; j < s->nfree; j++)
				cJSON_SetNumberValue(spec_material_number(m, s->key[j].name),
				                     j == k ? (side ? s->key[j].hi : s->key[j].lo)
				                            : s->key[j].start);
			int rc = spec_check_material(m, "the material");
			cJSON_Delete(m);
			if (rc)
				return cfg_error(cfg_item(c, "free", (size_t)k),
				                 side ? "max" : "min", "value %g: %s",
				                 side ? s->key[k].hi : s->key[k].lo, err_msg());
		}
	return 0;
}

int spec_load(const char *path, cal_spec *s)
{
	memset(s, 0, sizeof *s);
	s->source = xstrdup(path);
	cfg *c = cfg_load(path);
	if (!c)
		return -1;
	const char *name;
	int rc = cfg_string_or(c, "name", &name, NULL);
	if (rc == 0) {
		if (name) {
			s->name = xstrdup(name);
		} else { /* the file's name without .json */
			const char *base = strrchr(path, '/');
			s->name = xstrdup(base ? base + 1 : path);
			size_t n = strlen(s->name);
			if (n > 5 && strcmp(s->name + n - 5, ".json") == 0)
				s->name[n - 5] = '\0';
		}
	}
	rc = rc || load_material(c, s) || parse_free(c, s) || parse_tests(c, s) ||
	     check_cases(c, s) || parse_search(c, s) || assign_classes(c, s) || load_truth(c, s) ||
	     parse_targets(c, s) || check_bounds(c, s) || cfg_check_unused(c);
	cfg_free(c);
	return rc ? -1 : 0;
}

static void free_specimen(cal_specimen *sp)
{
	free(sp->config);
	free(sp->assembly);
}

void spec_free(cal_spec *s)
{
	for (int k = 0; k < s->nkey; k++)
		free(s->key[k].name);
	for (int k = 0; k < s->ntest; k++) {
		free(s->test[k].name);
		free(s->test[k].case_file);
		free(s->test[k].test);
		free_specimen(&s->test[k].search);
		free_specimen(&s->test[k].confirm);
	}
	cJSON_Delete(s->material);
	cJSON_Delete(s->truth);
	free(s->law);
	free(s->material_name);
	free(s->name);
	free(s->source);
	memset(s, 0, sizeof *s);
}
