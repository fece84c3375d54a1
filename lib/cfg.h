/* JSON configuration files (materials, cases) read through cJSON.
 *
 * Every lookup names its key, unit and allowed range, so a bad value gives
 * one message naming file, key, value and what was expected:
 *   cement.json: key 'E0': value -3.8e+09: expected a positive number (Pa)
 * Keys that were never looked up are reported by cfg_check_unused(), so a
 * misspelt key is an error rather than a silently ignored setting.
 *
 * A cfg is a view of one JSON object; views of nested objects are owned by
 * their parent and freed with the root.
 */
#ifndef DEM_CFG_H
#define DEM_CFG_H

#include <float.h>
#include <math.h>
#include <stddef.h>

typedef struct cfg cfg;

/* Lower bound meaning "strictly positive". */
#define CFG_POS DBL_TRUE_MIN

cfg *cfg_load(const char *path);
cfg *cfg_parse(const char *text, const char *source);
void cfg_free(cfg *c);

/* The file name given to cfg_load/cfg_parse, and the dotted path of this
 * object inside it ("" for the root). */
const char *cfg_source(const cfg *c);
const char *cfg_path(const cfg *c);
/* The whole object as compact JSON text (caller frees). */
char *cfg_text(const cfg *c);
/* The JSON file at path as a cJSON tree (caller cJSON_Deletes it), read
 * as cfg_load reads it; NULL with the message set (lib/err.h). */
struct cJSON *cfg_load_json(const char *path);

int cfg_has(const cfg *c, const char *key);

/* Required values: a missing key is an error. Bounds are inclusive. */
int cfg_number(cfg *c, const char *key, double *out, const char *unit, double lo, double hi);
int cfg_integer(cfg *c, const char *key, long *out, long lo, long hi);
int cfg_string(cfg *c, const char *key, const char **out);
/* Optional values: *out = def when the key is absent. */
int cfg_number_or(cfg *c, const char *key, double *out, double def, const char *unit, double lo,
                  double hi);
int cfg_integer_or(cfg *c, const char *key, long *out, long def, long lo, long hi);
int cfg_string_or(cfg *c, const char *key, const char **out, const char *def);
int cfg_bool_or(cfg *c, const char *key, int *out, int def);
/* One of a fixed list of words (NULL-terminated); *out is its index. */
int cfg_choice_or(cfg *c, const char *key, int *out, const char *const *words, int def);
/* A numeric array of exactly n elements (n > 0) or of any length (n == 0,
 * then *count is set); each element checked against [lo, hi]. Allocates
 * *out (caller frees). Required. */
int cfg_numbers(cfg *c, const char *key, double **out, size_t *count, size_t n, const char *unit,
                double lo, double hi);

/* The JSON text of a member, whatever its type, marked as read (for a
 * value passed on whole, e.g. a material inside another file); NULL when
 * absent. Caller frees. */
char *cfg_member_text(cfg *c, const char *key);

/* Nested object: required / optional (NULL and no error when absent). */
cfg *cfg_object(cfg *c, const char *key);
cfg *cfg_object_opt(cfg *c, const char *key);
/* Array of objects: number of items (0 when absent; -1 if not an array of
 * objects) and the k-th item as a view. */
long cfg_list(cfg *c, const char *key);
cfg *cfg_item(cfg *c, const char *key, size_t k);

/* Error if any key of this object (and of every nested object that was
 * opened) was never looked up. */
int cfg_check_unused(const cfg *c);

/* Report an error about a key's value in the standard form. Returns -1. */
int cfg_error(const cfg *c, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

#endif
