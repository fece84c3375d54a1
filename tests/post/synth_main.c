/* post_synth: write a synthetic run file (tests/post/synth.h) for trying
 * post by hand and for the script tests. */
#include <math.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "tests/post/synth.h"

int main(int argc, char **argv)
{
	synth_opts o = synth_defaults();
	long n = o.nparticles, nsnap = o.nsnap, seed = (long)o.seed;
	double tilt = 0;
	const cli_opt opts[] = {
	    {"particles", CLI_INT, &n, "N", "", "target number of spheres", 1, 1e6},
	    {"radius", CLI_NUM, &o.radius, "R", "m", "mean sphere radius", 1e-6, 1},
	    {"diameter", CLI_NUM, &o.diameter, "D", "m", "cylinder diameter", 1e-6, 10},
	    {"height", CLI_NUM, &o.height, "H", "m", "cylinder height", 1e-6, 10},
	    {"snapshots", CLI_INT, &nsnap, "K", "", "number of snapshots", 0, 1000},
	    {"tilt", CLI_NUM, &tilt, "A", "deg", "loading axis tilted from z towards x", -90, 90},
	    {"seed", CLI_INT, &seed, "S", "", "random seed", 0, 1e9},
	};
	const cli_spec spec = {.usage = "post_synth [options] RUN.h5",
	                       .summary = "Write a synthetic UCS run file (tests/post/synth.h).",
	                       .opts = opts,
	                       .nopts = sizeof opts / sizeof opts[0],
	                       .min_pos = 1,
	                       .max_pos = 1};
	char *pos[1];
	cli_parse(&spec, argc, argv, pos);
	o.nparticles = (int)n;
	o.nsnap = (int)nsnap;
	o.seed = (uint64_t)seed;
	o.axis[0] = sin(tilt * 3.14159265358979323846 / 180);
	o.axis[2] = cos(tilt * 3.14159265358979323846 / 180);
	if (synth_run(pos[0], &o))
		fatal(NULL);
	return 0;
}
