#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "lib/afile.h"
#include "lib/assembly.h"
#include "lib/cli.h"
#include "lib/depfile.h"
#include "lib/err.h"
#include "lib/progress.h"
#include "solve/case.h"
#include "solve/h5mpi.h"
#include "solve/par.h"
#include "solve/report.h"
#include "solve/run.h"

static int solve_main(int argc, char **argv)
{
	const char *assembly = NULL, *output = "run.h5", *restart = NULL, *report = NULL,
	           *depfile = NULL;
	long threads = 0, max_steps = 0;
	double max_wall = 0, log_every = 30;
	int quiet = 0, show_progress = 0;
	report_start();
	const cli_opt opts[] = {
	    {"assembly", CLI_STR, &assembly, "FILE", "",
	     "assembly file, instead of the case's \"assembly\"", 0, 0},
	    {"output", CLI_STR, &output, "FILE", "",
	     "run file to write (one already there is replaced when this run ends, and kept until "
	     "then)",
	     0, 0},
	    {"threads", CLI_INT, &threads, "N", "",
	     "OpenMP threads (0: the case's \"threads\", else all cores); results do not depend "
	     "on it",
	     0, 1024},
	    {"restart", CLI_STR, &restart, "RUN.h5", "",
	     "continue the run in RUN.h5 from its last checkpoint (no CASE)", 0, 0},
	    {"max-steps", CLI_INT, &max_steps, "N", "steps",
	     "stop after N steps of this invocation, checkpointed and restartable (0: no limit)", 0,
	     1e15},
	    {"max-wall", CLI_NUM, &max_wall, "S", "s",
	     "stop after S seconds of wall time, checkpointed and restartable (0: no limit)", 0,
	     1e12},
	    {"report", CLI_STR, &report, "FILE", "", "write the run report as JSON to FILE", 0, 0},
	    {"depfile", CLI_STR, &depfile, "FILE", "",
	     "write a make rule to FILE: the output depends on the case, material and assembly "
	     "files read",
	     0, 0},
	    {"progress", CLI_FLAG, &show_progress, NULL, "",
	     "show the progress line even when stderr is not a terminal", 0, 0},
	    {"log-every", CLI_NUM, &log_every, "S", "s",
	     "when stderr is not a terminal, a progress line every S seconds (0: none)", 0, 1e9},
	    {"quiet", CLI_FLAG, &quiet, NULL, "", "print nothing but errors", 0, 0},
	};
	static const char summary[] =
	    "Run a bonded discrete-element simulation of a laboratory test on an assembly and\n"
	    "write the history, snapshots, crack log and checkpoints to a run file. The case\n"
	    "file (JSON) names the assembly, the material and the loading program; its keys\n"
	    "are described in share/doc/solve.md.\n\n"
	    "Under mpirun -np K (a solve built with MPI) the specimen is split among K\n"
	    "ranks, each with its --threads; the run file is the same, bit for bit, on any\n"
	    "number of ranks and threads, and --restart may use another K. The run file's\n"
	    "directory must be shared by every rank (not /tmp on each node).\n\n"
	    "Exit status: 0 complete or stopped by a stop rule, 1 error or diagnosed failure\n"
	    "(the run file is kept, its status says why), 2 usage, 3 interrupted by a signal\n"
	    "or a budget (continue with --restart).";
	const cli_spec spec = {
	    .usage = "solve [options] CASE.json | solve --restart RUN.h5 [options]",
	    .summary = summary,
	    .epilog = "Examples:\n  solve --assembly runs/demo-ucs/assembly.h5 --output "
	              "runs/demo-ucs/run.h5 share/cases/demo-ucs.json\n"
	              "  mpirun -np 4 solve --threads 2 --output run.h5 case.json",
	    .opts = opts,
	    .nopts = (int)(sizeof opts / sizeof opts[0]),
	    .min_pos = 0,
	    .max_pos = 1,
	};
	char *pos[1];
	int npos = cli_parse(&spec, argc, argv, pos);
	afile_install_signal_cleanup();
	progress_log_every(log_every);
	if (show_progress)
		progress_force(1);
	/* Rank 0 speaks and writes for all (run.c). */
	quiet = quiet || par_rank() > 0;
	if (quiet)
		progress_force(0);
	run_opts o = {.output = output,
	              .restart = restart,
	              .max_steps = max_steps,
	              .max_wall = max_wall,
	              .report = report,
	              .threads = (int)threads,
	              .quiet = quiet};
	if (restart) {
		if (npos || assembly || depfile || strcmp(output, "run.h5") != 0)
			cli_usage_error(&spec, "--restart continues the run stored in %s: %s",
			                restart,
			                npos ? "give no case file"
			                     : "--assembly, --output and --depfile do not apply");
		o.output = restart;
		path_role outs[] = {{"--report", report}}, ins[] = {{"--restart", restart}};
		cli_check_outputs(&spec, outs, 1, ins, 1);
		/* The run's case and material files are not known here: any file
		 * but an earlier report is kept. */
		if (report && !report_replaceable(report))
			cli_usage_error(&spec,
			                "--report %s: a file that is not a run report is there: "
			                "expected a new file name, or an earlier report",
			                report);
		return run_restart(&o);
	}
	if (npos != 1)
		cli_usage_error(&spec, "missing argument CASE.json");
	dem_case cs;
	if (case_load(pos[0], assembly, &cs))
		fatal(NULL);
	const char *inputs[] = {pos[0], cs.material_file, cs.assembly};
	path_role outs[] = {{"--output", output}, {"--report", report}, {"--depfile", depfile}};
	path_role ins[] = {{"the case", pos[0]},
	                   {"the material", cs.material_file},
	                   {"the assembly", cs.assembly}};
	cli_check_outputs(&spec, outs, 3, ins, 3);
	if (!assembly && access(cs.assembly, F_OK) != 0)
		fatal("%s: key 'assembly': %s: %s (a relative path in a case file is relative to "
		      "the case file's directory); make it with pack, or give --assembly FILE",
		      pos[0], cs.assembly, strerror(errno));
	if (depfile && par_rank() == 0 && depfile_write(depfile, output, inputs, 3))
		fatal(NULL);
	dem_assembly a; /* each rank a piece (solve/order.h) */
	if (assembly_read_part(cs.assembly, par_rank(), par_size(), &a))
		fatal(NULL);
	int code = run_case(&cs, &a, &o);
	case_free(&cs);
	return code;
}

int main(int argc, char **argv)
{
	err_program(argv[0]);
	if (par_init(&argc, &argv))
		fatal(NULL);
#ifdef DEM_MPI
	h5mpi_install(); /* the run file written by every rank */
#endif
	int code = solve_main(argc, argv);
	par_finalize();
	return code;
}
