#include <stdio.h>

#include "lib/afile.h"
#include "lib/cli.h"
#include "lib/err.h"

int main(int argc, char **argv)
{
	static const cli_spec spec = {
	    .usage = "solve [options] CASE.json",
	    .summary = "Run a bonded discrete-element simulation of a laboratory test on "
	               "an\nassembly and write the history, snapshots and crack log to a run file.",
	    .opts = NULL,
	    .nopts = 0,
	    .min_pos = 1,
	    .max_pos = 1,
	};
	char *pos[1];
	cli_parse(&spec, argc, argv, pos);
	afile_install_signal_cleanup();
	fatal("%s: not implemented yet", pos[0]);
}
