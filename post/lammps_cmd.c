/* post lammps: a LAMMPS data file and its bond table (post/lammps.h) from
 * an assembly (the spheres as packed, bonded as solve would bond them) or
 * from a run at one snapshot (positions, velocities, the bonds not broken
 * by then). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "post/instant.h"
#include "post/lammps.h"
#include "post/load.h"
#include "post/output.h"
#include "post/post.h"
#include "solve/cells.h"

/* The bonds solve forms in an assembly: every pair with d <= (1 + beta)
 * (r_i + r_j) (Eq. 16 of Onate et al. 2015; gamma = 1 + beta for the laws
 * with an interaction range), in (i, j) order, d0 the distance. */
static void form_bonds(const char *file, const dem_assembly *a, double beta, dem_bonds *b)
{
	double rmax = 0;
	for (size_t i = 0; i < a->n; i++)
		rmax = fmax(rmax, a->r[i]);
	cells_pairs cp;
	size_t crowded;
	if (cells_pairs_within(a->x, a->r, a->n, 1 + beta, 2 * (1 + beta) * rmax, &cp, &crowded))
		fatal("%s: particle %zu has more than %d neighbours within the bond range: "
		      "overlapping spheres?",
		      file, crowded, CELLS_CAP);
	memset(b, 0, sizeof *b);
	b->n = cp.n;
	b->i = cp.i;
	b->j = cp.j;
	b->d0 = cp.d;
}

/* The material's density (kg/m^3) in the run's configuration, or 0. */
static double run_density(const dem_run *r)
{
	cJSON *c = r->prov.config ? cJSON_Parse(r->prov.config) : NULL;
	const cJSON *mat = cJSON_GetObjectItemCaseSensitive(c, "material");
	const cJSON *rho = cJSON_GetObjectItemCaseSensitive(mat, "density");
	double v = cJSON_IsNumber(rho) && rho->valuedouble > 0 ? rho->valuedouble : 0;
	cJSON_Delete(c);
	return v;
}

static double largest_diameter(const dem_assembly *a)
{
	double d = 0;
	for (size_t i = 0; i < a->n; i++)
		d = fmax(d, 2 * a->r[i]);
	return d;
}

static int parse_beta(const char *text, double *beta)
{
	char *end;
	*beta = strtod(text, &end);
	return end == text || *end || !(*beta >= 0 && *beta <= 1);
}

/* Into the output directory (made now, when the input has read well). */
static void write_both(const char *out, const char *file, const lammps_data *d)
{
	char *dir = out_dir(out, file);
	char *data = out_path(dir, "lammps.data"), *csv = out_path(dir, "lammps_bonds.csv");
	lammps_write_data(data, d);
	lammps_write_bonds(csv, d);
	printf("wrote %s (%zu spheres, %zu bonds of %zu, atom_style %s, units si) and %s\n", data,
	       d->n, lammps_bonded(d), d->bonds->n, lammps_style_name(d->style), csv);
	free(data), free(csv), free(dir);
}

static void from_assembly(const char *file, const char *out, lammps_data *d, double beta,
                          double margin)
{
	dem_assembly a;
	if (assembly_read(file, &a))
		fatal(NULL);
	if (a.n == 0)
		fatal("%s: the assembly has no spheres", file);
	if (beta < 0)
		beta = a.report.beta;
	if (!(beta >= 0 && beta <= 1))
		fatal("%s: its report gives no interaction range beta: give --beta B", file);
	dem_bonds b;
	form_bonds(file, &a, beta, &b);
	char comment[1200];
	snprintf(comment, sizeof comment,
	         "LAMMPS data file (units si, atom_style %s): the assembly %s, bonded for "
	         "d <= (1 + %g)(r_i + r_j)",
	         lammps_style_name(d->style), file, beta);
	d->comment = comment;
	d->n = a.n, d->x = a.x, d->r = a.r, d->material = a.material;
	d->bonds = &b;
	d->margin = margin * largest_diameter(&a);
	write_both(out, file, d);
	bonds_free(&b);
	assembly_free(&a);
}

static void from_run(const char *file, const char *out, lammps_data *d, const instant *in,
                     double margin)
{
	dem_run r;
	load_run("lammps", file, &r);
	if (d->density <= 0)
		d->density = run_density(&r);
	if (d->density <= 0)
		fatal("%s: its configuration has no material density: give --density RHO (kg/m^3)",
		      file);
	size_t k;
	char desc[1024];
	if (instant_pick(file, &r, in, &k, desc, sizeof desc))
		fatal(NULL);
	printf("%s\n", desc);
	dem_snapshot s;
	load_snapshot(file, &r, k, &s);
	char comment[1200];
	snprintf(comment, sizeof comment,
	         "LAMMPS data file (units si, atom_style %s): the run %s at step %lld (t = %.9g "
	         "s, axial strain %.6g)",
	         lammps_style_name(d->style), file, (long long)s.step, s.t, s.strain_axial);
	d->comment = comment;
	d->n = s.n, d->x = s.x, d->r = r.assembly.r, d->material = r.assembly.material;
	d->v = s.v, d->w = s.w;
	d->bonds = &r.bonds;
	d->state = s.state;
	d->margin = margin * largest_diameter(&r.assembly);
	write_both(out, file, d);
	snapshot_free(&s);
	run_free(&r);
}

int post_lammps(int argc, char **argv)
{
	const char *out = NULL, *style = "bpm/sphere", *beta_text = NULL;
	const char *at_snap = NULL, *at_time = NULL, *at_strain = NULL, *at_stress = NULL;
	double density = 0, margin = 1;
	const cli_opt opts[] = {
	    {"out", CLI_STR, &out, "DIR", "", "output directory (default: that of the file)", 0, 0},
	    {"atom-style", CLI_STR, &style, "STYLE", "",
	     "bpm/sphere (LAMMPS's BPM package) or hybrid (atom_style hybrid sphere bond)", 0, 0},
	    {"density", CLI_NUM, &density, "RHO", "kg/m^3",
	     "density of the spheres; 0: the run's material density (an assembly needs one)", 0,
	     1e9},
	    {"beta", CLI_STR, &beta_text, "B", "",
	     "assembly: bond the pairs with d <= (1 + B)(r_i + r_j), B in [0, 1] (default: the "
	     "beta of its report, pack --beta)",
	     0, 0},
	    {"margin", CLI_NUM, &margin, "M", "largest diameters",
	     "space between the spheres and the faces of the box", 0, 1e6},
	    {"snapshot", CLI_STR, &at_snap, "K", "",
	     "run: snapshot K (0 first, -1 last; default: the last)", 0, 0},
	    {"time", CLI_STR, &at_time, "T", "s", "run: the snapshot nearest to time T", 0, 0},
	    {"strain", CLI_STR, &at_strain, "E", "",
	     "run: where the axial strain first reaches E, a fraction (0.005 is 0.5 %; compression "
	     "positive)",
	     0, 0},
	    {"stress", CLI_STR, &at_stress, "S", "Pa",
	     "run: where the axial stress first reaches S", 0, 0},
	};
	const cli_spec spec = {
	    .usage = "post lammps [options] RUN.h5|ASSEMBLY.h5",
	    .summary = "A LAMMPS data file of the bonded spheres (units si): lammps.data, with\n"
	               "Atoms (diameter, density, position), Velocities (from a run) and Bonds\n"
	               "(every bond not broken, type 1), and lammps_bonds.csv, every bond with\n"
	               "its reference length and state. From a run, its state at one snapshot\n"
	               "(default: the last); from an assembly, the spheres as packed, bonded\n"
	               "as solve bonds them.",
	    .epilog =
	        "Example: post lammps --snapshot 0 runs/ucs/run.h5 (then in LAMMPS: units si,\n"
	        "atom_style bpm/sphere, read_data lammps.data; share/doc/post.md)",
	    .opts = opts,
	    .nopts = sizeof opts / sizeof opts[0],
	    .min_pos = 1,
	    .max_pos = 1,
	};
	char *pos[1];
	cli_parse(&spec, argc, argv, pos);
	lammps_data d = {.density = density};
	if (strcmp(style, "bpm/sphere") == 0)
		d.style = LAMMPS_BPM_SPHERE;
	else if (strcmp(style, "hybrid") == 0)
		d.style = LAMMPS_HYBRID;
	else
		cli_usage_error(&spec, "--atom-style %s: expected bpm/sphere or hybrid", style);
	double beta = -1; /* the assembly report's */
	if (beta_text && parse_beta(beta_text, &beta))
		cli_usage_error(&spec, "--beta %s: expected a number in [0, 1]", beta_text);
	/* Without an instant, the last snapshot. */
	int instant_given = at_snap || at_time || at_strain || at_stress;
	instant in;
	if (instant_parse(&in, instant_given ? at_snap : "-1", at_time, at_strain, at_stress))
		cli_usage_error(&spec, "%s", err_msg());
	const char *file = pos[0];
	file_kind kind = load_kind("lammps", file);
	if (kind == FILE_ASSEMBLY && instant_given)
		cli_usage_error(&spec,
		                "%s: an assembly has one state: --snapshot, --time, --strain "
		                "and --stress choose a run's",
		                file);
	if (kind == FILE_ASSEMBLY && density <= 0)
		cli_usage_error(
		    &spec, "%s: an assembly holds no density: give --density RHO (kg/m^3)", file);
	if (beta_text && kind == FILE_RUN)
		cli_usage_error(&spec,
		                "%s: --beta is for an assembly: a run's bonds are those solve "
		                "formed",
		                file);
	if (kind == FILE_ASSEMBLY)
		from_assembly(file, out, &d, beta, margin);
	else
		from_run(file, out, &d, &in, margin);
	return 0;
}
