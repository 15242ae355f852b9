/* LAMMPS-style text dump frames, written by rank 0 from gathered particles. */
#include "io/dump_lammps.h"
#include "io/gather.h"

#include <errno.h>
#include <string.h>

int dump_lammps_frame(const char *path, sim_t *sim, int truncate) {
  MPI_Comm comm = sim_comm(sim);
  int rank, rc = 0;
  MPI_Comm_rank(comm, &rank);
  particle_set_t set;
  if (gather_particles(sim, 0, 1, &set, NULL)) return -1;
  if (rank == 0) {
    const scene_t *s = sim_scene(sim);
    particle_set_sort_by_id(&set);
    FILE *fp = fopen(path, truncate ? "w" : "a");
    if (!fp) {
      fprintf(stderr, "%s: cannot write dump: %s\n", path, strerror(errno));
      rc = -1;
    } else {
      fprintf(fp, "ITEM: TIMESTEP\n%ld\nITEM: NUMBER OF ATOMS\n%ld\nITEM: BOX BOUNDS %s %s %s\n",
              sim_step_index(sim), set.n, s->periodic[0] ? "pp" : "ff",
              s->periodic[1] ? "pp" : "ff", s->periodic[2] ? "pp" : "ff");
      for (int d = 0; d < 3; d++) fprintf(fp, "%.17g %.17g\n", s->box_lo[d], s->box_hi[d]);
      fprintf(fp, "ITEM: ATOMS id type x y z vx vy vz fx fy fz%s\n", set.rho ? " rho" : "");
      for (long i = 0; i < set.n; i++) {
        const double *x = set.x + 3 * i, *v = set.v + 3 * i, *f = set.f + 3 * i;
        fprintf(fp, "%lld %d %.10g %.10g %.10g %.10g %.10g %.10g %.10g %.10g %.10g",
                (long long)set.id[i], set.species[i] + 1, x[0], x[1], x[2], v[0], v[1], v[2], f[0],
                f[1], f[2]);
        if (set.rho) fprintf(fp, " %.10g", set.rho[i]);
        fputc('\n', fp);
      }
      if (fclose(fp) != 0) rc = -1;
    }
  }
  particle_set_free(&set);
  MPI_Bcast(&rc, 1, MPI_INT, 0, comm);
  return rc;
}
