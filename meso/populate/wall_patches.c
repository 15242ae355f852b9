/* The wall patch database (wall_patches.h): its file, its cache, the orientations, and the
 * collective load-or-build. The runs and the cutting are in wall_patches_run.c.
 *
 * How a database is made (edge e, density rho, seed S):
 *  - A periodic cubic box of side L = m e, m the smallest integer with L >= 4 rc (the cell lists
 *    need three cutoffs per axis; the fourth is margin): edge 1 -> m = 4, L = 4; edge 0.5 -> m = 8;
 *    edge 1.5 -> m = 3, L = 4.5; edge 2 -> m = 2.
 *  - One species, the water model of physics.md: mDPD A = -40, B = 25, rd = 0.75, gamma = 4.5,
 *    kT = 1, rc = 1, mass 1, velocity Verlet with lambda = 0.5, dt = 0.01, on MPI_COMM_SELF with the
 *    CPU backend (its results do not depend on the thread count, so the run is bitwise
 *    reproducible). round(rho L^3) particles at uniformly random positions (Philox keyed on the run
 *    seed and the particle id), Maxwell-Boltzmann velocities at kT = 1 less their mean.
 *  - WALL_PATCHES_STEPS = 2000 steps (t = 20). Measured on the 4^3 box at rho = 8 (512 particles,
 *    one thread, 5 seeds): the random start's overlaps (closest pair ~ 0.01 rc) heat the box (kT
 *    ~ 12, pressure ~ 400 at step 10); by step ~ 150-200 kT is back within 3% of 1 (the scatter of
 *    a 512-particle box) and the pressure on its plateau (167 +- 2). Over steps 1000-6000 kT
 *    averages 1.004.
 *    After the pressure settled the particles diffuse (D ~ 0.04 rc^2 per unit time): from step 250
 *    to 2000 the mean squared displacement grows by ~ 4 rc^2, i.e. each particle moves ~ 2 rc,
 *    about four neighbour spacings, in the relaxed liquid. So 2000 steps is > 10 times the settling
 *    time, and ~ 1.1-1.4 s per box on one core. At 2000 steps (10 seeds): kT over the second half
 *    0.994-1.013, the closest pair within a patch 0.18-0.26 rc, no step problem reported.
 *  - The box is cut into m^3 cubes: each particle goes to the cube containing it, its position
 *    taken relative to the cube's corner, in [0, e) (in id order within a cube). Cubes are kept
 *    even when empty (small edges: at e = 0.5 and rho = 8 a cube holds 1 particle on average), so
 *    a random pick keeps the mean density. With fewer than 24 cubes per box (e > 4/3: m <= 2) the
 *    run is repeated with further seeds (splitmix64 of S and the run index) until there are at
 *    least 64 patches: ceil(64 / m^3) runs.
 *  - Only rank 0 builds, writes and reads the file; it broadcasts the arrays to the other ranks.
 *  - Processes that need the same file at once (the runs of `mdpore permeability --jobs N`) take
 *    turns on an exclusive lock of "<file>.lock" (flock) while they look for the file and, when it
 *    is missing, build and write it: the first builds it, the others wait and read it (a
 *    message says so). Without the lock each would build it (the same bytes, renamed over each
 *    other: correct, but N times the work at the start of every run). Where no lock can be made
 *    (a read-only folder, a file system without flock) it goes on without one.
 *
 * The file (HDF5, format_version 1): datasets /start (int64, count + 1) and /x (float64, n x 3);
 * root attributes edge, density (float64), seed (uint64), count, format_version,
 * equilibration_steps, runs, cubes_per_box_edge (int64), temperature, temperature_mean (float64)
 * and description (text: the parameters and steps of the run). Written to a temporary file renamed
 * over the target (common/atomic_file.h), without modification times, so the same (edge, density,
 * seed, steps) gives the same bytes. */
#include "common/hdf5_lock.h"
#include "populate/wall_patches.h"
#include "common/atomic_file.h"
#include "common/size_check.h"

#include <errno.h>
#include <fcntl.h>
#include <hdf5.h>
#include <limits.h>
#include <math.h>
#include <pwd.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <unistd.h>

#define PATCH_PATH_LEN 4096

static int fail(char *err, size_t errlen, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, errlen, fmt, ap);
  va_end(ap);
  return -1;
}

/* The shortest "%.Ng" that reads back as v (1, 0.5, 0.1, 8, 6.2). */
static void shortest(double v, char *out, size_t len) {
  for (int p = 1; p <= 17; p++) {
    snprintf(out, len, "%.*g", p, v);
    if (strtod(out, NULL) == v) return;
  }
}

void wall_patches_free(wall_patches_t *p) {
  free(p->start);
  free(p->x);
  p->start = NULL;
  p->x = NULL;
  p->count = 0;
}

void wall_patches_cache_path(double edge, double density, uint64_t seed, char *out, size_t len) {
  char dir[PATCH_PATH_LEN];
  const char *env = getenv("MDPORE_CACHE_DIR"), *xdg = getenv("XDG_CACHE_HOME");
  const char *home = getenv("HOME");
  if (!home || !home[0]) {
    const struct passwd *pw = getpwuid(getuid());
    home = pw && pw->pw_dir ? pw->pw_dir : ".";
  }
  if (env && env[0])
    snprintf(dir, sizeof dir, "%s", env);
  else if (xdg && xdg[0])
    snprintf(dir, sizeof dir, "%s/mdpore", xdg);
  else
    snprintf(dir, sizeof dir, "%s/.cache/mdpore", home);
  char e[32], d[32];
  shortest(edge, e, sizeof e);
  shortest(density, d, sizeof d);
  snprintf(out, len, "%s/wall-patches-e%s-d%s-s%llu.h5", dir, e, d, (unsigned long long)seed);
}

/* The 24 rotations of the cube: an axis permutation (6) and signs (4 of 8) with determinant +1.
 * Even permutations take the sign patterns with product +1, odd ones those with product -1. */
void wall_patch_orient(int o, double edge, const double in[3], double out[3]) {
  static const int perm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},  /* even */
                                 {1, 0, 2}, {0, 2, 1}, {2, 1, 0}}; /* odd */
  static const int sign[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  o = ((o % 24) + 24) % 24;
  const int *pm = perm[o / 4], *sg = sign[o % 4];
  const int flip = o / 4 >= 3 ? -1 : 1; /* odd permutation: every sign reversed */
  const double top = nextafter(edge, 0.0);
  for (int d = 0; d < 3; d++) {
    const double v = in[pm[d]];
    if (sg[d] * flip > 0) {
      out[d] = v;
    } else {
      const double w = edge - v; /* in (0, edge] for v in [0, edge): keep it below edge */
      out[d] = w > top ? top : w < 0.0 ? 0.0 : w;
    }
  }
}

/* ---- writing -------------------------------------------------------------------------------- */

static herr_t attr_put(hid_t loc, const char *name, hid_t ftype, hid_t mtype, const void *v) {
  hid_t sp = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(loc, name, ftype, sp, H5P_DEFAULT, H5P_DEFAULT);
  herr_t e = a < 0 ? -1 : H5Awrite(a, mtype, v);
  if (a >= 0) H5Aclose(a);
  H5Sclose(sp);
  return e < 0 ? -1 : 0;
}

static herr_t attr_text(hid_t loc, const char *name, const char *v) {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, strlen(v) + 1);
  herr_t e = attr_put(loc, name, t, t, v);
  H5Tclose(t);
  return e;
}

static herr_t dataset_put(hid_t loc, const char *name, hid_t ftype, hid_t mtype, const void *data,
                          hsize_t n, hsize_t m) {
  const hsize_t dims[2] = {n, m};
  hid_t sp = H5Screate_simple(m > 1 ? 2 : 1, dims, NULL);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_obj_track_times(dcpl, 0); /* no modification times: the same data, the same bytes */
  hid_t d = H5Dcreate2(loc, name, ftype, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  herr_t e = d < 0 ? -1 : n ? H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) : 0;
  if (d >= 0) H5Dclose(d);
  H5Pclose(dcpl);
  H5Sclose(sp);
  return e < 0 ? -1 : 0;
}

static void describe(const wall_patches_t *p, const wall_patches_run_t *run, char *out,
                     size_t len) {
  char e[32], d[32];
  shortest(p->edge, e, sizeof e);
  shortest(p->density, d, sizeof d);
  const double L = run->cubes * p->edge;
  snprintf(out, len,
           "mdpore wall patch database (mdpore build patches): %d cubes of edge %s rc cut from %d "
           "periodic cubic box(es) of side %d x %s = %.6g rc, one species at %s particles per "
           "rc^3 (%lld particles per box), mDPD A = -40, B = 25, rd = 0.75, gamma = 4.5, kT = 1, "
           "rc = 1, mass 1, velocity Verlet lambda = 0.5, dt = 0.01, CPU backend; random start, "
           "%ld equilibration steps per box, run seeds splitmix64(%llu, run); %ld particles in "
           "all; kT at the last step %.4f, mean kT over the second half %.4f",
           p->count, e, run->runs, run->cubes, e, L, d, llround(p->density * L * L * L), run->steps,
           (unsigned long long)p->seed, p->start[p->count], run->temperature,
           run->temperature_mean);
}

static int wall_patches_write_unlocked(const char *path, const wall_patches_t *p,
                                       const wall_patches_run_t *run, char *err, size_t errlen) {
  char tmp[PATCH_PATH_LEN + 32], text[2048];
  atomic_tmp_name(path, tmp, sizeof tmp);
  describe(p, run, text, sizeof text);
  H5E_auto2_t fn;
  void *cd;
  H5Eget_auto2(H5E_DEFAULT, &fn, &cd);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
  H5Pset_obj_track_times(fcpl, 0);
  hid_t f = H5Fcreate(tmp, H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
  H5Pclose(fcpl);
  if (f < 0) {
    H5Eset_auto2(H5E_DEFAULT, fn, cd);
    return fail(err, errlen, "%s: cannot create the file (%s)", tmp, strerror(errno));
  }
  const long n = p->start[p->count];
  const long count = p->count, version = WALL_PATCHES_FORMAT, steps = run->steps;
  const long runs = run->runs, cubes = run->cubes;
  const unsigned long long seed = p->seed;
  herr_t e = 0;
  e |= attr_put(f, "format_version", H5T_STD_I64LE, H5T_NATIVE_LONG, &version);
  e |= attr_put(f, "edge", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &p->edge);
  e |= attr_put(f, "density", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &p->density);
  e |= attr_put(f, "seed", H5T_STD_U64LE, H5T_NATIVE_ULLONG, &seed);
  e |= attr_put(f, "count", H5T_STD_I64LE, H5T_NATIVE_LONG, &count);
  e |= attr_put(f, "equilibration_steps", H5T_STD_I64LE, H5T_NATIVE_LONG, &steps);
  e |= attr_put(f, "runs", H5T_STD_I64LE, H5T_NATIVE_LONG, &runs);
  e |= attr_put(f, "cubes_per_box_edge", H5T_STD_I64LE, H5T_NATIVE_LONG, &cubes);
  e |= attr_put(f, "temperature", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &run->temperature);
  e |= attr_put(f, "temperature_mean", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &run->temperature_mean);
  e |= attr_text(f, "description", text);
  e |= dataset_put(f, "start", H5T_STD_I64LE, H5T_NATIVE_LONG, p->start, (hsize_t)count + 1, 1);
  e |= dataset_put(f, "x", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, p->x, (hsize_t)n, 3);
  e |= H5Fclose(f) < 0 ? -1 : 0;
  H5Eset_auto2(H5E_DEFAULT, fn, cd);
  if (e) {
    remove(tmp);
    return fail(err, errlen, "%s: writing the wall patch database failed", tmp);
  }
  if (atomic_rename(tmp, path)) return fail(err, errlen, "%s: cannot rename %s over it", path, tmp);
  return 0;
}

/* ---- reading -------------------------------------------------------------------------------- */

/* A scalar attribute of class cls (H5T_FLOAT, H5T_INTEGER) read as mtype. 0 or -1 + message. */
static int attr_get(hid_t f, const char *file, const char *name, H5T_class_t cls, hid_t mtype,
                    void *v, char *err, size_t errlen) {
  const char *what = cls == H5T_FLOAT ? "a scalar float attribute" : "a scalar integer attribute";
  if (H5Aexists(f, name) <= 0)
    return fail(err, errlen, "%s: key '%s': expected %s (missing)", file, name, what);
  hid_t a = H5Aopen(f, name, H5P_DEFAULT);
  hid_t t = a < 0 ? -1 : H5Aget_type(a), sp = a < 0 ? -1 : H5Aget_space(a);
  int rc = 0;
  if (a < 0 || t < 0 || sp < 0) {
    rc = fail(err, errlen, "%s: key '%s': expected %s (unreadable)", file, name, what);
  } else if (H5Tget_class(t) != cls) {
    rc = fail(err, errlen, "%s: key '%s': expected %s (wrong type)", file, name, what);
  } else if (H5Sget_simple_extent_npoints(sp) != 1) {
    rc = fail(err, errlen, "%s: key '%s': expected %s (%lld values)", file, name, what,
              (long long)H5Sget_simple_extent_npoints(sp));
  } else if (H5Aread(a, mtype, v) < 0) {
    rc = fail(err, errlen, "%s: key '%s': expected %s (read failed)", file, name, what);
  }
  if (sp >= 0) H5Sclose(sp);
  if (t >= 0) H5Tclose(t);
  if (a >= 0) H5Aclose(a);
  return rc;
}

static int attr_get_double(hid_t f, const char *file, const char *name, double lo, double hi,
                           double *v, char *err, size_t errlen) {
  if (attr_get(f, file, name, H5T_FLOAT, H5T_NATIVE_DOUBLE, v, err, errlen)) return -1;
  if (!(isfinite(*v) && *v >= lo && *v <= hi))
    return fail(err, errlen, "%s: key '%s': expected a finite value in [%g, %g] (got %g)", file,
                name, lo, hi, *v);
  return 0;
}

static int attr_get_long(hid_t f, const char *file, const char *name, long lo, long hi, long *v,
                         char *err, size_t errlen) {
  if (attr_get(f, file, name, H5T_INTEGER, H5T_NATIVE_LONG, v, err, errlen)) return -1;
  if (*v < lo || *v > hi)
    return fail(err, errlen, "%s: key '%s': expected %ld to %ld (got %ld)", file, name, lo, hi, *v);
  return 0;
}

/* Open a dataset of class cls with n x m values (m == 1: one dimension). Its id, or -1 + message. */
static hid_t dataset_open(hid_t f, const char *file, const char *name, H5T_class_t cls, hsize_t n,
                          hsize_t m, char *err, size_t errlen) {
  const char *what = cls == H5T_FLOAT ? "float" : "integer";
  if (H5Lexists(f, name, H5P_DEFAULT) <= 0) {
    fail(err, errlen, "%s: key '/%s': expected a dataset of %llu x %llu %s values (missing)", file,
         name, (unsigned long long)n, (unsigned long long)m, what);
    return -1;
  }
  hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  hid_t t = d < 0 ? -1 : H5Dget_type(d), sp = d < 0 ? -1 : H5Dget_space(d);
  hsize_t dims[2] = {0, 0};
  const int rank = sp < 0 ? -1 : H5Sget_simple_extent_ndims(sp);
  if (rank >= 1 && rank <= 2) H5Sget_simple_extent_dims(sp, dims, NULL);
  int bad = 0;
  if (d < 0 || t < 0 || sp < 0) {
    bad = fail(err, errlen, "%s: key '/%s': expected a dataset (unreadable)", file, name);
  } else if (H5Tget_class(t) != cls) {
    bad = fail(err, errlen, "%s: key '/%s': expected %s values (wrong type)", file, name, what);
  } else if (rank != (m > 1 ? 2 : 1) || dims[0] != n || (m > 1 && dims[1] != m)) {
    bad = fail(err, errlen,
               "%s: key '/%s': expected %llu x %llu values (got %d dimensions, %llu x "
               "%llu)",
               file, name, (unsigned long long)n, (unsigned long long)m, rank,
               (unsigned long long)dims[0], (unsigned long long)(rank == 2 ? dims[1] : 1));
  }
  if (sp >= 0) H5Sclose(sp);
  if (t >= 0) H5Tclose(t);
  if (bad && d >= 0) H5Dclose(d);
  return bad ? -1 : d;
}

/* Values as text that read back exactly, for the mismatch messages. */
static int mismatch(const char *file, const char *key, double want, double got, char *err,
                    size_t errlen) {
  char w[32], g[32];
  shortest(want, w, sizeof w);
  shortest(got, g, sizeof g);
  return fail(err, errlen, "%s: key '%s': expected %s (the request), the file has %s", file, key, w,
              g);
}

static int read_file(hid_t f, const char *file, double edge, double density, uint64_t seed,
                     wall_patches_t *out, wall_patches_run_t *run, char *err, size_t errlen) {
  long version = 0, count = 0;
  double fe = 0, fd = 0;
  unsigned long long fs = 0;
  if (attr_get_long(f, file, "format_version", 0, 1L << 30, &version, err, errlen)) return -1;
  if (version != WALL_PATCHES_FORMAT)
    return fail(err, errlen, "%s: key 'format_version': expected %d (got %ld)", file,
                WALL_PATCHES_FORMAT, version);
  if (attr_get_double(f, file, "edge", WALL_PATCHES_EDGE_MIN, WALL_PATCHES_EDGE_MAX, &fe, err,
                      errlen))
    return -1;
  if (fe != edge) return mismatch(file, "edge", edge, fe, err, errlen);
  if (attr_get_double(f, file, "density", 1e-300, WALL_PATCHES_DENSITY_MAX, &fd, err, errlen))
    return -1;
  if (fd != density) return mismatch(file, "density", density, fd, err, errlen);
  if (attr_get(f, file, "seed", H5T_INTEGER, H5T_NATIVE_ULLONG, &fs, err, errlen)) return -1;
  if (fs != (unsigned long long)seed)
    return fail(err, errlen, "%s: key 'seed': expected %llu (the request), the file has %llu", file,
                (unsigned long long)seed, fs);
  if (attr_get_long(f, file, "count", 24, 1L << 30, &count, err, errlen)) return -1;
  wall_patches_run_t r;
  long steps = 0, runs = 0, cubes = 0;
  if (attr_get_long(f, file, "equilibration_steps", 0, 1L << 40, &steps, err, errlen) ||
      attr_get_long(f, file, "runs", 1, 1L << 30, &runs, err, errlen) ||
      attr_get_long(f, file, "cubes_per_box_edge", 1, 1L << 20, &cubes, err, errlen) ||
      attr_get_double(f, file, "temperature", 0.0, 1e6, &r.temperature, err, errlen) ||
      attr_get_double(f, file, "temperature_mean", 0.0, 1e6, &r.temperature_mean, err, errlen))
    return -1;
  r.steps = steps;
  r.runs = (int)runs;
  r.cubes = (int)cubes;
  if (H5Aexists(f, "description") <= 0)
    return fail(err, errlen, "%s: key 'description': expected a text attribute (missing)", file);
  {
    hid_t a = H5Aopen(f, "description", H5P_DEFAULT), t = a < 0 ? -1 : H5Aget_type(a);
    const int text = t >= 0 && H5Tget_class(t) == H5T_STRING;
    if (t >= 0) H5Tclose(t);
    if (a >= 0) H5Aclose(a);
    if (!text)
      return fail(err, errlen, "%s: key 'description': expected a text attribute (wrong type)",
                  file);
  }
  memset(out, 0, sizeof *out);
  char why[320];
  if (mdp_size_check((double)count + 1, (double)(1L << 30) + 1, sizeof *out->start,
                     "entries of '/start'", why, sizeof why))
    return fail(err, errlen, "%s: key 'count': %s", file, why);
  out->start = malloc(((size_t)count + 1) * sizeof *out->start);
  if (!out->start) return fail(err, errlen, "%s: out of memory (%ld patches)", file, count);
  hid_t d = dataset_open(f, file, "start", H5T_INTEGER, (hsize_t)count + 1, 1, err, errlen);
  if (d < 0) goto bad;
  herr_t e = H5Dread(d, H5T_NATIVE_LONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, out->start);
  H5Dclose(d);
  if (e < 0) {
    fail(err, errlen, "%s: key '/start': expected %ld integers (read failed)", file, count + 1);
    goto bad;
  }
  if (out->start[0] != 0) {
    fail(err, errlen, "%s: key '/start': expected start[0] = 0 (got %ld)", file, out->start[0]);
    goto bad;
  }
  for (long p = 0; p < count; p++)
    if (out->start[p + 1] < out->start[p]) {
      fail(err, errlen,
           "%s: key '/start': expected non-decreasing values (start[%ld] = %ld > "
           "start[%ld] = %ld)",
           file, p, out->start[p], p + 1, out->start[p + 1]);
      goto bad;
    }
  const long n = out->start[count];
  if (n < 1) {
    fail(err, errlen, "%s: key '/start': expected at least one particle (start[count] = %ld)", file,
         n);
    goto bad;
  }
  d = dataset_open(f, file, "x", H5T_FLOAT, (hsize_t)n, 3, err, errlen);
  if (d < 0) goto bad; /* the message says n x 3 with n = start[count] */
  /* every rank holds the database (wall_patches_load_or_build_steps) */
  if (mdp_size_check((double)n, (double)LONG_MAX / 24, 3 * sizeof *out->x,
                     "particles of '/x' (start[count])", why, sizeof why)) {
    H5Dclose(d);
    fail(err, errlen, "%s: key '/x': %s", file, why);
    goto bad;
  }
  out->x = malloc((size_t)n * 3 * sizeof *out->x);
  e = out->x ? H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out->x) : -1;
  H5Dclose(d);
  if (e < 0) {
    fail(err, errlen, "%s: key '/x': expected %ld x 3 floats (read failed)", file, n);
    goto bad;
  }
  for (long i = 0; i < 3 * n; i++)
    if (!(out->x[i] >= 0.0 && out->x[i] < fe)) {
      char g[32];
      shortest(fe, g, sizeof g);
      fail(err, errlen,
           "%s: key '/x': expected positions in [0, edge = %s) (particle %ld, %c = %g)", file, g,
           i / 3, "xyz"[i % 3], out -> x[i]);
      goto bad;
    }
  out->edge = fe;
  out->density = fd;
  out->seed = (uint64_t)fs;
  out->count = (int)count;
  if (run) *run = r;
  return 0;
bad:
  wall_patches_free(out);
  return -1;
}

static int wall_patches_read_unlocked(const char *path, double edge, double density, uint64_t seed,
                                      wall_patches_t *out, wall_patches_run_t *run, char *err,
                                      size_t errlen) {
  memset(out, 0, sizeof *out);
  H5E_auto2_t fn;
  void *cd;
  H5Eget_auto2(H5E_DEFAULT, &fn, &cd);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  int rc = -1;
  hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0)
    fail(err, errlen, "%s: cannot open as an HDF5 wall patch database", path);
  else
    rc = read_file(f, path, edge, density, seed, out, run, err, errlen);
  if (f >= 0) H5Fclose(f);
  H5Eset_auto2(H5E_DEFAULT, fn, cd);
  return rc;
}

/* ---- load or build (collective) --------------------------------------------------------------- */

/* An exclusive lock on "<file>.lock", held until the descriptor is closed (-1: none could be
 * taken). Says on stderr when it waits for another process. */
static int lock_database(const char *file, int *waited) {
  char lock[PATCH_PATH_LEN + 8];
  *waited = 0;
  snprintf(lock, sizeof lock, "%s.lock", file);
  const int fd = open(lock, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return -1;
  if (flock(fd, LOCK_EX | LOCK_NB) == 0) return fd;
  if (errno == EWOULDBLOCK) {
    fprintf(stderr, "mdpore: wall patches: %s: another process is building it: waiting\n", file);
    *waited = 1;
    while (flock(fd, LOCK_EX) != 0)
      if (errno != EINTR) {
        close(fd);
        return -1;
      }
    return fd;
  }
  close(fd);
  return -1;
}

/* Rank 0: the database into out (read, or built and written and read back), under the file's lock.
 */
static int load_locked(const char *file, int cached, double edge, double density, uint64_t seed,
                       long steps, wall_patches_t *out, wall_patches_run_t *run, char *err,
                       size_t errlen);

static int load_on_root(const char *path, double edge, double density, uint64_t seed, long steps,
                        wall_patches_t *out, wall_patches_run_t *run, char *err, size_t errlen) {
  char file[PATCH_PATH_LEN] = "";
  const int cached = !path || !path[0];
  if (cached) {
    wall_patches_cache_path(edge, density, seed, file, sizeof file);
    char dir[PATCH_PATH_LEN];
    snprintf(dir, sizeof dir, "%s", file);
    char *slash = strrchr(dir, '/');
    if (slash && slash != dir) *slash = 0;
    if (slash && slash != dir && make_dirs(dir)) {
      fprintf(stderr,
              "mdpore: wall patches: cannot create the cache directory %s: building the "
              "database in memory, not cached\n",
              dir);
      file[0] = 0;
    }
  } else {
    snprintf(file, sizeof file, "%s", path);
  }
  int waited = 0;
  const int lock = file[0] ? lock_database(file, &waited) : -1;
  if (waited && access(file, F_OK) == 0)
    fprintf(stderr, "mdpore: wall patches: %s: built by the other process, read\n", file);
  const int rc = load_locked(file, cached, edge, density, seed, steps, out, run, err, errlen);
  if (lock >= 0) close(lock); /* releases the lock */
  return rc;
}

static int load_locked(const char *file, int cached, double edge, double density, uint64_t seed,
                       long steps, wall_patches_t *out, wall_patches_run_t *run, char *err,
                       size_t errlen) {
  if (file[0] && access(file, F_OK) == 0)
    return wall_patches_read(file, edge, density, seed, out, run, err, errlen);
  if (wall_patches_build(edge, density, seed, steps, out, run, err, errlen)) return -1;
  if (!file[0]) return 0;
  if (wall_patches_write(file, out, run, err, errlen)) {
    if (!cached) {
      wall_patches_free(out);
      return -1;
    }
    fprintf(stderr, "mdpore: wall patches: %s; using the database in memory, not cached\n", err);
    return 0;
  }
  wall_patches_free(out); /* every rank gets what the file holds */
  return wall_patches_read(file, edge, density, seed, out, run, err, errlen);
}

int wall_patches_load_or_build_steps(const char *path, double edge, double density, uint64_t seed,
                                     long steps, MPI_Comm comm, wall_patches_t *out,
                                     wall_patches_run_t *run, char *err, size_t errlen) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  memset(out, 0, sizeof *out);
  wall_patches_run_t r = {0};
  int rc = 0;
  if (rank == 0) rc = load_on_root(path, edge, density, seed, steps, out, &r, err, errlen);
  /* status, then the message or the arrays */
  long head[6] = {rc,      out->count, out->count ? out->start[out->count] : 0,
                  r.steps, r.runs,     r.cubes};
  MPI_Bcast(head, 6, MPI_LONG, 0, comm);
  if (head[0]) {
    char msg[1024];
    if (rank == 0) snprintf(msg, sizeof msg, "%s", err);
    MPI_Bcast(msg, sizeof msg, MPI_CHAR, 0, comm);
    if (rank != 0) snprintf(err, errlen, "%s", msg);
    return -1;
  }
  double vals[4] = {out->edge, out->density, r.temperature, r.temperature_mean};
  uint64_t s64 = out->seed;
  MPI_Bcast(vals, 4, MPI_DOUBLE, 0, comm);
  MPI_Bcast(&s64, 1, MPI_UINT64_T, 0, comm);
  const long count = head[1], n = head[2];
  int ok = 1;
  if (rank != 0) {
    out->start = malloc(((size_t)count + 1) * sizeof *out->start);
    out->x = malloc((size_t)n * 3 * sizeof *out->x);
    ok = out->start && out->x;
    out->edge = vals[0];
    out->density = vals[1];
    out->seed = s64;
    out->count = (int)count;
  }
  int all_ok = 0;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, comm);
  if (!all_ok) {
    wall_patches_free(out);
    return fail(err, errlen, "wall patches: out of memory for %ld patches on some rank", count);
  }
  MPI_Bcast(out->start, (int)count + 1, MPI_LONG, 0, comm);
  for (long off = 0; off < 3 * n; off += 1L << 28) { /* counts fit an int */
    const long k = 3 * n - off < (1L << 28) ? 3 * n - off : 1L << 28;
    MPI_Bcast(out->x + off, (int)k, MPI_DOUBLE, 0, comm);
  }
  if (run) {
    *run = (wall_patches_run_t){.steps = head[3],
                                .runs = (int)head[4],
                                .cubes = (int)head[5],
                                .temperature = vals[2],
                                .temperature_mean = vals[3]};
  }
  return 0;
}

int wall_patches_load_or_build(const char *path, double edge, double density, uint64_t seed,
                               MPI_Comm comm, wall_patches_t *out, char *err, size_t errlen) {
  return wall_patches_load_or_build_steps(path, edge, density, seed, WALL_PATCHES_STEPS, comm, out,
                                          NULL, err, errlen);
}

/* The public entry points: each whole call under the HDF5 lock (common/hdf5_lock.h). */
int wall_patches_write(const char *path, const wall_patches_t *p, const wall_patches_run_t *run,
                       char *err, size_t errlen) {
  hdf5_lock();
  const int rc = wall_patches_write_unlocked(path, p, run, err, errlen);
  hdf5_unlock();
  return rc;
}

int wall_patches_read(const char *path, double edge, double density, uint64_t seed,
                      wall_patches_t *out, wall_patches_run_t *run, char *err, size_t errlen) {
  hdf5_lock();
  const int rc = wall_patches_read_unlocked(path, edge, density, seed, out, run, err, errlen);
  hdf5_unlock();
  return rc;
}
