/* Error reporting shared by every stage.
 *
 * Library code never prints or exits: it records one message with err_set()
 * and returns -1 (or NULL). Programs print that message with fatal() and exit
 * non-zero. A message names the file, key and value at fault and what was
 * expected, e.g.
 *   cement.json: key 'E0': value -3.8e9: expected a positive number (Pa)
 */
#ifndef DEM_ERR_H
#define DEM_ERR_H

#include <stdarg.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Record the current error (replaces any earlier one; err_msg() may be one
 * of the arguments). Always returns -1. */
int err_set(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Prefix the current error with more context: "<context>: <message>". */
int err_wrap(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* The current error message ("" when none). */
const char *err_msg(void);
void err_clear(void);

/* The program name used by fatal() and warn() (set once from argv[0]). */
void err_program(const char *argv0);
const char *err_program_name(void);

/* A function fatal() calls before it prints (solve's ranks: par.c). */
void err_fatal_hook(void (*hook)(void));
/* Print "<program>: <message>" on stderr and exit with status 1. With fmt ==
 * NULL the current error message is printed; err_msg() may be an argument. */
void fatal(const char *fmt, ...) __attribute__((noreturn, format(printf, 1, 2)));
void warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* malloc/calloc/realloc that exit with a clear message when memory runs out. */
void *xmalloc(size_t n);
void *xcalloc(size_t count, size_t size);
void *xrealloc(void *p, size_t n);
/* n bytes aligned to `align` (a power of two, a multiple of sizeof(void *));
 * released with free. */
void *xaligned(size_t align, size_t n);
char *xstrdup(const char *s);

#ifdef __cplusplus
}
#endif

#endif
