/* File names written inside other files (a case naming its material, a pack
 * configuration naming its geometry) are relative to the directory of the
 * file that names them, so a case or specimen directory can be moved or used
 * from anywhere. */
#ifndef DEM_PATH_H
#define DEM_PATH_H

/* name as seen from the current directory when it is written in file:
 * absolute names stay; relative ones are joined to file's directory.
 * Returns a new string (caller frees). */
char *path_beside(const char *file, const char *name);

#endif
