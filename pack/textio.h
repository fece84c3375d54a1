/* Plain sphere lists, one sphere per line "x y z r" (m), as Yade's
 * export.text / ymport.text and many other codes write and read them, so
 * an assembly can be compared across codes. Lines starting with '#' and
 * blank lines are ignored on reading. */
#ifndef PACK_TEXTIO_H
#define PACK_TEXTIO_H

#include <stddef.h>

/* Written atomically (a "<path>.tmp" renamed when complete), with a
 * "#format x_y_z_r" header and every number to 17 significant digits, so
 * that reading it back gives the same doubles. */
int textio_write(const char *path, const double *x, const double *r, size_t n);
/* Allocates *x ([n][3]) and *r. */
int textio_read(const char *path, double **x, double **r, size_t *n);

#endif
