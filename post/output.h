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
