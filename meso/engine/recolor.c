/* sim_recolor (sim.h): flooding's change of species in a slab, on the backend's particles. */
#include "engine/sim_internal.h"
#include "physics/periodic_slab.h"

#include <math.h>

int sim_recolor(sim_t *sim, int axis, double lo, double hi, int from, int to, long *changed) {
  sim_state_t *st = &sim->st;
  long local = 0;
  int bad = 0;
  if (sim->ops->recolor) {
    bad = sim->ops->recolor(st, axis, lo, hi, from, to, &local) != 0; /* message printed */
  } else {
    particles_t *p = &st->p;
    const double box_lo = st->scene.box_lo[axis], box_len = st->scene.box_hi[axis] - box_lo;
    for (int i = 0; i < p->n_local; i++) {
      if (p->species[i] != from || !periodic_in_slab(p->x[axis][i], lo, hi, box_lo, box_len))
        continue;
      p->species[i] = to;
      local++;
    }
  }
  long in[2] = {local, bad}, out[2];
  MPI_Allreduce(in, out, 2, MPI_LONG, MPI_SUM, st->dc.cart);
  *changed = out[0];
  return out[1] ? -1 : 0;
}
