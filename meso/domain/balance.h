/* Load balancing by cost (docs/scene-format.md "Load balancing"): the cuts of the Cartesian grid
 * placed so that every slab along an axis carries the same share of the cost. The cost of a
 * particle is its weight (1 for a mobile particle, balance.frozen_weight for a frozen wall
 * particle, which is never integrated and meets no wall-wall pairs) times the seconds per unit
 * weight its rank measured (1 before anything was measured). The grid is a tensor product of
 * per-axis cuts, so each axis is balanced on its marginal cost: exact when the cost varies along
 * one axis (a layered or half-solid sample cut along its layering), approximate otherwise. */
#ifndef MESO_DOMAIN_BALANCE_H
#define MESO_DOMAIN_BALANCE_H

#include "decomp.h"
#include "particles.h"

#include <stddef.h>

/* Histogram bins along axis d: about 16 per rcut, at least 8 per slab, at most 65536. */
int balance_nbins(const decomp_t *dc, int d);

/* Add this rank's owned particles to hist[d][0..nbins(d)) (the caller zeroes and reduces): weight
 * frozen_weight for species with is_frozen[species], 1 otherwise, times scale. */
void balance_histogram_add(const decomp_t *dc, const particles_t *p, const int *is_frozen,
                           double frozen_weight, double scale, double *const hist[3]);

/* Cuts for m slabs of [lo, hi) over nb equal bins of cost w: cut k at cost fraction k / m (linear
 * inside a bin), then pushed apart to at least min_width (forward, then backward). cuts[0] = lo,
 * cuts[m] = hi. 0, or -1 when m slabs of min_width do not fit. */
int balance_cuts_1d(const double *w, int nb, double lo, double hi, int m, double min_width,
                    double *cuts);

/* max / mean of the m slab costs of cuts over the histogram w (the imbalance the cost model
 * predicts along one axis; slabs cut inside a bin share it linearly). */
double balance_slab_imbalance(const double *w, int nb, double lo, double hi, int m,
                              const double *cuts);

#endif
