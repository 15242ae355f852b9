/* Results of `mdpore darcy`: HDF5 fields and a JSON summary, written by rank 0, atomically. */
#ifndef MDPORE_UPSCALE_DARCY_OUTPUT_H
#define MDPORE_UPSCALE_DARCY_OUTPUT_H

#include "darcy_config.h"
#include "darcy_post.h"
#include "darcy_solve.h"
#include "darcy_upscale.h"

int darcy_write_hdf5(const char *path, const darcy_config *c, const double *pressure,
                     const darcy_post *post);
int darcy_write_json(const char *path, const char *config_path, const darcy_config *c,
                     const double *pressure, const darcy_post *post, const darcy_stats *st,
                     int nranks);

/* `mdpore darcy --upscale`: the tensors of each family (JSON: m^2 and mD under SI; HDF5: one
 * dataset per family with a `unit` attribute). */
int darcy_write_upscale_json(const char *path, const char *config_path, const darcy_config *c,
                             const darcy_upscale_result *r, int nranks);
int darcy_write_upscale_hdf5(const char *path, const darcy_config *c,
                             const darcy_upscale_result *r);

#endif
