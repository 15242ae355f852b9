/* HDF5 snapshots (serial HDF5 on rank 0) and their XDMF index. */
#include "common/hdf5_lock.h"
#include "io/snapshot.h"
#include "common/atomic_file.h"
#include "common/size_check.h"
#include "io/gather.h"
#include "io/h5_util.h"
#include "physics/density_kernels.h"

#include <dirent.h>
#include <hdf5.h>
#include <libgen.h>
#include <stdlib.h>
#include <string.h>

static void species_list(const scene_t *s, char *out, size_t len) {
  out[0] = 0;
  for (int k = 0; k < s->n_species; k++) {
    if (k) strncat(out, ";", len - strlen(out) - 1);
    strncat(out, s->species[k].name, len - strlen(out) - 1);
  }
}

static int snapshot_write_set_unlocked(const char *path, const scene_t *s,
                                       const particle_set_t *set, long step, double time) {
  char tmp[SCENE_PATH_LEN + 32];
  atomic_tmp_name(path, tmp, sizeof tmp);
  hid_t f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) {
    fprintf(stderr, "%s: cannot create HDF5 file\n", tmp);
    return -1;
  }
  char names[SCENE_MAX_SPECIES * (SCENE_NAME_LEN + 1)];
  species_list(s, names, sizeof names);
  h5_attr_long(f, "step", step);
  h5_attr_double(f, "time", &time, 1);
  h5_attr_double(f, "box_lo", s->box_lo, 3);
  h5_attr_double(f, "box_hi", s->box_hi, 3);
  h5_attr_string(f, "scene", s->name);
  h5_attr_string(f, "species", names);
  h5_attr_string(f, "kernel", s->density_kernel == MESO_KERNEL_LUCY ? "lucy" : "warren");
  hid_t g = H5Gcreate2(f, "particles", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t n = (hsize_t)set->n;
  int e = h5_write_dataset(g, "id", H5T_NATIVE_INT64, set->id, n, 1);
  e |= h5_write_dataset(g, "species", H5T_NATIVE_INT32, set->species, n, 1);
  e |= h5_write_dataset(g, "position", H5T_NATIVE_DOUBLE, set->x, n, 3);
  e |= h5_write_dataset(g, "velocity", H5T_NATIVE_DOUBLE, set->v, n, 3);
  if (set->rho) e |= h5_write_dataset(g, "density", H5T_NATIVE_DOUBLE, set->rho, n, 1);
  H5Gclose(g);
  e |= H5Fclose(f) < 0;
  if (e) {
    fprintf(stderr, "%s: HDF5 write failed\n", tmp);
    remove(tmp);
    return -1;
  }
  return atomic_rename(tmp, path);
}

static int snapshot_read_unlocked(const char *path, const scene_t *s, particle_set_t *out,
                                  long *step) {
  memset(out, 0, sizeof *out);
  H5E_auto2_t fn;
  void *cd;
  H5Eget_auto2(H5E_DEFAULT, &fn, &cd);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  int rc = -1;
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT), g = -1;
  if (f < 0) {
    fprintf(stderr, "%s: cannot open as an HDF5 snapshot\n", path);
    goto out;
  }
  /* Species names must match the scene's, in order. */
  hid_t a = H5Aopen(f, "species", H5P_DEFAULT);
  char names[SCENE_MAX_SPECIES * (SCENE_NAME_LEN + 1)] = "", want[sizeof names];
  if (a >= 0) {
    hid_t t = H5Aget_type(a);
    if (H5Tget_size(t) <= sizeof names) H5Aread(a, t, names);
    H5Tclose(t);
    H5Aclose(a);
  }
  species_list(s, want, sizeof want);
  if (strcmp(names, want)) {
    fprintf(stderr, "%s: attribute 'species': expected the scene's species '%s' (got '%s')\n", path,
            want, names);
    goto out;
  }
  if (step) {
    *step = 0;
    if ((a = H5Aopen(f, "step", H5P_DEFAULT)) >= 0) {
      H5Aread(a, H5T_NATIVE_LONG, step);
      H5Aclose(a);
    }
  }
  if ((g = H5Gopen2(f, "particles", H5P_DEFAULT)) < 0) {
    fprintf(stderr, "%s: expected group /particles (missing)\n", path);
    goto out;
  }
  hid_t d = H5Dopen2(g, "id", H5P_DEFAULT);
  if (d < 0) {
    fprintf(stderr, "%s: expected dataset /particles/id (missing)\n", path);
    goto out;
  }
  hid_t sp = H5Dget_space(d);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(sp, &n, NULL);
  H5Sclose(sp);
  H5Dclose(d);
  const int has_rho = H5Lexists(g, "density", H5P_DEFAULT) > 0;
  char why[320];
  if (mdp_size_check((double)n, 2147483646.0, particle_set_bytes(0, has_rho), "particles", why,
                     sizeof why)) {
    fprintf(stderr, "%s: key '/particles/id': %s\n", path, why);
    goto out;
  }
  if (particle_set_alloc(out, (long)n, 0, has_rho)) {
    fprintf(stderr, "%s: out of memory for %llu particles\n", path, (unsigned long long)n);
    goto out;
  }
  if (h5_read_dataset(g, "id", H5T_NATIVE_INT64, out->id, n, 1, path) ||
      h5_read_dataset(g, "species", H5T_NATIVE_INT32, out->species, n, 1, path) ||
      h5_read_dataset(g, "position", H5T_NATIVE_DOUBLE, out->x, n, 3, path) ||
      h5_read_dataset(g, "velocity", H5T_NATIVE_DOUBLE, out->v, n, 3, path) ||
      (has_rho && h5_read_dataset(g, "density", H5T_NATIVE_DOUBLE, out->rho, n, 1, path)))
    goto out;
  for (hsize_t i = 0; i < n; i++)
    if (out->species[i] < 0 || out->species[i] >= s->n_species) {
      fprintf(stderr, "%s: /particles/species[%llu]: expected 0..%d (got %d)\n", path,
              (unsigned long long)i, s->n_species - 1, out->species[i]);
      goto out;
    }
  out->has_v = 1;
  rc = 0;
out:
  if (g >= 0) H5Gclose(g);
  if (f >= 0) H5Fclose(f);
  H5Eset_auto2(H5E_DEFAULT, fn, cd);
  if (rc) particle_set_free(out);
  return rc;
}

int snapshot_read_bcast(const char *path, const scene_t *s, MPI_Comm comm, particle_set_t *out) {
  int rank, rc = 0;
  MPI_Comm_rank(comm, &rank);
  memset(out, 0, sizeof *out);
  if (rank == 0) rc = snapshot_read(path, s, out, NULL);
  MPI_Bcast(&rc, 1, MPI_INT, 0, comm);
  if (rc) return -1;
  return particle_set_bcast(out, 0, comm);
}

void snapshot_series_init(snapshot_series_t *ser, const char *base) {
  memset(ser, 0, sizeof *ser);
  snprintf(ser->base, sizeof ser->base, "%s", base);
}

void snapshot_series_free(snapshot_series_t *ser) {
  free(ser->steps);
  free(ser->times);
  free(ser->counts);
  memset(ser, 0, sizeof *ser);
}

void snapshot_series_path(const snapshot_series_t *ser, long step, char *out, size_t len) {
  snprintf(out, len, "%s_%09ld.h5", ser->base, step);
}

/* XDMF 3 temporal collection: one polyvertex grid per snapshot, pointing into the HDF5 files (paths
 * relative to the XDMF file, which sits beside them). */
static int write_xdmf(const snapshot_series_t *ser) {
  char path[1100], tmp[1200], bcopy[1024];
  snprintf(path, sizeof path, "%s.xdmf", ser->base);
  FILE *fp = atomic_open(path, tmp, sizeof tmp);
  if (!fp) return -1;
  snprintf(bcopy, sizeof bcopy, "%s", ser->base);
  const char *stem = basename(bcopy);
  fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
              "  <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  for (int k = 0; k < ser->n; k++) {
    const long n = ser->counts[k];
    char file[1100];
    snprintf(file, sizeof file, "%s_%09ld.h5", stem, ser->steps[k]);
    fprintf(fp, "   <Grid Name=\"step_%ld\" GridType=\"Uniform\">\n    <Time Value=\"%.10g\"/>\n",
            ser->steps[k], ser->times[k]);
    fprintf(fp,
            "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%ld\" "
            "NodesPerElement=\"1\"/>\n",
            n);
    fprintf(fp,
            "    <Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"%ld 3\" "
            "NumberType=\"Float\" "
            "Precision=\"8\" Format=\"HDF\">%s:/particles/position</DataItem>\n    </Geometry>\n",
            n, file);
    fprintf(fp,
            "    <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n     "
            "<DataItem "
            "Dimensions=\"%ld 3\" NumberType=\"Float\" Precision=\"8\" "
            "Format=\"HDF\">%s:/particles/velocity"
            "</DataItem>\n    </Attribute>\n",
            n, file);
    fprintf(
        fp,
        "    <Attribute Name=\"species\" AttributeType=\"Scalar\" Center=\"Node\">\n     <DataItem "
        "Dimensions=\"%ld\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">%s:/particles/species"
        "</DataItem>\n    </Attribute>\n",
        n, file);
    fprintf(fp,
            "    <Attribute Name=\"id\" AttributeType=\"Scalar\" Center=\"Node\">\n     <DataItem "
            "Dimensions=\"%ld\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">%s:/particles/id"
            "</DataItem>\n    </Attribute>\n",
            n, file);
    if (ser->has_rho)
      fprintf(fp,
              "    <Attribute Name=\"density\" AttributeType=\"Scalar\" Center=\"Node\">\n     "
              "<DataItem "
              "Dimensions=\"%ld\" NumberType=\"Float\" Precision=\"8\" "
              "Format=\"HDF\">%s:/particles/density"
              "</DataItem>\n    </Attribute>\n",
              n, file);
    fprintf(fp, "   </Grid>\n");
  }
  fprintf(fp, "  </Grid>\n </Domain>\n</Xdmf>\n");
  return atomic_commit(fp, tmp, path);
}

static int series_push(snapshot_series_t *ser, long step, double time, long count, int has_rho) {
  if (ser->n == ser->cap) {
    const int cap = ser->cap ? 2 * ser->cap : 16;
    long *steps = realloc(ser->steps, (size_t)cap * sizeof *steps);
    if (steps) ser->steps = steps;
    double *times = realloc(ser->times, (size_t)cap * sizeof *times);
    if (times) ser->times = times;
    long *counts = realloc(ser->counts, (size_t)cap * sizeof *counts);
    if (counts) ser->counts = counts;
    if (!steps || !times || !counts) return -1;
    ser->cap = cap;
  }
  ser->steps[ser->n] = step;
  ser->times[ser->n] = time;
  ser->counts[ser->n] = count;
  ser->has_rho = has_rho;
  ser->n++;
  return 0;
}

static int step_cmp(const void *a, const void *b) {
  const long x = *(const long *)a, y = *(const long *)b;
  return (x > y) - (x < y);
}

static int snapshot_series_resume_unlocked(snapshot_series_t *ser, const scene_t *s, long upto) {
  char dir[1024], stem[1024];
  snprintf(dir, sizeof dir, "%s", ser->base);
  snprintf(stem, sizeof stem, "%s", ser->base);
  const char *d = dirname(dir), *b = basename(stem);
  const size_t bl = strlen(b);
  DIR *dp = opendir(d);
  if (!dp) return 0;
  long *keep = NULL, nkeep = 0, cap = 0, removed = 0;
  struct dirent *e;
  while ((e = readdir(dp))) {
    /* "<stem>_<9 digits>.h5" */
    const char *name = e->d_name;
    if (strncmp(name, b, bl) != 0 || name[bl] != '_' || strlen(name) != bl + 13 ||
        strcmp(name + bl + 10, ".h5") != 0)
      continue;
    char *end;
    const long step = strtol(name + bl + 1, &end, 10);
    if (end != name + bl + 10) continue;
    if (step > upto) {
      char path[2200];
      snprintf(path, sizeof path, "%s/%s", d, name);
      if (remove(path) == 0) removed++;
      continue;
    }
    if (nkeep == cap) {
      cap = cap ? 2 * cap : 16;
      long *k = realloc(keep, (size_t)cap * sizeof *k);
      if (!k) break;
      keep = k;
    }
    keep[nkeep++] = step;
  }
  closedir(dp);
  if (removed)
    fprintf(stderr,
            "mdpore: %s_*.h5: restart at step %ld: removed %ld snapshot(s) written after it\n",
            ser->base, upto, removed);
  if (nkeep) qsort(keep, (size_t)nkeep, sizeof *keep, step_cmp);
  int rc = 0;
  for (long k = 0; k < nkeep && !rc; k++) {
    char path[1100];
    snapshot_series_path(ser, keep[k], path, sizeof path);
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) continue;
    const long count = h5_dataset_rows(f, "particles/id");
    const int rho = H5Lexists(f, "particles/density", H5P_DEFAULT) > 0;
    H5Fclose(f);
    if (count >= 0) rc = series_push(ser, keep[k], keep[k] * s->dt, count, rho);
  }
  free(keep);
  if (!rc && ser->n > 0) rc = write_xdmf(ser);
  return rc;
}

static int snapshot_series_write_unlocked(snapshot_series_t *ser, sim_t *sim) {
  int rank, rc = 0;
  MPI_Comm comm = sim_comm(sim);
  MPI_Comm_rank(comm, &rank);
  particle_set_t set;
  if (gather_particles(sim, 0, 0, &set, NULL)) return -1;
  if (rank == 0) {
    const scene_t *s = sim_scene(sim);
    const long step = sim_step_index(sim);
    char path[1100];
    snapshot_series_path(ser, step, path, sizeof path);
    rc = particle_set_sort_by_id(&set);
    if (rc) fprintf(stderr, "%s: out of memory sorting %ld particles\n", path, set.n);
    if (!rc) rc = snapshot_write_set(path, s, &set, step, step * s->dt);
    if (!rc) rc = series_push(ser, step, step * s->dt, set.n, set.rho != NULL);
    if (!rc) rc = write_xdmf(ser);
  }
  particle_set_free(&set);
  MPI_Bcast(&rc, 1, MPI_INT, 0, comm);
  return rc;
}

/* The public entry points: each whole call under the HDF5 lock (common/hdf5_lock.h). */
int snapshot_write_set(const char *path, const scene_t *s, const particle_set_t *set, long step,
                       double time) {
  hdf5_lock();
  const int rc = snapshot_write_set_unlocked(path, s, set, step, time);
  hdf5_unlock();
  return rc;
}

int snapshot_read(const char *path, const scene_t *s, particle_set_t *out, long *step) {
  hdf5_lock();
  const int rc = snapshot_read_unlocked(path, s, out, step);
  hdf5_unlock();
  return rc;
}

int snapshot_series_resume(snapshot_series_t *ser, const scene_t *s, long upto) {
  hdf5_lock();
  const int rc = snapshot_series_resume_unlocked(ser, s, upto);
  hdf5_unlock();
  return rc;
}

int snapshot_series_write(snapshot_series_t *ser, sim_t *sim) {
  hdf5_lock();
  const int rc = snapshot_series_write_unlocked(ser, sim);
  hdf5_unlock();
  return rc;
}
