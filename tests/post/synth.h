/* A synthetic run file for post's tests and examples, written with the
 * lib/runfile.h writer: spheres placed at random (without overlap) in a
 * cylinder of loading axis `axis`, bonded to every neighbour within
 * (1 + beta)(r_i + r_j), loaded by an affine strain field
 *   eps = -e a(x)a + nu e (I - a(x)a)     (e the axial strain, compression
 *                                          positive; a the unit axis)
 * so bond i-j of direction n and length d carries
 *   fn = kn d n.eps.n (1 + noise),  fs = ks (eps.d - (n.eps.d) n)
 * and breaks, in tension when fn reaches its strength or in shear when
 * |fs| reaches tau + mu |fn|, both linear in e so the failure strain of
 * each bond is known in closed form; strengths are halved in an inclined
 * band so the cracks draw a shear band. The axial stress follows
 * sigma_p (e / e_p) exp(1 - e / e_p), peaking at e_p. The configuration
 * names a material of density SYNTH_DENSITY. Everything is deterministic
 * for a seed.
 * With a non-zero `load`, the run is a Brazilian test instead: the
 * specimen is a disc of axis `axis`, diameter `diameter` and thickness
 * `height`, loaded along `load` (a diameter: normal to the axis) by the
 * same strain field about that direction; the case has "test": "bts" and
 * "axis": load, as solve's cases do, and the history a force_axial column,
 * P = sigma_a pi D^2 / 4 (solve's axial stress of a disc). */
#ifndef DEM_TESTS_POST_SYNTH_H
#define DEM_TESTS_POST_SYNTH_H

#include <stdint.h>

#define SYNTH_DENSITY 2000.0 /* kg/m^3 */

typedef struct {
	int nparticles;     /* target count (fewer if the cylinder is full) */
	double radius;      /* m, mean particle radius */
	double diameter;    /* m, cylinder */
	double height;      /* m */
	double axis[3];     /* loading axis (normalised); a disc's axis with `load` */
	double load[3];     /* a Brazilian test's loading diameter; 0: not one */
	double center[3];   /* m */
	int nsnap;          /* snapshots, evenly in strain from 0 */
	int nrows;          /* history rows */
	double peak_strain; /* e_p */
	double peak_stress; /* Pa, sigma_p */
	double end_strain;  /* last strain of the run */
	uint64_t seed;
} synth_opts;

/* Sensible defaults: a 10 mm x 20 mm cylinder of about 400 spheres. */
synth_opts synth_defaults(void);
/* Write the run; returns 0, or -1 with err_set(). */
int synth_run(const char *path, const synth_opts *o);

/* A tiny run for checking instants and errors: four spheres along z, two
 * bonds in compression, nsnap snapshots at times snap_t (s) with axial
 * stresses snap_stress (Pa), and nrows history rows (row_t, row_stress;
 * axial strain = t x 1/s). Without with_stress the history has no
 * stress_axial column. nsnap and nrows may be 0 (an empty run). */
int synth_tiny(const char *path, int nsnap, const double *snap_t, const double *snap_stress,
               int nrows, const double *row_t, const double *row_stress, int with_stress);

#endif
