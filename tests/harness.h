/* Running a program of the suite from a test: its stdout and stderr go to
 * files in the scratch directory (one pair per test process, since tests
 * run side by side there) and are read back as strings. */
#ifndef DEM_TESTS_HARNESS_H
#define DEM_TESTS_HARNESS_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/check.h"

/* The whole file as a string (caller frees), "" when missing. */
static inline char *harness_slurp(const char *path)
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

static inline int harness_exists(const char *path)
{
	struct stat st;
	return stat(path, &st) == 0;
}

typedef struct {
	int status; /* exit status */
	char *out, *err;
} harness_result;

/* Run "<program> <args>" (args formatted from fmt and ap) from the source
 * root; the program is taken from $DEM_BIN, else build/bin. */
static inline harness_result harness_vrun(const char *program, const char *fmt, va_list ap)
{
	char args[4096], cmd[8192], out_name[64], err_name[64];
	vsnprintf(args, sizeof args, fmt, ap);
	const char *bin = getenv("DEM_BIN");
	snprintf(out_name, sizeof out_name, "%s_stdout.%d.txt", program, (int)getpid());
	snprintf(err_name, sizeof err_name, "%s_stderr.%d.txt", program, (int)getpid());
	const char *out = check_tmp(out_name), *err = check_tmp(err_name);
	snprintf(cmd, sizeof cmd, "%s/%s %s >%s 2>%s", bin && bin[0] ? bin : "build/bin", program,
	         args, out, err);
	int rc = system(cmd);
	harness_result r = {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, harness_slurp(out),
	                    harness_slurp(err)};
	return r;
}

/* Run "<program> <args>" with args formatted printf-style. */
static inline harness_result harness_run(const char *program, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static inline harness_result harness_run(const char *program, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	harness_result r = harness_vrun(program, fmt, ap);
	va_end(ap);
	return r;
}

static inline void harness_free(harness_result *r)
{
	free(r->out);
	free(r->err);
}

#endif
