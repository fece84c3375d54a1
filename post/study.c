/* The study file (post/study.h): read, its keys and values checked, its
 * points made, and every point checked as solve and pack will read it. */
#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/cfg.h"
#include "lib/err.h"
#include "lib/path.h"
#include "pack/options.h"
#include "post/study.h"
#include "solve/case.h"

/* A file name or an inline object under key of the study: *json the
 * object, *file the file's absolute name (NULL when inline). */
static int file_or_object(cfg *c, const char *key, const char *beside, cJSON **json, char **file)
{
	char *text = cfg_member_text(c, key);
	cJSON *v = text ? cJSON_Parse(text) : NULL;
	free(text);
	*json = NULL;
	*file = NULL;
	if (cJSON_IsObject(v)) {
		*json = v;
		return 0;
	}
	if (!cJSON_IsString(v) || !v->valuestring[0]) {
		cJSON_Delete(v);
		return cfg_error(c, key, "expected a file name or an object");
	}
	char *name = path_beside(beside, v->valuestring);
	cJSON_Delete(v);
	*file = path_absolute(name);
	free(name);
	*json = cfg_load_json(*file);
	return *json ? 0 : cfg_error(c, key, "%s", err_msg());
}

/* A value as it appears in point names: numbers to 6 significant digits,
 * words as written (letters, digits and . _ + - only). */
static int value_text(cfg *c, const char *key, const cJSON *v, char *out, size_t n)
{
	if (cJSON_IsNumber(v)) {
		snprintf(out, n, "%.6g", v->valuedouble);
		return 0;
	}
	if (cJSON_IsBool(v)) {
		snprintf(out, n, "%s", cJSON_IsTrue(v) ? "true" : "false");
		return 0;
	}
	const char *s = cJSON_IsString(v) ? v->valuestring : NULL;
	int ok = s && s[0] && strlen(s) < n;
	for (const char *p = s; ok && *p; p++)
		ok = isalnum((unsigned char)*p) || strchr("._+-", *p);
	if (!ok) {
		/* A number beyond a double's range was read as infinite, and
		 * the list passes through JSON text, which writes it as null. */
		char *t = cJSON_IsNull(v)
		              ? xstrdup("null (or a number beyond the range of a double)")
		              : cJSON_PrintUnformatted(v);
		int rc = cfg_error(c, key,
		                   "value %s: expected a number, true, false or a word of at most "
		                   "%zu letters, digits and . _ + -",
		                   t, n - 1);
		free(t);
		return rc;
	}
	snprintf(out, n, "%s", s);
	return 0;
}

/* "range": {"from", "to", and "step" or "count" (with "log": true, a
 * geometric sequence)}, each value rounded to 12 significant digits so that
 * 0.1 + 0.2 is written 0.3. */
static int range_values(cfg *r, study_param *p)
{
	double from, to, step = 0;
	long count = 0;
	int log_scale;
	if (cfg_number(r, "from", &from, "", -INFINITY, INFINITY) ||
	    cfg_number(r, "to", &to, "", -INFINITY, INFINITY) ||
	    cfg_bool_or(r, "log", &log_scale, 0))
		return -1;
	int has_step = cfg_has(r, "step"), has_count = cfg_has(r, "count");
	if (has_step == has_count)
		return cfg_error(r, "step", "expected either \"step\" or \"count\"");
	if (has_count && cfg_integer(r, "count", &count, 1, STUDY_MAX_VALUES))
		return -1;
	if (has_step) {
		if (cfg_number(r, "step", &step, "", -INFINITY, INFINITY))
			return -1;
		if (log_scale)
			return cfg_error(r, "log",
			                 "value true: a \"step\" range is linear: expected "
			                 "\"count\" with \"log\"");
		if (step == 0 || (to - from) * step < 0)
			return cfg_error(r, "step", "value %g: expected a step from %g towards %g",
			                 step, from, to);
		double n = floor((to - from) / step * (1 + 1e-9)) + 1;
		if (n > STUDY_MAX_VALUES)
			return cfg_error(r, "step",
			                 "value %g: %.3g values from %g to %g: expected at "
			                 "most %d",
			                 step, isfinite(n) ? n : DBL_MAX, from, to,
			                 STUDY_MAX_VALUES);
		count = (long)n;
	}
	if (log_scale && (from <= 0 || to <= 0))
		return cfg_error(r, "log", "value true: expected \"from\" and \"to\" above 0");
	if (count == 1 && from != to && has_count)
		return cfg_error(r, "count", "value 1: expected at least 2 from %g to %g", from,
		                 to);
	for (long k = 0; k < count; k++) {
		double t = count > 1 ? (double)k / (double)(count - 1) : 0;
		double v = has_step    ? from + (double)k * step
		           : log_scale ? from * pow(to / from, t)
		                       : from + t * (to - from);
		char text[40];
		snprintf(text, sizeof text, "%.12g", v);
		p->value[p->n++] = cJSON_CreateNumber(strtod(text, NULL));
	}
	return 0;
}

static int list_values(cfg *c, study_param *p)
{
	char *text = cfg_member_text(c, "values");
	cJSON *a = cJSON_Parse(text);
	free(text);
	int n = cJSON_IsArray(a) ? cJSON_GetArraySize(a) : 0;
	if (n < 1 || n > STUDY_MAX_VALUES) {
		cJSON_Delete(a);
		return cfg_error(c, "values", "expected an array of 1 to %d values",
		                 STUDY_MAX_VALUES);
	}
	for (cJSON *v = a->child; v; v = v->next)
		p->value[p->n++] = cJSON_Duplicate(v, 1);
	cJSON_Delete(a);
	return 0;
}

/* "material.<key>", "case.<key>" or "specimen.<key>" (key, as given under
 * ckey of c): which file, and the key within it (*path points into key). */
static int where_of(cfg *c, const char *ckey, const char *key, study_where *where,
                    const char **path)
{
	static const struct {
		const char *prefix;
		study_where where;
	} kinds[] = {{"material.", IN_MATERIAL}, {"case.", IN_CASE}, {"specimen.", IN_SPECIMEN}};
	*path = NULL;
	for (size_t k = 0; k < sizeof kinds / sizeof *kinds; k++) {
		size_t n = strlen(kinds[k].prefix);
		if (strncmp(key, kinds[k].prefix, n) == 0 && key[n] && strlen(key) < 200) {
			*where = kinds[k].where;
			*path = key + n;
			break;
		}
	}
	if (!*path)
		return cfg_error(c, ckey,
		                 "value \"%s\": expected material.<key>, case.<key> or "
		                 "specimen.<key> (share/doc/studies.md)",
		                 key);
	if (*where == IN_CASE && (!strcmp(*path, "material") || !strncmp(*path, "material.", 9) ||
	                          !strcmp(*path, "assembly")))
		return cfg_error(c, ckey,
		                 "value \"%s\": the study sets the case's material and assembly: "
		                 "expected material.<key> for the material",
		                 key);
	if (*where == IN_SPECIMEN && strchr(*path, '.'))
		return cfg_error(c, ckey,
		                 "value \"%s\": a specimen key is one of pack's settings (radius, "
		                 "fuzz, dist, arrangement, count, seed, ...), not a nested key",
		                 key);
	return 0;
}

static int parse_key(cfg *c, study_param *p)
{
	const char *key;
	if (cfg_string(c, "key", &key))
		return -1;
	p->key = xstrdup(key);
	if (where_of(c, "key", p->key, &p->where, &p->path))
		return -1;
	const char *dot = strrchr(p->path, '.');
	p->name = xstrdup(dot ? dot + 1 : p->path);
	return 0;
}

static int parse_param(cfg *c, study_param *p)
{
	const char *label;
	if (parse_key(c, p) || cfg_number_or(c, "scale", &p->scale, 1, "", CFG_POS, INFINITY) ||
	    cfg_string_or(c, "label", &label, p->key))
		return -1;
	p->label = xstrdup(label);
	int has_values = cfg_has(c, "values"), has_range = cfg_has(c, "range");
	if (has_values == has_range)
		return cfg_error(c, "values", "expected either \"values\" (a list) or \"range\"");
	cfg *r = has_range ? cfg_object(c, "range") : NULL;
	if (has_range ? !r || range_values(r, p) : list_values(c, p))
		return -1;
	p->numeric = 1;
	for (int k = 0; k < p->n; k++) {
		p->numeric &= cJSON_IsNumber(p->value[k]);
		if (value_text(c, has_range ? "range" : "values", p->value[k], p->text[k],
		               sizeof p->text[k]))
			return -1;
	}
	return 0;
}

static void point_name(const study *s, study_point *pt)
{
	size_t len = 0;
	for (int i = 0; i < s->np; i++)
		len += (size_t)snprintf(pt->name + len, sizeof pt->name - len, "%s%s-%s",
		                        i ? "_" : "", s->p[i].name, s->p[i].text[pt->v[i]]);
	if (pt->seed >= 0)
		snprintf(pt->name + len, sizeof pt->name - len, "_seed-%ld", pt->seed);
}

/* Every combination of the values, and of the seeds when given; no two
 * points may share a directory. */
static int make_points(study *s, cfg *c)
{
	int n = s->p[0].n * (s->np > 1 ? s->p[1].n : 1) * (s->nseeds ? s->nseeds : 1);
	if (n > STUDY_MAX_POINTS)
		return cfg_error(c, "vary", "%d points: expected at most %d", n, STUDY_MAX_POINTS);
	s->point = xcalloc((size_t)n, sizeof *s->point);
	for (int k = 0; k < n; k++) {
		study_point *pt = &s->point[s->npoints++];
		int rest = k;
		pt->seed = s->nseeds ? s->seed[rest % s->nseeds] : -1;
		rest /= s->nseeds ? s->nseeds : 1;
		for (int i = s->np - 1; i >= 0; i--) {
			pt->v[i] = rest % s->p[i].n;
			rest /= s->p[i].n;
		}
		point_name(s, pt);
		for (int j = 0; j < k; j++)
			if (strcmp(s->point[j].name, pt->name) == 0) {
				int i = s->point[j].v[0] != pt->v[0] ? 0 : 1;
				cfg *item = cfg_item(c, "vary", (size_t)i);
				char *a = cJSON_PrintUnformatted(s->p[i].value[s->point[j].v[i]]),
				     *b = cJSON_PrintUnformatted(s->p[i].value[pt->v[i]]);
				int rc =
				    cfg_error(item, cfg_has(item, "range") ? "range" : "values",
				              "values %s and %s would both be point '%s': expected "
				              "values distinct to 6 significant digits",
				              a, b, pt->name);
				free(a), free(b);
				return rc;
			}
	}
	return 0;
}

/* Point k's case and material as solve reads them, and its specimen as pack
 * does. */
static int check_point(const study *s, int k)
{
	study_files f;
	if (study_point_files(s, k, &f)) {
		study_files_free(&f);
		return -1;
	}
	char what[STUDY_NAME + 600];
	snprintf(what, sizeof what, "%s: point %s: case", s->source, s->point[k].name);
	cJSON *inline_case = cJSON_Duplicate(f.kase, 1);
	cJSON_ReplaceItemInObjectCaseSensitive(inline_case, "material",
	                                       cJSON_Duplicate(f.material, 1));
	char *text = cJSON_PrintUnformatted(inline_case);
	cJSON_Delete(inline_case);
	dem_case dc;
	int rc = case_parse_text(text, what, &dc);
	free(text);
	if (!rc)
		case_free(&dc);
	if (!rc) {
		snprintf(what, sizeof what, "%s: point %s: specimen", s->source, s->point[k].name);
		text = cJSON_PrintUnformatted(f.specimen);
		rc = options_check_config(text, what);
		free(text);
	}
	study_files_free(&f);
	return rc;
}

static int load_base(cfg *c, study *s)
{
	const char *name;
	if (cfg_string(c, "case", &name))
		return -1;
	char *p = path_beside(s->source, name);
	s->case_file = path_absolute(p);
	free(p);
	s->kase = cfg_load_json(s->case_file);
	if (!s->kase)
		return cfg_error(c, "case", "%s", err_msg());
	if (cfg_has(c, "material")) {
		if (file_or_object(c, "material", s->source, &s->material, &s->material_file))
			return -1;
	} else {
		const cJSON *m = cJSON_GetObjectItemCaseSensitive(s->kase, "material");
		if (cJSON_IsObject(m)) {
			s->material = cJSON_Duplicate(m, 1);
		} else if (cJSON_IsString(m)) {
			p = path_beside(s->case_file, m->valuestring);
			s->material_file = path_absolute(p);
			free(p);
			s->material = cfg_load_json(s->material_file);
			if (!s->material)
				return cfg_error(c, "case", "%s: its material: %s", s->case_file,
				                 err_msg());
		} else {
			return cfg_error(c, "case",
			                 "%s names no material: expected its \"material\", or the "
			                 "study's",
			                 s->case_file);
		}
	}
	if (!cfg_has(c, "specimen"))
		return cfg_error(c, "specimen",
		                 "missing: expected a pack configuration file or "
		                 "object (share/doc/pack.md)");
	return file_or_object(c, "specimen", s->source, &s->specimen, &s->specimen_file);
}

static int load_seeds(cfg *c, study *s)
{
	if (!cfg_has(c, "seeds"))
		return 0;
	double *v = NULL;
	size_t n = 0;
	if (cfg_numbers(c, "seeds", &v, &n, 0, "", 0, 9.2e18))
		return -1;
	int rc = 0;
	if (n < 1 || n > STUDY_MAX_SEEDS)
		rc = cfg_error(c, "seeds", "expected 1 to %d seeds", STUDY_MAX_SEEDS);
	for (size_t k = 0; !rc && k < n; k++) {
		if (v[k] != floor(v[k]))
			rc = cfg_error(c, "seeds", "value %g: expected whole numbers", v[k]);
		for (size_t j = 0; !rc && j < k; j++)
			if (v[j] == v[k])
				rc = cfg_error(c, "seeds",
				               "value %g given twice: expected distinct seeds",
				               v[k]);
		s->seed[k] = (long)v[k];
	}
	s->nseeds = rc ? 0 : (int)n;
	free(v);
	return rc;
}

/* A specimen key varied or seeded must reach the packing: not with an
 * imported sphere list. */
static int check_specimen_keys(cfg *c, const study *s)
{
	if (!cJSON_IsString(cJSON_GetObjectItemCaseSensitive(s->specimen, "import")))
		return 0;
	for (int i = 0; i < s->np; i++)
		if (s->p[i].where == IN_SPECIMEN)
			return cfg_error(
			    cfg_item(c, "vary", (size_t)i), "key",
			    "value \"%s\": the specimen imports its spheres (\"import\"), "
			    "which no specimen key changes: expected a specimen that "
			    "packs",
			    s->p[i].key);
	for (int i = 0; i < s->nset; i++)
		if (s->set[i].where == IN_SPECIMEN)
			return cfg_error(
			    c, "set",
			    "value \"%s\": the specimen imports its spheres (\"import\"), "
			    "which no specimen key changes: expected a specimen that packs",
			    s->set[i].key);
	if (s->nseeds)
		return cfg_error(c, "seeds",
		                 "the specimen imports its spheres (\"import\"): "
		                 "expected a specimen that packs");
	return 0;
}

/* "set": {key: value}, keys of the same kinds set to one value at every
 * point. */
static int load_set(cfg *c, study *s)
{
	char *text = cfg_member_text(c, "set");
	if (!text)
		return 0;
	cJSON *o = cJSON_Parse(text);
	free(text);
	int rc =
	    cJSON_IsObject(o) ? 0 : cfg_error(c, "set", "expected an object of keys and values");
	for (cJSON *m = o ? o->child : NULL; !rc && m; m = m->next) {
		if (s->nset == STUDY_MAX_SETS) {
			rc = cfg_error(c, "set", "expected at most %d keys", STUDY_MAX_SETS);
			break;
		}
		study_set *e = &s->set[s->nset++];
		e->key = xstrdup(m->string);
		e->value = cJSON_Duplicate(m, 1);
		rc = where_of(c, "set", e->key, &e->where, &e->path);
		for (int i = 0; !rc && i < s->np; i++)
			if (!strcmp(s->p[i].key, e->key))
				rc = cfg_error(
				    c, "set",
				    "value \"%s\": also varied: expected it in one of \"set\" "
				    "and \"vary\"",
				    e->key);
	}
	cJSON_Delete(o);
	return rc;
}

static int load_vary(cfg *c, study *s)
{
	long n = cfg_list(c, "vary");
	if (n < 0)
		return -1;
	if (n < 1 || n > STUDY_MAX_PARAMS)
		return cfg_error(c, "vary",
		                 "expected an array of 1 or 2 parameters {key, values or "
		                 "range}");
	for (long i = 0; i < n; i++) {
		cfg *item = cfg_item(c, "vary", (size_t)i);
		if (parse_param(item, &s->p[s->np++]))
			return -1;
		if (i == 1 && strcmp(s->p[0].key, s->p[1].key) == 0)
			return cfg_error(item, "key", "value \"%s\": varied twice", s->p[1].key);
		if (s->p[i].where == IN_SPECIMEN && !strcmp(s->p[i].path, "seed") &&
		    cfg_has(c, "seeds"))
			return cfg_error(item, "key",
			                 "value \"%s\": the study's \"seeds\" set it: "
			                 "expected one of them",
			                 s->p[i].key);
	}
	/* Two keys of one name (material.E, case.E) name the points in full. */
	if (s->np == 2 && !strcmp(s->p[0].name, s->p[1].name))
		for (int i = 0; i < 2; i++) {
			free(s->p[i].name);
			s->p[i].name = xstrdup(s->p[i].key);
			for (char *q = s->p[i].name; *q; q++)
				if (*q == '.')
					*q = '-';
		}
	return 0;
}

int study_load(const char *path, study *s)
{
	memset(s, 0, sizeof *s);
	s->source = xstrdup(path);
	cfg *c = cfg_load(path);
	if (!c)
		return -1;
	const char *title;
	int rc = cfg_string_or(c, "title", &title, path) || load_base(c, s) || load_vary(c, s) ||
	         load_set(c, s) || load_seeds(c, s) || check_specimen_keys(c, s) ||
	         cfg_check_unused(c);
	if (!rc)
		s->title = xstrdup(title);
	rc = rc || make_points(s, c);
	for (int k = 0; !rc && k < s->npoints; k++)
		rc = check_point(s, k);
	cfg_free(c);
	return rc ? -1 : 0;
}

void study_free(study *s)
{
	for (int i = 0; i < s->np; i++) {
		free(s->p[i].key), free(s->p[i].name), free(s->p[i].label);
		for (int k = 0; k < s->p[i].n; k++)
			cJSON_Delete(s->p[i].value[k]);
	}
	for (int i = 0; i < s->nset; i++)
		free(s->set[i].key), cJSON_Delete(s->set[i].value);
	free(s->source), free(s->title), free(s->case_file), free(s->material_file);
	free(s->specimen_file);
	cJSON_Delete(s->kase), cJSON_Delete(s->material), cJSON_Delete(s->specimen);
	free(s->point);
	memset(s, 0, sizeof *s);
}
