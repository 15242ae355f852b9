/* Post-processing of the pressure field (see darcy_post.h). */
#include "darcy_post.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "darcy_fv.h"

long darcy_post_face_count(const darcy_problem *p, int axis) {
  long c = 1;
  for (int a = 0; a < 3; a++) c *= p->n[a] + (a == axis);
  return c;
}

static long face_index(const darcy_problem *p, int axis, int i, int j, int k) {
  int m[3] = {p->n[0], p->n[1], p->n[2]};
  m[axis]++;
  return i + (long)m[0] * (j + (long)m[1] * k);
}

/* A boundary face's pressure: the fixed value, or (no flow) the block's own pressure. */
static double boundary_p(const darcy_problem *p, int face, int i, int j, int k, double p_c) {
  return p->fixed[face] ? p->bc_p[face][darcy_face_index(p, face, i, j, k)] : p_c;
}

static int uniform_fixed(const darcy_problem *p, int face, double *value) {
  if (!p->fixed[face]) return 0;
  *value = p->bc_p[face][0];
  for (long c = 1; c < darcy_face_count(p, face); c++)
    if (p->bc_p[face][c] != *value) return 0;
  return 1;
}

int darcy_post_compute(const darcy_problem *p, const double *pr, darcy_post *o) {
  memset(o, 0, sizeof *o);
  long nb = darcy_nblocks(p);
  for (int a = 0; a < 3; a++) {
    o->flux[a] = calloc(darcy_post_face_count(p, a), sizeof(double));
    o->face_p[a] = calloc(darcy_post_face_count(p, a), sizeof(double));
  }
  o->block_dp = calloc(3 * nb, sizeof(double));
  o->block_grad = calloc(3 * nb, sizeof(double));
  int oom = !o->block_dp || !o->block_grad;
  for (int a = 0; a < 3; a++) oom |= !o->flux[a] || !o->face_p[a];
  if (oom) {
    darcy_post_free(o);
    return -1;
  }
  o->pmin = INFINITY;
  o->pmax = -INFINITY;
  for (int k = 0; k < p->n[2]; k++)
    for (int j = 0; j < p->n[1]; j++)
      for (int i = 0; i < p->n[0]; i++) {
        long b = darcy_index(p, i, j, k);
        int c[3] = {i, j, k};
        o->pmin = fmin(o->pmin, pr[b]);
        o->pmax = fmax(o->pmax, pr[b]);
        for (int a = 0; a < p->dim; a++) {
          /* the plus face of every block, and the minus face of the first block along the axis */
          for (int side = (c[a] == 0 ? 0 : 1); side < 2; side++) {
            int face = 2 * a + side, nbc[3] = {i, j, k};
            nbc[a] += side ? 1 : -1;
            int inside = nbc[a] >= 0 && nbc[a] < p->n[a];
            double p_nb = inside ? pr[darcy_index(p, nbc[0], nbc[1], nbc[2])] : 0.0, area;
            face_flux_result r = darcy_face(p, i, j, k, face, pr[b], p_nb, &area);
            double half = 0.5 * p->h[a];
            double pf = (inside || p->fixed[face]) ? pr[b] - half * r.g_a
                                                   : boundary_p(p, face, i, j, k, pr[b]);
            long fi = face_index(p, a, c[0] + side * (a == 0), c[1] + side * (a == 1),
                                 c[2] + side * (a == 2));
            o->flux[a][fi] = (side ? 1.0 : -1.0) * area * r.q; /* positive along +axis */
            o->face_p[a][fi] = pf;
          }
        }
      }
  /* block drops and gradients from the face pressures */
  for (int k = 0; k < p->n[2]; k++)
    for (int j = 0; j < p->n[1]; j++)
      for (int i = 0; i < p->n[0]; i++) {
        long b = darcy_index(p, i, j, k);
        for (int a = 0; a < p->dim; a++) {
          double pm = o->face_p[a][face_index(p, a, i, j, k)];
          double pp = o->face_p[a][face_index(p, a, i + (a == 0), j + (a == 1), k + (a == 2))];
          o->block_dp[3 * b + a] = pm - pp;
          o->block_grad[3 * b + a] = (pm - pp) / p->h[a];
        }
      }
  /* boundary flows, effective permeability, mass balance */
  double out_total = 0.0, src = 0.0, scale = 0.0;
  for (int a = 0; a < p->dim; a++) {
    int m[3] = {p->n[0], p->n[1], p->n[2]};
    for (int k = 0; k < m[2]; k++)
      for (int j = 0; j < m[1]; j++)
        for (int i = 0; i < m[0]; i++) {
          int c[3] = {i, j, k};
          if (c[a] != 0) continue;
          int e[3] = {i, j, k};
          e[a] = p->n[a];
          double fin = o->flux[a][face_index(p, a, i, j, k)];
          double fout = o->flux[a][face_index(p, a, e[0], e[1], e[2])];
          o->q_in[a] += fin;
          o->q_out[a] += fout;
          scale += fabs(fin) + fabs(fout);
        }
    out_total += o->q_out[a] - o->q_in[a];
    double p_minus, p_plus;
    if (uniform_fixed(p, 2 * a, &p_minus) && uniform_fixed(p, 2 * a + 1, &p_plus) &&
        p_minus != p_plus) {
      /* k_eff = mu Q L / (A dp), Q the mean of inflow and outflow (equal without sources) */
      double L = p->n[a] * p->h[a], A = 1.0;
      for (int b2 = 0; b2 < 3; b2++)
        if (b2 != a) A *= p->n[b2] * p->h[b2];
      o->keff_defined[a] = 1;
      o->keff[a] = p->fluid.mu * 0.5 * (o->q_in[a] + o->q_out[a]) * L / (A * (p_minus - p_plus));
    }
  }
  if (p->source)
    for (long b = 0; b < nb; b++) {
      src += p->source[b];
      scale += fabs(p->source[b]);
    }
  o->net_boundary_outflow = out_total;
  o->total_source = src;
  o->mass_balance_rel = scale > 0 ? fabs(out_total - src) / scale : 0.0;
  return 0;
}

void darcy_post_free(darcy_post *o) {
  for (int a = 0; a < 3; a++) {
    free(o->flux[a]);
    free(o->face_p[a]);
  }
  free(o->block_dp);
  free(o->block_grad);
  memset(o, 0, sizeof *o);
}
