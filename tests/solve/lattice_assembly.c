/* lattice-assembly: write a jittered FCC (or SC) lattice cut to a cylinder
 * of height twice its diameter, as an assembly file. A stand-in for pack in
 * the engine's tests and benchmark. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "tests/solve/fixture.h"

int main(int argc, char **argv)
{
	long spheres = 3000, seed = 1;
	double radius = 1e-3, jitter = 0.02, polydisp = 0.02;
	const char *kind = "fcc";
	const cli_opt opts[] = {
	    {"spheres", CLI_INT, &spheres, "N", "", "about this many spheres", 1, 1e8},
	    {"radius", CLI_NUM, &radius, "R", "m", "sphere radius", 1e-9, 1e3},
	    {"jitter", CLI_NUM, &jitter, "F", "", "random displacement, fraction of R", 0, 0.2},
	    {"polydisp", CLI_NUM, &polydisp, "F", "", "random radius change, fraction of R", 0,
	     0.2},
	    {"kind", CLI_STR, &kind, "fcc|sc", "", "lattice", 0, 0},
	    {"seed", CLI_INT, &seed, "S", "", "random seed", 0, 1e18},
	};
	const cli_spec spec = {.usage = "lattice-assembly [options] OUTPUT.h5",
	                       .summary = "Write a jittered lattice of spheres cut to a cylinder "
	                                  "(height = 2 x diameter).",
	                       .opts = opts,
	                       .nopts = (int)(sizeof opts / sizeof opts[0]),
	                       .min_pos = 1,
	                       .max_pos = 1};
	char *pos[1];
	cli_parse(&spec, argc, argv, pos);
	int fcc = strcmp(kind, "sc") != 0;
	/* Solid fraction ~0.74 (FCC) or 0.52 (SC) in a cylinder of volume pi/2 D^3. */
	double phi = fcc ? 0.74 : 0.52;
	double vsphere = 4.0 / 3.0 * 3.141592653589793 * radius * radius * radius;
	double D = cbrt(2 * spheres * vsphere / phi / 3.141592653589793);
	double edge = fcc ? 2 * sqrt(2) * radius : 2 * radius;
	lattice l = {.kind = fcc ? LATTICE_FCC : LATTICE_SC,
	             .nx = (int)ceil(D / edge) + 1,
	             .ny = (int)ceil(D / edge) + 1,
	             .nz = (int)floor(2 * D / edge),
	             .r = radius,
	             .jitter = jitter,
	             .polydisp = polydisp,
	             .diameter = D,
	             .seed = (uint64_t)seed};
	dem_assembly a;
	fixture_lattice(&a, &l);
	fixture_write(&a, pos[0]);
	printf("%s: %zu spheres, cylinder %.4g x %.4g m\n", pos[0], a.n, D, a.geom.height);
	assembly_free(&a);
	return 0;
}
