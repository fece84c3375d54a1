/* A byte copy of a file, made by the kernel where it can. */
#ifndef DEM_FCOPY_H
#define DEM_FCOPY_H

/* Copy the bytes of file from into file to (created, or truncated): by
 * copy_file_range(2), which copies inside the kernel (and shares the
 * blocks where the file system can), and by read and write where it
 * cannot (another file system, a kernel or file system without it, a file
 * that is not a regular one) and for whatever it leaves. Returns 0, or -1
 * with a message naming the file at fault. */
int fcopy(const char *from, const char *to);

#endif
