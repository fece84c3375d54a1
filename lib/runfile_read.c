/* The run file's reader (post, and solve --restart): everything but the
 * snapshots' contents at once, then one snapshot at a time. The layout is
 * share/doc/format.md; the writer is runfile_write.c. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"
#include "lib/h5.h"
#include "lib/runfile.h"
#include "lib/runfile_layout.h"

void bonds_free(dem_bonds *b)
{
	free(b->i), free(b->j), free(b->d0), free(b->area), free(b->kn), free(b->ks);
	memset(b, 0, sizeof *b);
}

static int read_bonds(hid_t f, dem_bonds *b, size_t nparticles)
{
	if (!h5_exists(f, "bonds"))
		return 0; /* a run stopped before its bonds formed */
	hid_t g = h5_open_group(f, "bonds");
	int rc = h5_read(g, "i", H5T_NATIVE_INT32, (void **)&b->i, &b->n, 0) ||
	         h5_read_n(g, "j", H5T_NATIVE_INT32, (void **)&b->j, b->n, 0) ||
	         h5_read_n(g, "d0", H5T_NATIVE_DOUBLE, (void **)&b->d0, b->n, 0) ||
	         h5_read_n(g, "area", H5T_NATIVE_DOUBLE, (void **)&b->area, b->n, 0) ||
	         h5_read_n(g, "kn", H5T_NATIVE_DOUBLE, (void **)&b->kn, b->n, 0) ||
	         h5_read_n(g, "ks", H5T_NATIVE_DOUBLE, (void **)&b->ks, b->n, 0);
	H5Gclose(g);
	if (rc)
		return -1;
	for (size_t k = 0; k < b->n; k++)
		if (b->i[k] < 0 || b->j[k] < 0 || (size_t)b->i[k] >= nparticles ||
		    (size_t)b->j[k] >= nparticles)
			return err_set(
			    "%s: dataset '/bonds/i' or '/bonds/j': particle index out of range "
			    "at bond %zu",
			    h5_name(f), k);
	return 0;
}

static int read_history(hid_t f, dem_run *r)
{
	hid_t h = h5_open_group(f, "history");
	if (h < 0)
		return -1;
	char *order = h5_read_attr_str(h, "columns");
	int rc = order ? 0 : -1;
	if (!rc) {
		int n = run_column_count(order);
		r->ncols = n;
		r->col_name = xcalloc((size_t)n, sizeof *r->col_name);
		r->col_unit = xcalloc((size_t)n, sizeof *r->col_unit);
		r->col = xcalloc((size_t)n, sizeof *r->col);
		char *save = NULL, *tok = strtok_r(order, ",", &save);
		for (int c = 0; !rc && tok; c++, tok = strtok_r(NULL, ",", &save)) {
			r->col_name[c] = xstrdup(tok);
			size_t rows = 0;
			rc = c == 0
			         ? h5_read(h, tok, H5T_NATIVE_DOUBLE, (void **)&r->col[c], &rows, 0)
			         : h5_read_n(h, tok, H5T_NATIVE_DOUBLE, (void **)&r->col[c],
			                     r->nrows, 0);
			if (c == 0)
				r->nrows = rows;
			if (!rc)
				rc = !(r->col_unit[c] = h5_read_units(h, tok));
		}
	}
	free(order);
	H5Gclose(h);
	return rc;
}

typedef struct {
	size_t n, cap;
	int64_t *step;
} step_list;

static herr_t collect_snapshot(hid_t g, const char *name, const H5L_info_t *info, void *data)
{
	(void)g, (void)info;
	step_list *l = data;
	char *end;
	long long step = strtoll(name, &end, 10);
	if (*end || end == name)
		return 0;
	if (l->n == l->cap)
		l->step = xrealloc(l->step, (l->cap = l->cap ? 2 * l->cap : 16) * sizeof *l->step);
	l->step[l->n++] = step;
	return 0;
}

static int cmp_i64(const void *a, const void *b)
{
	int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
	return (x > y) - (x < y);
}

size_t run_snapshot_steps(hid_t g, int64_t **steps)
{
	step_list l = {0};
	H5Literate(g, H5_INDEX_NAME, H5_ITER_NATIVE, NULL, collect_snapshot, &l);
	if (l.n) /* a run without snapshots has no list: qsort must not get NULL */
		qsort(l.step, l.n, sizeof *l.step, cmp_i64);
	*steps = l.step;
	return l.n;
}

static int read_snapshot_index(hid_t f, dem_run *r)
{
	hid_t g = h5_open_group(f, "snapshots");
	if (g < 0)
		return -1;
	step_list l = {0};
	l.n = run_snapshot_steps(g, &l.step);
	r->nsnap = l.n;
	r->snap_step = l.step;
	r->snap_t = xcalloc(l.n, sizeof *r->snap_t);
	r->snap_strain = xcalloc(l.n, sizeof *r->snap_strain);
	r->snap_stress = xcalloc(l.n, sizeof *r->snap_stress);
	int rc = 0;
	for (size_t k = 0; !rc && k < l.n; k++) {
		char name[64];
		snprintf(name, sizeof name, RUN_SNAPSHOT, l.step[k]);
		hid_t s = H5Gopen2(g, name, H5P_DEFAULT);
		rc = s < 0 || h5_read_attr_f64(s, "t", &r->snap_t[k]) ||
		     h5_read_attr_f64(s, "strain_axial", &r->snap_strain[k]) ||
		     h5_read_attr_f64(s, "stress_axial", &r->snap_stress[k]);
		if (s >= 0)
			H5Gclose(s);
	}
	H5Gclose(g);
	return rc ? -1 : 0;
}

static int read_cracks(hid_t f, dem_run *r)
{
	hid_t g = h5_open_group(f, "cracks");
	if (g < 0)
		return -1;
	double *t = NULL, *e = NULL, *rad = NULL, *fn = NULL, *fs = NULL, *x = NULL, *nn = NULL;
	int64_t *step = NULL;
	int32_t *i = NULL, *j = NULL, *mode = NULL;
	size_t n = 0;
	int rc = h5_read(g, "t", H5T_NATIVE_DOUBLE, (void **)&t, &n, 0) ||
	         h5_read_n(g, "strain_axial", H5T_NATIVE_DOUBLE, (void **)&e, n, 0) ||
	         h5_read_n(g, "step", H5T_NATIVE_INT64, (void **)&step, n, 0) ||
	         h5_read_n(g, "i", H5T_NATIVE_INT32, (void **)&i, n, 0) ||
	         h5_read_n(g, "j", H5T_NATIVE_INT32, (void **)&j, n, 0) ||
	         h5_read_n(g, "mode", H5T_NATIVE_INT32, (void **)&mode, n, 0) ||
	         h5_read_n(g, "x", H5T_NATIVE_DOUBLE, (void **)&x, n, 3) ||
	         h5_read_n(g, "normal", H5T_NATIVE_DOUBLE, (void **)&nn, n, 3) ||
	         h5_read_n(g, "radius", H5T_NATIVE_DOUBLE, (void **)&rad, n, 0) ||
	         h5_read_n(g, "fn", H5T_NATIVE_DOUBLE, (void **)&fn, n, 0) ||
	         h5_read_n(g, "fs", H5T_NATIVE_DOUBLE, (void **)&fs, n, 0);
	H5Gclose(g);
	if (!rc) {
		r->ncracks = n;
		r->cracks = xcalloc(n, sizeof *r->cracks);
		for (size_t k = 0; k < n; k++) {
			dem_crack *c = &r->cracks[k];
			c->t = t[k];
			c->strain_axial = e[k];
			c->step = step[k];
			c->i = i[k];
			c->j = j[k];
			c->mode = mode[k];
			c->radius = rad[k];
			c->fn = fn[k];
			c->fs = fs[k];
			memcpy(c->x, x + 3 * k, sizeof c->x);
			memcpy(c->normal, nn + 3 * k, sizeof c->normal);
		}
	}
	free(t), free(e), free(rad), free(fn), free(fs), free(x), free(nn), free(step);
	free(i), free(j), free(mode);
	return rc ? -1 : 0;
}

/* The history's row count (its first column's), into r->nrows. */
static int history_rows(hid_t f, dem_run *r)
{
	hid_t h = h5_open_group(f, "history");
	if (h < 0)
		return -1;
	char *order = h5_read_attr_str(h, "columns"), *save = NULL;
	char *first = order ? strtok_r(order, ",", &save) : NULL;
	long long rows = first ? h5_rows_of(h, first) : -1;
	if (order && rows < 0)
		err_set("%s: history: no readable first column", h5_name(f));
	free(order);
	H5Gclose(h);
	if (rows < 0)
		return -1;
	r->nrows = (size_t)rows;
	return 0;
}

/* The run in file f; with head, only what run_read_head reads, of the
 * assembly part `part` of `parts`. */
static int read_run(hid_t f, dem_run *r, int head, int part, int parts)
{
	memset(r, 0, sizeof *r);
	int rc = prov_read(f, &r->prov) || !(r->status = h5_read_attr_str(f, "status")) ||
	         assembly_read_groups_part(f, part, parts, &r->assembly) ||
	         (head ? history_rows(f, r)
	               : read_bonds(f, &r->bonds, r->assembly.n) || read_history(f, r) ||
	                     read_snapshot_index(f, r) || read_cracks(f, r));
	if (rc) {
		run_free(r);
		return -1;
	}
	return 0;
}

static int read_path(const char *path, dem_run *r, int head, int part, int parts)
{
	memset(r, 0, sizeof *r);
	hid_t f = h5_open(path, RUN_FORMAT, 0);
	if (f < 0)
		return -1;
	int rc = read_run(f, r, head, part, parts);
	H5Fclose(f);
	if (!rc)
		snprintf(r->assembly.file, sizeof r->assembly.file, "%s", path);
	return rc;
}

int run_read_file(hid_t f, dem_run *r) { return read_run(f, r, 0, 0, 1); }
int run_read(const char *path, dem_run *r) { return read_path(path, r, 0, 0, 1); }
int run_read_head(const char *path, dem_run *r) { return read_path(path, r, 1, 0, 1); }
int run_read_head_part(const char *path, int part, int parts, dem_run *r)
{
	return read_path(path, r, 1, part, parts);
}

void run_free(dem_run *r)
{
	prov_free(&r->prov);
	free(r->status);
	assembly_free(&r->assembly);
	bonds_free(&r->bonds);
	for (int c = 0; c < r->ncols; c++) {
		free(r->col_name ? r->col_name[c] : NULL);
		free(r->col_unit ? r->col_unit[c] : NULL);
		free(r->col ? r->col[c] : NULL);
	}
	free(r->col_name), free(r->col_unit), free(r->col);
	free(r->snap_step), free(r->snap_t), free(r->snap_strain), free(r->snap_stress);
	free(r->cracks);
	memset(r, 0, sizeof *r);
}

const double *run_column_data(const dem_run *r, const char *name)
{
	for (int c = 0; c < r->ncols; c++)
		if (strcmp(r->col_name[c], name) == 0)
			return r->col[c];
	return NULL;
}

void snapshot_free(dem_snapshot *s)
{
	free(s->x), free(s->v), free(s->w), free(s->state);
	free(s->damage_n), free(s->damage_s), free(s->fn), free(s->fs);
	memset(s, 0, sizeof *s);
}

int run_read_snapshot_file(hid_t f, const dem_run *r, size_t k, dem_snapshot *s)
{
	memset(s, 0, sizeof *s);
	if (k >= r->nsnap)
		return err_set("%s: snapshot %zu: out of range (the run has %zu)", h5_name(f), k,
		               r->nsnap);
	char name[64];
	snprintf(name, sizeof name, "snapshots/" RUN_SNAPSHOT, r->snap_step[k]);
	hid_t g = h5_open_group(f, name);
	size_t n = r->assembly.n, nb = r->bonds.n;
	int rc = g < 0 || h5_read_attr_i64(g, "step", &s->step) ||
	         h5_read_attr_f64(g, "t", &s->t) ||
	         h5_read_attr_f64(g, "strain_axial", &s->strain_axial) ||
	         h5_read_attr_f64(g, "stress_axial", &s->stress_axial) ||
	         h5_read_n(g, "x", H5T_NATIVE_DOUBLE, (void **)&s->x, n, 3) ||
	         h5_read_n(g, "v", H5T_NATIVE_DOUBLE, (void **)&s->v, n, 3) ||
	         h5_read_n(g, "w", H5T_NATIVE_DOUBLE, (void **)&s->w, n, 3) ||
	         h5_read_n(g, "bond_state", H5T_NATIVE_UINT8, (void **)&s->state, nb, 0) ||
	         h5_read_n(g, "bond_damage_n", H5T_NATIVE_DOUBLE, (void **)&s->damage_n, nb, 0) ||
	         h5_read_n(g, "bond_damage_s", H5T_NATIVE_DOUBLE, (void **)&s->damage_s, nb, 0) ||
	         h5_read_n(g, "bond_fn", H5T_NATIVE_DOUBLE, (void **)&s->fn, nb, 0) ||
	         h5_read_n(g, "bond_fs", H5T_NATIVE_DOUBLE, (void **)&s->fs, nb, 3);
	if (g >= 0)
		H5Gclose(g);
	s->n = n;
	s->nbonds = nb;
	if (rc) {
		snapshot_free(s);
		return -1;
	}
	return 0;
}

int run_read_snapshot(const char *path, const dem_run *r, size_t k, dem_snapshot *s)
{
	memset(s, 0, sizeof *s);
	hid_t f = h5_open(path, RUN_FORMAT, 0);
	if (f < 0)
		return -1;
	int rc = run_read_snapshot_file(f, r, k, s);
	H5Fclose(f);
	return rc;
}
