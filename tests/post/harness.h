/* Running the post program from a test: its stdout and stderr are kept
 * in files next to the scratch directory and read back as strings. */
#ifndef DEM_TESTS_POST_HARNESS_H
#define DEM_TESTS_POST_HARNESS_H

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
} post_result;

/* Run "post <args>" (args formatted printf-style). */
static inline post_result harness_post(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static inline post_result harness_post(const char *fmt, ...)
{
	char args[4096], cmd[8192];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(args, sizeof args, fmt, ap);
	va_end(ap);
	const char *bin = getenv("DEM_BIN");
	/* per process: tests run side by side in the same scratch directory */
	char out_name[64], err_name[64];
	snprintf(out_name, sizeof out_name, "post_stdout.%d.txt", (int)getpid());
	snprintf(err_name, sizeof err_name, "post_stderr.%d.txt", (int)getpid());
	const char *out = check_tmp(out_name), *err = check_tmp(err_name);
	snprintf(cmd, sizeof cmd, "%s/post %s >%s 2>%s", bin && bin[0] ? bin : "build/bin", args,
	         out, err);
	int rc = system(cmd);
	post_result r = {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, harness_slurp(out),
	                 harness_slurp(err)};
	return r;
}

static inline void harness_free(post_result *r)
{
	free(r->out);
	free(r->err);
}

/* dir (of size n) = a fresh empty scratch directory $TEST_TMPDIR/<name>. */
static inline void harness_dir(char *dir, size_t n, const char *name)
{
	snprintf(dir, n, "%s", check_tmp(name));
	char cmd[4200];
	snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", dir, dir);
	if (system(cmd) != 0)
		fprintf(stderr, "cannot create %s\n", dir);
}

/* Field k (0-based) of a CSV line without quoted fields, into buf. */
static inline const char *harness_field(const char *line, int k, char *buf, size_t n)
{
	for (; k > 0 && line; k--) {
		line = strchr(line, ',');
		if (line)
			line++;
	}
	size_t len = line ? strcspn(line, ",\n") : 0;
	if (len >= n)
		len = n - 1;
	memcpy(buf, line ? line : "", len);
	buf[len] = '\0';
	return buf;
}

#endif
