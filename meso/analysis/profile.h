/* Time-averaged 1D profiles along one box axis: number density per species, mean velocity of the
 * mobile particles, and the pressure tensor per bin, P_ab(bin) = sum_{i in bin} (m v_a v_b +
 * W_i,ab) / V_bin with W_i the engine's per-particle virial (1/2 sum_j r_ij,a F_ij,b, so the bins
 * add up to the box virial). Error bars come from block averaging: the samples of the run are cut
 * into up to PROFILE_BLOCKS equal blocks and the error is the standard deviation of the block means
 * over sqrt(blocks). */
#ifndef MESO_ANALYSIS_PROFILE_H
#define MESO_ANALYSIS_PROFILE_H

#include "engine/sim.h"

#define PROFILE_BLOCKS 20

typedef struct {
  const scene_t *scene;
  int axis, nbins, nsp, nf;
  double lo, len, vbin;
  long expected, samples, block_len;
  int nblocks;
  double *local;       /* one sample, this rank: nbins x nf                 */
  double *blocks;      /* rank 0: nblocks x nbins x nf sums                  */
  long *block_samples; /* rank 0: samples per block                          */
} profile_t;

/* Set up for samples at steps t in (first_step, last_step], t >= start, t % every == 0. */
int profile_init(profile_t *p, const scene_t *scene, long first_step, long last_step,
                 MPI_Comm comm);
void profile_free(profile_t *p);
/* Is `step` a sample step? */
int profile_wants(const profile_t *p, long step);
/* Collective: bin the current configuration (needs the per-particle virial of this step). */
void profile_sample(profile_t *p, sim_t *sim);
/* Rank 0: write the CSV (atomic). 0 or -1. */
int profile_write(const profile_t *p, const char *path);
/* Rank 0: density of the mobile species in the central plateau (bins above 0.9 of the maximum, 20%
 * trimmed at each end), with its block error. Returns the number of plateau bins used (0: none). */
int profile_plateau_density(const profile_t *p, double *mean, double *err, int *interfaces);

#endif
