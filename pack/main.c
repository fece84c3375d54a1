#include <stdio.h>

#include "lib/afile.h"
#include "lib/cli.h"
#include "lib/err.h"

int main(int argc, char **argv)
{
	static const cli_spec spec = {
	    .usage = "pack [options] OUTPUT.h5",
	    .summary = "Fill a specimen geometry with a dense polydisperse sphere assembly "
	               "and\nwrite it, with a packing report, to an HDF5 assembly file.",
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
