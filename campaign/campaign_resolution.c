/* The resolution of an IMAGE campaign (docs/permeability.md, "Resolution"): how many rc a voxel
 * is. mDPD resolves flow down to slits of h = 4 rc and tubes of R = 2 rc (docs/permeability.md,
 * "Measured: slits and tubes"), so the narrowest passage that carries the flow, the critical throat
 * of mercury-intrusion breakthrough (mdp_image_pore_sizes, in the periodic box the runs see), must
 * be at least --min-throat (default 4 rc) across. Without --rc-per-voxel the voxel edge is chosen
 * so (the fewest particles that resolve the throat); a given one below it is refused unless
 * --force. The report also estimates the particles (fluid at the template's density in the pore
 * voxels that carry flow, wall particles in the solid voxels within the wall thickness of the pore,
 * as the wall builder keeps them: meso/populate/image_walls.c) and the time at the measured
 * throughput (bench/RESULTS.md), and places rc in metres in its regime. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign.h"
#include "common/size_check.h"
#include "mdpore_image.h"

#define TEMPLATE_FLUID_DENSITY 6.2     /* the generated template's geometry.fluid_density */
#define TEMPLATE_FLUID_WALL_REACH 1.75 /* its fluid-wall rc + rd: the builder's default thickness */
#define TEMPLATE_STEPS 20000LL         /* its run.steps without --max-steps */
#define MDPD_WATER_RC_M 8.2e-10        /* physics.md section 4: the length without a voxel size */
/* Measured throughput (bench/RESULTS.md): the CPU path, one rank per core, 0.59-0.9 M
 * particle-steps/s per core (2-core EPYC VM to the 16-core Xeon host; the lower end here); the
 * CUDA path on one H200 depends on the run's size: 2.5e8 particle-steps/s for one run of 50k
 * particles, 2.3e9 from 2.1M particles on (the porous case, walls included); between the two a
 * power law through both points. */
#define CPU_STEPS_PER_CORE 0.6e6
#define GPU_SMALL_PARTICLES 5e4
#define GPU_SMALL_STEPS 2.5e8
#define GPU_FULL_PARTICLES 2.1e6
#define GPU_FULL_STEPS 2.3e9

/* One H200's particle-steps per second for one run of n particles (the interpolation above). */
static double gpu_steps_per_second(double n) {
  if (n <= GPU_SMALL_PARTICLES) return GPU_SMALL_STEPS;
  if (n >= GPU_FULL_PARTICLES) return GPU_FULL_STEPS;
  const double slope =
      log(GPU_FULL_STEPS / GPU_SMALL_STEPS) / log(GPU_FULL_PARTICLES / GPU_SMALL_PARTICLES);
  return GPU_SMALL_STEPS * pow(n / GPU_SMALL_PARTICLES, slope);
}
/* Regimes of rc (docs/permeability.md, "Resolution"): up to 10 nm slip and layering are physics
 * and mDPD is the model; from 100 nm mDPD is a Stokes solver and `mdpore foam` the reference. */
#define NANOPORE_RC_M 10e-9
#define CONTINUUM_RC_M 100e-9

/* x rounded up to two significant digits (0.5714 -> 0.58): a chosen voxel edge that reads well
 * and still resolves the throat. */
static double round_up_2(double x) {
  const double unit = pow(10.0, floor(log10(x)) - 1.0);
  return ceil(x / unit - 1e-9) * unit;
}

/* Solid voxels whose centre is within the wall thickness t (voxels) of a pore voxel centre: the
 * distance transform of the solid (the image with its phases swapped), periodic box. */
static long long wall_voxels(const mdp_image_t *img, double t, char *err) {
  mdp_image_t swapped = *img; /* shares the labels; only the map differs */
  for (int v = 0; v < 256; v++)
    swapped.phase_of[v] = img->phase_of[v] == MDP_PHASE_PORE    ? MDP_PHASE_INORGANIC
                          : img->phase_of[v] == MDP_PHASE_UNSET ? MDP_PHASE_UNSET
                                                                : MDP_PHASE_PORE;
  const size_t n = mdp_image_count(img);
  /* 4 bytes a voxel beside the image's 1 */
  char why[320];
  if (mdp_size_check((double)n, MDP_IMAGE_MAX_VOXELS, 5.0,
                     "voxels of the image and its distance transform", why, sizeof why)) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "the wall voxels' distance transform: %s", why);
    return -1;
  }
  uint32_t *d4 = malloc(n * sizeof *d4);
  const int periodic[3] = {1, 1, 1};
  if (!d4) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "out of memory for the wall voxels' distance transform");
    return -1;
  }
  if (mdp_image_pore_distance(&swapped, MDP_EDT_CENTRES, periodic, d4, err)) {
    free(d4);
    return -1;
  }
  const double limit = 4.0 * t * t * (1 + 1e-12);
  long long count = 0;
  for (size_t v = 0; v < n; v++) count += !mdp_image_is_pore(img, v) && (double)d4[v] <= limit;
  free(d4);
  return count;
}

static const char *regime_of(double rc_m) {
  return rc_m <= NANOPORE_RC_M ? "nanopore" : rc_m >= CONTINUUM_RC_M ? "continuum" : "intermediate";
}

static void print_duration(double seconds) {
  if (seconds < 3600)
    fprintf(stderr, "%.0f min", ceil(seconds / 60));
  else if (seconds < 86400 * 3)
    fprintf(stderr, "%.1f h", seconds / 3600);
  else
    fprintf(stderr, "%.1f days", seconds / 86400);
}

/* The particles of the largest run at voxel edge a (rc) and the report's lines about them. */
static int report_cost(const camp_opts *o, const mdp_image_t *img, const mdp_image_stats_t *st,
                       double a, campaign *c) {
  char err[MDP_IMAGE_ERR_LEN];
  /* the builder's default thickness: rc + rd, or one voxel edge where that is coarser */
  const double thickness = a > TEMPLATE_FLUID_WALL_REACH ? a : TEMPLATE_FLUID_WALL_REACH;
  const long long walls = wall_voxels(img, thickness / a, err);
  if (walls < 0) {
    fprintf(stderr, "mdpore permeability: %s: %s\n", o->input, err);
    return -1;
  }
  const int n[3] = {img->nx, img->ny, img->nz};
  long long fluid = 0, mirror_factor = 1;
  for (int i = 0; i < o->n_axes; i++) {
    const int ax = o->axes[i];
    long long f = st->connected_voxels[ax], m = 1; /* the image's copies in the mirrored box */
    for (int d = 0; d < 3; d++) m *= camp_mirrored_along(o, ax, d) ? 2 : 1;
    if (o->drive == CAMP_DRIVE_PRESSURE) /* the open reservoir along the axis */
      f += lround(o->reservoir / a) * (long long)n[(ax + 1) % 3] * n[(ax + 2) % 3];
    if (f * m > fluid) fluid = f * m;
    if (m > mirror_factor) mirror_factor = m;
  }
  const double v3 = a * a * a;
  const double fluid_particles = TEMPLATE_FLUID_DENSITY * (double)fluid * v3;
  const double wall_particles = o->wall_density * (double)(walls * mirror_factor) * v3;
  c->particles_estimate = fluid_particles + wall_particles;
  const int runs = o->n_axes * o->n_grads;
  const long long steps = o->max_steps ? o->max_steps : TEMPLATE_STEPS;
  const double work = c->particles_estimate * (double)steps * runs;
  fprintf(stderr,
          "  box %.4g x %.4g x %.4g rc; about %.3g particles per run (fluid %.3g at %g per rc^3 "
          "in %lld pore voxels that carry flow, walls %.3g at %g per rc^3 in %lld solid voxels "
          "within %g rc of the pore; x%lld for the mirrored copies)\n",
          n[0] * a, n[1] * a, n[2] * a, c->particles_estimate, fluid_particles,
          TEMPLATE_FLUID_DENSITY, fluid, wall_particles, o->wall_density, walls, thickness,
          mirror_factor);
  fprintf(stderr, "  time at the step budget (%d runs x %lld steps, %.3g particle-steps): CPU ",
          runs, steps, work);
  print_duration(work / (CPU_STEPS_PER_CORE * o->np));
  fprintf(stderr, " on %d core%s (%.2g per core, bench/RESULTS.md CPU path); GPU ", o->np,
          o->np > 1 ? "s" : "", CPU_STEPS_PER_CORE);
  const double gpu_rate = gpu_steps_per_second(c->particles_estimate);
  print_duration(work / gpu_rate);
  fprintf(stderr, " on one H200 (%.2g/s); runs that meet the target error stop earlier\n",
          gpu_rate);
  return 0;
}

/* rc in metres and its regime. */
static void report_scale(const camp_opts *o, const mdp_image_t *img, double a, campaign *c) {
  const double voxel_m = o->voxel_size_m > 0 ? o->voxel_size_m : mdp_image_voxel_size_m(img);
  const double rc_m = voxel_m > 0 ? voxel_m / a : MDPD_WATER_RC_M;
  snprintf(c->regime, sizeof c->regime, "%s", regime_of(rc_m));
  if (voxel_m > 0)
    fprintf(stderr, "  scale: rc = voxel %.4g m / %.4g = %.4g m", voxel_m, a, rc_m);
  else
    fprintf(stderr,
            "  scale: no voxel size: rc = %.3g m, the mDPD water mapping (a voxel is then "
            "%.3g m)",
            rc_m, a * rc_m);
  if (!strcmp(c->regime, "nanopore"))
    fprintf(stderr, ": nanopore regime (rc <= 10 nm): slip and layering at the walls are physics "
                    "and mDPD is the model\n");
  else if (!strcmp(c->regime, "continuum"))
    fprintf(stderr, ": continuum regime (rc >= 100 nm): mDPD is a Stokes solver here, and `mdpore "
                    "foam` on the same image is the reference (mDPD's wall slip and layering are "
                    "model artefacts at this scale)\n");
  else
    fprintf(stderr, ": between the nanopore (rc <= 10 nm) and continuum (rc >= 100 nm) regimes: "
                    "the wall slip mDPD gives is of the order a real one may have; compare with "
                    "`mdpore foam`\n");
}

int camp_resolution(camp_opts *o, campaign *c) {
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_read_opts_t ro;
  mdp_image_t img;
  mdp_image_read_opts_init(&ro);
  for (int d = 0; d < 3; d++) c->throat_voxels[d] = -1;
  c->min_throat = o->min_throat;
  c->particles_estimate = NAN;
  c->rc_per_voxel_source[0] = c->resolution_warning[0] = c->regime[0] = 0;
  if (mdp_image_read(o->input, &ro, &img, err)) {
    fprintf(stderr, "mdpore permeability: %s: %s\n", o->input, err);
    return -1;
  }
  mdp_image_stats_t st;
  mdp_image_pore_sizes_t ps;
  /* The throat as the runs see it: a ball may pass a periodic seam, not a mirrored face (there the
   * path continues into its own reflection: the same as an open face). A flow axis keeps its
   * treatment, the other axes follow --sides. */
  camp_resolve_boundaries(o, c, &img);
  int periodic[3];
  for (int d = 0; d < 3; d++)
    periodic[d] = o->boundary_of_axis[d] ? o->boundary_of_axis[d] == CAMP_BOUNDARY_PERIODIC
                                         : !o->sides_mirror;
  if (mdp_image_stats(&img, &st, err) || mdp_image_pore_sizes(&img, periodic, &ps, err)) {
    fprintf(stderr, "mdpore permeability: %s: %s\n", o->input, err);
    mdp_image_free(&img);
    return -1;
  }
  int throat = 0, axis = -1; /* the narrowest critical throat over the flow axes that percolate */
  for (int d = 0; d < 3; d++) c->throat_voxels[d] = ps.throat[d];
  for (int i = 0; i < o->n_axes; i++) {
    const int ax = o->axes[i];
    if (ps.throat[ax] > 0 && (axis < 0 || ps.throat[ax] < throat))
      throat = ps.throat[ax], axis = ax;
  }
  int rc = 0;
  if (axis < 0) { /* nothing percolates along the flow axes: planning says so */
    snprintf(c->rc_per_voxel_source, sizeof c->rc_per_voxel_source, "%s",
             o->rc_per_voxel_given ? "--rc-per-voxel" : "default 0.5 (no flow axis percolates)");
    goto done;
  }
  const double wanted = o->min_throat / throat; /* the voxel edge that makes it min_throat wide */
  fprintf(stderr,
          "mdpore permeability: resolution of %s:\n  critical throat (mercury-intrusion "
          "breakthrough diameter through the runs' faces: periodic seams wrap, mirrored ones do "
          "not), voxels:",
          o->input);
  for (int i = 0; i < o->n_axes; i++)
    fprintf(stderr, " %c %d", 'x' + o->axes[i], ps.throat[o->axes[i]]);
  fprintf(stderr, "; the narrowest along %c\n", 'x' + axis);
  const double needed = round_up_2(wanted);
  char why[512] = "";
  if (!o->rc_per_voxel_given) {
    o->rc_per_voxel = needed;
    snprintf(c->rc_per_voxel_source, sizeof c->rc_per_voxel_source,
             "chosen: the critical throat along %c, %d voxel%s, at least --min-throat %g rc wide "
             "(%g / %d = %.4g, rounded up)",
             'x' + axis, throat, throat > 1 ? "s" : "", o->min_throat, o->min_throat, throat,
             wanted);
  } else {
    snprintf(c->rc_per_voxel_source, sizeof c->rc_per_voxel_source, "--rc-per-voxel");
  }
  if (throat * o->rc_per_voxel < o->min_throat * (1 - 1e-12))
    snprintf(why, sizeof why,
             "the critical throat along %c is %d voxel%s = %.3g rc at %g rc per voxel, below "
             "--min-throat %g rc (mDPD flow is measured down to 4 rc slits and 2 rc tubes; "
             "narrower throats cavitate or block)",
             'x' + axis, throat, throat > 1 ? "s" : "", throat * o->rc_per_voxel, o->rc_per_voxel,
             o->min_throat);
  if (why[0] && !o->force) {
    fprintf(stderr,
            "mdpore permeability: %s: %s. Give --rc-per-voxel %.3g or more, or leave it out (the "
            "default resolves the throat), or lower --min-throat; --force runs anyway\n",
            o->input, why, needed);
    rc = -1;
    goto done;
  }
  if (why[0]) {
    snprintf(c->resolution_warning, sizeof c->resolution_warning, "--force: %.400s", why);
    fprintf(stderr, "mdpore permeability: warning: %s\n", c->resolution_warning);
  }
  fprintf(stderr, "  rc per voxel %.4g (%s): the throat is %.3g rc\n", o->rc_per_voxel,
          c->rc_per_voxel_source, throat * o->rc_per_voxel);
  rc = report_cost(o, &img, &st, o->rc_per_voxel, c);
  if (!rc) report_scale(o, &img, o->rc_per_voxel, c);
done:
  mdp_image_free(&img);
  return rc;
}
