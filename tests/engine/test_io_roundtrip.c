/* Round trips through the file formats: a particle set written as a LAMMPS data file and as an HDF5
 * snapshot reads back identically (ids, species, positions, velocities to the last bit); a data
 * file whose atom type has no species is rejected with a message naming the file and line. */
#include "common/mpi_singleton.h"
#include "populate/lammps_data.h"
#include "io/snapshot.h"

#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include "test_io_check.h"

static int same(const particle_set_t *a, const particle_set_t *b) {
  if (a->n != b->n) return 0;
  for (long i = 0; i < a->n; i++) {
    if (a->id[i] != b->id[i] || a->species[i] != b->species[i]) return 0;
    for (int d = 0; d < 3; d++)
      if (a->x[3 * i + d] != b->x[3 * i + d] || a->v[3 * i + d] != b->v[3 * i + d]) return 0;
  }
  return 1;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  scene_t s;
  memset(&s, 0, sizeof s);
  strcpy(s.name, "roundtrip");
  s.n_species = 2;
  strcpy(s.species[0].name, "liquid");
  strcpy(s.species[1].name, "wall");
  s.species[0].mass = s.species[1].mass = 1.0;
  for (int d = 0; d < 3; d++) s.box_hi[d] = 3.0 + d;
  particle_set_t set, back;
  const long n = 257;
  particle_set_alloc(&set, n, 0, 1);
  for (long i = 0; i < n; i++) {
    set.id[i] = 1000 + 7 * i;
    set.species[i] = (int)(i % 2);
    for (int d = 0; d < 3; d++) {
      set.x[3 * i + d] = fmod(0.1 + 0.7390851332151607 * (i + 1) * (d + 1), s.box_hi[d]);
      set.v[3 * i + d] = sin(1.0 + i * 3.0 + d) / 3.0;
    }
    set.rho[i] = 6 + 0.001 * i;
  }
  set.has_v = 1;

  CHECK(lammps_data_write("roundtrip.data", &s, &set, 42) == 0);
  CHECK(lammps_data_read("roundtrip.data", &s, &back) == 0);
  CHECK(back.has_v && same(&set, &back));
  particle_set_free(&back);

  long step = 0;
  CHECK(snapshot_write_set("roundtrip.h5", &s, &set, 42, 0.42) == 0);
  CHECK(snapshot_read("roundtrip.h5", &s, &back, &step) == 0);
  CHECK(step == 42 && same(&set, &back) && back.rho && back.rho[n - 1] == set.rho[n - 1]);
  particle_set_free(&back);

  /* A scene with fewer species than the file's atom types is rejected. */
  scene_t one = s;
  one.n_species = 1;
  fprintf(stderr, "(the next error message is expected)\n");
  CHECK(lammps_data_read("roundtrip.data", &one, &back) != 0);
  CHECK(snapshot_read("roundtrip.h5", &one, &back, NULL) != 0);

  particle_set_free(&set);
  remove("roundtrip.data");
  remove("roundtrip.h5");
  MPI_Finalize();
  if (failures) fprintf(stderr, "%d checks failed\n", failures);
  return failures ? 1 : 0;
}
