/* Checkpoint/restart files (see checkpoint.h). */
#include "common/hdf5_lock.h"
#include "io/checkpoint.h"
#include "common/atomic_file.h"
#include "io/crc32.h"
#include "io/gather.h"
#include "io/h5_util.h"
#include "engine/sim_balance.h"
#include "common/size_check.h"

#include <stdlib.h>
#include <string.h>

/* The checksums (attributes "crc32_<dataset>" and "crc32_header"): CRC-32 of each dataset's bytes
 * as stored (native types), and of the header attributes step, time, nranks, seed, scene_hash. */
static uint32_t header_crc(long step, double time, long nranks, unsigned long long seed,
                           unsigned long long hash) {
  uint32_t c = crc32_update(0, &step, sizeof step);
  c = crc32_update(c, &time, sizeof time);
  c = crc32_update(c, &nranks, sizeof nranks);
  c = crc32_update(c, &seed, sizeof seed);
  return crc32_update(c, &hash, sizeof hash);
}

static void put_crc(hid_t f, const char *dataset, const void *data, size_t bytes) {
  char name[64];
  snprintf(name, sizeof name, "crc32_%s", dataset);
  h5_attr_u64(f, name, crc32_update(0, data, bytes));
}

/* 0 when the stored CRC of `dataset` matches its bytes (or the file has none: *unchecked set);
 * -1 after a message naming the file, the dataset and both values. */
static int check_crc(hid_t f, const char *path, const char *dataset, const void *data, size_t bytes,
                     int *unchecked) {
  char name[64];
  snprintf(name, sizeof name, "crc32_%s", dataset);
  unsigned long long stored;
  if (h5_read_attr_u64(f, name, &stored)) {
    *unchecked = 1;
    return 0;
  }
  const uint32_t computed = crc32_update(0, data, bytes);
  if (stored == computed) return 0;
  fprintf(stderr,
          "%s: corrupted checkpoint refused: dataset '%s' has CRC-32 0x%08x, the file records "
          "0x%08llx (over its %zu bytes); restart from an earlier or an intact copy\n",
          path, dataset, computed, stored, bytes);
  return -1;
}

/* Every rank's subdomain (lo, hi) on rank 0, 6 doubles per rank (NULL elsewhere). Collective. */
static double *gather_subdomains(sim_t *sim, MPI_Comm comm, int rank, int size) {
  double box[6];
  sim_subdomain(sim, box, box + 3);
  double *boxes = rank == 0 ? malloc((size_t)size * 6 * sizeof *boxes) : NULL;
  MPI_Gather(box, 6, MPI_DOUBLE, boxes, 6, MPI_DOUBLE, 0, comm);
  return boxes;
}

static int checkpoint_write_unlocked(const char *path, sim_t *sim) {
  MPI_Comm comm = sim_comm(sim);
  int rank, size, rc = 0;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  double *boxes = gather_subdomains(sim, comm, rank, size);
  long *counts = rank == 0 ? malloc((size_t)size * sizeof *counts) : NULL;
  particle_set_t set;
  if (gather_particles(sim, 0, 1, &set, counts)) {
    free(boxes);
    free(counts);
    return -1;
  }
  if (rank == 0) {
    const scene_t *s = sim_scene(sim);
    double *lo = malloc((size_t)size * 3 * sizeof *lo), *hi = malloc((size_t)size * 3 * sizeof *hi);
    int64_t *c64 = malloc((size_t)size * sizeof *c64);
    for (int r = 0; lo && hi && c64 && r < size; r++) {
      memcpy(lo + 3 * r, boxes + 6 * r, 3 * sizeof *lo);
      memcpy(hi + 3 * r, boxes + 6 * r + 3, 3 * sizeof *hi);
      c64[r] = counts[r];
    }
    char tmp[SCENE_PATH_LEN + 32];
    atomic_tmp_name(path, tmp, sizeof tmp);
    hid_t f = !lo || !hi || !c64 ? -1 : H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (!lo || !hi || !c64) {
      fprintf(stderr, "%s: out of memory for the subdomain tables of %d ranks\n", path, size);
      rc = -1;
    } else if (f < 0) {
      fprintf(stderr, "%s: cannot create checkpoint file\n", tmp);
      rc = -1;
    } else {
      const double time = sim_step_index(sim) * s->dt;
      h5_attr_long(f, "step", sim_step_index(sim));
      h5_attr_double(f, "time", &time, 1);
      h5_attr_long(f, "nranks", size);
      h5_attr_u64(f, "seed", (unsigned long long)s->seed);
      h5_attr_u64(f, "scene_hash", (unsigned long long)scene_physics_hash(s));
      h5_attr_string(f, "scene", s->name);
      h5_attr_u64(f, "crc32_header",
                  header_crc(sim_step_index(sim), time, size, (unsigned long long)s->seed,
                             (unsigned long long)scene_physics_hash(s)));
      const size_t nb = (size_t)set.n, nr = (size_t)size;
      put_crc(f, "rank_counts", c64, nr * sizeof *c64);
      put_crc(f, "subdomain_lo", lo, 3 * nr * sizeof *lo);
      put_crc(f, "subdomain_hi", hi, 3 * nr * sizeof *hi);
      put_crc(f, "id", set.id, nb * sizeof *set.id);
      put_crc(f, "species", set.species, nb * sizeof *set.species);
      put_crc(f, "position", set.x, 3 * nb * sizeof *set.x);
      put_crc(f, "velocity", set.v, 3 * nb * sizeof *set.v);
      put_crc(f, "force", set.f, 3 * nb * sizeof *set.f);
      const hsize_t n = (hsize_t)set.n;
      rc |= h5_write_dataset(f, "rank_counts", H5T_NATIVE_INT64, c64, (hsize_t)size, 1);
      rc |= h5_write_dataset(f, "subdomain_lo", H5T_NATIVE_DOUBLE, lo, (hsize_t)size, 3);
      rc |= h5_write_dataset(f, "subdomain_hi", H5T_NATIVE_DOUBLE, hi, (hsize_t)size, 3);
      rc |= h5_write_dataset(f, "id", H5T_NATIVE_INT64, set.id, n, 1);
      rc |= h5_write_dataset(f, "species", H5T_NATIVE_INT32, set.species, n, 1);
      rc |= h5_write_dataset(f, "position", H5T_NATIVE_DOUBLE, set.x, n, 3);
      rc |= h5_write_dataset(f, "velocity", H5T_NATIVE_DOUBLE, set.v, n, 3);
      rc |= h5_write_dataset(f, "force", H5T_NATIVE_DOUBLE, set.f, n, 3);
      rc |= H5Fclose(f) < 0;
      if (rc) {
        fprintf(stderr, "%s: checkpoint write failed\n", tmp);
        remove(tmp);
      } else {
        rc = atomic_rename(tmp, path);
      }
    }
    free(lo);
    free(hi);
    free(c64);
  }
  free(boxes);
  free(counts);
  particle_set_free(&set);
  MPI_Bcast(&rc, 1, MPI_INT, 0, comm);
  return rc;
}

/* Rank 0: open and check the file against this run; on success fills the set and per-rank counts.
 */
static int read_on_root(const char *path, sim_t *sim, int size, double *boxes, particle_set_t *set,
                        long *counts, long *step) {
  const scene_t *s = sim_scene(sim);
  H5E_auto2_t fn;
  void *cd;
  H5Eget_auto2(H5E_DEFAULT, &fn, &cd);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  int rc = -1;
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  long nranks = -1;
  unsigned long long hash = 0, seed = 0, stored_header = 0;
  double time = 0;
  int unchecked = 0;
  if (f < 0) {
    fprintf(stderr, "%s: cannot open checkpoint (restart)\n", path);
    goto out;
  }
  if (h5_read_attr_long(f, "nranks", &nranks) || h5_read_attr_long(f, "step", step) ||
      h5_read_attr_u64(f, "scene_hash", &hash)) {
    fprintf(stderr,
            "%s: expected an mdpore checkpoint (attributes nranks, step, scene_hash missing)\n",
            path);
    goto out;
  }
  if (h5_read_attr_u64(f, "crc32_header", &stored_header) == 0) {
    h5_read_attr_double(f, "time", &time, 1);
    h5_read_attr_u64(f, "seed", &seed);
    const uint32_t computed = header_crc(*step, time, nranks, seed, hash);
    if (computed != stored_header) {
      fprintf(stderr,
              "%s: corrupted checkpoint refused: the header attributes (step %ld, time, nranks "
              "%ld, seed, scene_hash) have CRC-32 0x%08x, the file records 0x%08llx; restart "
              "from an earlier or an intact copy\n",
              path, *step, nranks, computed, stored_header);
      goto out;
    }
  } else {
    unchecked = 1;
  }
  if (nranks != size) {
    fprintf(stderr,
            "%s: decomposition mismatch: checkpoint written by %ld ranks, this run has %d (restart "
            "on the "
            "same number of ranks and box.procs)\n",
            path, nranks, size);
    goto out;
  }
  if (hash != (unsigned long long)scene_physics_hash(s)) {
    fprintf(stderr,
            "%s: scene mismatch: the checkpoint was written for different physics than %s (box, "
            "species, "
            "pairs, effects, dt or seed changed)\n",
            path, s->file);
    goto out;
  }
  double *lo = malloc((size_t)size * 3 * sizeof *lo), *hi = malloc((size_t)size * 3 * sizeof *hi);
  int64_t *c64 = malloc((size_t)size * sizeof *c64);
  if (!lo || !hi || !c64) {
    fprintf(stderr, "%s: out of memory for the subdomain tables of %d ranks\n", path, size);
    free(lo), free(hi), free(c64);
    goto out;
  }
  int bad = h5_read_dataset(f, "subdomain_lo", H5T_NATIVE_DOUBLE, lo, (hsize_t)size, 3, path) ||
            h5_read_dataset(f, "subdomain_hi", H5T_NATIVE_DOUBLE, hi, (hsize_t)size, 3, path) ||
            h5_read_dataset(f, "rank_counts", H5T_NATIVE_INT64, c64, (hsize_t)size, 1, path);
  const size_t nr = (size_t)size;
  bad = bad || check_crc(f, path, "subdomain_lo", lo, 3 * nr * sizeof *lo, &unchecked) ||
        check_crc(f, path, "subdomain_hi", hi, 3 * nr * sizeof *hi, &unchecked) ||
        check_crc(f, path, "rank_counts", c64, nr * sizeof *c64, &unchecked);
  /* The checkpoint's subdomains (its cuts: checkpoint_read adopts them, so that a run balanced by
   * cost restarts on the same decomposition). */
  for (int r = 0; r < size && !bad; r++)
    for (int d = 0; d < 3; d++) {
      boxes[6 * r + d] = lo[3 * r + d];
      boxes[6 * r + 3 + d] = hi[3 * r + d];
    }
  long total = 0;
  for (int r = 0; r < size; r++) total += (counts[r] = c64[r]);
  free(lo);
  free(hi);
  free(c64);
  if (bad) goto out;
  /* rank 0 holds every particle of the file before the memory plan is checked: its count first */
  char why[320];
  if (mdp_size_check((double)total, 2147483646.0, particle_set_bytes(1, 0), "particles", why,
                     sizeof why)) {
    fprintf(stderr, "%s: key 'rank_counts': %s\n", path, why);
    goto out;
  }
  if (particle_set_alloc(set, total, 1, 0)) {
    fprintf(stderr, "%s: out of memory for %ld particles\n", path, total);
    goto out;
  }
  const hsize_t n = (hsize_t)total;
  if (h5_read_dataset(f, "id", H5T_NATIVE_INT64, set->id, n, 1, path) ||
      h5_read_dataset(f, "species", H5T_NATIVE_INT32, set->species, n, 1, path) ||
      h5_read_dataset(f, "position", H5T_NATIVE_DOUBLE, set->x, n, 3, path) ||
      h5_read_dataset(f, "velocity", H5T_NATIVE_DOUBLE, set->v, n, 3, path) ||
      h5_read_dataset(f, "force", H5T_NATIVE_DOUBLE, set->f, n, 3, path)) {
    particle_set_free(set);
    goto out;
  }
  const size_t nb = (size_t)total;
  if (check_crc(f, path, "id", set->id, nb * sizeof *set->id, &unchecked) ||
      check_crc(f, path, "species", set->species, nb * sizeof *set->species, &unchecked) ||
      check_crc(f, path, "position", set->x, 3 * nb * sizeof *set->x, &unchecked) ||
      check_crc(f, path, "velocity", set->v, 3 * nb * sizeof *set->v, &unchecked) ||
      check_crc(f, path, "force", set->f, 3 * nb * sizeof *set->f, &unchecked)) {
    particle_set_free(set);
    goto out;
  }
  if (unchecked)
    fprintf(stderr,
            "mdpore: warning: %s has no checksums (written by an older mdpore): restarting "
            "without verifying it\n",
            path);
  rc = 0;
out:
  if (f >= 0) H5Fclose(f);
  H5Eset_auto2(H5E_DEFAULT, fn, cd);
  return rc;
}

/* Every rank takes the checkpoint's subdomains (boxes on rank 0: lo[3] hi[3] per rank) as the
 * cuts of the grid; a set of boxes that is not this run's grid is a decomposition mismatch. */
static int adopt_cuts(const char *path, sim_t *sim, MPI_Comm comm, int rank, int size,
                      double *boxes) {
  MPI_Bcast(boxes, 6 * size, MPI_DOUBLE, 0, comm);
  const double *cut_now[3];
  int dims[3], bad = 0;
  sim_cuts(sim, cut_now, dims);
  double *cuts[3] = {NULL, NULL, NULL};
  for (int d = 0; d < 3; d++) bad |= !(cuts[d] = malloc((size_t)(dims[d] + 1) * sizeof(double)));
  for (int d = 0; d < 3 && !bad; d++) {
    for (int c = 0; c < dims[d]; c++) { /* the lower bound of the subdomain at coords c along d */
      int coords[3] = {0, 0, 0}, r = 0;
      coords[d] = c;
      MPI_Cart_rank(comm, coords, &r);
      cuts[d][c] = boxes[6 * r + d];
    }
    cuts[d][dims[d]] = cut_now[d][dims[d]];
  }
  bad = bad || sim_set_cuts(sim, cuts);
  double lo[3], hi[3];
  sim_subdomain(sim, lo, hi);
  for (int d = 0; d < 3 && !bad; d++)
    bad = lo[d] != boxes[6 * rank + d] || hi[d] != boxes[6 * rank + 3 + d];
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm);
  if (bad && rank == 0)
    fprintf(stderr,
            "%s: decomposition mismatch: the checkpoint's subdomains are not a grid of this run's "
            "box.procs (restart with the same box.procs)\n",
            path);
  for (int d = 0; d < 3; d++) free(cuts[d]);
  return bad ? -1 : 0;
}

static int checkpoint_read_unlocked(const char *path, sim_t *sim) {
  MPI_Comm comm = sim_comm(sim);
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  double *boxes = malloc((size_t)size * 6 * sizeof *boxes);
  long *counts = calloc((size_t)size, sizeof *counts), step = 0;
  particle_set_t set;
  memset(&set, 0, sizeof set);
  int oom = !boxes || !counts;
  MPI_Allreduce(MPI_IN_PLACE, &oom, 1, MPI_INT, MPI_MAX, comm);
  if (oom) {
    if (rank == 0) fprintf(stderr, "%s: out of memory for the tables of %d ranks\n", path, size);
    free(boxes), free(counts);
    return -1;
  }
  int rc = rank == 0 ? read_on_root(path, sim, size, boxes, &set, counts, &step) : 0;
  MPI_Bcast(&rc, 1, MPI_INT, 0, comm);
  if (rc) {
    free(boxes);
    free(counts);
    return -1;
  }
  MPI_Bcast(&step, 1, MPI_LONG, 0, comm);
  MPI_Bcast(counts, size, MPI_LONG, 0, comm);
  if (adopt_cuts(path, sim, comm, rank, size, boxes)) {
    particle_set_free(&set);
    free(boxes);
    free(counts);
    return -1;
  }
  /* the memory plan (engine/memory_plan.h) with the checkpoint's counts, rank 0 holding them all */
  const scene_t *s = sim_scene(sim);
  memory_inputs_t in = {0};
  for (int r = 0; r < size; r++) in.total += (double)counts[r];
  in.owned = (double)counts[rank];
  in.input_set = rank == 0 ? in.total : 0;
  in.density = memory_scene_density(s);
  const double box =
      (s->box_hi[0] - s->box_lo[0]) * (s->box_hi[1] - s->box_lo[1]) * (s->box_hi[2] - s->box_lo[2]);
  if (box > 0 && in.total / box > in.density) in.density = in.total / box;
  if (sim_memory_check(sim, &in)) {
    particle_set_free(&set);
    free(boxes);
    free(counts);
    return -1;
  }
  /* Scatter each rank's block, field by field. */
  int *cnt = malloc((size_t)size * sizeof *cnt), *dsp = malloc((size_t)size * sizeof *dsp);
  int *cnt3 = malloc((size_t)size * sizeof *cnt3), *dsp3 = malloc((size_t)size * sizeof *dsp3);
  particle_set_t mine;
  memset(&mine, 0, sizeof mine);
  oom = !cnt || !dsp || !cnt3 || !dsp3 ||
        particle_set_alloc(&mine, counts[rank], 1, 0); /* counts: broadcast above */
  MPI_Allreduce(MPI_IN_PLACE, &oom, 1, MPI_INT, MPI_MAX, comm);
  if (oom) {
    if (rank == 0) fprintf(stderr, "%s: out of memory scattering the particles\n", path);
    particle_set_free(&set), particle_set_free(&mine);
    free(cnt), free(dsp), free(cnt3), free(dsp3), free(boxes), free(counts);
    return -1;
  }
  long off = 0;
  for (int r = 0; r < size; r++) {
    cnt[r] = (int)counts[r];
    dsp[r] = (int)off;
    cnt3[r] = 3 * cnt[r];
    dsp3[r] = 3 * dsp[r];
    off += counts[r];
  }
  const int n = cnt[rank];
  MPI_Scatterv(set.id, cnt, dsp, MPI_INT64_T, mine.id, n, MPI_INT64_T, 0, comm);
  MPI_Scatterv(set.species, cnt, dsp, MPI_INT32_T, mine.species, n, MPI_INT32_T, 0, comm);
  MPI_Scatterv(set.x, cnt3, dsp3, MPI_DOUBLE, mine.x, 3 * n, MPI_DOUBLE, 0, comm);
  MPI_Scatterv(set.v, cnt3, dsp3, MPI_DOUBLE, mine.v, 3 * n, MPI_DOUBLE, 0, comm);
  MPI_Scatterv(set.f, cnt3, dsp3, MPI_DOUBLE, mine.f, 3 * n, MPI_DOUBLE, 0, comm);
  particle_set_free(&set);
  /* Re-add in local order; every particle must land here (it was owned here). */
  int bad = 0;
  for (int i = 0; i < n && !bad; i++)
    bad = sim_add_particle(sim, mine.id[i], mine.species[i], mine.x + 3 * i, mine.v + 3 * i) != 1;
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm);
  if (bad) {
    if (rank == 0)
      fprintf(
          stderr,
          "%s: a particle of the checkpoint does not belong to its rank's subdomain (decomposition "
          "mismatch)\n",
          path);
  } else {
    particles_t *p = sim_particles(sim);
    for (int i = 0; i < n; i++)
      for (int d = 0; d < 3; d++) p->f[d][i] = mine.f[3 * i + d];
    sim_set_step_index(sim, step);
    sim_forces_loaded(sim);
  }
  particle_set_free(&mine);
  free(cnt);
  free(dsp);
  free(cnt3);
  free(dsp3);
  free(boxes);
  free(counts);
  return bad ? -1 : 0;
}

/* The public entry points: each whole call under the HDF5 lock (common/hdf5_lock.h). */
int checkpoint_write(const char *path, sim_t *sim) {
  hdf5_lock();
  const int rc = checkpoint_write_unlocked(path, sim);
  hdf5_unlock();
  return rc;
}

int checkpoint_read(const char *path, sim_t *sim) {
  hdf5_lock();
  const int rc = checkpoint_read_unlocked(path, sim);
  hdf5_unlock();
  return rc;
}
