/* The calibration file (share/doc/calibrate.md): the material template and
 * its free parameters, the tests and their specimens, the targets, the
 * budget and how to search. Every key is checked; a bad one is one message
 * naming the file, the key, the value and what was expected. */
#ifndef DEM_CALIBRATE_SPEC_H
#define DEM_CALIBRATE_SPEC_H

#include <cjson/cJSON.h>

#include "calibrate/scaling.h"

enum { CAL_MAX_FREE = 16, CAL_MAX_TESTS = 16, CAL_MAX_TARGETS = 32, CAL_MAX_KEYS = 32 };

/* A material key the calibration changes: a free parameter, or (with the
 * scaling) a key that keeps its ratio to the free ones of its class. */
typedef struct {
	char *name;      /* "E0", or "contact.E" in the nested object */
	scale_class cls; /* CLS_NONE without the scaling */
	int free;        /* 1 for a free parameter */
	double lo, hi;   /* bounds (free parameters) */
	double start;    /* start value (free parameters; tied ones: the template's) */
	double tmpl;     /* the template's value */
	int log;         /* searched on a log scale */
} cal_key;

/* A specimen: an assembly made by pack from a specimen file (with a count
 * and seed of its own when given), or an existing assembly file. */
typedef struct {
	char *config;   /* pack configuration, or NULL */
	long count;     /* 0: the specimen's own */
	long seed;      /* 0: the specimen's own */
	char *assembly; /* an assembly file, or NULL */
} cal_specimen;

typedef struct {
	char *name;
	char *case_file;
	char *test; /* the case's "test" word */
	cal_specimen search, confirm;
	int has_confirm;
} cal_test;

typedef struct {
	int test, quantity;
	double value, tol, weight;
	int from_truth; /* the value is what the truth gives (set by the caller) */
} cal_target;

typedef enum { LOCAL_BOBYQA, LOCAL_COBYLA, LOCAL_SBPLX } local_method;
typedef enum { GLOBAL_AUTO, GLOBAL_NEVER, GLOBAL_ALWAYS } global_mode;

typedef struct {
	char *source; /* the calibration file */
	char *name;
	cJSON *material; /* the template, a complete material */
	cJSON *truth;    /* a blind recovery's true material, or NULL */
	char *material_name, *law;
	cal_key key[CAL_MAX_KEYS];
	int nkey, nfree; /* free keys first, in the file's order */
	cal_test test[CAL_MAX_TESTS];
	int ntest;
	cal_target target[CAL_MAX_TARGETS];
	int ntarget;
	long runs;   /* budget: search runs */
	double wall; /* budget: s of wall time (0: none) */
	int local, global;
	long global_points;
	double global_above; /* a start worse than this (relative error) is poor */
	int scaling;
	double step, xtol, sens_step;
	long patience; /* rounds without a gain of 2 % before the search stops */
	long seed;
} cal_spec;

/* Read and check a calibration file. Returns 0, or -1 with err_set(). */
int spec_load(const char *path, cal_spec *s);
void spec_free(cal_spec *s);

/* A test's case as calibrate runs it, without its material (set per
 * point): no snapshot but the first and the last (solve always writes
 * those); the assembly is given on solve's command line. NULL with
 * err_set() when the file cannot be read. */
cJSON *spec_case_as_run(const cal_test *t);

/* The number value of a (possibly dotted) key of a material object; NULL
 * when absent or not a number. */
cJSON *spec_material_number(cJSON *m, const char *key);
/* Check a material as solve would read it (the law's keys and ranges, no
 * unknown key), naming it `what` in a message. 0, or -1 with err_set(). */
int spec_check_material(const cJSON *m, const char *what);

#endif
