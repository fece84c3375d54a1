/* The run file's writer (solve): create or continue a run file, then
 * append history rows, snapshots and cracks, and commit it under its final
 * name. The layout is share/doc/format.md; the reader is runfile_read.c. */
#include <errno.h>
#include <math.h>
#include <stddef.h>
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
	hid_t *types; /* [ncols] the type of each column in the file */
	size_t buffered;
	double *buffer; /* [ncols][HISTORY_BUFFER_ROWS], column-major */
};

hid_t run_hid(run_writer *w) { return w->file; }

/* The history columns that hold integers (the step, the counts), and their
 * type in the file; the others are float64. (Format 2 and older stored them
 * all as float64, and the first files of format 3 all but step and stage.) */
static hid_t column_type(const char *name)
{
	static const char *const counts[] = {"step",
	                                     "bonds_intact",
	                                     "bonds_damaged",
	                                     "bonds_broken_tension",
	                                     "bonds_broken_shear",
	                                     "contacts",
	                                     "contacts_platen"};
	for (size_t k = 0; k < sizeof counts / sizeof *counts; k++)
		if (strcmp(name, counts[k]) == 0)
			return H5T_NATIVE_INT64;
	if (strcmp(name, "stage") == 0)
		return H5T_NATIVE_INT32;
	return H5T_NATIVE_DOUBLE;
}

/* The history's dimension scale: its time column (which netCDF readers
 * such as xarray then show as the table's coordinate). */
#define HISTORY_SCALE "t"

/* Make the history's t column the scale of its rows and attach the other
 * columns to it (nothing when the table has no t column). */
static int history_scales(hid_t h, char *const *names, int ncols)
{
	if (!h5_exists(h, HISTORY_SCALE))
		return 0;
	int rc = h5_scale(h, HISTORY_SCALE);
	const char *dims[1] = {HISTORY_SCALE};
	for (int c = 0; !rc && c < ncols; c++)
		if (strcmp(names[c], HISTORY_SCALE) != 0)
			rc = h5_attach(h, names[c], dims, 1);
	return rc;
}

/* The crack log's columns, their type and units; the rows are the
 * dimension `crack` (an index) and the three components of x and normal
 * the dimension `xyz`. */
enum { F64, I64, I32, U8 };
static hid_t native(int type)
{
	return type == F64   ? H5T_NATIVE_DOUBLE
	       : type == I64 ? H5T_NATIVE_INT64
	       : type == I32 ? H5T_NATIVE_INT32
	                     : H5T_NATIVE_UINT8;
}
static const struct {
	const char *name;
	int type;
	size_t cols;
	const char *unit;
	size_t offset; /* in dem_crack */
} crack_fields[] = {
#define CRACK(f) offsetof(dem_crack, f)
    {"t", F64, 0, "s", CRACK(t)},
    {"strain_axial", F64, 0, "", CRACK(strain_axial)},
    {"step", I64, 0, "", CRACK(step)},
    {"i", I32, 0, "", CRACK(i)},
    {"j", I32, 0, "", CRACK(j)},
    {"mode", I32, 0, "", CRACK(mode)},
    {"x", F64, 3, "m", CRACK(x)},
    {"normal", F64, 3, "", CRACK(normal)},
    {"radius", F64, 0, "m", CRACK(radius)},
    {"fn", F64, 0, "N", CRACK(fn)},
    {"fs", F64, 0, "N", CRACK(fs)},
#undef CRACK
};
enum { NCRACK_FIELDS = sizeof crack_fields / sizeof crack_fields[0] };

static int create_cracks(hid_t k)
{
	int rc = h5_index(k, "crack", 0, 1) || h5_index(k, "xyz", 3, 0);
	const char *dims[2] = {"crack", "xyz"};
	for (int c = 0; !rc && c < NCRACK_FIELDS; c++) {
		rc = h5_create_ext(k, crack_fields[c].name, native(crack_fields[c].type),
		                   crack_fields[c].cols, crack_fields[c].unit) ||
		     h5_attach(k, crack_fields[c].name, dims, crack_fields[c].cols ? 2 : 1);
		/* CF: each crack's time is a coordinate of its row. */
		if (!rc && c > 0) {
			hid_t d = H5Dopen2(k, crack_fields[c].name, H5P_DEFAULT);
			rc = d < 0 || h5_attr_str(d, "coordinates", "t");
			if (d >= 0)
				H5Dclose(d);
		}
	}
	return rc;
}

static void writer_free(run_writer *w)
{
	for (int c = 0; c < w->ncols; c++)
		free(w->names[c]);
	free(w->names);
	free(w->types);
	free(w->buffer);
	free(w);
}

run_writer *run_create(const char *path, const dem_provenance *prov, const dem_assembly *a,
                       const run_column *cols, int ncols)
{
	run_writer *w = xcalloc(1, sizeof *w);
	snprintf(w->path, sizeof w->path, "%s", path);
	w->file = h5_create_shared(path, w->tmp, sizeof w->tmp);
	if (w->file < 0) {
		free(w);
		return NULL;
	}
	w->ncols = ncols;
	w->names = xcalloc((size_t)ncols, sizeof *w->names);
	w->types = xcalloc((size_t)ncols, sizeof *w->types);
	w->buffer = xmalloc((size_t)ncols * HISTORY_BUFFER_ROWS * sizeof *w->buffer);
	int rc = prov_write(w->file, RUN_FORMAT, prov) ||
	         h5_attr_str(w->file, "status", "running") || assembly_write_groups(w->file, a);
	hid_t h = rc ? -1 : h5_group(w->file, "history");
	rc = rc || h < 0;
	for (int c = 0; !rc && c < ncols; c++) {
		w->names[c] = xstrdup(cols[c].name);
		w->types[c] = column_type(cols[c].name);
		rc = h5_create_ext(h, cols[c].name, w->types[c], 0, cols[c].unit);
	}
	rc = rc || history_scales(h, w->names, ncols);
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
		rc = create_cracks(k);
		H5Gclose(k);
	}
	if (rc) {
		run_abort(w);
		return NULL;
	}
	return w;
}

void run_recovery_name(const char *path, char *out, size_t n) { snprintf(out, n, "%s.ckpt", path); }

static int write_series(hid_t file);

/* rc of rank 0, which alone did what it says (what), on every process. */
static int from_rank0(int rc, const char *path, const char *what)
{
	h5_bcast(&rc, sizeof rc);
	if (rc && h5_rank() > 0)
		return err_set("%s: cannot %s (rank 0 says why)", path, what);
	return rc;
}

/* The series and the status "interrupted" added to the copy tmp (rank 0
 * alone, with serial HDF5), then the copy committed as final. */
static int finish_recovery(run_writer *w, const char *tmp, const char *final)
{
	hid_t f = h5_open(tmp, RUN_FORMAT, 1);
	if (f < 0 || write_series(f) || h5_attr_str(f, "status", "interrupted")) {
		if (f >= 0)
			H5Fclose(f);
		afile_discard(tmp);
		return err_set("%s: cannot write the recovery copy %s: %s", w->path, final,
		               err_msg());
	}
	return h5_commit(f, tmp, final);
}

int run_save_recovery(run_writer *w)
{
	/* run_flush leaves the file whole on disk (H5Fflush; on several
	 * ranks, MPI_File_sync on each). Rank 0 claims the copy's temporary
	 * name and creates it, and says so (h5_begin_shared); then every rank
	 * copies its share of the bytes into it (h5_copy_shared, alone with
	 * one process), and rank 0 finishes it. */
	if (run_flush(w))
		return -1;
	char final[4200], tmp[4300];
	run_recovery_name(w->path, final, sizeof final);
	int rank = h5_rank();
	if (h5_begin_shared(final, tmp, sizeof tmp))
		return rank == 0
		           ? -1
		           : err_set("%s: cannot write the recovery copy %s (rank 0 says why)",
		                     w->path, final);
	if (h5_copy_shared(w->tmp, tmp)) {
		if (rank == 0)
			afile_discard(tmp);
		return err_set("%s: cannot write the recovery copy %s: %s", w->path, final,
		               err_msg());
	}
	return from_rank0(rank == 0 ? finish_recovery(w, tmp, final) : 0, w->path,
	                  "write the recovery copy");
}

run_writer *run_reopen(const char *from, const char *path, size_t history_rows, size_t crack_rows)
{
	run_writer *w = xcalloc(1, sizeof *w);
	snprintf(w->path, sizeof w->path, "%s", path);
	if (h5_begin_shared(path, w->tmp, sizeof w->tmp)) {
		free(w);
		return NULL;
	}
	/* Every rank copies its share into the file rank 0 created
	 * (h5_begin_shared), then opens the copy. */
	int rank = h5_rank();
	if (h5_copy_shared(from, w->tmp) || (w->file = h5_open_shared(w->tmp, RUN_FORMAT)) < 0) {
		if (rank == 0)
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
		w->types = xcalloc((size_t)n, sizeof *w->types);
		w->buffer = xmalloc((size_t)n * HISTORY_BUFFER_ROWS * sizeof *w->buffer);
		char *save = NULL, *tok = strtok_r(order, ",", &save);
		for (int c = 0; tok; c++, tok = strtok_r(NULL, ",", &save)) {
			w->names[c] = xstrdup(tok);
			w->types[c] = column_type(tok);
			rc = rc || h5_truncate(h, tok, history_rows);
		}
	}
	free(order);
	if (h >= 0)
		H5Gclose(h);
	hid_t k = rc ? -1 : h5_open_group(w->file, "cracks");
	for (int c = 0; k >= 0 && !rc && c < NCRACK_FIELDS; c++)
		rc = h5_truncate(k, crack_fields[c].name, crack_rows);
	/* The row index (absent from files of format 2 and older). */
	if (k >= 0 && !rc && h5_exists(k, "crack"))
		rc = h5_truncate(k, "crack", crack_rows);
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

void run_field_shape(int snapshot, int f, size_t *cols, size_t *size, int *per_bond)
{
	const rec_field *r = snapshot ? &snap_fields[f] : &bond_fields[f];
	*cols = r->cols;
	*size = row_bytes(r) / (r->cols ? r->cols : 1);
	*per_bond = r->per_bond;
}

/* One field of a run_fill (h5_fill). */
typedef struct {
	run_fill fill;
	void *ctx;
	int f;
} field_fill;

static void fill_field(void *ctx, size_t at, size_t m, void *buf)
{
	const field_fill *ff = ctx;
	ff->fill(ff->ctx, ff->f, at, m, buf);
}

enum { MAX_FIELDS = 8 };
_Static_assert((int)SNAP_NFIELDS <= MAX_FIELDS && (int)BTAB_NFIELDS <= MAX_FIELDS, "fields");

/* The fields of a bond table or a snapshot, open in rs, from fill (when
 * not NULL: every field's chunks compressed together, h5_rows_fill_all)
 * or each by put. */
static int put_fields(h5_rows *rs, int nf, run_put put, run_fill fill, void *ctx)
{
	if (!fill) {
		int rc = 0;
		for (int f = 0; !rc && f < nf; f++)
			rc = put(ctx, f, &rs[f]);
		return rc;
	}
	field_fill ff[MAX_FIELDS];
	h5_rows *r[MAX_FIELDS];
	h5_fill fills[MAX_FIELDS];
	void *ctxs[MAX_FIELDS];
	for (int f = 0; f < nf; f++) {
		ff[f] = (field_fill){fill, ctx, f};
		r[f] = &rs[f], fills[f] = fill_field, ctxs[f] = &ff[f];
	}
	return h5_rows_fill_all(r, nf, fills, ctxs);
}

/* Every field opened, then written (put_fields), then closed. */
static int write_fields(hid_t g, const rec_field *fs, int nf, size_t np, size_t nb, run_put put,
                        run_fill fill, void *ctx, const char *dim_particle, const char *dim_bond,
                        const char *dim_xyz)
{
	h5_rows rs[MAX_FIELDS];
	int rc = 0, f = 0;
	for (; !rc && f < nf; f++)
		rc = h5_rows_open(&rs[f], g, fs[f].name, native(fs[f].type),
		                  fs[f].per_bond ? nb : np, fs[f].cols, fs[f].unit);
	int open = f; /* a failed open is closed too (h5_rows_close) */
	rc = rc || put_fields(rs, nf, put, fill, ctx);
	for (f = 0; f < open; f++)
		rc = h5_rows_close(&rs[f]) || rc;
	/* The rows' and the components' dimension scales, of the group or of
	 * its parent (a snapshot's are those of /snapshots). */
	for (f = 0; !rc && f < nf; f++) {
		const char *dims[2] = {fs[f].per_bond ? dim_bond : dim_particle, dim_xyz};
		rc = h5_attach(g, fs[f].name, dims, fs[f].cols ? 2 : 1);
	}
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

/* The bond table from put or fill (write_fields). */
static int write_bonds(run_writer *w, size_t n, run_put put, run_fill fill, void *ctx)
{
	hid_t g = h5_group(w->file, "bonds");
	if (g < 0)
		return -1;
	int rc = h5_index(g, "bond", n, 0) || write_fields(g, bond_fields, BTAB_NFIELDS, 0, n, put,
	                                                   fill, ctx, NULL, "bond", "xyz");
	H5Gclose(g);
	return rc;
}

int run_write_bonds_put(run_writer *w, size_t n, run_put put, void *ctx)
{
	return write_bonds(w, n, put, NULL, ctx);
}

int run_write_bonds_fill(run_writer *w, size_t n, run_fill fill, void *ctx)
{
	return write_bonds(w, n, NULL, fill, ctx);
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
		int64_t *iv = xmalloc(HISTORY_BUFFER_ROWS * sizeof *iv);
		for (int c = 0; !rc && c < w->ncols; c++) {
			const double *v = w->buffer + (size_t)c * HISTORY_BUFFER_ROWS;
			if (w->types[c] == H5T_NATIVE_DOUBLE) {
				rc =
				    h5_append(h, w->names[c], H5T_NATIVE_DOUBLE, v, w->buffered, 0);
				continue;
			}
			/* An integer column: its values are whole numbers. */
			for (size_t k = 0; k < w->buffered; k++)
				iv[k] = isfinite(v[k]) && fabs(v[k]) < 9e18 ? (int64_t)llround(v[k])
				                                            : 0;
			rc = h5_append(h, w->names[c], H5T_NATIVE_INT64, iv, w->buffered, 0);
		}
		free(iv);
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

/* A snapshot from put or fill (write_fields). */
static int write_snapshot(run_writer *w, const dem_snapshot *s, run_put put, run_fill fill,
                          void *ctx)
{
	char name[64];
	/* The snapshots' dimensions, shared by all, made with the first. */
	hid_t sg = H5Gopen2(w->file, "snapshots", H5P_DEFAULT);
	if (sg < 0)
		return err_set("%s: group 'snapshots': missing", w->tmp);
	int rc = (!h5_exists(sg, "particle") && h5_index(sg, "particle", s->n, 0)) ||
	         (!h5_exists(sg, "bond") && h5_index(sg, "bond", s->nbonds, 0)) ||
	         (!h5_exists(sg, "xyz") && h5_index(sg, "xyz", 3, 0));
	H5Gclose(sg);
	snprintf(name, sizeof name, "snapshots/" RUN_SNAPSHOT, s->step);
	hid_t g = rc ? -1 : h5_group(w->file, name);
	if (g < 0)
		return -1;
	rc = h5_attr_i64(g, "step", s->step) || h5_attr_f64(g, "t", s->t) ||
	     h5_attr_f64(g, "strain_axial", s->strain_axial) ||
	     h5_attr_f64(g, "stress_axial", s->stress_axial) ||
	     write_fields(g, snap_fields, SNAP_NFIELDS, s->n, s->nbonds, put, fill, ctx,
	                  "/snapshots/particle", "/snapshots/bond", "/snapshots/xyz");
	H5Gclose(g);
	return rc ? -1 : 0;
}

int run_snapshot_put(run_writer *w, const dem_snapshot *s, run_put put, void *ctx)
{
	return write_snapshot(w, s, put, NULL, ctx);
}

int run_snapshot_fill(run_writer *w, const dem_snapshot *s, run_fill fill, void *ctx)
{
	return write_snapshot(w, s, NULL, fill, ctx);
}

int run_snapshot(run_writer *w, const dem_snapshot *s)
{
	const void *src[SNAP_NFIELDS] = {s->x,        s->v,        s->w,  s->state,
	                                 s->damage_n, s->damage_s, s->fn, s->fs};
	arrays a = {snap_fields, src};
	return run_snapshot_fill(w, s, from_arrays, &a);
}

/* Field f of every snapshot as one virtual dataset /snapshots/<name> of
 * shape [S, rows(, cols)]: slab k is the dataset of snapshot k (read in
 * place, nothing copied). rows is that of the last snapshot; a snapshot of
 * another row count is left out (its slab reads as the fill value: NaN, or
 * 255 for bond_state). */
static int write_virtual(hid_t g, const rec_field *f, const int64_t *steps, size_t ns)
{
	char src[96];
	snprintf(src, sizeof src, RUN_SNAPSHOT "/%s", steps[ns - 1], f->name);
	long long rows = h5_rows_of(g, src);
	if (rows < 0)
		return err_set("%s: dataset 'snapshots/%s': missing", h5_name(g), src);
	int rank = f->cols ? 3 : 2;
	hsize_t dims[3] = {ns, (hsize_t)rows, f->cols};
	hid_t vspace = H5Screate_simple(rank, dims, NULL);
	hid_t sspace = H5Screate_simple(rank - 1, dims + 1, NULL);
	hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
	double nan = NAN;
	uint8_t none = 255;
	herr_t rc = f->type == F64  ? H5Pset_fill_value(dcpl, H5T_NATIVE_DOUBLE, &nan)
	            : f->type == U8 ? H5Pset_fill_value(dcpl, H5T_NATIVE_UINT8, &none)
	                            : 0;
	for (size_t k = 0; rc >= 0 && rows > 0 && k < ns; k++) {
		snprintf(src, sizeof src, RUN_SNAPSHOT "/%s", steps[k], f->name);
		if (h5_rows_of(g, src) != rows)
			continue;
		char path[128];
		snprintf(path, sizeof path, "/snapshots/%s", src);
		hsize_t start[3] = {k, 0, 0}, count[3] = {1, (hsize_t)rows, f->cols};
		rc = H5Sselect_hyperslab(vspace, H5S_SELECT_SET, start, NULL, count, NULL);
		if (rc >= 0)
			rc = H5Pset_virtual(dcpl, vspace, ".", path, sspace);
	}
	H5Sselect_all(vspace);
	hid_t d = rc < 0 ? -1
	                 : H5Dcreate2(g, f->name, native(f->type), vspace, H5P_DEFAULT, dcpl,
	                              H5P_DEFAULT);
	int bad = d < 0 || (f->unit && h5_attr_str(d, "units", f->unit));
	if (d >= 0)
		H5Dclose(d);
	H5Pclose(dcpl);
	H5Sclose(sspace);
	H5Sclose(vspace);
	if (bad)
		return h5_write_dataset_error(g, f->name);
	const char *dn[3] = {"t", f->per_bond ? "bond" : "particle", "xyz"};
	return h5_attach(g, f->name, dn, rank);
}

/* The snapshots as time series, in /snapshots: `t` (the scale of their
 * dimension), `step`, `strain_axial` and `stress_axial` of each, and every
 * field as a virtual dataset over them (write_virtual). Written when the
 * file is complete or copied for recovery; replaces an older series (a
 * continued run's). */
static int write_series(hid_t file)
{
	hid_t g = h5_open_group(file, "snapshots");
	if (g < 0)
		return -1;
	static const char *const heads[] = {"step", "strain_axial", "stress_axial", "t"};
	int rc = 0;
	for (int f = 0; !rc && f < SNAP_NFIELDS; f++)
		rc = h5_delete(g, snap_fields[f].name);
	for (int h = 0; !rc && h < 4; h++)
		rc = h5_delete(g, heads[h]);
	int64_t *steps = NULL;
	size_t ns = 0;
	if (!rc)
		ns = run_snapshot_steps(g, &steps);
	if (!rc && ns) {
		double *t = xmalloc(ns * sizeof *t), *e = xmalloc(ns * sizeof *e);
		double *sa = xmalloc(ns * sizeof *sa);
		for (size_t k = 0; !rc && k < ns; k++) {
			char name[64];
			snprintf(name, sizeof name, RUN_SNAPSHOT, steps[k]);
			hid_t s = H5Gopen2(g, name, H5P_DEFAULT);
			rc = s < 0 || h5_read_attr_f64(s, "t", &t[k]) ||
			     h5_read_attr_f64(s, "strain_axial", &e[k]) ||
			     h5_read_attr_f64(s, "stress_axial", &sa[k]);
			if (s >= 0)
				H5Gclose(s);
		}
		const char *dims[1] = {"t"};
		rc = rc || h5_write(g, "t", H5T_NATIVE_DOUBLE, t, ns, 0, "s") || h5_scale(g, "t") ||
		     h5_write(g, "step", H5T_NATIVE_INT64, steps, ns, 0, NULL) ||
		     h5_write(g, "strain_axial", H5T_NATIVE_DOUBLE, e, ns, 0, NULL) ||
		     h5_write(g, "stress_axial", H5T_NATIVE_DOUBLE, sa, ns, 0, "Pa") ||
		     h5_attach(g, "step", dims, 1) || h5_attach(g, "strain_axial", dims, 1) ||
		     h5_attach(g, "stress_axial", dims, 1);
		/* The dimensions (missing from a run of format 2 continued). */
		char last[64];
		snprintf(last, sizeof last, RUN_SNAPSHOT, steps[ns - 1]);
		hid_t s = rc ? -1 : H5Gopen2(g, last, H5P_DEFAULT);
		long long np = s < 0 ? -1 : h5_rows_of(s, "x");
		long long nb = s < 0 ? -1 : h5_rows_of(s, "bond_state");
		if (s >= 0)
			H5Gclose(s);
		if (!rc && (np < 0 || nb < 0))
			rc = err_set("%s: snapshot %s: dataset 'x' or 'bond_state' missing",
			             h5_name(g), last);
		rc = rc || (!h5_exists(g, "particle") && h5_index(g, "particle", (size_t)np, 0)) ||
		     (!h5_exists(g, "bond") && h5_index(g, "bond", (size_t)nb, 0)) ||
		     (!h5_exists(g, "xyz") && h5_index(g, "xyz", 3, 0));
		for (int f = 0; !rc && f < SNAP_NFIELDS; f++)
			rc = write_virtual(g, &snap_fields[f], steps, ns);
		free(t), free(e), free(sa);
	}
	free(steps);
	H5Gclose(g);
	return rc ? -1 : 0;
}

int run_cracks_runs(run_writer *w, const dem_crack *c, size_t n, size_t rows, const size_t *at,
                    const size_t *cnt, size_t nruns)
{
	if (rows == 0)
		return 0;
	hid_t g = H5Gopen2(w->file, "cracks", H5P_DEFAULT);
	int rc = h5_exists(g, "crack") && h5_index_append(g, "crack", rows);
	unsigned char *buf = xmalloc(n * 3 * sizeof(double) + 1);
	for (int f = 0; !rc && f < NCRACK_FIELDS; f++) {
		/* Field f of each crack, in a column of its own. */
		hid_t type = native(crack_fields[f].type);
		size_t size = (crack_fields[f].cols ? crack_fields[f].cols : 1) * H5Tget_size(type);
		for (size_t k = 0; k < n; k++)
			memcpy(buf + k * size, (const char *)&c[k] + crack_fields[f].offset, size);
		rc = h5_append_runs(g, crack_fields[f].name, type, buf, rows, crack_fields[f].cols,
		                    at, cnt, nruns);
	}
	free(buf);
	H5Gclose(g);
	return rc ? -1 : 0;
}

int run_cracks(run_writer *w, const dem_crack *c, size_t n)
{
	return run_cracks_runs(w, c, n, n, &(size_t){0}, &n, 1);
}

/* The series and the status, then the file under its final name. */
static int finish(run_writer *w, const char *status)
{
	if (write_series(w->file) || h5_attr_str(w->file, "status", status)) {
		h5_discard(w->file, w->tmp);
		return -1;
	}
	if (h5_commit(w->file, w->tmp, w->path))
		return -1;
	/* The run file holds everything now: its recovery copy is stale. */
	char ckpt[4200];
	run_recovery_name(w->path, ckpt, sizeof ckpt);
	unlink(ckpt);
	return 0;
}

int run_finish(run_writer *w, const char *status)
{
	if (run_flush(w)) {
		run_abort(w);
		return -1;
	}
	int rc = 0;
	if (h5_shared(w->file)) {
		/* Every rank closes the file; rank 0 finishes it alone. */
		rc = h5_close_shared(w->file);
		if (h5_rank() == 0) {
			w->file = rc ? -1 : h5_open(w->tmp, RUN_FORMAT, 1);
			if (w->file < 0)
				afile_discard(w->tmp);
			rc = w->file < 0 || finish(w, status);
		}
		rc = from_rank0(rc, w->path, "finish the run file");
	} else {
		rc = finish(w, status);
	}
	writer_free(w);
	return rc;
}

void run_abort(run_writer *w)
{
	h5_discard(w->file, w->tmp);
	writer_free(w);
}
