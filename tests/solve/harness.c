#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "lib/err.h"
#include "tests/check.h"
#include "tests/harness.h"
#include "tests/solve/harness.h"

void harness_case(dem_case *c, const char *json)
{
	if (case_parse_text(json, "case.json", c)) {
		fprintf(stderr, "harness: case: %s\n", err_msg());
		exit(1);
	}
}

void harness_engine(engine *e, const dem_case *c, const dem_assembly *a)
{
	if (engine_setup(e, c, a, &(engine_opts){.quiet = 1})) {
		fprintf(stderr, "harness: setup: %s\n", err_msg());
		exit(1);
	}
}

int harness_solve(const char *args)
{
	const char *bin = getenv("DEM_BIN");
	char cmd[4096];
	snprintf(cmd, sizeof cmd, "%s/solve %s", bin && bin[0] ? bin : "build/bin", args);
	fprintf(stderr, "$ %s\n", cmd);
	int st = system(cmd);
	return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

void harness_read(const char *path, dem_run *r)
{
	if (run_read(path, r)) {
		fprintf(stderr, "harness: %s\n", err_msg());
		exit(1);
	}
}

const char *harness_file(const char *name, const char *text)
{
	const char *path = check_tmp(name);
	FILE *f = fopen(path, "w");
	if (!f || fputs(text, f) < 0 || fclose(f)) {
		fprintf(stderr, "harness: cannot write %s\n", path);
		exit(1);
	}
	return path;
}

static int same(const void *a, const void *b, size_t bytes, const char *what, int *shown)
{
	if (memcmp(a, b, bytes) == 0)
		return 0;
	if ((*shown)++ < 8)
		fprintf(stderr, "runs differ: %s\n", what);
	return 1;
}

int harness_same_runs(const char *pa, const char *pb)
{
	dem_run a, b;
	harness_read(pa, &a);
	harness_read(pb, &b);
	int diff = 0, shown = 0;
	if (a.ncols != b.ncols || a.nrows != b.nrows) {
		fprintf(stderr, "runs differ: %d x %zu vs %d x %zu history\n", a.ncols, a.nrows,
		        b.ncols, b.nrows);
		diff++;
	} else {
		for (int c = 0; c < a.ncols; c++)
			if (strcmp(a.col_name[c], "rate") != 0)
				diff += same(a.col[c], b.col[c], a.nrows * sizeof(double),
				             a.col_name[c], &shown);
	}
	if (a.ncracks != b.ncracks) {
		fprintf(stderr, "runs differ: %zu vs %zu cracks\n", a.ncracks, b.ncracks);
		diff++;
	} else {
		diff += same(a.cracks, b.cracks, a.ncracks * sizeof *a.cracks, "cracks", &shown);
	}
	if (a.nsnap != b.nsnap) {
		fprintf(stderr, "runs differ: %zu vs %zu snapshots\n", a.nsnap, b.nsnap);
		diff++;
	} else {
		diff += same(a.snap_step, b.snap_step, a.nsnap * sizeof *a.snap_step,
		             "snapshot steps", &shown);
		for (size_t k = 0; k < a.nsnap; k++) {
			dem_snapshot sa, sb;
			if (run_read_snapshot(pa, &a, k, &sa) ||
			    run_read_snapshot(pb, &b, k, &sb)) {
				fprintf(stderr, "harness: %s\n", err_msg());
				exit(1);
			}
			diff += same(sa.x, sb.x, 3 * sa.n * sizeof *sa.x, "snapshot x", &shown) +
			        same(sa.v, sb.v, 3 * sa.n * sizeof *sa.v, "snapshot v", &shown) +
			        same(sa.w, sb.w, 3 * sa.n * sizeof *sa.w, "snapshot w", &shown) +
			        same(sa.state, sb.state, sa.nbonds, "snapshot bond state", &shown) +
			        same(sa.fn, sb.fn, sa.nbonds * sizeof *sa.fn, "snapshot bond fn",
			             &shown) +
			        same(sa.fs, sb.fs, 3 * sa.nbonds * sizeof *sa.fs,
			             "snapshot bond fs", &shown);
			snapshot_free(&sa);
			snapshot_free(&sb);
		}
	}
	run_free(&a);
	run_free(&b);
	return diff;
}

void harness_edit_copy(const char *from, const char *to, const char *dataset, hid_t type,
                       void (*edit)(void *first))
{
	char *data = harness_slurp(from);
	struct stat st;
	FILE *f = fopen(to, "wb");
	CHECK(data && f && stat(from, &st) == 0 &&
	      fwrite(data, 1, (size_t)st.st_size, f) == (size_t)st.st_size);
	if (f)
		fclose(f);
	free(data);
	hid_t h = H5Fopen(to, H5F_ACC_RDWR, H5P_DEFAULT);
	hid_t d = H5Dopen2(h, dataset, H5P_DEFAULT);
	hid_t space = H5Dget_space(d);
	hssize_t n = H5Sget_simple_extent_npoints(space);
	char *values = calloc((size_t)(n > 0 ? n : 1), H5Tget_size(type));
	CHECK(n > 0 && H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values) >= 0);
	edit(values);
	CHECK(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values) >= 0);
	free(values);
	H5Sclose(space);
	H5Dclose(d);
	H5Fclose(h);
}
