/* The flood in the run loop (scene `flood:`, docs/twophase.md "Flooding"): at flood.start the
 * defending liquid on the injection side (from the sink round to the sample's inlet) becomes the
 * invading one, after every later step the defending particles in the sink do (sim_recolor); a
 * census every flood.every steps (analysis/flood.h) into the series, profiles and maps
 * (io/flood_log.h); the summary's flood lines. Without a flood block nothing here runs. */
#ifndef MESO_RUN_RUN_FLOOD_H
#define MESO_RUN_RUN_FLOOD_H

#include "analysis/flood.h"
#include "io/flood_log.h"

#include <stdio.h>

typedef struct run_flood {
  int on;
  flood_t f;
  flood_log_t log;
  long recolored; /* defending particles turned invading so far */
  int rank;
} run_flood_t;

/* Collective: set-up, files, and the first step's recolouring (start = first) and census. 0, or
 * -1 after a message. */
int run_flood_open(run_flood_t *r, sim_t *sim, long first, int rank);
/* Collective, after the step that reached `step`: recolouring, census and map when due. 0 or -1. */
int run_flood_step(run_flood_t *r, sim_t *sim, long step);
/* Rank 0: the summary's lines and its "flood" JSON object (with a trailing comma). */
void run_flood_text(FILE *out, const run_flood_t *r, const scene_t *s);
void run_flood_json(FILE *fp, const run_flood_t *r, const scene_t *s);
void run_flood_close(run_flood_t *r);

#endif
