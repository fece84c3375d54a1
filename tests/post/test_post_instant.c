/* Which snapshot post uses for an instant (post/instant.h): the peak, a
 * stress level, a strain, a time, an index; on the history table, or on
 * the snapshots when the history lacks the stress. The account printed
 * must name the snapshot used and where the instant fell. */
#include "tests/check.h"
#include "tests/post/harness.h"
#include "tests/post/synth.h"

static const double snap_t[5] = {0, 1e-3, 2e-3, 3e-3, 4e-3};
static const double snap_s[5] = {0, 10e6, 30e6, 25e6, 20e6};
static const double row_t[9] = {0, 0.5e-3, 1e-3, 1.5e-3, 2e-3, 2.4e-3, 3e-3, 3.5e-3, 4e-3};
static const double row_s[9] = {0, 5e6, 10e6, 20e6, 30e6, 32e6, 25e6, 22e6, 20e6};

/* post ratios with the instant options; stdout must contain want. */
static void expect_pick(const char *run, const char *opts, const char *want)
{
	post_result r = harness_post("ratios --no-png %s %s", opts, run);
	CHECK(r.status == 0);
	CHECK_CONTAINS(r.out, want);
	harness_free(&r);
}

static void expect_error(const char *run, const char *opts, const char *want)
{
	post_result r = harness_post("ratios --no-png %s %s", opts, run);
	CHECK(r.status == 1);
	CHECK_STR(r.err, want);
	harness_free(&r);
}

/* A bad instant option is a usage error: status 2, the message, the usage. */
static void expect_usage_error(const char *run, const char *opts, const char *want)
{
	post_result r = harness_post("ratios --no-png %s %s", opts, run);
	CHECK(r.status == 2);
	char full[1024];
	snprintf(full, sizeof full, "%s (usage: post ratios", want);
	CHECK(strncmp(r.err, full, strlen(full)) == 0);
	if (strncmp(r.err, full, strlen(full)) != 0)
		fprintf(stderr, "  got: %s", r.err);
	harness_free(&r);
}

int main(void)
{
	char dir[1024], run[1100], bare[1100], msg[2048];
	harness_dir(dir, sizeof dir, "instant");
	snprintf(run, sizeof run, "%s/run.h5", dir);
	snprintf(bare, sizeof bare, "%s/bare.h5", dir);
	CHECK(synth_tiny(run, 5, snap_t, snap_s, 9, row_t, row_s, 1) == 0);
	CHECK(synth_tiny(bare, 5, snap_t, snap_s, 9, row_t, NULL, 0) == 0);

	snprintf(msg, sizeof msg,
	         "%s: peak axial stress 32 MPa at t = 0.0024 s (axial strain 0.24 %%); between "
	         "snapshots 2 (t = 0.002 s) and 3 (t = 0.003 s): using the nearest, snapshot 2 "
	         "(step 200000, t = 0.002 s, axial strain 0.2 %%, axial stress 30 MPa); its axial "
	         "stress is 6 %% off the instant's 32 MPa: ask solve for snapshots nearer to it\n",
	         run);
	expect_pick(run, "", msg);
	snprintf(msg, sizeof msg,
	         "%s: axial stress first reaches 15 MPa at t = 0.00125 s (axial strain 0.125 %%); "
	         "between snapshots 1 (t = 0.001 s) and 2 (t = 0.002 s): using the nearest, "
	         "snapshot 1 (",
	         run);
	expect_pick(run, "--stress 15e6", msg);
	expect_pick(run, "--strain 0.0037",
	            "axial strain first reaches 0.37 % at t = 0.0037 s; between snapshots 3 (t = "
	            "0.003 s) and 4 (t = 0.004 s): using the nearest, snapshot 4 (");
	snprintf(msg, sizeof msg,
	         "%s: t = 0.003 s (axial strain 0.3 %%, axial stress 25 MPa); snapshot 3 (step "
	         "300000",
	         run);
	expect_pick(run, "--time 0.003", msg);
	snprintf(msg, sizeof msg, "axial stress 25 MPa)\n");
	expect_pick(run, "--time 0.003", msg); /* at a snapshot: no note */
	expect_pick(run, "--snapshot -1", "the last snapshot; snapshot 4 (step 400000");
	expect_pick(run, "--snapshot 1", ": snapshot 1 (step 100000");
	/* without a stress column the snapshots' own values are used */
	expect_pick(bare, "",
	            "peak axial stress 30 MPa at t = 0.002 s (axial strain 0.2 %); "
	            "snapshot 2 (step 200000");

	snprintf(msg, sizeof msg,
	         "post: %s: --stress 4e+07 Pa: the axial stress never reaches it (peak 3.2e+07 "
	         "Pa)\n",
	         run);
	expect_error(run, "--stress 40e6", msg);
	snprintf(msg, sizeof msg,
	         "post: %s: --strain 0.01: the axial strain never reaches it (largest 0.004)\n",
	         run);
	expect_error(run, "--strain 0.01", msg);
	snprintf(msg, sizeof msg,
	         "post: %s: --time 0.005 s: outside the run (t from 0 to 0.004 s)\n", run);
	expect_error(run, "--time 0.005", msg);
	snprintf(msg, sizeof msg,
	         "post: %s: --snapshot 5: out of range (the run has 5 snapshots: 0 to 4, or -1 "
	         "for the last)\n",
	         run);
	expect_error(run, "--snapshot 5", msg);
	expect_usage_error(run, "--snapshot 1 --time 0.001",
	                   "post: --snapshot and --time: give one instant only");
	expect_usage_error(run, "--snapshot 1.5",
	                   "post: --snapshot 1.5: expected an integer snapshot index");
	expect_usage_error(run, "--time -1", "post: --time -1: expected a time in s, >= 0");
	expect_usage_error(
	    run, "--stress 3MPa",
	    "post: --stress 3MPa: expected an axial stress in Pa > 0 (compression positive)");
	expect_usage_error(
	    run, "--stress -5",
	    "post: --stress -5: expected an axial stress in Pa > 0 (compression positive)");
	expect_usage_error(
	    run, "--strain -1",
	    "post: --strain -1: expected an axial strain > 0 (compression positive)");
	return check_done();
}
