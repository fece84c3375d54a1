/* A point's files (post/study.h): the base material, case and specimen
 * with the study's fixed and varied keys set, the case naming the files
 * beside it, the specimen's file names absolute, and for Yade's packing
 * the options of tools/yade-pack with pack importing its list. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/path.h"
#include "pack/options.h"
#include "post/study.h"

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
		char *p = path_beside(beside, name), *a = path_absolute(p);
		cJSON_ReplaceItemInObjectCaseSensitive(sp, keys[k], cJSON_CreateString(a));
		free(p), free(a);
	}
}

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
