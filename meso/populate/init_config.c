/* Initial configuration: offer a global particle source to the engine, generating Maxwell-Boltzmann
 * velocities (momentum-free) where the source has none. */
#include "populate/init_config.h"
#include "populate/image_walls.h"
#include "populate/lammps_data.h"
#include "io/snapshot.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* A global particle source: particle i of n (same on every rank). */
typedef void (*source_get_fn)(const void *ctx, long i, int64_t *id, int *species, double x[3],
                              double v[3]);

static int offer_source(sim_t *sim, const scene_t *s, long n, source_get_fn get, const void *ctx,
                        int has_v, const char *source) {
  MPI_Comm comm = sim_comm(sim);
  int rank;
  MPI_Comm_rank(comm, &rank);
  const double kT = s->init.temperature;
  /* Pass 1: centre-of-mass velocity of the generated mobile velocities, summed in global order on
   * every rank (bitwise the same everywhere, whatever the decomposition). */
  double vcm[3] = {0, 0, 0};
  if (!has_v) {
    double p[3] = {0, 0, 0}, mass = 0;
    for (long i = 0; i < n; i++) {
      int64_t id;
      int sp;
      double x[3], v[3];
      get(ctx, i, &id, &sp, x, v);
      if (s->species[sp].frozen) continue;
      init_mb_velocity(s, id, sp, kT, v);
      for (int d = 0; d < 3; d++) p[d] += s->species[sp].mass * v[d];
      mass += s->species[sp].mass;
    }
    for (int d = 0; d < 3; d++) vcm[d] = mass > 0 ? p[d] / mass : 0;
  }
  long stored = 0;
  int fail = 0;
  for (long i = 0; i < n && !fail; i++) {
    int64_t id;
    int sp;
    double x[3], v[3];
    get(ctx, i, &id, &sp, x, v);
    if (s->species[sp].frozen) {
      v[0] = v[1] = v[2] = 0;
    } else if (!has_v) {
      init_mb_velocity(s, id, sp, kT, v);
      for (int d = 0; d < 3; d++) v[d] -= vcm[d];
    }
    const int r = sim_add_particle(sim, id, sp, x, v);
    if (r < 0) fail = 1;
    stored += r > 0;
  }
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  if (fail) {
    if (rank == 0) fprintf(stderr, "%s: out of memory while adding %ld particles\n", source, n);
    return -1;
  }
  MPI_Allreduce(MPI_IN_PLACE, &stored, 1, MPI_LONG, MPI_SUM, comm);
  if (stored != n) {
    if (rank == 0)
      fprintf(
          stderr,
          "%s: %ld particles generated but %ld stored (positions outside a non-periodic box?)\n",
          source, n, stored);
    return -1;
  }
  return 0;
}

/* Volume of the overlap of box [alo, ahi) with box [blo, bhi). */
static double overlap_volume(const double alo[3], const double ahi[3], const double blo[3],
                             const double bhi[3]) {
  double v = 1;
  for (int d = 0; d < 3; d++) {
    const double lo = alo[d] > blo[d] ? alo[d] : blo[d], hi = ahi[d] < bhi[d] ? ahi[d] : bhi[d];
    v *= hi > lo ? hi - lo : 0;
  }
  return v;
}

/* The memory plan (engine/memory_plan.h) of n_total particles spread evenly over the box, before
 * they are added: this rank's share is n_total times its subdomain's share of the box. */
static int check_memory_even(sim_t *sim, const scene_t *s, double n_total, double input_set) {
  double lo[3], hi[3];
  sim_subdomain(sim, lo, hi);
  const double box = overlap_volume(s->box_lo, s->box_hi, s->box_lo, s->box_hi);
  memory_inputs_t in = {0};
  in.total = n_total;
  in.owned = box > 0 ? n_total * overlap_volume(lo, hi, s->box_lo, s->box_hi) / box : n_total;
  in.input_set = input_set;
  in.density = memory_scene_density(s);
  if (box > 0 && n_total / box > in.density) in.density = n_total / box;
  return sim_memory_check(sim, &in);
}

/* Fill regions: global index -> (region, index in region); ids are 1 + global index. */
typedef struct {
  const scene_t *s;
  long start[SCENE_MAX_FILLS + 1];
  long *kept[SCENE_MAX_FILLS]; /* shaped fills: candidate index of each kept particle */
} fill_ctx_t;

static void fill_get(const void *vctx, long i, int64_t *id, int *sp, double x[3], double v[3]) {
  const fill_ctx_t *c = vctx;
  int k = 0;
  while (i >= c->start[k + 1]) k++;
  *id = (int64_t)i + 1;
  *sp = c->s->init.fill[k].species;
  const long j = i - c->start[k];
  init_fill_position(c->s, k, c->kept[k] ? c->kept[k][j] : j, x);
  v[0] = v[1] = v[2] = 0;
}

static void set_get(const void *vctx, long i, int64_t *id, int *sp, double x[3], double v[3]) {
  const particle_set_t *set = vctx;
  *id = set->id[i];
  *sp = set->species[i];
  for (int d = 0; d < 3; d++) {
    x[d] = set->x[3 * i + d];
    v[d] = set->v[3 * i + d];
  }
}

/* The geometry builder (populate/image_walls.h): each rank builds the particles of the voxels that
 * overlap its subdomain and offers them. The centre-of-mass velocity removed is that of the whole
 * list summed in id order, as offer_source sums it: the walls (ids 1..n_wall) are frozen, the fluid
 * takes ids n_wall + 1 .. total, and a Maxwell-Boltzmann velocity depends on the id and species
 * alone, so every rank sums the same numbers in the same order without the list (O(fluid) time). */
static int offer_geometry(sim_t *sim, const scene_t *s) {
  MPI_Comm comm = sim_comm(sim);
  int rank;
  MPI_Comm_rank(comm, &rank);
  double sub_lo[3], sub_hi[3];
  sim_subdomain(sim, sub_lo, sub_hi);
  /* the build's own peak and the image's voxel maps, before anything is read or allocated (the
   * particles are counted by the build, then checked below) */
  image_walls_plan_t wp;
  const int planned = !image_walls_plan(s, comm, sub_lo, sub_hi, &wp);
  if (planned) {
    char stage[1536];
    snprintf(
        stage, sizeof stage,
        "the geometry build of key 'geometry.image' (%.1000s: %d x %d x %d voxels, a window of "
        "%lld of them on rank 0)",
        s->geometry.image, wp.n[0], wp.n[1], wp.n[2], wp.window);
    memory_inputs_t pre = {0};
    pre.density = memory_scene_density(s);
    pre.voxels = (double)wp.n[0] * wp.n[1] * wp.n[2];
    pre.build_bytes = wp.bytes;
    pre.stage = stage;
    if (sim_memory_check(sim, &pre)) return -1;
  }
  image_walls_t g;
  if (image_walls_build_local(s, comm, sub_lo, sub_hi, &g)) return -1;
  if (rank == 0) image_walls_report(&g, stdout);
  if (planned) { /* what was checked before the build, against the peak the report just gave */
    double most = wp.bytes;
    MPI_Allreduce(MPI_IN_PLACE, &most, 1, MPI_DOUBLE, MPI_MAX, comm);
    if (rank == 0)
      printf("  build checked before it ran: at most %.4g MB per rank (the largest rank's upper "
             "bound)\n",
             most / 1e6);
    fflush(stdout);
  }
  memory_inputs_t in = {0};
  in.owned = (double)image_walls_local(&g);
  in.total = (double)image_walls_total(&g);
  in.density = memory_scene_density(s);
  in.voxels = (double)g.n[0] * g.n[1] * g.n[2];
  in.build_bytes = (double)g.mem_now;
  if (sim_memory_check(sim, &in)) {
    image_walls_free(&g);
    return -1;
  }
  const double kT = s->init.temperature;
  const int fsp = s->geometry.fluid_species;
  double vcm[3] = {0, 0, 0}, p[3] = {0, 0, 0}, mass = 0;
  for (long i = g.n_wall; i < image_walls_total(&g); i++) {
    double v[3];
    init_mb_velocity(s, (int64_t)i + 1, fsp, kT, v);
    for (int d = 0; d < 3; d++) p[d] += s->species[fsp].mass * v[d];
    mass += s->species[fsp].mass;
  }
  for (int d = 0; d < 3; d++) vcm[d] = mass > 0 ? p[d] / mass : 0;
  const long n = image_walls_local(&g);
  long stored = 0;
  int fail = 0;
  for (long i = 0; i < n && !fail; i++) {
    int64_t id;
    int sp;
    double x[3], v[3] = {0, 0, 0};
    image_walls_particle(&g, i, &id, &sp, x);
    if (!s->species[sp].frozen) {
      init_mb_velocity(s, id, sp, kT, v);
      for (int d = 0; d < 3; d++) v[d] -= vcm[d];
    }
    const int r = sim_add_particle(sim, id, sp, x, v);
    if (r < 0) fail = 1;
    stored += r > 0;
  }
  const long total = image_walls_total(&g);
  image_walls_free(&g);
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  if (fail) {
    if (rank == 0) fprintf(stderr, "%s: out of memory while adding %ld particles\n", s->file, n);
    return -1;
  }
  MPI_Allreduce(MPI_IN_PLACE, &stored, 1, MPI_LONG, MPI_SUM, comm);
  if (stored != total) {
    if (rank == 0)
      fprintf(stderr,
              "%s: geometry: %ld particles in the list but %ld stored (a particle kept by no "
              "rank or by two: a bug of the rank-local build)\n",
              s->file, total, stored);
    return -1;
  }
  return 0;
}

int init_offer_set(sim_t *sim, const scene_t *s, const particle_set_t *set, const char *source) {
  return offer_source(sim, s, set->n, set_get, set, set->has_v, source);
}

int init_configuration(sim_t *sim, const scene_t *s) {
  MPI_Comm comm = sim_comm(sim);
  if (s->init.kind == INIT_FILL) {
    fill_ctx_t c = {.s = s};
    int rank;
    MPI_Comm_rank(comm, &rank);
    int oom = 0;
    for (int k = 0; k < s->init.n_fill; k++) {
      const scene_fill_t *f = &s->init.fill[k];
      if (f->shape != FILL_SHAPE_NONE) {
        oom |= !(c.kept[k] = init_fill_kept_list(s, k));
        c.start[k + 1] = c.start[k] + (c.kept[k] ? init_fill_kept(s, k, NULL) : 0);
        continue; /* the shape's volume is not the region's: no density check */
      }
      c.start[k + 1] = c.start[k] + init_fill_count(s, k);
      const double vol = (f->hi[0] - f->lo[0]) * (f->hi[1] - f->lo[1]) * (f->hi[2] - f->lo[2]);
      const double got = init_fill_count(s, k) / vol;
      if (rank == 0 && fabs(got / f->density - 1) > 0.01)
        fprintf(
            stderr,
            "%s: warning: initial.fill[%d]: the %s fill realises density %.4g (requested %.4g)\n",
            s->file, k, f->mode == FILL_LATTICE ? "lattice" : "random", got, f->density);
    }
    /* the memory plan: each fill's particles spread evenly over its region */
    double lo[3], hi[3];
    sim_subdomain(sim, lo, hi);
    memory_inputs_t in = {0};
    in.total = (double)c.start[s->init.n_fill];
    in.density = memory_scene_density(s);
    for (int k = 0; k < s->init.n_fill; k++) {
      const scene_fill_t *f = &s->init.fill[k];
      const double vol = overlap_volume(f->lo, f->hi, f->lo, f->hi);
      const double n = (double)(c.start[k + 1] - c.start[k]);
      in.owned += vol > 0 ? n * overlap_volume(f->lo, f->hi, lo, hi) / vol : n;
    }
    int rc = oom ? -1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &rc, 1, MPI_INT, MPI_MIN, comm); /* (every rank checks, or none) */
    if (!rc) rc = sim_memory_check(sim, &in);
    if (!rc) rc = offer_source(sim, s, c.start[s->init.n_fill], fill_get, &c, 0, s->file);
    if (oom && rank == 0)
      fprintf(stderr, "%s: out of memory for the shaped fill regions\n", s->file);
    for (int k = 0; k < s->init.n_fill; k++) free(c.kept[k]);
    return rc;
  }
  if (s->init.kind == INIT_GEOMETRY) return offer_geometry(sim, s);
  particle_set_t set;
  int rc = s->init.kind == INIT_LAMMPS_DATA ? lammps_data_read_bcast(s->init.path, s, comm, &set)
                                            : snapshot_read_bcast(s->init.path, s, comm, &set);
  if (rc) return -1;
  rc = check_memory_even(sim, s, (double)set.n, (double)set.n);
  if (!rc) rc = init_offer_set(sim, s, &set, s->init.path);
  particle_set_free(&set);
  return rc;
}
