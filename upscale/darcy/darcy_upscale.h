/* `mdpore darcy --upscale`: the effective permeability tensor of a grid of Darcy blocks, with the
 * three boundary-condition families of OPM's upscale_perm (docs/darcy-config.md, "Upscaling"):
 *   fixed     pressure drop between the two faces normal to the flow axis, no flow through the
 *             others: one solve per axis, the diagonal only;
 *   linear    on every boundary face the pressure of a uniform gradient along the axis: the full
 *             tensor (not symmetric in general);
 *   periodic  p = p~ - G.x with p~ periodic over the grid: the full, symmetric tensor.
 * K_ij = mu <q_i> L_j / dp_j, where a pressure drop dp_j over the length L_j drives along j and
 * <q_i> is the mean Darcy flux density (along +i) through the two boundary faces normal to i, as
 * OPM's upscale_perm defines it. With fixed and periodic conditions every cross-section carries the
 * same flow, so <q_i> is also the volume-mean velocity; with linear conditions flow also crosses
 * the side faces and the two definitions differ. */
#ifndef MDPORE_UPSCALE_DARCY_UPSCALE_H
#define MDPORE_UPSCALE_DARCY_UPSCALE_H

#include <mpi.h>
#include <stddef.h>

#include "darcy_problem.h"

typedef enum { UPSCALE_FIXED = 0, UPSCALE_LINEAR, UPSCALE_PERIODIC, UPSCALE_COUNT } upscale_family;

/* "fixed", "linear", "periodic", NULL (keyword lists), and one sentence naming each family's
 * conditions (printed with its tensor). */
extern const char *const darcy_upscale_names[UPSCALE_COUNT + 1];
const char *darcy_upscale_conditions(upscale_family f);

typedef struct {
  int dim;
  int done[UPSCALE_COUNT];
  int defined[UPSCALE_COUNT][3][3]; /* fixed: the diagonal; linear, periodic: all of dim x dim */
  double k[UPSCALE_COUNT][3][3];    /* K[i][j] in the problem's permeability unit */
  double asymmetry[UPSCALE_COUNT];  /* max |K_ij - K_ji| / max K_ii */
  double seconds[UPSCALE_COUNT];    /* wall time of the family's solves */
  int converged[UPSCALE_COUNT];     /* every solve of the family met its tolerance */
  int linear_its[UPSCALE_COUNT];    /* CG iterations, all directions */
  char reason[UPSCALE_COUNT][64];   /* the last solve's convergence reason */
} darcy_upscale_result;

/* Can this problem be upscaled with these families (bit f set: family f)? Every block must follow
 * Darcy's law, no sources, and the periodic family needs at least 2 blocks along each axis.
 * Returns 0, or -1 with the reason in why. */
int darcy_upscale_check(const darcy_problem *p, int families, char *why, size_t why_len);

/* Collective on comm: solves each requested family along each axis of `base` (its laws, fluid and
 * grid; its boundary conditions and sources are not used) and fills r on every rank. Returns 0, or
 * non-zero on a PETSc error. */
int darcy_upscale(MPI_Comm comm, const darcy_problem *base, int families, darcy_upscale_result *r);

#endif
