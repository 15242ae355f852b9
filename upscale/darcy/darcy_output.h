/* Results of `mdpore darcy`: HDF5 fields and a JSON summary, written by rank 0, atomically. */
#ifndef MDPORE_UPSCALE_DARCY_OUTPUT_H
#define MDPORE_UPSCALE_DARCY_OUTPUT_H

#include "darcy_config.h"
#include "darcy_post.h"
#include "darcy_solve.h"

int darcy_write_hdf5(const char *path, const darcy_config *c, const double *pressure,
                     const darcy_post *post);
int darcy_write_json(const char *path, const char *config_path, const darcy_config *c,
                     const double *pressure, const darcy_post *post, const darcy_stats *st,
                     int nranks);

#endif
