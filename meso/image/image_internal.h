/* Helpers shared by the image module's files (not part of the public API). */
#ifndef MDPORE_IMAGE_INTERNAL_H
#define MDPORE_IMAGE_INTERNAL_H

#include <stddef.h>

/* Temporary name in the same folder as path, for write-then-rename. */
void mdp_image_tmp_path(const char *path, char *tmp, size_t len);
/* rename(tmp, path); on failure removes tmp and writes err. */
int mdp_image_commit(const char *tmp, const char *path, char *err);
/* Parse "NXxNYxNZ", "NX,NY,NZ" or "NX NY NZ". */
int mdp_image_parse_dims(const char *text, int dims[3]);

/* Prefix err with "PATH: key 'KEY': " (a message of a helper that does not know the file). */
void mdp_image_err_prefix(char *err, const char *path, const char *key);
/* 0 when `bytes` fit under mdp_memory_limit() (common/memory_limit.h); else err = "PATH: WHAT needs N GB of memory, more than ..." and
 * 1. `what` names the key or header value the size comes from. */
int mdp_image_check_memory(double bytes, const char *path, const char *what, char *err);

#endif
