#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "lib/path.h"
#include "pack/geometry.h"
#include "pack/options.h"

#define LEN 1e-9, 1e3 /* bounds of a length (m) */
/* Bounds of a specimen's size (m): the geometry kernel (OpenCASCADE) works
 * to 1e-7 m and throws on smaller shapes. */
#define SIZE 1e-6, 1e3

enum { NOPT = 32 }; /* room in the option table */

static int table(pack_options *o, cli_opt *t)
{
	const cli_opt opts[] = {
	    {"shape", CLI_STR, &o->shape, "NAME", "", "built-in specimen: cylinder, disc or box", 0,
	     0},
	    {"geometry", CLI_STR, &o->geometry, "FILE", "",
	     "specimen from a file gmsh reads (.geo, .step/.stp, .brep, .msh, .stl) instead of "
	     "--shape",
	     0, 0},
	    {"diameter", CLI_NUM, &o->diameter, "D", "m", "cylinder or disc diameter", SIZE},
	    {"height", CLI_NUM, &o->height, "H", "m", "cylinder height; box edge along z", SIZE},
	    {"thickness", CLI_NUM, &o->thickness, "T", "m", "disc thickness", SIZE},
	    {"length", CLI_NUM, &o->length, "L", "m", "box edge along x", SIZE},
	    {"width", CLI_NUM, &o->width, "W", "m", "box edge along y", SIZE},
	    {"scale", CLI_NUM, &o->scale, "S", "",
	     "factor on the coordinates of a --geometry file (STEP files are read in metres)",
	     1e-12, 1e12},
	    {"dist", CLI_STR, &o->dist, "NAME", "",
	     "size distribution: uniform (in radius, --rmin/--rmax), fuzz (--radius, --fuzz), "
	     "lognormal (--radius, --sigma) or grading (--grading)",
	     0, 0},
	    {"rmin", CLI_NUM, &o->rmin, "R", "m", "smallest radius (uniform)", LEN},
	    {"rmax", CLI_NUM, &o->rmax, "R", "m", "largest radius (uniform)", LEN},
	    {"radius", CLI_NUM, &o->radius, "R", "m",
	     "mean radius (fuzz); median radius (lognormal)", LEN},
	    {"fuzz", CLI_NUM, &o->fuzz, "F", "",
	     "relative fuzz: r = radius (1 + F u), u in [-1, 1]", 0, 0.99},
	    {"sigma", CLI_NUM, &o->sigma, "S", "",
	     "standard deviation of ln r (lognormal, truncated at 3 sigma)", 1e-3, 1.5},
	    {"grading", CLI_STR, &o->grading, "FILE", "",
	     "grading curve (JSON: \"sieve\" sizes in m, cumulative mass fraction \"passing\")", 0,
	     0},
	    {"arrangement", CLI_STR, &o->arrangement, "NAME", "",
	     "how the spheres are placed: random (a jammed periodic cell tiled over the "
	     "specimen) or hcp (hexagonal close packing of equal spheres of --radius, cut to "
	     "the specimen)",
	     0, 0},
	    {"count", CLI_INT, &o->count, "N", "",
	     "scale the sizes so that about N spheres fill the specimen (0: sizes as given)", 0,
	     1e9},
	    {"mean-radius", CLI_NUM, &o->mean_radius, "R", "m",
	     "scale the sizes to this mean radius (0: sizes as given)", 0, 1e3},
	    {"seed", CLI_INT, &o->seed, "N", "", "random seed", 0, 9.2e18},
	    {"threads", CLI_INT, &o->threads, "N", "",
	     "OpenMP threads (0: all cores); the result does not depend on it", 0, 4096},
	    {"beta", CLI_NUM, &o->beta, "B", "",
	     "interaction range for the reported coordination and alpha: spheres i, j count as "
	     "bonded when d_ij <= (1 + B)(r_i + r_j) (Eq. 16, 22; a fraction)",
	     0, 1},
	    {"cell", CLI_INT, &o->cell, "N", "", "largest number of spheres in the periodic cell",
	     100, 1e7},
	    {"keep", CLI_NUM, &o->keep, "K", "radii",
	     "keep a tiled sphere whose centre lies at least K radii inside", 0, 1},
	    {"band", CLI_NUM, &o->band, "B", "mean diameters",
	     "depth of the layer relaxed against the boundary (band and mobile buffer)", 0, 100},
	    {"grow-to", CLI_NUM, &o->grow_to, "PHI", "",
	     "grow every sphere about its centre until the solid fraction (sphere volume over "
	     "the specimen's, overlaps counted twice) is PHI (0: as packed)",
	     0, 0.95},
	    {"import", CLI_STR, &o->import_path, "FILE", "",
	     "take the spheres from a text file of lines 'x y z r' (m) instead of packing", 0, 0},
	    {"export", CLI_STR, &o->export_path, "FILE", "",
	     "also write the spheres as lines 'x y z r' (m), as Yade's export.text", 0, 0},
	    {"config", CLI_STR, &o->config, "FILE", "",
	     "JSON file of settings (keys: these option names with _ for -); options given on "
	     "the command line win",
	     0, 0},
	    {"depfile", CLI_STR, &o->depfile, "FILE", "",
	     "write a make rule to FILE: OUTPUT depends on the configuration, geometry, "
	     "grading and import files read",
	     0, 0},
	    {"quiet", CLI_FLAG, &o->quiet, NULL, "",
	     "print nothing but errors (no summary, no progress)", 0, 0},
	};
	_Static_assert(sizeof opts / sizeof opts[0] <= NOPT, "option table too small");
	memcpy(t, opts, sizeof opts);
	return (int)(sizeof opts / sizeof opts[0]);
}

static void defaults(pack_options *o)
{
	memset(o, 0, sizeof *o);
	o->shape = "cylinder";
	o->diameter = 0.025;
	o->height = 0.05;
	o->thickness = 0.0125;
	o->length = 0.025;
	o->width = 0.025;
	o->scale = 1;
	o->dist = "uniform";
	o->arrangement = "random";
	o->rmin = 0.0005;
	o->rmax = 0.0015;
	o->radius = 0.001;
	o->fuzz = 0.3;
	o->sigma = 0.25;
	o->seed = 1;
	o->beta = 0.10;
	o->cell = 4000;
	o->keep = 0.3;
	o->band = 3;
}

static void json_key(const char *name, char *key, size_t n)
{
	snprintf(key, n, "%s", name);
	for (char *p = key; *p; p++)
		if (*p == '-')
			*p = '_';
}

/* File names given in the --config file are relative to its directory. */
static void resolve_names(pack_options *o, const char *path)
{
	static const char *const keys[] = {"geometry", "grading", "import"};
	const char **names[] = {&o->geometry, &o->grading, &o->import_path};
	for (int k = 0; k < 3; k++)
		if (cfg_has(o->file, keys[k]) && *names[k]) {
			free(o->resolved[k]);
			*names[k] = o->resolved[k] = path_beside(path, *names[k]);
		}
}

/* Settings from a configuration (o->file), checked against the same
 * bounds as the options. */
static int apply_config(pack_options *o, const cli_opt *t, int n)
{
	cfg *c = o->file;
	if (cfg_has(c, "grading")) {
		o->inline_grading = cfg_object_opt(c, "grading");
		if (!o->inline_grading) {
			err_clear();
			if (cfg_string(c, "grading", &o->grading))
				return -1;
		} else { /* read once here, so that its keys count as used */
			psd check = {0};
			int rc = psd_grading(&check, o->inline_grading);
			psd_free(&check);
			if (rc)
				return -1;
		}
	}
	for (int k = 0; k < n; k++) {
		char key[64];
		json_key(t[k].name, key, sizeof key);
		if (strcmp(key, "grading") == 0 || strcmp(key, "config") == 0 || !cfg_has(c, key))
			continue;
		int rc = 0;
		switch (t[k].kind) {
		case CLI_FLAG:
			rc = cfg_bool_or(c, key, t[k].value, 0);
			break;
		case CLI_INT:
			rc = cfg_integer_or(c, key, t[k].value, 0, (long)t[k].lo, (long)t[k].hi);
			break;
		case CLI_NUM:
			rc = cfg_number_or(c, key, t[k].value, 0, t[k].unit, t[k].lo, t[k].hi);
			break;
		case CLI_STR:
			rc = cfg_string_or(c, key, t[k].value, NULL);
			break;
		}
		if (rc)
			return -1;
	}
	return cfg_check_unused(c);
}

/* The --config file, its file names relative to its directory. */
static int apply_file(pack_options *o, const cli_opt *t, int n, const char *path)
{
	o->file = cfg_load(path);
	if (!o->file || apply_config(o, t, n))
		return -1;
	resolve_names(o, path);
	return 0;
}

/* A warning for each setting that differs from its default but does not
 * apply to the chosen shape (or geometry file) and size distribution. */
static void warn_ignored(const pack_options *o)
{
	pack_options d;
	defaults(&d);
	int file = o->geometry != NULL, disc = !strcmp(o->shape, "disc");
	int box = !strcmp(o->shape, "box"), cyl = !strcmp(o->shape, "cylinder");
	int hcp = options_hcp(o);
	const char *dist = o->dist;
	char shape[64], sizes[64];
	snprintf(shape, sizeof shape, file ? "with --geometry" : "to --shape %s", o->shape);
	snprintf(sizes, sizeof sizes, "to --dist %s", dist);
	const struct {
		const char *name;
		int changed, applies;
		const char *why;
	} rules[] = {
	    {"shape", strcmp(o->shape, d.shape) != 0, !file, "with --geometry"},
	    {"diameter", o->diameter != d.diameter, !file && (cyl || disc), shape},
	    {"height", o->height != d.height, !file && (cyl || box), shape},
	    {"thickness", o->thickness != d.thickness, !file && disc, shape},
	    {"length", o->length != d.length, !file && box, shape},
	    {"width", o->width != d.width, !file && box, shape},
	    {"scale", o->scale != d.scale, file && !geometry_is_step(o->geometry),
	     file ? "to a STEP file (read in metres)" : "without --geometry"},
	    {"rmin", o->rmin != d.rmin, !strcmp(dist, "uniform"), sizes},
	    {"rmax", o->rmax != d.rmax, !strcmp(dist, "uniform"), sizes},
	    {"radius", o->radius != d.radius,
	     hcp || !strcmp(dist, "fuzz") || !strcmp(dist, "lognormal"), sizes},
	    {"fuzz", o->fuzz != d.fuzz, !strcmp(dist, "fuzz"), sizes},
	    {"sigma", o->sigma != d.sigma, !strcmp(dist, "lognormal"), sizes},
	    {"grading", o->grading || o->inline_grading, !strcmp(dist, "grading"), sizes},
	    {"cell", o->cell != d.cell, !hcp, "to --arrangement hcp"},
	    {"keep", o->keep != d.keep, !hcp, "to --arrangement hcp"},
	    {"band", o->band != d.band, !hcp, "to --arrangement hcp"},
	};
	for (size_t k = 0; k < sizeof rules / sizeof *rules; k++)
		if (rules[k].changed && !rules[k].applies)
			warn("--%s does not apply %s: ignored", rules[k].name, rules[k].why);
}

/* --arrangement is a word pack knows, and hcp makes its own spheres. */
static int check_arrangement(const pack_options *o)
{
	if (strcmp(o->arrangement, "random") && strcmp(o->arrangement, "hcp"))
		return err_set("--arrangement %s: expected random or hcp", o->arrangement);
	if (options_hcp(o) && o->import_path)
		return err_set("--arrangement hcp and --import %s: expected one of them (imported "
		               "spheres are taken as listed)",
		               o->import_path);
	return 0;
}

int options_check_config(const char *text, const char *source)
{
	pack_options o;
	defaults(&o);
	cli_opt t[NOPT];
	int n = table(&o, t);
	o.file = cfg_parse(text, source);
	if (!o.file || apply_config(&o, t, n)) {
		options_free(&o);
		return -1;
	}
	/* The shape, the arrangement and the sizes (a grading curve in a file
	 * is read by pack itself). */
	geometry_spec g;
	psd d = {0};
	int rc =
	    check_arrangement(&o) || options_geometry(&o, &g) ||
	    (!o.import_path && !(o.grading && !strcmp(o.dist, "grading")) && options_psd(&o, &d));
	psd_free(&d);
	options_free(&o);
	return rc ? err_wrap("%s", source) : 0;
}

void options_parse(pack_options *o, int argc, char **argv)
{
	defaults(o);
	cli_opt t[NOPT];
	int n = table(o, t);
	err_program(argv[0]);
	for (int k = 1; k < argc; k++) {
		const char *path = NULL;
		if (strcmp(argv[k], "--config") == 0 && k + 1 < argc)
			path = argv[k + 1];
		else if (strncmp(argv[k], "--config=", 9) == 0)
			path = argv[k] + 9;
		else if (strcmp(argv[k], "--") == 0)
			break;
		if (path && apply_file(o, t, n, path))
			fatal(NULL);
	}
	static const cli_spec spec_base = {
	    .usage = "pack [options] OUTPUT.h5",
	    .summary =
	        "Fill a specimen with a dense polydisperse sphere assembly and write it, with a\n"
	        "packing report (solid fraction, wall deficit, sizes, coordination, fabric,\n"
	        "overlaps), to an HDF5 assembly file. Lengths are in metres.",
	    .epilog = "Examples:\n"
	              "  pack out.h5                                   25 x 50 mm cylinder, "
	              "radii 0.5-1.5 mm\n"
	              "  pack --diameter 0.05 --height 0.1 ucs.h5      the 50 x 100 mm UCS "
	              "specimen\n"
	              "  pack --shape disc --diameter 0.0378 --thickness 0.0219 bd.h5\n"
	              "  pack --geometry share/geometry/cylinder_150x300.geo --count 100000 c.h5\n"
	              "  pack --dist grading --grading mix.json --count 50000 concrete.h5",
	    .min_pos = 1,
	    .max_pos = 1,
	};
	cli_spec spec = spec_base;
	spec.opts = t;
	spec.nopts = n;
	char *pos[1];
	cli_parse(&spec, argc, argv, pos);
	o->output = pos[0];
	if (check_arrangement(o))
		cli_usage_error(&spec, "%s", err_msg());
	warn_ignored(o);
	path_role outs[] = {
	    {"OUTPUT", o->output}, {"--export", o->export_path}, {"--depfile", o->depfile}};
	path_role ins[] = {{"--config", o->config},
	                   {"--geometry", o->geometry},
	                   {"--grading", o->grading},
	                   {"--import", o->import_path}};
	cli_check_outputs(&spec, outs, 3, ins, 4);
}

void options_free(pack_options *o)
{
	cfg_free(o->file);
	for (int k = 0; k < 3; k++)
		free(o->resolved[k]);
}

/* A geometry file is a file of a kind gmsh reads, by its name: a directory
 * or a specimen file (.json) given here would fail inside gmsh with a
 * message that names neither the option nor what was expected. */
static int geometry_file_kind(const char *path)
{
	static const char *const kinds[] = {".geo", ".step", ".stp", ".brep", ".msh", ".stl"};
	struct stat st;
	if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
		return err_set("--geometry %s: a directory: expected a geometry file", path);
	const char *dot = strrchr(path, '.');
	for (size_t k = 0; dot && k < sizeof kinds / sizeof *kinds; k++)
		if (strcasecmp(dot, kinds[k]) == 0)
			return 0;
	return err_set("--geometry %s: expected a file gmsh reads, named .geo, .step/.stp, .brep, "
	               ".msh or .stl%s",
	               path,
	               dot && strcasecmp(dot, ".json") == 0 ? " (a specimen file goes to --config)"
	                                                    : "");
}

int options_geometry(const pack_options *o, geometry_spec *g)
{
	memset(g, 0, sizeof *g);
	g->scale = o->scale;
	if (o->geometry) {
		g->kind = SHAPE_FILE;
		g->file = o->geometry;
		return geometry_file_kind(o->geometry);
	}
	if (strcmp(o->shape, "cylinder") == 0 || strcmp(o->shape, "disc") == 0) {
		g->kind = o->shape[0] == 'c' ? SHAPE_CYLINDER : SHAPE_DISC;
		g->diameter = o->diameter;
		g->height = g->kind == SHAPE_DISC ? o->thickness : o->height;
		return 0;
	}
	if (strcmp(o->shape, "box") == 0) {
		g->kind = SHAPE_BOX;
		g->size[0] = o->length;
		g->size[1] = o->width;
		g->size[2] = o->height;
		return 0;
	}
	return err_set("--shape %s: expected cylinder, disc or box (or --geometry FILE)", o->shape);
}

int options_hcp(const pack_options *o) { return strcmp(o->arrangement, "hcp") == 0; }

/* The equal spheres of --arrangement hcp: of --radius, with no other size
 * setting, or with --dist fuzz and --fuzz 0 (monodisperse spheres in Yade's
 * terms). */
static int hcp_psd(const pack_options *o, psd *d)
{
	pack_options def;
	defaults(&def);
	int fuzz = !strcmp(o->dist, "fuzz");
	int plain = !strcmp(o->dist, "uniform") && o->rmin == def.rmin && o->rmax == def.rmax;
	if (fuzz && o->fuzz != 0)
		return err_set("--arrangement hcp places equal spheres: --fuzz %g: expected 0",
		               o->fuzz);
	if (!fuzz && !plain)
		return err_set(
		    "--arrangement hcp places equal spheres of --radius: --dist %s with "
		    "its sizes does not apply: expected --dist fuzz with --fuzz 0, or no "
		    "size setting but --radius",
		    o->dist);
	psd_uniform(d, o->radius, o->radius);
	return 0;
}

int options_psd(const pack_options *o, psd *d)
{
	if (options_hcp(o))
		return hcp_psd(o, d);
	if (strcmp(o->dist, "uniform") == 0) {
		if (o->rmin > o->rmax)
			return err_set(
			    "--rmin %g is larger than --rmax %g: expected rmin <= rmax (m)",
			    o->rmin, o->rmax);
		psd_uniform(d, o->rmin, o->rmax);
		return 0;
	}
	if (strcmp(o->dist, "fuzz") == 0) {
		psd_uniform(d, o->radius * (1 - o->fuzz), o->radius * (1 + o->fuzz));
		return 0;
	}
	if (strcmp(o->dist, "lognormal") == 0) {
		psd_lognormal(d, o->radius, o->sigma);
		return 0;
	}
	if (strcmp(o->dist, "grading") == 0) {
		if (o->inline_grading && !o->grading)
			return psd_grading(d, o->inline_grading);
		if (!o->grading)
			return err_set(
			    "--dist grading: expected --grading FILE.json (sieve sizes and "
			    "fractions passing)");
		cfg *c = cfg_load(o->grading);
		if (!c)
			return -1;
		int rc = psd_grading(d, c) || cfg_check_unused(c);
		cfg_free(c);
		return rc ? -1 : 0;
	}
	return err_set("--dist %s: expected uniform, fuzz, lognormal or grading", o->dist);
}

char *options_json(const pack_options *o)
{
	pack_options copy = *o;
	cli_opt t[NOPT];
	int n = table(&copy, t);
	cJSON *root = cJSON_CreateObject();
	for (int k = 0; k < n; k++) {
		char key[64];
		json_key(t[k].name, key, sizeof key);
		if (strcmp(key, "config") == 0 || strcmp(key, "quiet") == 0)
			continue;
		switch (t[k].kind) {
		case CLI_FLAG:
			cJSON_AddBoolToObject(root, key, *(int *)t[k].value);
			break;
		case CLI_INT:
			cJSON_AddNumberToObject(root, key, (double)*(long *)t[k].value);
			break;
		case CLI_NUM:
			cJSON_AddNumberToObject(root, key, *(double *)t[k].value);
			break;
		case CLI_STR:
			if (*(const char **)t[k].value)
				cJSON_AddStringToObject(root, key, *(const char **)t[k].value);
			break;
		}
	}
	if (o->inline_grading && !o->grading) {
		char *text = cfg_text(o->inline_grading);
		cJSON_AddItemToObject(root, "grading", cJSON_Parse(text));
		free(text);
	}
	char *s = cJSON_PrintUnformatted(root);
	cJSON_Delete(root);
	return s;
}
