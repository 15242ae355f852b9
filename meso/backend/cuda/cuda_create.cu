/* The device constants of a scene (dev_params) and the creation of the device state. Cells: nb[d]
 * bins of width >= the ghost cutoff over the box; a periodic axis too short for 3 bins has one, and
 * the box must be >= 2 cutoffs along it (a pair meets at most one image of its partner). */
#include "cuda_state.cuh"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void fill_coef(struct dev_coef *d, const pair_coef_t *c) {
  d->A = (meso_real)c->A;
  d->B = (meso_real)c->B;
  d->gamma = (meso_real)c->gamma;
  d->sigma = (meso_real)c->sigma;
  d->inv_rc = (meso_real)c->inv_rc;
  d->rc2 = (meso_real)c->rc2;
  d->inv_rd = (meso_real)c->inv_rd;
  d->rd2 = (meso_real)c->rd2;
  d->wnorm = (meso_real)c->wnorm;
  d->cut2 = (meso_real)c->cut2;
  d->wall_phi2 = (meso_real)c->wall_phi2;
  d->s_exp = (meso_real)c->s_exp;
  d->s_one = c->s_one;
}

static int fill_cells(struct dev_params *q, const plan_t *plan, const scene_t *s,
                      const double sub_lo[3], const double sub_hi[3], const int dims[3],
                      int compact, char *err, size_t len) {
  const int multi = dims[0] * dims[1] * dims[2] > 1;
  const double rcut = plan->rcut > 0 ? plan->rcut : 1.0;
  /* Several ranks rebuild the ghosts, and with them the lists, every step: no skin there. */
  const double skin = multi || !plan->pair_terms || compact ? 0.0
                      : s->neighbour_skin >= 0              ? s->neighbour_skin
                                                            : CUDA_DEFAULT_SKIN;
  const double list_cut = sqrt((double)q->cut2_max) + skin;
  q->skin = skin;
  q->list_cut2 = skin > 0.0 ? (meso_real)(list_cut * list_cut) : q->cut2_max;
  q->half_skin2 = (meso_real)(0.25 * skin * skin);
  q->multi = multi;
  q->rcut = rcut;
  for (int d = 0; d < 3; d++) {
    q->box_lo[d] = s->box_lo[d];
    q->box_hi[d] = s->box_hi[d];
    q->box_len[d] = s->box_hi[d] - s->box_lo[d];
    q->box_periodic[d] = s->periodic[d];
    q->sub_lo[d] = sub_lo[d];
    q->sub_hi[d] = sub_hi[d];
    /* An axis cut between ranks: the subdomain plus the ghost layer, no wrap (ghosts carry the
     * images). Any other axis: the whole box, wrapping when periodic (as on one rank). */
    q->split[d] = dims[d] > 1;
    q->lo[d] = q->split[d] ? sub_lo[d] - rcut : s->box_lo[d];
    q->hi[d] = q->split[d] ? sub_hi[d] + rcut : s->box_hi[d];
    q->L[d] = q->hi[d] - q->lo[d];
    q->periodic[d] = q->split[d] ? 0 : s->periodic[d];
    /* Bins at least as wide as the list cutoff (the cutoff plus the skin). */
    int nb = (int)(q->L[d] / (q->split[d] ? rcut : rcut + skin));
    /* A periodic axis of fewer than 3 bins takes the minimum image: one bin the box long, so a
     * row of bins along x holds the particles of every height along it and the scan visits half
     * the rows of two bins (the same candidates; positions packed from the box's lower face). */
    if (nb < 1 || (nb < 3 && q->periodic[d])) nb = 1;
    if (q->periodic[d] && q->L[d] < 2.0 * rcut && plan->pair_terms) {
      snprintf(err, len,
               "%s: CUDA backend: periodic box length %g along %c is shorter than twice the "
               "cutoff %g (use --backend cpu)",
               s->file, q->L[d], "xyz"[d], rcut);
      return -1;
    }
    q->nb[d] = nb;
    q->inv_bin[d] = nb / q->L[d];
    q->bin_w[d] = (meso_real)(q->L[d] / nb);
    q->box_L[d] = (meso_real)q->L[d];
    q->inv_box_L[d] = (meso_real)(1.0 / q->L[d]);
    q->min_image[d] = q->periodic[d] && nb < 3;
    q->near_L[d] = q->min_image[d] ? q->box_L[d] : (meso_real)0;
    q->near_inv_L[d] = q->min_image[d] ? q->inv_box_L[d] : (meso_real)0;
    q->off_lo[d] = nb >= 3 || !q->periodic[d] ? -1 : 0; /* periodic, one bin: that bin only */
    q->off_hi[d] = nb >= 2 ? 1 : 0;
  }
  /* The scan (docs/engine-cuda.md "Neighbour scan"), MDPORE_CUDA_SCAN: auto (default: on one
   * rank, quarter bins along x, whose rows stay those of y and z; half bins along y and z in a
   * quasi-2D box, one axis of fewer than 3 bins, else bins of the cutoff's size, as measured faster
   * in 3D: bench/RESULTS.md, 2026-11-26 5c41b6f and 5851dff), fine (half bins along y and z in 3D
   * too), coarse (bins of the cutoff's size along every axis), nested (the bin-by-bin loops of
   * coarse bins, as before the row traversal). MDPORE_CUDA_XSUB = 1, 2, 4 or 8 sets the fine bins
   * per bin along x alone. Several ranks keep coarse keys (the ghosts' bins). Every row scan is
   * trimmed to its caller's reach unless MDPORE_CUDA_TRIM=0. (The switches are for measuring.) */
  const char *scan = getenv("MDPORE_CUDA_SCAN");
  const int nested = scan && !strcmp(scan, "nested");
  const int all_coarse = nested || (scan && !strcmp(scan, "coarse"));
  /* an axis of fewer than 3 periodic bins: the pair loops take the minimum image (quasi-2D) */
  q->near_axes = q->min_image[0] | q->min_image[1] << 1 | q->min_image[2] << 2;
  const int quasi_2d = q->near_axes != 0;
  const int yz_halves = !all_coarse && (quasi_2d || (scan && !strcmp(scan, "fine")));
  q->row_scan = !nested;
  const char *trim_env = getenv("MDPORE_CUDA_TRIM");
  q->trim_any = !(trim_env && !strcmp(trim_env, "0"));
  int x_shift = all_coarse ? 0 : 2;
  const char *xsub_env = getenv("MDPORE_CUDA_XSUB");
  if (xsub_env && !nested)
    for (int k = 0; k <= 3; k++)
      if (atoi(xsub_env) == 1 << k) x_shift = k;
  /* keys are 32-bit, bin starts int (the sentinel key is ncell): fine bins only where they fit
   * (level 2: as chosen; 1: x as y and z; 0: coarse) */
  long long ncell = 1;
  for (int level = multi ? 0 : 2; level >= 0; level--) {
    ncell = 1;
    for (int d = 0; d < 3; d++) {
      const int yz_shift = level >= 1 && yz_halves ? 1 : 0;
      q->sub_shift[d] = q->min_image[d] ? 0 : d == 0 && level == 2 ? x_shift : yz_shift;
      q->sub[d] = 1 << q->sub_shift[d];
      q->nf[d] = q->sub[d] * q->nb[d];
      q->fine_w[d] = (meso_real)(q->L[d] / q->nf[d]);
      q->inv_fine_w[d] = (meso_real)(q->nf[d] / q->L[d]);
      ncell *= q->nf[d];
    }
    if (ncell <= INT_MAX / 2) break;
  }
  if (ncell > INT_MAX / 2) {
    snprintf(err, len,
             "%s: CUDA backend: %lld cells of the cutoff's size (%d x %d x %d) do not fit "
             "a 32-bit cell index; split the box over MPI ranks",
             s->file, ncell, q->nb[0], q->nb[1], q->nb[2]);
    return -1;
  }
  q->ncell = (int)ncell;
  /* 1e-4 of the cutoff covers the float rounding of the packed positions and of the bin edges */
  const double scan_cut = sqrt((double)q->list_cut2) * (1.0 + 1e-4);
  q->scan_cut2 = (meso_real)(scan_cut * scan_cut);
  const double scan_rd = sqrt((double)q->rd2_max) * (1.0 + 1e-4);
  q->scan_rd2 = (meso_real)(scan_rd * scan_rd);
  return 0;
}

extern "C" int cuda_plan_static_tail(const plan_t *plan) {
  int any_static = 0, any_moving = 0;
  for (int a = 0; a < plan->n_species; a++) {
    any_static |= plan->static_frozen[a];
    any_moving |= plan->moving[a];
  }
  return any_static && !any_moving;
}

extern "C" cuda_sim_t *cuda_sim_create(const plan_t *plan, const scene_t *s, const double sub_lo[3],
                                       const double sub_hi[3], const int dims[3], char *err,
                                       size_t len) {
  char why[256];
  if (cuda_device_count(why, sizeof why) < 1) {
    snprintf(err, len, "CUDA backend asked for but no GPU is visible: %s", why);
    return NULL;
  }
  cuda_sim_t *g = (cuda_sim_t *)calloc(1, sizeof *g);
  if (!g) {
    snprintf(err, len, "out of memory");
    return NULL;
  }
  struct dev_params *q = &g->prm;
  q->n_species = plan->n_species;
  q->terms = plan->pair_terms;
  q->density = plan->density;
  q->kernel = plan->density_kernel;
  q->walls = plan->walls;
  q->particle_forces = plan->particle_forces;
  q->pe = plan->particle;
  q->use_vpred = plan->use_vpred;
  q->inv_sqrt_dt = (meso_real)plan->inv_sqrt_dt;
  q->seed = plan->seed;
  q->rng = plan->pair_rng;
  q->dt = plan->dt;
  q->half_dt = plan->half_dt;
  q->max_disp = plan->max_disp;
  q->predict_c = plan->predict_c;
  /* On the GPU the cache is opt-in (MDPORE_DENSITY_CACHE=1): on the H100 it cost 2-3% at 14-28%
   * wall particles (bench/RESULTS.md), the per-build bin flags and table loads outweighing the
   * skipped scans. */
  const char *cache_env = getenv("MDPORE_DENSITY_CACHE");
  q->density_cache = plan->density_cache && cache_env && !strcmp(cache_env, "1");
  for (int a = 0; a < plan->n_species; a++) {
    q->mobile[a] = plan->mobile[a];
    q->moving[a] = plan->moving[a];
    q->static_frozen[a] = plan->static_frozen[a];
    for (int d = 0; d < 3; d++) q->wall_u[a][d] = plan->wall_u[a][d];
    q->inv_mass[a] = plan->inv_mass[a];
    q->mass[a] = plan->mass[a];
    for (int b = 0; b < plan->n_species; b++) {
      fill_coef(&q->coef[a][b], &plan->coef[a][b]);
      if (q->coef[a][b].cut2 > q->cut2_max) q->cut2_max = q->coef[a][b].cut2;
      if (q->coef[a][b].rd2 > q->rd2_max) q->rd2_max = q->coef[a][b].rd2;
    }
  }
  const char *uni_env = getenv("MDPORE_CUDA_UNIFORM");
  q->coef_uniform = !(uni_env && !strcmp(uni_env, "0"));
  for (int a = 0; a < plan->n_species; a++)
    for (int b = 0; b < plan->n_species; b++)
      if (memcmp(&q->coef[a][b], &q->coef[0][0], sizeof q->coef[0][0])) q->coef_uniform = 0;
  /* Several ranks overlap interior passes with the host exchanges unless MDPORE_CUDA_OVERLAP=0
   * (kept for measuring what the overlap gains: bench/RESULTS.md). */
  g->memory_request = s->gpu_memory;
  /* MDPORE_GPU_MEMORY=auto|fast|compact stands in for --gpu-memory where a scene is built in code
   * (tests, benchmarks); the command-line choice wins when it is not auto. */
  const char *mem_env = getenv("MDPORE_GPU_MEMORY");
  if (mem_env && *mem_env && g->memory_request == SCENE_GPU_MEMORY_AUTO) {
    if (!strcmp(mem_env, "fast"))
      g->memory_request = SCENE_GPU_MEMORY_FAST;
    else if (!strcmp(mem_env, "compact"))
      g->memory_request = SCENE_GPU_MEMORY_COMPACT;
    else if (strcmp(mem_env, "auto")) {
      snprintf(err, len, "MDPORE_GPU_MEMORY: expected auto, fast or compact (got '%s')", mem_env);
      free(g);
      return NULL;
    }
  }
  g->compact = g->memory_request == SCENE_GPU_MEMORY_COMPACT; /* (no skin: fill_cells) */
  const char *ov = getenv("MDPORE_CUDA_OVERLAP");
  g->overlap = !(ov && !strcmp(ov, "0"));
  const char *mob = getenv("MDPORE_CUDA_MOBILE_SLOTS");
  int any_frozen = 0;
  for (int a = 0; a < plan->n_species; a++) any_frozen |= !plan->mobile[a];
  g->mobile_slots_on = any_frozen && !(mob && !strcmp(mob, "0"));
  if (fill_cells(q, plan, s, sub_lo, sub_hi, dims, g->compact, err, len)) {
    free(g);
    return NULL;
  }
  /* The static tail (cuda_state.cuh; docs/engine-cuda.md step 2). MDPORE_CUDA_TAIL=0 turns it off
   * (the mobile-first partition of every build instead: bench/RESULTS.md, 2026-11-26 76c87e8). */
  const char *tail_env = getenv("MDPORE_CUDA_TAIL");
  g->tail_on = !(tail_env && !strcmp(tail_env, "0")) && !q->multi && !g->compact &&
               q->skin == 0.0 && q->row_scan && cuda_plan_static_tail(plan) && !q->density_cache;
  q->tail = 0; /* (set by the first sort) */
  q->tail_off = q->ncell + 1;
  if (g->tail_on) g->mobile_slots_on = 0;
  const char *tail_rho_env = getenv("MDPORE_CUDA_TAIL_RHO");
  g->tail_rho_on = !(tail_rho_env && !strcmp(tail_rho_env, "0"));
  /* One GPU per rank: the ranks of a node take the visible GPUs in turn (local rank from the MPI
   * launcher, else 0). */
  const int ngpu = cuda_device_count(why, sizeof why);
  const char *lr = getenv("OMPI_COMM_WORLD_LOCAL_RANK");
  if (!lr) lr = getenv("SLURM_LOCALID");
  const int dev = (lr ? atoi(lr) : 0) % ngpu;
  if (cuda_check(cudaSetDevice(dev), "cudaSetDevice")) {
    snprintf(err, len, "CUDA backend: cannot use GPU %d", dev);
    free(g);
    return NULL;
  }
  cudaDeviceProp prop;
  if (cudaGetDeviceProperties(&prop, dev) == cudaSuccess)
    snprintf(g->device_name, sizeof g->device_name, "%s", prop.name);
  /* The per-particle effects' arrays (e.g. bounce_back's solid map): a device copy each, and the
   * device's parameters point at it. */
  for (int k = 0; k < plan->n_arrays; k++) {
    const size_t bytes = plan->arrays[k].bytes;
    if (cuda_alloc(g, &g->effect_arrays[k], bytes ? bytes : 1) ||
        cuda_check(
            cudaMemcpy(g->effect_arrays[k], plan_array(plan, k), bytes, cudaMemcpyHostToDevice),
            "effect array")) {
      snprintf(err, len, "CUDA backend: out of device memory for an effect array of %zu bytes",
               bytes);
      g->n_effect_arrays = k + 1;
      cuda_sim_destroy(g);
      return NULL;
    }
    g->n_effect_arrays = k + 1;
    *(void **)((char *)&q->pe + plan->arrays[k].offset) = g->effect_arrays[k];
  }
  if (cuda_alloc(g, (void **)&g->cell_start,
                 (size_t)(q->ncell + 1) * (g->tail_on ? 2 : 1) * sizeof(int)) ||
      cuda_alloc(g, (void **)&g->gcell_start, /* the ghosts' bins: several ranks only */
                 (q->multi ? (size_t)q->ncell + 1 : 1) * sizeof(int)) ||
      cuda_alloc(g, (void **)&g->counter, sizeof(int)) ||
      cuda_alloc(g, (void **)&g->thermo_part, (size_t)THERMO_SUMS * (THERMO_BLOCKS + 1) * 8) ||
      cuda_alloc(g, (void **)&g->problem, sizeof(struct dev_problem)) ||
      cuda_alloc(g, (void **)&g->nbr_most, sizeof(int)) ||
      cuda_alloc(g, (void **)&g->rebuild, sizeof(int))) {
    snprintf(err, len, "CUDA backend: out of device memory");
    cuda_sim_destroy(g);
    return NULL;
  }
  g->fixed_bytes = g->bytes;
  /* MDPORE_CUDA_IDLE=1: the GPU idle probes (cuda_idle_mark; measuring only, off by default) */
  const char *idle = getenv("MDPORE_CUDA_IDLE");
  if (idle && !strcmp(idle, "1")) {
    int made = 0;
    while (made < 2 * CUDA_IDLE_SECTIONS && cudaEventCreate(&g->idle_ev[made]) == cudaSuccess)
      made++;
    if (made == 2 * CUDA_IDLE_SECTIONS)
      g->idle_on = 1;
    else
      while (made > 0) cudaEventDestroy(g->idle_ev[--made]);
  }
  return g;
}
