/* File names. Those written inside other files (a case naming its
 * material, a pack configuration naming its geometry) are relative to the
 * directory of the file that names them, so a case or specimen directory
 * can be moved or used from anywhere. The outputs a program is asked for
 * are checked before any work: none may overwrite an input or another
 * output, and each must be writable. */
#ifndef DEM_PATH_H
#define DEM_PATH_H

/* name as seen from the current directory when it is written in file:
 * absolute names stay; relative ones are joined to file's directory.
 * Returns a new string (caller frees). */
char *path_beside(const char *file, const char *name);

/* name as an absolute path: resolved (symbolic links, "..") when it
 * exists, else joined to the current directory. A new string. */
char *path_absolute(const char *name);

/* name as a shell word, to paste into a command: as it is when it needs
 * no quoting, else in single quotes. A new string. */
char *path_shell_word(const char *name);

/* Whether a and b name the same file: the same inode when both exist, else
 * the same name once the directory part is resolved. */
int path_same(const char *a, const char *b);

/* A file a program reads or writes, with what the user calls it
 * ("--output", "the assembly"); path may be NULL (not given). */
typedef struct {
	const char *role;
	const char *path;
} path_role;

/* Refuses (-1, with "<role> <path> would overwrite <role> <path>: ...")
 * an output that is the same file as an input or as another output, and
 * an output name that is empty or an existing directory. */
int path_check_outputs(const path_role *out, int nout, const path_role *in, int nin);
/* Refuses (-1) an output in a directory that cannot be written. */
int path_check_writable(const path_role *out, int nout);

#endif
