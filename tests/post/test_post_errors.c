/* Bad input to post: one exact message on stderr, a non-zero exit status
 * and no output left behind (the output directory is not even made). */
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "lib/runfile.h"
#include "tests/check.h"
#include "tests/post/harness.h"
#include "tests/post/synth.h"

static char dir[1024], out[1100];

/* post <cmd> --out <out> <args> fails with status and exactly message. */
static void expect(int status, const char *message, const char *cmd, const char *args)
{
	post_result r = harness_post("%s --out %s %s", cmd, out, args);
	if (r.status != status)
		fprintf(stderr, "post %s %s: status %d\n", cmd, args, r.status);
	CHECK(r.status == status);
	CHECK_STR(r.err, message);
	CHECK(!harness_exists(out));
	harness_free(&r);
}

int main(void)
{
	harness_dir(dir, sizeof dir, "errors");
	snprintf(out, sizeof out, "%s/out", dir);
	char run[1100], empty[1100], assembly[1100], text[1100], exp[1100], msg[4096];
	snprintf(run, sizeof run, "%s/run.h5", dir);
	snprintf(empty, sizeof empty, "%s/empty.h5", dir);
	snprintf(assembly, sizeof assembly, "%s/assembly.h5", dir);
	snprintf(text, sizeof text, "%s/notes.txt", dir);
	snprintf(exp, sizeof exp, "%s/exp.csv", dir);
	const double t[2] = {0, 1e-3}, s[2] = {0, 5e6};
	CHECK(synth_tiny(run, 2, t, s, 2, t, s, 1) == 0);
	CHECK(synth_tiny(empty, 0, NULL, NULL, 0, NULL, NULL, 1) == 0);
	dem_run r;
	CHECK(run_read(run, &r) == 0);
	CHECK(assembly_write(assembly, &r.assembly) == 0);
	run_free(&r);
	FILE *f = fopen(text, "w");
	fputs("not a run\n", f);
	fclose(f);

	/* vtk and lammps read assemblies too */
	const char *commands[] = {"ratios", "cracks", "vtk", "curve", "lammps"};
	const int both[] = {0, 0, 1, 0, 1};
	for (int c = 0; c < 5; c++) {
		snprintf(msg, sizeof msg,
		         "post: %s/missing.h5: cannot read: No such file or directory\n", dir);
		char args[1200];
		snprintf(args, sizeof args, "%s/missing.h5", dir);
		expect(1, msg, commands[c], args);
		if (both[c])
			snprintf(msg, sizeof msg,
			         "post: %s: not a run file (solve) or an assembly file (pack): "
			         "post %s reads one of them\n",
			         text, commands[c]);
		else
			snprintf(msg, sizeof msg,
			         "post: %s: not a readable HDF5 file (truncated or another "
			         "format)\n",
			         text);
		expect(1, msg, commands[c], text);
		if (both[c])
			continue;
		snprintf(msg, sizeof msg,
		         "post: %s: attribute 'format': value \"dem-assembly\": expected "
		         "\"dem-run\" (an "
		         "assembly written by pack: post %s reads a run file written by solve)\n",
		         assembly, commands[c]);
		expect(1, msg, commands[c], assembly);
	}
	/* the temporary of a killed run */
	char killed[1200], stem[1100];
	snprintf(stem, sizeof stem, "%s/killed.h5", dir);
	snprintf(killed, sizeof killed, "%s.tmp", stem);
	FILE *k = fopen(killed, "w");
	CHECK(k != NULL);
	if (k) {
		fputs("half an HDF5 file\n", k);
		fclose(k);
	}
	/* ... with nothing beside it, with an earlier finished run, with the
	 * recovery copy that continues it. */
	char ckpt[1200];
	snprintf(ckpt, sizeof ckpt, "%s.ckpt", stem);
	for (int c = 0; c < 5; c++) {
		const char *was = "left by a program killed while writing it";
		snprintf(msg, sizeof msg,
		         "post: %s: %s: post %s reads finished files (run that program again)\n",
		         killed, was, commands[c]);
		expect(1, msg, commands[c], killed);
		CHECK(link(empty, stem) == 0);
		snprintf(msg, sizeof msg,
		         "post: %s: %s: post %s reads finished files, such as %s beside it (an "
		         "earlier one)\n",
		         killed, was, commands[c], stem);
		expect(1, msg, commands[c], killed);
		CHECK(link(empty, ckpt) == 0);
		snprintf(msg, sizeof msg,
		         "post: %s: %s: post %s reads finished files (a killed solve continues "
		         "with solve --restart %s)\n",
		         killed, was, commands[c], stem);
		expect(1, msg, commands[c], killed);
		unlink(stem), unlink(ckpt);
		/* ... and one a program holds (afile.h): still being written. */
		int fd = open(killed, O_RDWR);
		CHECK(fd >= 0 && flock(fd, LOCK_EX) == 0);
		snprintf(msg, sizeof msg,
		         "post: %s: a program is writing it now: post %s reads finished files (%s, "
		         "once it is done)\n",
		         killed, commands[c], stem);
		expect(1, msg, commands[c], killed);
		close(fd);
	}
	/* an empty run: nothing was written after the start */
	snprintf(msg, sizeof msg,
	         "post: %s: the run has no snapshots (it stopped before writing one)\n", empty);
	expect(1, msg, "ratios", empty);
	expect(1, msg, "vtk", empty);
	snprintf(msg, sizeof msg,
	         "post: %s: the history table is empty (the run stopped before its first row)\n",
	         empty);
	expect(1, msg, "curve", empty);
	/* options */
	char args[2400];
	snprintf(args, sizeof args, "--labels a,b %s", run);
	expect(1, "post: --labels a,b: 2 labels for 1 run files (one per run, comma-separated)\n",
	       "ratios", args);
	snprintf(args, sizeof args, "--bin-width 0 %s", run);
	expect(2, "post: --bin-width 0: expected a number in [0.1, 90] (deg)\n", "ratios", args);
	snprintf(args, sizeof args, "%s %s", run, run);
	snprintf(
	    msg, sizeof msg,
	    "post: unexpected argument '%s' (usage: post curve [options] RUN.h5; see --help)\n",
	    run);
	expect(2, msg, "curve", args);
	/* one run given twice to ratios, by its name or by another name of it */
	snprintf(msg, sizeof msg,
	         "post: %s: given twice (run files 1 and 2): expected each run once (it would "
	         "be counted twice)\n",
	         run);
	expect(1, msg, "ratios", args);
	snprintf(args, sizeof args, "%s %s/./run.h5", run, dir);
	snprintf(msg, sizeof msg,
	         "post: %s/./run.h5: the same file as %s (run files 1 and 2): expected each run "
	         "once (it would be counted twice)\n",
	         dir, run);
	expect(1, msg, "ratios", args);
	/* experimental points */
	f = fopen(exp, "w");
	fputs("# test\nstrain_axial,stress_axial_MPa\n0.001,12\n0.002,2O\n", f);
	fclose(f);
	snprintf(args, sizeof args, "--experiment %s %s", exp, run);
	snprintf(msg, sizeof msg,
	         "post: %s: line 4: column 'stress_axial_MPa': value '2O': expected a number\n",
	         exp);
	expect(1, msg, "curve", args);
	f = fopen(exp, "w");
	fputs("strain,stress\n0.001,12\n", f);
	fclose(f);
	snprintf(msg, sizeof msg,
	         "post: %s: line 1: the header must name the columns strain_axial and stress_axial "
	         "(Pa) or stress_axial_MPa\n",
	         exp);
	expect(1, msg, "curve", args);
	/* A row of more fields than the header (decimal commas), no points, MPa
	 * under the Pa column, both stress columns, a column named twice: one
	 * message each. */
	const char *bad[][2] = {
	    {"strain_axial,stress_axial_MPa\n0,001,5\n",
	     "line 2: 3 fields, the header has 2 (a decimal comma? the separator is the comma, "
	     "the decimal mark the point)"},
	    {"strain_axial,stress_axial_MPa\n", "a header and no points"},
	    {"strain_axial,stress_axial\n0.001,5\n0.002,9\n",
	     "column 'stress_axial' (Pa): at most 9 Pa: values in MPa go in a column named "
	     "stress_axial_MPa"},
	    {"strain_axial,stress_axial,stress_axial_MPa\n0.001,5e6,5\n",
	     "line 1: the header names stress_axial and stress_axial_MPa: expected one of them"},
	    {"# a column twice\nstrain_axial,stress_axial_MPa,strain_axial\n0.001,5,0.002\n",
	     "line 2: column 'strain_axial' is named twice in the header (fields 1 and 3): "
	     "expected each column once"},
	    {"stress_axial_MPa,strain_axial,stress_axial_MPa\n5,0.001,6\n",
	     "line 1: column 'stress_axial_MPa' is named twice in the header (fields 1 and 3): "
	     "expected each column once"}};
	for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
		f = fopen(exp, "w");
		fputs(bad[k][0], f);
		fclose(f);
		snprintf(msg, sizeof msg, "post: %s: %s\n", exp, bad[k][1]);
		expect(1, msg, "curve", args);
	}
	/* A spreadsheet's byte order mark before the header is skipped. */
	f = fopen(exp, "w");
	fputs("\xEF\xBB\xBFstrain_axial,stress_axial_MPa\n0.001,12\n", f);
	fclose(f);
	post_result ok = harness_post("curve --no-png --experiment %s %s", exp, run);
	CHECK(ok.status == 0);
	harness_free(&ok);
	/* commands */
	post_result res = harness_post("nonsense %s", run);
	CHECK(res.status == 2);
	CHECK_STR(res.err, "post: unknown command 'nonsense': expected ratios, cracks, vtk, curve, "
	                   "summary, lammps or study (see post --help)\n");
	harness_free(&res);
	res = harness_post("--help");
	CHECK(res.status == 0);
	CHECK_CONTAINS(res.out, "  ratios   ");
	CHECK_CONTAINS(res.out, "  curve    ");
	harness_free(&res);
	res = harness_post("ratios --help");
	CHECK(res.status == 0);
	CHECK_CONTAINS(res.out,
	               "--bin-width DEG          width of the angle bins (deg) [default: 10]");
	harness_free(&res);
	return check_done();
}
