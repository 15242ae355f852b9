/* LAMMPS-style text dump frames, written by rank 0 from gathered particles. */
#include "io/dump_lammps.h"
#include "io/gather.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int dump_lammps_frame(const char *path, sim_t *sim, int truncate) {
  MPI_Comm comm = sim_comm(sim);
  int rank, rc = 0;
  MPI_Comm_rank(comm, &rank);
  particle_set_t set;
  if (gather_particles(sim, 0, 1, &set, NULL)) return -1;
  if (rank == 0) {
    const scene_t *s = sim_scene(sim);
    FILE *fp = NULL;
    if (particle_set_sort_by_id(&set)) {
      fprintf(stderr, "%s: out of memory sorting %ld particles for the dump\n", path, set.n);
      rc = -1;
    } else if (!(fp = fopen(path, truncate ? "w" : "a"))) {
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

/* Frames are appended in step order, each 9 + N lines (TIMESTEP, step, NUMBER OF ATOMS, N, BOX
 * BOUNDS + 3 lines, ATOMS header, N atom lines): the file is cut at the start of the first frame
 * that is incomplete or after `upto`. */
int dump_lammps_trim(const char *path, long upto) {
  FILE *fp = fopen(path, "r");
  if (!fp) return 0;
  char *line = NULL;
  size_t cap = 0;
  long keep = 0, kept = 0, step = -1, atoms = -1, at = 0; /* at: line within the frame */
  ssize_t L;
  int cut = 0;
  while (!cut && (L = getline(&line, &cap, fp)) > 0) {
    if (line[L - 1] != '\n') { /* a half-written last line */
      cut = 1;
      break;
    }
    if (at == 0 && strncmp(line, "ITEM: TIMESTEP", 14) != 0) {
      cut = 1; /* not a frame boundary: garbage after the last complete frame */
      break;
    }
    if (at == 1) step = strtol(line, NULL, 10);
    if (at == 3) atoms = strtol(line, NULL, 10);
    if (at == 1 && step > upto) {
      cut = 1;
      break;
    }
    at++;
    if (at >= 9 && atoms >= 0 && at == 9 + atoms) { /* a complete frame */
      keep = ftell(fp);
      kept++;
      at = 0;
    }
  }
  if (at != 0) cut = 1; /* ended inside a frame */
  free(line);
  fclose(fp);
  if (!cut) return 0;
  if (truncate(path, keep) != 0) {
    fprintf(stderr, "%s: cannot cut the dump back to step %ld: %s\n", path, upto, strerror(errno));
    return -1;
  }
  fprintf(stderr,
          "mdpore: %s: restart at step %ld: kept %ld complete frame(s), dropped what followed "
          "(frames after the checkpoint or a half-written frame)\n",
          path, upto, kept);
  return 0;
}
