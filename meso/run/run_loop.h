/* The run driver: build (or restart) the configuration, step, write the periodic outputs, finish
 * with the summary. Used by `mdpore run`. */
#ifndef MESO_RUN_RUN_LOOP_H
#define MESO_RUN_RUN_LOOP_H

#include "scene/scene.h"

#include <mpi.h>

/* Collective. Returns the exit code: 0, or non-zero after a message (engine failure, I/O error). */
int run_scene(const scene_t *scene, MPI_Comm comm);

/* Prefix relative output paths (thermo, profile, snapshot, dump, checkpoint, flux, summary) with
 * `dir`. */
void run_apply_output_dir(scene_t *scene, const char *dir);

#endif
