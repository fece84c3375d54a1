/* pack's settings: command-line options, optionally preceded by a JSON file
 * (--config) whose keys are the option names with '_' for '-'; the command
 * line wins over the file. */
#ifndef PACK_OPTIONS_H
#define PACK_OPTIONS_H

#include "lib/cfg.h"
#include "pack/geometry.h"
#include "pack/psd.h"

typedef struct {
	const char *shape, *geometry;
	double diameter, height, thickness, length, width, scale;
	const char *dist, *grading, *arrangement;
	double rmin, rmax, radius, fuzz, sigma, mean_radius;
	long count;
	long seed, threads, cell;
	double beta, keep, band, grow_to;
	const char *export_path, *import_path, *config, *depfile;
	int quiet;
	cfg *file;           /* the --config file (owns its strings) */
	cfg *inline_grading; /* its "grading" object, if given inline */
	char *resolved[3];   /* its geometry, grading, import names beside it */
	char *output;
} pack_options;

/* Parse argv (exits with a message on a bad option or config file). */
void options_parse(pack_options *o, int argc, char **argv);
/* Check a configuration given as JSON text (what a --config file holds;
 * source names it in messages) as pack reads one: every key known, every
 * value within its bounds, the shape, arrangement and sizes consistent.
 * Files it names are not opened. 0, or -1 with err_set(). */
int options_check_config(const char *text, const char *source);
void options_free(pack_options *o);

int options_geometry(const pack_options *o, geometry_spec *g);
/* The size distribution as given (before --count / --mean-radius); with
 * --arrangement hcp, equal spheres of --radius. */
int options_psd(const pack_options *o, psd *d);
/* --arrangement hcp (else random). */
int options_hcp(const pack_options *o);
/* Every setting as one JSON object (caller frees), for provenance. */
char *options_json(const pack_options *o);

#endif
