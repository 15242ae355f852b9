/* A per-block permeability dataset of an HDF5 file (laws.hdf5 of the `mdpore darcy` config):
 * its `unit` attribute (or the config's laws.hdf5.unit), its shape against the grid, and the
 * optional `axis_order` attribute that names the axes of its dimensions, slowest first ("zyx", the
 * default, is C order with x fastest; "xyz" is a dataset stored x slowest, which is transposed). */
#ifndef MDPORE_UPSCALE_DARCY_K_DATASET_H
#define MDPORE_UPSCALE_DARCY_K_DATASET_H

#include <stddef.h>

#include "darcy_problem.h"

typedef enum { KSET_KEY_FILE = 0, KSET_KEY_DATASET, KSET_KEY_UNIT } kset_key;

/* Reads dataset `dset` of `file` into k (one value per block, x fastest, in the base permeability
 * unit of the system: m^2 when si, rc^2 otherwise). config_unit: the unit the config states ("" if
 * none). Under SI a dataset without a `unit` attribute is refused unless config_unit is given; a
 * config unit that contradicts the attribute is refused. Returns 0, or -1 with "expected ... (got
 * ...)" in msg and the config key it belongs to in *key. */
int darcy_k_dataset_read(const char *file, const char *dset, const darcy_problem *p, int si,
                         const char *config_unit, double *k, char *msg, size_t len, kset_key *key);

#endif
