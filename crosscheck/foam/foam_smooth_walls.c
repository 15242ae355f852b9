/* --walls smooth: sub-voxel walls reconstructed from the image, by moving the points of the subset
 * mesh after `subsetMesh -overwrite`.
 *
 * Interface: the 0.5 iso-surface of the local solid fraction. The solid fraction at a voxel corner
 * is the mean solid indicator of the 2 x 2 x 2 voxels that share the corner (the smallest
 * symmetric box filter, no free width); between corners it is interpolated trilinearly. This is
 * the surface that marching cubes extracts from the corner-averaged image. At a flat voxel wall
 * the corner values are exactly 1/2, so flat walls (a slit) do not move at all; a box filter of
 * one voxel shifts the level set of a curved surface by about kappa/24 voxels (variance 1/12 per
 * axis), 0.3% of the solid volume of a sphere of radius 10 voxels.
 *
 * Points: each wall point (a mesh point with pore and solid cells around it) moves along the
 * gradient of the solid fraction (central differences at the corners, interpolated) to where the
 * field is 1/2, at most half a voxel along each axis (its dual cell); no crossing there (a feature
 * below the filter's resolution, e.g. a tube one voxel wide) leaves the point where it is. The
 * image is mirrored across the box faces, so points on a box face stay in it (symmetry planes),
 * and the two ends of a periodic sample (equal end slices) move alike. The next R layers of
 * interior points (R = --refine, one voxel) follow by Laplacian smoothing of the displacement
 * (Jacobi, zero beyond the band; points on a box face use neighbours in that face only). Finally
 * every pore cell is checked: where a corner tetrahedron of a hex would fall below 5% of its
 * undeformed volume, the displacements of that cell's points are halved, repeatedly. */
#include "foam_case.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  const mdp_image_t *img;
  int R;              /* fine cells per voxel edge */
  long long N[3];     /* fine cells per box edge */
  double *S;          /* solid fraction at voxel corners, (nx+1)(ny+1)(nz+1) */
  double *G;          /* its gradient at the corners (3 per corner) */
  double (*D)[3];     /* displacement of each lattice point (fine cell units: voxels) */
  unsigned char *tag; /* per lattice point: 0 not a mesh point, 1 interior, 2 wall, 3 band */
} lattice_t;

enum { PT_NONE = 0, PT_INTERIOR = 1, PT_WALL = 2, PT_BAND = 3 };

static long long pidx(const lattice_t *L, long long I, long long J, long long K) {
  return I + (L->N[0] + 1) * (J + (L->N[1] + 1) * K);
}

static int clampi(int v, int lo, int hi) {
  return v < lo ? lo : v > hi ? hi : v;
}

/* Solid indicator of a voxel, the image mirrored across its faces. */
static int solid_at(const mdp_image_t *img, int i, int j, int k) {
  i = i < 0 ? -1 - i : i >= img->nx ? 2 * img->nx - 1 - i : i;
  j = j < 0 ? -1 - j : j >= img->ny ? 2 * img->ny - 1 - j : j;
  k = k < 0 ? -1 - k : k >= img->nz ? 2 * img->nz - 1 - k : k;
  i = clampi(i, 0, img->nx - 1), j = clampi(j, 0, img->ny - 1), k = clampi(k, 0, img->nz - 1);
  return !mdp_image_is_pore(img, mdp_image_index(img, i, j, k));
}

/* Is fine cell (I, J, K) a pore cell (inside the box)? */
static int pore_cell(const lattice_t *L, long long I, long long J, long long K) {
  if (I < 0 || J < 0 || K < 0 || I >= L->N[0] || J >= L->N[1] || K >= L->N[2]) return 0;
  return mdp_image_is_pore(
      L->img, mdp_image_index(L->img, (int)(I / L->R), (int)(J / L->R), (int)(K / L->R)));
}

static double corner_s(const lattice_t *L, int i, int j, int k) {
  const mdp_image_t *m = L->img;
  /* corners beyond the box mirror into it: corner -1 equals corner 1 */
  i = i < 0 ? -i : i > m->nx ? 2 * m->nx - i : i;
  j = j < 0 ? -j : j > m->ny ? 2 * m->ny - j : j;
  k = k < 0 ? -k : k > m->nz ? 2 * m->nz - k : k;
  return L->S[i + (m->nx + 1) * ((size_t)j + (m->ny + 1) * (size_t)k)];
}

/* Trilinear interpolation of the corner solid fraction (and its gradient) at x (voxel units). */
static double field(const lattice_t *L, const double x[3], double grad[3]) {
  const int n[3] = {L->img->nx, L->img->ny, L->img->nz};
  int c[3];
  double w[3];
  for (int a = 0; a < 3; a++) {
    double xa = fmin(fmax(x[a], 0.0), (double)n[a]);
    c[a] = clampi((int)floor(xa), 0, n[a] - 1);
    w[a] = xa - c[a];
  }
  double v = 0;
  if (grad) grad[0] = grad[1] = grad[2] = 0;
  for (int q = 0; q < 8; q++) {
    const int d[3] = {q & 1, (q >> 1) & 1, (q >> 2) & 1};
    double wt = 1;
    for (int a = 0; a < 3; a++) wt *= d[a] ? w[a] : 1 - w[a];
    const int ci = c[0] + d[0], cj = c[1] + d[1], ck = c[2] + d[2];
    v += wt * corner_s(L, ci, cj, ck);
    if (grad) {
      const double *g = L->G + 3 * (ci + (n[0] + 1) * ((size_t)cj + (n[1] + 1) * (size_t)ck));
      for (int a = 0; a < 3; a++) grad[a] += wt * g[a];
    }
  }
  return v;
}

/* Displacement of wall point x onto the 1/2 level, within its dual cell; 0 when none is found. */
static void project(const lattice_t *L, const double x[3], const int on_face[3], double d[3]) {
  const int n[3] = {L->img->nx, L->img->ny, L->img->nz};
  double g[3];
  const double v = field(L, x, g);
  d[0] = d[1] = d[2] = 0;
  if (fabs(v - 0.5) < 1e-12) return;
  for (int a = 0; a < 3; a++)
    if (on_face[a]) g[a] = 0;
  const double gn = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  if (gn < 1e-12) return;
  /* walk down the gradient when the point sits in too much solid, up it otherwise */
  double dir[3], tmax = INFINITY;
  for (int a = 0; a < 3; a++) {
    dir[a] = (v > 0.5 ? -g[a] : g[a]) / gn;
    if (fabs(dir[a]) > 1e-15) {
      double lim = 0.5 / fabs(dir[a]); /* dual cell */
      double to_face = dir[a] > 0 ? (n[a] - x[a]) / dir[a] : -x[a] / dir[a];
      tmax = fmin(tmax, fmin(lim, to_face));
    }
  }
  const int steps = 32;
  double t0 = 0, f0 = v - 0.5;
  for (int s = 1; s <= steps; s++) {
    double t1 = tmax * s / steps, y[3];
    for (int a = 0; a < 3; a++) y[a] = x[a] + t1 * dir[a];
    double f1 = field(L, y, NULL) - 0.5;
    if ((f0 > 0) != (f1 > 0) || f1 == 0) {
      for (int it = 0; it < 50; it++) { /* bisection on [t0, t1] */
        double tm = 0.5 * (t0 + t1), fm;
        for (int a = 0; a < 3; a++) y[a] = x[a] + tm * dir[a];
        fm = field(L, y, NULL) - 0.5;
        if ((fm > 0) == (f0 > 0) && fm != 0)
          t0 = tm, f0 = fm;
        else
          t1 = tm;
      }
      for (int a = 0; a < 3; a++) d[a] = 0.5 * (t0 + t1) * dir[a];
      return;
    }
    t0 = t1, f0 = f1;
  }
}

/* Volume of the hex corner tetrahedra of fine cell (I, J, K), relative to the undeformed one;
 * returns the smallest. */
static double min_corner_tet(const lattice_t *L, long long I, long long J, long long K) {
  double p[8][3];
  const double h = 1.0 / L->R;
  for (int q = 0; q < 8; q++) {
    const int d[3] = {q & 1, (q >> 1) & 1, (q >> 2) & 1};
    const long long id = pidx(L, I + d[0], J + d[1], K + d[2]);
    for (int a = 0; a < 3; a++) p[q][a] = d[a] * h + L->D[id][a];
  }
  double vmin = INFINITY;
  for (int q = 0; q < 8; q++) {
    double e[3][3], sgn = 1;
    for (int a = 0; a < 3; a++) {
      const int nb = q ^ (1 << a);
      for (int b = 0; b < 3; b++) e[a][b] = p[nb][b] - p[q][b];
      if (q & (1 << a)) sgn = -sgn;
    }
    const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                       e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                       e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    vmin = fmin(vmin, sgn * det / (h * h * h));
  }
  return vmin;
}

static void build_fields(lattice_t *L) {
  const mdp_image_t *m = L->img;
  const int cx = m->nx + 1, cy = m->ny + 1, cz = m->nz + 1;
  for (int k = 0; k < cz; k++)
    for (int j = 0; j < cy; j++)
      for (int i = 0; i < cx; i++) {
        int s = 0;
        for (int q = 0; q < 8; q++)
          s += solid_at(m, i - 1 + (q & 1), j - 1 + ((q >> 1) & 1), k - 1 + ((q >> 2) & 1));
        L->S[i + cx * ((size_t)j + cy * (size_t)k)] = s / 8.0;
      }
  for (int k = 0; k < cz; k++)
    for (int j = 0; j < cy; j++)
      for (int i = 0; i < cx; i++) {
        double *g = L->G + 3 * (i + cx * ((size_t)j + cy * (size_t)k));
        g[0] = 0.5 * (corner_s(L, i + 1, j, k) - corner_s(L, i - 1, j, k));
        g[1] = 0.5 * (corner_s(L, i, j + 1, k) - corner_s(L, i, j - 1, k));
        g[2] = 0.5 * (corner_s(L, i, j, k + 1) - corner_s(L, i, j, k - 1));
      }
}

/* Tag mesh points, project wall points, blend into the band, limit to valid cells. Returns 1 when
 * out of memory. */
static int displace(lattice_t *L, mdp_foam_smooth_t *st) {
  const long long *N = L->N;
  const int R = L->R;
  for (long long K = 0; K <= N[2]; K++)
    for (long long J = 0; J <= N[1]; J++)
      for (long long I = 0; I <= N[0]; I++) {
        int pore = 0, solid = 0;
        for (int q = 0; q < 8; q++) {
          long long a = I - 1 + (q & 1), b = J - 1 + ((q >> 1) & 1), c = K - 1 + ((q >> 2) & 1);
          if (a < 0 || b < 0 || c < 0 || a >= N[0] || b >= N[1] || c >= N[2]) continue;
          if (pore_cell(L, a, b, c))
            pore++;
          else
            solid++;
        }
        const long long id = pidx(L, I, J, K);
        L->tag[id] = !pore ? PT_NONE : solid ? PT_WALL : PT_INTERIOR;
        if (L->tag[id] != PT_WALL) continue;
        const double x[3] = {(double)I / R, (double)J / R, (double)K / R};
        const int face[3] = {I == 0 || I == N[0], J == 0 || J == N[1], K == 0 || K == N[2]};
        project(L, x, face, L->D[id]);
        double m = fmax(fabs(L->D[id][0]), fmax(fabs(L->D[id][1]), fabs(L->D[id][2])));
        st->wall_points++;
        st->moved_points += m > 0;
        st->max_move = fmax(st->max_move, m);
      }
  /* band: interior points within R lattice steps of a wall point (in-face for face points) */
  for (long long K = 0; K <= N[2]; K++)
    for (long long J = 0; J <= N[1]; J++)
      for (long long I = 0; I <= N[0]; I++) {
        const long long id = pidx(L, I, J, K);
        if (L->tag[id] != PT_INTERIOR) continue;
        const long long P[3] = {I, J, K};
        int lo[3], hi[3];
        for (int a = 0; a < 3; a++) {
          int face = P[a] == 0 || P[a] == N[a];
          lo[a] = face ? 0 : -R, hi[a] = face ? 0 : R;
        }
        int near = 0;
        for (int c = lo[2]; c <= hi[2] && !near; c++)
          for (int b = lo[1]; b <= hi[1] && !near; b++)
            for (int a = lo[0]; a <= hi[0] && !near; a++) {
              long long q[3] = {I + a, J + b, K + c};
              if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] > N[0] || q[1] > N[1] || q[2] > N[2])
                continue;
              near = L->tag[pidx(L, q[0], q[1], q[2])] == PT_WALL;
            }
        if (near) L->tag[id] = PT_BAND;
      }
  /* Laplacian smoothing of the displacement over the band (Gauss-Seidel sweeps). */
  for (int sweep = 0; sweep < 10 * (R + 1); sweep++)
    for (long long K = 0; K <= N[2]; K++)
      for (long long J = 0; J <= N[1]; J++)
        for (long long I = 0; I <= N[0]; I++) {
          const long long id = pidx(L, I, J, K);
          if (L->tag[id] != PT_BAND) continue;
          const long long P[3] = {I, J, K};
          double sum[3] = {0, 0, 0};
          int cnt = 0;
          for (int a = 0; a < 3; a++) {
            if (P[a] == 0 || P[a] == N[a]) continue; /* face points: in-face neighbours */
            for (int s = -1; s <= 1; s += 2) {
              long long q[3] = {I, J, K};
              q[a] += s;
              const long long nb = pidx(L, q[0], q[1], q[2]);
              if (L->tag[nb] == PT_NONE) continue;
              for (int b = 0; b < 3; b++) sum[b] += L->D[nb][b];
              cnt++;
            }
          }
          for (int b = 0; b < 3; b++) {
            const int face = P[b] == 0 || P[b] == N[b];
            L->D[id][b] = cnt && !face ? sum[b] / cnt : 0;
          }
        }
  /* validity: halve the displacements of any cell whose corner tetrahedra shrink below 5% */
  const long long cells = N[0] * N[1] * N[2];
  /* The cells that fail are the ones whose wall face would fold to a line (a tetrahedron of ~0):
   * any threshold from 1e-3 to 0.2 gives the same permeability to 2e-5 (measured). */
  const double tet_min = 0.05;
  const size_t np = (size_t)(N[0] + 1) * (N[1] + 1) * (N[2] + 1);
  unsigned char *halve = calloc(np, 1), *held = calloc(np / 8 + 1, 1);
  if (!halve || !held) {
    free(halve);
    free(held);
    return 1;
  }
  for (int pass = 0; pass < 12; pass++) {
    long long bad = 0;
    for (long long c = 0; c < cells; c++) {
      const long long I = c % N[0], J = (c / N[0]) % N[1], K = c / (N[0] * N[1]);
      if (!pore_cell(L, I, J, K) || min_corner_tet(L, I, J, K) >= tet_min) continue;
      bad++;
      for (int q = 0; q < 8; q++)
        halve[pidx(L, I + (q & 1), J + ((q >> 1) & 1), K + ((q >> 2) & 1))] = 1;
    }
    if (!bad) break;
    for (size_t p = 0; p < np; p++)
      if (halve[p]) {
        const double f = pass == 11 ? 0 : 0.5;
        for (int b = 0; b < 3; b++) L->D[p][b] *= f;
        if (L->tag[p] == PT_WALL && (L->D[p][0] || L->D[p][1] || L->D[p][2]) &&
            !(held[p / 8] & (1u << p % 8)))
          held[p / 8] |= (unsigned char)(1u << p % 8), st->limited_points++;
        halve[p] = 0;
      }
  }
  free(halve);
  free(held);
  return 0;
}

/* Read the points file, move each point by the displacement of its lattice site, write it back. */
static int rewrite_points(const char *dir, const lattice_t *L, char *err) {
  char path[4200], tmp[4300], line[1024];
  snprintf(path, sizeof path, "%s/constant/polyMesh/points", dir);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *in = fopen(path, "r"), *out = in ? fopen(tmp, "w") : NULL;
  if (!in || !out) {
    snprintf(err, MDP_FOAM_ERR_LEN, "%.1500s: cannot %s: %s", in ? tmp : path,
             in ? "write" : "read", strerror(errno));
    if (in) fclose(in);
    return 1;
  }
  long long n = -1, done = 0;
  int in_header = 0, bad = 0;
  /* header (FoamFile { ... }) and comments are copied; then the count, "(", n "(x y z)", ")" */
  while (n < 0 && fgets(line, sizeof line, in)) {
    fputs(line, out);
    if (strstr(line, "FoamFile")) in_header = 1;
    if (in_header && strchr(line, '}')) {
      in_header = 0;
      continue;
    }
    char *end;
    long long v = strtoll(line, &end, 10);
    if (!in_header && end != line && (*end == '\n' || *end == '\r' || *end == 0)) n = v;
  }
  if (n < 0 || !fgets(line, sizeof line, in) || line[0] != '(') bad = 1;
  if (!bad) fputs(line, out);
  for (; !bad && done < n; done++) {
    double x[3];
    if (fscanf(in, " (%lf %lf %lf)", &x[0], &x[1], &x[2]) != 3) {
      bad = 1;
      break;
    }
    long long P[3];
    for (int a = 0; a < 3; a++) {
      P[a] = llround(x[a] * L->R);
      if (P[a] < 0 || P[a] > L->N[a] || fabs(x[a] * L->R - P[a]) > 1e-6) bad = 1;
    }
    if (bad) break;
    const double *d = L->D[pidx(L, P[0], P[1], P[2])];
    fprintf(out, "(%.15g %.15g %.15g)\n", (double)P[0] / L->R + d[0], (double)P[1] / L->R + d[1],
            (double)P[2] / L->R + d[2]);
  }
  while (!bad && fgets(line, sizeof line, in)) fputs(line, out);
  fclose(in);
  if (bad) {
    fclose(out);
    remove(tmp);
    snprintf(err, MDP_FOAM_ERR_LEN,
             "%.1500s: point %lld: expected %lld points \"(x y z)\" on the blockMesh lattice", path,
             done, n);
    return 1;
  }
  if (fclose(out) != 0 || rename(tmp, path) != 0) {
    snprintf(err, MDP_FOAM_ERR_LEN, "%.1500s: cannot write: %s", path, strerror(errno));
    remove(tmp);
    return 1;
  }
  return 0;
}

int mdp_foam_smooth_walls(const char *dir, const mdp_image_t *img, const mdp_foam_opts_t *o,
                          mdp_foam_smooth_t *st, char *err) {
  memset(st, 0, sizeof *st);
  lattice_t L = {.img = img, .R = o->refine};
  L.N[0] = (long long)img->nx * o->refine, L.N[1] = (long long)img->ny * o->refine;
  L.N[2] = (long long)img->nz * o->refine;
  const size_t corners = (size_t)(img->nx + 1) * (img->ny + 1) * (img->nz + 1);
  const size_t points = (size_t)(L.N[0] + 1) * (L.N[1] + 1) * (L.N[2] + 1);
  L.S = malloc(corners * sizeof *L.S);
  L.G = malloc(3 * corners * sizeof *L.G);
  L.D = calloc(points, sizeof *L.D);
  L.tag = calloc(points, 1);
  int rc = 1;
  if (L.S && L.G && L.D && L.tag) build_fields(&L);
  if (!L.S || !L.G || !L.D || !L.tag || displace(&L, st))
    snprintf(err, MDP_FOAM_ERR_LEN, "smooth walls: out of memory for %zu mesh points", points);
  else
    rc = rewrite_points(dir, &L, err);
  free(L.S);
  free(L.G);
  free(L.D);
  free(L.tag);
  return rc;
}
