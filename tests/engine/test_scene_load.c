/* Parse scene files and report: exit 0 when every file given parses and validates, 1 otherwise.
 * Used by the tests that every scene in cases/ loads and that bad scenes fail with a clear message.
 */
#include "common/mpi_singleton.h"
#include "effects/plan.h"
#include "effects/scene_load.h"
#include "scene/scene.h"

#include <mpi.h>
#include <stdio.h>

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  int bad = 0;
  for (int i = 1; i < argc; i++) {
    scene_t s;
    if (scene_load(argv[i], &s)) {
      bad = 1;
      continue;
    }
    plan_t plan;
    char err[1024];
    if (plan_build(&plan, &s, err, sizeof err)) {
      fprintf(stderr, "%s\n", err);
      bad = 1;
      continue;
    }
    printf("%s: '%s' %d species, %ld steps, box %g x %g x %g, cutoff %g, %d phases a step\n",
           argv[i], s.name, s.n_species, s.steps, s.box_hi[0] - s.box_lo[0],
           s.box_hi[1] - s.box_lo[1], s.box_hi[2] - s.box_lo[2], plan.rcut, plan.n_step);
  }
  MPI_Finalize();
  return argc < 2 ? 2 : bad;
}
