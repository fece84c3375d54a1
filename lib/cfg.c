#include <cjson/cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/cfg.h"
#include "lib/err.h"

struct cfg {
	cJSON *json;         /* the object this view reads */
	cJSON *root;         /* owned by the root view only */
	char *source;        /* file name, owned by the root view only */
	char *path;          /* dotted path, "" for the root */
	unsigned char *used; /* per member of json */
	cfg **children;      /* per member: a view when opened as an object */
	cfg ***items;        /* per member when it is an array of objects */
	size_t *nitems;
	int nmembers;
};

static cfg *view_new(cJSON *json, const char *source, const char *path)
{
	cfg *c = xcalloc(1, sizeof *c);
	c->json = json;
	c->source = (char *)source;
	c->path = xstrdup(path);
	c->nmembers = cJSON_GetArraySize(json);
	c->used = xcalloc((size_t)c->nmembers, 1);
	c->children = xcalloc((size_t)c->nmembers, sizeof *c->children);
	c->items = xcalloc((size_t)c->nmembers, sizeof *c->items);
	c->nitems = xcalloc((size_t)c->nmembers, sizeof *c->nitems);
	return c;
}

static void view_free(cfg *c)
{
	if (!c)
		return;
	for (int k = 0; k < c->nmembers; k++) {
		view_free(c->children[k]);
		for (size_t i = 0; i < c->nitems[k]; i++)
			view_free(c->items[k][i]);
		free(c->items[k]);
	}
	free(c->children);
	free(c->items);
	free(c->nitems);
	free(c->used);
	free(c->path);
	free(c);
}

void cfg_free(cfg *c)
{
	if (!c)
		return;
	cJSON *root = c->root;
	char *source = c->source;
	view_free(c);
	cJSON_Delete(root);
	free(source);
}

cfg *cfg_parse(const char *text, const char *source)
{
	/* Nothing but white space may follow the object. */
	cJSON *root = cJSON_ParseWithOpts(text, NULL, 1);
	if (!root) {
		const char *at = cJSON_GetErrorPtr();
		int line = 1;
		for (const char *p = text; at && p < at && *p; p++)
			line += *p == '\n';
		err_set("%s: line %d: not valid JSON", source, line);
		return NULL;
	}
	if (!cJSON_IsObject(root)) {
		cJSON_Delete(root);
		err_set("%s: expected a JSON object at the top level", source);
		return NULL;
	}
	char *src = xstrdup(source);
	cfg *c = view_new(root, src, "");
	c->root = root;
	return c;
}

cfg *cfg_load(const char *path)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		err_set("%s: cannot open: %s", path, strerror(errno));
		return NULL;
	}
	size_t cap = 1 << 14, len = 0;
	char *text = xmalloc(cap);
	size_t got;
	while ((got = fread(text + len, 1, cap - len - 1, f)) > 0) {
		len += got;
		if (len + 1 == cap)
			text = xrealloc(text, cap *= 2);
	}
	int bad = ferror(f) ? errno : 0;
	fclose(f);
	if (bad) {
		free(text);
		err_set("%s: cannot read: %s", path, strerror(bad));
		return NULL;
	}
	text[len] = '\0';
	cfg *c = cfg_parse(text, path);
	free(text);
	return c;
}

const char *cfg_source(const cfg *c) { return c->source; }
const char *cfg_path(const cfg *c) { return c->path; }
char *cfg_text(const cfg *c) { return cJSON_PrintUnformatted(c->json); }

cJSON *cfg_load_json(const char *path)
{
	cfg *c = cfg_load(path);
	if (!c)
		return NULL;
	cJSON *j = cJSON_Duplicate(c->json, 1);
	cfg_free(c);
	return j;
}

static void full_key(const cfg *c, const char *key, char *buf, size_t n)
{
	if (c->path[0])
		snprintf(buf, n, "%s.%s", c->path, key);
	else
		snprintf(buf, n, "%s", key);
}

/* Whether b looks like a, mistyped: the same but for case, '_' or '-',
 * two neighbouring letters swapped, or one letter more or less (not one
 * letter for another: "mu1" and "mu2" are two keys). */
static int mistyped(const char *a, const char *b)
{
	char x[128], y[128];
	size_t n = 0, m = 0;
	for (; *a && n + 1 < sizeof x; a++)
		if (*a != '_' && *a != '-')
			x[n++] = (char)tolower((unsigned char)*a);
	for (; *b && m + 1 < sizeof y; b++)
		if (*b != '_' && *b != '-')
			y[m++] = (char)tolower((unsigned char)*b);
	x[n] = y[m] = '\0';
	if (n == m) {
		size_t i = 0;
		while (i < n && x[i] == y[i])
			i++;
		return i == n || (i + 1 < n && x[i] == y[i + 1] && x[i + 1] == y[i] &&
		                  strcmp(x + i + 2, y + i + 2) == 0);
	}
	if (n + 1 != m && m + 1 != n)
		return 0;
	const char *l = n > m ? x : y, *sh = n > m ? y : x;
	size_t i = 0;
	while (sh[i] && sh[i] == l[i])
		i++;
	return strcmp(sh + i, l + i + 1) == 0;
}

int cfg_error(const cfg *c, const char *key, const char *fmt, ...)
{
	char what[1024], name[512];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(what, sizeof what, fmt, ap);
	va_end(ap);
	full_key(c, key, name, sizeof name);
	/* A key missing where one like it is given: name that one. */
	if (strncmp(what, "missing", 7) == 0)
		for (cJSON *m = c->json->child; m; m = m->next)
			if (m->string && strcmp(m->string, key) != 0 && mistyped(key, m->string)) {
				size_t len = strlen(what);
				snprintf(what + len, sizeof what - len, " (found '%s': misspelt?)",
				         m->string);
				break;
			}
	return err_set("%s: key '%s': %s", c->source, name, what);
}

/* The member named key and its index, marking it used; NULL if absent. */
static cJSON *member(const cfg *c, const char *key, int *index)
{
	int k = 0;
	for (cJSON *m = c->json->child; m; m = m->next, k++)
		if (m->string && strcmp(m->string, key) == 0) {
			c->used[k] = 1;
			if (index)
				*index = k;
			return m;
		}
	return NULL;
}

int cfg_has(const cfg *c, const char *key)
{
	return cJSON_GetObjectItemCaseSensitive(c->json, key) != NULL;
}

static void describe(char *buf, size_t n, cJSON *v)
{
	if (cJSON_IsNumber(v) && !isfinite(v->valuedouble)) { /* cJSON prints it as null */
		snprintf(buf, n, "%s (beyond the range of a double)",
		         v->valuedouble > 0 ? "+inf" : "-inf");
		return;
	}
	char *text = cJSON_PrintUnformatted(v);
	snprintf(buf, n, "%s", text ? text : "?");
	if (strlen(buf) > 60)
		strcpy(buf + 56, "...");
	free(text);
}

static void range_text(char *buf, size_t n, double lo, double hi, const char *unit)
{
	char u[64] = "";
	if (unit && unit[0])
		snprintf(u, sizeof u, " (%s)", unit);
	if (lo == CFG_POS && hi == INFINITY)
		snprintf(buf, n, "a positive number%s", u);
	else if (lo == 0 && hi == INFINITY)
		snprintf(buf, n, "a non-negative number%s", u);
	else if (lo == -INFINITY && hi == INFINITY)
		snprintf(buf, n, "a number%s", u);
	else if (hi == INFINITY)
		snprintf(buf, n, "a number >= %g%s", lo, u);
	else if (lo == -INFINITY)
		snprintf(buf, n, "a number <= %g%s", hi, u);
	else if (lo == CFG_POS)
		snprintf(buf, n, "a number in (0, %g]%s", hi, u);
	else
		snprintf(buf, n, "a number in [%g, %g]%s", lo, hi, u);
}

static int check_number(const cfg *c, const char *key, cJSON *v, double *out, const char *unit,
                        double lo, double hi)
{
	char expected[160], got[80];
	range_text(expected, sizeof expected, lo, hi, unit);
	describe(got, sizeof got, v);
	if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble) || v->valuedouble < lo ||
	    v->valuedouble > hi)
		return cfg_error(c, key, "value %s: expected %s", got, expected);
	*out = v->valuedouble;
	return 0;
}

int cfg_number_or(cfg *c, const char *key, double *out, double def, const char *unit, double lo,
                  double hi)
{
	cJSON *v = member(c, key, NULL);
	if (!v) {
		*out = def;
		return 0;
	}
	return check_number(c, key, v, out, unit, lo, hi);
}

int cfg_number(cfg *c, const char *key, double *out, const char *unit, double lo, double hi)
{
	cJSON *v = member(c, key, NULL);
	if (!v) {
		char expected[160];
		range_text(expected, sizeof expected, lo, hi, unit);
		return cfg_error(c, key, "missing: expected %s", expected);
	}
	return check_number(c, key, v, out, unit, lo, hi);
}

static int check_integer(const cfg *c, const char *key, cJSON *v, long *out, long lo, long hi)
{
	char got[80];
	describe(got, sizeof got, v);
	/* The range first, as doubles: converting a double beyond a long to a
	 * long is undefined. (double)hi + 1 is exact where it matters (it is
	 * 2^63 for LONG_MAX). */
	double d = cJSON_IsNumber(v) ? v->valuedouble : NAN;
	if (!(d >= (double)lo && d < (double)hi + 1 && d == floor(d)) || (long)d > hi)
		return cfg_error(c, key, "value %s: expected an integer in [%ld, %ld]", got, lo,
		                 hi);
	*out = (long)d;
	return 0;
}

int cfg_integer(cfg *c, const char *key, long *out, long lo, long hi)
{
	cJSON *v = member(c, key, NULL);
	if (!v)
		return cfg_error(c, key, "missing: expected an integer in [%ld, %ld]", lo, hi);
	return check_integer(c, key, v, out, lo, hi);
}

int cfg_integer_or(cfg *c, const char *key, long *out, long def, long lo, long hi)
{
	cJSON *v = member(c, key, NULL);
	if (!v) {
		*out = def;
		return 0;
	}
	return check_integer(c, key, v, out, lo, hi);
}

static int check_string(const cfg *c, const char *key, cJSON *v, const char **out)
{
	char got[80];
	describe(got, sizeof got, v);
	if (!cJSON_IsString(v))
		return cfg_error(c, key, "value %s: expected a string", got);
	*out = v->valuestring;
	return 0;
}

int cfg_string(cfg *c, const char *key, const char **out)
{
	cJSON *v = member(c, key, NULL);
	if (!v)
		return cfg_error(c, key, "missing: expected a string");
	return check_string(c, key, v, out);
}

int cfg_string_or(cfg *c, const char *key, const char **out, const char *def)
{
	cJSON *v = member(c, key, NULL);
	if (!v) {
		*out = def;
		return 0;
	}
	return check_string(c, key, v, out);
}

int cfg_bool_or(cfg *c, const char *key, int *out, int def)
{
	cJSON *v = member(c, key, NULL);
	if (!v) {
		*out = def;
		return 0;
	}
	if (!cJSON_IsBool(v)) {
		char got[80];
		describe(got, sizeof got, v);
		return cfg_error(c, key, "value %s: expected true or false", got);
	}
	*out = cJSON_IsTrue(v);
	return 0;
}

int cfg_choice_or(cfg *c, const char *key, int *out, const char *const *words, int def)
{
	const char *s = NULL;
	if (cfg_string_or(c, key, &s, NULL))
		return -1;
	if (!s) {
		*out = def;
		return 0;
	}
	char list[512] = "";
	for (int k = 0; words[k]; k++) {
		if (strcmp(s, words[k]) == 0) {
			*out = k;
			return 0;
		}
		size_t len = strlen(list);
		snprintf(list + len, sizeof list - len, "%s'%s'", k ? ", " : "", words[k]);
	}
	return cfg_error(c, key, "value \"%s\": expected one of %s", s, list);
}

int cfg_numbers(cfg *c, const char *key, double **out, size_t *count, size_t n, const char *unit,
                double lo, double hi)
{
	cJSON *v = member(c, key, NULL);
	char shape[64];
	if (n)
		snprintf(shape, sizeof shape, "an array of %zu numbers", n);
	else
		snprintf(shape, sizeof shape, "a non-empty array of numbers");
	if (!v)
		return cfg_error(c, key, "missing: expected %s", shape);
	size_t len = cJSON_IsArray(v) ? (size_t)cJSON_GetArraySize(v) : 0;
	if (!cJSON_IsArray(v) || len == 0 || (n && len != n)) {
		char got[80];
		describe(got, sizeof got, v);
		return cfg_error(c, key, "value %s: expected %s", got, shape);
	}
	double *a = xmalloc(len * sizeof *a);
	size_t k = 0;
	char elem[600];
	for (cJSON *e = v->child; e; e = e->next, k++) {
		snprintf(elem, sizeof elem, "%s[%zu]", key, k);
		if (check_number(c, elem, e, &a[k], unit, lo, hi)) {
			free(a);
			return -1;
		}
	}
	*out = a;
	if (count)
		*count = len;
	return 0;
}

char *cfg_member_text(cfg *c, const char *key)
{
	cJSON *v = member(c, key, NULL);
	return v ? cJSON_PrintUnformatted(v) : NULL;
}

static cfg *child_view(cfg *c, const char *key, int required)
{
	int k;
	cJSON *v = member(c, key, &k);
	if (!v) {
		if (required)
			cfg_error(c, key, "missing: expected an object");
		return NULL;
	}
	if (!cJSON_IsObject(v)) {
		char got[80];
		describe(got, sizeof got, v);
		cfg_error(c, key, "value %s: expected an object", got);
		return NULL;
	}
	if (!c->children[k]) {
		char name[512];
		full_key(c, key, name, sizeof name);
		c->children[k] = view_new(v, c->source, name);
	}
	return c->children[k];
}

cfg *cfg_object(cfg *c, const char *key) { return child_view(c, key, 1); }

cfg *cfg_object_opt(cfg *c, const char *key)
{
	err_clear();
	cfg *v = child_view(c, key, 0);
	return v;
}

/* The items of an array-of-objects member, created on first use. */
static cfg **list_views(cfg *c, const char *key, size_t *n)
{
	int k;
	cJSON *v = member(c, key, &k);
	*n = 0;
	if (!v)
		return NULL;
	if (!cJSON_IsArray(v))
		goto bad;
	for (cJSON *e = v->child; e; e = e->next)
		if (!cJSON_IsObject(e))
			goto bad;
	if (!c->items[k]) {
		size_t len = (size_t)cJSON_GetArraySize(v), i = 0;
		cfg **views = xcalloc(len, sizeof *views);
		char name[600], base[512];
		full_key(c, key, base, sizeof base);
		for (cJSON *e = v->child; e; e = e->next, i++) {
			snprintf(name, sizeof name, "%s[%zu]", base, i);
			views[i] = view_new(e, c->source, name);
		}
		c->items[k] = views;
		c->nitems[k] = len;
	}
	*n = c->nitems[k];
	return c->items[k];
bad:
	cfg_error(c, key, "expected an array of objects");
	*n = (size_t)-1;
	return NULL;
}

long cfg_list(cfg *c, const char *key)
{
	size_t n;
	list_views(c, key, &n);
	return n == (size_t)-1 ? -1 : (long)n;
}

cfg *cfg_item(cfg *c, const char *key, size_t k)
{
	size_t n;
	cfg **views = list_views(c, key, &n);
	if (!views || n == (size_t)-1 || k >= n)
		return NULL;
	return views[k];
}

int cfg_check_unused(const cfg *c)
{
	int k = 0;
	for (cJSON *m = c->json->child; m; m = m->next, k++) {
		if (!c->used[k]) {
			for (cJSON *p = c->json->child; p != m; p = p->next)
				if (strcmp(p->string, m->string) == 0)
					return cfg_error(c, m->string, "given twice");
			return cfg_error(c, m->string,
			                 "unknown key (misspelt, or not used by this program)");
		}
		if (c->children[k] && cfg_check_unused(c->children[k]))
			return -1;
		for (size_t i = 0; i < c->nitems[k]; i++)
			if (cfg_check_unused(c->items[k][i]))
				return -1;
	}
	return 0;
}
