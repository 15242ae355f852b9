/* The end of one particle's step on the device, shared by the finishing kernel (cuda_integrate.cu
 * k_finish) and the force pass, whose thread holds the particle's whole pair force when it ends
 * (cuda_force.cu: one rank, a step, so the finishing kernel's second read and write of f, v and x
 * is saved): the particle forces of the named effects (effects/effect_list.h), the finiteness of
 * f, and the second half kick v += dt/2 f/m of a mobile particle (physics/verlet.h), all in double
 * as the CPU path computes them. */
#ifndef MESO_BACKEND_CUDA_FINISH_CUH
#define MESO_BACKEND_CUDA_FINISH_CUH

#include "cuda_state.cuh"
#include "physics/verlet.h"

/* f: slot i's force so far, completed here (add_particle: the particle forces added); the caller
 * stores it. kick: the second half kick of a mobile species. */
__device__ __forceinline__ void dev_finish_particle(const struct dev_params &q,
                                                    const struct dev_fields &p,
                                                    struct dev_problem *pb, int i, int s,
                                                    double f[3], int add_particle, int kick) {
  if (add_particle && q.particle_forces) {
    const double x[3] = {p.x[0][i], p.x[1][i], p.x[2][i]};
    particle_effects_force(&q.pe, s, x, f);
  }
  if (!isfinite(f[0] + f[1] + f[2]))
    dev_note(pb, CUDA_NONFINITE, 0, p.id[i], p.x[0][i], p.x[1][i], p.x[2][i], 0.0);
  if (!kick || !q.mobile[s]) return;
  double v[3] = {p.v[0][i], p.v[1][i], p.v[2][i]};
  verlet_kick(v, f, q.half_dt, q.inv_mass[s]);
  for (int d = 0; d < 3; d++) p.v[d][i] = v[d];
}

#endif
