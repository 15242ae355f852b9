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

#endif
