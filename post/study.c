#define _XOPEN_SOURCE 700 /* realpath */
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lib/cfg.h"
#include "lib/err.h"
#include "lib/path.h"
#include "pack/options.h"
#include "post/study.h"
#include "solve/case.h"

/* ---- files ------------------------------------------------------------ */

/* An absolute name for path (resolved when it exists). Caller frees. */
static char *absolute(const char *path)
{
	char real[PATH_MAX], cwd[PATH_MAX];
	if (realpath(path, real))
		return xstrdup(real);
	if (path[0] == '/' || !getcwd(cwd, sizeof cwd))
		return xstrdup(path);
	size_t n = strlen(cwd) + strlen(path) + 2;
	char *out = xmalloc(n);
	snprintf(out, n, "%s/%s", cwd, path);
	return out;
}

/* The JSON object in a file, or NULL with err_set(). */
static cJSON *read_json(const char *path)
{
	cfg *c = cfg_load(path);
	if (!c)
		return NULL;
	char *text = cfg_text(c);
	cfg_free(c);
	cJSON *j = cJSON_Parse(text);
	free(text);
	return j;
}

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
	*file = absolute(name);
	free(name);
	*json = read_json(*file);
	return *json ? 0 : cfg_error(c, key, "%s", err_msg());
}

/* ---- keys inside a JSON tree ----------------------------------------------- */

/* Set the member at a dotted path ("damping.translational", "loading.0.axial.rate":
 * a number indexes an array) to a copy of v, making the objects on the way
 * that are missing (the file's reader then says whether it knows them).
 * 0, or -1 with err_set(). */
static int set_path(cJSON *root, const char *path, const cJSON *v)
{
	char buf[256];
	snprintf(buf, sizeof buf, "%s", path);
	cJSON *node = root;
	char *save = NULL, *part = strtok_r(buf, ".", &save);
	while (part) {
		char *next = strtok_r(NULL, ".", &save);
		cJSON *child = NULL;
		int index = -1;
		if (cJSON_IsArray(node)) {
			char *end;
			long k = strtol(part, &end, 10);
			if (*end || k < 0 || k >= cJSON_GetArraySize(node))
				return err_set("'%s' is not an index of that array", part);
			index = (int)k;
			child = cJSON_GetArrayItem(node, index);
		} else if (cJSON_IsObject(node)) {
			child = cJSON_GetObjectItemCaseSensitive(node, part);
		} else {
			return err_set(
			    "'%s' is inside a value that is neither an object nor an array", part);
		}
		if (!next) {
			cJSON *copy = cJSON_Duplicate(v, 1);
			if (index >= 0)
				cJSON_ReplaceItemInArray(node, index, copy);
			else if (child)
				cJSON_ReplaceItemInObjectCaseSensitive(node, part, copy);
			else
				cJSON_AddItemToObject(node, part, copy);
			return 0;
		}
		if (!child)
			cJSON_AddItemToObject(node, part, child = cJSON_CreateObject());
		node = child;
		part = next;
	}
	return err_set("an empty key");
}

static const char *string_of(const cJSON *o, const char *key)
{
	const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
	return cJSON_IsString(v) ? v->valuestring : NULL;
}

/* ---- the varied parameters ----------------------------------------------- */

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
		char *t = cJSON_PrintUnformatted(v);
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
			                 "value %g: %.0f values from %g to %g: expected at "
			                 "most %d",
			                 step, n, from, to, STUDY_MAX_VALUES);
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

/* ---- the points ------------------------------------------------------------- */

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

/* ---- the specimen -------------------------------------------------------------- */

/* The keys Yade's randomDensePack of a cylinder takes (tools/yade-pack). */
static const char *const yade_keys[] = {"arrangement", "shape", "diameter", "height", "dist",
                                        "radius",      "fuzz",  "seed",     "cell"};

static int is_yade(const cJSON *specimen)
{
	const char *a = string_of(specimen, "arrangement");
	return a && !strcmp(a, "yade");
}

/* A specimen of Yade's packing (f->specimen): its keys checked; the
 * tools/yade-pack options, and pack's configuration importing the sphere
 * list in its place. */
static int yade_specimen(study_files *f, const char *what)
{
	cJSON *sp = f->specimen;
	for (cJSON *m = sp->child; m; m = m->next) {
		size_t k = 0;
		while (k < sizeof yade_keys / sizeof *yade_keys && strcmp(m->string, yade_keys[k]))
			k++;
		if (k == sizeof yade_keys / sizeof *yade_keys)
			return err_set("%s: key '%s': does not apply to arrangement yade: expected "
			               "diameter, height, radius, fuzz, seed and cell (Yade's "
			               "randomDensePack of a cylinder, tools/yade-pack)",
			               what, m->string);
	}
	const char *shape = string_of(sp, "shape"), *dist = string_of(sp, "dist");
	if (shape && strcmp(shape, "cylinder"))
		return err_set("%s: key 'shape': value \"%s\": expected cylinder with arrangement "
		               "yade (tools/yade-pack)",
		               what, shape);
	if (dist && strcmp(dist, "fuzz"))
		return err_set("%s: key 'dist': value \"%s\": expected fuzz with arrangement yade "
		               "(Yade's radius and rRelFuzz)",
		               what, dist);
	const cJSON *d = cJSON_GetObjectItemCaseSensitive(sp, "diameter"),
	            *h = cJSON_GetObjectItemCaseSensitive(sp, "height");
	if (!cJSON_IsNumber(d) || !cJSON_IsNumber(h))
		return err_set("%s: key '%s': missing: expected the cylinder's diameter and height "
		               "(m) with arrangement yade",
		               what, cJSON_IsNumber(d) ? "height" : "diameter");
	const cJSON *seed = cJSON_GetObjectItemCaseSensitive(sp, "seed");
	if (cJSON_IsNumber(seed) && seed->valuedouble > INT_MAX)
		return err_set("%s: key 'seed': value %.0f: expected at most %d with arrangement "
		               "yade (Yade's seed is an int)",
		               what, seed->valuedouble, INT_MAX);
	/* The values within pack's bounds for the same keys. */
	cJSON *check = cJSON_Duplicate(sp, 1);
	cJSON_DeleteItemFromObjectCaseSensitive(check, "arrangement");
	cJSON_DeleteItemFromObjectCaseSensitive(check, "dist");
	cJSON_AddStringToObject(check, "dist", "fuzz");
	char *text = cJSON_PrintUnformatted(check);
	cJSON_Delete(check);
	int rc = options_check_config(text, what);
	free(text);
	if (rc)
		return -1;
	char args[512];
	size_t len = 0;
	static const char *const opts[] = {"diameter", "height", "radius", "fuzz", "seed", "cell"};
	for (size_t k = 0; k < sizeof opts / sizeof *opts; k++) {
		const cJSON *v = cJSON_GetObjectItemCaseSensitive(sp, opts[k]);
		if (cJSON_IsNumber(v))
			len += (size_t)snprintf(args + len, sizeof args - len, "%s--%s %.10g",
			                        len ? " " : "", opts[k], v->valuedouble);
	}
	f->yade_args = xstrdup(args);
	f->specimen = cJSON_CreateObject();
	cJSON_AddStringToObject(f->specimen, "shape", "cylinder");
	cJSON_AddNumberToObject(f->specimen, "diameter", d->valuedouble);
	cJSON_AddNumberToObject(f->specimen, "height", h->valuedouble);
	cJSON_AddStringToObject(f->specimen, "import", "spheres.txt");
	cJSON_Delete(sp);
	return 0;
}

/* The file names of a pack configuration made absolute (they are relative
 * to the file that names them). */
static void absolute_names(cJSON *sp, const char *beside)
{
	static const char *const keys[] = {"geometry", "grading", "import"};
	for (size_t k = 0; k < sizeof keys / sizeof *keys; k++) {
		const char *name = string_of(sp, keys[k]);
		if (!name)
			continue;
		char *p = path_beside(beside, name), *a = absolute(p);
		cJSON_ReplaceItemInObjectCaseSensitive(sp, keys[k], cJSON_CreateString(a));
		free(p), free(a);
	}
}

/* ---- a point's files ------------------------------------------------------------ */

int study_point_files(const study *s, int k, study_files *f)
{
	const study_point *pt = &s->point[k];
	memset(f, 0, sizeof *f);
	f->material = cJSON_Duplicate(s->material, 1);
	f->kase = cJSON_Duplicate(s->kase, 1);
	cJSON *sp = f->specimen = cJSON_Duplicate(s->specimen, 1);
	cJSON *files[] = {f->material, f->kase, sp};
	for (int i = 0; i < s->nset; i++)
		if (set_path(files[s->set[i].where], s->set[i].path, s->set[i].value))
			return err_wrap("%s: key 'set': '%s'", s->source, s->set[i].key);
	for (int i = 0; i < s->np; i++)
		if (set_path(files[s->p[i].where], s->p[i].path, s->p[i].value[pt->v[i]]))
			return err_wrap("%s: point %s: key '%s'", s->source, pt->name, s->p[i].key);
	if (pt->seed >= 0) {
		cJSON *seed = cJSON_CreateNumber((double)pt->seed);
		set_path(sp, "seed", seed);
		cJSON_Delete(seed);
	}
	cJSON *name = cJSON_CreateString("material.json");
	set_path(f->kase, "material", name);
	cJSON_Delete(name);
	name = cJSON_CreateString("assembly.h5");
	set_path(f->kase, "assembly", name);
	cJSON_Delete(name);
	absolute_names(sp, s->specimen_file ? s->specimen_file : s->source);
	char what[STUDY_NAME + 600];
	snprintf(what, sizeof what, "%s: point %s: specimen", s->source, pt->name);
	const char *a = string_of(sp, "arrangement");
	if (a && strcmp(a, "random") && strcmp(a, "hcp") && strcmp(a, "yade"))
		return err_set(
		    "%s: key 'arrangement': value \"%s\": expected random or hcp (pack's) "
		    "or yade (Yade's randomDensePack, tools/yade-pack)",
		    what, a);
	return is_yade(sp) ? yade_specimen(f, what) : 0;
}

void study_files_free(study_files *f)
{
	cJSON_Delete(f->material);
	cJSON_Delete(f->kase);
	cJSON_Delete(f->specimen);
	free(f->yade_args);
	memset(f, 0, sizeof *f);
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

/* ---- the study file ---------------------------------------------------------------- */

static int load_base(cfg *c, study *s)
{
	const char *name;
	if (cfg_string(c, "case", &name))
		return -1;
	char *p = path_beside(s->source, name);
	s->case_file = absolute(p);
	free(p);
	s->kase = read_json(s->case_file);
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
			s->material_file = absolute(p);
			free(p);
			s->material = read_json(s->material_file);
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
	if (!string_of(s->specimen, "import"))
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
