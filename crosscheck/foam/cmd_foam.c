/* mdpore foam IMAGE --axis x|y|z: continuum (OpenFOAM simpleFoam, Stokes) permeability of a voxel
 * image, the cross-check for the mDPD pore solver. Prints one JSON object. */
#define _GNU_SOURCE /* nftw */
#include "foam_case.h"
#include "mdpore_image_cli.h"

#include <errno.h>
#include <ftw.h>
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define EXIT_NOT_CONVERGED 3
#define EXIT_NO_OPENFOAM 4

static const cli_help_option_t foam_options[] = {
    {"--axis x|y|z", "flow direction (required)", 1},
    {"--refine R", "R^3 hex cells per voxel (default 1)", 1},
    {"--walls staircase|smooth",
     "voxel faces as walls (default), or sub-voxel walls: the wall points move onto the 0.5 "
     "iso-surface of the solid fraction averaged over the 2x2x2 voxels at each corner (flat walls "
     "stay)",
     0},
    {"--drive pressure|periodic",
     "pressure drop between inlet and outlet faces (default), or cyclic inlet/outlet with a body "
     "force: the image is one period along the axis; where the first and last slices meet pore "
     "to solid, the face is a wall (smooth walls need matching slices)",
     0},
    {"--boundary faces|mirror|periodic",
     "the faces normal to the flow: inlet and outlet at fixed pressures (faces, the default; = "
     "--drive pressure), the same with no tangential velocity on them (mirror: the planes of a "
     "mirrored periodic sample, as mdpore permeability --boundary mirror), or cyclic (periodic; = "
     "--drive periodic)",
     0},
    {"--sides symmetry|wall|periodic",
     "the four box faces parallel to the flow (default symmetry; periodic: cyclic pairs, pore "
     "meeting solid across the wrap is a wall, as the lateral wrap of mdpore permeability)",
     0},
    {"--solver pimple|simple",
     "pimpleFoam marched in pseudo-time to the steady state (default; converges in far fewer "
     "steps) or simpleFoam (SIMPLEC)",
     0},
    {"--dt DT",
     "pimple: pseudo time step in voxel units (nu = 1; default 20 / R^2, divided by 4 "
     "automatically while the march diverges)",
     0},
    {"--np N", "run OpenFOAM on N ranks (decomposePar, mpirun)", 1},
    {"--tol-residual T", "initial residuals of p and U along the axis (default 1e-6)", 0},
    {"--tol-flux T",
     "relative flow-rate change between checks, and its estimated distance from convergence "
     "(geometric extrapolation) (default 1e-5)",
     0},
    {"--check-every N", "steps between flow-rate checks (default 5; simple: 10)", 0},
    {"--max-iter N", "give up after N steps (default 5000; simple: 50000; exit 3)", 1},
    {"--gradient G", "kinematic pressure gradient, voxel units (default 1e-5)", 0},
    {"--case DIR", "build the case in DIR (new or empty) and keep it", 1},
    {"--keep", "keep the temporary case folder", 0},
    {"--output FILE", "also write the JSON to FILE", 1},
    {"--verbose", "report each tool and convergence check on stderr", 1},
    {NULL, NULL, 0}};

static const cli_help_page_t foam_help = {
    .command = "foam",
    .usage = "usage: mdpore foam IMAGE --axis x|y|z [options]\n",
    .purpose = "Stokes-flow permeability of an image with OpenFOAM (the continuum cross-check).",
    .about = "Stokes flow through the pore voxels with OpenFOAM (laminar, nu = 1 in voxel units) "
             "and the permeability k = mu q L / dp with q = Q / A_total: the superficial "
             "velocity over the whole cross-section, solid included. Prints JSON.",
    .options = foam_options,
    .options2 = mdp_image_cli_options,
    .notes = "exit: 0 converged, 1 error, 2 usage, 3 not converged, 4 OpenFOAM not installed",
    .more = "docs/foam.md",
};

static int rm_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw) {
  (void)sb, (void)flag, (void)ftw;
  return remove(path);
}

/* v formatted with fmt, or "null" when it is not finite (JSON has no NaN or inf). */
static const char *finite_or_null(char *buf, size_t len, const char *fmt, double v) {
  if (!isfinite(v)) return "null";
  snprintf(buf, len, fmt, v);
  return buf;
}

static int axis_of(const char *s) {
  return !strcmp(s, "x") ? 0 : !strcmp(s, "y") ? 1 : !strcmp(s, "z") ? 2 : -1;
}

/* --drive periodic: the faces where the first and last slices meet pore to solid. On the staircase
 * mesh subsetMesh turns them into walls (the cyclic pair keeps the pore-pore faces); the smooth-wall
 * mesh moves points on the cyclic planes and needs them to match. */
static long long end_slice_mismatch(const mdp_image_t *img, int axis) {
  const int n[3] = {img->nx, img->ny, img->nz};
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  long long bad = 0;
  for (int b = 0; b < n[v]; b++)
    for (int a = 0; a < n[u]; a++) {
      int p[3], q[3];
      p[axis] = 0, q[axis] = n[axis] - 1, p[u] = q[u] = a, p[v] = q[v] = b;
      bad += mdp_image_is_pore(img, mdp_image_index(img, p[0], p[1], p[2])) !=
             mdp_image_is_pore(img, mdp_image_index(img, q[0], q[1], q[2]));
    }
  return bad;
}

int cmd_foam(int argc, char **argv) {
  int nranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  if (nranks > 1) {
    fprintf(stderr, "mdpore foam: run as one process; --np N runs OpenFOAM itself in parallel\n");
    return 2;
  }
  char err[MDP_FOAM_ERR_LEN];
  mdp_image_cli_t cli;
  mdp_image_cli_init(&cli);
  mdp_foam_opts_t o = {.axis = -1,
                       .refine = 1,
                       .np = 1,
                       .gradient = 1e-5,
                       .tol_residual = 1e-6,
                       .tol_flux = 1e-5,
                       .check_every = 0,
                       .max_iter = 0,
                       .chunk = 0,
                       .dt = 0};
  const char *path = NULL, *case_dir = NULL, *output = NULL;
  int keep = 0;
  for (int i = 1; i < argc;) {
    int r = mdp_image_cli_parse(argc, argv, &i, &cli, err);
    if (r < 0) {
      fprintf(stderr, "mdpore foam: %s\n", err);
      return 2;
    }
    if (r) continue;
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int bad = 0, takes = 1;
    if (cli_help_flag(a)) {
      cli_help_print(stdout, &foam_help, cli_help_flag(a));
      return 0;
    } else if (!strcmp(a, "--keep"))
      keep = 1, takes = 0;
    else if (!strcmp(a, "--verbose"))
      o.verbose = 1, takes = 0;
    else if (a[0] != '-') {
      if (path) {
        fprintf(stderr, "mdpore foam: unexpected argument '%s'\n", a);
        return 2;
      }
      path = a, takes = 0;
    } else if (!v)
      bad = 1;
    else if (!strcmp(a, "--axis"))
      bad = (o.axis = axis_of(v)) < 0;
    else if (!strcmp(a, "--refine"))
      bad = (o.refine = atoi(v)) < 1;
    else if (!strcmp(a, "--walls")) {
      o.smooth_walls = !strcmp(v, "smooth");
      bad = !o.smooth_walls && strcmp(v, "staircase");
    } else if (!strcmp(a, "--drive")) {
      o.periodic = !strcmp(v, "periodic");
      bad = !o.periodic && strcmp(v, "pressure");
    } else if (!strcmp(a, "--boundary")) {
      o.periodic = !strcmp(v, "periodic");
      o.mirror_faces = !strcmp(v, "mirror");
      bad = !o.periodic && !o.mirror_faces && strcmp(v, "faces");
    } else if (!strcmp(a, "--sides")) {
      o.side_walls = !strcmp(v, "wall");
      o.side_periodic = !strcmp(v, "periodic");
      bad = !o.side_walls && !o.side_periodic && strcmp(v, "symmetry");
    } else if (!strcmp(a, "--solver")) {
      o.simple = !strcmp(v, "simple");
      bad = !o.simple && strcmp(v, "pimple");
    } else if (!strcmp(a, "--dt"))
      bad = !((o.dt = atof(v)) > 0);
    else if (!strcmp(a, "--np"))
      bad = (o.np = atoi(v)) < 1;
    else if (!strcmp(a, "--tol-residual"))
      bad = !((o.tol_residual = atof(v)) > 0);
    else if (!strcmp(a, "--tol-flux"))
      bad = !((o.tol_flux = atof(v)) > 0);
    else if (!strcmp(a, "--check-every"))
      bad = (o.check_every = atoi(v)) < 1;
    else if (!strcmp(a, "--max-iter"))
      bad = (o.max_iter = atoi(v)) < 1;
    else if (!strcmp(a, "--gradient"))
      bad = !((o.gradient = atof(v)) > 0);
    else if (!strcmp(a, "--case"))
      case_dir = v;
    else if (!strcmp(a, "--output"))
      output = v;
    else {
      fprintf(stderr, "mdpore foam: unknown option '%s' (see mdpore foam --help)\n", a);
      return 2;
    }
    if (bad) {
      fprintf(stderr, "mdpore foam: option %s: bad or missing value '%s'\n", a, v ? v : "");
      return 2;
    }
    i += 1 + takes;
  }
  if (!path || o.axis < 0) {
    cli_help_print(stderr, &foam_help, CLI_HELP_SHORT);
    return 2;
  }
  if (o.side_periodic && o.smooth_walls) {
    fprintf(stderr, "mdpore foam: --sides periodic with --walls smooth: the smooth walls mirror "
                    "the image across the side faces; use --walls staircase or --sides symmetry\n");
    return 2;
  }
  /* SIMPLE iterations are cheap and many; pseudo-time steps are dearer and few. */
  if (!o.check_every) o.check_every = o.simple ? 10 : 5;
  if (!o.max_iter) o.max_iter = o.simple ? 50000 : 5000;
  if (!o.chunk) o.chunk = o.simple ? 2000 : 50;
  /* The stable pseudo time step scales with the cell size squared (viscous time of one cell). */
  if (!(o.dt > 0)) o.dt = 20.0 / ((double)o.refine * o.refine);
  mdp_image_t img;
  if (mdp_image_cli_load(path, &cli, &img, err)) {
    fprintf(stderr, "mdpore foam: %s\n", err);
    return 1;
  }
  mdp_image_stats_t st;
  long long dropped = 0;
  int rc = 1;
  char dir[4096] = "";
  if (mdp_image_stats(&img, &st, err) ||
      mdp_image_require_percolation(&img, &st, o.axis, path, err))
    goto out;
  /* non-spanning clusters become solid, so OpenFOAM never sees a closed region with an undetermined
   * pressure */
  if (mdp_image_drop_nonspanning(&img, o.axis, &dropped, err)) goto out;
  long long end_walls = 0;
  if (o.periodic) {
    end_walls = end_slice_mismatch(&img, o.axis);
    if (end_walls && o.smooth_walls) {
      snprintf(err, sizeof err,
               "%s: --drive periodic with --walls smooth needs the same pore voxels on the first "
               "and last slices along %c (they differ at %lld voxels); use --walls staircase or "
               "--drive pressure",
               path, 'x' + o.axis, end_walls);
      goto out;
    }
  }
  if (!mdp_foam_bashrc()) {
    fprintf(stderr,
            "mdpore foam: OpenFOAM not found (no /usr/share/openfoam/etc/bashrc; install the "
            "Debian package openfoam, see scripts/setup.sh, or set MDPORE_OPENFOAM_BASHRC)\n");
    mdp_image_free(&img);
    return EXIT_NO_OPENFOAM;
  }
  const int dim[3] = {img.nx, img.ny, img.nz};
  o.length_voxels = dim[o.axis];
  memcpy(o.box, dim, sizeof o.box);
  if (case_dir) {
    snprintf(dir, sizeof dir, "%s", case_dir);
    if (mkdir(dir, 0755) != 0 && errno != EEXIST) {
      snprintf(err, sizeof err, "--case %s: cannot create: %s", dir, strerror(errno));
      goto out;
    }
    char probe[4200];
    snprintf(probe, sizeof probe, "%s/system", dir);
    if (access(probe, F_OK) == 0) {
      snprintf(err, sizeof err, "--case %s: folder already holds a case; give a new or empty one",
               dir);
      dir[0] = 0;
      goto out;
    }
    keep = 1;
  } else {
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/mdpore-foam-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
      snprintf(err, sizeof err, "cannot create a temporary case folder %s: %s", dir,
               strerror(errno));
      dir[0] = 0;
      goto out;
    }
  }
  mdp_foam_result_t res;
  if (mdp_foam_run(dir, &img, &o, &res, err)) goto out;
  /* Darcy: k = nu q / G with q = int(u_axis dV) / V_box (superficial velocity; nu = 1). */
  const double vbox = (double)img.nx * img.ny * img.nz, area = vbox / dim[o.axis];
  const double q = res.int_u[o.axis] / vbox, k_vox = q / o.gradient;
  const double dx = mdp_image_voxel_size_m(&img);
  char json[4096], kphys[256] = "null", kmd[64] = "null", walls[768] = "\"staircase\"";
  if (o.smooth_walls) /* mesh porosity: the pore volume of the moved mesh over the box */
    snprintf(walls, sizeof walls,
             "\"smooth\", \"mesh_porosity\": %.8f, \"wall_points\": %lld, \"moved_wall_points\": "
             "%lld, \"held_back_wall_points\": %lld, \"max_wall_move\": %.4f, \"mesh_check\": "
             "\"%s\"",
             res.smooth.mesh_volume / vbox, res.smooth.wall_points, res.smooth.moved_points,
             res.smooth.limited_points, res.smooth.max_move, res.smooth.mesh_check);
  if (dx > 0) {
    snprintf(kphys, sizeof kphys, "%.8e", k_vox * dx * dx);
    snprintf(kmd, sizeof kmd, "%.8e", k_vox * dx * dx / 9.869233e-16);
  }
  /* the solver's diagnostics can be undefined (an error estimate from too few samples is NaN):
   * written as null, so the JSON stays valid */
  char tort[32], rp[32], ru[32], fc[32], fe[32];
  snprintf(json, sizeof json,
           "{\"image\": \"%s\", \"axis\": \"%c\", \"dims\": [%d, %d, %d], \"refine\": %d, "
           "\"cells\": %d, \"walls\": %s, \"drive\": \"%s\", \"sides\": \"%s\", \"ranks\": %d, "
           "\"solver\": \"%s\", "
           "\"pseudo_dt\": %.6g, \"restarts\": %d,\n"
           " \"voxel_size\": %.10g, \"unit\": \"%s\", \"porosity\": %.8f, "
           "\"connected_porosity\": %.8f, \"dropped_nonspanning_voxels\": %lld, "
           "\"periodic_end_wall_faces\": %lld,\n"
           " \"permeability_voxel2\": %.10e, \"permeability_m2\": %s, \"permeability_mD\": %s,\n"
           " \"convention\": \"k = mu q L / dp, q = Q / A_total: superficial (Darcy) velocity over "
           "the whole cross-section including solid\",\n"
           " \"model_units\": \"lengths in voxels, nu = 1, kinematic pressure gradient %.6g\",\n"
           " \"flow_rate\": %.10e, \"superficial_velocity\": %.10e, \"mean_pore_velocity\": %.10e, "
           "\"tortuosity\": %s,\n"
           " \"converged\": %s, \"iterations\": %d, \"residual_p\": %s, \"residual_U\": %s, "
           "\"flux_change\": %s, \"flux_error_estimate\": %s, \"tol_residual\": %.3g, "
           "\"tol_flux\": %.3g, \"wall_s\": %.2f, "
           "\"case\": %s%s%s}\n",
           path, 'x' + o.axis, img.nx, img.ny, img.nz, o.refine, res.cells, walls,
           o.periodic       ? "periodic"
           : o.mirror_faces ? "mirror"
                            : "pressure",
           o.side_walls      ? "wall"
           : o.side_periodic ? "periodic"
                             : "symmetry",
           o.np, o.simple ? "simpleFoam" : "pimpleFoam", o.simple ? 0.0 : res.dt, res.restarts,
           img.voxel_size, img.unit, st.porosity, st.connected_porosity[o.axis], dropped, end_walls,
           k_vox, kphys, kmd, o.gradient, q * area, q, q / st.porosity,
           finite_or_null(tort, sizeof tort, "%.8f", res.int_mag_u / res.int_u[o.axis]),
           res.converged ? "true" : "false", res.iterations,
           finite_or_null(rp, sizeof rp, "%.3e", res.res_p),
           finite_or_null(ru, sizeof ru, "%.3e", res.res_u),
           finite_or_null(fc, sizeof fc, "%.3e", res.flux_change),
           finite_or_null(fe, sizeof fe, "%.3e", res.flux_error), o.tol_residual, o.tol_flux,
           res.wall_s, keep ? "\"" : "", keep ? dir : "null", keep ? "\"" : "");
  fputs(json, stdout);
  rc = res.converged ? 0 : EXIT_NOT_CONVERGED;
  if (!res.converged)
    fprintf(stderr,
            "mdpore foam: NOT converged after %d iterations (residual p %.3g, U %.3g, flux "
            "change %.3g); raise --max-iter or loosen the tolerances\n",
            res.iterations, res.res_p, res.res_u, res.flux_change);
  if (output) {
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", output, (long)getpid());
    FILE *f = fopen(tmp, "w");
    if (!f || fputs(json, f) < 0 || fclose(f) != 0 || rename(tmp, output) != 0) {
      fprintf(stderr, "mdpore foam: cannot write %s: %s\n", output, strerror(errno));
      remove(tmp);
      rc = 1;
    }
  }
  err[0] = 0;
out:
  if (rc == 1 && err[0]) fprintf(stderr, "mdpore foam: %s\n", err);
  if (dir[0] && !keep) nftw(dir, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
  mdp_image_free(&img);
  return rc;
}
