#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lib/err.h"

static _Thread_local char message[2048];
static const char *program = "dem";

/* Formatted into a copy first, so that an argument may be err_msg() itself. */
static void set_message(const char *fmt, va_list ap)
{
	char text[sizeof message];
	vsnprintf(text, sizeof text, fmt, ap);
	memcpy(message, text, sizeof message);
}

int err_set(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	set_message(fmt, ap);
	va_end(ap);
	return -1;
}

int err_wrap(const char *fmt, ...)
{
	char old[sizeof message];
	memcpy(old, message, sizeof old);
	va_list ap;
	va_start(ap, fmt);
	int len = vsnprintf(message, sizeof message, fmt, ap);
	va_end(ap);
	if (len >= 0 && (size_t)len < sizeof message)
		snprintf(message + len, sizeof message - (size_t)len, ": %.*s",
		         (int)(sizeof message - (size_t)len), old);
	return -1;
}

const char *err_msg(void) { return message; }

void err_clear(void) { message[0] = '\0'; }

void err_program(const char *argv0)
{
	const char *slash = strrchr(argv0, '/');
	program = slash ? slash + 1 : argv0;
}

const char *err_program_name(void) { return program; }

static void (*fatal_hook)(void);

void err_fatal_hook(void (*hook)(void)) { fatal_hook = hook; }

_Noreturn void fatal(const char *fmt, ...)
{
	if (fatal_hook)
		fatal_hook();
	fflush(stdout);
	if (fmt) {
		va_list ap;
		va_start(ap, fmt);
		set_message(fmt, ap);
		va_end(ap);
	}
	fprintf(stderr, "%s: %s\n", program, message[0] ? message : "unknown error");
	exit(1);
}

void warn(const char *fmt, ...)
{
	char text[2048];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(text, sizeof text, fmt, ap);
	va_end(ap);
	fprintf(stderr, "%s: warning: %s\n", program, text);
}

static void *check(void *p, size_t n)
{
	if (!p && n)
		fatal("out of memory (allocating %zu bytes)", n);
	return p;
}

void *xmalloc(size_t n) { return check(malloc(n ? n : 1), n); }

void *xcalloc(size_t count, size_t size)
{
	return check(calloc(count ? count : 1, size ? size : 1), count * size);
}

void *xrealloc(void *p, size_t n) { return check(realloc(p, n ? n : 1), n); }

void *xaligned(size_t align, size_t n)
{
	void *p = NULL;
	return check(posix_memalign(&p, align, n ? n : 1) ? NULL : p, n);
}

char *xstrdup(const char *s) { return check(strdup(s), strlen(s) + 1); }
