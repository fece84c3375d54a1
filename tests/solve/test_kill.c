/* Nothing is lost on a hard kill: a run with periodic checkpoints is killed
 * with SIGKILL 20 times at random moments (pseudo-random but seeded, so the
 * test is the same every time; some kills land while a checkpoint or its
 * recovery copy is being written), and each time it continues from its last
 * complete checkpoint, by `solve --restart` or by the same command run again
 * (as make does). The run that finally completes must equal an
 * uninterrupted one bit for bit: every history column but the wall-clock
 * rate, every crack, every snapshot. A run killed where a finished one of
 * the same name lies continues from its copy by --restart. A recovery copy whose checkpoint data
 * have one value changed is refused by its checksum; one left by another
 * case is not continued, and is kept until a run of that case passes its
 * checks; a run still going is not taken for a killed one. */
#include <hdf5.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "lib/rng.h"
#include "tests/check.h"
#include "tests/harness.h"
#include "tests/solve/fixture.h"
#include "tests/solve/harness.h"

enum { KILLS = 20 };

static const char *case_text =
    "{\"assembly\": \"%s\", \"material\": {\"name\": \"demo\", \"law\": \"linear\", "
    "\"density\": 1700, \"E\": 10e9, \"nu\": 0.2, \"tensile_strength\": 5e6, "
    "\"shear_strength\": 10e6, \"mu2\": 0.5},"
    "\"output\": {\"history_every\": 50, \"snapshot_every\": 1000, \"checkpoint_every\": 150},"
    "\"loading\": [{\"axial\": {\"mode\": \"strain_rate\", \"rate\": 5}}],"
    "\"stop\": {\"strain_axial\": 0.0036}}";

static const char *solve_exe(void)
{
	static char exe[1024];
	const char *bin = getenv("DEM_BIN");
	snprintf(exe, sizeof exe, "%s/solve", bin && bin[0] ? bin : "build/bin");
	return exe;
}

static int exists(const char *path)
{
	struct stat st;
	return stat(path, &st) == 0;
}

static void sleep_s(double s)
{
	nanosleep(&(struct timespec){(time_t)s, (long)((s - (double)(time_t)s) * 1e9)}, NULL);
}

/* Start solve with args (NULL-terminated after the output or restart
 * options); returns its pid. */
static pid_t start(const char *mode, const char *run, const char *casefile)
{
	pid_t pid = fork();
	if (pid == 0) {
		if (casefile)
			execl(solve_exe(), solve_exe(), "--quiet", "--threads", "1", mode, run,
			      casefile, (char *)NULL);
		else
			execl(solve_exe(), solve_exe(), "--quiet", "--threads", "1", mode, run,
			      (char *)NULL);
		_exit(127);
	}
	return pid;
}

/* Wait for pid; returns its exit status, or 128 + the signal that ended it. */
static int finish(pid_t pid)
{
	int status;
	waitpid(pid, &status, 0);
	return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* A value one unit in the last place off. */
static void nudge(void *first) { *(double *)first = nextafter(*(double *)first, 1.0); }

int main(void)
{
	/* One thread runs it, so the specimen need not be the 2 500 spheres the
	 * two-thread tests need: about 900 of the same spheres, to the same
	 * strain past the peak. */
	lattice l = {.kind = LATTICE_FCC,
	             .nx = 7,
	             .ny = 7,
	             .nz = 11,
	             .r = 1e-3,
	             .jitter = 0.02,
	             .polydisp = 0.02,
	             .diameter = 0.0163,
	             .seed = 5};
	dem_assembly a;
	fixture_lattice(&a, &l);
	fprintf(stderr, "%zu particles\n", a.n);
	char apath[1024], run[1024], ckpt[1100], ref[1024], json[2048];
	snprintf(apath, sizeof apath, "%s", check_tmp("kill.h5"));
	fixture_write(&a, apath);
	assembly_free(&a);
	snprintf(json, sizeof json, case_text, apath);
	const char *cpath = harness_file("kill.json", json);
	snprintf(ref, sizeof ref, "%s", check_tmp("kill-ref.h5"));
	snprintf(run, sizeof run, "%s", check_tmp("kill-run.h5"));
	snprintf(ckpt, sizeof ckpt, "%s.ckpt", run);
	unlink(run);
	unlink(ckpt);

	struct timespec t0, t1;
	clock_gettime(CLOCK_MONOTONIC, &t0);
	CHECK(finish(start("--output", ref, cpath)) == 0);
	clock_gettime(CLOCK_MONOTONIC, &t1);
	double whole = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
	dem_run r;
	harness_read(ref, &r);
	fprintf(stderr, "uninterrupted: %.2f s, %zu cracks, %zu snapshots\n", whole, r.ncracks,
	        r.nsnap);
	/* The checkpoints hold broken bonds and a growing crack log. */
	CHECK(r.ncracks > 10);
	run_free(&r);

	/* The first kill after the first recovery copy; then restarts, each
	 * killed after 0.1 to 0.6 of a twentieth of the whole run: the kills
	 * together take well under the run, even if it runs faster now than
	 * when it was timed on a busy machine. */
	rng g;
	rng_seed(&g, 2026);
	pid_t pid = start("--output", run, cpath);
	for (int k = 0; k < 3000 && !exists(ckpt); k++)
		sleep_s(0.002);
	CHECK(exists(ckpt));
	int kills = 0, during_copy = 0, restarts_ok = 1;
	while (kills < KILLS) {
		sleep_s(rng_range(&g, 0.1, 0.6) * whole / KILLS);
		during_copy += exists(check_tmp("kill-run.h5.ckpt.tmp"));
		kill(pid, SIGKILL);
		int code = finish(pid);
		if (code != 128 + SIGKILL) {
			fprintf(stderr, "kill %d: solve had already ended with %d\n", kills + 1,
			        code);
			restarts_ok = 0;
			break;
		}
		kills++;
		pid = kills % 2 ? start("--restart", run, NULL) : start("--output", run, cpath);
	}
	fprintf(stderr, "%d kills, %d of them while a recovery copy was being written\n", kills,
	        during_copy);
	CHECK(restarts_ok && kills == KILLS);
	CHECK(finish(pid) == 0);
	CHECK(!exists(ckpt));
	CHECK(harness_same_runs(ref, run) == 0);

	/* The same run again under the same name, killed: --restart takes its
	 * recovery copy, not the finished run file beside it. */
	pid = start("--output", run, cpath);
	for (int k = 0; k < 3000 && !exists(ckpt); k++)
		sleep_s(0.002);
	kill(pid, SIGKILL);
	finish(pid);
	CHECK(exists(ckpt));
	CHECK(finish(start("--restart", run, NULL)) == 0);
	CHECK(!exists(ckpt));
	CHECK(harness_same_runs(ref, run) == 0);

	/* A recovery copy of another case is not continued. But first: the
	 * same command while that run is going is refused at once, its copy
	 * not taken for a killed run's. */
	pid = start("--output", run, cpath);
	for (int k = 0; k < 3000 && !exists(ckpt); k++)
		sleep_s(0.002);
	char other[2048], args[3000], said[1100];
	snprintf(said, sizeof said, "%s", check_tmp("kill-busy.txt"));
	snprintf(args, sizeof args, "--output %s %s 2> %s", run, cpath, said);
	CHECK(harness_solve(args) == 1);
	char *busy = harness_slurp(said);
	CHECK(strstr(busy, "another program is writing it now") && !strstr(busy, "continuing"));
	free(busy);
	kill(pid, SIGKILL);
	finish(pid);
	snprintf(json, sizeof json, case_text, apath);
	/* ... nor removed by one that fails its checks. */
	char *rate = strstr(json, "\"rate\": 5}");
	snprintf(other, sizeof other, "%.*s\"rate\": 5e6}%s", (int)(rate - json), json,
	         rate + strlen("\"rate\": 5}"));
	snprintf(args, sizeof args, "--output %s %s 2> %s", run,
	         harness_file("kill-fast.json", other), check_tmp("kill-fast.txt"));
	CHECK(harness_solve(args) == 1);
	CHECK(exists(ckpt));
	snprintf(other, sizeof other, "%.*s, \"threads\": 1}", (int)strlen(json) - 1, json);
	const char *opath = harness_file("kill-other.json", other);
	snprintf(said, sizeof said, "%s", check_tmp("kill-other.txt"));
	snprintf(args, sizeof args, "--max-steps 10 --output %s %s 2> %s", run, opath, said);
	CHECK(harness_solve(args) == 3);
	char *message = harness_slurp(said);
	CHECK(strstr(message, "continuing") == NULL);
	free(message);
	CHECK(!exists(ckpt));

	/* A damaged checkpoint: refused, not continued. */
	pid = start("--output", run, cpath);
	for (int k = 0; k < 3000 && !exists(ckpt); k++)
		sleep_s(0.002);
	kill(pid, SIGKILL);
	finish(pid);
	unlink(run);
	char bad[1100];
	snprintf(bad, sizeof bad, "%s", check_tmp("kill-bad.h5"));
	snprintf(said, sizeof said, "%s", check_tmp("kill-bad.txt"));
	char badckpt[1200];
	snprintf(badckpt, sizeof badckpt, "%s.ckpt", bad);
	harness_edit_copy(ckpt, badckpt, "/checkpoint/x", H5T_NATIVE_DOUBLE, nudge);
	unlink(bad);
	snprintf(args, sizeof args, "--quiet --restart %s 2> %s", bad, said);
	CHECK(harness_solve(args) == 1);
	message = harness_slurp(said);
	CHECK_CONTAINS(message, "the checkpoint's data do not match its checksum");
	free(message);
	return check_done();
}
