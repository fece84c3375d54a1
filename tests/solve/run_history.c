/* run-history: print a run file's status and history table as CSV (for the
 * engine's tests and for looking at a run without post). */
#include <stdio.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "lib/runfile.h"

int main(int argc, char **argv)
{
	long every = 1;
	const cli_opt opts[] = {
	    {"every", CLI_INT, &every, "N", "", "print every N-th row", 1, 1e9}};
	const cli_spec spec = {.usage = "run-history [options] RUN.h5",
	                       .summary = "Print the status, counts and history of a run file.",
	                       .opts = opts,
	                       .nopts = 1,
	                       .min_pos = 1,
	                       .max_pos = 1};
	char *pos[1];
	cli_parse(&spec, argc, argv, pos);
	dem_run r;
	if (run_read(pos[0], &r))
		fatal(NULL);
	printf("# status: %s\n# particles %zu, bonds %zu, snapshots %zu, cracks %zu\n", r.status,
	       r.assembly.n, r.bonds.n, r.nsnap, r.ncracks);
	for (int c = 0; c < r.ncols; c++)
		printf("%s%s", c ? "," : "", r.col_name[c]);
	printf("\n");
	for (size_t k = 0; k < r.nrows; k += (size_t)every) {
		for (int c = 0; c < r.ncols; c++)
			printf("%s%.10g", c ? "," : "", r.col[c][k]);
		printf("\n");
	}
	run_free(&r);
	return 0;
}
