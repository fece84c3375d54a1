/* The commands of post (post/main.c dispatches to them). Each parses its
 * own options with lib/cli.h from argv (argv[0] is the program) and
 * returns the exit status. */
#ifndef DEM_POST_POST_H
#define DEM_POST_POST_H

#include "lib/cli.h"

int post_ratios(int argc, char **argv);
int post_cracks(int argc, char **argv);
int post_vtk(int argc, char **argv);
int post_curve(int argc, char **argv);
int post_summary(int argc, char **argv);
int post_lammps(int argc, char **argv);
int post_study(int argc, char **argv);

/* Parse the options of a command that takes one file (usage and summary
 * as in lib/cli.h's cli_spec); returns that file's name. */
const char *post_one_file(const char *usage, const char *summary, const cli_opt *opts, int nopts,
                          int argc, char **argv);

/* The --threads option of the commands that write a VTK series (vtk,
 * cracks), each frame's files on one thread; and its effect, OpenMP's
 * threads: that many, or every core for 0, but at most POST_THREADS (a
 * file each at once); and VTK ready for them (vtkio_threads). */
enum { POST_THREADS = 32 };
#define POST_THREADS_HELP                                                                 \
	"OpenMP threads writing VTK frames at once (0: all cores; at most 32 are used); " \
	"the files do not depend on it"
#define POST_THREADS_OPT(var)                                                   \
	{                                                                       \
		"threads", CLI_INT, &(var), "N", "", POST_THREADS_HELP, 0, 4096 \
	}
void post_threads(long threads);

/* The label of a run in legends and tables: the file name without .h5, or
 * the directory name for a file called run.h5 (runs/ucs/run.h5 -> ucs).
 * Caller frees. */
char *post_run_label(const char *path);

#endif
