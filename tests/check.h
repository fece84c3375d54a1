/* A minimal test harness: CHECK* macros record failures with file and line
 * and go on; check_done() prints "N passed, N failed" and gives the exit
 * status. Each test file is one executable registered with ctest. */
#ifndef DEM_TEST_CHECK_H
#define DEM_TEST_CHECK_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int check_passed, check_failed;

#define CHECK(cond)                                                                              \
	do {                                                                                     \
		if (cond)                                                                        \
			check_passed++;                                                          \
		else {                                                                           \
			check_failed++;                                                          \
			fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
		}                                                                                \
	} while (0)

/* |a - b| <= tol (absolute) */
#define CHECK_NEAR(a, b, tol)                                                                 \
	do {                                                                                  \
		double a_ = (a), b_ = (b), t_ = (tol);                                        \
		if (fabs(a_ - b_) <= t_)                                                      \
			check_passed++;                                                       \
		else {                                                                        \
			check_failed++;                                                       \
			fprintf(stderr,                                                       \
			        "%s:%d: CHECK_NEAR failed: %s = %.17g, %s = %.17g, tol %g\n", \
			        __FILE__, __LINE__, #a, a_, #b, b_, t_);                      \
		}                                                                             \
	} while (0)

/* |a - b| <= rel * max(|a|, |b|) */
#define CHECK_REL(a, b, rel)                                                                 \
	do {                                                                                 \
		double a_ = (a), b_ = (b), r_ = (rel);                                       \
		if (fabs(a_ - b_) <= r_ * fmax(fabs(a_), fabs(b_)))                          \
			check_passed++;                                                      \
		else {                                                                       \
			check_failed++;                                                      \
			fprintf(stderr,                                                      \
			        "%s:%d: CHECK_REL failed: %s = %.17g, %s = %.17g, rel %g\n", \
			        __FILE__, __LINE__, #a, a_, #b, b_, r_);                     \
		}                                                                            \
	} while (0)

#define CHECK_STR(a, b)                                                                        \
	do {                                                                                   \
		const char *a_ = (a), *b_ = (b);                                               \
		if (a_ && b_ && strcmp(a_, b_) == 0)                                           \
			check_passed++;                                                        \
		else {                                                                         \
			check_failed++;                                                        \
			fprintf(stderr, "%s:%d: CHECK_STR failed: %s = \"%s\", %s = \"%s\"\n", \
			        __FILE__, __LINE__, #a, a_ ? a_ : "(null)", #b,                \
			        b_ ? b_ : "(null)");                                           \
		}                                                                              \
	} while (0)

/* The message contains the substring. */
#define CHECK_CONTAINS(msg, sub) CHECK_STR_CONTAINS_((msg), (sub), #msg)
#define CHECK_STR_CONTAINS_(m_, s_, name)                                                         \
	do {                                                                                      \
		const char *mm_ = (m_);                                                           \
		if (mm_ && strstr(mm_, (s_)))                                                     \
			check_passed++;                                                           \
		else {                                                                            \
			check_failed++;                                                           \
			fprintf(stderr, "%s:%d: %s = \"%s\" does not contain \"%s\"\n", __FILE__, \
			        __LINE__, name, mm_ ? mm_ : "(null)", (s_));                      \
		}                                                                                 \
	} while (0)

static inline int check_done(void)
{
	printf("%d passed, %d failed\n", check_passed, check_failed);
	return check_failed ? 1 : 0;
}

/* A scratch path for this test: $TEST_TMPDIR/<name> (or /tmp/<name>). */
static inline const char *check_tmp(const char *name)
{
	static char buf[8][1024];
	static int slot;
	const char *dir = getenv("TEST_TMPDIR");
	char *out = buf[slot++ % 8];
	snprintf(out, 1024, "%s/%s", dir && dir[0] ? dir : "/tmp", name);
	return out;
}

#endif
