/* Two-point flux residual and Jacobian (see darcy_fv.h). */
#include "darcy_fv.h"

#include <math.h>

static const int step[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

face_flux_result darcy_face(const darcy_problem *p, int i, int j, int k, int face, double p_c,
                            double p_nb, double *area) {
  int axis = face / 2, c[3] = {i, j, k};
  int nb[3] = {i + step[face][0], j + step[face][1], k + step[face][2]};
  *area = p->h[(axis + 1) % 3] * p->h[(axis + 2) % 3];
  double half = 0.5 * p->h[axis];
  const flow_law *la = darcy_law(p, darcy_index(p, i, j, k), axis);
  face_flux_result r = {0.0, 0.0, 0.0};
  if (darcy_has_neighbour(p, c, face)) { /* interior face: two halves in series */
    nb[axis] = (nb[axis] + p->n[axis]) % p->n[axis];
    double jump = p->periodic ? (face % 2 ? 1.0 : -1.0) * p->drive[axis] * p->h[axis] : 0.0;
    r = face_flux(la, half, darcy_law(p, darcy_index(p, nb[0], nb[1], nb[2]), axis), half,
                  &p->fluid, p->g_lin, p_c - p_nb + jump);
  } else if (p->fixed[face]) { /* fixed pressure at the face: one half */
    double pb = p->bc_p[face][darcy_face_index(p, face, i, j, k)];
    r = face_flux(la, half, NULL, 0.0, &p->fluid, p->g_lin, p_c - pb);
  }
  return r;
}

/* Equivalent Darcy conductance of the face, used only as a floor for dq/dp: laws with zero slope at
 * zero gradient (smoothed threshold) would otherwise give singular Jacobian rows in stagnant
 * blocks. */
static double linear_conductance(const darcy_problem *p, int i, int j, int k, int face) {
  int axis = face / 2, c[3] = {i, j, k};
  int nb[3] = {i + step[face][0], j + step[face][1], k + step[face][2]};
  double half = 0.5 * p->h[axis], r = half / darcy_k_lin(p, darcy_index(p, i, j, k), axis);
  if (darcy_has_neighbour(p, c, face)) {
    nb[axis] = (nb[axis] + p->n[axis]) % p->n[axis];
    r += half / darcy_k_lin(p, darcy_index(p, nb[0], nb[1], nb[2]), axis);
  }
  return 1.0 / (p->fluid.mu * r);
}

/* Pressure of the neighbour across `face` from the local (ghosted) array: on a periodic DMDA the
 * ghosts at -1 and n hold the wrapped values. */
static double neighbour_p(PetscScalar ***pr, const darcy_problem *p, int i, int j, int k,
                          int face) {
  int c[3] = {i, j, k};
  if (!darcy_has_neighbour(p, c, face)) return 0.0;
  return pr[k + step[face][2]][j + step[face][1]][i + step[face][0]];
}

/* The tie of a periodic problem's block (0,0,0) to p~ = 0, in equation units (see darcy_problem.h).
 */
static int anchored(const darcy_problem *p, int i, int j, int k) {
  return p->periodic && i == 0 && j == 0 && k == 0;
}

PetscErrorCode darcy_residual_local(DMDALocalInfo *info, PetscScalar ***pr, PetscScalar ***f,
                                    void *ctx) {
  const darcy_problem *p = ctx;
  PetscFunctionBeginUser;
  for (int k = info->zs; k < info->zs + info->zm; k++)
    for (int j = info->ys; j < info->ys + info->ym; j++)
      for (int i = info->xs; i < info->xs + info->xm; i++) {
        double out = 0.0, area;
        for (int face = 0; face < 2 * p->dim; face++) {
          face_flux_result r =
              darcy_face(p, i, j, k, face, pr[k][j][i], neighbour_p(pr, p, i, j, k, face), &area);
          out += area * r.q;
        }
        f[k][j][i] = p->eq_scale * (out - (p->source ? p->source[darcy_index(p, i, j, k)] : 0.0));
        if (anchored(p, i, j, k)) f[k][j][i] += pr[k][j][i];
      }
  PetscFunctionReturn(0);
}

PetscErrorCode darcy_jacobian_local(DMDALocalInfo *info, PetscScalar ***pr, Mat J, Mat Jpre,
                                    void *ctx) {
  (void)J;
  const darcy_problem *p = ctx;
  PetscFunctionBeginUser;
  /* values are added: on a periodic axis of 2 blocks both faces lead to the same neighbour */
  PetscCall(MatZeroEntries(Jpre));
  for (int k = info->zs; k < info->zs + info->zm; k++)
    for (int j = info->ys; j < info->ys + info->ym; j++)
      for (int i = info->xs; i < info->xs + info->xm; i++) {
        MatStencil row = {.k = k, .j = j, .i = i}, cols[7];
        PetscScalar vals[7];
        int nc = 1, c[3] = {i, j, k};
        double diag = anchored(p, i, j, k) ? 1.0 : 0.0, area;
        for (int face = 0; face < 2 * p->dim; face++) {
          int ni = i + step[face][0], nj = j + step[face][1], nk = k + step[face][2];
          int inside = darcy_has_neighbour(p, c, face); /* periodic: PETSc wraps -1 and n */
          if (!inside && !p->fixed[face]) continue;
          face_flux_result r =
              darcy_face(p, i, j, k, face, pr[k][j][i], neighbour_p(pr, p, i, j, k, face), &area);
          double g =
              p->eq_scale * area * fmax(r.dq_dp, 1e-10 * linear_conductance(p, i, j, k, face));
          diag += g;
          if (inside) {
            cols[nc] = (MatStencil){.k = nk, .j = nj, .i = ni};
            vals[nc++] = -g;
          }
        }
        cols[0] = row;
        vals[0] = diag;
        PetscCall(MatSetValuesStencil(Jpre, 1, &row, nc, cols, vals, ADD_VALUES));
      }
  PetscCall(MatAssemblyBegin(Jpre, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Jpre, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}
