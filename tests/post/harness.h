/* Running the post program from a test (tests/harness.h), and reading its
 * CSV output. */
#ifndef DEM_TESTS_POST_HARNESS_H
#define DEM_TESTS_POST_HARNESS_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/harness.h"

typedef harness_result post_result;

/* Run "post <args>" (args formatted printf-style). */
#define harness_post(...) harness_run("post", __VA_ARGS__)

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

/* The rows of datablock `name` ("$name << EOD" to "EOD") of a gnuplot
 * input text: the first cols numbers of row k into out[k cols ...], for
 * the first max rows (none when out is NULL); the number of rows. */
static inline size_t harness_datablock(const char *text, const char *name, int cols, double *out,
                                       size_t max)
{
	char head[64];
	snprintf(head, sizeof head, "%s << EOD\n", name);
	const char *p = text ? strstr(text, head) : NULL;
	size_t n = 0;
	for (p = p ? p + strlen(head) : NULL; p && *p && strncmp(p, "EOD", 3); n++) {
		char *end = (char *)p;
		for (int c = 0; c < cols; c++) {
			double v = strtod(end, &end);
			if (out && n < max)
				out[n * (size_t)cols + (size_t)c] = v;
		}
		p = strchr(p, '\n');
		p = p ? p + 1 : NULL;
	}
	return n;
}

#endif
