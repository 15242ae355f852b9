/* Test-only fault injection (see run_fault.h). */
#include "run/run_fault.h"
#include "domain/particle_store.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const kinds[] = {"", "nan_velocity", "nan_position", "jump", "remove"};

int run_fault_init(run_fault_t *f, const sim_t *sim, int rank) {
  memset(f, 0, sizeof *f);
  const char *env = getenv("MDPORE_TEST_FAULT");
  if (!env || !env[0]) return 0;
  char kind[32];
  long step = 0;
  long long id = 0;
  char extra;
  if (sscanf(env, "%31[a-z_]:%ld:%lld%c", kind, &step, &id, &extra) == 3 && step >= 1 && id >= 1)
    for (int k = RUN_FAULT_NAN_VELOCITY; k <= RUN_FAULT_REMOVE; k++)
      if (!strcmp(kind, kinds[k])) f->kind = k;
  if (f->kind == RUN_FAULT_NONE) {
    if (rank == 0)
      fprintf(stderr,
              "mdpore: MDPORE_TEST_FAULT='%s': expected KIND:STEP:ID with KIND nan_velocity, "
              "nan_position, jump or remove, STEP >= 1, ID >= 1 (a test-only fault; unset it "
              "for a real run)\n",
              env);
    return -1;
  }
  /* The CUDA backend keeps the particles on the GPU between steps: the value faults are one
   * device write (sim_fault_write); removing a particle from the device arrays is not offered. */
  if (f->kind == RUN_FAULT_REMOVE && strcmp(sim_backend_name(sim), "cpu")) {
    if (rank == 0)
      fprintf(stderr,
              "mdpore: MDPORE_TEST_FAULT=remove works on the cpu backend only (this run: %s; "
              "nan_velocity, nan_position and jump work on both)\n",
              sim_backend_name(sim));
    return -1;
  }
  f->step = step;
  f->id = (int64_t)id;
  if (rank == 0)
    fprintf(stderr, "mdpore: MDPORE_TEST_FAULT: %s of particle %lld before step %ld (test only)\n",
            kinds[f->kind], id, step);
  return 0;
}

int run_fault_apply(const run_fault_t *f, sim_t *sim) {
  const scene_t *s = sim_scene(sim);
  switch (f->kind) {
  case RUN_FAULT_NAN_VELOCITY:
    return sim_fault_write(sim, f->id, 1, 0, NAN, 0);
  case RUN_FAULT_NAN_POSITION:
    return sim_fault_write(sim, f->id, 0, 0, NAN, 0);
  case RUN_FAULT_JUMP: /* beyond the periodic wrap of one box length, on any decomposition */
    return sim_fault_write(sim, f->id, 0, 0, 3.0 * (s->box_hi[0] - s->box_lo[0]), 1);
  case RUN_FAULT_REMOVE: { /* cpu backend only (run_fault_init) */
    particles_t *p = sim_particles(sim);
    for (int i = 0; i < p->n_local; i++)
      if (p->id[i] == f->id) {
        pstore_copy(p, i, p->n_local - 1);
        p->n_local--;
        break;
      }
    return 0;
  }
  }
  return 0;
}
