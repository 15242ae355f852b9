/* Whether two paths name one file: the same device and inode when both exist, else the same
 * canonical path (realpath of the folder + the name) for one not written yet. Commands check their
 * outputs against their inputs and against each other before writing anything. */
#ifndef COMMON_SAME_FILE_H
#define COMMON_SAME_FILE_H

#include <stddef.h>

/* 1 when a and b name the same file (existing or to be created), else 0. */
int mdp_same_file(const char *a, const char *b);

/* 0 when none of the n outputs names one of the n_in inputs or another output; else -1 and `msg`
 * (len bytes) "OUTPUT_ROLE 'path' would overwrite INPUT_ROLE 'path'". Roles name the option or key
 * ("--json", "output.summary", "the table"). */
int mdp_check_outputs(const char *const *outputs, const char *const *output_roles, int n,
                      const char *const *inputs, const char *const *input_roles, int n_in,
                      char *msg, size_t len);

#endif
