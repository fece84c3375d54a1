/* post: what a run means. Dispatches `post COMMAND [options] FILE` to the
 * command's own parser; `post --help` lists the commands. */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/afile.h"
#include "lib/cli.h"
#include "lib/err.h"
#include "post/post.h"
#include "post/vtkio.h"

static const struct {
	const char *name;
	int (*run)(int, char **);
	const char *summary;
} commands[] = {
    {"ratios", post_ratios,
     "micro-macro compressive stress ratios by contact orientation (Fig. 11)"},
    {"cracks", post_cracks, "crack discs as a VTK series, crack maps and counts"},
    {"vtk", post_vtk, "ParaView files: particles, bonds, cracks, platens (.pvd series)"},
    {"curve", post_curve, "stress-strain, volumetric strain, broken bonds, energies"},
    {"summary", post_summary, "summary.json: peak, modulus, strengths, bonds broken, timing"},
    {"lammps", post_lammps, "a LAMMPS data file of the bonded spheres, and their bond table"},
    {"study", post_study, "a parametric study's points, and their table and figures"},
};
enum { NCOMMANDS = sizeof commands / sizeof commands[0] };

const char *post_one_file(const char *usage, const char *summary, const cli_opt *opts, int nopts,
                          int argc, char **argv)
{
	const cli_spec spec = {.usage = usage,
	                       .summary = summary,
	                       .opts = opts,
	                       .nopts = nopts,
	                       .min_pos = 1,
	                       .max_pos = 1};
	char *pos[1];
	cli_parse(&spec, argc, argv, pos);
	return pos[0];
}

void post_threads(long threads)
{
	int n = threads ? (int)threads : omp_get_num_procs();
	omp_set_num_threads(n < POST_THREADS ? n : POST_THREADS);
	vtkio_threads();
}

char *post_run_label(const char *path)
{
	const char *base = strrchr(path, '/');
	base = base ? base + 1 : path;
	if (strcmp(base, "run.h5") == 0 && base != path) {
		const char *end = base - 1, *start = end;
		while (start > path && start[-1] != '/')
			start--;
		if (end > start) {
			char *label = xmalloc((size_t)(end - start) + 1);
			memcpy(label, start, (size_t)(end - start));
			label[end - start] = '\0';
			return label;
		}
	}
	char *label = xstrdup(base);
	size_t n = strlen(label);
	if (n > 3 && strcmp(label + n - 3, ".h5") == 0)
		label[n - 3] = '\0';
	return label;
}

int main(int argc, char **argv)
{
	static char epilog[2048];
	int len = snprintf(epilog, sizeof epilog, "Commands:\n");
	for (int k = 0; k < NCOMMANDS; k++)
		len += snprintf(epilog + len, sizeof epilog - (size_t)len, "  %-8s %s\n",
		                commands[k].name, commands[k].summary);
	snprintf(epilog + len, sizeof epilog - (size_t)len,
	         "\nRun 'post COMMAND --help' for the options of a command (share/doc/post.md).");
	static const cli_spec spec = {
	    .usage = "post COMMAND [options] RUN.h5",
	    .summary = "Post-process a run file: micro-macro stress ratios, crack maps,\n"
	               "ParaView files, stress-strain curves and LAMMPS data files; and the\n"
	               "points and table of a parametric study.",
	    .epilog = epilog,
	    .min_pos = 1,
	    .max_pos = 1,
	};
	err_program(argv[0]);
	afile_install_signal_cleanup();
	if (argc < 2 || (argv[1][0] == '-' && argv[1][1])) {
		char *pos[1];
		cli_parse(&spec, argc < 2 ? argc : 2, argv, pos); /* --help, --version, errors */
		return 2; /* not reached: cli_parse exits on every option */
	}
	for (int k = 0; k < NCOMMANDS; k++)
		if (strcmp(argv[1], commands[k].name) == 0) {
			argv[1] = argv[0]; /* the command sees "post [options] FILE" */
			return commands[k].run(argc - 1, argv + 1);
		}
	fprintf(stderr,
	        "%s: unknown command '%s': expected ratios, cracks, vtk, curve, summary, lammps "
	        "or study (see post --help)\n",
	        err_program_name(), argv[1]);
	return 2;
}
