/* The memory plan of one rank (memory_plan.h): each item from the sizes of the structures that hold
 * it (domain/particles.h, domain/cell_list.h, backend/cpu/cpu_passes.h, domain/ghosts.h, ...) and
 * the particle counts, in double so that no product overflows. */
#include "engine/memory_plan.h"
#include "domain/cell_list.h"
#include "domain/ghosts.h"
#include "physics/wall_boundary.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

static void add(memory_plan_t *mp, const char *name, double bytes) {
  if (!(bytes > 0) || mp->n >= MEMORY_PLAN_ITEMS) return;
  mp->item[mp->n].name = name;
  mp->item[mp->n].bytes = bytes;
  mp->n++;
  mp->total += bytes;
}

/* Bins of width >= rcut over the subdomain grown by rcut each side (domain/cell_list.c). */
static double cell_count(const double extent[3], double rcut) {
  double cells = 1;
  for (int d = 0; d < 3; d++) {
    const double k = floor((extent[d] + 2 * rcut) / rcut);
    cells *= k < 1 ? 1 : k;
  }
  return cells;
}

/* Bytes of one particle slot of particles_t (id, species, x, v, f; rho, vpred, virial when on). */
static double slot_bytes(const scene_t *s, const plan_t *plan) {
  double b = sizeof(int64_t) + sizeof(int32_t) + 9 * sizeof(double);
  if (plan->density) b += sizeof(double);
  if (plan->use_vpred) b += 3 * sizeof(double);
  if (s->profile.nbins > 0 || s->flux.every > 0) b += 6 * sizeof(double); /* per-particle virial */
  return b;
}

void memory_plan_build(const scene_t *s, const plan_t *plan, const memory_inputs_t *in,
                       memory_plan_t *mp) {
  memset(mp, 0, sizeof *mp);
  const double rcut = plan->rcut > 0 ? plan->rcut : 1.0;
  const double vol = in->extent[0] * in->extent[1] * in->extent[2];
  const double grown =
      (in->extent[0] + 2 * rcut) * (in->extent[1] + 2 * rcut) * (in->extent[2] + 2 * rcut);
  mp->owned = in->owned;
  /* ghosts: the layer of width rcut around the subdomain at the rank's mean density */
  mp->ghosts = vol > 0 ? in->owned / vol * (grown - vol) : 0;
  const double slots = mp->owned + mp->ghosts, cells = cell_count(in->extent, rcut);
  add(mp, "particle arrays (owned + ghosts)", slots * slot_bytes(s, plan));
  if (in->backend == SCENE_BACKEND_CPU) {
    add(mp, "cell list",
        slots * (2 * sizeof(int) + 3 * sizeof(double)) + (cells + 1) * sizeof(int));
    /* The list room per particle (backend/cpu/neighbour_list.c): 64, grown to the most neighbours
     * within rcut over the particles + 1/4 + 8. The mean is n 4/3 pi rcut^3; the most, over ~1e5 particles of
     * a liquid, about 4.5 standard deviations (sqrt of the mean) above it. */
    const double mean = in->density * 4.0 / 3.0 * 3.14159265358979323846 * rcut * rcut * rcut;
    const double most = ceil(mean + 4.5 * sqrt(mean));
    mp->stride = floor(most + most / 4) + 8;
    if (mp->stride < 64) mp->stride = 64; /* the first room */
    add(mp, "neighbour lists", mp->owned * (2 + mp->stride) * sizeof(int));
    add(mp, "sort scratch", mp->owned * (2 * sizeof(int) + sizeof(double)) + cells * sizeof(int));
    if (plan->density_cache) { /* table of 2-4 x the static particles (16 B), prefix, rho_static */
      add(mp, "density cache", mp->owned * (4 * 16 + sizeof(double)) + (slots + 1) * sizeof(int));
    }
    if (plan->wall_field) add(mp, "wall field", mp->owned * sizeof(wall_field_t));
  }
  add(mp, "ghost exchange buffers", mp->ghosts * (2 * (double)ghosts_record_bytes() + sizeof(int)));
  double arrays = 0;
  for (int k = 0; k < plan->n_arrays; k++) arrays += (double)plan->arrays[k].bytes;
  add(mp, "effect arrays (bounce_back's solid map)", arrays);
  /* analysis/penetration.c: the image (1 B), the depth map (float), and while it is made a queue
   * (size_t) and a seen flag (1 B) per voxel */
  add(mp, "pore depth map (penetration count; while built)", in->voxels * (1 + 4 + 8 + 1));
  add(mp, "geometry build (image window, particle list)", in->build_bytes);
  /* io/particle_set.h: id, species, x, v (+ f in a checkpoint, rho in a snapshot) */
  const double set_bytes = sizeof(int64_t) + sizeof(int32_t) + 6 * sizeof(double);
  add(mp, "initial configuration (read on every rank)", in->input_set * (set_bytes + 8));
  /* io/gather.c: snapshot, dump and checkpoint gather every particle on rank 0, then sort by id
   * (a copy of one array and a permutation) */
  if (s->snapshot.every > 0 || s->dump.every > 0 || s->checkpoint.every > 0)
    add(mp, "output gather (rank 0)", in->total * (set_bytes + 4 * sizeof(double) + 16));
  mp->device = in->device_bytes_per_particle * mp->owned;
}

const char *memory_bytes_text(double bytes, char *buf, size_t len) {
  if (bytes >= 1e9)
    snprintf(buf, len, "%.3g GB", bytes / 1e9);
  else if (bytes >= 1e6)
    snprintf(buf, len, "%.3g MB", bytes / 1e6);
  else
    snprintf(buf, len, "%.3g kB", bytes / 1e3);
  return buf;
}

void memory_plan_print(const memory_plan_t *mp, FILE *out) {
  char b[32];
  fprintf(out, "memory plan per rank (%.4g owned particles, %.4g ghosts):\n", mp->owned,
          mp->ghosts);
  for (int k = 0; k < mp->n; k++)
    fprintf(out, "  %-48s %s\n", mp->item[k].name,
            memory_bytes_text(mp->item[k].bytes, b, sizeof b));
  fprintf(out, "  %-48s %s\n", "total (host)", memory_bytes_text(mp->total, b, sizeof b));
  if (mp->device > 0)
    fprintf(out, "  %-48s %s\n", "GPU (CUDA path, one per rank)",
            memory_bytes_text(mp->device, b, sizeof b));
}

void memory_plan_largest(const memory_plan_t *mp, char *out, size_t len) {
  int used[MEMORY_PLAN_ITEMS] = {0};
  size_t at = 0;
  out[0] = 0;
  for (int r = 0; r < 3 && r < mp->n; r++) {
    int best = -1;
    for (int k = 0; k < mp->n; k++)
      if (!used[k] && (best < 0 || mp->item[k].bytes > mp->item[best].bytes)) best = k;
    used[best] = 1;
    char b[32];
    const int w = snprintf(out + at, len - at, "%s%s %s", r ? ", " : "", mp->item[best].name,
                           memory_bytes_text(mp->item[best].bytes, b, sizeof b));
    if (w < 0 || (size_t)w >= len - at) break;
    at += (size_t)w;
  }
}

double memory_geometry_build_bytes(double window, double gen, double lines, double segments,
                                   int labels) {
  /* per window voxel while the window is held: its phase and class (1 B each) and the label entry
   * (1 B, with fluid_species_labels) */
  const double w = window * (2 + (labels ? 1 : 0));
  /* image_window.c: the phases and label entries, and one piece of the file read (<= the window) */
  const double read = window * (labels ? 2 : 1) + window;
  /* image_clusters_mpi.c: an int32 label per gen voxel, 10 B per local cluster (<= one per gen
   * voxel) */
  const double clusters = w + gen * (4 + 10);
  /* image_walls.c: the squared distances of the distance transform (uint32 per window voxel) */
  const double edt = w + window * 4;
  /* after the phases are freed: image_fluid.c's kept counts (uint16 per gen voxel) and a key and a
   * voxel (16 B) per own voxel (<= gen) */
  const double held = w - window;
  const double fluid = held + gen * (2 + 16);
  /* image_ids.c: 16 B per x line and segment, and the local lists of wall and fluid voxels (24 B
   * an entry; capacities doubled from 1024, so at most twice the gen voxels, plus 2 x 1024) */
  const double ids = held + gen * 2 + lines * segments * 16 + (2 * gen + 2048) * 24;
  double peak = read;
  const double stage[4] = {clusters, edt, fluid, ids};
  for (int k = 0; k < 4; k++)
    if (stage[k] > peak) peak = stage[k];
  return peak;
}

double memory_scene_density(const scene_t *s) {
  double rho = 0;
  for (int k = 0; k < s->init.n_fill; k++)
    if (s->init.fill[k].density > rho) rho = s->init.fill[k].density;
  if (s->geometry.on) {
    if (s->geometry.fluid_density > rho) rho = s->geometry.fluid_density;
    if (s->geometry.wall_density > rho) rho = s->geometry.wall_density;
  }
  return rho;
}

void memory_inputs_from_scene(const scene_t *s, const int dims[3], memory_inputs_t *in) {
  memset(in, 0, sizeof *in);
  double box = 1;
  for (int d = 0; d < 3; d++) {
    in->extent[d] = (s->box_hi[d] - s->box_lo[d]) / dims[d];
    box *= s->box_hi[d] - s->box_lo[d];
  }
  const double ranks = (double)dims[0] * dims[1] * dims[2];
  in->density = memory_scene_density(s);
  if (s->init.kind == INIT_FILL)
    for (int k = 0; k < s->init.n_fill; k++) {
      const scene_fill_t *f = &s->init.fill[k];
      in->total +=
          f->density * (f->hi[0] - f->lo[0]) * (f->hi[1] - f->lo[1]) * (f->hi[2] - f->lo[2]);
    }
  if (s->init.kind == INIT_GEOMETRY) {
    in->total = in->density * box;
    const double h = s->geometry.rc_per_voxel;
    double n[3];
    in->voxels = 1;
    for (int d = 0; d < 3; d++) {
      n[d] = h > 0 ? ceil((s->box_hi[d] - s->box_lo[d]) / h) : 1;
      in->voxels *= n[d];
    }
    /* the build of an equal share of the image per rank (its halo left out) */
    in->build_bytes =
        memory_geometry_build_bytes(in->voxels / ranks, in->voxels / ranks, n[1] * n[2], dims[0],
                                    s->geometry.n_species_labels > 0);
  }
  in->owned = in->total / ranks;
  in->backend = s->backend;
}
