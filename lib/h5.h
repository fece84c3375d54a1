/* Thin helpers over the HDF5 C API shared by the assembly and run files.
 * Errors are reported through err_set() naming the file and object, never
 * through HDF5's own error stack (which is silenced). */
#ifndef DEM_H5_H
#define DEM_H5_H

#include <hdf5.h>
#include <stddef.h>
#include <stdint.h>

/* Silence HDF5's error stack and cap its free lists (called by h5_create and h5_open). */
void h5_quiet(void);

/* Create "<final>.tmp" for writing (registered for removal on failure). */
hid_t h5_create(const char *final, char *tmp, size_t tmpsize);
/* Close the file and rename tmp to final (atomic output). */
int h5_commit(hid_t file, const char *tmp, const char *final);
/* err_set for a write to path that failed, saying why where it can (a full
 * file system, or the errno of the failed write); what names what was
 * written. Returns -1. */
int h5_write_error(const char *path, const char *what);
/* The same for dataset name under loc. */
int h5_write_dataset_error(hid_t loc, const char *name);
/* Close the file and remove tmp. */
void h5_discard(hid_t file, const char *tmp);
/* Open an existing file and check its `format` attribute equals format and
 * its format_version is one this build reads. */
hid_t h5_open(const char *path, const char *format, int readwrite);
/* The same for a file image of n bytes in memory (HDF5's core driver; the
 * buffer is copied and nothing touches the disk), read-only. Messages name
 * the file H5_IMAGE_NAME. */
#define H5_IMAGE_NAME "(file image)"
hid_t h5_open_image(const void *buf, size_t n, const char *format);

/* Files that several processes write together (solve's ranks: parallel
 * HDF5 over MPI-IO). The program supplies what that needs from MPI and from
 * HDF5's parallel interface (solve/h5mpi.c: lib is compiled against the
 * serial headers, which declare neither). Until it does, or with one
 * process, the _shared functions below are the plain ones.
 *
 * In a shared file every process makes the same calls in the same order:
 * every creation, attribute, extension and close. Attributes take rank 0's
 * values; h5_write, h5_append, h5_rows_put and h5_rows_fill write rank 0's
 * rows (h5_rows_fill: every process fills an even share of the chunks, in
 * rounds, so its fill must be able to give any rows); h5_rows_write_at
 * writes each process's own; h5_slab writes independently (datasets without
 * filters only). */
typedef struct {
	int rank, size;
	hid_t (*fapl)(void);                /* a new file-access list: every process's file */
	hid_t (*dxpl)(void);                /* a new transfer list: a collective write */
	void (*bcast)(void *buf, size_t n); /* rank 0's n bytes to every process */
	void (*sum)(uint64_t *v, size_t n); /* v summed over the processes, on each */
	/* from's bytes into to (which rank 0 has created), each process
	 * copying an even share: 0, or -1 with the same message on every
	 * process when any failed. */
	int (*copy)(const char *from, const char *to);
} h5_procs;
void h5_set_procs(const h5_procs *p);
int h5_rank(void); /* this process's rank among h5_procs (0 without) */
/* -1 on every process if rc is nonzero on any, else 0. */
int h5_agree(int rc);
/* Rank 0's n bytes at buf to every process (nothing without h5_procs). */
void h5_bcast(void *buf, size_t n);
/* A byte copy of file from into to (fcopy), by every process together
 * (h5_procs copy): every process calls it, after rank 0 has created to
 * (h5_begin_shared), once every write to from is flushed (H5Fflush). 0, or
 * -1 on every process with a message naming the file. */
int h5_copy_shared(const char *from, const char *to);
/* The temporary name of final (afile_begin), registered on rank 0 alone. */
int h5_begin_shared(const char *final, char *tmp, size_t tmpsize);
/* h5_create and h5_open (read-write) by every process together; only rank
 * 0 registers tmp for removal (afile.h). h5_close_shared closes such a file
 * (0 when it closed on every process); h5_discard of one only removes tmp
 * on rank 0, without closing (the program is ending). */
hid_t h5_create_shared(const char *final, char *tmp, size_t tmpsize);
hid_t h5_open_shared(const char *path, const char *format);
int h5_close_shared(hid_t file);
/* Whether obj is in a file every process writes. */
int h5_shared(hid_t obj);
/* Called by every process together, for obj in the shared file, before
 * what makes the processes read different parts of its metadata (each
 * writing rows of its own, or rank 0 alone): HDF5 1.10's metadata cache
 * holds back its sync point (a barrier and broadcasts every process
 * joins) until the first look-up after its dirty bytes pass a threshold;
 * a look-up that one process makes alone would start it there alone, and
 * the file's processes would wait for each other forever. h5_settle runs
 * a sync point so held back, on every process at once. Nothing without a
 * shared file. */
void h5_settle(hid_t obj);

/* The file name an object belongs to (for messages). */
const char *h5_name(hid_t obj);

hid_t h5_group(hid_t loc, const char *name);      /* create */
hid_t h5_open_group(hid_t loc, const char *name); /* open existing */
int h5_exists(hid_t loc, const char *path);

/* Attributes on any object. Strings are variable-length UTF-8. */
int h5_attr_str(hid_t obj, const char *name, const char *value);
int h5_attr_f64(hid_t obj, const char *name, double value);
int h5_attr_i64(hid_t obj, const char *name, int64_t value);
int h5_attr_f64v(hid_t obj, const char *name, const double *v, size_t n);
char *h5_read_attr_str(hid_t obj, const char *name); /* caller frees; NULL on error */
int h5_read_attr_f64(hid_t obj, const char *name, double *value);
int h5_read_attr_i64(hid_t obj, const char *name, int64_t *value);
int h5_read_attr_f64v(hid_t obj, const char *name, double *v, size_t n);

/* Whole datasets of rank 1 (cols == 0) or rank 2 ([rows, cols]) with an
 * optional `units` attribute (CF's name; format 2 and older wrote `unit`). type is
 * H5T_NATIVE_DOUBLE, H5T_NATIVE_INT32, H5T_NATIVE_INT64 or H5T_NATIVE_UINT8. Large datasets are
 * chunked and compressed. */
int h5_write(hid_t loc, const char *name, hid_t type, const void *data, size_t rows, size_t cols,
             const char *unit);
/* The same dataset written a piece at a time, in row order, so that the
 * whole array never has to be in memory: open it, then put pieces of at
 * most h5_rows_piece() rows (one chunk) until all rows are written, then
 * close it (which fails if rows are missing or a put failed). */
enum { H5_PIECE_ELEMENTS = 65536 }; /* a piece holds at most this many values */
typedef struct {
	hid_t loc, d, type;
	const char *name;
	size_t rows, cols, at;
	int failed, chunked; /* chunked: compressed, in chunks of one piece */
} h5_rows;
/* Write (or read) rows [at, at + m) of an open dataset of cols columns
 * (0: rank 1) from (into) buf. No message set: the caller names the file. */
int h5_slab(hid_t d, hid_t type, size_t at, size_t m, size_t cols, void *buf, int write);
/* Read the m rows rows[0..m) (any order, each in range) of an open dataset
 * of cols columns (0: rank 1) into buf, row k's values k-th. No message
 * set. */
int h5_rows_at(hid_t d, hid_t type, const int32_t *rows, size_t m, size_t cols, void *buf);
int h5_rows_open(h5_rows *r, hid_t loc, const char *name, hid_t type, size_t rows, size_t cols,
                 const char *unit);
size_t h5_rows_piece(const h5_rows *r);
int h5_rows_put(h5_rows *r, const void *data, size_t m);
/* In a shared file: every process writes its own rows [at, at + m) from
 * buf (m may be 0), together; r counts the rows of all. */
int h5_rows_write_at(h5_rows *r, size_t at, size_t m, const void *buf);
int h5_rows_close(h5_rows *r);
/* Put all the rows not yet written, a piece at a time from fill(ctx, at, m,
 * buf), which writes rows [at, at + m) (at most one piece) into buf in the
 * dataset's type. A chunked dataset's chunks are compressed on the
 * threads h5_set_threads sets, one chunk each at a time, with the shuffle and
 * deflate filters its creation properties declare (exactly what HDF5 would
 * write), and written in order: the file is the same whatever the thread
 * count. fill is then called on several threads at once, each
 * with its own rows and buffer; a fill that calls HDF5 does it inside
 * `#pragma omp critical(dem_hdf5)`, as the chunks' writes are. */
typedef void (*h5_fill)(void *ctx, size_t at, size_t m, void *buf);
int h5_rows_fill(h5_rows *r, h5_fill fill, void *ctx);
/* h5_rows_fill of n datasets at once, r[d] from fill[d](ctx[d], ...), in
 * one process's file, each begun at a chunk's first row (or at its first
 * row, if too small to be chunked): the chunks of all are shared by the
 * threads, so that a dataset of one chunk compresses beside the others,
 * and written in order, dataset by dataset (the file is the same whatever
 * the thread count). On a failed write every dataset is marked failed. */
int h5_rows_fill_all(h5_rows *const *r, int n, const h5_fill *fill, void *const *ctx);
/* A fill (ctx an h5_whole) from a whole array of rows of row bytes each. */
typedef struct {
	const void *data;
	size_t row;
} h5_whole;
void h5_from_whole(void *ctx, size_t at, size_t m, void *buf);
/* The rows of each chunk of a dataset of rows x cols that has several (0
 * for one chunk, or a dataset too small to be chunked): where the rows are
 * not all in one place (solve's ranks), each chunk's rows are gathered
 * where it is written. */
size_t h5_chunk_rows(size_t rows, size_t cols);
/* The threads that compress the chunks of h5_rows_fill, h5_write and
 * h5_index (1 until set; n < 1 sets 1). */
void h5_set_threads(int n);
/* Read a dataset, checking its rank and (when cols > 0) its column count.
 * *rows gets the row count; the data is allocated (caller frees). Reading a
 * dataset of zero rows gives a valid pointer. */
int h5_read(hid_t loc, const char *name, hid_t type, void **data, size_t *rows, size_t cols);
/* As h5_read, but only part `part` of `parts` even parts of the rows:
 * rows [*first, *first + *held) of the *rows. */
int h5_read_part(hid_t loc, const char *name, hid_t type, void **data, size_t *rows, size_t cols,
                 int part, int parts, size_t *first, size_t *held);
/* Whether dataset d can hold n values: a damaged dataspace can claim any
 * number of rows, which would then be allocated before anything is read. */
int h5_stored_holds(hid_t d, double n);
/* As h5_read but the row count must equal rows. */
int h5_read_n(hid_t loc, const char *name, hid_t type, void **data, size_t rows, size_t cols);

/* Extendible rank-1/2 datasets for tables that grow (history, cracks). */
int h5_create_ext(hid_t loc, const char *name, hid_t type, size_t cols, const char *unit);
int h5_append(hid_t loc, const char *name, hid_t type, const void *data, size_t rows, size_t cols);
/* The same where the rows come in runs, each process its own (in a shared
 * file): rows rows are added, and run k of this process's data, n[k] rows
 * of it in order, goes to rows [at[k], at[k] + n[k]) of them. */
int h5_append_runs(hid_t loc, const char *name, hid_t type, const void *data, size_t rows,
                   size_t cols, const size_t *at, const size_t *n, size_t nruns);
/* Keep the first rows rows of an extendible dataset (error if it has fewer). */
int h5_truncate(hid_t loc, const char *name, size_t rows);
/* The row count of dataset name under loc (-1 if it cannot be opened). */
long long h5_rows_of(hid_t loc, const char *name);

/* The `units` attribute of dataset name under loc, or the `unit` of files
 * of format 2 and older; "" when it has neither. Caller frees; NULL on
 * error. */
char *h5_read_units(hid_t loc, const char *name);

/* Dimension scales (HDF5's high-level H5DS API, as netCDF-4 and so xarray
 * read them). h5_index writes dataset name under loc holding 0, 1, ...,
 * rows - 1 (int64; extendible when ext) and makes it the scale of a
 * dimension of that name; h5_index_append extends such an extendible index
 * by rows rows. h5_scale makes an existing rank-1 dataset a scale.
 * h5_attach attaches to each axis k of dataset name the scale dims[k] (a
 * path from loc; NULL leaves the axis alone); naxes is the dataset's rank. */
int h5_index(hid_t loc, const char *name, size_t rows, int ext);
int h5_index_append(hid_t loc, const char *name, size_t rows);
int h5_scale(hid_t loc, const char *name);
int h5_attach(hid_t loc, const char *name, const char *const *dims, int naxes);
/* Delete dataset name under loc, detaching it first from the scales of its
 * axes (so their back references stay valid); nothing if it is absent. */
int h5_delete(hid_t loc, const char *name);

#endif
