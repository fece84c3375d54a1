/* The run file (run.h5), written by solve (runfile_write.c) and read by post
 * (runfile_read.c): the assembly the run started from, the bonds, the
 * history table, snapshots and the crack log. The layout is specified in
 * share/doc/format.md. solve keeps its own /checkpoint group in the same
 * file through run_hid(). */
#ifndef DEM_RUNFILE_H
#define DEM_RUNFILE_H

#include <hdf5.h>
#include <stddef.h>
#include <stdint.h>

#include "lib/assembly.h"
#include "lib/h5.h"
#include "lib/states.h"

#define RUN_FORMAT "dem-run"

/* A column of the history table. */
typedef struct {
	const char *name;
	const char *unit; /* "" when dimensionless */
} run_column;

/* Per-bond values fixed when the bonds form. */
typedef struct {
	size_t n;
	int32_t *i, *j;  /* particle indices, i < j */
	double *d0;      /* m, reference length (centre distance at bonding) */
	double *area;    /* m^2, effective contact area */
	double *kn, *ks; /* N/m, initial normal and shear stiffness */
} dem_bonds;

typedef struct {
	int64_t step;
	double t;            /* s */
	double strain_axial; /* compression positive */
	double stress_axial; /* Pa, compression positive */
	size_t n;
	double *x, *v, *w; /* [n][3]: m, m/s, rad/s */
	size_t nbonds;
	uint8_t *state;   /* [nbonds] BOND_* */
	double *damage_n; /* [nbonds] tension/normal damage in [0, 1] */
	double *damage_s; /* [nbonds] shear damage in [0, 1] */
	double *fn;       /* [nbonds] N, normal force, tension positive */
	double *fs;       /* [nbonds][3] N, shear force on particle i */
} dem_snapshot;

typedef struct {
	double t;            /* s */
	double strain_axial; /* at failure */
	int64_t step;
	int32_t i, j;     /* the two particles */
	int32_t mode;     /* CRACK_TENSION or CRACK_SHEAR */
	double x[3];      /* m, contact point */
	double normal[3]; /* unit bond direction from i to j */
	double radius;    /* m, contact radius r_c */
	double fn, fs;    /* N, normal (tension positive) and shear force magnitude at failure */
} dem_crack;

typedef struct run_writer run_writer;

/* Create "<path>.tmp" with provenance, the starting assembly and an empty
 * history of the given columns. */
run_writer *run_create(const char *path, const dem_provenance *prov, const dem_assembly *a,
                       const run_column *cols, int ncols);
/* Continue a run file (solve --restart): copy `from` (the run file at path,
 * or its recovery copy) to "<path>.tmp", keep the first history_rows rows of
 * its history and crack_rows rows of its crack log, and set its status to
 * "running". The originals stay untouched until run_finish renames the copy
 * over path. */
run_writer *run_reopen(const char *from, const char *path, size_t history_rows, size_t crack_rows);
/* The recovery copy of the run file at path: "<path>.ckpt". */
void run_recovery_name(const char *path, char *out, size_t n);
/* Save a recovery point: flush the run file and copy it as it stands, with
 * the status "interrupted", to its recovery copy, through a temporary file
 * renamed into place, so that a kill at any moment (kill -9, a lost node)
 * leaves the previous copy whole. Called after each checkpoint; run_finish
 * removes the copy once the run file itself is complete. */
int run_save_recovery(run_writer *w);
int run_write_bonds(run_writer *w, const dem_bonds *b);
/* Append one row (ncols values). Rows are buffered; run_flush writes them. */
int run_history(run_writer *w, const double *row);
int run_snapshot(run_writer *w, const dem_snapshot *s);
/* The same two without the whole arrays in memory: fill(ctx, f, at, m, buf)
 * writes rows [at, at + m) of field f into buf, in the dataset's type
 * (double; int32_t for the bond ends; uint8_t for bond_state) and columns
 * (3 for x, v, w and bond_fs), and may be called on several threads at once
 * (h5_rows_fill), each with its own rows and buf. run_snapshot_fill takes
 * the header, n and nbonds from s and does not read its arrays. */
enum { BTAB_I, BTAB_J, BTAB_D0, BTAB_AREA, BTAB_KN, BTAB_KS, BTAB_NFIELDS };
enum {
	SNAP_X,
	SNAP_V,
	SNAP_W,
	SNAP_STATE,
	SNAP_DAMAGE_N,
	SNAP_DAMAGE_S,
	SNAP_FN,
	SNAP_FS,
	SNAP_NFIELDS
};
typedef void (*run_fill)(void *ctx, int f, size_t at, size_t m, void *buf);
int run_write_bonds_fill(run_writer *w, size_t n, run_fill fill, void *ctx);
int run_snapshot_fill(run_writer *w, const dem_snapshot *s, run_fill fill, void *ctx);
/* The same two with put(ctx, f, r), which writes every row of field f into
 * r (h5.h, open for them), by h5_rows_fill or chunk by chunk; and each
 * field's shape: its columns (0: one), the bytes of a value, and whether
 * its rows are bonds (else particles), in the bond table (snapshot 0) or a
 * snapshot (1). */
typedef int (*run_put)(void *ctx, int f, h5_rows *r);
int run_write_bonds_put(run_writer *w, size_t n, run_put put, void *ctx);
int run_snapshot_put(run_writer *w, const dem_snapshot *s, run_put put, void *ctx);
void run_field_shape(int snapshot, int f, size_t *cols, size_t *size, int *per_bond);
/* Append n rows to the crack log (one process). */
int run_cracks(run_writer *w, const dem_crack *c, size_t n);
/* Append rows rows, of which this process's n are runs: run k, cnt[k] of
 * them in order, at rows [at[k], at[k] + cnt[k]) of those appended (every
 * process of a shared file its own, h5.h). */
int run_cracks_runs(run_writer *w, const dem_crack *c, size_t n, size_t rows, const size_t *at,
                    const size_t *cnt, size_t nruns);
int run_flush(run_writer *w);
hid_t run_hid(run_writer *w);
/* Set the root `status` attribute ("complete", "stopped: <why>", ...),
 * close, and rename to the final name. Frees w. */
int run_finish(run_writer *w, const char *status);
/* Close and remove the temporary file. Frees w. */
void run_abort(run_writer *w);

/* A run file read back (everything but snapshot contents). */
typedef struct {
	dem_provenance prov;
	char *status;
	dem_assembly assembly;
	dem_bonds bonds;
	int ncols;
	char **col_name, **col_unit;
	size_t nrows;
	double **col; /* [ncols][nrows] */
	size_t nsnap;
	int64_t *snap_step;  /* ascending */
	double *snap_t;      /* s */
	double *snap_strain; /* axial strain, compression positive */
	double *snap_stress; /* Pa, axial stress, compression positive */
	size_t ncracks;
	dem_crack *cracks;
} dem_run;

int run_read(const char *path, dem_run *r);
/* Only the provenance, the status, the assembly and the history's row
 * count (what a restart needs; the rest stays empty). */
int run_read_head(const char *path, dem_run *r);
/* The same with only part `part` of `parts` of the assembly's particles
 * (assembly_read_part). */
int run_read_head_part(const char *path, int part, int parts, dem_run *r);
/* The same from an open file whose format was checked (h5_open, or
 * h5_open_image); the file stays open. */
int run_read_file(hid_t file, dem_run *r);
void run_free(dem_run *r);
/* The history column of that name, or NULL. */
const double *run_column_data(const dem_run *r, const char *name);
/* Read snapshot k (0 <= k < r->nsnap). */
int run_read_snapshot(const char *path, const dem_run *r, size_t k, dem_snapshot *s);
/* The same from the open run file r was read from. */
int run_read_snapshot_file(hid_t file, const dem_run *r, size_t k, dem_snapshot *s);
void snapshot_free(dem_snapshot *s);
void bonds_free(dem_bonds *b);

#endif
