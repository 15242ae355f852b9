/* OpenFOAM cross-check: write a case from a voxel image, run it, read the results.
 *
 * Mesh: blockMesh makes the image box with (nx r) x (ny r) x (nz r) hex cells (r = refine) in voxel
 * units; the pore cells are written as a cellSet and kept by `subsetMesh -patch walls`, so every
 * face between a pore cell and a solid voxel becomes the no-slip patch "walls". Box faces normal to
 * the flow are "inlet"/"outlet" (fixed pressures, or a cyclic pair with a body force for --drive
 * periodic; with --boundary mirror no tangential velocity on them); the other four box faces are
 * the patch "sides" (symmetry = mirror/slip, or wall = no slip) or, for --sides periodic, the
 * cyclic pairs "sides<a>0"/"sides<a>1" per lateral axis a. */
#ifndef MDPORE_FOAM_CASE_H
#define MDPORE_FOAM_CASE_H

#include "mdpore_image.h"

#define MDP_FOAM_ERR_LEN 2048

typedef struct {
  int axis;          /* flow axis: 0 x, 1 y, 2 z */
  int refine;        /* hex cells per voxel edge */
  int periodic;      /* 0: pressure drop inlet -> outlet; 1: cyclic inlet/outlet + body force */
  int mirror_faces;  /* pressure drop with no tangential velocity on inlet/outlet (--boundary
                     * mirror): the faces are the mirror planes of a mirrored periodic sample */
  int side_walls;    /* 0: symmetry on the four side faces; 1: no-slip walls */
  int side_periodic; /* 1: cyclic pairs on the side faces (the lateral periodic wrap) */
  int np;            /* OpenFOAM ranks (decomposePar + mpirun) when > 1 */
  int simple;        /* 1: simpleFoam (SIMPLEC); 0: pimpleFoam marched in pseudo-time to steady */
  double dt;         /* pimple: pseudo time step (voxel units, nu = 1) */
  double gradient;   /* applied kinematic pressure gradient (voxel units, nu = 1) */
  double length_voxels; /* sample length along the axis (set by the driver) */
  int box[3];           /* image dimensions (set by the driver) */
  double tol_residual;  /* initial residual of p and of U along the axis */
  double tol_flux;      /* relative flow-rate change between checks and estimated remaining error */
  int check_every;      /* iterations (time steps) between flux checks */
  int max_iter;         /* iterations (time steps) before giving up */
  int chunk;            /* iterations (time steps) per solver run between convergence checks */
  int verbose;
  int smooth_walls; /* 1: move the wall points onto the sub-voxel interface (foam_smooth_walls.c) */
} mdp_foam_opts_t;

/* What --walls smooth did to the mesh. */
typedef struct {
  long long wall_points, moved_points; /* points on the walls patch; those that moved */
  long long limited_points;            /* wall points held back to keep every cell valid */
  double max_move;                     /* largest displacement along one axis (voxels) */
  double mesh_volume;                  /* checkMesh "Total volume" (voxel units) */
  char mesh_check[256];                /* "ok" or checkMesh's failed checks */
} mdp_foam_smooth_t;

typedef struct {
  int iterations, converged, cells;
  int restarts;        /* pimple: restarts with a smaller time step after a divergence */
  double dt;           /* pimple: the time step that converged */
  double res_p, res_u; /* last initial residuals (p; U along the axis) */
  double flux_change;  /* relative change of q over the last check interval */
  double flux_error;   /* estimated relative distance of q from its converged value (NaN: none) */
  double int_u[3];     /* volume integral of U over the pore space (voxel units) */
  double int_mag_u;    /* volume integral of |U| */
  double wall_s;
  mdp_foam_smooth_t smooth; /* --walls smooth only */
} mdp_foam_result_t;

/* Path of the OpenFOAM environment script, or NULL when OpenFOAM is not installed. */
const char *mdp_foam_bashrc(void);
/* Write system/, constant/ (mesh dictionaries, transport, fvOptions) and the pore cellSet source.
 */
int mdp_foam_write_case(const char *dir, const mdp_image_t *img, const mdp_foam_opts_t *o,
                        char *err);
/* Write the cellSet of pore cells (blockMesh numbering) into constant/polyMesh/sets/poreCells. */
int mdp_foam_write_pore_set(const char *dir, const mdp_image_t *img, const mdp_foam_opts_t *o,
                            long long *n_cells, char *err);
/* Write 0/U and 0/p (after subsetMesh, so that the walls patch exists). */
int mdp_foam_write_fields(const char *dir, const mdp_foam_opts_t *o, char *err);
/* controlDict, fvSchemes and fvSolution for a run from iteration (time step) start to end;
 * simpleFoam also stops itself when the initial residual of p falls below tol. */
int mdp_foam_write_control(const char *dir, const mdp_foam_opts_t *o, int start, int end,
                           double tol, char *err);
/* Mesh, decompose, iterate simpleFoam until converged (see foam_run.c). */
int mdp_foam_run(const char *dir, const mdp_image_t *img, const mdp_foam_opts_t *o,
                 mdp_foam_result_t *res, char *err);

/* --walls smooth: move the wall points of the subset mesh in constant/polyMesh/points onto the 0.5
 * iso-surface of the corner-averaged solid fraction (foam_smooth_walls.c). */
int mdp_foam_smooth_walls(const char *dir, const mdp_image_t *img, const mdp_foam_opts_t *o,
                          mdp_foam_smooth_t *st, char *err);

/* Parsing (foam_parse.c). */
/* Last "Time =" value, the initial residuals of the last step's first p solve and of U along the
 * axis, and whether simpleFoam reported convergence. */
int mdp_foam_parse_log(const char *log, int axis, double *last_time, double *res_p, double *res_u,
                       int *solver_converged);
/* Read every postProcessing/flow/<start>/volFieldValue.dat; rows of (iter, int U xyz, int |U|). */
int mdp_foam_read_flow(const char *dir, double **rows, int *n_rows, char *err);
/* checkMesh log: "Total volume", the failed checks ("ok" when none) and whether one of them makes
 * the mesh unusable (inverted or open cells). */
int mdp_foam_parse_checkmesh(const char *log, double *volume, char *failed, size_t len, int *fatal);

#endif
