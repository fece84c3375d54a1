#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/afile.h"
#include "lib/err.h"
#include "lib/h5.h"
#include "lib/json.h"

void json_num(cJSON *o, const char *key, double v)
{
	cJSON_AddItemToObject(o, key, isfinite(v) ? cJSON_CreateNumber(v) : cJSON_CreateNull());
}

void json_str(cJSON *o, const char *key, const char *v)
{
	cJSON_AddItemToObject(o, key, cJSON_CreateString(v ? v : ""));
}

void json_bool(cJSON *o, const char *key, int known, int v)
{
	cJSON_AddItemToObject(o, key, known ? cJSON_CreateBool(v) : cJSON_CreateNull());
}

int json_write(const char *path, cJSON *o)
{
	char *text = cJSON_Print(o);
	cJSON_Delete(o);
	if (!text)
		return err_set("%s: out of memory for the JSON text", path);
	char tmp[4200];
	int rc = afile_begin(path, tmp, sizeof tmp);
	FILE *f = rc ? NULL : fopen(tmp, "w");
	if (!rc && !f)
		rc = err_set("%s: cannot create: %s", tmp, strerror(errno));
	if (f) {
		int bad = fputs(text, f) < 0 || fputc('\n', f) < 0;
		if (fclose(f) || bad)
			rc = h5_write_error(tmp, "the JSON text");
		rc = rc || afile_commit(tmp, path);
		if (rc)
			afile_discard(tmp);
	}
	free(text);
	return rc ? -1 : 0;
}
