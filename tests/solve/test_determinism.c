/* The same run, bit for bit, whatever the number of threads and however
 * often it is interrupted and restarted: a short UCS past the peak (bonds
 * breaking, the crack log filling) is run
 *   A  on one thread,
 *   C  on two threads with a step budget, then restarted on one thread,
 *   D  on two threads, interrupted by SIGINT at an arbitrary moment, then
 *      restarted on two threads (its report must say two threads ran);
 *   E  on three threads whose shares of the particles move every few steps
 *      to random ends (DEM_BALANCE_TEST: the balance of the threads, bonds.h,
 *      made to move them far more often and farther than it does);
 * C, D and E must equal A in every history column (but the wall-clock rate),
 * every crack and every snapshot. D runs on two threads from start to end,
 * so a result that depended on the threads would differ from A there. The
 * interrupted files must be valid run files with status "interrupted"; one
 * whose checkpoint is corrupt is refused. */
#include <hdf5.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "lib/cfg.h"
#include "tests/check.h"
#include "tests/harness.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

static const char *case_text =
    "{\"assembly\": \"%s\", \"material\": {\"name\": \"demo\", \"law\": \"linear\", "
    "\"density\": 1700, \"E\": 10e9, \"nu\": 0.2, \"tensile_strength\": 5e6, "
    "\"shear_strength\": 10e6, \"mu2\": 0.5},"
    "\"output\": {\"history_every\": 50, \"snapshot_every\": 2000, \"checkpoint_every\": 1500},"
    "\"loading\": [{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 5}}],"
    "\"stop\": {\"strain_axial\": 0.0036}}";

static const char *path(const char *name) { return check_tmp(name); }

static int solve(const char *args)
{
	char cmd[2048];
	snprintf(cmd, sizeof cmd, "--quiet %s", args);
	return harness_solve(cmd);
}

/* Start solve in the background, interrupt it with SIGINT once it has
 * written something, and return its exit status. */
static int interrupted_run(const char *out, const char *casefile)
{
	const char *bin = getenv("DEM_BIN");
	char exe[1024], tmp[1100];
	snprintf(exe, sizeof exe, "%s/solve", bin && bin[0] ? bin : "build/bin");
	snprintf(tmp, sizeof tmp, "%s.tmp", out);
	pid_t pid = fork();
	if (pid == 0) {
		execl(exe, exe, "--quiet", "--threads", "2", "--output", out, casefile,
		      (char *)NULL);
		_exit(127);
	}
	struct stat st;
	for (int k = 0; k < 600 && stat(tmp, &st) != 0; k++)
		nanosleep(&(struct timespec){0, 10000000}, NULL);
	nanosleep(&(struct timespec){0, 700000000}, NULL);
	kill(pid, SIGINT);
	int status;
	waitpid(pid, &status, 0);
	return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* A bond state that does not exist. */
static void state_200(void *first) { *(uint8_t *)first = 200; }

int main(void)
{
	dem_assembly a;
	fixture_cylinder(&a, 5);
	const char *apath = path("det.h5");
	fixture_write(&a, apath);
	fprintf(stderr, "%zu particles\n", a.n);
	CHECK(a.n > 2000);
	char json[2048], args[4096];
	snprintf(json, sizeof json, case_text, apath);
	const char *cpath = harness_file("det.json", json);

	snprintf(args, sizeof args, "--threads 1 --output %s %s", path("det-A.h5"), cpath);
	CHECK(solve(args) == 0);
	snprintf(args, sizeof args, "--threads 2 --max-steps 1333 --output %s %s", path("det-C.h5"),
	         cpath);
	CHECK(solve(args) == 3);
	dem_run c;
	harness_read(path("det-C.h5"), &c);
	CHECK_STR(c.status, "interrupted");
	CHECK(c.nrows == 1333 / 50 + 1);
	run_free(&c);
	/* A checkpoint holding a bond state that does not exist is refused. */
	char bad[1024], said[1024];
	snprintf(bad, sizeof bad, "%s", path("det-bad.h5"));
	snprintf(said, sizeof said, "%s", path("det-bad.txt"));
	harness_edit_copy(path("det-C.h5"), bad, "/checkpoint/bond_state", H5T_NATIVE_UINT8,
	                  state_200);
	snprintf(args, sizeof args, "--restart %s 2> %s", bad, said);
	CHECK(solve(args) == 1);
	char *message = harness_slurp(said);
	CHECK_CONTAINS(message, "checkpoint dataset 'bond_state': value 200 at row 0: expected");
	free(message);
	snprintf(args, sizeof args, "--restart %s", path("det-C.h5"));
	CHECK(solve(args) == 0);
	CHECK(interrupted_run(path("det-D.h5"), cpath) == 3);
	dem_run d;
	harness_read(path("det-D.h5"), &d);
	CHECK_STR(d.status, "interrupted");
	fprintf(stderr, "SIGINT after %zu history rows\n", d.nrows);
	run_free(&d);
	snprintf(args, sizeof args, "--restart %s --threads 2 --report %s", path("det-D.h5"),
	         path("det-D.json"));
	CHECK(solve(args) == 0);

	/* The two-thread run did use two threads. */
	cfg *report = cfg_load(path("det-D.json"));
	long threads = 0;
	CHECK(report && cfg_integer(report, "threads", &threads, 1, 1024) == 0 && threads == 2);
	cfg_free(report);

	/* E: the shares' ends moved, the forces the same. */
	setenv("DEM_BALANCE_TEST", "1", 1);
	snprintf(args, sizeof args, "--threads 3 --report %s --output %s %s", path("det-E.json"),
	         path("det-E.h5"), cpath);
	CHECK(solve(args) == 0);
	unsetenv("DEM_BALANCE_TEST");
	report = cfg_load(path("det-E.json"));
	long resplits = 0;
	CHECK(report && cfg_integer(report, "threads_resplits", &resplits, 0, 1L << 30) == 0);
	fprintf(stderr, "E: the shares moved %ld times\n", resplits);
	CHECK(resplits > 100);
	cfg_free(report);

	dem_run ra;
	harness_read(path("det-A.h5"), &ra);
	fprintf(stderr, "A: %s, %zu rows, %zu cracks, %zu snapshots\n", ra.status, ra.nrows,
	        ra.ncracks, ra.nsnap);
	CHECK(ra.ncracks > 10);
	CHECK(ra.nsnap >= 3);
	run_free(&ra);
	/* A run that ended (here by its stop rule) does not continue. */
	snprintf(args, sizeof args, "--restart %s 2> %s", path("det-A.h5"), said);
	CHECK(solve(args) == 1);
	message = harness_slurp(said);
	CHECK_CONTAINS(message, "det-A.h5: the run has status 'stopped: ");
	CHECK_CONTAINS(message, "': only an interrupted run continues");
	free(message);
	CHECK(harness_same_runs(path("det-A.h5"), path("det-C.h5")) == 0);
	CHECK(harness_same_runs(path("det-A.h5"), path("det-D.h5")) == 0);
	CHECK(harness_same_runs(path("det-A.h5"), path("det-E.h5")) == 0);
	assembly_free(&a);
	return check_done();
}
