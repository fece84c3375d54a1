/* Atomic output: an interrupted write leaves no file under the final name
 * (neither when killed outright nor when interrupted with SIGINT), a
 * committed file replaces the old one whole, and a second program writing
 * the same name is refused without harming the first one's file. */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lib/afile.h"
#include "lib/assembly.h"
#include "lib/err.h"
#include "lib/h5.h"
#include "tests/check.h"

static int exists(const char *p) { return access(p, F_OK) == 0; }

/* In a child: start writing final and die of sig before committing. */
static void interrupted_write(const char *final, int sig)
{
	pid_t pid = fork();
	if (pid == 0) {
		afile_install_signal_cleanup();
		char tmp[1024];
		hid_t f = h5_create(final, tmp, sizeof tmp);
		double x[300] = {0};
		h5_write(f, "x", H5T_NATIVE_DOUBLE, x, 100, 3, "m");
		H5Fflush(f, H5F_SCOPE_GLOBAL);
		raise(sig);
		_exit(0);
	}
	int status;
	waitpid(pid, &status, 0);
	CHECK(WIFSIGNALED(status) && WTERMSIG(status) == sig);
}

int main(void)
{
	const char *final = check_tmp("atomic.h5");
	char tmp[1024];
	snprintf(tmp, sizeof tmp, "%s.tmp", final);
	unlink(final);
	unlink(tmp);

	interrupted_write(final, SIGKILL);
	CHECK(!exists(final));
	CHECK(exists(tmp)); /* killed outright: the temporary remains, the final name does not */
	/* ... and the next writer takes it over. */
	hid_t f = h5_create(final, tmp, sizeof tmp);
	CHECK(f >= 0);
	h5_discard(f, tmp);

	interrupted_write(final, SIGINT);
	CHECK(!exists(final));
	CHECK(!exists(tmp)); /* interrupted: cleaned up */

	/* A committed write appears under the final name and the temporary is
	 * gone; another program that starts writing the same name meanwhile is
	 * refused, leaves the temporary as it is and removes nothing at its
	 * exit. */
	f = h5_create(final, tmp, sizeof tmp);
	CHECK(f >= 0);
	CHECK(exists(tmp) && !exists(final));
	double x[30];
	for (int k = 0; k < 30; k++)
		x[k] = k;
	CHECK(h5_attr_str(f, "format", "test") == 0);
	CHECK(h5_write(f, "x", H5T_NATIVE_DOUBLE, x, 10, 3, "m") == 0);
	H5Fflush(f, H5F_SCOPE_GLOBAL);
	pid_t pid = fork();
	if (pid == 0) { /* _exit: this copy's pending list is the parent's */
		char t2[1024];
		hid_t g = h5_create(final, t2, sizeof t2);
		char csv[1100];
		int refused = g < 0 && strstr(err_msg(), "another program is writing it") &&
		              snprintf(csv, sizeof csv, "%s.tmp", final) > 0 &&
		              afile_begin(final, csv, sizeof csv) != 0;
		_exit(refused ? 0 : 1);
	}
	int status;
	waitpid(pid, &status, 0);
	CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
	CHECK(exists(tmp));
	CHECK(h5_commit(f, tmp, final) == 0);
	CHECK(exists(final) && !exists(tmp));
	f = h5_open(final, "test", 0);
	void *got = NULL;
	size_t rows = 0;
	CHECK(f >= 0 && h5_read(f, "x", H5T_NATIVE_DOUBLE, &got, &rows, 3) == 0 && rows == 10 &&
	      memcmp(got, x, sizeof x) == 0);
	free(got);
	H5Fclose(f);
	unlink(final);

	/* A failed write discards its temporary. */
	f = h5_create(final, tmp, sizeof tmp);
	h5_discard(f, tmp);
	CHECK(!exists(final) && !exists(tmp));

	/* An unwritable place gives a clear error. */
	dem_assembly a = {0};
	CHECK(assembly_write("/nonexistent-dir/a.h5", &a) == -1);
	CHECK_CONTAINS(err_msg(), "/nonexistent-dir/a.h5: cannot create it (written first as "
	                          "/nonexistent-dir/a.h5.tmp, renamed when complete): No such "
	                          "file or directory");
	return check_done();
}
