/* The flood's files (scene `flood:`; analysis/flood.h has the definitions), written by rank 0:
 * - the series (flood.file, CSV, '#' lines state the definitions), one row per census:
 *   step, time, S_inv, S_def, N_inv, N_def, q_inv, q_def, recovery, pvi, front, recolored,
 *   N_inv_box, N_def_box;
 * - the saturation profiles (flood.profile, CSV): step, then S_inv of every bin across the sample;
 * - the saturation maps (flood.maps): PATH_<step>.h5 with the invading and defending number
 *   densities and the invading saturation on a grid of cells over the whole box (NaN where a cell
 *   holds no liquid), and PATH.xdmf, a temporal collection of them for ParaView. Each map file
 *   and the XDMF index are written atomically. */
#ifndef MESO_IO_FLOOD_LOG_H
#define MESO_IO_FLOOD_LOG_H

#include "analysis/flood.h"

#include <stdio.h>

typedef struct {
  int active; /* rank 0 and a flood block */
  FILE *series, *profile;
  /* the maps written so far (their steps and times, for the XDMF index) */
  int n_maps, cap_maps;
  long *map_steps;
  double *map_times;
  int cells[3];
  double cell[3];
} flood_log_t;

/* Rank 0 creates the files (`rank` other than 0: nothing). 0 or -1 + message. */
int flood_log_open(flood_log_t *log, const scene_t *s, const flood_t *f, int rank);
/* One census row (and the profile row), flushed. `recolored`: particles changed so far. */
void flood_log_row(flood_log_t *log, const flood_t *f, long recolored);
/* Collective: a saturation map of the current particles. 0 or -1 (message printed). */
int flood_log_map(flood_log_t *log, const scene_t *s, const flood_t *f, sim_t *sim, int rank);
void flood_log_close(flood_log_t *log);

#endif
