/* Penetration count of a geometry scene (penetration.h). */
#include "analysis/penetration.h"
#include "scene/scene_geometry.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

/* Breadth-first layers (26-connected, periodic along periodic axes) from the voxels whose label
 * class is `from_pore` into the others: each reached voxel gets sign x (layer x voxel edge). */
static int layer_distance(penetration_map_t *m, const mdp_image_t *img, int from_pore, float sign) {
  const size_t n = mdp_image_count(img);
  size_t *queue = n > SIZE_MAX / sizeof(size_t) ? NULL : malloc((n ? n : 1) * sizeof(size_t));
  if (!queue) return -1;
  unsigned char *seen = calloc(n ? n : 1, 1);
  if (!seen) {
    free(queue);
    return -1;
  }
  size_t head = 0, tail = 0;
  for (size_t i = 0; i < n; i++)
    if ((mdp_image_is_pore(img, i) != 0) == (from_pore != 0)) {
      seen[i] = 1;
      queue[tail++] = i;
    }
  const int *N = m->n;
  while (head < tail) {
    const size_t v = queue[head++];
    const int c[3] = {(int)(v % (size_t)N[0]), (int)((v / (size_t)N[0]) % (size_t)N[1]),
                      (int)(v / ((size_t)N[0] * (size_t)N[1]))};
    const float dv = seen[v] == 1 ? 0.0f : m->depth[v];
    for (int dz = -1; dz <= 1; dz++)
      for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
          const int o[3] = {dx, dy, dz};
          int q[3], ok = 1;
          for (int d = 0; d < 3; d++) {
            q[d] = c[d] + o[d];
            if (q[d] < 0 || q[d] >= N[d]) {
              if (!m->scene->periodic[d]) ok = 0;
              q[d] = (q[d] + N[d]) % N[d];
            }
          }
          if (!ok) continue;
          const size_t w = (size_t)q[0] + (size_t)N[0] * ((size_t)q[1] + (size_t)N[1] * q[2]);
          if (seen[w]) continue;
          seen[w] = 2;
          m->depth[w] = dv + sign * (float)m->h;
          queue[tail++] = w;
        }
  }
  free(seen);
  free(queue);
  return 0;
}

/* The signed depth map: solid voxels by their layer distance from the pore (> 0), pore voxels by
 * minus their layer distance from the solid (-FLT_MAX where no solid exists). */
static int depth_map(penetration_map_t *m, const mdp_image_t *img) {
  const size_t n = mdp_image_count(img);
  for (size_t i = 0; i < n; i++) m->depth[i] = mdp_image_is_pore(img, i) ? -FLT_MAX : 0.0f;
  if (layer_distance(m, img, 1, 1.0f) || layer_distance(m, img, 0, -1.0f)) return -1;
  for (size_t i = 0; i < n; i++)
    if (m->depth[i] <= (float)-m->core_rc) m->core_voxels++;
  return 0;
}

int penetration_map_create(penetration_map_t *m, const scene_t *s, char *err, size_t errlen) {
  memset(m, 0, sizeof *m);
  m->scene = s;
  if (!s->geometry.on) return 0;
  mdp_image_t img;
  if (scene_geometry_read_image(s, &img, err, errlen)) return -1;
  m->n[0] = img.nx;
  m->n[1] = img.ny;
  m->n[2] = img.nz;
  m->h = s->geometry.rc_per_voxel;
  m->core_rc = MESO_PORE_CORE_RC;
  scene_geometry_grid(s, &img, &m->grid);
  const size_t n = mdp_image_count(&img);
  m->depth = malloc((n ? n : 1) * sizeof(float));
  if (!m->depth || depth_map(m, &img)) {
    snprintf(err, errlen, "%s: penetration count: out of memory for %zu voxels", s->file, n);
    mdp_image_free(&img);
    penetration_map_free(m);
    return -1;
  }
  mdp_image_free(&img);
  m->on = 1;
  return 0;
}

void penetration_map_free(penetration_map_t *m) {
  free(m->depth);
  m->depth = NULL;
  m->on = 0;
}

void penetration_count(const penetration_map_t *m, sim_t *sim, penetration_t *out) {
  memset(out, 0, sizeof *out);
  out->id = -1;
  if (!m->on) return;
  const scene_t *s = m->scene;
  const particles_t *p = sim_particles(sim);
  struct {
    double depth;
    int rank;
  } deepest = {-1.0, 0};
  MPI_Comm comm = sim_comm(sim);
  MPI_Comm_rank(comm, &deepest.rank);
  long count = 0, core = 0;
  int best = -1, best_voxel[3] = {0, 0, 0};
  const float core_depth = (float)-m->core_rc;
  for (int i = 0; i < p->n_local; i++) {
    if (s->species[p->species[i]].frozen) continue;
    const double x[3] = {p->x[0][i], p->x[1][i], p->x[2][i]};
    const long idx = voxel_grid_index(&m->grid, x);
    const float d = idx >= 0 ? m->depth[idx] : 0.0f;
    if (idx >= 0 && d <= core_depth) core++;
    if (d <= 0.0f) continue;
    count++;
    if (d > deepest.depth) {
      deepest.depth = d;
      best = i;
      best_voxel[0] = (int)(idx % m->n[0]);
      best_voxel[1] = (int)((idx / m->n[0]) % m->n[1]);
      best_voxel[2] = (int)(idx / ((long)m->n[0] * m->n[1]));
    }
  }
  MPI_Allreduce(&count, &out->count, 1, MPI_LONG, MPI_SUM, comm);
  MPI_Allreduce(&core, &out->core_count, 1, MPI_LONG, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, &deepest, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  if (out->count == 0) return;
  out->max_depth = deepest.depth;
  /* the deepest particle, from the rank that holds it */
  double rec[7] = {0};
  int me;
  MPI_Comm_rank(comm, &me);
  if (me == deepest.rank && best >= 0) {
    rec[0] = (double)p->id[best];
    for (int d = 0; d < 3; d++) {
      rec[1 + d] = p->x[d][best];
      rec[4 + d] = best_voxel[d];
    }
  }
  MPI_Bcast(rec, 7, MPI_DOUBLE, deepest.rank, comm);
  out->id = (int64_t)rec[0];
  for (int d = 0; d < 3; d++) {
    out->x[d] = rec[1 + d];
    out->voxel[d] = (int)rec[4 + d];
  }
}
