/* The permeability tensor with fixed, linear and periodic boundary conditions (see
 * darcy_upscale.h). */
#include "darcy_upscale.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "darcy_fv.h"
#include "darcy_solve.h"

const char *const darcy_upscale_names[UPSCALE_COUNT + 1] = {"fixed", "linear", "periodic", NULL};

const char *darcy_upscale_conditions(upscale_family f) {
  static const char *const text[UPSCALE_COUNT] = {
      "fixed pressure on the two faces normal to the flow, no flow through the other faces "
      "(diagonal only)",
      "linear pressure p = -G.x on every boundary face (full tensor)",
      "periodic: p - (-G.x) periodic over the grid (full, symmetric tensor)"};
  return text[f];
}

int darcy_upscale_check(const darcy_problem *p, int families, char *why, size_t why_len) {
  for (int k = 0; k < p->n[2]; k++)
    for (int j = 0; j < p->n[1]; j++)
      for (int i = 0; i < p->n[0]; i++) {
        for (int a = 0; a < (darcy_is_diagonal(p) ? p->dim : 1); a++) {
          const flow_law *l = darcy_law(p, darcy_index(p, i, j, k), a);
          if (l->kind != LAW_DARCY) {
            char along[16] = "";
            if (darcy_is_diagonal(p)) snprintf(along, sizeof along, " along %c", 'x' + a);
            snprintf(why, why_len,
                     "a permeability tensor needs Darcy laws in every block (block (%d, %d, %d) "
                     "has law %s%s)",
                     i, j, k, flow_law_name(l->kind), along);
            return -1;
          }
        }
      }
  if (p->source)
    for (long b = 0; b < darcy_nblocks(p); b++)
      if (p->source[b] != 0.0) {
        snprintf(why, why_len, "a permeability tensor is defined without sources (got some)");
        return -1;
      }
  if (families & (1 << UPSCALE_PERIODIC))
    for (int a = 0; a < p->dim; a++)
      if (p->n[a] < 2) {
        snprintf(why, why_len,
                 "periodic conditions need at least 2 blocks along every axis (got %d along %c)",
                 p->n[a], "xyz"[a]);
        return -1;
      }
  return 0;
}

static double length(const darcy_problem *p, int a) {
  return p->n[a] * p->h[a];
}

/* Boundary pressure of the linear family at the centre of face `face` of boundary block c. */
static double linear_value(const darcy_problem *p, int face, const int c[3], int dir, double dp) {
  double x = (c[dir] + 0.5) * p->h[dir];
  if (face / 2 == dir) x = face % 2 ? length(p, dir) : 0.0;
  return dp * (1.0 - x / length(p, dir));
}

/* The base problem with the boundary conditions of family f driving along dir (pressure drop dp
 * over the grid). Shares laws and k_lin with base; its own bc_p arrays (*oom = 1 when one of them
 * could not be allocated). */
static darcy_problem family_problem(const darcy_problem *base, int f, int dir, double dp,
                                    int *oom) {
  darcy_problem q = *base;
  memset(q.fixed, 0, sizeof q.fixed);
  memset(q.bc_p, 0, sizeof q.bc_p);
  memset(q.drive, 0, sizeof q.drive);
  q.source = NULL;
  q.periodic = f == UPSCALE_PERIODIC;
  if (q.periodic) q.drive[dir] = dp / length(base, dir);
  for (int face = 0; face < 2 * q.dim && !q.periodic; face++) {
    if (f == UPSCALE_FIXED && face / 2 != dir) continue;
    long n = darcy_face_count(&q, face);
    q.fixed[face] = 1;
    q.bc_p[face] = malloc(n * sizeof(double));
    if (!q.bc_p[face]) {
      q.fixed[face] = 0;
      *oom = 1;
      continue;
    }
    int axis = face / 2, t1 = (axis + 1) % 3, t2 = (axis + 2) % 3;
    for (int b = 0; b < q.n[t2]; b++)
      for (int a = 0; a < q.n[t1]; a++) {
        int c[3];
        c[axis] = face % 2 ? q.n[axis] - 1 : 0;
        c[t1] = a;
        c[t2] = b;
        q.bc_p[face][darcy_face_index(&q, face, c[0], c[1], c[2])] =
            linear_value(&q, face, c, dir, dp);
      }
  }
  darcy_problem_linearise(&q, 1e-6);
  return q;
}

/* Mean flux density along each axis i through the two boundary faces normal to i (for a periodic
 * problem the wrapping face layer), from the solved pressure (see darcy_upscale.h). */
static void face_velocity(const darcy_problem *p, const double *pr, double qbar[3]) {
  for (int a = 0; a < 3; a++) qbar[a] = 0.0;
  for (int a = 0; a < p->dim; a++) {
    double sum = 0.0, area, total_area = 0.0;
    for (int k = 0; k < p->n[2]; k++)
      for (int j = 0; j < p->n[1]; j++)
        for (int i = 0; i < p->n[0]; i++) {
          int c[3] = {i, j, k}, nb[3] = {i, j, k};
          long b = darcy_index(p, i, j, k);
          if (c[a] == p->n[a] - 1) { /* the plus face (periodic: the wrapping face), outward */
            nb[a] = 0;
            double p_nb = p->periodic ? pr[darcy_index(p, nb[0], nb[1], nb[2])] : 0.0;
            face_flux_result r = darcy_face(p, i, j, k, 2 * a + 1, pr[b], p_nb, &area);
            sum += area * r.q * (p->periodic ? 2.0 : 1.0);
            total_area += area * (p->periodic ? 2.0 : 1.0);
          }
          if (c[a] == 0 && !p->periodic) { /* the minus face: flow along +a is inflow */
            face_flux_result r = darcy_face(p, i, j, k, 2 * a, pr[b], 0.0, &area);
            sum -= area * r.q;
            total_area += area;
          }
        }
    qbar[a] = sum / total_area;
  }
}

static void free_bc(darcy_problem *q) {
  for (int f = 0; f < 6; f++) free(q->bc_p[f]);
}

int darcy_upscale(MPI_Comm comm, const darcy_problem *base, int families, darcy_upscale_result *r) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  memset(r, 0, sizeof *r);
  r->dim = base->dim;
  for (int f = 0; f < UPSCALE_COUNT; f++) {
    if (!(families & (1 << f))) continue;
    double t0 = MPI_Wtime();
    r->done[f] = 1;
    r->converged[f] = 1;
    for (int dir = 0; dir < base->dim; dir++) {
      const double dp = 1.0; /* any drop: the problem is linear and its equations scaled */
      int oom = 0;
      darcy_problem q = family_problem(base, f, dir, dp, &oom);
      MPI_Allreduce(MPI_IN_PLACE, &oom, 1, MPI_INT, MPI_MAX, comm);
      if (oom) {
        if (rank == 0) fprintf(stderr, "mdpore darcy: --upscale: out of memory for a boundary\n");
        free_bc(&q);
        return 1;
      }
      double *pr = NULL;
      darcy_stats st;
      int err = darcy_solve(comm, &q, &pr, &st);
      if (err) {
        free_bc(&q);
        return err;
      }
      r->converged[f] &= st.converged;
      r->linear_its[f] += st.linear_its;
      snprintf(r->reason[f], sizeof r->reason[f], "%s", st.reason);
      if (rank == 0) {
        double qbar[3];
        face_velocity(&q, pr, qbar);
        const double g = dp / length(base, dir);
        for (int i = 0; i < base->dim; i++) {
          r->k[f][i][dir] = base->fluid.mu * qbar[i] / g;
          r->defined[f][i][dir] = f != UPSCALE_FIXED || i == dir;
        }
      }
      free(pr);
      free_bc(&q);
    }
    r->seconds[f] = MPI_Wtime() - t0;
    double diag = 0.0, off = 0.0;
    for (int i = 0; i < base->dim; i++) {
      diag = fmax(diag, fabs(r->k[f][i][i]));
      for (int j = 0; j < i; j++)
        if (r->defined[f][i][j]) off = fmax(off, fabs(r->k[f][i][j] - r->k[f][j][i]));
    }
    r->asymmetry[f] = diag > 0 ? off / diag : 0.0;
  }
  MPI_Bcast(r, (int)sizeof *r, MPI_BYTE, 0, comm);
  return 0;
}
