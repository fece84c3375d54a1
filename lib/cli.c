#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/cli.h"
#include "lib/err.h"
#include "version.h"

void cli_usage_error(const cli_spec *spec, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	fprintf(stderr, "%s: ", err_program_name());
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	fprintf(stderr, " (usage: %s; see --help)\n", spec->usage);
	exit(2);
}

void cli_check_outputs(const cli_spec *spec, const path_role *out, int nout, const path_role *in,
                       int nin)
{
	if (path_check_outputs(out, nout, in, nin))
		cli_usage_error(spec, "%s", err_msg());
	if (path_check_writable(out, nout))
		fatal(NULL);
}

static void default_text(const cli_opt *o, char *buf, size_t n)
{
	buf[0] = '\0';
	switch (o->kind) {
	case CLI_FLAG:
		break;
	case CLI_INT:
		snprintf(buf, n, " [default: %ld]", *(long *)o->value);
		break;
	case CLI_NUM:
		snprintf(buf, n, " [default: %g]", *(double *)o->value);
		break;
	case CLI_STR:
		if (*(const char **)o->value)
			snprintf(buf, n, " [default: %s]", *(const char **)o->value);
		break;
	}
}

void cli_help(const cli_spec *spec)
{
	printf("Usage: %s\n\n%s\n\nOptions:\n", spec->usage, spec->summary);
	for (int k = 0; k < spec->nopts; k++) {
		const cli_opt *o = &spec->opts[k];
		char left[96], dflt[160], unit[48] = "";
		if (o->kind == CLI_FLAG)
			snprintf(left, sizeof left, "--%s", o->name);
		else
			snprintf(left, sizeof left, "--%s %s", o->name, o->arg ? o->arg : "X");
		if (o->unit && o->unit[0])
			snprintf(unit, sizeof unit, " (%s)", o->unit);
		default_text(o, dflt, sizeof dflt);
		printf("  %-24s %s%s%s\n", left, o->help, unit, dflt);
	}
	printf("  %-24s %s\n  %-24s %s\n", "--help", "show this help and exit", "--version",
	       "show the version and exit");
	if (spec->epilog)
		printf("\n%s\n", spec->epilog);
}

static _Noreturn void bad_value(const cli_opt *o, const char *text, const char *what)
{
	const char *unit = o->unit ? o->unit : "";
	fprintf(stderr, "%s: --%s %s: expected %s in [%g, %g]%s%s%s\n", err_program_name(), o->name,
	        text, what, o->lo, o->hi, unit[0] ? " (" : "", unit, unit[0] ? ")" : "");
	exit(2);
}

static void set_value(const cli_opt *o, const char *text)
{
	char *end;
	errno = 0;
	switch (o->kind) {
	case CLI_FLAG:
		*(int *)o->value = 1;
		return;
	case CLI_STR:
		*(const char **)o->value = text;
		return;
	case CLI_INT: {
		long v = strtol(text, &end, 10);
		if (errno || *end || end == text || v < o->lo || v > o->hi)
			bad_value(o, text, "an integer");
		*(long *)o->value = v;
		return;
	}
	case CLI_NUM: {
		double v = strtod(text, &end);
		if (errno || *end || end == text || !(v >= o->lo && v <= o->hi))
			bad_value(o, text, "a number");
		*(double *)o->value = v;
		return;
	}
	}
}

int cli_parse(const cli_spec *spec, int argc, char **argv, char **pos)
{
	int npos = 0, options_done = 0;
	err_program(argv[0]);
	for (int k = 1; k < argc; k++) {
		const char *a = argv[k];
		if (options_done || a[0] != '-' || strcmp(a, "-") == 0) {
			if (npos >= spec->max_pos)
				cli_usage_error(spec, "unexpected argument '%s'", a);
			pos[npos++] = argv[k];
			continue;
		}
		if (strcmp(a, "--") == 0) {
			options_done = 1;
			continue;
		}
		if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
			cli_help(spec);
			exit(0);
		}
		if (strcmp(a, "--version") == 0) {
			printf("%s %s\n", err_program_name(), DEM_VERSION);
			exit(0);
		}
		const char *name = a + (a[1] == '-' ? 2 : 1);
		const char *eq = strchr(name, '=');
		size_t len = eq ? (size_t)(eq - name) : strlen(name);
		const cli_opt *o = NULL;
		for (int i = 0; i < spec->nopts; i++)
			if (strlen(spec->opts[i].name) == len &&
			    strncmp(spec->opts[i].name, name, len) == 0)
				o = &spec->opts[i];
		if (!o)
			cli_usage_error(spec, "unknown option '%s'", a);
		if (o->kind == CLI_FLAG) {
			if (eq)
				cli_usage_error(spec, "option '--%s' takes no value", o->name);
			set_value(o, NULL);
		} else if (eq) {
			set_value(o, eq + 1);
		} else if (k + 1 < argc) {
			set_value(o, argv[++k]);
		} else {
			cli_usage_error(spec, "option '--%s' needs a value", o->name);
		}
	}
	if (npos < spec->min_pos)
		cli_usage_error(spec, "missing argument%s", spec->min_pos > 1 ? "s" : "");
	return npos;
}
