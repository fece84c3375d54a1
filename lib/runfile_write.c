/* The run file's writer (solve): create or continue a run file, then
 * append history rows, snapshots and cracks, and commit it under its final
 * name. The layout is share/doc/format.md; the reader is runfile_read.c. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lib/afile.h"
#include "lib/err.h"
#include "lib/h5.h"
#include "lib/runfile.h"
#include "lib/runfile_layout.h"

enum { HISTORY_BUFFER_ROWS = 256 };

struct run_writer {
	hid_t file;
	char path[4096], tmp[4096];
	int ncols;
	char **names;
	size_t buffered;
	double *buffer; /* [ncols][HISTORY_BUFFER_ROWS], column-major */
};

hid_t run_hid(run_writer *w) { return w->file; }

static void writer_free(run_writer *w)
{
	for (int c = 0; c < w->ncols; c++)
		free(w->names[c]);
	free(w->names);
	free(w->buffer);
	free(w);
}

run_writer *run_create(const char *path, const dem_provenance *prov, const dem_assembly *a,
                       const run_column *cols, int ncols)
{
	run_writer *w = xcalloc(1, sizeof *w);
	snprintf(w->path, sizeof w->path, "%s", path);
	w->file = h5_create(path, w->tmp, sizeof w->tmp);
	if (w->file < 0) {
		free(w);
		return NULL;
	}
	w->ncols = ncols;
	w->names = xcalloc((size_t)ncols, sizeof *w->names);
	w->buffer = xmalloc((size_t)ncols * HISTORY_BUFFER_ROWS * sizeof *w->buffer);
	int rc = prov_write(w->file, RUN_FORMAT, prov) ||
	         h5_attr_str(w->file, "status", "running") || assembly_write_groups(w->file, a);
	hid_t h = rc ? -1 : h5_group(w->file, "history");
	rc = rc || h < 0;
	for (int c = 0; !rc && c < ncols; c++) {
		w->names[c] = xstrdup(cols[c].name);
		rc = h5_create_ext(h, cols[c].name, H5T_NATIVE_DOUBLE, 0, cols[c].unit);
	}
	if (h >= 0) {
		/* Column order, so readers list them as the writer meant. */
		size_t len = 1;
		for (int c = 0; c < ncols; c++)
			len += strlen(cols[c].name) + 1;
		char *order = xcalloc(len, 1);
		for (int c = 0; c < ncols; c++) {
			strcat(order, cols[c].name);
			if (c + 1 < ncols)
				strcat(order, ",");
		}
		rc = rc || h5_attr_str(h, "columns", order);
		free(order);
		H5Gclose(h);
	}
	hid_t g = rc ? -1 : h5_group(w->file, "snapshots");
	if (g >= 0)
		H5Gclose(g);
	rc = rc || g < 0;
	hid_t k = rc ? -1 : h5_group(w->file, "cracks");
	rc = rc || k < 0;
	if (!rc) {
		rc = h5_create_ext(k, "t", H5T_NATIVE_DOUBLE, 0, "s") ||
		     h5_create_ext(k, "strain_axial", H5T_NATIVE_DOUBLE, 0, "") ||
		     h5_create_ext(k, "step", H5T_NATIVE_INT64, 0, "") ||
		     h5_create_ext(k, "i", H5T_NATIVE_INT32, 0, "") ||
		     h5_create_ext(k, "j", H5T_NATIVE_INT32, 0, "") ||
		     h5_create_ext(k, "mode", H5T_NATIVE_INT32, 0, "") ||
		     h5_create_ext(k, "x", H5T_NATIVE_DOUBLE, 3, "m") ||
		     h5_create_ext(k, "normal", H5T_NATIVE_DOUBLE, 3, "") ||
		     h5_create_ext(k, "radius", H5T_NATIVE_DOUBLE, 0, "m") ||
		     h5_create_ext(k, "fn", H5T_NATIVE_DOUBLE, 0, "N") ||
		     h5_create_ext(k, "fs", H5T_NATIVE_DOUBLE, 0, "N");
		H5Gclose(k);
	}
	if (rc) {
		run_abort(w);
		return NULL;
	}
	return w;
}

static const char *const crack_columns[] = {"t", "strain_axial", "step",   "i",  "j", "mode",
                                            "x", "normal",       "radius", "fn", "fs"};

static int copy_file(const char *from, const char *to)
{
	FILE *in = fopen(from, "rb");
	if (!in)
		return err_set("%s: cannot open: %s", from, strerror(errno));
	FILE *out = fopen(to, "wb");
	if (!out) {
		fclose(in);
		return err_set("%s: cannot create: %s", to, strerror(errno));
	}
	char buf[1 << 16];
	size_t got;
	int rc = 0;
	while (!rc && (got = fread(buf, 1, sizeof buf, in)) > 0)
		rc = fwrite(buf, 1, got, out) != got;
	rc = rc || ferror(in);
	fclose(in);
	if (fclose(out) || rc)
		return h5_write_error(to, "a copy of the run file");
	return 0;
}

void run_recovery_name(const char *path, char *out, size_t n) { snprintf(out, n, "%s.ckpt", path); }

int run_save_recovery(run_writer *w)
{
	char final[4200], tmp[4300];
	run_recovery_name(w->path, final, sizeof final);
	if (run_flush(w))
		return -1;
	if (H5Fflush(w->file, H5F_SCOPE_GLOBAL) < 0)
		return h5_write_error(w->tmp, "the run file");
	if (afile_begin(final, tmp, sizeof tmp))
		return -1;
	hid_t f = copy_file(w->tmp, tmp) ? -1 : h5_open(tmp, RUN_FORMAT, 1);
	if (f < 0 || h5_attr_str(f, "status", "interrupted")) {
		if (f >= 0)
			H5Fclose(f);
		afile_discard(tmp);
		return err_set("%s: cannot write the recovery copy %s: %s", w->path, final,
		               err_msg());
	}
	return h5_commit(f, tmp, final);
}

run_writer *run_reopen(const char *from, const char *path, size_t history_rows, size_t crack_rows)
{
	run_writer *w = xcalloc(1, sizeof *w);
	snprintf(w->path, sizeof w->path, "%s", path);
	if (afile_begin(path, w->tmp, sizeof w->tmp)) {
		free(w);
		return NULL;
	}
	if (copy_file(from, w->tmp)) {
		afile_discard(w->tmp);
		free(w);
		return NULL;
	}
	w->file = h5_open(w->tmp, RUN_FORMAT, 1);
	if (w->file < 0) {
		afile_discard(w->tmp);
		free(w);
		return NULL;
	}
	hid_t h = h5_open_group(w->file, "history");
	char *order = h >= 0 ? h5_read_attr_str(h, "columns") : NULL;
	int rc = order ? 0 : -1;
	if (order) {
		int n = run_column_count(order);
		w->ncols = n;
		w->names = xcalloc((size_t)n, sizeof *w->names);
		w->buffer = xmalloc((size_t)n * HISTORY_BUFFER_ROWS * sizeof *w->buffer);
		char *save = NULL, *tok = strtok_r(order, ",", &save);
		for (int c = 0; tok; c++, tok = strtok_r(NULL, ",", &save)) {
			w->names[c] = xstrdup(tok);
			rc = rc || h5_truncate(h, tok, history_rows);
		}
	}
	free(order);
	if (h >= 0)
		H5Gclose(h);
	hid_t k = rc ? -1 : h5_open_group(w->file, "cracks");
	for (size_t c = 0; k >= 0 && !rc && c < sizeof crack_columns / sizeof *crack_columns; c++)
		rc = h5_truncate(k, crack_columns[c], crack_rows);
	if (k >= 0)
		H5Gclose(k);
	rc = rc || k < 0 || h5_attr_str(w->file, "status", "running");
	if (rc) {
		run_abort(w);
		return NULL;
	}
	return w;
}

/* The datasets of the bond table and of a snapshot, in file order (the
 * field numbers of runfile.h). per_bond: rows are bonds, else particles. */
enum { F64, I32, U8 };
typedef struct {
	const char *name;
	int type, per_bond;
	size_t cols;
	const char *unit;
} rec_field;

static const rec_field bond_fields[BTAB_NFIELDS] = {
    {"i", I32, 1, 0, NULL},     {"j", I32, 1, 0, NULL},   {"d0", F64, 1, 0, "m"},
    {"area", F64, 1, 0, "m^2"}, {"kn", F64, 1, 0, "N/m"}, {"ks", F64, 1, 0, "N/m"},
};
static const rec_field snap_fields[SNAP_NFIELDS] = {
    {"x", F64, 0, 3, "m"},
    {"v", F64, 0, 3, "m/s"},
    {"w", F64, 0, 3, "rad/s"},
    {"bond_state", U8, 1, 0, NULL},
    {"bond_damage_n", F64, 1, 0, NULL},
    {"bond_damage_s", F64, 1, 0, NULL},
    {"bond_fn", F64, 1, 0, "N"},
    {"bond_fs", F64, 1, 3, "N"},
};

static size_t row_bytes(const rec_field *f)
{
	return (f->cols ? f->cols : 1) * (f->type == F64 ? 8 : f->type == I32 ? 4 : 1);
}

/* Each field a piece at a time: memory is one piece, not the whole arrays. */
static int write_fields(hid_t g, const rec_field *fs, int nf, size_t np, size_t nb, run_fill fill,
                        void *ctx)
{
	unsigned char *buf = xmalloc(H5_PIECE_ELEMENTS * sizeof(double));
	int rc = 0;
	for (int f = 0; !rc && f < nf; f++) {
		hid_t type = fs[f].type == F64   ? H5T_NATIVE_DOUBLE
		             : fs[f].type == I32 ? H5T_NATIVE_INT32
		                                 : H5T_NATIVE_UINT8;
		h5_rows r;
		rc = h5_rows_open(&r, g, fs[f].name, type, fs[f].per_bond ? nb : np, fs[f].cols,
		                  fs[f].unit);
		for (size_t m; !rc && (m = h5_rows_piece(&r)) > 0;) {
			fill(ctx, f, r.at, m, buf);
			rc = h5_rows_put(&r, buf, m);
		}
		rc = h5_rows_close(&r) || rc;
	}
	free(buf);
	return rc ? -1 : 0;
}

/* A fill from whole arrays, one per field. */
typedef struct {
	const rec_field *fs;
	const void *const *src;
} arrays;

static void from_arrays(void *ctx, int f, size_t at, size_t m, void *buf)
{
	const arrays *a = ctx;
	size_t row = row_bytes(&a->fs[f]);
	memcpy(buf, (const unsigned char *)a->src[f] + at * row, m * row);
}

int run_write_bonds_fill(run_writer *w, size_t n, run_fill fill, void *ctx)
{
	hid_t g = h5_group(w->file, "bonds");
	if (g < 0)
		return -1;
	int rc = write_fields(g, bond_fields, BTAB_NFIELDS, 0, n, fill, ctx);
	H5Gclose(g);
	return rc;
}

int run_write_bonds(run_writer *w, const dem_bonds *b)
{
	const void *src[BTAB_NFIELDS] = {b->i, b->j, b->d0, b->area, b->kn, b->ks};
	arrays a = {bond_fields, src};
	return run_write_bonds_fill(w, b->n, from_arrays, &a);
}

int run_flush(run_writer *w)
{
	if (w->buffered) {
		hid_t h = H5Gopen2(w->file, "history", H5P_DEFAULT);
		int rc = 0;
		for (int c = 0; !rc && c < w->ncols; c++)
			rc = h5_append(h, w->names[c], H5T_NATIVE_DOUBLE,
			               w->buffer + (size_t)c * HISTORY_BUFFER_ROWS, w->buffered, 0);
		H5Gclose(h);
		if (rc)
			return -1;
		w->buffered = 0;
	}
	if (H5Fflush(w->file, H5F_SCOPE_GLOBAL) < 0)
		return h5_write_error(w->tmp, "the run file");
	return 0;
}

int run_history(run_writer *w, const double *row)
{
	for (int c = 0; c < w->ncols; c++)
		w->buffer[(size_t)c * HISTORY_BUFFER_ROWS + w->buffered] = row[c];
	if (++w->buffered == HISTORY_BUFFER_ROWS)
		return run_flush(w);
	return 0;
}

int run_snapshot_fill(run_writer *w, const dem_snapshot *s, run_fill fill, void *ctx)
{
	char name[64];
	snprintf(name, sizeof name, "snapshots/" RUN_SNAPSHOT, s->step);
	hid_t g = h5_group(w->file, name);
	if (g < 0)
		return -1;
	int rc = h5_attr_i64(g, "step", s->step) || h5_attr_f64(g, "t", s->t) ||
	         h5_attr_f64(g, "strain_axial", s->strain_axial) ||
	         h5_attr_f64(g, "stress_axial", s->stress_axial) ||
	         write_fields(g, snap_fields, SNAP_NFIELDS, s->n, s->nbonds, fill, ctx);
	H5Gclose(g);
	return rc ? -1 : 0;
}

int run_snapshot(run_writer *w, const dem_snapshot *s)
{
	const void *src[SNAP_NFIELDS] = {s->x,        s->v,        s->w,  s->state,
	                                 s->damage_n, s->damage_s, s->fn, s->fs};
	arrays a = {snap_fields, src};
	return run_snapshot_fill(w, s, from_arrays, &a);
}

int run_cracks(run_writer *w, const dem_crack *c, size_t n)
{
	if (n == 0)
		return 0;
	double *t = xmalloc(n * sizeof *t), *e = xmalloc(n * sizeof *e);
	double *rad = xmalloc(n * sizeof *rad), *fn = xmalloc(n * sizeof *fn);
	double *fs = xmalloc(n * sizeof *fs), *x = xmalloc(3 * n * sizeof *x);
	double *nn = xmalloc(3 * n * sizeof *nn);
	int64_t *step = xmalloc(n * sizeof *step);
	int32_t *i = xmalloc(n * sizeof *i), *j = xmalloc(n * sizeof *j);
	int32_t *mode = xmalloc(n * sizeof *mode);
	for (size_t k = 0; k < n; k++) {
		t[k] = c[k].t;
		e[k] = c[k].strain_axial;
		step[k] = c[k].step;
		i[k] = c[k].i;
		j[k] = c[k].j;
		mode[k] = c[k].mode;
		rad[k] = c[k].radius;
		fn[k] = c[k].fn;
		fs[k] = c[k].fs;
		memcpy(x + 3 * k, c[k].x, sizeof c[k].x);
		memcpy(nn + 3 * k, c[k].normal, sizeof c[k].normal);
	}
	hid_t g = H5Gopen2(w->file, "cracks", H5P_DEFAULT);
	int rc = h5_append(g, "t", H5T_NATIVE_DOUBLE, t, n, 0) ||
	         h5_append(g, "strain_axial", H5T_NATIVE_DOUBLE, e, n, 0) ||
	         h5_append(g, "step", H5T_NATIVE_INT64, step, n, 0) ||
	         h5_append(g, "i", H5T_NATIVE_INT32, i, n, 0) ||
	         h5_append(g, "j", H5T_NATIVE_INT32, j, n, 0) ||
	         h5_append(g, "mode", H5T_NATIVE_INT32, mode, n, 0) ||
	         h5_append(g, "x", H5T_NATIVE_DOUBLE, x, n, 3) ||
	         h5_append(g, "normal", H5T_NATIVE_DOUBLE, nn, n, 3) ||
	         h5_append(g, "radius", H5T_NATIVE_DOUBLE, rad, n, 0) ||
	         h5_append(g, "fn", H5T_NATIVE_DOUBLE, fn, n, 0) ||
	         h5_append(g, "fs", H5T_NATIVE_DOUBLE, fs, n, 0);
	H5Gclose(g);
	free(t), free(e), free(rad), free(fn), free(fs), free(x), free(nn), free(step);
	free(i), free(j), free(mode);
	return rc ? -1 : 0;
}

int run_finish(run_writer *w, const char *status)
{
	int rc = run_flush(w) || h5_attr_str(w->file, "status", status);
	if (rc) {
		run_abort(w);
		return -1;
	}
	rc = h5_commit(w->file, w->tmp, w->path);
	if (!rc) {
		/* The run file holds everything now: its recovery copy is stale. */
		char ckpt[4200];
		run_recovery_name(w->path, ckpt, sizeof ckpt);
		unlink(ckpt);
	}
	writer_free(w);
	return rc;
}

void run_abort(run_writer *w)
{
	h5_discard(w->file, w->tmp);
	writer_free(w);
}
