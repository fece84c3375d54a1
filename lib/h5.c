#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <time.h>
#include <unistd.h>

#include <hdf5_hl.h>
#include <zlib.h>

#include "lib/afile.h"
#include "lib/err.h"
#include "lib/fcopy.h"
#include "lib/h5.h"

/* The format version this build writes, and the oldest it reads: 3 names
 * units `units` (CF) and attaches dimension scales, 2 names them `unit`
 * and stores strings with a fixed length, 1 with a variable length. */
#define FORMAT_VERSION 3
#define FORMAT_OLDEST 1

/* Said before main, since it must be said before the library's first use:
 * HDF5 closes the files still open when the process exits. After a write
 * that failed (a full disk), its close of such a file crashes inside the
 * library (HDF5 1.10), turning a clear error message into a segmentation
 * fault. Every file this toolchain writes is closed explicitly, or is a
 * temporary that an error removes, so the library is told not to. And
 * HDF5's own file locking is off (overriding a site's
 * HDF5_USE_FILE_LOCKING): a file being written is claimed by its writer
 * (afile.h) before HDF5 opens it, and HDF5's lock would conflict with that
 * claim; it also comes too late (HDF5 truncates a file it creates before
 * locking it). */
__attribute__((constructor)) static void h5_before_main(void)
{
	H5dont_atexit();
	setenv("HDF5_USE_FILE_LOCKING", "FALSE", 1);
}

/* No error stack printed (the callers report); and HDF5's free lists, which
 * otherwise keep every block freed while writing (several MB for a snapshot
 * of 20 000 spheres), capped at 256 KiB each kind. */
void h5_quiet(void)
{
	H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
	H5set_free_list_limits(256 << 10, 64 << 10, 256 << 10, 64 << 10, 256 << 10, 64 << 10);
}

const char *h5_name(hid_t obj)
{
	static _Thread_local char name[1024];
	if (H5Fget_name(obj, name, sizeof name) < 0)
		strcpy(name, "(hdf5)");
	return name;
}

static const h5_procs *procs_;
/* The file every process has open (one at a time: solve's run file), by
 * its name. */
static char shared_[1024];

void h5_set_procs(const h5_procs *p) { procs_ = p && p->size > 1 ? p : NULL; }
int h5_rank(void) { return procs_ ? procs_->rank : 0; }

int h5_shared(hid_t obj) { return procs_ && shared_[0] && strcmp(h5_name(obj), shared_) == 0; }

void h5_settle(hid_t obj)
{
	if (!h5_shared(obj))
		return;
	/* A look-up of obj's header: its release (H5AC_unprotect) runs the
	 * sync point if one is due, on every process, since every process
	 * makes it. */
	H5O_info_t info;
	H5Oget_info2(obj, &info, H5O_INFO_BASIC);
}

int h5_agree(int rc)
{
	if (!procs_)
		return rc ? -1 : 0;
	uint64_t bad = rc != 0;
	procs_->sum(&bad, 1);
	return bad ? -1 : 0;
}

void h5_bcast(void *buf, size_t n)
{
	if (procs_)
		procs_->bcast(buf, n);
}

int h5_copy_shared(const char *from, const char *to)
{
	return procs_ ? procs_->copy(from, to) : fcopy(from, to);
}

/* What a process sees of a file: whether it sees one (else errno), its
 * size and the time of its last change, and, for a file rank 0 has just
 * made, the token rank 0 wrote in it. */
typedef struct {
	uint64_t seen, err, size, sec, nsec;
	char token[48];
} file_view;

static file_view view_of(const char *path, int read_token)
{
	/* Opened, not only looked up: an open checks the attributes a
	 * network file system's client may have kept from before. */
	FILE *f = fopen(path, "rb");
	struct stat st;
	if (!f || fstat(fileno(f), &st) != 0) {
		file_view none = {.err = (uint64_t)errno};
		if (f)
			fclose(f);
		return none;
	}
	file_view v = {.seen = 1,
	               .size = (uint64_t)st.st_size,
	               .sec = (uint64_t)st.st_mtim.tv_sec,
	               .nsec = (uint64_t)st.st_mtim.tv_nsec};
	if (read_token && fread(v.token, 1, sizeof v.token - 1, f) == 0)
		v.token[0] = '\0';
	fclose(f);
	return v;
}

/* Whether every process sees the file at path (name in messages) that
 * rank 0 sees (every process calls it): not when it is missing on some,
 * or another file on some (a directory local to each machine, holding
 * copies), which an MPI-IO open does not survive (Open MPI's OMPIO waits
 * forever in an open that some processes cannot make) or turns into a
 * file of its own on each machine, each holding a part of the run. A file
 * rank 0 has just made for it (token) is told by a token rank 0 writes in
 * it; an existing one by its size and time. 0, or -1 on every process
 * with a message. */
static int seen_by_all(const char *path, const char *name, int token)
{
	file_view mine = {0}, first;
	if (procs_->rank == 0) {
		FILE *f = token ? fopen(path, "wb") : NULL;
		if (f) {
			struct timespec now;
			clock_gettime(CLOCK_REALTIME, &now);
			fprintf(f, "dem %lld.%09ld %ld", (long long)now.tv_sec, now.tv_nsec,
			        (long)getpid());
			fclose(f);
		}
		mine = view_of(path, token);
	}
	first = mine;
	procs_->bcast(&first, sizeof first);
	if (!first.seen)
		return err_set("%s: cannot open: %s", name, strerror((int)first.err));
	if (procs_->rank > 0)
		mine = view_of(path, token);
	uint64_t bad = !mine.seen || (token ? strcmp(mine.token, first.token) != 0
	                                    : mine.size != first.size || mine.sec != first.sec ||
	                                          mine.nsec != first.nsec);
	procs_->sum(&bad, 1);
	if (!bad)
		return 0;
	return err_set("%s: not the same file on every rank (%llu of the %d ranks see none or "
	               "another): its directory must be one directory shared by every rank (a "
	               "parallel or network file system), not one local to each machine",
	               name, (unsigned long long)bad, procs_->size);
}

int h5_begin_shared(const char *final, char *tmp, size_t tmpsize)
{
	int rc =
	    h5_rank() == 0 ? (procs_ ? afile_begin_shared : afile_begin)(final, tmp, tmpsize) : 0;
	if (!rc && h5_rank() > 0)
		snprintf(tmp, tmpsize, "%s.tmp", final);
	h5_bcast(&rc, sizeof rc);
	if (rc || !procs_ || !seen_by_all(tmp, final, 1))
		return rc;
	if (procs_->rank == 0)
		afile_discard(tmp);
	return -1;
}

/* The file-access list of every file written: the oldest format that holds
 * what is written (HDF5 1.8), and the shared file's driver. */
static hid_t access_list(int shared)
{
	hid_t fapl = shared ? procs_->fapl() : H5Pcreate(H5P_FILE_ACCESS);
	H5Pset_libver_bounds(fapl, H5F_LIBVER_V18, H5F_LIBVER_LATEST);
	return fapl;
}

static const char *obj_path(hid_t obj)
{
	static _Thread_local char path[1024];
	if (H5Iget_name(obj, path, sizeof path) < 0)
		strcpy(path, "?");
	return path;
}

static hid_t check_format(hid_t f, const char *name, const char *format);

static hid_t create(const char *final, char *tmp, size_t tmpsize, int shared)
{
	h5_quiet();
	if (shared ? h5_begin_shared(final, tmp, tmpsize) : afile_begin(final, tmp, tmpsize))
		return -1;
	hid_t fapl = access_list(shared);
	hid_t f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
	H5Pclose(fapl);
	if (shared && h5_agree(f < 0)) {
		if (procs_->rank == 0)
			afile_discard(tmp);
		return err_set("%s: cannot create file on every rank (is the directory writable "
		               "and shared?)",
		               tmp);
	}
	if (f < 0) {
		/* HDF5 does not say why: the system's reason, from a plain
		 * create of the same name */
		int fd = open(tmp, O_WRONLY | O_CREAT, 0666);
		const char *why = fd < 0 ? strerror(errno) : "HDF5 could not create it";
		if (fd >= 0)
			close(fd);
		afile_discard(tmp);
		return err_set(
		    "%s: cannot create it (written first as %s, renamed when complete): %s", final,
		    tmp, why);
	}
	if (shared)
		snprintf(shared_, sizeof shared_, "%s", h5_name(f));
	if (h5_attr_i64(f, "format_version", FORMAT_VERSION)) {
		h5_discard(f, tmp);
		return -1;
	}
	return f;
}

hid_t h5_create(const char *final, char *tmp, size_t tmpsize)
{
	return create(final, tmp, tmpsize, 0);
}

hid_t h5_create_shared(const char *final, char *tmp, size_t tmpsize)
{
	return create(final, tmp, tmpsize, procs_ != NULL);
}

hid_t h5_open_shared(const char *path, const char *format)
{
	if (!procs_)
		return h5_open(path, format, 1);
	h5_quiet();
	if (seen_by_all(path, path, 0))
		return -1;
	hid_t fapl = access_list(1);
	hid_t f = H5Fopen(path, H5F_ACC_RDWR, fapl);
	H5Pclose(fapl);
	if (h5_agree(f < 0)) {
		if (f >= 0)
			H5Fclose(f);
		return err_set("%s: cannot open HDF5 file on every rank", path);
	}
	/* Every rank reads the same attributes: the same answer. */
	f = check_format(f, path, format);
	if (f >= 0)
		snprintf(shared_, sizeof shared_, "%s", h5_name(f));
	return f;
}

int h5_close_shared(hid_t file)
{
	int shared = h5_shared(file);
	int rc = H5Fclose(file) < 0;
	if (!shared)
		return rc ? -1 : 0;
	shared_[0] = '\0';
	return h5_agree(rc);
}

/* Whether errno e is that of a failed write: a full disk, a quota, a file
 * size limit, an I/O error. */
static int write_errno(int e) { return e == ENOSPC || e == EDQUOT || e == EFBIG || e == EIO; }

int h5_write_error(const char *path, const char *what)
{
	/* HDF5 keeps no errno; the last failed write usually left it. */
	int e = errno;
	struct statvfs st;
	char why[160];
	if (statvfs(path, &st) == 0 && (double)st.f_bavail * (double)st.f_frsize < 1 << 20)
		snprintf(why, sizeof why, "the file system is full (%.0f bytes free)",
		         (double)st.f_bavail * (double)st.f_frsize);
	else if (write_errno(e))
		snprintf(why, sizeof why, "%s", strerror(e));
	else
		snprintf(why, sizeof why, "the disk is full or failing");
	return err_set("%s: cannot write %s: %s", path, what, why);
}

/* h5_write_error for the object of a kind ("dataset", "group", ...) and
 * name in loc. */
static int object_write_error(hid_t loc, const char *kind, const char *name)
{
	char what[300];
	snprintf(what, sizeof what, "%s '%s'", kind, name);
	return h5_write_error(h5_name(loc), what);
}

int h5_write_dataset_error(hid_t loc, const char *name)
{
	return object_write_error(loc, "dataset", name);
}

int h5_commit(hid_t file, const char *tmp, const char *final)
{
	if (H5Fclose(file) < 0) {
		h5_write_error(tmp, "the file's last data");
		afile_discard(tmp);
		return -1;
	}
	return afile_commit(tmp, final);
}

void h5_discard(hid_t file, const char *tmp)
{
	if (h5_shared(file)) {
		/* Closing is collective; the others may not be here. */
		if (procs_->rank == 0)
			afile_discard(tmp);
		return;
	}
	H5Fclose(file);
	afile_discard(tmp);
}

/* Check that open file f (named name in messages) has the `format`
 * attribute format and a format_version this build reads; close it if not. */
static hid_t check_format(hid_t f, const char *name, const char *format)
{
	char *fmt = NULL;
	int64_t version = 0;
	if (H5Aexists(f, "format") <= 0 || !(fmt = h5_read_attr_str(f, "format"))) {
		H5Fclose(f);
		return err_set("%s: attribute 'format': missing: expected \"%s\" (not a file "
		               "written by this toolchain)",
		               name, format);
	}
	if (strcmp(fmt, format) != 0) {
		err_set("%s: attribute 'format': value \"%s\": expected \"%s\"", name, fmt, format);
		free(fmt);
		H5Fclose(f);
		return -1;
	}
	free(fmt);
	if (h5_read_attr_i64(f, "format_version", &version) || version < FORMAT_OLDEST ||
	    version > FORMAT_VERSION) {
		H5Fclose(f);
		return err_set("%s: attribute 'format_version': value %lld: expected %d to %d "
		               "(a file of another version of this toolchain)",
		               name, (long long)version, FORMAT_OLDEST, FORMAT_VERSION);
	}
	return f;
}

hid_t h5_open(const char *path, const char *format, int readwrite)
{
	h5_quiet();
	if (access(path, F_OK) != 0)
		return err_set("%s: cannot read: %s", path, strerror(errno));
	if (H5Fis_hdf5(path) <= 0)
		return err_set("%s: not a readable HDF5 file (truncated or another format)", path);
	hid_t f = H5Fopen(path, readwrite ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT);
	if (f < 0)
		return err_set("%s: cannot open HDF5 file", path);
	return check_format(f, path, format);
}

hid_t h5_open_image(const void *buf, size_t n, const char *format)
{
	h5_quiet();
	/* The core driver holds the file in memory; without a backing store
	 * nothing is read from or written to disk. */
	hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
	herr_t rc = H5Pset_fapl_core(fapl, 1 << 16, 0);
	if (rc >= 0)
		rc = H5Pset_file_image(fapl, (void *)buf, n);
	hid_t f = rc < 0 ? -1 : H5Fopen(H5_IMAGE_NAME, H5F_ACC_RDONLY, fapl);
	H5Pclose(fapl);
	if (f < 0)
		return err_set("%s: not a readable HDF5 file image (truncated or another format)",
		               H5_IMAGE_NAME);
	return check_format(f, H5_IMAGE_NAME, format);
}

/* After an HDF5 call that failed with errno cleared before it: whether a
 * write of the file failed, which HDF5 may find while making an object,
 * when it writes what its cache held. The message then says so
 * (h5_write_error). */
static int write_failed(void) { return write_errno(errno); }

hid_t h5_group(hid_t loc, const char *name)
{
	errno = 0;
	hid_t g = H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
	if (g < 0)
		return write_failed() ? object_write_error(loc, "group", name)
		                      : err_set("%s: cannot create group '%s'", h5_name(loc), name);
	return g;
}

hid_t h5_open_group(hid_t loc, const char *name)
{
	hid_t g = h5_exists(loc, name) ? H5Gopen2(loc, name, H5P_DEFAULT) : -1;
	if (g < 0)
		return err_set("%s: group '%s': missing", h5_name(loc), name);
	return g;
}

int h5_exists(hid_t loc, const char *path)
{
	/* Check each component so that a missing parent is not an error. */
	char buf[1024];
	snprintf(buf, sizeof buf, "%s", path);
	for (char *p = buf + (buf[0] == '/'); (p = strchr(p, '/')); p++) {
		*p = '\0';
		if (H5Lexists(loc, buf, H5P_DEFAULT) <= 0)
			return 0;
		*p = '/';
	}
	return H5Lexists(loc, buf, H5P_DEFAULT) > 0;
}

static int write_attr(hid_t obj, const char *name, hid_t type, hid_t space, const void *data)
{
	void *own = NULL;
	if (h5_shared(obj)) { /* rank 0's value (the same size on every rank) */
		size_t bytes = H5Tget_size(type) * (size_t)H5Sget_simple_extent_npoints(space);
		own = xmalloc(bytes + 1);
		memcpy(own, data, bytes);
		procs_->bcast(own, bytes);
		data = own;
	}
	if (H5Aexists(obj, name) > 0)
		H5Adelete(obj, name);
	errno = 0;
	hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
	herr_t rc = a < 0 ? -1 : H5Awrite(a, type, data);
	if (a >= 0)
		H5Aclose(a);
	H5Sclose(space);
	free(own);
	if (rc < 0 && write_failed())
		return object_write_error(obj, "attribute", name);
	if (rc < 0)
		return err_set("%s: cannot write attribute '%s' on '%s'", h5_name(obj), name,
		               obj_path(obj));
	return 0;
}

/* Strings are fixed-length, NUL-terminated UTF-8. (Format 1 stored them
 * with a variable length, in HDF5's global heap, where one damaged byte
 * crashes or hangs the library's reader.) size is in bytes, 0 for a
 * variable length. */
static hid_t str_type(size_t size)
{
	hid_t t = H5Tcopy(H5T_C_S1);
	H5Tset_size(t, size ? size : H5T_VARIABLE);
	H5Tset_strpad(t, H5T_STR_NULLTERM);
	H5Tset_cset(t, H5T_CSET_UTF8);
	return t;
}

int h5_attr_str(hid_t obj, const char *name, const char *value)
{
	char *own = NULL;
	if (h5_shared(obj)) { /* rank 0's value */
		uint64_t n = strlen(value) + 1;
		procs_->bcast(&n, sizeof n);
		own = xmalloc(n);
		if (procs_->rank == 0)
			memcpy(own, value, n);
		procs_->bcast(own, n);
		value = own;
	}
	hid_t t = str_type(strlen(value) + 1);
	int rc = write_attr(obj, name, t, H5Screate(H5S_SCALAR), value);
	H5Tclose(t);
	free(own);
	return rc;
}

/* The longest string attribute read (a configuration is a few kB). */
enum { STR_MAX = 64 << 20 };

/* The value of string attribute a of type ft, or NULL. */
static char *read_str(hid_t a, hid_t ft)
{
	if (H5Tis_variable_str(ft) > 0) {
		hid_t t = str_type(0);
		char *value = NULL, *out = NULL;
		if (H5Aread(a, t, &value) >= 0 && value) {
			out = xstrdup(value);
			H5free_memory(value);
		}
		H5Tclose(t);
		return out;
	}
	size_t size = H5Tget_size(ft);
	if (size == 0 || size > STR_MAX)
		return NULL;
	char *out = xmalloc(size + 1);
	if (H5Aread(a, ft, out) < 0) {
		free(out);
		return NULL;
	}
	out[size] = '\0';
	return out;
}

int h5_attr_f64(hid_t obj, const char *name, double value)
{
	return write_attr(obj, name, H5T_NATIVE_DOUBLE, H5Screate(H5S_SCALAR), &value);
}

int h5_attr_i64(hid_t obj, const char *name, int64_t value)
{
	return write_attr(obj, name, H5T_NATIVE_INT64, H5Screate(H5S_SCALAR), &value);
}

int h5_attr_f64v(hid_t obj, const char *name, const double *v, size_t n)
{
	hsize_t dim = n;
	return write_attr(obj, name, H5T_NATIVE_DOUBLE, H5Screate_simple(1, &dim, NULL), v);
}

/* Open attribute name on obj and check it holds n elements. */
static hid_t open_attr(hid_t obj, const char *name, hssize_t n)
{
	if (H5Aexists(obj, name) <= 0)
		return err_set("%s: attribute '%s' on '%s': missing", h5_name(obj), name,
		               obj_path(obj));
	hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
	hid_t s = H5Aget_space(a);
	hssize_t got = H5Sget_simple_extent_npoints(s);
	H5Sclose(s);
	if (got != n) {
		H5Aclose(a);
		return err_set("%s: attribute '%s' on '%s': has %lld values, expected %lld",
		               h5_name(obj), name, obj_path(obj), (long long)got, (long long)n);
	}
	return a;
}

char *h5_read_attr_str(hid_t obj, const char *name)
{
	hid_t a = open_attr(obj, name, 1);
	if (a < 0)
		return NULL;
	hid_t ft = H5Aget_type(a);
	char *out = H5Tget_class(ft) == H5T_STRING ? read_str(a, ft) : NULL;
	H5Tclose(ft);
	H5Aclose(a);
	if (!out)
		err_set("%s: attribute '%s': expected a string", h5_name(obj), name);
	return out;
}

static int read_attr(hid_t obj, const char *name, hid_t type, void *v, size_t n)
{
	hid_t a = open_attr(obj, name, (hssize_t)n);
	if (a < 0)
		return -1;
	herr_t rc = H5Aread(a, type, v);
	H5Aclose(a);
	if (rc < 0)
		return err_set("%s: attribute '%s': unreadable or not numeric", h5_name(obj), name);
	return 0;
}

int h5_read_attr_f64(hid_t obj, const char *name, double *value)
{
	return read_attr(obj, name, H5T_NATIVE_DOUBLE, value, 1);
}

int h5_read_attr_i64(hid_t obj, const char *name, int64_t *value)
{
	return read_attr(obj, name, H5T_NATIVE_INT64, value, 1);
}

int h5_read_attr_f64v(hid_t obj, const char *name, double *v, size_t n)
{
	return read_attr(obj, name, H5T_NATIVE_DOUBLE, v, n);
}

/* Rows of one chunk (chunked_plist), the piece size of h5_rows. */
static size_t chunk_rows(size_t cols) { return H5_PIECE_ELEMENTS / (cols ? cols : 1); }

/* The deflate level of every compressed dataset. */
enum { DEFLATE_LEVEL = 1 };

/* The values of a chunk of an extendible dataset (the history, the crack
 * log): each append reads its last chunk, adds the rows and compresses
 * the chunk again, so a small chunk keeps that cheap. With chunks of a
 * whole piece, a run file's flush took tens of milliseconds (about 30
 * history columns, each a 512 kB chunk for a few hundred rows). */
enum { EXT_CHUNK_ELEMENTS = 4096 };

/* Chunked, deflate-compressed creation properties for a dataset of the
 * given shape (rank 1 or 2); extendible along rows, in chunks of about
 * ext values, when ext > 0. */
static hid_t chunked_plist(size_t rows, size_t cols, size_t ext)
{
	hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
	hsize_t chunk[2] = {rows, cols ? cols : 1};
	hsize_t target = ext ? ext / chunk[1] : chunk_rows(cols);
	if (ext || chunk[0] > target)
		chunk[0] = target ? target : 1;
	if (chunk[0] == 0)
		chunk[0] = 1;
	H5Pset_chunk(dcpl, cols ? 2 : 1, chunk);
	H5Pset_shuffle(dcpl);
	H5Pset_deflate(dcpl, DEFLATE_LEVEL);
	return dcpl;
}

int h5_slab(hid_t d, hid_t type, size_t at, size_t m, size_t cols, void *buf, int write)
{
	hid_t fs = H5Dget_space(d);
	hsize_t start[2] = {at, 0}, count[2] = {m, cols};
	herr_t rc = H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL);
	hid_t mem = H5Screate_simple(cols ? 2 : 1, count, NULL);
	if (rc >= 0)
		rc = write ? H5Dwrite(d, type, mem, fs, H5P_DEFAULT, buf)
		           : H5Dread(d, type, mem, fs, H5P_DEFAULT, buf);
	H5Sclose(mem);
	H5Sclose(fs);
	return rc < 0 ? -1 : 0;
}

/* Runs of rows of d from consecutive rows of buf: run k is rows [base +
 * at[k], base + at[k] + n[k]). In a shared file a write every process
 * makes together (collective, as filtered datasets need), selecting
 * nothing where not mine; in another, the process's own. */
static int write_runs(hid_t d, hid_t type, size_t base, const size_t *at, const size_t *n,
                      size_t nruns, size_t cols, const void *buf, int mine)
{
	size_t m = 0, row = (cols ? cols : 1) * H5Tget_size(type);
	for (size_t k = 0; k < nruns; k++)
		m += n[k];
	if (!h5_shared(d)) {
		int rc = 0;
		for (size_t k = 0, done = 0; !rc && k < nruns; done += n[k++])
			rc = n[k] ? h5_slab(d, type, base + at[k], n[k], cols,
			                    (unsigned char *)buf + done * row, 1)
			          : 0;
		return rc;
	}
	mine = mine && m > 0;
	/* Each process looks up the chunks of its own rows: not one alone
	 * into a sync point (h5_settle). */
	h5_settle(d);
	hid_t fs = H5Dget_space(d);
	herr_t rc = H5Sselect_none(fs);
	for (size_t k = 0, first = 1; mine && rc >= 0 && k < nruns; k++) {
		hsize_t start[2] = {base + at[k], 0}, count[2] = {n[k], cols};
		if (n[k])
			rc = H5Sselect_hyperslab(fs, first ? H5S_SELECT_SET : H5S_SELECT_OR, start,
			                         NULL, count, NULL);
		first = first && !n[k];
	}
	hsize_t count[2] = {mine ? m : 1, cols};
	hid_t mem = H5Screate_simple(cols ? 2 : 1, count, NULL);
	if (rc >= 0 && !mine)
		rc = H5Sselect_none(mem);
	/* Values converted here to the file's type: a conversion would make
	 * HDF5 write independently, which a filtered dataset refuses. */
	hid_t ft = H5Dget_type(d);
	void *conv = NULL;
	if (rc >= 0 && mine && H5Tequal(ft, type) <= 0) {
		size_t nv = m * (cols ? cols : 1), sz = H5Tget_size(ft) > H5Tget_size(type)
		                                            ? H5Tget_size(ft)
		                                            : H5Tget_size(type);
		conv = xmalloc(nv * sz);
		memcpy(conv, buf, nv * H5Tget_size(type));
		rc = H5Tconvert(type, ft, nv, conv, NULL, H5P_DEFAULT);
		buf = conv;
	}
	hid_t xfer = procs_->dxpl();
	static const double none;
	if (rc >= 0)
		rc = H5Dwrite(d, ft, mem, fs, xfer, mine ? buf : &none);
	H5Pclose(xfer);
	H5Tclose(ft);
	free(conv);
	H5Sclose(mem);
	H5Sclose(fs);
	return rc < 0 ? -1 : 0;
}

static int write_rows(hid_t d, hid_t type, size_t at, size_t m, size_t cols, const void *buf,
                      int mine)
{
	return write_runs(d, type, at, &(size_t){0}, &m, 1, cols, buf, mine);
}

int h5_rows_at(hid_t d, hid_t type, const int32_t *rows, size_t m, size_t cols, void *buf)
{
	if (!m)
		return 0;
	size_t w = cols ? cols : 1, rank = cols ? 2 : 1;
	hsize_t *at = xmalloc(m * w * rank * sizeof *at);
	for (size_t k = 0; k < m; k++)
		for (size_t c = 0; c < w; c++) {
			hsize_t *p = at + (k * w + c) * rank;
			p[0] = (hsize_t)rows[k];
			if (cols)
				p[1] = c;
		}
	hid_t fs = H5Dget_space(d);
	herr_t rc = H5Sselect_elements(fs, H5S_SELECT_SET, m * w, at);
	hsize_t count = m * w;
	hid_t mem = H5Screate_simple(1, &count, NULL);
	if (rc >= 0)
		rc = H5Dread(d, type, mem, fs, H5P_DEFAULT, buf);
	H5Sclose(mem);
	H5Sclose(fs);
	free(at);
	return rc < 0 ? -1 : 0;
}

int h5_rows_open(h5_rows *r, hid_t loc, const char *name, hid_t type, size_t rows, size_t cols,
                 const char *unit)
{
	*r = (h5_rows){.loc = loc, .d = -1, .type = type, .name = name, .rows = rows, .cols = cols};
	hsize_t dims[2] = {rows, cols};
	hid_t space = H5Screate_simple(cols ? 2 : 1, dims, NULL);
	r->chunked = rows * (cols ? cols : 1) >= 4096;
	hid_t dcpl = r->chunked ? chunked_plist(rows, cols, 0) : H5P_DEFAULT;
	r->d = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
	if (r->d >= 0 && unit && unit[0] && h5_attr_str(r->d, "units", unit))
		r->failed = 1;
	if (dcpl != H5P_DEFAULT)
		H5Pclose(dcpl);
	H5Sclose(space);
	if (r->d < 0 || r->failed) {
		r->failed = 1;
		return h5_write_dataset_error(loc, name);
	}
	return 0;
}

size_t h5_rows_piece(const h5_rows *r)
{
	size_t left = r->rows - r->at, piece = chunk_rows(r->cols);
	return left < piece ? left : piece;
}

int h5_rows_put(h5_rows *r, const void *data, size_t m)
{
	if (r->failed || m == 0)
		return r->failed ? -1 : 0;
	if (m > r->rows - r->at) {
		r->failed = 1;
		return err_set("%s: dataset '%s': more rows than declared", h5_name(r->loc),
		               r->name);
	}
	if (write_rows(r->d, r->type, r->at, m, r->cols, data, h5_rank() == 0)) {
		r->failed = 1;
		return h5_write_dataset_error(r->loc, r->name);
	}
	r->at += m;
	return 0;
}

int h5_rows_write_at(h5_rows *r, size_t at, size_t m, const void *buf)
{
	int bad =
	    r->failed || at + m > r->rows || write_rows(r->d, r->type, at, m, r->cols, buf, 1) != 0;
	uint64_t got[2] = {m, (uint64_t)bad};
	if (h5_shared(r->d))
		procs_->sum(got, 2);
	if (got[1]) {
		r->failed = 1;
		return h5_write_dataset_error(r->loc, r->name);
	}
	r->at += got[0];
	return 0;
}

int h5_rows_close(h5_rows *r)
{
	int rc = r->failed ? -1 : 0;
	if (!rc && r->at != r->rows)
		rc = err_set("%s: dataset '%s': %zu of %zu rows written", h5_name(r->loc), r->name,
		             r->at, r->rows);
	if (r->d >= 0)
		H5Dclose(r->d);
	r->d = -1;
	return rc;
}

static int threads_ = 1;
void h5_set_threads(int n) { threads_ = n > 0 ? n : 1; }

/* HDF5's shuffle filter (H5Zshuffle.c): byte k of every element, for k =
 * 0, 1, ..., size - 1 in turn, from n elements of size bytes. */
static void shuffle(unsigned char *restrict out, const unsigned char *restrict in, size_t n,
                    size_t size)
{
	if (size < 2 || n < 2) {
		memcpy(out, in, n * size);
		return;
	}
	for (size_t i = 0; i < n; i++)
		for (size_t k = 0; k < size; k++)
			out[k * n + i] = in[i * size + k];
}

size_t h5_chunk_rows(size_t rows, size_t cols)
{
	size_t piece = chunk_rows(cols);
	return rows * (cols ? cols : 1) >= 4096 && rows > piece ? piece : 0;
}

static size_t chunk_zcap(size_t bytes) { return (size_t)ceil((double)bytes * 1.001) + 12; }

/* A chunk of piece rows of width values of size bytes, the first m of them
 * in raw (room for piece), shuffled and deflated into z (chunk_zcap bytes)
 * with shuf (room for the chunk) as scratch, as the dataset's filters
 * would: the bytes to write are returned, *data points at them and *mask
 * is the chunk's filter mask. The deflate filter (H5Zdeflate.c) compresses
 * into ceil(1.001 bytes) + 12 bytes; if that fails, the filter, being
 * optional, is skipped for the chunk and flagged in its filter mask. */
static size_t chunk_compress(unsigned char *raw, unsigned char *shuf, unsigned char *z,
                             size_t piece, size_t m, size_t width, size_t size, unsigned *mask,
                             const unsigned char **data)
{
	size_t bytes = piece * width * size;
	memset(raw + m * width * size, 0, bytes - m * width * size);
	shuffle(shuf, raw, piece * width, size);
	uLongf zn = (uLongf)chunk_zcap(bytes);
	int ok = compress2(z, &zn, shuf, (uLong)bytes, DEFLATE_LEVEL) == Z_OK;
	*mask = ok ? 0 : 1u << 1;
	*data = ok ? z : shuf;
	return ok ? (size_t)zn : bytes;
}

/* One chunk of h5_rows_fill_all: rows [at, at + m) of dataset d, in a
 * chunk of piece rows (or, d being too small to be chunked, as they are),
 * and once made, the bytes to write and their filter mask. */
typedef struct {
	int d, made;
	size_t at, m, piece, size; /* size: bytes of a value (no HDF5 call on the threads) */
	unsigned char *out;
	size_t n;
	unsigned mask;
} chunk_task;

/* Chunk t's rows filled and, when chunked, compressed (chunk_compress,
 * with the thread's buffers raw and shuf) into t->out, of cap bytes. */
static void chunk_make(const h5_rows *r, chunk_task *t, h5_fill fill, void *ctx, unsigned char *raw,
                       unsigned char *shuf, size_t cap)
{
	size_t width = r->cols ? r->cols : 1;
	const unsigned char *data = raw;
	t->out = xmalloc(cap);
	t->mask = 0;
	t->n = t->m * width * t->size;
	fill(ctx, t->at, t->m, raw);
	if (r->chunked)
		t->n = chunk_compress(raw, shuf, t->out, t->piece, t->m, width, t->size, &t->mask,
		                      &data);
	if (data != t->out)
		memcpy(t->out, data, t->n);
}

static int chunk_write(h5_rows *r, const chunk_task *t)
{
	if (!r->chunked)
		return write_rows(r->d, r->type, t->at, t->m, r->cols, t->out, 1);
	hsize_t offset[2] = {t->at, 0};
	return H5Dwrite_chunk(r->d, H5P_DEFAULT, t->mask, offset, t->n, t->out) < 0 ? -1 : 0;
}

/* The state of an h5_rows_fill_all shared by its threads. */
typedef struct {
	h5_rows *const *r;
	chunk_task *task;
	size_t ntask, written; /* tasks written (in order), under chunks_order */
	int failed, werrno;    /* the dataset whose write failed, or -1 */
} chunk_order;

/* Inside critical(chunks_order): the chunks made from the first not yet
 * written on, written in order (by whichever thread made the one that
 * was next), and their bytes freed. */
static void chunks_write(chunk_order *o)
{
	for (chunk_task *t; o->written < o->ntask && (t = &o->task[o->written])->made;) {
		if (o->failed < 0) {
			int w;
#pragma omp critical(dem_hdf5) /* fill may read another file (assembly.c) */
			w = chunk_write(o->r[t->d], t);
			if (w < 0) {
				o->werrno = errno;
#pragma omp atomic write
				o->failed = t->d;
			}
		}
		free(t->out);
		t->out = NULL;
#pragma omp atomic write
		o->written = o->written + 1;
	}
}

/* Whether the rows left of r are whole chunks of one process's file
 * (h5_rows_fill_all). */
static int whole_chunks(const h5_rows *r)
{
	return !h5_shared(r->d) && (r->chunked ? r->at % chunk_rows(r->cols) == 0 : r->at == 0);
}

int h5_rows_fill_all(h5_rows *const *r, int n, const h5_fill *fill, void *const *ctx)
{
	for (int d = 0; d < n; d++)
		if (r[d]->failed)
			return -1;
	for (int d = 0; d < n; d++)
		if (!whole_chunks(r[d])) {
			int rc = 0;
			for (int k = 0; !rc && k < n; k++)
				rc = h5_rows_fill(r[k], fill[k], ctx[k]);
			return rc;
		}
	size_t ntask = 0, cap = 0, bytes = 0;
	chunk_task *task = NULL;
	for (int d = 0; d < n; d++) {
		size_t piece = chunk_rows(r[d]->cols), size = H5Tget_size(r[d]->type);
		if (!r[d]->chunked || r[d]->rows <= piece)
			piece = r[d]->rows; /* one chunk (chunked_plist), or none */
		for (size_t at = r[d]->at; at < r[d]->rows; at += piece) {
			if (ntask == cap)
				task = xrealloc(task, (cap = cap ? 2 * cap : 16) * sizeof *task);
			size_t m = r[d]->rows - at < piece ? r[d]->rows - at : piece;
			task[ntask++] =
			    (chunk_task){.d = d, .at = at, .m = m, .piece = piece, .size = size};
		}
		size_t b = piece * (r[d]->cols ? r[d]->cols : 1) * size;
		bytes = b > bytes ? b : bytes;
	}
	/* Each thread makes the next chunk of the list and writes what is made
	 * in order, so none waits for another's chunk to be written; at most
	 * window chunks are made ahead of the writes (a thread that would go
	 * further spins until the next write: memory stays a few chunks). */
	int team = threads_ < (int)ntask ? threads_ : (int)ntask;
	size_t zcap = chunk_zcap(bytes), next = 0, window = 4 * (size_t)(team > 0 ? team : 1);
	chunk_order o = {r, task, ntask, 0, -1, 0};
#pragma omp parallel num_threads(team > 0 ? team : 1)
	{
		unsigned char *raw = xmalloc(bytes), *shuf = xmalloc(bytes);
		for (;;) {
			size_t k, written;
			int stop;
#pragma omp atomic capture
			k = next++;
			if (k >= ntask)
				break;
			do {
#pragma omp atomic read
				written = o.written;
			} while (k >= written + window);
#pragma omp atomic read
			stop = o.failed;
			chunk_task *t = &task[k];
			if (stop < 0)
				chunk_make(r[t->d], t, fill[t->d], ctx[t->d], raw, shuf, zcap);
#pragma omp critical(chunks_order)
			{
				t->made = 1;
				chunks_write(&o);
			}
		}
		free(raw), free(shuf);
	}
	free(task);
	for (int d = 0; d < n; d++) {
		r[d]->failed = o.failed >= 0;
		r[d]->at = o.failed >= 0 ? r[d]->at : r[d]->rows;
	}
	if (o.failed >= 0) {
		errno = o.werrno; /* for the message: the write failed on another thread */
		return h5_write_dataset_error(r[o.failed]->loc, r[o.failed]->name);
	}
	return 0;
}

/* The chunks a process writes at a time in a shared file. */
enum { ROUND_CHUNKS = 16 };

/* h5_rows_fill in a shared file: every process fills and writes an even
 * share of each round's chunks (HDF5 compresses them where they are
 * written), all together. */
static int fill_shared(h5_rows *r, h5_fill fill, void *ctx, size_t piece)
{
	size_t row = (r->cols ? r->cols : 1) * H5Tget_size(r->type), at0 = r->at;
	size_t n = (r->rows - at0 + piece - 1) / piece, np = (size_t)procs_->size;
	unsigned char *buf = xmalloc(ROUND_CHUNKS * piece * row);
	int rc = 0;
	for (size_t c0 = 0, nc; !rc && c0 < n; c0 += nc) {
		nc = n - c0 < ROUND_CHUNKS * np ? n - c0 : ROUND_CHUNKS * np;
		size_t q = (size_t)procs_->rank, lo = at0 + (c0 + q * nc / np) * piece,
		       hi = at0 + (c0 + (q + 1) * nc / np) * piece;
		lo = lo < r->rows ? lo : r->rows;
		hi = hi < r->rows ? hi : r->rows;
		for (size_t at = lo, m; at < hi; at += m) {
			m = hi - at < piece ? hi - at : piece;
			fill(ctx, at, m, buf + (at - lo) * row);
		}
		rc = h5_rows_write_at(r, lo, hi - lo, buf);
	}
	free(buf);
	return rc;
}

int h5_rows_fill(h5_rows *r, h5_fill fill, void *ctx)
{
	if (r->failed)
		return -1;
	size_t piece = chunk_rows(r->cols);
	if (r->chunked && r->at % piece == 0 && h5_shared(r->d))
		return fill_shared(r, fill, ctx, piece);
	/* Whole chunks from the first: compressed here. */
	if (whole_chunks(r))
		return h5_rows_fill_all(&r, 1, &fill, &ctx);
	/* What is left (the rest of a chunk begun by h5_rows_put, or a shared
	 * file's dataset too small to be chunked): through HDF5. */
	void *buf = xmalloc(piece * (r->cols ? r->cols : 1) * H5Tget_size(r->type));
	int rc = 0;
	for (size_t m; !rc && (m = h5_rows_piece(r)) > 0;) {
		fill(ctx, r->at, m, buf);
		rc = h5_rows_put(r, buf, m);
	}
	free(buf);
	return rc;
}

void h5_from_whole(void *ctx, size_t at, size_t m, void *buf)
{
	const h5_whole *w = ctx;
	memcpy(buf, (const unsigned char *)w->data + at * w->row, m * w->row);
}

int h5_write(hid_t loc, const char *name, hid_t type, const void *data, size_t rows, size_t cols,
             const char *unit)
{
	h5_rows r;
	h5_whole w = {data, (cols ? cols : 1) * H5Tget_size(type)};
	int rc = h5_rows_open(&r, loc, name, type, rows, cols, unit);
	rc = rc || h5_rows_fill(&r, h5_from_whole, &w);
	return h5_rows_close(&r) || rc ? -1 : 0;
}

/* (h5.h) The values take their type's size in the storage, unless a
 * filter compresses them (deflate to a 1032th at most), and the storage
 * cannot be larger than the file. */
int h5_stored_holds(hid_t d, double n)
{
	if (n == 0)
		return 1;
	double stored = (double)H5Dget_storage_size(d);
	hsize_t size = 0;
	hid_t f = H5Iget_file_id(d);
	if (f < 0 || H5Fget_filesize(f, &size) < 0)
		size = 0;
	if (f >= 0)
		H5Fclose(f);
	hid_t t = H5Dget_type(d), dcpl = H5Dget_create_plist(d);
	double bytes = n * (double)(t < 0 ? 1 : H5Tget_size(t));
	int filtered = dcpl < 0 || H5Pget_nfilters(dcpl) != 0;
	if (t >= 0)
		H5Tclose(t);
	if (dcpl >= 0)
		H5Pclose(dcpl);
	return bytes <= (filtered ? 1032 : 1) * fmin(stored, (double)size);
}

int h5_read(hid_t loc, const char *name, hid_t type, void **data, size_t *rows, size_t cols)
{
	size_t first, held;
	return h5_read_part(loc, name, type, data, rows, cols, 0, 1, &first, &held);
}

int h5_read_part(hid_t loc, const char *name, hid_t type, void **data, size_t *rows, size_t cols,
                 int part, int parts, size_t *first, size_t *held)
{
	*data = NULL;
	if (!h5_exists(loc, name))
		return err_set("%s: dataset '%s' in '%s': missing", h5_name(loc), name,
		               obj_path(loc));
	hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
	if (d < 0)
		return err_set("%s: dataset '%s': cannot open", h5_name(loc), name);
	hid_t s = H5Dget_space(d);
	hsize_t dims[2] = {0, 0};
	int rank = H5Sget_simple_extent_ndims(s);
	int want = cols ? 2 : 1;
	if (rank == want)
		H5Sget_simple_extent_dims(s, dims, NULL);
	H5Sclose(s);
	if (rank != want || (cols && dims[1] != cols)) {
		H5Dclose(d);
		if (cols)
			return err_set("%s: dataset '%s': wrong shape: expected [N, %zu]",
			               h5_name(loc), name, cols);
		return err_set("%s: dataset '%s': wrong shape: expected [N]", h5_name(loc), name);
	}
	if (!h5_stored_holds(d, (double)dims[0] * (double)(cols ? cols : 1))) {
		H5Dclose(d);
		return err_set("%s: dataset '%s': %llu rows, more than the file holds (a damaged "
		               "file)",
		               h5_name(loc), name, (unsigned long long)dims[0]);
	}
	*first = (size_t)dims[0] * (size_t)part / (size_t)parts;
	*held = (size_t)dims[0] * (size_t)(part + 1) / (size_t)parts - *first;
	size_t n = *held * (cols ? cols : 1);
	void *buf = xmalloc(n * H5Tget_size(type) + 1);
	int whole = *held == (size_t)dims[0];
	if (n && (whole ? H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf)
	                : h5_slab(d, type, *first, *held, cols, buf, 0)) < 0) {
		free(buf);
		H5Dclose(d);
		return err_set("%s: dataset '%s': unreadable (truncated or corrupt file?)",
		               h5_name(loc), name);
	}
	H5Dclose(d);
	*data = buf;
	*rows = (size_t)dims[0];
	return 0;
}

int h5_read_n(hid_t loc, const char *name, hid_t type, void **data, size_t rows, size_t cols)
{
	size_t got = 0;
	if (h5_read(loc, name, type, data, &got, cols))
		return -1;
	if (got != rows) {
		free(*data);
		*data = NULL;
		return err_set("%s: dataset '%s': has %zu rows, expected %zu", h5_name(loc), name,
		               got, rows);
	}
	return 0;
}

int h5_create_ext(hid_t loc, const char *name, hid_t type, size_t cols, const char *unit)
{
	hsize_t dims[2] = {0, cols}, maxdims[2] = {H5S_UNLIMITED, cols};
	hid_t space = H5Screate_simple(cols ? 2 : 1, dims, maxdims);
	hid_t dcpl = chunked_plist(0, cols, EXT_CHUNK_ELEMENTS);
	errno = 0;
	hid_t d = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
	int rc = d < 0 ? -1 : 0;
	if (rc == 0 && unit && unit[0])
		rc = h5_attr_str(d, "units", unit);
	if (d >= 0)
		H5Dclose(d);
	H5Pclose(dcpl);
	H5Sclose(space);
	if (rc < 0 && d < 0 && write_failed())
		return h5_write_dataset_error(loc, name);
	if (rc < 0)
		return err_set("%s: cannot create dataset '%s'", h5_name(loc), name);
	return 0;
}

/* Extend dataset name by rows rows and write runs of them (write_runs). */
static int append(hid_t loc, const char *name, hid_t type, const void *data, size_t rows,
                  size_t cols, const size_t *run_at, const size_t *run_n, size_t nruns, int mine)
{
	if (rows == 0)
		return 0;
	hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
	if (d < 0)
		return err_set("%s: dataset '%s': missing", h5_name(loc), name);
	hid_t s = H5Dget_space(d);
	hsize_t dims[2] = {0, cols};
	H5Sget_simple_extent_dims(s, dims, NULL);
	H5Sclose(s);
	size_t at = dims[0];
	dims[0] += rows;
	herr_t rc = H5Dset_extent(d, dims);
	if (rc >= 0)
		rc = write_runs(d, type, at, run_at, run_n, nruns, cols, data, mine);
	H5Dclose(d);
	if (rc < 0)
		return h5_write_dataset_error(loc, name);
	return 0;
}

int h5_append(hid_t loc, const char *name, hid_t type, const void *data, size_t rows, size_t cols)
{
	return append(loc, name, type, data, rows, cols, &(size_t){0}, &rows, 1, h5_rank() == 0);
}

int h5_append_runs(hid_t loc, const char *name, hid_t type, const void *data, size_t rows,
                   size_t cols, const size_t *run_at, const size_t *run_n, size_t nruns)
{
	return append(loc, name, type, data, rows, cols, run_at, run_n, nruns, 1);
}

int h5_truncate(hid_t loc, const char *name, size_t rows)
{
	hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
	if (d < 0)
		return err_set("%s: dataset '%s': missing", h5_name(loc), name);
	hid_t s = H5Dget_space(d);
	hsize_t dims[2] = {0, 0};
	int rank = H5Sget_simple_extent_ndims(s);
	H5Sget_simple_extent_dims(s, dims, NULL);
	H5Sclose(s);
	herr_t rc = -1;
	if (rank >= 1 && dims[0] >= rows) {
		dims[0] = rows;
		rc = H5Dset_extent(d, dims);
	}
	H5Dclose(d);
	if (rc < 0)
		return err_set("%s: dataset '%s': cannot keep %zu rows (it has %llu)", h5_name(loc),
		               name, rows, (unsigned long long)dims[0]);
	return 0;
}

long long h5_rows_of(hid_t loc, const char *name)
{
	hid_t d = h5_exists(loc, name) ? H5Dopen2(loc, name, H5P_DEFAULT) : -1;
	if (d < 0)
		return -1;
	hid_t s = H5Dget_space(d);
	hsize_t dims[3] = {0, 0, 0};
	int rank = H5Sget_simple_extent_ndims(s);
	if (rank >= 1 && rank <= 3)
		H5Sget_simple_extent_dims(s, dims, NULL);
	H5Sclose(s);
	H5Dclose(d);
	return rank >= 1 && rank <= 3 ? (long long)dims[0] : -1;
}

char *h5_read_units(hid_t loc, const char *name)
{
	hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
	if (d < 0) {
		err_set("%s: dataset '%s': cannot open", h5_name(loc), name);
		return NULL;
	}
	char *out = H5Aexists(d, "units") > 0  ? h5_read_attr_str(d, "units")
	            : H5Aexists(d, "unit") > 0 ? h5_read_attr_str(d, "unit")
	                                       : xstrdup("");
	H5Dclose(d);
	return out;
}

int h5_scale(hid_t loc, const char *name)
{
	hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
	herr_t rc = d < 0 ? -1 : H5DSset_scale(d, name);
	if (d >= 0)
		H5Dclose(d);
	if (rc < 0)
		return err_set("%s: cannot make dataset '%s' a dimension scale", h5_name(loc),
		               name);
	return 0;
}

/* Rows of an index (h5_fill): the values at, at + 1, ... */
static void index_rows(void *ctx, size_t at, size_t m, void *buf)
{
	(void)ctx;
	int64_t *v = buf;
	for (size_t k = 0; k < m; k++)
		v[k] = (int64_t)(at + k);
}

/* Rows [at, at + n) of the extendible index dataset d. */
static int put_index(hid_t d, size_t at, size_t n)
{
	int rc = 0;
	int64_t *v = xmalloc(H5_PIECE_ELEMENTS * sizeof *v);
	for (size_t done = 0; !rc && done < n;) {
		size_t m = n - done < H5_PIECE_ELEMENTS ? n - done : H5_PIECE_ELEMENTS;
		index_rows(NULL, at + done, m, v);
		rc = write_rows(d, H5T_NATIVE_INT64, at + done, m, 0, v, h5_rank() == 0);
		done += m;
	}
	free(v);
	return rc;
}

int h5_index(hid_t loc, const char *name, size_t rows, int ext)
{
	if (ext) {
		if (h5_create_ext(loc, name, H5T_NATIVE_INT64, 0, NULL))
			return -1;
	} else {
		h5_rows r;
		int rc = h5_rows_open(&r, loc, name, H5T_NATIVE_INT64, rows, 0, NULL);
		rc = rc || h5_rows_fill(&r, index_rows, NULL);
		if (h5_rows_close(&r) || rc)
			return -1;
	}
	return h5_scale(loc, name) || (ext && h5_index_append(loc, name, rows)) ? -1 : 0;
}

int h5_index_append(hid_t loc, const char *name, size_t rows)
{
	if (rows == 0)
		return 0;
	long long at = h5_rows_of(loc, name);
	hid_t d = at < 0 ? -1 : H5Dopen2(loc, name, H5P_DEFAULT);
	hsize_t dims[1] = {(hsize_t)at + rows};
	int rc = d < 0 || H5Dset_extent(d, dims) < 0 || put_index(d, (size_t)at, rows);
	if (d >= 0)
		H5Dclose(d);
	return rc ? h5_write_dataset_error(loc, name) : 0;
}

int h5_attach(hid_t loc, const char *name, const char *const *dims, int naxes)
{
	hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
	int rc = d < 0;
	for (int k = 0; !rc && k < naxes; k++) {
		if (!dims[k])
			continue;
		hid_t s = H5Dopen2(loc, dims[k], H5P_DEFAULT);
		rc = s < 0 || H5DSattach_scale(d, s, (unsigned)k) < 0;
		if (s >= 0)
			H5Dclose(s);
		if (rc)
			err_set("%s: cannot attach dimension scale '%s' to dataset '%s'",
			        h5_name(loc), dims[k], name);
	}
	if (d >= 0)
		H5Dclose(d);
	else
		err_set("%s: dataset '%s': cannot open", h5_name(loc), name);
	return rc ? -1 : 0;
}

/* H5DSiterate_scales visitor: remember the scale attached to an axis. */
static herr_t scale_of(hid_t d, unsigned axis, hid_t scale, void *out)
{
	(void)d, (void)axis;
	*(hid_t *)out = H5Dopen2(scale, ".", H5P_DEFAULT);
	return 1;
}

int h5_delete(hid_t loc, const char *name)
{
	if (!h5_exists(loc, name))
		return 0;
	hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
	if (d >= 0) {
		hid_t s = H5Dget_space(d);
		int rank = H5Sget_simple_extent_ndims(s);
		H5Sclose(s);
		for (int k = 0; k < rank; k++) {
			hid_t scale = -1;
			if (H5DSget_num_scales(d, (unsigned)k) > 0 &&
			    H5DSiterate_scales(d, (unsigned)k, NULL, scale_of, &scale) >= 0 &&
			    scale >= 0)
				H5DSdetach_scale(d, scale, (unsigned)k);
			if (scale >= 0)
				H5Dclose(scale);
		}
		H5Dclose(d);
	}
	if (H5Ldelete(loc, name, H5P_DEFAULT) < 0)
		return err_set("%s: cannot delete dataset '%s'", h5_name(loc), name);
	return 0;
}
