/* Device memory of the CUDA backend: allocation with byte accounting, growth, error reporting. */
#include "cuda_state.cuh"

#include <cub/device/device_radix_sort.cuh>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cuda_check(cudaError_t e, const char *what) {
  if (e == cudaSuccess) return 0;
  fprintf(stderr, "mdpore: CUDA error in %s: %s\n", what, cudaGetErrorString(e));
  return -1;
}

int cuda_alloc(struct cuda_sim *g, void **ptr, size_t bytes) {
  *ptr = NULL;
  if (bytes == 0) return 0;
  if (cuda_check(cudaMalloc(ptr, bytes), "cudaMalloc")) return -1;
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

static int alloc_fields(struct cuda_sim *g, struct dev_fields *f, int cap) {
  const size_t n = (size_t)cap;
  int rc = cuda_alloc(g, (void **)&f->id, n * sizeof(int64_t)) ||
           cuda_alloc(g, (void **)&f->species, n * sizeof(int32_t));
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
  g->prm.pe.wall_boundary.field = NULL;
  g->lists_valid = 0;
  g->nbr_stride = 0;
  g->virial_cap = 0;
  g->bytes = 0;
  if (n >= (1 << NBR_SLOT_BITS) - 4096) {
    fprintf(stderr, "mdpore: CUDA backend: %d particles on one GPU: at most %d\n", n,
            (1 << NBR_SLOT_BITS) - 4096);
    return -1;
  }
  const size_t c = (size_t)cap;
  const int blocks = (cap + CUDA_BLOCK - 1) / CUDA_BLOCK;
  size_t tmp = 0;
  cub::DeviceRadixSort::SortPairs(NULL, tmp, (const uint32_t *)NULL, (uint32_t *)NULL,
                                  (const int *)NULL, (int *)NULL, cap);
  if (alloc_fields(g, &g->a, cap) || alloc_fields(g, &g->b, cap) ||
      (g->prm.density && cuda_alloc(g, (void **)&g->rho, c * sizeof(meso_real))) ||
      cuda_alloc(g, (void **)&g->key, c * sizeof(uint32_t)) ||
      cuda_alloc(g, (void **)&g->key_sorted, c * sizeof(uint32_t)) ||
      cuda_alloc(g, (void **)&g->iota, c * sizeof(int)) ||
      cuda_alloc(g, (void **)&g->perm, c * sizeof(int)) ||
      cuda_alloc(g, (void **)&g->pos, c * sizeof(struct dev_pos)) ||
      cuda_alloc(g, (void **)&g->nbr_count, c * sizeof(int)) ||
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

/* Slots for need particles with a margin; several ranks leave room for the ghost layer, which
 * cuda_grow widens when a step needs more (MDPORE_CUDA_TIGHT_ROOM=1: almost no margin, so that the
 * tests exercise the growth). */
static int room_for(const struct cuda_sim *g, int need) {
  if (!g->prm.multi) return need + need / 16 + 256;
  const char *tight = getenv("MDPORE_CUDA_TIGHT_ROOM");
  if (tight && !strcmp(tight, "1")) return need + 64;
  return need + need / 4 + 4096;
}

/* Room for n particles; contents are not kept (called before an upload only). */
int cuda_reserve(struct cuda_sim *g, int n) {
  if (n <= g->cap) return 0;
  return reserve_cap(g, n, room_for(g, n));
}

static int copy_back(void *dst, const void *src, size_t bytes) {
  return bytes ? cuda_check(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToDevice), "grow") : 0;
}

/* Room for need slots, keeping the owned particles [0, n), their bins (key_sorted), boundary flags
 * (key) and the boundary permutation (perm[0, n_boundary)); everything else is rebuilt by the
 * passes that follow. Waits for the work in flight. 0 or -1. */
int cuda_grow(struct cuda_sim *g, int need) {
  if (need <= g->cap) return 0;
  if (cuda_check(cudaDeviceSynchronize(), "grow")) return -1;
  const size_t n = (size_t)g->n, nb = (size_t)g->n_boundary;
  struct dev_fields old = g->a;
  uint32_t *okey = g->key, *oks = g->key_sorted;
  int *operm = g->perm;
  memset(&g->a, 0, sizeof g->a); /* detached: reserve_cap frees the rest */
  g->key = g->key_sorted = NULL;
  g->perm = NULL;
  const int cap_was = g->cap;
  int rc = reserve_cap(g, need, room_for(g, need));
  if (!rc) {
    rc = copy_back(g->a.id, old.id, n * 8) || copy_back(g->a.species, old.species, n * 4) ||
         copy_back(g->key, okey, n * 4) || copy_back(g->key_sorted, oks, n * 4) ||
         copy_back(g->perm, operm, nb * 4);
    for (int d = 0; d < 3 && !rc; d++)
      rc = copy_back(g->a.x[d], old.x[d], n * 8) || copy_back(g->a.v[d], old.v[d], n * 8) ||
           copy_back(g->a.f[d], old.f[d], n * 8) ||
           (old.vpred[d] && copy_back(g->a.vpred[d], old.vpred[d], n * 8));
  }
  free_fields(g, &old);
  cuda_free_ptr(g, (void **)&okey);
  cuda_free_ptr(g, (void **)&oks);
  cuda_free_ptr(g, (void **)&operm);
  if (rc) fprintf(stderr, "mdpore: CUDA backend: cannot grow from %d to %d slots\n", cap_was, need);
  return rc ? -1 : 0;
}

/* Neighbour-list room for stride entries per particle. */
int cuda_nbr_reserve(struct cuda_sim *g, int stride) {
  stride = (stride + NBR_CHUNK - 1) / NBR_CHUNK * NBR_CHUNK; /* whole chunks */
  if (stride <= g->nbr_stride) return 0;
  cuda_free_ptr(g, (void **)&g->nbr);
  if (cuda_alloc(g, (void **)&g->nbr, (size_t)g->cap * (size_t)stride * sizeof(uint32_t)))
    return -1;
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
  void **ptrs[] = {(void **)&g->rho,          (void **)&g->virial,
                   (void **)&g->key,          (void **)&g->key_sorted,
                   (void **)&g->iota,         (void **)&g->perm,
                   (void **)&g->cell_start,   &g->sort_tmp,
                   (void **)&g->block_virial, (void **)&g->thermo_part,
                   (void **)&g->problem,      (void **)&g->pos,
                   (void **)&g->vel,          (void **)&g->nbr,
                   (void **)&g->nbr_count,    (void **)&g->nbr_most,
                   (void **)&g->gcell_start,  (void **)&g->counter,
                   (void **)&g->rho_stage,    (void **)&g->pos0,
                   (void **)&g->rebuild,      (void **)&g->wall_field,
                   (void **)&g->rho_static,   (void **)&g->cell_dynamic};
  for (size_t k = 0; k < sizeof ptrs / sizeof ptrs[0]; k++) cuda_free_ptr(g, ptrs[k]);
  for (int k = 0; k < g->n_effect_arrays; k++) cuda_free_ptr(g, &g->effect_arrays[k]);
  if (g->pinned) cudaFreeHost(g->pinned);
  free(g);
}

extern "C" int cuda_sim_count(const cuda_sim_t *g) {
  return g->n;
}

extern "C" int cuda_sim_overlap(const cuda_sim_t *g) {
  return g->overlap && g->prm.multi;
}

extern "C" size_t cuda_sim_bytes(const cuda_sim_t *g) {
  return g->bytes;
}

extern "C" const char *cuda_sim_device_name(const cuda_sim_t *g) {
  return g->device_name;
}

extern "C" int cuda_sim_double_precision(void) {
  return sizeof(meso_real) == sizeof(double);
}
