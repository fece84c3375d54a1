/* The laws selectable by name from a material file's "law" key, in the
 * order messages list them. A law's file defines `const law law_NAME`;
 * adding a law is adding NAME to this one list. */
#include <stdio.h>
#include <string.h>

#include "lib/err.h"
#include "solve/law.h"

#define LAWS(X) X(linear) X(onate) X(jcfpm) X(exponential)

#define DECLARE(name) extern const law law_##name;
#define ENTRY(name) &law_##name,
LAWS(DECLARE)

static const law *const registry[] = {LAWS(ENTRY) NULL};

const law *const *law_all(void) { return registry; }

law_params *law_params_dup(const law_params *p, size_t size)
{
	void *q = xmalloc(size);
	memcpy(q, p, size);
	return q;
}

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
