/* Host <-> device copies of the particle state: upload at setup, download for outputs only. */
#include "cuda_state.cuh"

#include <stdlib.h>
#include <string.h>

extern "C" int cuda_sim_upload(cuda_sim_t *g, const particles_t *p) {
  const int n = p->n_local;
  if (cuda_reserve(g, n > 0 ? n : 1)) return -1;
  g->n = n;
  g->lists_valid = 0; /* a new set of particles: the next step sorts and builds */
  g->keys_ready = 0;
  g->mobile_slots_ready = 0;
  g->prm.tail = 0; /* (the next sort places the static tail) */
  const size_t nd = (size_t)n * sizeof(double);
  int rc = cuda_check(cudaMemcpy(g->a.id, p->id, (size_t)n * 8, cudaMemcpyHostToDevice), "upload");
  rc |= cuda_check(cudaMemcpy(g->a.species, p->species, (size_t)n * 4, cudaMemcpyHostToDevice),
                   "upload");
  for (int d = 0; d < 3 && !rc; d++) {
    rc |= cuda_check(cudaMemcpy(g->a.x[d], p->x[d], nd, cudaMemcpyHostToDevice), "upload");
    rc |= cuda_check(cudaMemcpy(g->a.v[d], p->v[d], nd, cudaMemcpyHostToDevice), "upload");
    rc |= cuda_check(cudaMemcpy(g->a.f[d], p->f[d], nd, cudaMemcpyHostToDevice), "upload");
  }
  return rc ? -1 : 0;
}

extern "C" int cuda_sim_download(cuda_sim_t *g, particles_t *p) {
  const int n = g->n;
  const size_t nd = (size_t)n * sizeof(double);
  int rc =
      cuda_check(cudaMemcpy(p->id, g->a.id, (size_t)n * 8, cudaMemcpyDeviceToHost), "download");
  rc |= cuda_check(cudaMemcpy(p->species, g->a.species, (size_t)n * 4, cudaMemcpyDeviceToHost),
                   "download");
  for (int d = 0; d < 3 && !rc; d++) {
    rc |= cuda_check(cudaMemcpy(p->x[d], g->a.x[d], nd, cudaMemcpyDeviceToHost), "download");
    rc |= cuda_check(cudaMemcpy(p->v[d], g->a.v[d], nd, cudaMemcpyDeviceToHost), "download");
    rc |= cuda_check(cudaMemcpy(p->f[d], g->a.f[d], nd, cudaMemcpyDeviceToHost), "download");
    if (p->vpred[d] && g->a.vpred[d])
      rc |= cuda_check(cudaMemcpy(p->vpred[d], g->a.vpred[d], nd, cudaMemcpyDeviceToHost),
                       "download");
  }
  if (p->rho && g->rho && !rc) {
    /* rho is kept in the pair math's precision on the device. */
    meso_real *tmp = (meso_real *)malloc((size_t)(n > 0 ? n : 1) * sizeof(meso_real));
    if (!tmp) return -1;
    rc |= cuda_check(cudaMemcpy(tmp, g->rho, (size_t)n * sizeof(meso_real), cudaMemcpyDeviceToHost),
                     "download");
    for (int i = 0; i < n; i++) p->rho[i] = (double)tmp[i];
    free(tmp);
  }
  if (p->virial && g->virial && !rc)
    rc |= cuda_check(cudaMemcpy(p->virial, g->virial, 6 * nd, cudaMemcpyDeviceToHost), "download");
  p->n_local = n;
  p->n_ghost = 0;
  return rc ? -1 : 0;
}
