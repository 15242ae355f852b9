/* Atomic output: write to a temporary file in the target's directory, then rename() over the
 * target, so a reader never sees a half-written file. */
#ifndef MDPORE_UPSCALE_ATOMIC_FILE_H
#define MDPORE_UPSCALE_ATOMIC_FILE_H

#include <stdio.h>

typedef struct {
  FILE *f;
  char final_path[4096];
  char temp_path[4096 + 32];
} atomic_file;

/* Opens PATH.tmp.PID for writing; returns 0 or prints an error naming the path and returns -1. */
int atomic_open(atomic_file *a, const char *path);
/* Closes and renames; on any earlier write error removes the temporary file and returns -1. */
int atomic_commit(atomic_file *a);
/* Fills temp_path for writers (like HDF5) that open files themselves; commit with atomic_rename. */
void atomic_temp_name(atomic_file *a, const char *path);
int atomic_rename(atomic_file *a);

#endif
