/* Wall particles from a segmented image (image_walls.h, docs/walls.md; physics.md section 3, Li
 * et al. JCP 355 (2018) 534, section 2.3): the image as the box sees it, the pore clusters that get
 * fluid, an exact Euclidean distance transform of the pore space to find the solid voxels within the
 * wall thickness, and per wall voxel a patch of the database in one of the 24 cube orientations. */
#include "build/image_walls.h"
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

/* d2[voxel] = squared distance (voxel units) from its centre to the nearest pore voxel centre,
 * periodic along the periodic axes (a line is transformed three times over and its middle kept:
 * every periodic image within half a period is then inside); EDT_INF without any pore voxel.
 * Three separable passes, O(voxels) each (x3 along periodic axes). 0, or -1 (memory). */
static int edt_pore(const mdp_image_t *img, const int periodic[3], uint32_t *d2) {
  const int n[3] = {img->nx, img->ny, img->nz};
  const size_t stride[3] = {1, (size_t)n[0], (size_t)n[0] * (size_t)n[1]};
  const size_t total = mdp_image_count(img);
  for (size_t i = 0; i < total; i++) d2[i] = mdp_image_is_pore(img, i) ? 0 : EDT_INF;
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

/* ---- pore clusters: which get fluid ------------------------------------------------------------ */

static int32_t uf_find(int32_t *parent, int32_t a) {
  while (parent[a] != a) {
    parent[a] = parent[parent[a]];
    a = parent[a];
  }
  return a;
}

/* cls of every pore voxel: FLUID or EMPTY. A cluster (6-connected, image_stats.c) carries flow when
 * it touches both faces normal to the flow axis (the image module's spanning rule, shared with
 * mdp_image_drop_nonspanning); a cluster joined to such one through a periodic face of the box is
 * the same pore space seen across the boundary (a dead-end branch of the flow path) and gets fluid
 * too, so no fluid ever faces an empty pore across a periodic face. The others (isolated: touching
 * no face; dead-end: touching a face) get fluid only with isolated_pores: fill. Also fills the
 * percolation statistics mdp_image_require_percolation reads. 0, or -1 + err. */
static int classify_pores(const scene_t *s, const mdp_image_t *img, const int32_t *cl, int nc,
                          image_walls_t *g, mdp_image_stats_t *st, char *err, size_t errlen) {
  const int n[3] = {img->nx, img->ny, img->nz}, fa = s->geometry.flow_axis;
  const size_t stride[3] = {1, (size_t)n[0], (size_t)n[0] * (size_t)n[1]};
  unsigned char *faces = calloc((size_t)nc + 1, 1); /* bit 0, 1: flow faces; bit 2: any face */
  long long *size = calloc((size_t)nc + 1, sizeof *size);
  int32_t *parent = malloc(((size_t)nc + 1) * sizeof *parent);
  unsigned char *fill = calloc((size_t)nc + 1, 1);
  if (!faces || !size || !parent || !fill) {
    free(faces), free(size), free(parent), free(fill);
    snprintf(err, errlen, "%s: geometry: out of memory for %d pore clusters", s->file, nc);
    return -1;
  }
  for (int c = 0; c < nc; c++) parent[c] = c;
  for (int k = 0; k < n[2]; k++)
    for (int j = 0; j < n[1]; j++)
      for (int i = 0; i < n[0]; i++) {
        const int32_t c = cl[mdp_image_index(img, i, j, k)];
        if (c < 0) continue;
        size[c]++;
        const int ijk[3] = {i, j, k};
        for (int a = 0; a < 3; a++)
          if (ijk[a] == 0 || ijk[a] == n[a] - 1) faces[c] |= 4;
        if (ijk[fa] == 0) faces[c] |= 1;
        if (ijk[fa] == n[fa] - 1) faces[c] |= 2;
      }
  /* join clusters across the periodic faces */
  for (int a = 0; a < 3; a++) {
    if (!g->periodic[a]) continue;
    const int b = (a + 1) % 3, c2 = (a + 2) % 3;
    for (int kc = 0; kc < n[c2]; kc++)
      for (int kb = 0; kb < n[b]; kb++) {
        const size_t i0 = (size_t)kb * stride[b] + (size_t)kc * stride[c2];
        const size_t i1 = i0 + (size_t)(n[a] - 1) * stride[a];
        if (cl[i0] < 0 || cl[i1] < 0) continue;
        const int32_t r0 = uf_find(parent, cl[i0]), r1 = uf_find(parent, cl[i1]);
        if (r0 < r1)
          parent[r1] = r0;
        else if (r1 < r0)
          parent[r0] = r1;
      }
  }
  image_walls_counts_t *ct = &g->count;
  for (int c = 0; c < nc; c++)
    if ((faces[c] & 3) == 3) fill[uf_find(parent, c)] = 1;
  long long largest = 0;
  for (int c = 0; c < nc; c++) {
    if (size[c] > largest) largest = size[c];
    if ((faces[c] & 3) == 3) {
      ct->spanning++, ct->spanning_voxels += size[c];
    } else if (fill[uf_find(parent, c)]) {
      ct->joined++, ct->joined_voxels += size[c];
    } else if (!(faces[c] & 4)) {
      ct->isolated++, ct->isolated_voxels += size[c];
    } else {
      ct->dead_end++, ct->dead_end_voxels += size[c];
    }
  }
  const int fill_others = s->geometry.isolated_pores == ISOLATED_FILL;
  const size_t total = mdp_image_count(img);
  for (size_t i = 0; i < total; i++) {
    if (cl[i] < 0) continue;
    const int f = fill[uf_find(parent, cl[i])] || fill_others;
    g->cls[i] = f ? IMAGE_VOXEL_FLUID : IMAGE_VOXEL_EMPTY;
    ct->fluid_voxels += f;
  }
  memset(st, 0, sizeof *st);
  st->n_voxels = (long long)total;
  st->n_pore = ct->pore;
  st->n_clusters = nc;
  st->spans[fa] = ct->spanning > 0;
  st->largest_cluster = largest;
  free(faces), free(size), free(parent), free(fill);
  return 0;
}

/* ---- the build ------------------------------------------------------------------------------------ */

/* Wall thickness (rc): geometry.wall_thickness, or when <= 0 the largest rc + rd of the fluid-wall
 * pairs: a fluid particle then sees a full wall within every cutoff it has (forces and density). */
static double wall_thickness(const scene_t *s) {
  const scene_geometry_t *geo = &s->geometry;
  if (geo->wall_thickness > 0) return geo->wall_thickness;
  const int walls[2] = {geo->organic_species, geo->inorganic_species};
  double t = 0;
  for (int k = 0; k < 2; k++) {
    if (walls[k] < 0) continue;
    const scene_pair_t *p = &s->pair[geo->fluid_species][walls[k]];
    if (p->rc + p->rd > t) t = p->rc + p->rd;
  }
  return t;
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
static int check_moving_walls(const scene_t *s, const mdp_image_t *img, char *err, size_t errlen) {
  const scene_geometry_t *geo = &s->geometry;
  const int n[3] = {img->nx, img->ny, img->nz};
  for (int k = 0; k < 2; k++) {
    const int sp = k ? geo->inorganic_species : geo->organic_species;
    if (sp < 0 || !s->species[sp].moving) continue;
    const int ax = s->species[sp].move_axis;
    for (int z = 0; z < n[2]; z++)
      for (int y = 0; y < n[1]; y++)
        for (int x = 0; x < n[0]; x++) {
          int c[3] = {x, y, z};
          const size_t i = mdp_image_index(img, c[0], c[1], c[2]);
          if (wall_species_of_phase(geo, mdp_image_phase(img, i)) != sp) continue;
          c[ax] = (c[ax] + 1) % n[ax];
          const size_t j = mdp_image_index(img, c[0], c[1], c[2]);
          if (wall_species_of_phase(geo, mdp_image_phase(img, j)) == sp) continue;
          snprintf(err, errlen,
                   "%s: key 'species[%d].velocity': expected the solid voxels of the moving "
                   "species '%s' (geometry.species.%s) to be translation-invariant along %c, the "
                   "axis it moves along (got voxel (%d, %d, %d) of it followed by voxel (%d, %d, "
                   "%d) that is not: a moving wall must be the same after any shift along its "
                   "velocity, e.g. a slit wall)",
                   s->file, sp, s->species[sp].name, k ? "inorganic" : "organic", "xyz"[ax], x, y,
                   z, c[0], c[1], c[2]);
          return -1;
        }
  }
  return 0;
}

/* Steps of the build that every rank runs alike; -1 with the message in err. */
static int build_local(const scene_t *s, image_walls_t *g, char *err, size_t errlen) {
  const scene_geometry_t *geo = &s->geometry;
  struct stat sb;
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
  mdp_image_t img;
  if (scene_geometry_read_image(s, &img, err, errlen)) return -1;
  g->n[0] = img.nx, g->n[1] = img.ny, g->n[2] = img.nz;
  const size_t total = mdp_image_count(&img);
  image_walls_counts_t *ct = &g->count;
  ct->voxels = (long long)total;
  for (size_t i = 0; i < total; i++) {
    const int p = mdp_image_phase(&img, i);
    ct->pore += p == MDP_PHASE_PORE;
    ct->organic += p == MDP_PHASE_ORGANIC;
    ct->inorganic += p == MDP_PHASE_INORGANIC;
  }
  const long long nsolid[2] = {ct->organic, ct->inorganic};
  const int wsp[2] = {geo->organic_species, geo->inorganic_species};
  for (int k = 0; k < 2; k++)
    if (nsolid[k] > 0 && wsp[k] < 0) {
      snprintf(err, errlen,
               "%s: key 'geometry.species.%s': expected a wall species for the %lld %s voxels of "
               "%s (got none)",
               s->file, k ? "inorganic" : "organic", nsolid[k], k ? "inorganic" : "organic",
               geo->image);
      mdp_image_free(&img);
      return -1;
    }
  if (check_moving_walls(s, &img, err, errlen)) {
    mdp_image_free(&img);
    return -1;
  }
  g->cls = calloc(total ? total : 1, 1);
  int32_t *cl = malloc((total ? total : 1) * sizeof *cl);
  if (!g->cls || !cl) {
    free(cl);
    mdp_image_free(&img);
    snprintf(err, errlen, "%s: geometry: out of memory for %zu voxels", s->file, total);
    return -1;
  }
  char e[MDP_IMAGE_ERR_LEN];
  int nc = 0;
  mdp_image_stats_t st;
  if (mdp_image_label_clusters(&img, cl, &nc, e)) {
    snprintf(err, errlen, "%s: key 'geometry.image': %s", s->file, e);
    free(cl), mdp_image_free(&img);
    return -1;
  }
  ct->clusters = nc;
  int rc = classify_pores(s, &img, cl, nc, g, &st, err, errlen);
  free(cl);
  if (!rc && mdp_image_require_percolation(&img, &st, geo->flow_axis, geo->image, e)) {
    snprintf(err, errlen,
             "%s: key 'geometry.flow_axis': expected a box axis along which the pore space "
             "percolates (after axis_map): %s",
             s->file, e);
    rc = -1;
  }
  /* walls: solid voxels whose centre is within the thickness of a pore voxel centre */
  uint32_t *d2 = rc ? NULL : malloc(total * sizeof *d2);
  if (!rc && (!d2 || edt_pore(&img, g->periodic, d2))) {
    snprintf(err, errlen, "%s: geometry: out of memory for the distance transform", s->file);
    rc = -1;
  }
  if (!rc) {
    const double t = g->thickness / g->h, t2 = t * t * (1 + 1e-12);
    for (size_t i = 0; i < total; i++) {
      const int p = mdp_image_phase(&img, i);
      if (p == MDP_PHASE_PORE) continue;
      const int k = p == MDP_PHASE_INORGANIC;
      if ((double)d2[i] <= t2) {
        g->cls[i] = k ? IMAGE_VOXEL_INORGANIC : IMAGE_VOXEL_ORGANIC;
        ct->wall_voxels[k]++;
      } else {
        g->cls[i] = IMAGE_VOXEL_DEEP;
        ct->deep_voxels[k]++;
      }
    }
  }
  free(d2);
  mdp_image_free(&img);
  return rc ? -1 : 0;
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

int image_walls_build(const scene_t *s, MPI_Comm comm, image_walls_t *g) {
  const scene_geometry_t *geo = &s->geometry;
  memset(g, 0, sizeof *g);
  g->scene = s;
  g->h = geo->rc_per_voxel;
  g->min_distance = geo->min_wall_distance;
  for (int d = 0; d < 3; d++) g->lo[d] = s->box_lo[d], g->periodic[d] = s->periodic[d];
  g->thickness = wall_thickness(s);
  char err[4 * MDP_IMAGE_ERR_LEN] = "";
  int rc = build_local(s, g, err, sizeof err);
  if (agree(rc != 0, err, comm)) {
    image_walls_free(g);
    return -1;
  }
  int rank;
  MPI_Comm_rank(comm, &rank);
  const int wsp[2] = {geo->organic_species, geo->inorganic_species};
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
  /* wall voxels in voxel order and their first particles */
  image_walls_counts_t *ct = &g->count;
  const int64_t total = (int64_t)ct->voxels;
  g->n_wall_vox = (long)(ct->wall_voxels[0] + ct->wall_voxels[1]);
  g->wall_vox = malloc(((size_t)g->n_wall_vox + 1) * sizeof *g->wall_vox);
  g->wall_start = malloc(((size_t)g->n_wall_vox + 1) * sizeof *g->wall_start);
  rc = !g->wall_vox || !g->wall_start;
  if (rc) snprintf(err, sizeof err, "%s: geometry: out of memory for the wall voxels", s->file);
  long w = 0;
  g->n_wall = 0;
  for (int64_t v = 0; !rc && v < total; v++) {
    const int c = g->cls[v] & IMAGE_VOXEL_CLASS;
    if (c != IMAGE_VOXEL_ORGANIC && c != IMAGE_VOXEL_INORGANIC) continue;
    const long np = image_walls_voxel_count(g, v);
    g->wall_vox[w] = v;
    g->wall_start[w++] = g->n_wall;
    g->n_wall += np;
    ct->wall_particles[c == IMAGE_VOXEL_INORGANIC] += np;
  }
  if (!rc) g->wall_start[w] = g->n_wall;
  if (!rc) rc = image_fluid_count(g, err, sizeof err);
  if (agree(rc != 0, err, comm)) {
    image_walls_free(g);
    return -1;
  }
  return 0;
}

void image_walls_free(image_walls_t *g) {
  free(g->cls);
  free(g->wall_vox), free(g->wall_start);
  free(g->fluid_vox), free(g->fluid_start);
  wall_patches_free(&g->db);
  free(g->cache);
  memset(g, 0, sizeof *g);
}

/* ---- the particles ------------------------------------------------------------------------------- */

long image_walls_voxel_count(const image_walls_t *g, int64_t v) {
  const int c = g->cls[v] & IMAGE_VOXEL_CLASS;
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
  *id = (int64_t)i + 1;
  if (i >= g->n_wall) {
    *species = geo->fluid_species;
    image_fluid_particle(g, i - g->n_wall, x);
    return;
  }
  const long w = image_walls_find(g->wall_start, g->n_wall_vox, i);
  const int64_t v = g->wall_vox[w];
  *species = (g->cls[v] & IMAGE_VOXEL_CLASS) == IMAGE_VOXEL_ORGANIC ? geo->organic_species
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
      geo->wall_thickness > 0 ? "" : " = rc + rd of the fluid-wall pairs",
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
  fprintf(out, "  particles: %ld (walls %ld, fluid %ld), ids 1..%ld\n", image_walls_total(g),
          g->n_wall, g->n_fluid, image_walls_total(g));
  fflush(out);
}
