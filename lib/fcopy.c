#define _GNU_SOURCE /* copy_file_range (glibc 2.27, Linux 4.5) */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lib/err.h"
#include "lib/fcopy.h"

/* The errors by which copy_file_range(2) says it cannot copy between these
 * two files, rather than that the copy failed: EXDEV (two file systems,
 * before Linux 5.3 and again, between types, since 5.19), ENOSYS (before
 * Linux 4.5), EINVAL (a file that is not a regular one), EOPNOTSUPP (a
 * file system without it). */
static int unsupported(int e)
{
	return e == EXDEV || e == ENOSYS || e == EINVAL || e == EOPNOTSUPP;
}

static int write_error(const char *from, const char *to, int e)
{
	return err_set("%s: cannot write a copy of %s: %s", to, from, strerror(e));
}

int fcopy(const char *from, const char *to)
{
	int in = open(from, O_RDONLY | O_CLOEXEC);
	if (in < 0)
		return err_set("%s: cannot open: %s", from, strerror(errno));
	int out = open(to, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
	if (out < 0) {
		int e = errno;
		close(in);
		return err_set("%s: cannot create: %s", to, strerror(e));
	}
	int rc = 0;
	ssize_t n;
	/* Both files' offsets advance with each call (NULL offsets), so the
	 * read and write below go on where the kernel stopped. */
	while ((n = copy_file_range(in, NULL, out, NULL, 1u << 30, 0)) > 0)
		;
	if (n < 0 && !unsupported(errno))
		rc = write_error(from, to, errno);
	/* What is left: all of it where the kernel could not copy, else
	 * nothing (one read finds the end). */
	enum { BUF = 1 << 18 };
	char *buf = rc ? NULL : xmalloc(BUF);
	while (!rc && (n = read(in, buf, BUF)) != 0) {
		if (n < 0) {
			if (errno != EINTR)
				rc = err_set("%s: cannot read: %s", from, strerror(errno));
			continue;
		}
		for (ssize_t at = 0, m; !rc && at < n; at += m)
			if ((m = write(out, buf + at, (size_t)(n - at))) < 0) {
				m = 0;
				if (errno != EINTR)
					rc = write_error(from, to, errno);
			}
	}
	free(buf);
	close(in);
	if (close(out) != 0 && !rc)
		rc = write_error(from, to, errno);
	return rc;
}
