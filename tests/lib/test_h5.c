/* Datasets of several chunks, compressed by h5_rows_fill on any number of
 * threads, read back with plain H5Dread as written, and are stored as
 * HDF5's own filters store them: the same chunks (offsets, filter masks,
 * sizes, bytes) at the same addresses, in a file of the same size, as the
 * same rows written a piece at a time through H5Dwrite. Written all at once
 * (h5_rows_fill_all), they read back the same, their chunks are HDF5's,
 * and the file is the same on 1 and 3 threads. */
#include <stdint.h>
#include <unistd.h>

#include "lib/err.h"
#include "lib/h5.h"
#include "tests/check.h"

enum { NSETS = 6 };
static const struct {
	const char *name;
	size_t rows, cols;
	int type; /* 0 double, 1 int32, 2 uint8, 3 int64 */
} sets[NSETS] = {
    {"x", 70001, 3, 0},      /* 4 chunks, the last partial */
    {"i", 200003, 0, 1},     /* 4 chunks, the last partial */
    {"state", 150000, 0, 2}, /* elements of one byte: no shuffling */
    {"k", 131072, 0, 3},     /* 2 whole chunks */
    {"fs", 65536, 3, 0},     /* 4 chunks, the last of one row */
    {"small", 5000, 0, 0},   /* one chunk: HDF5's filters */
};

static hid_t type_of(int t)
{
	return t == 0   ? H5T_NATIVE_DOUBLE
	       : t == 1 ? H5T_NATIVE_INT32
	       : t == 2 ? H5T_NATIVE_UINT8
	                : H5T_NATIVE_INT64;
}

/* Values that compress somewhat, as a run's do: smooth, with noisy low bits. */
static void *values(int s)
{
	size_t n = sets[s].rows * (sets[s].cols ? sets[s].cols : 1);
	size_t size = H5Tget_size(type_of(sets[s].type));
	unsigned char *v = malloc(n * size);
	uint64_t r = 88172645463325252u + (uint64_t)s;
	for (size_t k = 0; k < n; k++) {
		r ^= r << 13, r ^= r >> 7, r ^= r << 17;
		double x = 0.05 * sin(1e-4 * (double)k) + 1e-9 * (double)(r % 1000);
		int32_t i = (int32_t)(k / 3) + (int32_t)(r % 4);
		uint8_t b = (uint8_t)(r % 7 == 0);
		int64_t l = (int64_t)k;
		memcpy(v + k * size,
		       sets[s].type == 0   ? (void *)&x
		       : sets[s].type == 1 ? (void *)&i
		       : sets[s].type == 2 ? (void *)&b
		                           : (void *)&l,
		       size);
	}
	return v;
}

/* Every set opened, then all written by one h5_rows_fill_all. */
static void fill_all(hid_t f, void *const *data)
{
	h5_rows rs[NSETS], *r[NSETS];
	h5_whole c[NSETS];
	h5_fill fill[NSETS];
	void *ctx[NSETS];
	for (int s = 0; s < NSETS; s++) {
		hid_t t = type_of(sets[s].type);
		CHECK(h5_rows_open(&rs[s], f, sets[s].name, t, sets[s].rows, sets[s].cols, NULL) ==
		      0);
		c[s] = (h5_whole){data[s], (sets[s].cols ? sets[s].cols : 1) * H5Tget_size(t)};
		r[s] = &rs[s], fill[s] = h5_from_whole, ctx[s] = &c[s];
	}
	CHECK(h5_rows_fill_all(r, NSETS, fill, ctx) == 0);
	for (int s = 0; s < NSETS; s++)
		CHECK(h5_rows_close(&rs[s]) == 0);
}

/* The file of every set, written with h5_write (fill_path 1), all at once
 * (2, fill_all) on threads threads, or a piece at a time through H5Dwrite. */
static void write_file(const char *path, int fill_path, int threads, void *const *data)
{
	char tmp[4096];
	h5_set_threads(threads);
	hid_t f = h5_create(path, tmp, sizeof tmp);
	CHECK(f >= 0);
	if (fill_path == 2)
		fill_all(f, data);
	for (int s = 0; fill_path < 2 && s < NSETS; s++) {
		hid_t t = type_of(sets[s].type);
		if (fill_path) {
			CHECK(h5_write(f, sets[s].name, t, data[s], sets[s].rows, sets[s].cols,
			               NULL) == 0);
			continue;
		}
		size_t row = (sets[s].cols ? sets[s].cols : 1) * H5Tget_size(t);
		h5_rows r;
		CHECK(h5_rows_open(&r, f, sets[s].name, t, sets[s].rows, sets[s].cols, NULL) == 0);
		for (size_t m; (m = h5_rows_piece(&r)) > 0;)
			CHECK(h5_rows_put(&r, (const unsigned char *)data[s] + r.at * row, m) == 0);
		CHECK(h5_rows_close(&r) == 0);
	}
	CHECK(h5_commit(f, tmp, path) == 0);
	h5_set_threads(1);
}

/* Every set of file path reads back (plain H5Dread) as data. */
static void check_values(const char *path, void *const *data)
{
	hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
	CHECK(f >= 0);
	for (int s = 0; s < NSETS; s++) {
		hid_t t = type_of(sets[s].type);
		size_t bytes = sets[s].rows * (sets[s].cols ? sets[s].cols : 1) * H5Tget_size(t);
		unsigned char *back = malloc(bytes);
		hid_t d = H5Dopen2(f, sets[s].name, H5P_DEFAULT);
		CHECK(H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, back) >= 0);
		CHECK(memcmp(back, data[s], bytes) == 0);
		H5Dclose(d);
		free(back);
	}
	H5Fclose(f);
}

/* Files a and b hold their sets in the same chunks, stored alike; placed
 * alike too (the same addresses, files of the same size) if placed. */
static void check_same_chunks(const char *a, const char *b, int placed)
{
	hid_t fa = H5Fopen(a, H5F_ACC_RDONLY, H5P_DEFAULT),
	      fb = H5Fopen(b, H5F_ACC_RDONLY, H5P_DEFAULT);
	hsize_t sa = 0, sb = 0;
	CHECK(H5Fget_filesize(fa, &sa) >= 0 && H5Fget_filesize(fb, &sb) >= 0);
	CHECK(sa == sb || !placed);
	size_t differ = 0;
	for (int s = 0; s < NSETS; s++) {
		hid_t da = H5Dopen2(fa, sets[s].name, H5P_DEFAULT);
		hid_t db = H5Dopen2(fb, sets[s].name, H5P_DEFAULT);
		hid_t spa = H5Dget_space(da), spb = H5Dget_space(db);
		hsize_t na = 0, nb = 0;
		CHECK(H5Dget_num_chunks(da, spa, &na) >= 0 && H5Dget_num_chunks(db, spb, &nb) >= 0);
		CHECK(na == nb && na >= 1);
		for (hsize_t k = 0; k < na && na == nb; k++) {
			hsize_t oa[2], ob[2], size_a = 0, size_b = 0;
			unsigned ma = 9, mb = 9;
			haddr_t aa = 0, ab = 0;
			CHECK(H5Dget_chunk_info(da, spa, k, oa, &ma, &aa, &size_a) >= 0);
			CHECK(H5Dget_chunk_info(db, spb, k, ob, &mb, &ab, &size_b) >= 0);
			differ +=
			    oa[0] != ob[0] || ma != mb || (placed && aa != ab) || size_a != size_b;
			unsigned char *ca = malloc(size_a + 1), *cb = malloc(size_b + 1);
			uint32_t fa_mask = 9, fb_mask = 9;
			CHECK(H5Dread_chunk(da, H5P_DEFAULT, oa, &fa_mask, ca) >= 0);
			CHECK(H5Dread_chunk(db, H5P_DEFAULT, ob, &fb_mask, cb) >= 0);
			differ += fa_mask != 0 || fb_mask != 0 || size_a != size_b ||
			          memcmp(ca, cb, size_a) != 0;
			free(ca), free(cb);
		}
		H5Sclose(spa);
		H5Sclose(spb);
		H5Dclose(da);
		H5Dclose(db);
	}
	CHECK(differ == 0);
	if (differ)
		fprintf(stderr, "%s and %s: %zu chunks stored differently\n", a, b, differ);
	H5Fclose(fa);
	H5Fclose(fb);
}

/* A fill that counts the rows it gave. */
static void count_rows(void *ctx, size_t at, size_t m, void *buf)
{
	double *v = buf;
	for (size_t k = 0; k < m; k++)
		v[k] = (double)(at + k);
#pragma omp atomic
	*(size_t *)ctx += m;
}

/* h5_rows_fill finishes a dataset begun with h5_rows_put (through HDF5's
 * filters, the rows not being chunk-aligned), and refuses a failed one. */
static void test_fill_after_put(const char *path)
{
	char tmp[4096];
	h5_set_threads(2);
	hid_t f = h5_create(path, tmp, sizeof tmp);
	h5_rows r;
	double first[10] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
	size_t given = 0, rows = 200000;
	CHECK(h5_rows_open(&r, f, "v", H5T_NATIVE_DOUBLE, rows, 0, NULL) == 0);
	CHECK(h5_rows_put(&r, first, 10) == 0);
	CHECK(h5_rows_fill(&r, count_rows, &given) == 0 && given == rows - 10);
	CHECK(h5_rows_close(&r) == 0);
	double *back = NULL;
	CHECK(h5_read_n(f, "v", H5T_NATIVE_DOUBLE, (void **)&back, rows, 0) == 0);
	size_t bad = 0;
	for (size_t k = 0; back && k < rows; k++)
		bad += back[k] != (double)k;
	CHECK(back && bad == 0);
	free(back);
	CHECK(h5_rows_open(&r, f, "w", H5T_NATIVE_DOUBLE, rows, 0, NULL) == 0);
	r.failed = 1;
	given = 0;
	CHECK(h5_rows_fill(&r, count_rows, &given) == -1 && given == 0);
	h5_rows_close(&r);
	h5_discard(f, tmp);
	h5_set_threads(1);
}

int main(void)
{
	void *data[NSETS];
	for (int s = 0; s < NSETS; s++)
		data[s] = values(s);
	const char *filters = check_tmp("h5-filters.h5"), *one = check_tmp("h5-fill-1.h5"),
	           *three = check_tmp("h5-fill-3.h5"), *all1 = check_tmp("h5-all-1.h5"),
	           *all3 = check_tmp("h5-all-3.h5");
	write_file(filters, 0, 1, data);
	write_file(one, 1, 1, data);
	write_file(three, 1, 3, data);
	write_file(all1, 2, 1, data);
	write_file(all3, 2, 3, data);
	const char *files[5] = {filters, one, three, all1, all3};
	for (int k = 0; k < 5; k++)
		check_values(files[k], data);
	check_same_chunks(filters, one, 1);
	check_same_chunks(filters, three, 1);
	check_same_chunks(filters, all1, 0);
	check_same_chunks(all1, all3, 1);
	test_fill_after_put(check_tmp("h5-after-put.h5"));
	for (int s = 0; s < NSETS; s++)
		free(data[s]);
	for (int k = 0; k < 5; k++)
		unlink(files[k]);
	return check_done();
}
