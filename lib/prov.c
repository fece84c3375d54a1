#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "lib/err.h"
#include "lib/h5.h"
#include "lib/prov.h"
#include "version.h"

void prov_init(dem_provenance *p, const char *program, const char *config, uint64_t seed)
{
	char when[32];
	time_t now = time(NULL);
	struct tm tm;
	gmtime_r(&now, &tm);
	strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &tm);
	p->program = xstrdup(program);
	p->version = xstrdup(DEM_VERSION);
	p->created = xstrdup(when);
	p->config = xstrdup(config ? config : "{}");
	p->seed = seed;
}

void prov_free(dem_provenance *p)
{
	free(p->program);
	free(p->version);
	free(p->created);
	free(p->config);
	memset(p, 0, sizeof *p);
}

int prov_write(hid_t file, const char *format, const dem_provenance *p)
{
	if (format && h5_attr_str(file, "format", format))
		return -1;
	if (h5_attr_str(file, "program", p->program) ||
	    h5_attr_str(file, "program_version", p->version) ||
	    h5_attr_str(file, "created", p->created) || h5_attr_str(file, "config", p->config) ||
	    h5_attr_i64(file, "seed", (int64_t)p->seed))
		return -1;
	return 0;
}

int prov_read(hid_t file, dem_provenance *p)
{
	int64_t seed = 0;
	memset(p, 0, sizeof *p);
	if (!(p->program = h5_read_attr_str(file, "program")) ||
	    !(p->version = h5_read_attr_str(file, "program_version")) ||
	    !(p->created = h5_read_attr_str(file, "created")) ||
	    !(p->config = h5_read_attr_str(file, "config")) ||
	    h5_read_attr_i64(file, "seed", &seed)) {
		prov_free(p);
		return -1;
	}
	p->seed = (uint64_t)seed;
	return 0;
}
