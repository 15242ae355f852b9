/* Fuzz entry: a LAMMPS data file (atomic style) through lammps_data_read, against a fixed scene of
 * two species (masses 1 and 2) in the box [0, 10]^3. */
#include "populate/lammps_data.h"
#include "fuzz_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static scene_t *scene(void) {
  static scene_t *s;
  if (!s) {
    s = calloc(1, sizeof *s);
    if (!s) abort();
    strcpy(s->file, "fuzz.yaml");
    s->n_species = 2;
    strcpy(s->species[0].name, "liquid");
    s->species[0].mass = 1.0;
    strcpy(s->species[1].name, "wall");
    s->species[1].mass = 2.0;
    for (int d = 0; d < 3; d++) s->box_lo[d] = 0, s->box_hi[d] = 10, s->periodic[d] = 1;
  }
  return s;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300];
  fuzz_path("data.lmp", path, sizeof path);
  fuzz_write(path, data, size);
  particle_set_t set;
  fuzz_capture_begin();
  const int rc = lammps_data_read(path, scene(), &set);
  const char *msg = fuzz_capture_end();
  if (rc == 0) {
    /* an accepted set has finite positions and species among the scene's */
    for (long i = 0; i < set.n; i++) {
      int bad = set.species[i] < 0 || set.species[i] >= scene()->n_species;
      for (int d = 0; d < 3; d++) bad |= !isfinite(set.x[3 * i + d]);
      if (bad) {
        fprintf(stderr, "fuzz: %s accepted with a bad atom %ld\n", path, i);
        abort();
      }
    }
    particle_set_free(&set);
  }
  fuzz_outcome(rc, msg, path);
  return 0;
}
