/* Error messages: err_set, err_wrap and fatal() keep the current message
 * intact when it is one of their own arguments, as in
 * fatal("%s: %s", file, err_msg()). */
#include <sys/wait.h>
#include <unistd.h>

#include "lib/err.h"
#include "tests/check.h"

/* What fatal("%s: %s", "case.json", err_msg()) prints, and its status. */
static void fatal_output(char *out, size_t size, int *status)
{
	int fd[2];
	out[0] = '\0';
	if (pipe(fd)) {
		CHECK(0);
		return;
	}
	fflush(stderr);
	pid_t pid = fork();
	if (pid == 0) {
		dup2(fd[1], 2);
		close(fd[0]);
		fatal("%s: %s", "case.json", err_msg());
	}
	close(fd[1]);
	size_t got = 0;
	ssize_t k;
	while (got + 1 < size && (k = read(fd[0], out + got, size - 1 - got)) > 0)
		got += (size_t)k;
	out[got] = '\0';
	close(fd[0]);
	waitpid(pid, status, 0);
}

int main(void)
{
	err_program("solve");
	err_set("time step %g s above the stable limit", 1.0);
	CHECK_STR(err_msg(), "time step 1 s above the stable limit");
	err_set("%s: %s", "case.json", err_msg());
	CHECK_STR(err_msg(), "case.json: time step 1 s above the stable limit");
	err_wrap("run %s", "r.h5");
	CHECK_STR(err_msg(), "run r.h5: case.json: time step 1 s above the stable limit");

	err_set("the assembly has no particles");
	char out[4096];
	int status = 0;
	fatal_output(out, sizeof out, &status);
	CHECK_STR(out, "solve: case.json: the assembly has no particles\n");
	CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 1);
	return check_done();
}
