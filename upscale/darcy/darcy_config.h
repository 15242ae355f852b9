/* `mdpore darcy` configuration file (YAML, documented in docs/darcy-config.md) -> darcy_problem. */
#ifndef MDPORE_UPSCALE_DARCY_CONFIG_H
#define MDPORE_UPSCALE_DARCY_CONFIG_H

#include "darcy_problem.h"
#include "twophase_config.h"

typedef struct {
  darcy_problem problem;
  int si;                /* unit system: 1 SI, 0 reduced */
  double g_lin_fraction; /* power laws linear below this fraction of the characteristic gradient */
  char hdf5_path[4096];  /* output files (empty: not written) */
  char json_path[4096];
  int json_blocks; /* write per-block results into the JSON (default: when <= 10000 blocks) */
  int upscale;     /* permeability tensor: bit f for family f of darcy_upscale.h; 0: one solve */
  twophase_config twophase; /* water/oil displacement instead of one steady solve (enabled) */
} darcy_config;

/* Reads and validates the file; laws that reference fit JSON or HDF5 files are resolved relative to
 * the config file's folder. Returns 0, or -1 after printing "FILE:LINE:COL: key 'a.b': expected ...
 * (got ...)" to stderr (nothing printed when quiet, e.g. on ranks other than 0). */
int darcy_config_read(const char *path, darcy_config *c, int quiet);
/* The same for `mdpore darcy --upscale`: `boundary` may be left out (the upscaling families set the
 * conditions) and, when no `upscale` key says otherwise, all three families are computed. */
int darcy_config_read_upscale(const char *path, darcy_config *c, int quiet);

#endif
