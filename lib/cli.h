/* Command-line options from a table: the same table drives parsing, range
 * checks and --help (every option with its unit and default), so the help
 * text cannot drift from what the program accepts. --help and --version are
 * built in; an unknown option or a bad value is one line on stderr and exit
 * status 2. */
#ifndef DEM_CLI_H
#define DEM_CLI_H

#include "lib/path.h"

typedef enum { CLI_FLAG, CLI_INT, CLI_NUM, CLI_STR } cli_kind;

typedef struct {
	const char *name; /* long name without "--" */
	cli_kind kind;
	void *value;      /* int* (flag), long*, double*, const char** */
	const char *arg;  /* metavariable shown in help, e.g. "N", "FILE" */
	const char *unit; /* SI unit shown in help, "" if none */
	const char *help;
	double lo, hi; /* inclusive bounds for CLI_INT/CLI_NUM */
} cli_opt;

typedef struct {
	const char *usage;   /* "pack [options] OUTPUT.h5" */
	const char *summary; /* what the program does, a few lines */
	const char *epilog;  /* examples, or NULL */
	const cli_opt *opts;
	int nopts;
	int min_pos, max_pos; /* number of positional arguments allowed */
} cli_spec;

/* Parse argv[1..argc-1] (options may follow positionals; "--" ends them).
 * Positional arguments are stored in pos[], their count is returned. */
int cli_parse(const cli_spec *spec, int argc, char **argv, char **pos);
void cli_help(const cli_spec *spec);
/* A usage error: "<program>: <message> (usage: <usage>; see --help)" on
 * stderr, exit status 2. */
_Noreturn void cli_usage_error(const cli_spec *spec, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* The outputs asked for, checked before any work (lib/path.h): one that
 * would overwrite an input or another output, or is no file name, is a
 * usage error; one in a directory that cannot be written exits with 1. */
void cli_check_outputs(const cli_spec *spec, const path_role *out, int nout, const path_role *in,
                       int nin);

#endif
