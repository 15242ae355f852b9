/* mdpore couple: the continuum <-> pore-scale loop (docs/coupling.md).
 *
 * A segmented image is split into a grid of blocks (or a list of block images is given). Per block, a
 * permeability campaign along the loop's axis (`mdpore permeability`, cached and resumable) gives a
 * flow table and fitted laws; the laws go into the continuum solve (upscale/darcy) over the block
 * grid with the field's boundary pressures; each block's mean gradient in that solution is compared
 * with the range its law was calibrated on, and blocks outside it get new pore-scale runs at that
 * gradient; refit, solve again, until the block fluxes of two passes agree within their statistical
 * error or a maximum number of passes. Everything is in the reduced units of the pore-scale runs;
 * the SI mapping of the campaigns (rc in metres) converts k for the report.
 *
 * Files: couple_config.c (the YAML config), couple_blocks.c (block images), couple_campaigns.c (the
 * per-block campaigns through `mdpore permeability`), couple_law.c (a block's law with its errors
 * from the fit JSON), couple_solve.c (continuum solve, block gradients and fluxes, Monte-Carlo
 * errors), couple_output.c (tables, field, JSON, PNG), cmd_couple.c (the loop). */
#ifndef MDPORE_COUPLING_COUPLE_H
#define MDPORE_COUPLING_COUPLE_H

#include <stddef.h>
#include <stdint.h>

#include "law/flow_law.h"

#define COUPLE_PATH 4096
#define COUPLE_MAX_GRADIENTS 64 /* = CAMP_MAX_GRADIENTS: runs per block campaign */
#define COUPLE_MAX_BLOCKS 4096

enum { COUPLE_LAUNCH_MPIEXEC = 0, COUPLE_LAUNCH_SLURM };
enum { COUPLE_LAW_DARCY = 0, COUPLE_LAW_CHOSEN };
/* campaign.axes: which axes each block's permeability is measured along. FLOW: the loop's axis only,
 * one scalar law per block (the default). ALL: every axis along which the block grid has more than
 * one block (the only axes whose faces between blocks carry flow), a diagonal law per block. AUTO:
 * the loop's axis, then a cross axis of a block wherever the continuum's flow through the block
 * along it exceeds COUPLE_CROSS_FLOW_FRACTION of its flow along the loop's axis. */
enum { COUPLE_AXES_FLOW = 0, COUPLE_AXES_ALL, COUPLE_AXES_AUTO };
#define COUPLE_CROSS_FLOW_FRACTION 0.05
/* The state of a block's campaign along a cross axis. */
enum { CROSS_NONE = 0, CROSS_WANTED, CROSS_NO_SPAN, CROSS_MEASURED };

typedef struct {
  char path[COUPLE_PATH];    /* the config file */
  char workdir[COUPLE_PATH]; /* absolute */
  /* geometry: one image split into blocks[3], or one image per block */
  char image[COUPLE_PATH];          /* "" when block images are listed */
  char image_labels[256];           /* label map passed to the image reader ("" = the file's own) */
  char image_voxel_size[64];        /* e.g. "10 nm" ("" = the file's own) */
  int blocks[3];                    /* block grid */
  int n_block_images;               /* listed block images (0 = split `image`) */
  char (*block_image)[COUPLE_PATH]; /* [n_blocks], x fastest */
  int axis;                         /* flow axis 0..2 */
  /* drive: the mean gradient G = -dp/dx over the sample along the axis (reduced kT/rc^4) */
  int gradient_auto;
  double gradient; /* reduced, when not auto */
  int gradient_si; /* 1: given in Pa/m (converted with the campaigns' unit mapping) */
  double gradient_si_value;
  int law_choice; /* COUPLE_LAW_DARCY (linear response, default) or COUPLE_LAW_CHOSEN */
  /* campaign options (passed to mdpore permeability) */
  double rc_per_voxel;
  int np;
  int jobs; /* runs of a campaign at once (--jobs; 0: auto, default 1) */
  int n_gradients;
  double u_lo, u_hi;
  double target_error;
  long long max_steps;
  int target_error_given, max_steps_given; /* given in the config (they win over accuracy) */
  char accuracy[16];                       /* --accuracy preset ("" = none) */
  long long seed;
  char voxel_size[64]; /* --voxel-size in metres as text ("" = default) */
  double viscosity;    /* 0 = the campaign's default */
  char mpiexec[512];   /* "" = the campaign's default */
  int drive_pressure;  /* 1: --drive pressure (inlet force in a reservoir, measured G) */
  char boundary[16];   /* --boundary of every block campaign ("" = the campaign's default, auto) */
  char sides[16];      /* --sides ("" = the campaign's default, periodic) */
  int axes;            /* COUPLE_AXES_* (campaign.axes) */
  /* loop */
  int max_passes;
  double tolerance_sigma;     /* fluxes agree when |dq| <= tol * combined standard error */
  double resolvable_fraction; /* new runs down to this fraction of a block's smallest gradient */
  int error_samples;          /* Monte-Carlo samples of the law parameters */
  int launcher;
  char slurm_header[1024]; /* extra #SBATCH lines for the job array ("" = none) */
  char self_exe[COUPLE_PATH];
} couple_config;

/* A block's law as fitted, with its parameter errors (covariance of the law's parameters, in the
 * order k|K, then G0|beta|n) and the gradients it was calibrated on. */
typedef struct {
  flow_law law;         /* the law used in the continuum solve */
  flow_law chosen;      /* the fit's chosen law (reported, and used with law: chosen) */
  char chosen_name[32]; /* its name */
  int n_par;
  double par[3], cov[3][3];
  double k_darcy, k_darcy_err; /* the Darcy fit */
  double g_min, g_max;         /* calibrated range of G (smallest and largest |G| of the table) */
  int n_rows;
  double mu, density; /* fluid of the fit */
  int percolates;     /* 0: no flow along the axis, the block is (nearly) impermeable */
  double length_unit_m;
  double G_Pa_per_m; /* the campaigns' SI mapping of a reduced gradient */
} couple_law;

typedef struct {
  int index[3];
  char image[COUPLE_PATH];   /* the block's image file */
  char workdir[COUPLE_PATH]; /* its campaign folder */
  double porosity;
  int percolates; /* the pore space spans the loop's axis */
  int spans[3];   /* the pore space spans axis a */
  /* along each cross axis a (a != the loop's axis): CROSS_* and, when measured, the law of the
   * block's campaign along a (WORKDIR/blocks/bI_J_K/campaign_<a>; auto ladder, no feedback runs) */
  int cross_state[3];
  int cross_run[3]; /* its campaign ran (or was collected) in this loop */
  couple_law cross[3];
  int n_extra; /* gradients added by the loop */
  int n_extra_run; /* n_extra when its campaign last ran (-1: not yet): unchanged blocks are not rerun */
  double extra_g[COUPLE_MAX_GRADIENTS]; /* body forces per particle added by the loop */
  double ladder_g[COUPLE_MAX_GRADIENTS];
  int n_ladder;   /* every g of the block's campaign (auto ladder + extra) */
  double density; /* fluid number density n of the block's runs (G = n g) */
  couple_law law;
  int pending; /* runs not finished (slurm launcher) */
  /* the boundary treatment its campaign resolved (campaign.txt), per axis: CAMP_BOUNDARY_* (0 = no
   * campaign yet), the image's seam continuity and whether the lateral faces were mirrored */
  int boundary[3];
  double seam_continuity[3];
  int sides_mirror;
} couple_block;

/* One continuum solve with its derived block quantities. */
typedef struct {
  int converged;
  double *pressure; /* per block */
  double *grad;     /* per block: mean gradient along the axis */
  double *flux;     /* per block: mean superficial velocity along the axis (mean of its faces) */
  double *flux_err; /* Monte-Carlo standard error of flux */
  double *cross;    /* per block and axis [3 b + a]: mean |superficial velocity| through the block's
                       two faces normal to a, over |flux| (0 along the loop's axis) */
  double keff, keff_err; /* effective permeability along the axis and its error */
  double q_total;        /* mean superficial velocity through the sample */
  double dp;             /* pressure drop over the sample */
  int samples_ok;        /* Monte-Carlo samples that solved */
  double seconds;
} couple_solution;

/* couple_config.c */
int couple_config_read(const char *path, couple_config *c);
void couple_config_free(couple_config *c);

/* couple_blocks.c: block images under WORKDIR/blocks (written once, reused when present and equal).
 * Fills blocks[n] (index, image, workdir, porosity, percolates). 0 or -1 with a message. */
int couple_make_blocks(const couple_config *c, couple_block *blocks, double block_size[3]);

/* couple_campaigns.c: run (or reuse) the campaign of every block with its current gradients, and
 * the cross-axis campaigns wanted (cross_state CROSS_WANTED, not run yet); with the slurm launcher,
 * write the job array of the unfinished runs instead and set *pending. Then collect (tables, fits)
 * the campaigns whose runs are all finished. 0 or -1. */
int couple_run_campaigns(const couple_config *c, couple_block *blocks, int n, int pass,
                         int *pending);
/* The gradients (body forces per particle) of a block's campaign manifest. */
int couple_read_ladder(couple_block *b);

/* The folder of block b's campaign along axis a (its workdir along the loop's axis). */
void couple_campaign_dir(const couple_config *c, const couple_block *b, int a, char *out,
                         size_t len);

/* couple_law.c: reads a block's fit JSON (WORKDIR/fit_<axis>.json). 0 or -1 with a message. */
int couple_read_law(const couple_config *c, couple_block *b);
/* The same for the block's campaign along cross axis a (into b->cross[a], CROSS_MEASURED). */
int couple_read_cross_law(const couple_config *c, couple_block *b, int a);
/* A law with parameters drawn from the fit's covariance (normal deviates z[3]). */
void couple_law_sample(const couple_law *L, const double z[3], flow_law *out);

/* couple_solve.c: the continuum solve over the block grid (reduced units), the block gradients and
 * fluxes along the axis, and errors by solving again with laws drawn from their fits. 0 or -1. */
int couple_solve(const couple_config *c, const couple_block *blocks, const double block_size[3],
                 double gradient, couple_solution *s);
void couple_solution_free(couple_solution *s);

/* couple_output.c */
/* "block (i,j,k) axis x: mirror (seam continuity 0.13; auto: periodic at >= 0.80), sides periodic" */
void couple_boundary_text(const couple_config *c, const couple_block *b, char *out, size_t len);
/* The same for the campaign along axis a. */
void couple_boundary_text_axis(const couple_config *c, const couple_block *b, int a, char *out,
                               size_t len);
/* The Darcy k of block b along axis a that the continuum uses (the flow axis's along an axis not
 * measured), its error, and where it comes from ("campaign", "flow axis", "impermeable"). */
const char *couple_k_along(const couple_config *c, const couple_block *b, int a, double *k,
                           double *err);
int couple_write_pass_table(const couple_config *c, const couple_block *blocks, int n, int pass,
                            const couple_solution *s, const int *new_runs);
int couple_write_field(const couple_config *c, const couple_block *blocks, int pass,
                       const double block_size[3], const couple_solution *s);
typedef struct {
  int passes, converged, pending;
  char stop_reason[512];
  double keff[16], keff_err[16], max_dq_sigma[16]; /* per pass */
  int new_runs[16];
  int new_cross[16]; /* cross-axis campaigns asked for after each pass (campaign.axes: auto) */
  int left_out[16];  /* blocks outside their range whose run there the fit left out, per pass */
} couple_history;
int couple_write_summary(const couple_config *c, const couple_block *blocks, int n,
                         const double block_size[3], const couple_solution *s,
                         const couple_history *h);
void couple_plot(const couple_config *c);

#endif
