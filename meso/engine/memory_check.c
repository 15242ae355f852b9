/* sim_memory_check (sim.h): the memory plan of the largest rank against the memory available on
 * the node, before the particle arrays, lists, image fields and output buffers are allocated. */
#include "common/memory_limit.h"
#include "engine/memory_plan.h"
#include "engine/sim_internal.h"

#include <string.h>

int sim_memory_check(sim_t *sim, memory_inputs_t *in) {
  sim_state_t *st = &sim->st;
  MPI_Comm comm = st->dc.cart;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  /* the largest rank's inputs (each one alone: an upper bound of that rank) */
  double big[8] = {in->owned,
                   in->build_bytes,
                   in->density,
                   in->input_set,
                   in->total,
                   st->dc.hi[0] - st->dc.lo[0],
                   st->dc.hi[1] - st->dc.lo[1],
                   st->dc.hi[2] - st->dc.lo[2]};
  MPI_Allreduce(MPI_IN_PLACE, big, 8, MPI_DOUBLE, MPI_MAX, comm);
  in->owned = big[0];
  in->build_bytes = big[1];
  in->density = big[2];
  in->input_set = big[3];
  in->total = big[4];
  for (int d = 0; d < 3; d++) in->extent[d] = big[5 + d];
  in->backend = st->scene.backend;
  /* the device is checked by the backend at its first upload (its free memory); the host plan
   * counts the host's copies only */
  in->device_bytes_per_particle = 0;
  memory_plan_t mp;
  memory_plan_build(&st->scene, &st->plan, in, &mp);
  /* ranks that share this node's memory; the node with the most ranks and the least memory */
  MPI_Comm node;
  int here = 1;
  if (MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node) == MPI_SUCCESS) {
    MPI_Comm_size(node, &here);
    MPI_Comm_free(&node);
  }
  char from[64];
  double worst[2] = {(double)here, -mdp_memory_available(from, sizeof from)};
  MPI_Allreduce(MPI_IN_PLACE, worst, 2, MPI_DOUBLE, MPI_MAX, comm);
  const double need = mp.total * worst[0], available = -worst[1];
  if (need <= available) return 0;
  if (rank == 0) {
    char largest[512], b_need[32], b_rank[32], b_avail[32];
    memory_plan_largest(&mp, largest, sizeof largest);
    if (in->stage) /* before a build whose particles are not counted yet */
      fprintf(stderr,
              "mdpore: %s: not enough memory for %s: it needs ~%s (%s per rank x %.0f rank(s) on "
              "a node) before any particle is made, but %s are available (%s); largest: %s. Try "
              "a smaller crop of the image or a coarser one (mdpore image convert --crop, "
              "--downsample) or more ranks on more nodes; mdpore run --explain prints the plan\n",
              st->scene.file, in->stage, memory_bytes_text(need, b_need, sizeof b_need),
              memory_bytes_text(mp.total, b_rank, sizeof b_rank), worst[0],
              memory_bytes_text(available, b_avail, sizeof b_avail), from, largest);
    else
      fprintf(
          stderr,
          "mdpore: %s: not enough memory: the run needs ~%s (%s per rank x %.0f rank(s) on a "
          "node; %.4g particles on the largest rank) but %s are available (%s); largest: %s. "
          "Try fewer particles (a coarser geometry.rc_per_voxel, a smaller crop of the image, a "
          "smaller box or fill) or more ranks on more nodes; mdpore run --explain prints the "
          "plan\n",
          st->scene.file, memory_bytes_text(need, b_need, sizeof b_need),
          memory_bytes_text(mp.total, b_rank, sizeof b_rank), worst[0], mp.owned,
          memory_bytes_text(available, b_avail, sizeof b_avail), from, largest);
    memory_plan_print(&mp, stderr);
  }
  return -1;
}
