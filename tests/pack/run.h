/* Running the pack program from a test: its stdout and stderr go to files
 * in the scratch directory and are read back as strings; assemblies it
 * writes are checked with an independent brute-force pass. */
#ifndef DEM_TESTS_PACK_RUN_H
#define DEM_TESTS_PACK_RUN_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lib/assembly.h"
#include "tests/check.h"

static inline char *run_slurp(const char *path)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		return calloc(1, 1);
	fseek(f, 0, SEEK_END);
	long n = ftell(f);
	fseek(f, 0, SEEK_SET);
	char *s = malloc((size_t)n + 1);
	size_t got = fread(s, 1, (size_t)n, f);
	s[got] = '\0';
	fclose(f);
	return s;
}

static inline int run_exists(const char *path)
{
	struct stat st;
	return stat(path, &st) == 0;
}

typedef struct {
	int status; /* exit status */
	char *out, *err;
} run_result;

/* Run "pack <args>" (args formatted printf-style) from the source root. */
static inline run_result run_pack(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static inline run_result run_pack(const char *fmt, ...)
{
	char args[4096], cmd[8192], out_name[64], err_name[64];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(args, sizeof args, fmt, ap);
	va_end(ap);
	const char *bin = getenv("DEM_BIN");
	snprintf(out_name, sizeof out_name, "pack_stdout.%d.txt", (int)getpid());
	snprintf(err_name, sizeof err_name, "pack_stderr.%d.txt", (int)getpid());
	const char *out = check_tmp(out_name), *err = check_tmp(err_name);
	snprintf(cmd, sizeof cmd, "%s/pack %s >%s 2>%s", bin && bin[0] ? bin : "build/bin", args,
	         out, err);
	int rc = system(cmd);
	run_result r = {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, run_slurp(out), run_slurp(err)};
	return r;
}

static inline void run_free(run_result *r)
{
	free(r->out);
	free(r->err);
}

static const double *run_sort_x;
static inline int run_cmp_x(const void *a, const void *b)
{
	double u = run_sort_x[3 * *(const size_t *)a], v = run_sort_x[3 * *(const size_t *)b];
	return (u > v) - (u < v);
}

/* Largest overlap of any pair relative to the smaller radius, by sweeping
 * the spheres sorted along x. */
static inline double run_max_overlap(const dem_assembly *a)
{
	size_t n = a->n, *o = malloc(n * sizeof *o + 1);
	double rmax = 0, worst = 0;
	for (size_t i = 0; i < n; i++) {
		o[i] = i;
		rmax = fmax(rmax, a->r[i]);
	}
	run_sort_x = a->x;
	qsort(o, n, sizeof *o, run_cmp_x);
	for (size_t p = 0; p < n; p++)
		for (size_t q = p + 1; q < n; q++) {
			size_t i = o[p], j = o[q];
			double dx = a->x[3 * j] - a->x[3 * i];
			if (dx > 2 * rmax)
				break;
			double dy = a->x[3 * j + 1] - a->x[3 * i + 1],
			       dz = a->x[3 * j + 2] - a->x[3 * i + 2];
			double d = sqrt(dx * dx + dy * dy + dz * dz);
			worst = fmax(worst, (a->r[i] + a->r[j] - d) / fmin(a->r[i], a->r[j]));
		}
	free(o);
	return worst;
}

#endif
