/* Writing the OpenFOAM case dictionaries for a voxel image (see foam_case.h for the conventions).
 */
#include "foam_case.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

const char *mdp_foam_bashrc(void) {
  static char path[4096];
  const char *env = getenv("MDPORE_OPENFOAM_BASHRC"); /* set: use exactly this one */
  const char *candidates[] = {"/usr/share/openfoam/etc/bashrc", "/usr/lib/openfoam/etc/bashrc"};
  if (env && env[0]) {
    if (access(env, R_OK) != 0) return NULL;
    snprintf(path, sizeof path, "%s", env);
    return path;
  }
  for (size_t c = 0; c < sizeof candidates / sizeof candidates[0]; c++)
    if (access(candidates[c], R_OK) == 0) {
      snprintf(path, sizeof path, "%s", candidates[c]);
      return path;
    }
  return NULL;
}

/* Open dir/rel for writing through a temporary name; mdp_foam_close renames it into place. */
typedef struct {
  FILE *f;
  char path[4096], tmp[4200];
} out_t;

static int open_out(out_t *o, const char *dir, const char *rel, char *err) {
  snprintf(o->path, sizeof o->path, "%s/%s", dir, rel);
  snprintf(o->tmp, sizeof o->tmp, "%s.tmp", o->path);
  o->f = fopen(o->tmp, "w");
  if (!o->f) snprintf(err, MDP_FOAM_ERR_LEN, "%.1500s: cannot write: %s", o->tmp, strerror(errno));
  return !o->f;
}

static int close_out(out_t *o, char *err) {
  if (fclose(o->f) != 0 || rename(o->tmp, o->path) != 0) {
    snprintf(err, MDP_FOAM_ERR_LEN, "%.1500s: cannot write: %s", o->path, strerror(errno));
    remove(o->tmp);
    return 1;
  }
  return 0;
}

static void header(FILE *f, const char *cls, const char *object) {
  fprintf(f,
          "/* written by mdpore foam */\nFoamFile\n{\n    version 2.0;\n    format ascii;\n"
          "    class %s;\n    object %s;\n}\n\n",
          cls, object);
}

static const char *face_names[3][2] = {
    {"(0 4 7 3)", "(1 2 6 5)"}, {"(0 1 5 4)", "(3 7 6 2)"}, {"(0 3 2 1)", "(4 5 6 7)"}};

static int write_block_mesh(const char *dir, const mdp_image_t *img, const mdp_foam_opts_t *o,
                            char *err) {
  out_t out;
  if (open_out(&out, dir, "system/blockMeshDict", err)) return 1;
  FILE *f = out.f;
  header(f, "dictionary", "blockMeshDict");
  const int nx = img->nx, ny = img->ny, nz = img->nz, r = o->refine, a = o->axis;
  fprintf(f, "convertToMeters 1; // lengths in voxels\n\nvertices\n(\n");
  fprintf(f,
          "    (0 0 0) (%d 0 0) (%d %d 0) (0 %d 0)\n    (0 0 %d) (%d 0 %d) (%d %d %d) (0 %d "
          "%d)\n);\n\n",
          nx, nx, ny, ny, nz, nx, nz, nx, ny, nz, ny, nz);
  fprintf(f, "blocks\n(\n    hex (0 1 2 3 4 5 6 7) (%d %d %d) simpleGrading (1 1 1)\n);\n\n",
          nx * r, ny * r, nz * r);
  fprintf(f, "boundary\n(\n");
  if (o->periodic) {
    fprintf(f, "    inlet { type cyclic; neighbourPatch outlet; faces (%s); }\n", face_names[a][0]);
    fprintf(f, "    outlet { type cyclic; neighbourPatch inlet; faces (%s); }\n", face_names[a][1]);
  } else {
    fprintf(f, "    inlet { type patch; faces (%s); }\n", face_names[a][0]);
    fprintf(f, "    outlet { type patch; faces (%s); }\n", face_names[a][1]);
  }
  if (o->side_periodic) {
    /* where pore meets solid across the wrap, subsetMesh moves the face to the walls patch */
    for (int b = 0; b < 3; b++)
      if (b != a)
        fprintf(f,
                "    sides%c0 { type cyclic; neighbourPatch sides%c1; faces (%s); }\n"
                "    sides%c1 { type cyclic; neighbourPatch sides%c0; faces (%s); }\n",
                'x' + b, 'x' + b, face_names[b][0], 'x' + b, 'x' + b, face_names[b][1]);
  } else {
    fprintf(f, "    sides { type %s; faces (", o->side_walls ? "wall" : "symmetry");
    for (int b = 0; b < 3; b++)
      if (b != a) fprintf(f, " %s %s", face_names[b][0], face_names[b][1]);
    fprintf(f, " ); }\n");
  }
  fprintf(f, "    walls { type wall; faces (); } // filled by subsetMesh\n);\n");
  return close_out(&out, err);
}

int mdp_foam_write_control(const char *dir, const mdp_foam_opts_t *o, int start, int end,
                           double tol, char *err) {
  out_t out;
  const double dt = o->simple ? 1.0 : o->dt;
  if (open_out(&out, dir, "system/controlDict", err)) return 1;
  FILE *f = out.f;
  header(f, "dictionary", "controlDict");
  fprintf(
      f,
      "application %s;\nstartFrom latestTime;\nstartTime 0;\nstopAt endTime;\n"
      "endTime %.17g;\ndeltaT %.17g;\nwriteControl timeStep;\nwriteInterval %d;\npurgeWrite 1;\n"
      "writeFormat ascii;\nwritePrecision 14;\ntimePrecision 12;\nrunTimeModifiable false;\n\n",
      o->simple ? "simpleFoam" : "pimpleFoam", end * dt, dt, end - start);
  /* Volume integrals of U and |U| over the pore space: the superficial velocity is int(U)/V_box
   * (exact for incompressible flow: int u_a dV = Q L), tortuosity int|U| / int(U_a). */
  fprintf(f,
          "functions\n{\n"
          "    magU { type mag; libs (\"libfieldFunctionObjects.so\"); field U; result magU;\n"
          "           executeControl timeStep; executeInterval %d; writeControl none; }\n"
          "    flow { type volFieldValue; libs (\"libfieldFunctionObjects.so\"); fields (U magU);\n"
          "           operation volIntegrate; regionType all; writeFields false; log false;\n"
          "           executeControl timeStep; executeInterval %d;\n"
          "           writeControl timeStep; writeInterval %d; }\n}\n",
          o->check_every, o->check_every, o->check_every);
  if (close_out(&out, err)) return 1;
  if (open_out(&out, dir, "system/fvSchemes", err)) return 1;
  header(out.f, "dictionary", "fvSchemes");
  /* Stokes regime: the drive is small enough (Re << 1e-3) that convection is negligible. */
  fprintf(out.f,
          "ddtSchemes { default %s; }\ngradSchemes { default Gauss linear; }\n"
          "divSchemes { default none; div(phi,U) bounded Gauss linear;\n"
          "             div((nuEff*dev2(T(grad(U))))) Gauss linear; }\n"
          "laplacianSchemes { default Gauss linear corrected; }\n"
          "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n",
          o->simple ? "steadyState" : "Euler");
  if (close_out(&out, err)) return 1;
  if (open_out(&out, dir, "system/fvSolution", err)) return 1;
  f = out.f;
  header(f, "dictionary", "fvSolution");
  fprintf(
      f, "solvers\n{\n"
         "    \"(p|pFinal)\" { solver GAMG; smoother GaussSeidel; tolerance 1e-14; relTol 0.01; }\n"
         "    \"(U|UFinal)\" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-15;\n"
         "                   relTol 0.05; }\n}\n\n");
  if (o->simple) {
    /* residualControl lets simpleFoam stop itself once p has converged; U along the axis and the
     * flux are checked by the driver (a transverse U component that is zero everywhere has a
     * meaningless normalised residual, so U cannot be listed here). */
    fprintf(f,
            "SIMPLE\n{\n    nNonOrthogonalCorrectors 0;\n    consistent yes; // SIMPLEC\n"
            "    pRefCell 0;\n    pRefValue 0;\n    residualControl { p %.3g; } // 0: none\n}\n\n"
            "relaxationFactors { equations { U 0.9; } }\n",
            tol);
  } else {
    /* Pseudo-transient march to the steady Stokes state: PISO with a large time step converges in
     * a few hundred steps where SIMPLE needs thousands of iterations (docs/foam.md). The steady
     * state carries a Rhie-Chow (ddtCorr) term of relative size ~ h^2 / (nu dt), below 1e-4 here.
     */
    fprintf(f,
            "PIMPLE\n{\n    momentumPredictor yes;\n    nOuterCorrectors 1;\n    nCorrectors 4;\n"
            "    nNonOrthogonalCorrectors 0;\n    pRefCell 0;\n    pRefValue 0;\n}\n");
  }
  return close_out(&out, err);
}

static int write_static(const char *dir, const mdp_foam_opts_t *o, char *err) {
  out_t out;
  if (open_out(&out, dir, "constant/transportProperties", err)) return 1;
  header(out.f, "dictionary", "transportProperties");
  fprintf(out.f, "transportModel Newtonian;\nnu 1; // voxel units\n");
  if (close_out(&out, err)) return 1;
  if (open_out(&out, dir, "constant/turbulenceProperties", err)) return 1;
  header(out.f, "dictionary", "turbulenceProperties");
  fprintf(out.f, "simulationType laminar;\n");
  if (close_out(&out, err)) return 1;
  if (o->periodic) { /* body force per unit mass = the kinematic pressure gradient */
    if (open_out(&out, dir, "constant/fvOptions", err)) return 1;
    header(out.f, "dictionary", "fvOptions");
    double g[3] = {0, 0, 0};
    g[o->axis] = o->gradient;
    fprintf(out.f,
            "drive\n{\n    type vectorSemiImplicitSource;\n    selectionMode all;\n"
            "    volumeMode specific;\n    injectionRateSuSp { U ((%.17g %.17g %.17g) 0); }\n}\n",
            g[0], g[1], g[2]);
    if (close_out(&out, err)) return 1;
  }
  if (o->np > 1) {
    if (open_out(&out, dir, "system/decomposeParDict", err)) return 1;
    header(out.f, "dictionary", "decomposeParDict");
    /* "simple" slabs along the longest box edge: needs no graph partitioner (Debian's OpenFOAM
     * has only a stub for scotch). */
    int n[3] = {1, 1, 1}, longest = 0;
    for (int a = 1; a < 3; a++)
      if (o->box[a] > o->box[longest]) longest = a;
    n[longest] = o->np;
    fprintf(out.f,
            "numberOfSubdomains %d;\nmethod simple;\nsimpleCoeffs { n (%d %d %d); delta 0.001; }\n",
            o->np, n[0], n[1], n[2]);
    if (close_out(&out, err)) return 1;
  }
  return 0;
}

int mdp_foam_write_case(const char *dir, const mdp_image_t *img, const mdp_foam_opts_t *o,
                        char *err) {
  const char *sub[] = {"system", "constant", "constant/polyMesh", "0"};
  for (size_t s = 0; s < sizeof sub / sizeof sub[0]; s++) {
    char p[4200];
    snprintf(p, sizeof p, "%s/%s", dir, sub[s]);
    if (mkdir(p, 0755) != 0 && errno != EEXIST) {
      snprintf(err, MDP_FOAM_ERR_LEN, "%.1500s: cannot create folder: %s", p, strerror(errno));
      return 1;
    }
  }
  return write_block_mesh(dir, img, o, err) || write_static(dir, o, err) ||
         mdp_foam_write_control(dir, o, 0, o->chunk, o->tol_residual, err);
}

int mdp_foam_write_pore_set(const char *dir, const mdp_image_t *img, const mdp_foam_opts_t *o,
                            long long *n_cells, char *err) {
  char sets[4200];
  snprintf(sets, sizeof sets, "%s/constant/polyMesh/sets", dir);
  if (mkdir(sets, 0755) != 0 && errno != EEXIST) {
    snprintf(err, MDP_FOAM_ERR_LEN, "%.1500s: cannot create folder: %s", sets, strerror(errno));
    return 1;
  }
  const int r = o->refine;
  const long long NX = (long long)img->nx * r, NY = (long long)img->ny * r,
                  NZ = (long long)img->nz * r;
  long long n = 0;
  for (size_t idx = 0; idx < mdp_image_count(img); idx++) n += mdp_image_is_pore(img, idx);
  n *= (long long)r * r * r;
  out_t out;
  if (open_out(&out, dir, "constant/polyMesh/sets/poreCells", err)) return 1;
  FILE *f = out.f;
  header(f, "cellSet", "poreCells");
  fprintf(f, "%lld\n(\n", n);
  /* blockMesh numbers the cells of one block x fastest: I + NX (J + NY K). */
  for (long long K = 0; K < NZ; K++)
    for (long long J = 0; J < NY; J++)
      for (long long I = 0; I < NX; I++)
        if (mdp_image_is_pore(img, mdp_image_index(img, (int)(I / r), (int)(J / r), (int)(K / r))))
          fprintf(f, "%lld\n", I + NX * (J + NY * K));
  fprintf(f, ")\n");
  *n_cells = n;
  return close_out(&out, err);
}

/* The side patches' entry of a field: one "sides" patch, or the cyclic pairs of --sides periodic. */
static void side_entries(FILE *f, const mdp_foam_opts_t *o, const char *type) {
  if (!o->side_periodic) {
    fprintf(f, "    sides { type %s; }\n", type);
    return;
  }
  for (int b = 0; b < 3; b++)
    if (b != o->axis)
      fprintf(f, "    sides%c0 { type cyclic; }\n    sides%c1 { type cyclic; }\n", 'x' + b,
              'x' + b);
}

/* --boundary mirror: the velocity's components along the face are fixed at zero and the normal one
 * has zero gradient (directionMixed, valueFraction = I - n n as xx xy xz yy yz zz). At a mirror plane
 * of a mirrored sample the tangential velocity vanishes by symmetry and continuity then gives
 * d u_n / d n = 0: the same plane as mdpore permeability's --boundary mirror. */
static void mirror_face_velocity(FILE *f, const char *patch, int axis) {
  const int xx = axis != 0, yy = axis != 1, zz = axis != 2;
  fprintf(f,
          "    %s { type directionMixed; refValue uniform (0 0 0); refGradient uniform (0 0 0); "
          "valueFraction uniform (%d 0 0 %d 0 %d); value uniform (0 0 0); }\n",
          patch, xx, yy, zz);
}

int mdp_foam_write_fields(const char *dir, const mdp_foam_opts_t *o, char *err) {
  const char *io = o->periodic ? "cyclic" : NULL;
  const char *side = o->side_walls ? "noSlip" : "symmetry";
  out_t out;
  if (open_out(&out, dir, "0/U", err)) return 1;
  header(out.f, "volVectorField", "U");
  fprintf(out.f,
          "dimensions [0 1 -1 0 0 0 0];\ninternalField uniform (0 0 0);\n\nboundaryField\n{\n");
  if (o->mirror_faces && !io) {
    mirror_face_velocity(out.f, "inlet", o->axis);
    mirror_face_velocity(out.f, "outlet", o->axis);
  } else
    fprintf(out.f, "    inlet { type %s; }\n    outlet { type %s; }\n", io ? io : "zeroGradient",
            io ? io : "zeroGradient");
  side_entries(out.f, o, side);
  fprintf(out.f, "    walls { type noSlip; }\n}\n");
  if (close_out(&out, err)) return 1;
  if (open_out(&out, dir, "0/p", err)) return 1;
  header(out.f, "volScalarField", "p");
  fprintf(out.f, "dimensions [0 2 -2 0 0 0 0]; // kinematic pressure\ninternalField uniform 0;\n\n"
                 "boundaryField\n{\n");
  if (io) {
    fprintf(out.f, "    inlet { type cyclic; }\n    outlet { type cyclic; }\n");
  } else {
    /* kinematic pressure drop dp = G L over the sample length L (voxels) */
    fprintf(out.f,
            "    inlet { type fixedValue; value uniform %.17g; }\n"
            "    outlet { type fixedValue; value uniform 0; }\n",
            o->gradient * o->length_voxels);
  }
  side_entries(out.f, o, o->side_walls ? "zeroGradient" : "symmetry");
  fprintf(out.f, "    walls { type zeroGradient; }\n}\n");
  return close_out(&out, err);
}
