/* Whole output files are written atomically: into a temporary file in the same directory, then
 * rename()d over the target, so a reader never sees a half-written file (and a crash keeps the old
 * one). */
#ifndef MDPORE_COMMON_ATOMIC_FILE_H
#define MDPORE_COMMON_ATOMIC_FILE_H

#include <stddef.h>
#include <stdio.h>

/* The temporary name used for `path`: "<path>.tmp.<pid>". */
void atomic_tmp_name(const char *path, char *tmp, size_t len);
/* Open the temporary file for writing (text or binary). NULL + message on failure. */
FILE *atomic_open(const char *path, char *tmp, size_t len);
/* Flush, close and rename the temporary over `path`. 0, or -1 with a message (the temp is removed).
 */
int atomic_commit(FILE *fp, const char *tmp, const char *path);
/* Rename a finished temporary (e.g. an HDF5 file closed by the library) over `path`. */
int atomic_rename(const char *tmp, const char *path);
/* Write text as the whole file at path, atomically. 0, or -1 with a message. */
int atomic_write_text(const char *path, const char *text);
/* Create a directory and its parents (mkdir -p). 0 or -1 with a message. */
int make_dirs(const char *dir);

#endif
