/* The continuum step of the loop: the block grid as a darcy_problem (upscale/darcy) in the reduced
 * units of the pore-scale runs, the sample's mean gradient G along the axis as a fixed pressure drop
 * G L between the two end faces (no flow through the sides), one solve with the blocks' laws, and
 * from it each block's mean gradient along the axis (what its next pore-scale runs are driven at)
 * and mean superficial velocity (the mean of the flux densities through its two faces along the
 * axis).
 *
 * Errors: the laws' parameters are uncertain (the fits' covariances). The loop solves again with
 * error_samples sets of parameters drawn from those covariances (normal, independent between blocks,
 * a fixed seed so that a rerun gives the same numbers) and takes the standard deviation of the
 * effective permeability and of each block flux over the draws. */
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "couple.h"
#include "darcy_post.h"
#include "darcy_problem.h"
#include "darcy_solve.h"

/* An impermeable block (its pore space does not span the axis) gets this fraction of the smallest
 * permeability of the others: the solver needs k > 0, and the flow through it is then negligible. */
#define COUPLE_TIGHT_FRACTION 1e-6

/* A cross-axis law entry that stands for an impermeable direction (the block's pore space does not
 * span that axis). */
#define TIGHT_KIND LAW_COUNT

/* laws: the law of every block along the loop's axis; cross[a] (NULL: none) the law of every block
 * along cross axis a, TIGHT_KIND for an impermeable direction. With no cross laws the problem has
 * one scalar law per block. */
static int build(const couple_config *c, const couple_block *blocks, const double size[3],
                 double gradient, const flow_law *laws, flow_law *const cross[3],
                 darcy_problem *p) {
  memset(p, 0, sizeof *p);
  p->dim = 3;
  for (int a = 0; a < 3; a++) {
    p->n[a] = c->blocks[a];
    p->h[a] = size[a];
  }
  long nb = darcy_nblocks(p);
  p->laws = malloc((size_t)nb * sizeof *p->laws);
  p->k_lin = malloc((size_t)nb * sizeof *p->k_lin);
  if (!p->laws || !p->k_lin) return -1;
  double kmin = INFINITY;
  for (long b = 0; b < nb; b++)
    if (blocks[b].percolates) {
      if (!(p->fluid.mu > 0)) {
        p->fluid.mu = blocks[b].law.mu;
        p->fluid.rho = blocks[b].law.density;
      }
      kmin = fmin(kmin, laws[b].kind == LAW_POWER ? INFINITY : laws[b].k);
    }
  if (!isfinite(kmin)) kmin = 1.0;
  for (long b = 0; b < nb; b++) {
    if (blocks[b].percolates) {
      p->laws[b] = laws[b];
    } else {
      memset(&p->laws[b], 0, sizeof p->laws[b]);
      p->laws[b].kind = LAW_DARCY;
      p->laws[b].k = COUPLE_TIGHT_FRACTION * kmin;
    }
  }
  if (cross[0] || cross[1] || cross[2]) {
    /* a diagonal law per block: every axis starts as a copy of the loop axis's laws (darcy_problem
     * holds the x laws in `laws`, y and z in laws_axis[1], [2]); the cross axes measured replace
     * them */
    if (darcy_problem_make_diagonal(p)) return -1;
    flow_law *along[3] = {p->laws, p->laws_axis[1], p->laws_axis[2]};
    const flow_law tight = {.kind = LAW_DARCY, .k = COUPLE_TIGHT_FRACTION * kmin};
    for (int d = 0; d < 3; d++)
      if (d != c->axis && cross[d])
        for (long b = 0; b < nb; b++)
          along[d][b] = cross[d][b].kind == TIGHT_KIND ? tight : cross[d][b];
  }
  int a = c->axis;
  double L = p->n[a] * p->h[a];
  for (int side = 0; side < 2; side++) {
    int f = 2 * a + side;
    long m = darcy_face_count(p, f);
    p->fixed[f] = 1;
    p->bc_p[f] = malloc((size_t)m * sizeof(double));
    if (!p->bc_p[f]) return -1;
    for (long i = 0; i < m; i++) p->bc_p[f][i] = side ? 0.0 : gradient * L;
  }
  p->rtol = 1e-10;
  p->max_it = 50;
  darcy_problem_linearise(p, 1e-6);
  return 0;
}

/* Index of the face (i,j,k) (lower face of block (i,j,k)) in darcy_post's flux[a] layout. */
static long face_of(const darcy_problem *p, int a, int i, int j, int k) {
  int m[3] = {p->n[0], p->n[1], p->n[2]};
  m[a] += 1;
  return i + (long)m[0] * (j + (long)m[1] * k);
}

typedef struct {
  double keff, *flux, *grad;
  int converged;
  double
      *cross; /* [3 b + d]: the block's mean |flux| along d over |flux| along the axis, or NULL */
} one_solve;

static int solve_once(const couple_config *c, const couple_block *blocks, const double size[3],
                      double gradient, const flow_law *laws, flow_law *const cross[3],
                      one_solve *out, double **pressure) {
  darcy_problem p;
  int rc = -1;
  if (build(c, blocks, size, gradient, laws, cross, &p)) goto out;
  double *pr = NULL;
  darcy_stats st;
  if (darcy_solve(MPI_COMM_WORLD, &p, &pr, &st) || !pr) goto out;
  darcy_post post;
  if (darcy_post_compute(&p, pr, &post)) {
    fprintf(stderr, "mdpore couple: out of memory for the continuum field of %ld blocks\n",
            darcy_nblocks(&p));
    goto out;
  }
  int a = c->axis;
  double area = 1.0;
  for (int d = 0; d < 3; d++)
    if (d != a) area *= p.h[d];
  for (int k = 0; k < p.n[2]; k++)
    for (int j = 0; j < p.n[1]; j++)
      for (int i = 0; i < p.n[0]; i++) {
        long b = darcy_index(&p, i, j, k);
        long lo = face_of(&p, a, i, j, k);
        long hi = face_of(&p, a, i + (a == 0), j + (a == 1), k + (a == 2));
        out->flux[b] = 0.5 * (post.flux[a][lo] + post.flux[a][hi]) / area;
        out->grad[b] = post.block_grad[3 * b + a];
        for (int d = 0; out->cross && d < 3; d++) {
          if (d == a) {
            out->cross[3 * b + d] = 0.0;
            continue;
          }
          const double area_d = p.h[(d + 1) % 3] * p.h[(d + 2) % 3];
          long dlo = face_of(&p, d, i, j, k);
          long dhi = face_of(&p, d, i + (d == 0), j + (d == 1), k + (d == 2));
          const double q_d = 0.5 * (fabs(post.flux[d][dlo]) + fabs(post.flux[d][dhi])) / area_d;
          out->cross[3 * b + d] = fabs(out->flux[b]) > 0 ? q_d / fabs(out->flux[b]) : 0.0;
        }
      }
  out->keff = post.keff_defined[a] ? post.keff[a] : NAN;
  out->converged = st.converged;
  darcy_post_free(&post);
  if (pressure)
    *pressure = pr;
  else
    free(pr);
  rc = 0;
out:
  darcy_problem_free(&p);
  return rc;
}

static double normal(unsigned short state[3]) {
  /* Box-Muller from two uniforms in (0, 1] */
  double u1 = 1.0 - erand48(state), u2 = erand48(state);
  return sqrt(-2.0 * log(u1)) * cos(2.0 * M_PI * u2);
}

int couple_solve(const couple_config *c, const couple_block *blocks, const double size[3],
                 double gradient, couple_solution *s) {
  memset(s, 0, sizeof *s);
  long nb = (long)c->blocks[0] * c->blocks[1] * c->blocks[2];
  double t0 = MPI_Wtime();
  flow_law *laws = malloc((size_t)nb * sizeof *laws), *cross[3] = {NULL, NULL, NULL};
  for (int d = 0; d < 3; d++) { /* the cross axes along which some block was measured */
    for (long b = 0; b < nb && !cross[d]; b++)
      if (d != c->axis && blocks[b].cross_state[d] >= CROSS_NO_SPAN)
        cross[d] = malloc((size_t)nb * sizeof(flow_law));
    if (cross[d])
      for (long b = 0; b < nb; b++) /* not measured: the loop axis's law (isotropic) */
        cross[d][b] = blocks[b].cross_state[d] == CROSS_MEASURED ? blocks[b].cross[d].law
                      : blocks[b].cross_state[d] == CROSS_NO_SPAN || !blocks[b].percolates
                          ? (flow_law){.kind = TIGHT_KIND}
                          : blocks[b].law.law;
  }
  s->grad = calloc((size_t)nb, sizeof(double));
  s->cross = calloc((size_t)nb * 3, sizeof(double));
  s->flux = calloc((size_t)nb, sizeof(double));
  s->flux_err = calloc((size_t)nb, sizeof(double));
  double *sum = calloc((size_t)nb, sizeof(double)), *sum2 = calloc((size_t)nb, sizeof(double));
  one_solve one = {0, calloc((size_t)nb, sizeof(double)), calloc((size_t)nb, sizeof(double)), 0,
                   NULL};
  int rc = -1;
  if (!laws || !s->grad || !s->flux || !s->flux_err || !sum || !sum2 || !one.flux || !one.grad ||
      !s->cross)
    goto out;
  for (int d = 0; d < 3; d++)
    for (long b = 0; b < nb && !cross[d]; b++)
      if (d != c->axis && blocks[b].cross_state[d] >= CROSS_NO_SPAN) goto out; /* no memory */
  for (long b = 0; b < nb; b++) laws[b] = blocks[b].law.law;
  one_solve main_solve = {0, s->flux, s->grad, 0, s->cross};
  if (solve_once(c, blocks, size, gradient, laws, cross, &main_solve, &s->pressure)) goto out;
  s->converged = main_solve.converged;
  s->keff = main_solve.keff;
  int a = c->axis;
  s->dp = gradient * c->blocks[a] * size[a];
  s->q_total = s->keff * gradient / blocks[0].law.mu;
  for (long b = 0; b < nb; b++)
    if (blocks[b].percolates) {
      s->q_total = s->keff * gradient / blocks[b].law.mu;
      break;
    }
  /* Monte-Carlo errors over the fits' parameter covariances */
  unsigned short state[3] = {0x330e, (unsigned short)(c->seed & 0xffff),
                             (unsigned short)((c->seed >> 16) & 0xffff)};
  double ks = 0, ks2 = 0;
  for (int m = 0; m < c->error_samples; m++) {
    for (long b = 0; b < nb; b++) {
      double z[3] = {normal(state), normal(state), normal(state)};
      couple_law_sample(&blocks[b].law, z, &laws[b]);
    }
    /* the cross-axis laws drawn from their own fits, after the loop axis's (whose draws are then
     * those of a loop without cross axes) */
    for (int d = 0; d < 3; d++)
      for (long b = 0; cross[d] && b < nb; b++) {
        if (blocks[b].cross_state[d] == CROSS_MEASURED) {
          double z[3] = {normal(state), normal(state), normal(state)};
          couple_law_sample(&blocks[b].cross[d], z, &cross[d][b]);
        } else if (cross[d][b].kind != TIGHT_KIND) {
          cross[d][b] = laws[b]; /* isotropic: the loop axis's draw */
        }
      }
    if (solve_once(c, blocks, size, gradient, laws, cross, &one, NULL) || !one.converged ||
        !isfinite(one.keff))
      continue;
    s->samples_ok++;
    ks += one.keff;
    ks2 += one.keff * one.keff;
    for (long b = 0; b < nb; b++) {
      sum[b] += one.flux[b];
      sum2[b] += one.flux[b] * one.flux[b];
    }
  }
  if (s->samples_ok >= 2) {
    double n = s->samples_ok;
    s->keff_err = sqrt(fmax(0.0, (ks2 - ks * ks / n) / (n - 1)));
    for (long b = 0; b < nb; b++)
      s->flux_err[b] = sqrt(fmax(0.0, (sum2[b] - sum[b] * sum[b] / n) / (n - 1)));
  } else {
    s->keff_err = NAN;
    for (long b = 0; b < nb; b++) s->flux_err[b] = NAN;
  }
  s->seconds = MPI_Wtime() - t0;
  rc = 0;
out:
  free(laws);
  for (int d = 0; d < 3; d++) free(cross[d]);
  free(sum);
  free(sum2);
  free(one.flux);
  free(one.grad);
  return rc;
}

void couple_solution_free(couple_solution *s) {
  free(s->pressure);
  free(s->grad);
  free(s->flux);
  free(s->flux_err);
  free(s->cross);
  memset(s, 0, sizeof *s);
}
