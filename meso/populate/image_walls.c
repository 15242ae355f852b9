/* Wall particles from a segmented image (image_walls.h, docs/walls.md; physics.md section 3, Li
 * et al. JCP 355 (2018) 534, section 2.3): the image as the box sees it, the pore clusters that get
 * fluid, an exact Euclidean distance transform of the pore space to find the solid voxels within the
 * wall thickness, and per wall voxel a patch of the database in one of the 24 cube orientations. */
#include "populate/image_walls.h"
#include "populate/init_config.h"
#include "engine/memory_plan.h"
#include "scene/scene_geometry.h"

#include <Random123/philox.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define EDT_INF UINT32_MAX
enum { TAG_PATCH = 0x77616c6c }; /* 'wall': the fourth Philox counter word of the patch choice */

void image_walls_patch_of(uint64_t patch_seed, int64_t voxel, int patches, int *patch,
                          int *orient) {
  const uint64_t v = (uint64_t)voxel;
  philox4x32_ctr_t ctr = {{(uint32_t)v, (uint32_t)(v >> 32), 0, TAG_PATCH}};
  philox4x32_key_t key = {{(uint32_t)patch_seed, (uint32_t)(patch_seed >> 32)}};
  philox4x32_ctr_t r = philox4x32(ctr, key);
  /* multiply-shift: uniform in [0, m) without the modulo's bias beyond 2^-32 */
  *patch = (int)(((uint64_t)r.v[0] * (uint64_t)patches) >> 32);
  *orient = (int)(((uint64_t)r.v[1] * 24u) >> 32);
}

/* ---- exact squared Euclidean distance transform (Felzenszwalb & Huttenlocher 2012) ---------- */

/* d[q] = min over sites p (f[p] finite) of (q - p)^2 + f[p]; HUGE_VAL when there is no site.
 * v (n ints) and z (n + 1 doubles) are work arrays: the lower envelope of the parabolas. */
static void edt_1d(const double *f, int n, double *d, int *v, double *z) {
  int k = -1;
  for (int q = 0; q < n; q++) {
    if (f[q] == HUGE_VAL) continue;
    double s = -HUGE_VAL;
    while (k >= 0) {
      s = ((f[q] + (double)q * q) - (f[v[k]] + (double)v[k] * v[k])) / (2.0 * (q - v[k]));
      if (s > z[k]) break;
      k--;
    }
    k++;
    v[k] = q;
    z[k] = k == 0 ? -HUGE_VAL : s;
    z[k + 1] = HUGE_VAL;
  }
  if (k < 0) {
    for (int q = 0; q < n; q++) d[q] = HUGE_VAL;
    return;
  }
  k = 0;
  for (int q = 0; q < n; q++) {
    while (z[k + 1] < q) k++;
    d[q] = (double)(q - v[k]) * (q - v[k]) + f[v[k]];
  }
}

/* d2[voxel] = squared distance (voxel units) from its centre to the nearest pore voxel centre of
 * the n[0] x n[1] x n[2] window, periodic along the axes where periodic[a] (the window is the whole
 * periodic axis: a line is transformed three times over and its middle kept: every periodic image
 * within half a period is then inside); EDT_INF without any pore voxel. Three separable passes,
 * O(voxels) each (x3 along periodic axes). A voxel at least the thickness inside the window (or at
 * the image's own faces) gets the image's exact distance wherever that is within the thickness:
 * its nearest pore voxel is then in the window. With to_solid the same to the nearest solid voxel
 * (a window's distance is then never below the image's). 0, or -1 (memory). */
static int edt_to(const uint8_t *phase, const int n[3], const int periodic[3], int to_solid,
                  uint32_t *d2) {
  const size_t stride[3] = {1, (size_t)n[0], (size_t)n[0] * (size_t)n[1]};
  const size_t total = (size_t)n[0] * (size_t)n[1] * (size_t)n[2];
  for (size_t i = 0; i < total; i++) d2[i] = (phase[i] == MDP_PHASE_PORE) != to_solid ? 0 : EDT_INF;
  int nmax = n[0] > n[1] ? n[0] : n[1];
  if (n[2] > nmax) nmax = n[2];
  const size_t len = 3 * (size_t)nmax;
  double *f = malloc(len * sizeof *f), *d = malloc(len * sizeof *d);
  double *z = malloc((len + 1) * sizeof *z);
  int *v = malloc(len * sizeof *v);
  if (!f || !d || !z || !v) {
    free(f), free(d), free(z), free(v);
    return -1;
  }
  for (int a = 0; a < 3; a++) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const int m = periodic[a] ? 3 * n[a] : n[a], off = periodic[a] ? n[a] : 0;
    for (int kc = 0; kc < n[c]; kc++)
      for (int kb = 0; kb < n[b]; kb++) {
        const size_t base = (size_t)kb * stride[b] + (size_t)kc * stride[c];
        for (int q = 0; q < m; q++) {
          const uint32_t x = d2[base + (size_t)(q % n[a]) * stride[a]];
          f[q] = x == EDT_INF ? HUGE_VAL : (double)x;
        }
        edt_1d(f, m, d, v, z);
        for (int q = 0; q < n[a]; q++) {
          const double x = d[off + q];
          d2[base + (size_t)q * stride[a]] = x >= (double)(EDT_INF - 1) ? EDT_INF : (uint32_t)x;
        }
      }
  }
  free(f), free(d), free(z), free(v);
  return 0;
}

/* ---- the build ------------------------------------------------------------------------------------ */

/* Wall thickness (rc): geometry.wall_thickness, or when <= 0 the largest rc + rd of the fluid-wall
 * pairs: a fluid particle then sees a full wall within every cutoff it has (forces and density).
 * A voxel edge h coarser than that keeps one voxel layer (thickness h >= rc + rd): the face
 * neighbours of every pore voxel, which is all the cutoffs need. */
static double wall_thickness(const scene_t *s, double h) {
  const scene_geometry_t *geo = &s->geometry;
  if (geo->wall_thickness > 0) return geo->wall_thickness;
  const int walls[2] = {geo->organic_species, geo->inorganic_species};
  double t = 0;
  for (int k = 0; k < 2; k++)
    for (int f = -1; f < geo->n_species_regions + geo->n_species_labels && walls[k] >= 0; f++) {
      const int fluid = f < 0 ? geo->fluid_species
                        : f < geo->n_species_regions
                            ? geo->species_region[f].species
                            : geo->species_label_species[f - geo->n_species_regions];
      const scene_pair_t *p = &s->pair[fluid][walls[k]];
      if (p->rc + p->rd > t) t = p->rc + p->rd;
    }
  return t > h ? t : h;
}

/* The wall species of a voxel's phase (-1: pore or a phase without one). */
static int wall_species_of_phase(const scene_geometry_t *geo, int phase) {
  return phase == MDP_PHASE_ORGANIC     ? geo->organic_species
         : phase == MDP_PHASE_INORGANIC ? geo->inorganic_species
                                        : -1;
}

/* A moving wall species (species[].velocity) slides along its axis, so its solid voxels must be
 * the same after any shift along that axis (e.g. a slit wall, not a sphere): every voxel of the
 * species has a voxel of the same species as its neighbour along the axis (periodic). Otherwise
 * the frozen particles would leave their voxels and bounce_back's solid map would be wrong. */
static int check_moving_walls(const scene_t *s, const image_walls_t *g, const uint8_t *phase,
                              char *err, size_t errlen) {
  const scene_geometry_t *geo = &s->geometry;
  for (int k = 0; k < 2; k++) {
    const int sp = k ? geo->inorganic_species : geo->organic_species;
    if (sp < 0 || !s->species[sp].moving) continue;
    const int ax = s->species[sp].move_axis;
    for (int z = 0; z < g->own_n[2]; z++)
      for (int y = 0; y < g->own_n[1]; y++)
        for (int x = 0; x < g->own_n[0]; x++) {
          const int lc[3] = {x, y, z};
          int c[3], q[3];
          image_walls_global(g, g->own_lo, lc, q);
          memcpy(c, q, sizeof c);
          if (wall_species_of_phase(geo, phase[image_walls_win(g, q)]) != sp) continue;
          c[ax] = (c[ax] + 1) % g->n[ax];
          if (wall_species_of_phase(geo, phase[image_walls_win(g, c)]) == sp) continue;
          snprintf(err, errlen,
                   "%s: key 'species[%d].velocity': expected the solid voxels of the moving "
                   "species '%s' (geometry.species.%s) to be translation-invariant along %c, the "
                   "axis it moves along (got voxel (%d, %d, %d) of it followed by voxel (%d, %d, "
                   "%d) that is not: a moving wall must be the same after any shift along its "
                   "velocity, e.g. a slit wall)",
                   s->file, sp, s->species[sp].name, k ? "inorganic" : "organic", "xyz"[ax], q[0],
                   q[1], q[2], c[0], c[1], c[2]);
          return -1;
        }
  }
  return 0;
}

/* The halo around gen (voxels): the fluid's min_wall_distance scan reaches ceil(d / voxel) voxels
 * and needs the wall classes there, which need the pore voxels within the thickness of them. */
static int halo_voxels(const image_walls_t *g) {
  const int scan = g->min_distance > 0 ? (int)ceil(g->min_distance / g->h) : 0;
  return scan + (int)ceil(g->thickness / g->h * (1 + 1e-12));
}

/* geometry.min_wall_distance within the box: no two points of it are farther apart than its
 * diagonal (half an edge along a periodic axis, whose nearest image is used), so a larger distance
 * leaves no place for any fluid particle, and its scan (ceil(d / voxel) voxels each side, per try)
 * would run without end. 0 or -1 + err. */
static int check_min_distance(const scene_t *s, const image_walls_t *g, char *err, size_t errlen) {
  double reach2 = 0;
  for (int d = 0; d < 3; d++) {
    const double edge = s->box_hi[d] - s->box_lo[d], far = g->periodic[d] ? 0.5 * edge : edge;
    reach2 += far * far;
  }
  const double reach = sqrt(reach2);
  if (isfinite(g->min_distance) && g->min_distance < reach) return 0;
  snprintf(err, errlen,
           "%s: key 'geometry.min_wall_distance': expected a distance (rc) less than %g, the "
           "farthest two points of the box can be apart (its diagonal, half an edge along a "
           "periodic axis), so that the fluid has room; typical values are below rc, e.g. the "
           "default 0.25 (got %g)",
           s->file, reach, g->min_distance);
  return -1;
}

/* The local steps before the first collective one: the image file, the thickness, the window. */
static int read_stage(const scene_t *s, image_walls_t *g, const double *sub_lo,
                      const double *sub_hi, uint8_t **phase, char *err, size_t errlen) {
  const scene_geometry_t *geo = &s->geometry;
  struct stat sb;
  *phase = NULL;
  if (stat(geo->image, &sb) != 0) {
    snprintf(err, errlen,
             "%s: key 'geometry.image': expected a segmented image (raw + PATH.hdr sidecar, .h5, "
             ".tif or a folder of slices) (got '%s': no such file or folder)",
             s->file, geo->image);
    return -1;
  }
  if (g->thickness < g->h * (1 - 1e-12)) {
    snprintf(
        err, errlen,
        "%s: key 'geometry.wall_thickness': expected at least the voxel edge rc_per_voxel = %g "
        "rc (no solid voxel centre is nearer a pore voxel centre) (got %g rc%s)",
        s->file, g->h, g->thickness,
        geo->wall_thickness > 0 ? "" : ", the default rc + rd of the fluid-wall pairs");
    return -1;
  }
  if (check_min_distance(s, g, err, errlen)) return -1;
  if (image_window_read(s, g, sub_lo, sub_hi, halo_voxels(g), phase, err, errlen)) return -1;
  const long long total = (long long)g->win_n[0] * g->win_n[1] * g->win_n[2];
  g->cls = calloc(total ? (size_t)total : 1, 1);
  if (!g->cls) {
    snprintf(err, errlen, "%s: geometry: out of memory for %lld voxels", s->file, total);
    return -1;
  }
  image_walls_mem(g, total);
  return check_moving_walls(s, g, *phase, err, errlen);
}

/* The squared distance transform of the window (edt_to: to the pore voxels with to_pore, else to
 * the solid ones), periodic along the axes the window covers whole; counted in the build's memory
 * (window_edt_free gives it back). NULL + err without memory. */
static uint32_t *window_edt(const scene_t *s, image_walls_t *g, const uint8_t *phase, int to_pore,
                            char *err, size_t errlen) {
  const long long total = (long long)g->win_n[0] * g->win_n[1] * g->win_n[2];
  uint32_t *d2 = malloc((total ? (size_t)total : 1) * sizeof *d2);
  int per[3];
  for (int d = 0; d < 3; d++) per[d] = g->periodic[d] && g->win_n[d] == g->n[d];
  if (!d2 || edt_to(phase, g->win_n, per, to_pore, d2)) {
    free(d2);
    snprintf(err, errlen, "%s: geometry: out of memory for the distance transform", s->file);
    return NULL;
  }
  image_walls_mem(g, total * 4);
  return d2;
}

static void window_edt_free(image_walls_t *g, uint32_t *d2) {
  free(d2);
  image_walls_mem(g, -(long long)g->win_n[0] * g->win_n[1] * g->win_n[2] * 4);
}

/* The wall voxels of the window: solid voxels whose centre is within the thickness of a pore
 * voxel centre (exact where it is used: gen and the min_wall_distance scan around it); the counts
 * of the rank's own voxels ([organic, inorganic][wall, deep]). 0 or -1 + err (memory). */
static int classify_walls(const scene_t *s, image_walls_t *g, const uint8_t *phase,
                          long long own[2][2], char *err, size_t errlen) {
  const long long total = (long long)g->win_n[0] * g->win_n[1] * g->win_n[2];
  uint32_t *d2 = window_edt(s, g, phase, 0, err, errlen);
  if (!d2) return -1;
  const double t = g->thickness / g->h, t2 = t * t * (1 + 1e-12);
  for (long long i = 0; i < total; i++) {
    const int p = phase[i];
    if (p == MDP_PHASE_PORE) {
      if (!g->cls[i]) g->cls[i] = IMAGE_VOXEL_EMPTY; /* a halo pore voxel: no particles here */
      continue;
    }
    const int k = p == MDP_PHASE_INORGANIC;
    g->cls[i] =
        (double)d2[i] <= t2 ? (k ? IMAGE_VOXEL_INORGANIC : IMAGE_VOXEL_ORGANIC) : IMAGE_VOXEL_DEEP;
  }
  window_edt_free(g, d2);
  for (int z = 0; z < g->own_n[2]; z++)
    for (int y = 0; y < g->own_n[1]; y++)
      for (int x = 0; x < g->own_n[0]; x++) {
        const int lc[3] = {x, y, z};
        int q[3];
        image_walls_global(g, g->own_lo, lc, q);
        const long long w = image_walls_win(g, q);
        const int p = phase[w];
        if (p == MDP_PHASE_PORE) continue;
        own[p == MDP_PHASE_INORGANIC][(g->cls[w] & IMAGE_VOXEL_CLASS) == IMAGE_VOXEL_DEEP]++;
      }
  return 0;
}

/* The room geometry.min_wall_distance leaves: no point of a pore voxel is farther than (D + sqrt 3)
 * voxel edges from a wall particle, D the distance (voxels) from its centre to the nearest solid
 * voxel centre (that voxel is a wall voxel: one of its face neighbours is pore). The largest over
 * the own pore voxels, in rc, reduced over the ranks (collective: every rank calls it, failed or
 * not); HUGE_VAL without solid voxels. A distance at least that large leaves the fluid no place,
 * and its scan would run without end. 0 or -1 + err (memory, or no room). */
static int check_room(const scene_t *s, image_walls_t *g, const uint8_t *phase, int failed,
                      char *err, size_t errlen) {
  double room = -1; /* -1: this rank failed before */
  if (!failed && g->min_distance > 0) {
    uint32_t *d2 = window_edt(s, g, phase, 1, err, errlen);
    if (!d2) {
      failed = 1;
    } else {
      uint32_t far2 = 0;
      for (int z = 0; z < g->own_n[2]; z++)
        for (int y = 0; y < g->own_n[1]; y++)
          for (int x = 0; x < g->own_n[0]; x++) {
            const int lc[3] = {x, y, z};
            int q[3];
            image_walls_global(g, g->own_lo, lc, q);
            const long long w = image_walls_win(g, q);
            if (phase[w] == MDP_PHASE_PORE && d2[w] > far2) far2 = d2[w];
          }
      window_edt_free(g, d2);
      room = far2 == EDT_INF ? HUGE_VAL : (sqrt((double)far2) + sqrt(3.0)) * g->h;
    }
  }
  if (!failed && g->min_distance <= 0) room = HUGE_VAL;
  MPI_Allreduce(MPI_IN_PLACE, &room, 1, MPI_DOUBLE, MPI_MAX, g->work);
  if (failed || room < 0) return -1;
  if (g->min_distance < room) return 0;
  snprintf(err, errlen,
           "%s: key 'geometry.min_wall_distance': expected less than %g rc, the farthest a point "
           "of a pore voxel of %s can be from every wall particle (the largest distance from a "
           "pore voxel centre to a solid one plus a voxel diagonal), so that the fluid has room; "
           "typical values are below rc, e.g. the default 0.25 (got %g)",
           s->file, room, s->geometry.image, g->min_distance);
  return -1;
}

/* Every rank's failure, agreed: the message of the lowest failing rank is printed (by it). */
static int agree(int failed, const char *err, MPI_Comm comm) {
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int first = failed ? rank : size;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first < size && rank == first) fprintf(stderr, "%s\n", err);
  return first < size ? -1 : 0;
}

/* The build: whole = every rank the whole image (its reductions over MPI_COMM_SELF), else the
 * rank's part for its subdomain [sub_lo, sub_hi). */
static int build(const scene_t *s, MPI_Comm comm, int whole, const double *sub_lo,
                 const double *sub_hi, image_walls_t *g) {
  const scene_geometry_t *geo = &s->geometry;
  memset(g, 0, sizeof *g);
  g->scene = s;
  g->whole = whole;
  int comm_size = 1;
  MPI_Comm_size(comm, &comm_size);
  /* a one-rank comm is its own (the replicas of mdpore run --replicas: threads of one process must
   * not share MPI_COMM_SELF's collectives) */
  g->work = whole && comm_size > 1 ? MPI_COMM_SELF : comm;
  g->h = geo->rc_per_voxel;
  g->min_distance = geo->min_wall_distance;
  for (int d = 0; d < 3; d++) g->lo[d] = s->box_lo[d], g->periodic[d] = s->periodic[d];
  g->thickness = wall_thickness(s, g->h);
  char err[4 * MDP_IMAGE_ERR_LEN] = "";
  uint8_t *phase = NULL;
  int rc = read_stage(s, g, sub_lo, sub_hi, &phase, err, sizeof err);
  if (agree(rc != 0, err, comm)) {
    free(phase);
    image_walls_free(g);
    return -1;
  }
  /* phase counts of the own voxels, summed over the ranks */
  image_walls_counts_t *ct = &g->count;
  long long cnt[4] = {0, 0, 0, 0};
  for (int z = 0; z < g->own_n[2]; z++)
    for (int y = 0; y < g->own_n[1]; y++)
      for (int x = 0; x < g->own_n[0]; x++) {
        const int lc[3] = {x, y, z};
        int q[3];
        image_walls_global(g, g->own_lo, lc, q);
        const int p = phase[image_walls_win(g, q)];
        cnt[0]++;
        cnt[1] += p == MDP_PHASE_PORE, cnt[2] += p == MDP_PHASE_ORGANIC;
        cnt[3] += p == MDP_PHASE_INORGANIC;
        if (g->label_sp && g->label_sp[image_walls_win(g, q)])
          g->label_voxels[g->label_sp[image_walls_win(g, q)] - 1]++;
      }
  MPI_Allreduce(MPI_IN_PLACE, cnt, 4, MPI_LONG_LONG, MPI_SUM, g->work);
  if (geo->n_species_labels > 0)
    MPI_Allreduce(MPI_IN_PLACE, g->label_voxels, geo->n_species_labels, MPI_LONG_LONG, MPI_SUM,
                  g->work);
  ct->voxels = cnt[0], ct->pore = cnt[1], ct->organic = cnt[2], ct->inorganic = cnt[3];
  /* the checks below see the same sums on every rank, so they fail everywhere or nowhere */
  if (ct->voxels != (long long)g->n[0] * g->n[1] * g->n[2]) {
    snprintf(err, sizeof err,
             "%s: geometry: internal error: the ranks' own voxels sum to %lld, the image has "
             "%lld (the decomposition is not a grid of boxes?)",
             s->file, ct->voxels, (long long)g->n[0] * g->n[1] * g->n[2]);
    rc = -1;
  }
  const long long nsolid[2] = {ct->organic, ct->inorganic};
  const int wsp[2] = {geo->organic_species, geo->inorganic_species};
  for (int k = 0; k < 2 && !rc; k++)
    if (nsolid[k] > 0 && wsp[k] < 0) {
      snprintf(err, sizeof err,
               "%s: key 'geometry.species.%s': expected a wall species for the %lld %s voxels of "
               "%s (got none)",
               s->file, k ? "inorganic" : "organic", nsolid[k], k ? "inorganic" : "organic",
               geo->image);
      rc = -1;
    }
  for (int k = 0; k < geo->n_species_labels && !rc; k++)
    if (g->label_voxels[k] == 0) {
      snprintf(err, sizeof err,
               "%s: key 'geometry.fluid_species_labels.%d': expected a label that voxels of %s "
               "carry (got %d: no voxel of the image has it)",
               s->file, geo->species_label[k], geo->image, geo->species_label[k]);
      rc = -1;
    }
  if (!rc && ct->pore == 0) {
    snprintf(err, sizeof err,
             "%s: key 'geometry.flow_axis': expected a box axis along which the pore space "
             "percolates (after axis_map): %s: empty pore space: no voxel is labelled pore",
             s->file, geo->image);
    rc = -1;
  }
  if (!rc) rc = image_clusters_classify(s, g, phase, err, sizeof err);
  long long own[2][2] = {{0, 0}, {0, 0}};
  if (!rc) rc = classify_walls(s, g, phase, own, err, sizeof err);
  rc = check_room(s, g, phase, rc != 0, err, sizeof err) ? -1 : rc;
  free(phase);
  image_walls_mem(g, -(long long)g->win_n[0] * g->win_n[1] * g->win_n[2]);
  if (agree(rc != 0, err, comm)) {
    image_walls_free(g);
    return -1;
  }
  MPI_Allreduce(MPI_IN_PLACE, own, 4, MPI_LONG_LONG, MPI_SUM, g->work);
  for (int k = 0; k < 2; k++) ct->wall_voxels[k] = own[k][0], ct->deep_voxels[k] = own[k][1];
  int rank;
  MPI_Comm_rank(comm, &rank);
  for (int k = 0; k < 2; k++) {
    const double rc = wsp[k] < 0 ? 0 : s->pair[geo->fluid_species][wsp[k]].rc;
    if (rank == 0 && g->count.wall_voxels[k] > 0 && floor(g->thickness / g->h + 1e-9) * g->h < rc)
      fprintf(stderr,
              "%s: warning: geometry: the walls are %g rc thick at a flat pore surface (%g "
              "voxel layers), less than the fluid-%s cutoff rc = %g: fluid near the surface sees "
              "the empty space behind the wall (set geometry.wall_thickness >= rc + rd)\n",
              s->file, floor(g->thickness / g->h + 1e-9) * g->h, floor(g->thickness / g->h + 1e-9),
              s->species[wsp[k]].name, rc);
  }
  /* the patch database (collective: it may be built) */
  char e[MDP_IMAGE_ERR_LEN] = "";
  rc = wall_patches_load_or_build(geo->patches, g->h, geo->wall_density, geo->patch_seed, comm,
                                  &g->db, e, sizeof e);
  if (!rc && g->db.count < 1) {
    snprintf(e, sizeof e, "the database holds no patch");
    rc = -1;
  }
  if (rc) snprintf(err, sizeof err, "%s: geometry: wall patch database: %s", s->file, e);
  if (agree(rc != 0, err, comm)) {
    image_walls_free(g);
    return -1;
  }
  /* fluid counts (collective, the same result everywhere), then the local list and its ids */
  uint16_t *kept = NULL;
  rc = image_fluid_count(g, &kept, err, sizeof err);
  if (!rc) rc = image_ids_assign(g, kept, err, sizeof err);
  if (kept) image_walls_mem(g, -2LL * g->gen_n[0] * g->gen_n[1] * g->gen_n[2]);
  free(kept);
  if (agree(rc != 0, err, comm)) {
    image_walls_free(g);
    return -1;
  }
  /* every rank's voxels read and peak bytes, for the report */
  MPI_Comm_size(comm, &g->ranks);
  long long mine[2] = {g->voxels_read, g->mem_peak};
  long long *all = rank == 0 ? malloc(2 * (size_t)g->ranks * sizeof *all) : NULL;
  MPI_Gather(mine, 2, MPI_LONG_LONG, all, 2, MPI_LONG_LONG, 0, comm);
  if (all) {
    g->rank_read = malloc((size_t)g->ranks * sizeof *g->rank_read);
    g->rank_peak = malloc((size_t)g->ranks * sizeof *g->rank_peak);
    for (int r = 0; g->rank_read && g->rank_peak && r < g->ranks; r++)
      g->rank_read[r] = all[2 * r], g->rank_peak[r] = all[2 * r + 1];
    free(all);
  }
  return 0;
}

int image_walls_plan(const scene_t *s, MPI_Comm comm, const double sub_lo[3],
                     const double sub_hi[3], image_walls_plan_t *p) {
  const scene_geometry_t *geo = &s->geometry;
  image_walls_t g;
  memset(p, 0, sizeof *p);
  memset(&g, 0, sizeof g);
  g.scene = s;
  g.h = geo->rc_per_voxel;
  g.min_distance = geo->min_wall_distance;
  for (int d = 0; d < 3; d++) g.lo[d] = s->box_lo[d], g.periodic[d] = s->periodic[d];
  g.thickness = wall_thickness(s, g.h);
  char err[4 * MDP_IMAGE_ERR_LEN];
  /* the checks of read_stage that keep the halo finite, then the ranges (the header alone) */
  int rc = g.thickness < g.h * (1 - 1e-12) || check_min_distance(s, &g, err, sizeof err) ||
                   image_window_ranges(s, &g, sub_lo, sub_hi, halo_voxels(&g), err, sizeof err)
               ? -1
               : 0;
  /* the x segments of the id table (image_ids.c): the distinct x cuts of the ranks' own voxels */
  int size;
  MPI_Comm_size(comm, &size);
  int mine[2] = {g.own_lo[0], g.own_lo[0] + g.own_n[0]};
  int *cut = malloc((2 * (size_t)size + 2) * sizeof *cut);
  int fail = rc || !cut;
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  if (fail) {
    free(cut);
    return -1;
  }
  MPI_Allgather(mine, 2, MPI_INT, cut, 2, MPI_INT, comm);
  int segments = 0;
  for (int i = 0; i < 2 * size; i++) {
    int seen = 0;
    for (int j = 0; j < i && !seen; j++) seen = cut[j] == cut[i];
    segments += !seen && cut[i] > 0 && cut[i] < g.n[0]; /* an inner cut adds a segment */
  }
  free(cut);
  segments++;
  for (int d = 0; d < 3; d++) p->n[d] = g.n[d];
  p->window = (long long)g.win_n[0] * g.win_n[1] * g.win_n[2];
  p->gen = (long long)g.gen_n[0] * g.gen_n[1] * g.gen_n[2];
  p->bytes = memory_geometry_build_bytes((double)p->window, (double)p->gen, (double)g.n[1] * g.n[2],
                                         segments, geo->n_species_labels > 0);
  return 0;
}

int image_walls_build(const scene_t *s, MPI_Comm comm, image_walls_t *g) {
  return build(s, comm, 1, NULL, NULL, g);
}

int image_walls_build_local(const scene_t *s, MPI_Comm comm, const double sub_lo[3],
                            const double sub_hi[3], image_walls_t *g) {
  return build(s, comm, 0, sub_lo, sub_hi, g);
}

void image_walls_free(image_walls_t *g) {
  free(g->cls), free(g->label_sp);
  free(g->wall_vox), free(g->wall_start), free(g->wall_id);
  free(g->fluid_vox), free(g->fluid_start), free(g->fluid_id);
  free(g->rank_read), free(g->rank_peak);
  wall_patches_free(&g->db);
  free(g->cache);
  memset(g, 0, sizeof *g);
}

/* ---- the particles ------------------------------------------------------------------------------- */

long image_walls_voxel_count(const image_walls_t *g, int64_t v) {
  const int q[3] = {(int)(v % g->n[0]), (int)(v / g->n[0] % g->n[1]),
                    (int)(v / ((int64_t)g->n[0] * g->n[1]))};
  const long long w = image_walls_win(g, q);
  if (w < 0) return 0;
  const int c = g->cls[w] & IMAGE_VOXEL_CLASS;
  if (c != IMAGE_VOXEL_ORGANIC && c != IMAGE_VOXEL_INORGANIC) return 0;
  int p, o;
  image_walls_patch_of(g->scene->geometry.patch_seed, v, g->db.count, &p, &o);
  return g->db.start[p + 1] - g->db.start[p];
}

void image_walls_voxel_particle(const image_walls_t *g, int64_t v, long j, double x[3]) {
  int p, o;
  image_walls_patch_of(g->scene->geometry.patch_seed, v, g->db.count, &p, &o);
  double r[3];
  wall_patch_orient(o, g->h, g->db.x + 3 * (g->db.start[p] + j), r);
  const int64_t ijk[3] = {v % g->n[0], v / g->n[0] % g->n[1], v / ((int64_t)g->n[0] * g->n[1])};
  for (int d = 0; d < 3; d++) x[d] = g->lo[d] + (double)ijk[d] * g->h + r[d];
}

long image_walls_total(const image_walls_t *g) {
  return g->n_wall + g->n_fluid;
}

long image_walls_local(const image_walls_t *g) {
  return g->wall_start[g->n_wall_vox] + g->fluid_start[g->n_fluid_vox];
}

long image_walls_find(const long *start, long n, long i) {
  long lo = 0, hi = n; /* start[lo] <= i < start[hi] (start[n] = the total) */
  while (hi - lo > 1) {
    const long mid = lo + (hi - lo) / 2;
    if (start[mid] <= i)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

void image_walls_particle(const image_walls_t *g, long i, int64_t *id, int *species, double x[3]) {
  const scene_geometry_t *geo = &g->scene->geometry;
  const long nw = g->wall_start[g->n_wall_vox];
  if (i >= nw) {
    const long f = image_walls_find(g->fluid_start, g->n_fluid_vox, i - nw);
    *id = 1 + g->n_wall + g->fluid_id[f] + (i - nw - g->fluid_start[f]);
    image_fluid_particle(g, i - nw, x);
    *species = geo->fluid_species;
    if (g->label_sp) { /* geometry.fluid_species_labels: the species of the voxel's label */
      const int64_t v = g->fluid_vox[f];
      const int q[3] = {(int)(v % g->n[0]), (int)(v / g->n[0] % g->n[1]),
                        (int)(v / ((int64_t)g->n[0] * g->n[1]))};
      const int k = g->label_sp[image_walls_win(g, q)];
      if (k) *species = geo->species_label_species[k - 1];
    }
    for (int k = 0; k < geo->n_species_regions; k++) {
      const scene_fill_t *r = &geo->species_region[k];
      int in = init_shape_keeps(r, x);
      for (int d = 0; d < 3 && in; d++) in = x[d] >= r->lo[d] && x[d] < r->hi[d];
      if (in) {
        *species = r->species;
        break;
      }
    }
    return;
  }
  const long w = image_walls_find(g->wall_start, g->n_wall_vox, i);
  const int64_t v = g->wall_vox[w];
  *id = 1 + g->wall_id[w] + (i - g->wall_start[w]);
  const int q[3] = {(int)(v % g->n[0]), (int)(v / g->n[0] % g->n[1]),
                    (int)(v / ((int64_t)g->n[0] * g->n[1]))};
  *species = (g->cls[image_walls_win(g, q)] & IMAGE_VOXEL_CLASS) == IMAGE_VOXEL_ORGANIC
                 ? geo->organic_species
                 : geo->inorganic_species;
  image_walls_voxel_particle(g, v, i - g->wall_start[w], x);
}

/* ---- the report ---------------------------------------------------------------------------------- */

void image_walls_report(const image_walls_t *g, FILE *out) {
  const scene_t *s = g->scene;
  const scene_geometry_t *geo = &s->geometry;
  const image_walls_counts_t *ct = &g->count;
  const double vox = g->h * g->h * g->h;
  const char *ax = "xyz";
  fprintf(out, "geometry: %s\n", geo->image);
  fprintf(out,
          "  image: %d x %d x %d voxels (box axes), rc_per_voxel %g: box %g x %g x %g rc, "
          "flow along %c\n",
          g->n[0], g->n[1], g->n[2], g->h, g->n[0] * g->h, g->n[1] * g->h, g->n[2] * g->h,
          ax[geo->flow_axis]);
  fprintf(out, "  phases: pore %lld (porosity %.4f), organic %lld, inorganic %lld voxels\n",
          ct->pore, ct->voxels ? (double)ct->pore / (double)ct->voxels : 0.0, ct->organic,
          ct->inorganic);
  fprintf(
      out,
      "  walls: thickness %g rc (%.3g voxels)%s; wall voxels kept %lld (organic %lld, inorganic "
      "%lld), deep solid voxels dropped %lld (organic %lld, inorganic %lld)\n",
      g->thickness, g->thickness / g->h,
      geo->wall_thickness > 0 ? ""
      : g->thickness > g->h   ? " = rc + rd of the fluid-wall pairs"
                              : " = one voxel edge (coarser than rc + rd of the fluid-wall pairs)",
      ct->wall_voxels[0] + ct->wall_voxels[1], ct->wall_voxels[0], ct->wall_voxels[1],
      ct->deep_voxels[0] + ct->deep_voxels[1], ct->deep_voxels[0], ct->deep_voxels[1]);
  char cache[1024];
  if (!geo->patches[0])
    wall_patches_cache_path(g->h, geo->wall_density, geo->patch_seed, cache, sizeof cache);
  fprintf(out, "  patches: %d of edge %g rc at density %g, seed %llu (%s)\n", g->db.count,
          g->db.edge, g->db.density, (unsigned long long)geo->patch_seed,
          geo->patches[0] ? geo->patches : cache);
  const int wsp[2] = {geo->organic_species, geo->inorganic_species};
  for (int sp = 0; sp < s->n_species; sp++) {
    long n = 0;
    long long nv = 0;
    for (int k = 0; k < 2; k++)
      if (wsp[k] == sp) n += ct->wall_particles[k], nv += ct->wall_voxels[k];
    if (wsp[0] != sp && wsp[1] != sp) continue;
    fprintf(out, "  wall particles: %s %ld in %lld voxels (density %.4g per rc^3)\n",
            s->species[sp].name, n, nv, nv ? (double)n / ((double)nv * vox) : 0.0);
  }
  const char *others = geo->isolated_pores == ISOLATED_FILL ? "filled" : "left empty";
  fprintf(out,
          "  pore clusters: %d; spanning %c: %d (%lld voxels), filled; joined to them through a "
          "periodic face: %d (%lld voxels), filled; isolated: %d (%lld voxels) and dead-end: %d "
          "(%lld voxels), %s (isolated_pores: %s)\n",
          ct->clusters, ax[geo->flow_axis], ct->spanning, ct->spanning_voxels, ct->joined,
          ct->joined_voxels, ct->isolated, ct->isolated_voxels, ct->dead_end, ct->dead_end_voxels,
          others, geo->isolated_pores == ISOLATED_FILL ? "fill" : "empty");
  const double pv = ct->fluid_volume;
  if (geo->fluid_region)
    fprintf(out,
            "  fluid_region: [%g, %g] x [%g, %g] x [%g, %g] rc: %lld filled pore voxels inside "
            "(%lld of them partly), %lld outside left empty\n",
            geo->fluid_lo[0], geo->fluid_hi[0], geo->fluid_lo[1], geo->fluid_hi[1],
            geo->fluid_lo[2], geo->fluid_hi[2], ct->fluid_voxels, ct->region_partial,
            ct->region_outside);
  fprintf(out,
          "  fluid: %s %ld particles in %lld pore voxels (%g rc^3): target %ld = round(%g x %g), "
          "%ld dropped (no place %g rc from every wall particle in %d tries; %ld positions "
          "redrawn); density %.4g per rc^3 of filled pore\n",
          s->species[geo->fluid_species].name, ct->fluid_particles, ct->fluid_voxels, pv,
          ct->fluid_target, geo->fluid_density, pv, ct->fluid_dropped, g->min_distance,
          IMAGE_FLUID_TRIES, ct->fluid_redrawn, pv > 0 ? (double)ct->fluid_particles / pv : 0.0);
  long long labelled = 0;
  for (int k = 0; k < geo->n_species_labels; k++) {
    fprintf(out, "  fluid_species_labels: label %d: %lld particles of %s in %lld voxels\n",
            geo->species_label[k], g->label_particles[k],
            s->species[geo->species_label_species[k]].name, g->label_voxels[k]);
    labelled += g->label_particles[k];
  }
  if (geo->n_species_labels > 0)
    fprintf(out,
            "  fluid_species_labels: %lld of the %ld fluid particles stay %s (before "
            "fluid_species_regions)\n",
            (long long)ct->fluid_particles - labelled, ct->fluid_particles,
            s->species[geo->fluid_species].name);
  fprintf(out, "  particles: %ld (walls %ld, fluid %ld), ids 1..%ld\n", image_walls_total(g),
          g->n_wall, g->n_fluid, image_walls_total(g));
  /* memory: what each rank read and the peak of the build's arrays (window, clusters, distance
   * transform, id table, local list; not the patch database, the same on every rank) */
  if (g->rank_read && g->rank_peak) {
    long long rmin = g->rank_read[0], rmax = rmin, pmin = g->rank_peak[0], pmax = pmin;
    for (int r = 1; r < g->ranks; r++) {
      rmin = g->rank_read[r] < rmin ? g->rank_read[r] : rmin;
      rmax = g->rank_read[r] > rmax ? g->rank_read[r] : rmax;
      pmin = g->rank_peak[r] < pmin ? g->rank_peak[r] : pmin;
      pmax = g->rank_peak[r] > pmax ? g->rank_peak[r] : pmax;
    }
    fprintf(out,
            "  ranks: %d%s; voxels read per rank %lld..%lld (image %lld: %.3g of it at most); "
            "build peak per rank %.4g..%.4g MB\n",
            g->ranks, g->whole ? " (each built the whole image)" : "", rmin, rmax, ct->voxels,
            ct->voxels ? (double)rmax / (double)ct->voxels : 0.0, (double)pmin / 1e6,
            (double)pmax / 1e6);
    if (g->ranks <= 16) {
      fprintf(out, "  per rank (voxels read, peak bytes):");
      for (int r = 0; r < g->ranks; r++)
        fprintf(out, " %d: %lld %lld%s", r, g->rank_read[r], g->rank_peak[r],
                r + 1 < g->ranks ? ";" : "\n");
    }
  }

  fflush(out);
}
