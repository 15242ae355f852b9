/* The run driver: build (or restart) the configuration, step, write the periodic outputs, finish
 * with the summary. Used by `mdpore run`. */
#ifndef MESO_RUN_RUN_LOOP_H
#define MESO_RUN_RUN_LOOP_H

#include "scene/scene.h"

#include <mpi.h>

/* Collective. Returns the exit code: 0, or non-zero after a message (engine failure, I/O error). */
int run_scene(const scene_t *scene, MPI_Comm comm);

/* Where a run stands, for a watcher in another thread (run_replicas.c; read with atomic loads):
 * the first and last step of the loop once set up, the step just done (last once the loop ended,
 * also after an early stop or a failure), and MPI_Wtime() when the loop started (0 before). */
typedef struct {
  long first, last, step;
  double t_loop;
} run_watch_t;
/* run_scene, keeping *watch up to date (NULL: none). */
int run_scene_watched(const scene_t *scene, MPI_Comm comm, run_watch_t *watch);

/* Prefix relative output paths (thermo, profile, snapshot, dump, checkpoint, flux, summary) with
 * `dir`. */
void run_apply_output_dir(scene_t *scene, const char *dir);

#endif
