/* `mdpore run --replicas SCENE...`: several independent one-rank runs stepped at once in this
 * process, one host thread each (docs/engine-cuda.md, "Replicas"). */
#ifndef MESO_RUN_RUN_REPLICAS_H
#define MESO_RUN_RUN_REPLICAS_H

#include "scene/scene.h"

/* Prepares n loaded scenes as replicas: each one's relative output paths are put in the folder of
 * its scene file (as `mdpore run --output-dir DIR DIR/scene.yaml` would), its own progress line is
 * off (this driver prints one for all). 0, or -1 after a message naming the two scenes when two
 * replicas would write the same output file. */
int run_replicas_prepare(scene_t *scenes, int n);

/* Runs the n prepared scenes at once, each on its own duplicate of MPI_COMM_SELF in its own thread
 * (MPI must be initialised with MPI_THREAD_MULTIPLE), each with omp_threads OpenMP threads (0:
 * leave OpenMP's default). A replica that fails does not stop the others. Returns 0 when all
 * finished, else 1 after a line per failed replica naming its scene. */
int run_replicas(scene_t *scenes, int n, int omp_threads);

/* The OpenMP threads of each of n replicas: OMP_NUM_THREADS when set (each replica that many),
 * else the cores this process may use divided among them (at least 1). */
int run_replicas_omp_threads(int n);

#endif
