/* The laws selectable by name from a material file's "law" key. */
#include <stdio.h>
#include <string.h>

#include "lib/err.h"
#include "solve/law.h"

extern const law law_linear, law_onate, law_jcfpm, law_exponential;

static const law *const registry[] = {&law_linear, &law_onate, &law_jcfpm, &law_exponential, NULL};

const law *const *law_all(void) { return registry; }

const law *law_find(const char *name)
{
	char known[256] = "";
	for (int k = 0; registry[k]; k++) {
		if (strcmp(registry[k]->name, name) == 0)
			return registry[k];
		size_t len = strlen(known);
		snprintf(known + len, sizeof known - len, "%s'%s'", k ? ", " : "",
		         registry[k]->name);
	}
	err_set("unknown law \"%s\": expected one of %s", name, known);
	return NULL;
}
