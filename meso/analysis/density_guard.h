/* Density collapse / cavitation guard: every guard.density_every steps the
 * mobile particles are counted on a coarse grid of bins (edge about guard.density_bin rc). A bin is
 * watched when it is mostly pore (at least half of its voxels pore with a geometry image; every bin
 * without one), held fluid at the first check (density at least guard.density_fraction of the mean)
 * and is expected to hold at least DENSITY_GUARD_MIN_COUNT particles. The run stops when a watched
 * bin's density falls below guard.density_fraction x the mean fluid density of the first check,
 * naming the bin's region, its density and the step. Off (guard.density_every = 0): nothing is
 * allocated or run. On: one pass over the local particles and one MPI_Allreduce of the bin counts
 * per check. */
#ifndef MESO_ANALYSIS_DENSITY_GUARD_H
#define MESO_ANALYSIS_DENSITY_GUARD_H

#include "analysis/penetration.h"
#include "engine/sim.h"

#include <stddef.h>

#define DENSITY_GUARD_MIN_COUNT 10.0

typedef struct {
  int on;
  long every;
  double fraction;
  int n[3];           /* bins per axis */
  double lo[3], h[3]; /* box corner, bin edges */
  long nbins;
  double *pore;    /* per bin: pore volume (rc^3) */
  long *count;     /* per bin: mobile particles (this check, summed over ranks) */
  double *ref;     /* per bin: density at the first check; < 0: not watched */
  double mean_ref; /* mean fluid density of the first check (watched bins) */
  long watched;    /* bins watched */
  int have_ref;
  long checks;    /* checks run */
  double seconds; /* time spent in them (this rank) */
} density_guard_t;

/* Collective. The pore volume of each bin from the geometry's voxels (map may be off: all pore).
 * 0, or -1 out of memory (message printed). */
int density_guard_init(density_guard_t *g, sim_t *sim, const penetration_map_t *map);
/* Is `step` a check step? */
int density_guard_due(const density_guard_t *g, long step);
/* Collective, at a check step: 1 to stop (message in msg, identical on every rank), 0 to go on. */
int density_guard_check(density_guard_t *g, sim_t *sim, long step, char *msg, size_t len);
void density_guard_free(density_guard_t *g);

#endif
