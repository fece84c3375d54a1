/* Atomic output: an interrupted write leaves no file under the final name
 * (neither when killed outright nor when interrupted with SIGINT), and a
 * committed file replaces the old one whole. */
#include <signal.h>
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
	unlink(tmp);

	interrupted_write(final, SIGINT);
	CHECK(!exists(final));
	CHECK(!exists(tmp)); /* interrupted: cleaned up */

	/* A committed write appears under the final name and the temporary is gone. */
	hid_t f = h5_create(final, tmp, sizeof tmp);
	CHECK(f >= 0);
	CHECK(exists(tmp) && !exists(final));
	CHECK(h5_commit(f, tmp, final) == 0);
	CHECK(exists(final) && !exists(tmp));
	unlink(final);

	/* A failed write discards its temporary. */
	f = h5_create(final, tmp, sizeof tmp);
	h5_discard(f, tmp);
	CHECK(!exists(final) && !exists(tmp));

	/* An unwritable place gives a clear error. */
	dem_assembly a = {0};
	CHECK(assembly_write("/nonexistent-dir/a.h5", &a) == -1);
	CHECK_CONTAINS(err_msg(), "/nonexistent-dir/a.h5.tmp: cannot create file");
	return check_done();
}
