/* Problem setup helpers (see darcy_problem.h). */
#include "darcy_problem.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Power law: secant permeability mu q(G)/G at the characteristic gradient; the others: their k. */
static double linearised_k(const darcy_problem *p, const flow_law *l, double g_char) {
  if (l->kind == LAW_POWER)
    return p->fluid.mu * flow_law_q(l, &p->fluid, p->g_lin, g_char, NULL) / g_char;
  return l->k;
}

int darcy_problem_make_diagonal(darcy_problem *p) {
  const long nb = darcy_nblocks(p);
  for (int a = 1; a < p->dim; a++) {
    if (p->laws_axis[a]) continue;
    p->laws_axis[a] = malloc((size_t)nb * sizeof(flow_law));
    p->k_lin_axis[a] = malloc((size_t)nb * sizeof(double));
    if (!p->laws_axis[a] || !p->k_lin_axis[a]) return -1;
    memcpy(p->laws_axis[a], p->laws, (size_t)nb * sizeof(flow_law));
    memcpy(p->k_lin_axis[a], p->k_lin, (size_t)nb * sizeof(double));
  }
  return 0;
}

void darcy_problem_linearise(darcy_problem *p, double g_lin_fraction) {
  /* characteristic gradient: largest pressure difference between fixed faces over the domain size
   */
  double pmin = INFINITY, pmax = -INFINITY, Lmax = 0;
  for (int a = 0; a < 3; a++) Lmax = fmax(Lmax, p->n[a] * p->h[a] * (a < p->dim));
  for (int f = 0; f < 6; f++)
    if (p->fixed[f])
      for (long c = 0; c < darcy_face_count(p, f); c++) {
        pmin = fmin(pmin, p->bc_p[f][c]);
        pmax = fmax(pmax, p->bc_p[f][c]);
      }
  double g_char = (pmax > pmin && Lmax > 0) ? (pmax - pmin) / Lmax : 1.0;
  p->g_lin = g_lin_fraction * g_char;
  p->p_scale = g_char * Lmax;
  double logk = 0.0;
  for (long b = 0; b < darcy_nblocks(p); b++) {
    p->k_lin[b] = linearised_k(p, &p->laws[b], g_char);
    logk += log(p->k_lin[b]);
  }
  for (int a = 1; a < 3; a++)
    if (p->laws_axis[a])
      for (long b = 0; b < darcy_nblocks(p); b++)
        p->k_lin_axis[a][b] = linearised_k(p, &p->laws_axis[a][b], g_char);
  double k_ref = exp(logk / darcy_nblocks(p)), c_ref = 0.0;
  for (int a = 0; a < p->dim; a++)
    c_ref = fmax(c_ref, p->h[(a + 1) % 3] * p->h[(a + 2) % 3] / p->h[a]);
  p->eq_scale = p->fluid.mu / (k_ref * c_ref);
}

void darcy_problem_free(darcy_problem *p) {
  free(p->laws);
  free(p->k_lin);
  free(p->source);
  for (int f = 0; f < 6; f++) free(p->bc_p[f]);
  for (int a = 0; a < 3; a++) {
    free(p->laws_axis[a]);
    free(p->k_lin_axis[a]);
    p->laws_axis[a] = NULL;
    p->k_lin_axis[a] = NULL;
  }
  p->laws = NULL;
  p->k_lin = p->source = NULL;
  for (int f = 0; f < 6; f++) p->bc_p[f] = NULL;
}
