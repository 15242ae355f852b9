/* Device memory of the CUDA backend: allocation with byte accounting, growth, error reporting. */
#include "cuda_select.cuh"

#include "common/memory_limit.h"

#include <cub/device/device_radix_sort.cuh>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* What to try when the GPU has no room (docs/engine-cuda.md "Memory modes"). */
static const char advice[] =
    "try --gpu-memory compact (no neighbour lists, <= 200 bytes per particle), fewer particles (a "
    "coarser geometry.rc_per_voxel, a smaller crop of the image, a smaller box) or more ranks, one "
    "GPU each";

/* The device's free and total bytes; 0 when cudaMemGetInfo fails (a sticky error). */
static int device_memory(size_t *free_b, size_t *total_b) {
  *free_b = *total_b = 0;
  return cudaMemGetInfo(free_b, total_b) == cudaSuccess;
}

/* The device memory the plan may count on: the free memory, capped by MDPORE_GPU_MEMORY_LIMIT
 * (bytes, suffix K/M/G/T allowed; docs/engine-cuda.md "Memory plan"). */
static double plan_free_bytes(size_t free_b) {
  const double cap = mdp_parse_bytes(getenv("MDPORE_GPU_MEMORY_LIMIT"));
  return cap > 0 && cap < (double)free_b ? cap : (double)free_b;
}

int cuda_check_alloc(cudaError_t e, const char *what, size_t bytes, const char *where) {
  if (e == cudaSuccess) return 0;
  if (e == cudaErrorMemoryAllocation) (void)cudaGetLastError(); /* not sticky: clear it */
  size_t free_b, total_b;
  fprintf(stderr, "mdpore: CUDA backend: cannot allocate %s", what);
  if (bytes) fprintf(stderr, " (%.4g MB)", (double)bytes / 1e6);
  fprintf(stderr, " on the %s: %s; ", where, cudaGetErrorString(e));
  if (device_memory(&free_b, &total_b))
    fprintf(stderr, "the GPU has %.4g GB free of %.4g GB; ", (double)free_b / 1e9,
            (double)total_b / 1e9);
  fprintf(stderr, "%s\n", advice);
  return -1;
}

int cuda_check(cudaError_t e, const char *what) {
  if (e == cudaSuccess) return 0;
  if (e == cudaErrorMemoryAllocation) return cuda_check_alloc(e, what, 0, "GPU");
  fprintf(stderr, "mdpore: CUDA error in %s: %s\n", what, cudaGetErrorString(e));
  return -1;
}

int cuda_alloc_named(struct cuda_sim *g, void **ptr, size_t bytes, const char *what) {
  *ptr = NULL;
  if (bytes == 0) return 0;
  const char *amp = strrchr(what, '&'); /* "(void **)&g->rho" names g->rho */
  char name[96];
  snprintf(name, sizeof name, "device array %s", amp ? amp + 1 : what);
  if (cuda_check_alloc(cudaMalloc(ptr, bytes), name, bytes, "GPU")) {
    *ptr = NULL;
    return -1;
  }
  g->bytes += bytes;
  return 0;
}

void cuda_free_ptr(struct cuda_sim *g, void **ptr) {
  (void)g;
  if (*ptr) cudaFree(*ptr);
  *ptr = NULL;
}

static void free_fields(struct cuda_sim *g, struct dev_fields *f) {
  cuda_free_ptr(g, (void **)&f->id);
  cuda_free_ptr(g, (void **)&f->species);
  for (int d = 0; d < 3; d++) {
    cuda_free_ptr(g, (void **)&f->x[d]);
    cuda_free_ptr(g, (void **)&f->v[d]);
    cuda_free_ptr(g, (void **)&f->f[d]);
    cuda_free_ptr(g, (void **)&f->vpred[d]);
  }
}

/* In the compact mode on one rank every field array takes 8 bytes per slot (species too), so that
 * the sort can gather any field into sort_scratch and swap the two pointers (cuda_cells.cu). */
static int one_set(const struct cuda_sim *g) {
  return g->compact && !g->prm.multi;
}

static int alloc_fields(struct cuda_sim *g, struct dev_fields *f, int cap) {
  const size_t n = (size_t)cap;
  int rc = cuda_alloc(g, (void **)&f->id, n * sizeof(int64_t)) ||
           cuda_alloc(g, (void **)&f->species, n * (one_set(g) ? 8 : sizeof(int32_t)));
  for (int d = 0; d < 3 && !rc; d++) {
    rc = cuda_alloc(g, (void **)&f->x[d], n * sizeof(double)) ||
         cuda_alloc(g, (void **)&f->v[d], n * sizeof(double)) ||
         cuda_alloc(g, (void **)&f->f[d], n * sizeof(double));
    if (!rc && g->prm.use_vpred) rc = cuda_alloc(g, (void **)&f->vpred[d], n * sizeof(double));
  }
  return rc ? -1 : 0;
}

/* Room for cap slots; contents are not kept. */
static int reserve_cap(struct cuda_sim *g, int n, int cap) {
  free_fields(g, &g->a);
  free_fields(g, &g->b);
  cuda_free_ptr(g, (void **)&g->rho);
  cuda_free_ptr(g, (void **)&g->key);
  cuda_free_ptr(g, (void **)&g->key_sorted);
  cuda_free_ptr(g, (void **)&g->iota);
  cuda_free_ptr(g, (void **)&g->perm);
  cuda_free_ptr(g, &g->sort_tmp);
  cuda_free_ptr(g, (void **)&g->block_virial);
  cuda_free_ptr(g, (void **)&g->virial);
  cuda_free_ptr(g, (void **)&g->pos);
  cuda_free_ptr(g, (void **)&g->vel);
  cuda_free_ptr(g, (void **)&g->nbr);
  cuda_free_ptr(g, (void **)&g->nbr_count);
  cuda_free_ptr(g, (void **)&g->rho_stage);
  cuda_free_ptr(g, (void **)&g->pos0);
  cuda_free_ptr(g, (void **)&g->wall_field);
  cuda_free_ptr(g, (void **)&g->sort_scratch);
  cuda_free_ptr(g, (void **)&g->mobile_slot); /* (made again by the next force pass) */
  cuda_free_ptr(g, (void **)&g->mobile_count);
  cuda_free_ptr(g, (void **)&g->tail_rho);
  g->tail_rho_bytes = 0;
  g->tail_rho_ready = 0;
  g->mobile_slot_bytes = 0;
  g->prm.pe.wall_boundary.field = NULL;
  g->lists_valid = 0;
  g->nbr_stride = 0;
  g->virial_cap = 0;
  g->bytes = g->fixed_bytes;
  if (!g->compact && n >= (1 << NBR_SLOT_BITS) - 4096) {
    fprintf(stderr, "mdpore: CUDA backend: %d particles on one GPU: at most %d\n", n,
            (1 << NBR_SLOT_BITS) - 4096);
    return -1;
  }
  const size_t c = (size_t)cap;
  const int blocks = (cap + CUDA_BLOCK - 1) / CUDA_BLOCK;
  size_t tmp = 0;
  if (one_set(g)) { /* the double-buffer sort: no key / value copies in its temporary storage */
    cub::DoubleBuffer<uint32_t> keys(NULL, NULL);
    cub::DoubleBuffer<int> values(NULL, NULL);
    cub::DeviceRadixSort::SortPairs(NULL, tmp, keys, values, cap);
  } else {
    cub::DeviceRadixSort::SortPairs(NULL, tmp, (const uint32_t *)NULL, (uint32_t *)NULL,
                                    (const int *)NULL, (int *)NULL, cap);
  }
  if (alloc_fields(g, &g->a, cap) || (!one_set(g) && alloc_fields(g, &g->b, cap)) ||
      (one_set(g) && cuda_alloc(g, (void **)&g->sort_scratch, c * sizeof(double))) ||
      (g->prm.density && cuda_alloc(g, (void **)&g->rho, c * sizeof(meso_real))) ||
      cuda_alloc(g, (void **)&g->key, c * sizeof(uint32_t)) ||
      cuda_alloc(g, (void **)&g->key_sorted, c * sizeof(uint32_t)) ||
      cuda_alloc(g, (void **)&g->iota, c * sizeof(int)) ||
      cuda_alloc(g, (void **)&g->perm, c * sizeof(int)) ||
      cuda_alloc(g, (void **)&g->pos, c * sizeof(struct dev_pos)) ||
      (!one_set(g) && cuda_alloc(g, (void **)&g->nbr_count, c * sizeof(int))) ||
      (g->prm.multi && g->prm.density &&
       cuda_alloc(g, (void **)&g->rho_stage, c * sizeof(meso_real))) ||
      ((g->prm.terms & PAIR_TERM_THERMOSTAT) &&
       cuda_alloc(g, (void **)&g->vel, c * sizeof(struct dev_vel))) ||
      (g->prm.pe.on[EFFECT_WALL_BOUNDARY] &&
       cuda_alloc(g, (void **)&g->wall_field, c * sizeof(wall_field_t))) ||
      cuda_alloc(g, &g->sort_tmp, tmp) ||
      cuda_alloc(g, (void **)&g->block_virial, (size_t)blocks * 6 * sizeof(double)))
    return -1;
  g->prm.pe.wall_boundary.field = g->wall_field;
  g->sort_tmp_bytes = tmp;
  g->block_virial_cap = blocks;
  g->cap = cap;
  return 0;
}

int cuda_tight_room(void) {
  const char *tight = getenv("MDPORE_CUDA_TIGHT_ROOM");
  return tight && !strcmp(tight, "1");
}

/* Slots for need particles with a margin; several ranks leave room for the ghost layer, which
 * cuda_grow widens when a step needs more (MDPORE_CUDA_TIGHT_ROOM=1: almost no margin, so that the
 * tests exercise the growth). */
static int room_for(const struct cuda_sim *g, int need) {
  if (!g->prm.multi) return need + need / 16 + 256;
  if (cuda_tight_room()) return need + 64;
  return need + need / 4 + 4096;
}

/* Bytes per slot of the fast mode's arrays besides the lists (reserve_cap), and the list room a
 * run of mDPD water at rho 6.2-8 ends up with (strides of ~128 entries measured on the porous
 * benchmark: bench/RESULTS.md, 791 bytes per particle). The auto mode's choice. */
static size_t fast_bytes_per_slot(const struct cuda_sim *g) {
  const size_t set = 8 + 4 + 3 * 3 * 8 + (g->prm.use_vpred ? 3 * 8 : 0);
  return 2 * set + sizeof(meso_real) + 4 * 4 + sizeof(struct dev_pos) + 4 +
         ((g->prm.terms & PAIR_TERM_THERMOSTAT) ? sizeof(struct dev_vel) : 0) + 8 /* sort */ +
         128 * 4 /* lists */;
}

/* The device plan per slot: the arrays reserve_cap makes in a memory mode (compact or not), the
 * lists of the fast mode at the room fast_bytes_per_slot counts, the wall field and the sort's
 * temporary storage (~8 bytes). */
static size_t plan_bytes_per_slot(int use_vpred, int thermostat, int density, int wall_field,
                                  int terms, int multi, int compact) {
  const int one_set = compact && !multi;
  const size_t set = 8 + (one_set ? 8 : 4) + 3 * 3 * 8 + (use_vpred ? 3 * 8 : 0);
  size_t b = (one_set ? set + 8 /* sort_scratch */ : 2 * set) + 4 * 4 /* keys, iota, perm */ +
             sizeof(struct dev_pos) + 8 /* sort */;
  if (density) b += sizeof(meso_real) * (multi ? 2 : 1); /* rho (+ rho_stage) */
  if (!one_set) b += 4;                                  /* nbr_count */
  if (thermostat) b += sizeof(struct dev_vel);
  if (wall_field) b += sizeof(wall_field_t);
  if (!compact && terms) b += 128 * 4; /* lists */
  return b;
}

static size_t sim_plan_bytes_per_slot(const struct cuda_sim *g, int compact) {
  return plan_bytes_per_slot(g->prm.use_vpred, (g->prm.terms & PAIR_TERM_THERMOSTAT) != 0,
                             g->prm.density, g->prm.pe.on[EFFECT_WALL_BOUNDARY], g->prm.terms,
                             g->prm.multi, compact);
}

extern "C" double cuda_device_bytes_per_particle(const plan_t *plan, int nranks, int gpu_memory) {
  const int multi = nranks > 1;
  const double slots = multi ? 1.25 : 1.0625; /* room_for's margin */
  return slots * (double)plan_bytes_per_slot(
                     plan->use_vpred, (plan->pair_terms & PAIR_TERM_THERMOSTAT) != 0, plan->density,
                     plan->named[EFFECT_WALL_BOUNDARY], plan->pair_terms, multi,
                     gpu_memory == SCENE_GPU_MEMORY_COMPACT);
}

/* Room for n particles; contents are not kept (called before an upload only). With --gpu-memory
 * auto the fast mode is kept unless its estimate exceeds 92% of the device's free memory. Then the
 * device plan: the arrays of the mode (with the fast mode's lists) against the free memory (capped
 * by MDPORE_GPU_MEMORY_LIMIT) and what this run's particle arrays hold now (made again here); over
 * it, a refusal naming the sizes and what to try, before any allocation. */
int cuda_reserve(struct cuda_sim *g, int n) {
  if (n <= g->cap) return 0;
  if (!g->compact && g->memory_request == SCENE_GPU_MEMORY_AUTO && g->prm.terms) {
    size_t free_b = 0, total_b = 0;
    const double need = (double)room_for(g, n) * (double)fast_bytes_per_slot(g);
    const int info = cudaMemGetInfo(&free_b, &total_b) == cudaSuccess;
    /* test hook: pretend this much is free (ctest cuda_memory_auto) */
    const char *fake = getenv("MDPORE_CUDA_TEST_FREE_BYTES");
    if (info && fake && *fake) free_b = (size_t)strtod(fake, NULL);
    if (info && need > 0.92 * (double)free_b) {
      char why[256];
      snprintf(why, sizeof why,
               "the fast mode would need ~%.1f GB for %d particles, %.1f GB of %.1f GB are free",
               need / 1e9, n, (double)free_b / 1e9, (double)total_b / 1e9);
      if (cuda_go_compact(g, why)) return -1;
    }
  }
  size_t free_b = 0, total_b = 0;
  if (device_memory(&free_b, &total_b)) {
    const double slots = (double)room_for(g, n);
    const double per_slot = (double)sim_plan_bytes_per_slot(g, g->compact);
    const double need = slots * per_slot, free_plan = plan_free_bytes(free_b);
    const double held = g->bytes > g->fixed_bytes ? (double)(g->bytes - g->fixed_bytes) : 0.0;
    if (need > free_plan + held) {
      fprintf(stderr,
              "mdpore: CUDA backend: not enough GPU memory: %d particles need ~%.4g GB in the %s "
              "mode (%.0f slots x %.0f bytes: particle fields, sort keys, packed positions%s%s) "
              "but %.4g GB are free (%s; the GPU has %.4g GB, this run holds %.4g GB there); "
              "%s\n",
              n, need / 1e9, g->compact ? "compact" : "fast", slots, per_slot,
              g->compact ? "" : ", neighbour lists of 128 entries",
              g->prm.pe.on[EFFECT_WALL_BOUNDARY] ? ", wall field" : "", free_plan / 1e9,
              free_plan < (double)free_b ? "MDPORE_GPU_MEMORY_LIMIT" : "cudaMemGetInfo",
              (double)total_b / 1e9, (double)g->bytes / 1e9, advice);
      return -1;
    }
  }
  return reserve_cap(g, n, room_for(g, n));
}

static int copy_on_device(void *dst, const void *src, size_t bytes, const char *what) {
  return bytes ? cuda_check(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToDevice), what) : 0;
}

static int copy_back(void *dst, const void *src, size_t bytes) {
  return copy_on_device(dst, src, bytes, "grow");
}

int cuda_copy_fields(struct dev_fields *dst, const struct dev_fields *src, size_t k, size_t m,
                     const char *what) {
  int rc = copy_on_device(dst->id + k, src->id + k, m * 8, what) ||
           copy_on_device(dst->species + k, src->species + k, m * 4, what);
  for (int d = 0; d < 3 && !rc; d++)
    rc = copy_on_device(dst->x[d] + k, src->x[d] + k, m * 8, what) ||
         copy_on_device(dst->v[d] + k, src->v[d] + k, m * 8, what) ||
         copy_on_device(dst->f[d] + k, src->f[d] + k, m * 8, what) ||
         (src->vpred[d] && copy_on_device(dst->vpred[d] + k, src->vpred[d] + k, m * 8, what));
  return rc ? -1 : 0;
}

/* Room for need slots, keeping the owned particles [0, n), their bins (key_sorted), boundary flags
 * (key) and the boundary permutation (perm[0, n_boundary)); everything else is rebuilt by the
 * passes that follow. Waits for the work in flight. 0 or -1. */
static int realloc_keep(struct cuda_sim *g, int need);

int cuda_grow(struct cuda_sim *g, int need) {
  if (need <= g->cap) return 0;
  return realloc_keep(g, need);
}

/* Compact mode from now on (docs/engine-cuda.md "Memory modes"); called before the first upload
 * (auto) or when a list would not fit (cuda_density.cu). Every array is re-made in the new mode,
 * the particles kept. */
int cuda_go_compact(struct cuda_sim *g, const char *why) {
  if (g->compact) return 0;
  fprintf(stderr, "mdpore: CUDA backend: compact memory mode (no neighbour lists): %s\n", why);
  /* a static tail already placed (a list that did not fit during a run): the tail's particles
   * sit after the others with bin starts of their own, which the compact mode does not keep */
  const int tail_placed = g->prm.tail && g->n > 0;
  g->compact = 1;
  if (g->tail_on) { /* the static tail's second set of bin starts (cuda_sim_create): not needed */
    const size_t one = (size_t)(g->prm.ncell + 1) * sizeof(int);
    cuda_free_ptr(g, (void **)&g->cell_start);
    g->bytes -= 2 * one;
    g->fixed_bytes -= 2 * one;
    if (cuda_alloc(g, (void **)&g->cell_start, one)) return -1;
    g->fixed_bytes += one;
  }
  g->tail_on = g->prm.tail = 0; /* (one field set: no tail) */
  g->prm.skin = 0.0;            /* no lists to keep */
  g->prm.list_cut2 = g->prm.cut2_max;
  g->lists_valid = g->lists_maybe_valid = 0;
  if (g->cap > 0 && realloc_keep(g, g->cap)) return -1;
  if (!tail_placed) return 0;
  g->keys_ready = 0; /* every particle into bin order again, one set of bin starts */
  return cuda_sort_cells(g, 0, 0);
}

static int realloc_keep(struct cuda_sim *g, int need) {
  if (cuda_check(cudaDeviceSynchronize(), "grow")) return -1;
  const size_t n = (size_t)g->n, nb = (size_t)g->n_boundary;
  struct dev_fields old = g->a;
  uint32_t *okey = g->key, *oks = g->key_sorted;
  int *operm = g->perm;
  memset(&g->a, 0, sizeof g->a); /* detached: reserve_cap frees the rest */
  g->key = g->key_sorted = NULL;
  g->perm = NULL;
  const int cap_was = g->cap;
  int rc = reserve_cap(g, need, need > cap_was ? room_for(g, need) : cap_was);
  if (!rc) {
    rc = cuda_copy_fields(&g->a, &old, 0, n, "grow") || copy_back(g->key, okey, n * 4) ||
         copy_back(g->key_sorted, oks, n * 4) || copy_back(g->perm, operm, nb * 4);
  }
  free_fields(g, &old);
  cuda_free_ptr(g, (void **)&okey);
  cuda_free_ptr(g, (void **)&oks);
  cuda_free_ptr(g, (void **)&operm);
  if (rc) fprintf(stderr, "mdpore: CUDA backend: cannot grow from %d to %d slots\n", cap_was, need);
  return rc ? -1 : 0;
}

int cuda_dev_room(struct cuda_sim *g, char **buf, size_t *cap, size_t bytes) {
  if (bytes <= *cap) return 0;
  cuda_free_ptr(g, (void **)buf);
  *cap = 0;
  const size_t want = bytes + bytes / 4 + 4096;
  if (cuda_alloc(g, (void **)buf, want)) return -1;
  *cap = want;
  return 0;
}

int cuda_select_room(struct cuda_sim *g, size_t need) {
  if (need <= g->select_tmp_bytes) return 0;
  cuda_free_ptr(g, &g->select_tmp);
  g->select_tmp_bytes = 0;
  if (cuda_alloc(g, &g->select_tmp, need)) return -1;
  g->select_tmp_bytes = need;
  return 0;
}

int cuda_select_slots(struct cuda_sim *g, const int *flag, int *out, int *count_dev, int n,
                      const char *what) {
  const thrust::counting_iterator<int> slots(0);
  return cuda_cub_call(
      g,
      [&](void *tmp, size_t &bytes) {
        return cub::DeviceSelect::Flagged(tmp, bytes, slots, flag, out, count_dev, n);
      },
      what);
}

/* Neighbour-list room for stride entries per particle. When the device has no room for it, the
 * memory mode is auto and there is one rank, the compact mode takes over (the caller sees
 * g->compact set; the packed arrays were re-made and must be packed again). */
int cuda_nbr_reserve(struct cuda_sim *g, int stride) {
  stride = (stride + NBR_CHUNK - 1) / NBR_CHUNK * NBR_CHUNK; /* whole chunks */
  if (g->compact || stride <= g->nbr_stride) return 0;
  cuda_free_ptr(g, (void **)&g->nbr);
  g->nbr_stride = 0;
  const size_t bytes = (size_t)g->cap * (size_t)stride * sizeof(uint32_t);
  /* test hook: the lists' allocation fails as on a full device (ctest cuda_memory_auto) */
  const char *fail = getenv("MDPORE_CUDA_TEST_LIST_FAIL");
  const cudaError_t e =
      fail && !strcmp(fail, "1") ? cudaErrorMemoryAllocation : cudaMalloc((void **)&g->nbr, bytes);
  if (e == cudaErrorMemoryAllocation && g->memory_request == SCENE_GPU_MEMORY_AUTO &&
      !g->prm.multi) { /* (several ranks decide before the upload only: cuda_reserve) */
    g->nbr = NULL;
    (void)cudaGetLastError(); /* not sticky: clear it */
    char why[256];
    snprintf(why, sizeof why, "no room for neighbour lists of %d entries (%.1f GB) on the device",
             stride, (double)bytes / 1e9);
    return cuda_go_compact(g, why);
  }
  if (cuda_check_alloc(e, "the neighbour lists", bytes, "GPU")) {
    g->nbr = NULL;
    return -1;
  }
  g->bytes += bytes;
  g->nbr_stride = stride;
  return 0;
}

int cuda_set_virial(struct cuda_sim *g, int on) {
  if (!on || g->virial_cap >= g->cap) return 0;
  cuda_free_ptr(g, (void **)&g->virial);
  if (cuda_alloc(g, (void **)&g->virial, (size_t)g->cap * 6 * sizeof(double))) return -1;
  g->virial_cap = g->cap;
  return 0;
}

extern "C" int cuda_device_count(char *why, size_t len) {
  int n = 0;
  const cudaError_t e = cudaGetDeviceCount(&n);
  if (e != cudaSuccess) {
    snprintf(why, len, "cudaGetDeviceCount = 0 (%s)", cudaGetErrorString(e));
    return 0;
  }
  if (n == 0) snprintf(why, len, "cudaGetDeviceCount = 0");
  return n;
}

extern "C" void cuda_sim_destroy(cuda_sim_t *g) {
  if (!g) return;
  free_fields(g, &g->a);
  free_fields(g, &g->b);
  void **ptrs[] = {(void **)&g->rho,
                   (void **)&g->virial,
                   (void **)&g->key,
                   (void **)&g->key_sorted,
                   (void **)&g->iota,
                   (void **)&g->perm,
                   (void **)&g->cell_start,
                   &g->sort_tmp,
                   (void **)&g->block_virial,
                   (void **)&g->thermo_part,
                   (void **)&g->problem,
                   (void **)&g->pos,
                   (void **)&g->vel,
                   (void **)&g->nbr,
                   (void **)&g->nbr_count,
                   (void **)&g->nbr_most,
                   (void **)&g->gcell_start,
                   (void **)&g->counter,
                   (void **)&g->rho_stage,
                   (void **)&g->pos0,
                   (void **)&g->rebuild,
                   (void **)&g->wall_field,
                   (void **)&g->rho_static,
                   (void **)&g->cell_dynamic,
                   (void **)&g->sort_scratch,
                   (void **)&g->halo_count_dev,
                   (void **)&g->ghost_send_dev,
                   (void **)&g->ghost_recv_dev,
                   (void **)&g->mig_dev,
                   (void **)&g->bslots,
                   &g->select_tmp,
                   (void **)&g->mobile_slot,
                   (void **)&g->tail_rho,
                   (void **)&g->mobile_count};
  for (size_t k = 0; k < sizeof ptrs / sizeof ptrs[0]; k++) cuda_free_ptr(g, ptrs[k]);
  for (int k = 0; k < g->n_effect_arrays; k++) cuda_free_ptr(g, &g->effect_arrays[k]);
  if (g->pinned) cudaFreeHost(g->pinned);
  if (g->mig_pinned) cudaFreeHost(g->mig_pinned);
  if (g->counts_pinned) cudaFreeHost(g->counts_pinned);
  if (g->idle_on)
    for (int k = 0; k < 2 * CUDA_IDLE_SECTIONS; k++) cudaEventDestroy(g->idle_ev[k]);
  if (g->packed_made) {
    cudaEventDestroy(g->packed);
    cudaEventDestroy(g->ready);
    cudaEventDestroy(g->copied);
    cudaStreamDestroy(g->copies);
  }
  free(g);
}

extern "C" int cuda_sim_count(const cuda_sim_t *g) {
  return g->n;
}

extern "C" int cuda_sim_overlap(const cuda_sim_t *g) {
  return g->overlap && g->prm.multi;
}

extern "C" const char *cuda_sim_memory_mode(const cuda_sim_t *g) {
  return g->compact ? "compact" : "fast";
}

extern "C" size_t cuda_sim_bytes(const cuda_sim_t *g) {
  return g->bytes;
}

extern "C" long cuda_sim_static_tail(const cuda_sim_t *g) {
  return g->prm.tail ? (long)(g->n - g->n_dyn) : 0;
}

extern "C" int cuda_sim_coef_uniform(const cuda_sim_t *g) {
  return g->prm.coef_uniform;
}

extern "C" const char *cuda_sim_device_name(const cuda_sim_t *g) {
  return g->device_name;
}

extern "C" int cuda_sim_double_precision(void) {
  return sizeof(meso_real) == sizeof(double);
}

/* GPU idle probes: the device time between a section's two marks is the GPU work queued between
 * them plus the time the device waited for the host (a section opened while the device is busy
 * and closed before the host queues the next large pass: what the host's exchanges cost the
 * device). A closed pair is read when the section opens again, by then long completed. */
extern "C" void cuda_idle_mark(cuda_sim_t *g, int s, int end) {
  if (!g->idle_on || s < 0 || s >= CUDA_IDLE_SECTIONS) return;
  cudaEvent_t a = g->idle_ev[2 * s], b = g->idle_ev[2 * s + 1];
  if (end) {
    if (g->idle_state[s] == 1 && cudaEventRecord(b, 0) == cudaSuccess) g->idle_state[s] = 2;
    return;
  }
  float ms = 0.0f;
  if (g->idle_state[s] == 2 && cudaEventSynchronize(b) == cudaSuccess &&
      cudaEventElapsedTime(&ms, a, b) == cudaSuccess) {
    g->idle_ms[s] += ms;
    g->idle_n[s]++;
  }
  g->idle_state[s] = cudaEventRecord(a, 0) == cudaSuccess ? 1 : 0;
}

extern "C" void cuda_idle_read(cuda_sim_t *g, double ms[CUDA_IDLE_SECTIONS],
                               long n[CUDA_IDLE_SECTIONS], int reset) {
  for (int s = 0; s < CUDA_IDLE_SECTIONS; s++) {
    ms[s] = g->idle_ms[s];
    n[s] = g->idle_n[s];
    if (reset) {
      g->idle_ms[s] = 0.0;
      g->idle_n[s] = 0;
    }
  }
}
