/* LAMMPS data files (atomic style): reader and writer. */
#include "populate/lammps_data.h"
#include "common/atomic_file.h"
#include "common/size_check.h"
#include "io/gather.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LINE_LEN 4096

typedef struct {
  const char *path;
  FILE *fp;
  long line;
  char buf[LINE_LEN];
} reader_t;

/* Next line with comments stripped; returns NULL at end of file. */
static char *next_line(reader_t *r) {
  if (!fgets(r->buf, sizeof r->buf, r->fp)) return NULL;
  r->line++;
  char *h = strchr(r->buf, '#');
  if (h) *h = 0;
  r->buf[strcspn(r->buf, "\r\n")] = 0; /* messages quote the line without its end */
  return r->buf;
}

static int blank(const char *s) {
  for (; *s; s++)
    if (*s != ' ' && *s != '\t' && *s != '\r' && *s != '\n') return 0;
  return 1;
}

static int fail(reader_t *r, const char *fmt, const char *what) {
  fprintf(stderr, "%s:%ld: ", r->path, r->line);
  fprintf(stderr, fmt, what);
  fputc('\n', stderr);
  return -1;
}

/* Skip blank lines up to the first line of a section body. */
static char *section_body(reader_t *r) {
  char *l;
  while ((l = next_line(r)) && blank(l)) {
  }
  return l;
}

static long find_id(const int64_t *sorted_ids, const long *order, long n, int64_t id) {
  long lo = 0, hi = n - 1;
  while (lo <= hi) {
    const long mid = (lo + hi) / 2;
    if (sorted_ids[mid] == id) return order[mid];
    if (sorted_ids[mid] < id)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

/* qsort's comparator context: one per thread (the replicas of mdpore run --replicas) */
static _Thread_local const int64_t *cmp_ids;
static int cmp_order(const void *a, const void *b) {
  const int64_t x = cmp_ids[*(const long *)a], y = cmp_ids[*(const long *)b];
  return (x > y) - (x < y);
}

/* A whole word as an integer / a finite number; 0 or -1. */
static int parse_long(const char *w, long *v) {
  char *end;
  errno = 0;
  *v = strtol(w, &end, 10);
  return end == w || *end || errno ? -1 : 0;
}

static int parse_finite(const char *w, double *v) {
  char *end;
  errno = 0;
  *v = strtod(w, &end);
  return end == w || *end || errno || !isfinite(*v) ? -1 : 0;
}

/* The first id that appears twice among n ids, or -1 when all differ. */
static int64_t duplicate_id(const int64_t *ids, long n) {
  long *order = malloc((size_t)(n > 0 ? n : 1) * sizeof *order);
  int64_t dup = -1;
  if (!order) return -1;
  for (long i = 0; i < n; i++) order[i] = i;
  cmp_ids = ids;
  qsort(order, (size_t)n, sizeof *order, cmp_order);
  for (long i = 1; i < n && dup < 0; i++)
    if (ids[order[i]] == ids[order[i - 1]]) dup = ids[order[i]];
  free(order);
  return dup;
}

int lammps_data_read(const char *path, const scene_t *s, particle_set_t *out) {
  reader_t r = {.path = path};
  memset(out, 0, sizeof *out);
  if (!(r.fp = fopen(path, "r"))) {
    fprintf(stderr, "%s: cannot open LAMMPS data file: %s\n", path, strerror(errno));
    return -1;
  }
  long natoms = -1, ntypes = -1, file_bytes = 0;
  if (fseek(r.fp, 0, SEEK_END) == 0) file_bytes = ftell(r.fp);
  rewind(r.fp);
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  int have_box[3] = {0, 0, 0}, have_atoms = 0, rc = -1;
  char *l = next_line(&r); /* the first line is a title */
  while ((l = next_line(&r))) {
    if (blank(l)) continue;
    char w1[64] = "", w2[64] = "", w3[64] = "", w4[64] = "";
    const int nw = sscanf(l, "%63s %63s %63s %63s", w1, w2, w3, w4);
    if (nw >= 2 && !strcmp(w2, "atoms")) {
      /* every atom needs a line of at least 10 bytes ("1 1 0 0 0") in the Atoms section */
      if (parse_long(w1, &natoms) || natoms < 0 || natoms > file_bytes / 10) {
        fprintf(stderr,
                "%s:%ld: header 'N atoms': expected a count of atoms that fits in this file of "
                "%ld bytes (got '%s')\n",
                path, r.line, file_bytes, w1);
        goto done;
      }
    } else if (nw >= 3 && !strcmp(w2, "atom") && !strcmp(w3, "types")) {
      if (parse_long(w1, &ntypes)) ntypes = -1;
      if (ntypes < 1 || ntypes > s->n_species) {
        fprintf(stderr,
                "%s:%ld: expected at most %d atom types, the scene's species in order (got %ld)\n",
                path, r.line, s->n_species, ntypes);
        goto done;
      }
    } else if (nw >= 4 && w3[1] == 'l' && w3[2] == 'o' && w4[1] == 'h' && w4[2] == 'i' &&
               w3[0] == w4[0] && w3[0] >= 'x' && w3[0] <= 'z') {
      const int d = w3[0] - 'x';
      if (parse_finite(w1, &lo[d]) || parse_finite(w2, &hi[d]) || !(hi[d] > lo[d])) {
        fprintf(stderr, "%s:%ld: header '%s %s': expected two finite numbers lo < hi (got %s %s)\n",
                path, r.line, w3, w4, w1, w2);
        goto done;
      }
      have_box[d] = 1;
    } else if (nw >= 3 && !strcmp(w3, "xz")) {
      fail(&r, "expected an orthogonal box (got a triclinic tilt line%s)", "");
      goto done;
    } else if (!strcmp(w1, "Masses")) {
      l = section_body(&r);
      for (long k = 0; k < ntypes && l; k++, l = next_line(&r)) {
        int type;
        double m;
        if (sscanf(l, "%d %lf", &type, &m) != 2 || type < 1 || type > ntypes || !(m > 0) ||
            !isfinite(m)) {
          fail(&r, "Masses: expected 'type mass' with type in 1..ntypes and a mass > 0 (got '%s')",
               l);
          goto done;
        }
        if (fabs(m - s->species[type - 1].mass) > 1e-12 * m)
          fprintf(stderr,
                  "%s:%ld: warning: mass of type %d is %g but scene species '%s' has %g (using the "
                  "scene's)\n",
                  path, r.line, type, m, s->species[type - 1].name, s->species[type - 1].mass);
      }
    } else if (!strcmp(w1, "Atoms")) {
      if (have_atoms) {
        fail(&r, "expected one Atoms section (got a second one)%s", "");
        goto done;
      }
      if (nw >= 2 && strcmp(w2, "atomic") && strcmp(w2, "#")) {
        fail(&r, "expected atom style 'atomic' (got '%s')", w2);
        goto done;
      }
      if (natoms < 0 || ntypes < 0 || !have_box[0] || !have_box[1] || !have_box[2]) {
        fail(
            &r,
            "expected the header lines 'N atoms', 'M atom types' and the box bounds before Atoms%s",
            "");
        goto done;
      }
      for (int d = 0; d < 3; d++)
        if (fabs(lo[d] - s->box_lo[d]) > 1e-9 * (1 + fabs(lo[d])) ||
            fabs(hi[d] - s->box_hi[d]) > 1e-9 * (1 + fabs(hi[d]))) {
          fprintf(stderr, "%s: box bounds %c: expected the scene's box %g %g (got %g %g)\n", path,
                  'x' + d, s->box_lo[d], s->box_hi[d], lo[d], hi[d]);
          goto done;
        }
      char why[320];
      if (mdp_size_check((double)natoms, 2147483646.0, particle_set_bytes(0, 0), "atoms", why,
                         sizeof why)) {
        fprintf(stderr, "%s: key 'atoms': %s\n", path, why);
        goto done;
      }
      if (particle_set_alloc(out, natoms, 0, 0)) {
        fprintf(stderr, "%s: out of memory for %ld atoms\n", path, natoms);
        goto done;
      }
      l = section_body(&r);
      for (long i = 0; i < natoms; i++, l = next_line(&r)) {
        long id;
        int type, im[3];
        double x[3];
        const int got = l ? sscanf(l, "%ld %d %lf %lf %lf %d %d %d", &id, &type, &x[0], &x[1],
                                   &x[2], &im[0], &im[1], &im[2])
                          : 0;
        if (got != 5 && got != 8) {
          fail(&r, "Atoms: expected 'id type x y z [ix iy iz]' (got '%s')", l ? l : "end of file");
          goto done;
        }
        if (type < 1 || type > ntypes) {
          fprintf(stderr, "%s:%ld: Atoms: expected an atom type in 1..%ld (got %d)\n", path, r.line,
                  ntypes, type);
          goto done;
        }
        if (id < 1 || !isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2])) {
          fail(&r, "Atoms: expected an id >= 1 and finite coordinates (got '%s')", l);
          goto done;
        }
        out->id[i] = id;
        out->species[i] = type - 1;
        for (int d = 0; d < 3; d++) out->x[3 * i + d] = x[d];
      }
      have_atoms = 1;
      const int64_t dup = duplicate_id(out->id, natoms);
      if (dup >= 0) {
        fprintf(stderr, "%s: Atoms: expected each atom id once (got id %lld twice)\n", path,
                (long long)dup);
        goto done;
      }
    } else if (!strcmp(w1, "Velocities")) {
      if (!have_atoms) {
        fail(&r, "expected the Atoms section before Velocities%s", "");
        goto done;
      }
      if (out->has_v) {
        fail(&r, "expected one Velocities section (got a second one)%s", "");
        goto done;
      }
      long *order = malloc((size_t)(natoms > 0 ? natoms : 1) * sizeof *order);
      int64_t *sorted = malloc((size_t)(natoms > 0 ? natoms : 1) * sizeof *sorted);
      if (!order || !sorted) {
        free(order);
        free(sorted);
        fprintf(stderr, "%s: out of memory for %ld atoms\n", path, natoms);
        goto done;
      }
      for (long i = 0; i < natoms; i++) order[i] = i;
      cmp_ids = out->id;
      qsort(order, (size_t)natoms, sizeof *order, cmp_order);
      for (long i = 0; i < natoms; i++) sorted[i] = out->id[order[i]];
      l = section_body(&r);
      int bad = 0;
      for (long i = 0; i < natoms && !bad; i++, l = next_line(&r)) {
        long id;
        double v[3];
        long k = -1;
        if (!l || sscanf(l, "%ld %lf %lf %lf", &id, &v[0], &v[1], &v[2]) != 4 || !isfinite(v[0]) ||
            !isfinite(v[1]) || !isfinite(v[2]) || (k = find_id(sorted, order, natoms, id)) < 0) {
          fail(&r,
               "Velocities: expected 'id vx vy vz' with an id from Atoms and finite velocities "
               "(got '%s')",
               l ? l : "end of file");
          bad = 1;
          break;
        }
        for (int d = 0; d < 3; d++) out->v[3 * k + d] = v[d];
      }
      free(order);
      free(sorted);
      if (bad) goto done;
      out->has_v = 1;
    } else if (w1[0] >= 'A' && w1[0] <= 'Z') {
      fail(&r, "expected a section of an atomic-style file: Masses, Atoms, Velocities (got '%s')",
           w1);
      goto done;
    }
  }
  if (!have_atoms) {
    fprintf(stderr, "%s: expected an Atoms section (got none)\n", path);
    goto done;
  }
  rc = 0;
done:
  fclose(r.fp);
  if (rc) particle_set_free(out);
  return rc;
}

int lammps_data_read_bcast(const char *path, const scene_t *s, MPI_Comm comm, particle_set_t *out) {
  int rank, rc = 0;
  MPI_Comm_rank(comm, &rank);
  memset(out, 0, sizeof *out);
  if (rank == 0) rc = lammps_data_read(path, s, out);
  MPI_Bcast(&rc, 1, MPI_INT, 0, comm);
  if (rc) return -1;
  return particle_set_bcast(out, 0, comm);
}

int lammps_data_write(const char *path, const scene_t *s, const particle_set_t *set, long step) {
  char tmp[SCENE_PATH_LEN + 32];
  FILE *fp = atomic_open(path, tmp, sizeof tmp);
  if (!fp) return -1;
  fprintf(fp, "LAMMPS data file written by mdpore (scene %s, step %ld)\n\n", s->name, step);
  fprintf(fp, "%ld atoms\n%d atom types\n\n", set->n, s->n_species);
  for (int d = 0; d < 3; d++)
    fprintf(fp, "%.17g %.17g %clo %chi\n", s->box_lo[d], s->box_hi[d], 'x' + d, 'x' + d);
  fprintf(fp, "\nMasses\n\n");
  for (int k = 0; k < s->n_species; k++)
    fprintf(fp, "%d %.17g # %s\n", k + 1, s->species[k].mass, s->species[k].name);
  fprintf(fp, "\nAtoms # atomic\n\n");
  for (long i = 0; i < set->n; i++)
    fprintf(fp, "%lld %d %.17g %.17g %.17g\n", (long long)set->id[i], set->species[i] + 1,
            set->x[3 * i], set->x[3 * i + 1], set->x[3 * i + 2]);
  fprintf(fp, "\nVelocities\n\n");
  for (long i = 0; i < set->n; i++)
    fprintf(fp, "%lld %.17g %.17g %.17g\n", (long long)set->id[i], set->v[3 * i], set->v[3 * i + 1],
            set->v[3 * i + 2]);
  return atomic_commit(fp, tmp, path);
}
