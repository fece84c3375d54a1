/* Small JSON outputs (the run report, summaries) built with cJSON and
 * written atomically (lib/afile.h), with one spelling of every key across
 * programs. Numbers that are not finite are written as null. */
#ifndef DEM_JSON_H
#define DEM_JSON_H

#include <cjson/cJSON.h>

void json_num(cJSON *o, const char *key, double v);
void json_str(cJSON *o, const char *key, const char *v);
/* true, false, or null when known is 0. */
void json_bool(cJSON *o, const char *key, int known, int v);
/* Write o, indented, to path (through a temporary renamed into place) and
 * free it; 0, or -1 and err_msg. */
int json_write(const char *path, cJSON *o);

#endif
