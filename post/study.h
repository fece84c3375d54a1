/* A parametric study (share/doc/studies.md): one case run on one specimen
 * with one or two parameters varied over lists or ranges of values (keys
 * of the material, the case or the specimen; others may be set to one
 * value at every point), optionally repeated over packing seeds. study_load reads the study file
 * and checks it and every point it makes as pack and solve will read them, so that a bad key or
 * value is one message before anything runs. post study writes the points'
 * files (study_cmd.c) and collects their results (study_table.c). */
#ifndef DEM_POST_STUDY_H
#define DEM_POST_STUDY_H

#include <cjson/cJSON.h>

enum {
	STUDY_MAX_PARAMS = 2,
	STUDY_MAX_VALUES = 64,
	STUDY_MAX_SEEDS = 64,
	STUDY_MAX_POINTS = 1000,
	STUDY_MAX_SETS = 32,
	STUDY_NAME = 160
};

/* The file a varied key belongs to. */
typedef enum { IN_MATERIAL, IN_CASE, IN_SPECIMEN } study_where;

typedef struct {
	char *key; /* as written, e.g. "material.interaction_range" */
	study_where where;
	const char *path; /* the key within its file ("interaction_range"; into key) */
	char *name;       /* in point names and table columns */
	char *label;      /* the figures' axis label */
	double scale;     /* factor on the values in the figures */
	int n, numeric;   /* values; all of them numbers */
	cJSON *value[STUDY_MAX_VALUES];
	char text[STUDY_MAX_VALUES][40]; /* each value as in point names */
} study_param;

/* A key set to one value at every point ("set"). */
typedef struct {
	char *key;
	study_where where;
	const char *path; /* into key */
	cJSON *value;
} study_set;

typedef struct {
	char name[STUDY_NAME];   /* its directory under the study's */
	int v[STUDY_MAX_PARAMS]; /* the value of each parameter (index) */
	long seed;               /* the packing seed; -1: the specimen's own */
} study_point;

typedef struct {
	char *source;                      /* the study file */
	char *title;                       /* the figures' title */
	char *case_file;                   /* absolute */
	char *material_file;               /* absolute; NULL when inline */
	char *specimen_file;               /* absolute; NULL when inline */
	cJSON *kase, *material, *specimen; /* the base files */
	study_set set[STUDY_MAX_SETS];
	int nset;
	study_param p[STUDY_MAX_PARAMS];
	int np;
	long seed[STUDY_MAX_SEEDS];
	int nseeds; /* 0: the specimen's own seed */
	study_point *point;
	int npoints;
} study;

/* Read and check a study file and its points. 0, or -1 with err_set(). */
int study_load(const char *path, study *s);
void study_free(study *s);

/* The files of point k: its material; its case, naming "material.json"
 * and "assembly.h5" beside it; its pack configuration, file names
 * absolute; and for a specimen of Yade's packing (arrangement "yade") the
 * options of tools/yade-pack, the configuration then importing
 * "spheres.txt" (yade_args NULL otherwise). */
typedef struct {
	cJSON *material, *kase, *specimen;
	char *yade_args;
} study_files;

int study_point_files(const study *s, int k, study_files *f);
void study_files_free(study_files *f);

#endif
