/* Atomic output files: a program writes "<name>.tmp", and only when the file
 * is complete does afile_commit() fsync it and rename it to its final name.
 * A crashed or interrupted program therefore never leaves a file that looks
 * finished. Temporary names are registered so that the signals that end a
 * program (afile_signals) and a fatal() exit remove them. */
#ifndef DEM_AFILE_H
#define DEM_AFILE_H

#include <stddef.h>

/* Fill tmp (of size n) with the temporary name for final and register it
 * for removal at exit or on a signal. Returns 0, or -1 if the name is too
 * long. */
int afile_begin(const char *final, char *tmp, size_t n);
/* As afile_begin for a file that the processes of an MPI run write
 * together: the name is checked for another program's claim, but not held
 * (a whole-file lock held by one process could stall the MPI-IO layer's
 * own locks on a network file system). */
int afile_begin_shared(const char *final, char *tmp, size_t n);
/* Whether another program is writing final now: its temporary claimed
 * (only where the file system has flock; on NFS, and on Lustre without
 * its flock option, the claim is best effort). */
int afile_held(const char *final);
/* 0, or -1 with the message that afile_begin would give when another
 * program is writing final. */
int afile_check_free(const char *final);
/* fsync tmp, rename it to final and fsync the directory; unregisters tmp. */
int afile_commit(const char *tmp, const char *final);
/* fsync a directory, so that the renames in it are on disk (errors
 * ignored: a file system may not sync directories). */
void afile_sync_dir(const char *dir);
/* Remove tmp and unregister it. */
void afile_discard(const char *tmp);
/* The signals that ask a program to end: Ctrl-C, a closed terminal or a
 * dropped ssh connection, and those batch schedulers send before their
 * kill (SIGTERM; SIGUSR1, SIGUSR2 or SIGXCPU where configured). */
enum { AFILE_NSIGNALS = 6 };
extern const int afile_signals[AFILE_NSIGNALS];
/* Register dir, a directory of files staged to be moved in together (post
 * vtk's series), for removal with its files at exit or on a signal, as the
 * temporaries; NULL unregisters it (once it is moved in). One at a time.
 * Returns 0, or -1 if the name is too long. */
int afile_stage_dir(const char *dir);
/* Install handlers for afile_signals that remove pending temporaries and
 * then die of the same signal. Programs call this once at start. */
void afile_install_signal_cleanup(void);

#endif
