/* The device side of the plan's phases (effects/plan.h), driven by the host glue
 * (cuda_glue.c on one rank, cuda_glue_halo.c on several). One rank: kick + drift + constraints +
 * periodic wrap in one kernel, cell sort, prediction, pack + neighbour scan with the densities,
 * force pass, particle forces + second kick in the finishing kernel; one copy of the problem
 * record per step. */
#include "cuda_state.cuh"

/* Launch errors of the step, then the problem record (this synchronises with the step). */
extern "C" int cuda_sim_fetch_problems(cuda_sim_t *g, cuda_problem_t *pr) {
  if (cuda_check(cudaGetLastError(), "step kernels")) return -1;
  return cuda_problem_fetch(g, pr);
}

extern "C" int cuda_sim_kick_drift(cuda_sim_t *g, int want_virial) {
  if (cuda_set_virial(g, want_virial)) return -1;
  g->n_steps++;
  cuda_kick_drift(g);
  return 0;
}

/* Set-up: sort by cell (with the forces when they were loaded from a checkpoint). A step: the sort
 * waits for the neighbour phase, after the prediction, since it does not carry the forces that the
 * prediction reads; with a skin that phase may keep the lists and skip it. */
extern "C" int cuda_sim_sort(cuda_sim_t *g, int setup, int keep_forces, int want_virial) {
  if (setup) return cuda_set_virial(g, want_virial) || cuda_sort_cells(g, keep_forces, 0) ? -1 : 0;
  g->lists_maybe_valid = g->prm.skin > 0.0 && g->lists_valid;
  g->sort_pending = 1;
  return 0;
}

extern "C" int cuda_sim_predict(cuda_sim_t *g, int setup) {
  cuda_predict(g, setup);
  return 0;
}

/* Packed positions and densities of this step. With a skin the lists of the last build serve
 * until a particle has moved more than skin / 2; then (and always without a skin) the particles are
 * sorted by cell again and the bin scan builds new lists (with the densities). */
extern "C" int cuda_sim_neighbours(cuda_sim_t *g) {
  const int sort = g->sort_pending;
  g->sort_pending = 0;
  if (g->lists_maybe_valid) {
    g->lists_maybe_valid = 0;
    const int r = cuda_pack_check(g);
    if (r < 0) return -1;
    if (r == 0) {
      cuda_density_from_lists(g);
      cuda_wall_field(g);
      return 0;
    }
  }
  if (sort) {
    if (cuda_sort_cells(g, 0, 1)) return -1; /* the force pass rewrites f; packed by the sort */
  } else {
    cuda_pack(g);
  }
  if (cuda_density_pass(g)) return -1;
  cuda_wall_field(g);
  return 0;
}

extern "C" int cuda_sim_pair_forces(cuda_sim_t *g, long step, int want_virial, int keep_forces,
                                    int finish) {
  cuda_force_pass(g, (uint64_t)step, want_virial, keep_forces, finish);
  return 0;
}

/* Particle forces of the named effects (add_particle), finite check of f, second half kick. */
extern "C" int cuda_sim_finish(cuda_sim_t *g, int add_particle, int kick) {
  cuda_finish_forces(g, add_particle, kick);
  return 0;
}

extern "C" void cuda_sim_rebuild_lists(cuda_sim_t *g) {
  g->lists_valid = 0;
}

extern "C" void cuda_sim_list_stats(const cuda_sim_t *g, long *builds, long *steps, double *skin) {
  *builds = g->n_builds;
  *steps = g->n_steps;
  *skin = g->prm.skin;
}

/* Pieces of the step for several ranks (cuda_glue_halo.c drives them around the host exchanges). */
extern "C" int cuda_halo_kick_drift(cuda_sim_t *g) {
  cuda_kick_drift(g);
  return cuda_check(cudaGetLastError(), "kick-drift");
}

extern "C" int cuda_halo_predict(cuda_sim_t *g, int setup) {
  cuda_predict(g, setup);
  return cuda_check(cudaGetLastError(), "prediction");
}

/* Overlap (several ranks): after cuda_halo_boundary the key array flags each owned slot, 0 for
 * the boundary set and 1 for the interior, whose partners are all owned. The interior halves of the
 * density and force passes are launched before the host exchanges (kernel launches return at once,
 * so the GPU computes while the host builds ghosts or syncs densities); the boundary halves follow
 * when the ghosts or their densities are on the device. Each slot is computed once, by the same
 * code, so the results are those of the one-part passes. */
extern "C" int cuda_halo_density_early(cuda_sim_t *g) {
  g->split_passes = g->overlap && g->n > 0;
  if (!g->split_passes) return 0;
  cuda_pack_range(g, 0, g->n);
  if (cuda_density_pass_interior(g)) return -1;
  return cuda_check(cudaGetLastError(), "interior densities");
}

extern "C" int cuda_halo_density(cuda_sim_t *g) {
  int rc;
  if (!g->split_passes) {
    cuda_pack(g);
    rc = cuda_density_pass(g);
  } else {
    cuda_pack_range(g, g->n, g->n + g->n_ghost);
    rc = cuda_density_pass_rest(g);
  }
  if (!rc) cuda_wall_field(g); /* every list is complete here, before any force launch */
  return rc;
}

extern "C" int cuda_halo_forces_early(cuda_sim_t *g, long step, int want_virial, int keep_forces) {
  if (!g->split_passes) return 0;
  if (cuda_set_virial(g, want_virial)) return -1;
  /* (the density passes stored the owned densities in vel.pad already) */
  cuda_force_pass_part(g, (uint64_t)step, want_virial, keep_forces, 1, 0);
  return cuda_check(cudaGetLastError(), "interior forces");
}

/* Joins the copy stream into the default stream (its ghost densities, or boundary forces). */
static int join_copies(cuda_sim_t *g) {
  return cuda_check(cudaEventRecord(g->copied, g->copies), "density halo") ||
                 cuda_check(cudaStreamWaitEvent(0, g->copied, 0), "density halo")
             ? -1
             : 0;
}

extern "C" int cuda_halo_forces(cuda_sim_t *g, long step, int want_virial, int keep_forces) {
  if (cuda_set_virial(g, want_virial)) return -1;
  /* The ghost densities were put on the copy stream (cuda_halo_rho_unpack): the boundary forces
   * follow them there, concurrent with the interior forces on the default stream, which then
   * waits for both before the finishing kernel. Otherwise (no room for the boundary part's own
   * virial rows, one-part passes, the host halo path) the default stream waits first. */
  const int concurrent = g->split_passes && g->rho_on_copies && cuda_force_boundary_rows_fit(g);
  if (g->rho_on_copies && !concurrent && join_copies(g)) return -1;
  g->rho_on_copies = 0;
  if (g->split_passes) {
    const cudaStream_t s = concurrent ? g->copies : 0;
    if (g->prm.terms & PAIR_TERM_THERMOSTAT) cuda_rho_to_vel(g, g->n, g->n + g->n_ghost, s);
    cuda_force_pass_part(g, (uint64_t)step, want_virial, keep_forces, 0, s);
    if (concurrent && join_copies(g)) return -1;
  } else {
    cuda_force_pass(g, (uint64_t)step, want_virial, keep_forces, 0);
  }
  g->split_passes = 0;
  return cuda_check(cudaGetLastError(), "forces");
}
