/* What a flood measures (scene `flood:`, docs/twophase.md "Flooding"): at every census, per bin
 * across the sample the particles of the invading and the defending liquid, their velocity sums
 * along the axis in the sample, and what follows from them:
 *   S_i = N_i / (N_inv + N_def)                       saturation of liquid i in the sample
 *   q_i = sum_{j in i, sample} v_j / (n V_sample)     superficial (Darcy) velocity of liquid i,
 *                                                    V_sample = A_total L_sample (solid included)
 *   RF  = 1 - N_def(t) / N_def(start)                 recovery factor of the defending liquid
 *   PVI = int_start^t u(t') dt' / L_sample            pore volumes injected; u = the mean velocity
 *                                                    of all fluid in the sample (Q / V_pore = u / L)
 *   front: the downstream edge of the farthest bin whose invading saturation is >= 1/2
 *   breakthrough: the first census after the start at which the invading saturation of the
 *   sample's last bin reaches flood.breakthrough.
 * The census reads the particles on the host (sim_particles: the CUDA backend copies them back). */
#ifndef MESO_ANALYSIS_FLOOD_H
#define MESO_ANALYSIS_FLOOD_H

#include "engine/sim.h"

typedef struct {
  int on;
  int axis, nbins, inv, def;
  double lo, hi, length, bin_w; /* the sample along the axis */
  double area, volume;          /* A_total (box cross-section) and A_total L_sample */
  double n_fluid;               /* the fluid number density n of q_i */
  const char *density_source;   /* where n came from */
  /* the latest census (global, the same on every rank) */
  long step;
  double time;
  double *bin_inv, *bin_def; /* [nbins] particles per bin */
  double n_inv, n_def;       /* in the sample */
  double v_inv, v_def;       /* sum of v_axis in the sample */
  double box_inv, box_def;   /* in the whole box */
  /* what follows (flood_update) */
  double s_inv, q_inv, q_def, recovery, pvi, front;
  int started;           /* a census at or after flood.start was taken */
  double n_def_start;    /* defending particles in the sample at the start */
  double t_prev, u_prev; /* the PVI integral's previous point */
  int broke_through;
  long bt_step;
  double bt_time, bt_recovery, bt_pvi, bt_s_inv;
  double q_sum, q_n; /* sum and count of q_inv + q_def after the start (Ca) */
} flood_t;

/* Collective set-up from the scene (off when the scene has no flood block): the bins and the
 * density n (flood.density, else geometry.fluid_density, else the mobile particles over the fill
 * regions' volume). 0, or -1 after a message on rank 0. */
int flood_init(flood_t *f, const scene_t *s, sim_t *sim);
void flood_free(flood_t *f);
/* Collective census at the current step (host particles). 0 or -1 (memory; message printed). */
int flood_census(flood_t *f, sim_t *sim);
/* The derived quantities after a census at `step` (the same on every rank). */
void flood_update(flood_t *f, const scene_t *s, long step);
/* Invading saturation of bin b (NaN when it holds no fluid). */
double flood_bin_saturation(const flood_t *f, int b);

#endif
