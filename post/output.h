/* Where post writes and how: an output directory (created when missing,
 * by default the input file's directory) and text files written under a
 * temporary name and renamed when complete (lib/afile.h). These are
 * program-level helpers: a failure is fatal. */
#ifndef DEM_POST_OUTPUT_H
#define DEM_POST_OUTPUT_H

#include <stdio.h>

/* The output directory: opt when given, else the directory of input.
 * Created (with its parents) when missing. Caller frees. */
char *out_dir(const char *opt, const char *input);
/* "dir/name" (caller frees). */
char *out_path(const char *dir, const char *name);
/* Create a directory and its parents; fatal on failure. */
void out_mkdir(const char *dir);

/* A series of files (post vtk's frames, post cracks' discs) that replaces
 * the older one in dir as a whole. Its files are written into a staging
 * directory, dir/.NAME.new (out_series_begin: made empty, its path
 * returned; caller frees), then moved into dir (out_series_commit): the
 * marker (the file whose presence says the series is complete) and every
 * file of the older series (those ours() accepts) removed, the new files
 * renamed in, the marker last. A kill before the commit leaves the older
 * series whole, one during it a series without its marker: never a marker
 * over files of two series. Until the commit an interrupting signal or a
 * fatal error removes the staging directory (afile_stage_dir); a kill -9
 * leaves it, and the next out_series_begin removes it. */
char *out_series_begin(const char *dir, const char *name);
void out_series_commit(const char *dir, const char *stage, const char *marker,
                       int (*ours)(const char *name));

/* Whether name is a file of part's series: PART.pvd or PART_<digits>.EXT. */
int out_series_name(const char *name, const char *part, const char *ext);

/* A text file written atomically. */
typedef struct {
	FILE *f;
	char *path;
	char tmp[4096];
} out_text;

void out_text_open(out_text *o, const char *path);
void out_text_commit(out_text *o);

/* A CSV field: quoted when it holds a comma, a quote or a newline. A
 * number, empty when not finite (a missing value). */
void out_csv_str(FILE *f, const char *s);
void out_csv_num(FILE *f, double v);

#endif
