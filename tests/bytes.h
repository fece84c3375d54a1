/* Files of known bytes for the tests of file copies (test_fcopy,
 * test_copy_ranks). */
#ifndef DEM_TESTS_BYTES_H
#define DEM_TESTS_BYTES_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/check.h"

/* n bytes drawn from seed (the same in every process), one more allocated
 * so that n may be 0; the caller frees. */
static inline unsigned char *bytes(size_t n, uint32_t seed)
{
	unsigned char *b = malloc(n + 1);
	for (size_t k = 0; k < n; k++) {
		seed = seed * 1664525u + 1013904223u;
		b[k] = (unsigned char)(seed >> 24);
	}
	return b;
}

static inline void put(const char *path, const unsigned char *b, size_t n)
{
	FILE *f = fopen(path, "wb");
	CHECK(f && fwrite(b, 1, n, f) == n && fclose(f) == 0);
}

/* Whether file path holds exactly the n bytes b. */
static inline int holds(const char *path, const unsigned char *b, size_t n)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		return 0;
	unsigned char *got = malloc(n + 1);
	size_t m = fread(got, 1, n + 1, f);
	fclose(f);
	int same = m == n && memcmp(got, b, n) == 0;
	free(got);
	return same;
}

#endif
