#include <stdio.h>

#include "lib/afile.h"
#include "lib/cli.h"
#include "lib/err.h"

int main(int argc, char **argv)
{
	static const cli_spec spec = {
	    .usage = "post COMMAND [options] RUN.h5",
	    .summary = "Post-process a run file: micro-macro stress ratios, crack maps,\nParaView "
	               "files and stress-strain curves.",
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
