/* A byte copy of a file (lib/fcopy.h): files of 0, 1 and some MB plus an
 * odd tail, over a longer file left in the way, byte for byte, by the
 * kernel; from a FIFO (where copy_file_range says EINVAL) and from another
 * file system (/dev/shm, where it says EXDEV) by read and write; a missing
 * source or destination directory named in the message. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lib/err.h"
#include "lib/fcopy.h"
#include "tests/bytes.h"
#include "tests/check.h"

/* n bytes copied from a file in dir (NULL: TEST_TMPDIR) over a longer
 * one. */
static void copy(const char *dir, size_t n)
{
	char from[1024];
	if (dir)
		snprintf(from, sizeof from, "%s/fcopy-from-%d", dir, (int)getpid());
	else
		snprintf(from, sizeof from, "%s", check_tmp("fcopy-from"));
	const char *to = check_tmp("fcopy-to");
	unsigned char *b = bytes(n, (uint32_t)n + 1), *junk = bytes(n + 5000, 3);
	put(from, b, n);
	put(to, junk, n + 5000);
	CHECK(fcopy(from, to) == 0);
	CHECK(holds(to, b, n));
	if (dir)
		unlink(from);
	free(b);
	free(junk);
}

int main(void)
{
	copy(NULL, 0);
	copy(NULL, 1);
	copy(NULL, (3 << 20) + 7);
	/* Another file system, where there is one. */
	struct stat shm, tmp;
	if (stat("/dev/shm", &shm) == 0 && S_ISDIR(shm.st_mode) &&
	    stat(check_tmp("."), &tmp) == 0 && shm.st_dev != tmp.st_dev &&
	    access("/dev/shm", W_OK) == 0)
		copy("/dev/shm", (1 << 20) + 3);
	/* A FIFO that a child writes into. */
	const char *fifo = check_tmp("fcopy-fifo"), *to = check_tmp("fcopy-to");
	size_t n = 300007;
	unsigned char *b = bytes(n, 5);
	unlink(fifo);
	CHECK(mkfifo(fifo, 0600) == 0);
	pid_t pid = fork();
	if (pid == 0) {
		FILE *f = fopen(fifo, "wb");
		_exit(f && fwrite(b, 1, n, f) == n && fclose(f) == 0 ? 0 : 1);
	}
	CHECK(fcopy(fifo, to) == 0);
	int status = 1;
	waitpid(pid, &status, 0);
	CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
	CHECK(holds(to, b, n));
	unlink(fifo);
	free(b);
	/* Failures name the file. */
	const char *missing = check_tmp("fcopy-no-such-file");
	CHECK(fcopy(missing, to) == -1);
	CHECK_CONTAINS(err_msg(), missing);
	CHECK_CONTAINS(err_msg(), "cannot open: No such file or directory");
	const char *nodir = check_tmp("fcopy-no-such-dir/to");
	CHECK(fcopy(check_tmp("fcopy-from"), nodir) == -1);
	CHECK_CONTAINS(err_msg(), nodir);
	CHECK_CONTAINS(err_msg(), "cannot create");
	return check_done();
}
