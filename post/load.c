#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "lib/afile.h"
#include "lib/err.h"
#include "lib/h5.h"
#include "lib/vec3.h"
#include "post/load.h"
#include "post/plot.h"

static void readable_or_die(const char *path)
{
	if (access(path, R_OK) != 0)
		fatal("%s: cannot read: %s", path, strerror(errno));
}

/* A temporary file (NAME.tmp) is not read: what it is, and where the
 * finished file is or will be. */
static void unfinished(const char *cmd, const char *path)
{
	size_t len = strlen(path);
	if (len <= 4 || strcmp(path + len - 4, ".tmp") != 0)
		return;
	char final[4096], ckpt[4200];
	snprintf(final, sizeof final, "%.*s", (int)(len - 4), path);
	snprintf(ckpt, sizeof ckpt, "%s.ckpt", final);
	if (afile_held(final))
		fatal("%s: a program is writing it now: post %s reads finished files (%s, once it "
		      "is done)",
		      path, cmd, final);
	const char *was = "left by a program killed while writing it";
	if (access(ckpt, F_OK) == 0)
		fatal("%s: %s: post %s reads finished files (a killed solve continues with solve "
		      "--restart %s)",
		      path, was, cmd, final);
	if (access(final, F_OK) == 0)
		fatal("%s: %s: post %s reads finished files, such as %s beside it (an earlier "
		      "one)",
		      path, was, cmd, final);
	fatal("%s: %s: post %s reads finished files (run that program again)", path, was, cmd);
}

file_kind load_kind(const char *cmd, const char *path)
{
	readable_or_die(path);
	unfinished(cmd, path);
	h5_quiet();
	hid_t f = H5Fis_hdf5(path) > 0 ? H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT) : -1;
	char *fmt = f >= 0 && H5Aexists(f, "format") > 0 ? h5_read_attr_str(f, "format") : NULL;
	if (f >= 0)
		H5Fclose(f);
	file_kind kind = FILE_RUN;
	int known = fmt && (strcmp(fmt, RUN_FORMAT) == 0 || strcmp(fmt, ASSEMBLY_FORMAT) == 0);
	if (known)
		kind = strcmp(fmt, RUN_FORMAT) == 0 ? FILE_RUN : FILE_ASSEMBLY;
	free(fmt);
	if (!known)
		fatal("%s: not a run file (solve) or an assembly file (pack): post %s reads one of "
		      "them",
		      path, cmd);
	return kind;
}

char *load_caption(const char *path, const dem_run *r)
{
	cJSON *c = r->prov.config ? cJSON_Parse(r->prov.config) : NULL;
	const cJSON *test = cJSON_GetObjectItemCaseSensitive(c, "test");
	const cJSON *mat = cJSON_GetObjectItemCaseSensitive(c, "material");
	const cJSON *name = cJSON_GetObjectItemCaseSensitive(mat, "name");
	char *text = NULL;
	size_t n = 0;
	FILE *f = open_memstream(&text, &n);
	if (!f)
		fatal("out of memory");
	fputs(path, f);
	if (cJSON_IsString(test))
		fprintf(f, " · %s", test->valuestring);
	if (cJSON_IsString(name))
		fprintf(f, " · %s", name->valuestring);
	fclose(f);
	cJSON_Delete(c);
	return text;
}

int load_is_bts(const dem_run *r)
{
	cJSON *c = r->prov.config ? cJSON_Parse(r->prov.config) : NULL;
	const cJSON *test = cJSON_GetObjectItemCaseSensitive(c, "test");
	int bts = cJSON_IsString(test) && strcmp(test->valuestring, "bts") == 0;
	cJSON_Delete(c);
	return bts;
}

void load_axis(const dem_run *r, double a[3])
{
	cJSON *c = r->prov.config ? cJSON_Parse(r->prov.config) : NULL;
	const cJSON *axis = cJSON_GetObjectItemCaseSensitive(c, "axis");
	double v[3] = {0, 0, 0};
	if (cJSON_IsArray(axis) && cJSON_GetArraySize(axis) == 3)
		for (int k = 0; k < 3; k++) {
			const cJSON *x = cJSON_GetArrayItem(axis, k);
			v[k] = cJSON_IsNumber(x) ? x->valuedouble : 0;
		}
	cJSON_Delete(c);
	if (v3_norm(v) == 0)
		v3_copy(v, r->assembly.geom.axis);
	if (v3_norm(v) == 0)
		v[2] = 1;
	v3_scale(a, v, 1 / v3_norm(v));
}

void load_run(const char *cmd, const char *path, dem_run *r)
{
	readable_or_die(path);
	unfinished(cmd, path);
	if (run_read(path, r) == 0) {
		char *caption = load_caption(path, r);
		plot_set_footer(caption);
		free(caption);
		return;
	}
	if (!strstr(err_msg(), "\"" ASSEMBLY_FORMAT "\""))
		fatal(NULL);
	fatal("%s (an assembly written by pack: post %s reads a run file written by solve)",
	      err_msg(), cmd);
}

void load_snapshot(const char *path, const dem_run *r, size_t k, dem_snapshot *s)
{
	if (run_read_snapshot(path, r, k, s))
		fatal(NULL);
}
