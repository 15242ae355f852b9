/* The measured driving gradient of a pressure-driven run (effect inlet_force with `sample`;
 * docs/permeability.md "Pressure-driven runs"). At every flux sample (the per-particle virial of
 * that step requested):
 *   P_aa(slab) = sum_{i in slab} (m v_a^2 + W_i,aa) / V_slab     (a = the flow axis)
 * with W_i the engine's per-particle virial (1/2 sum_j r_ij,a F_ij,a, as analysis/profile.c and
 * the surface tension use), in two probe slabs of the open reservoir just outside the sample's
 * faces, [lo - gap - w, lo - gap) upstream and [hi + gap, hi + gap + w) downstream, and in bins of
 * about 0.5 rc along the whole axis (the profile). Per sample:
 *   dp = P_in - P_out,  G = dp / L_sample  (L_sample = hi - lo),
 *   F_in = sum_{i in forced slab} g_s,a          (the total inlet force).
 * At the end, from the flux's steady-state start (MSER-5 of q, analysis/steady_state.c): the means
 * and block errors (block_average_plateau) of P_in, P_out, dp and F_in, and the momentum balance
 * F_in / A_total against dp: at steady state the fluid between the two probe planes holds the inlet
 * force against the pressure step alone (the reservoir is open fluid, periodic across), so the two
 * agree up to the reservoir's own drag and the probes' finite width. */
#ifndef MESO_ANALYSIS_PRESSURE_DROP_H
#define MESO_ANALYSIS_PRESSURE_DROP_H

#include "analysis/block_average.h"
#include "engine/sim.h"
#include "physics/inlet_force.h"

/* Profile bins are about this wide (rc). */
#define PRESSURE_PROFILE_BIN 0.5

typedef struct {
  int on, axis, nbins;
  double box_lo, box_len, area;        /* the box along the axis; A_total = V / L */
  double sample_lo, sample_hi, length; /* sample faces, L_sample */
  double in_lo, out_lo, width;         /* probe slabs [in_lo, in_lo + w), [out_lo, out_lo + w) */
  double v_probe, v_bin;               /* probe and bin volumes */
  inlet_force_params_t inlet;          /* the effect's slab and forces (box wrap set) */
  long first_sample;                   /* flux series index of this object's first sample */
  char profile_path[SCENE_PATH_LEN];   /* pressure_profile.csv beside the flux file */
  /* rank 0: the series, one entry per sample, and the profile rows (nbins per sample) */
  series_t p_in, p_out, dp, force;
  double *rows;
  long n_rows, cap_rows;
  double *local; /* nbins + 4 sums of this rank */
} pressure_drop_t;

typedef struct {
  long samples_used;
  block_average_t p_in, p_out, dp, force;
  double G, G_err;       /* dp / L_sample */
  double force_per_area; /* F_in / A_total */
  double force_per_area_err;
  double balance; /* dp / (F_in / A_total) */
} pressure_drop_result_t;

/* Set up from the scene (on = 0 when the scene has no inlet_force with a sample); first_sample:
 * the flux series' length now (earlier rows of a restart). 0, or -1 (out of memory). */
int pressure_drop_init(pressure_drop_t *pd, const scene_t *scene, long first_sample, int rank);
void pressure_drop_free(pressure_drop_t *pd);
/* Collective, at a flux sample step whose per-particle virial was computed: one sample. Returns
 * the sample's G = dp / L_sample on rank 0 (NaN elsewhere). */
double pressure_drop_sample(pressure_drop_t *pd, sim_t *sim, int rank);
/* Rank 0: the averages from flux series index `flux_start` (the steady-state start) on. */
void pressure_drop_analyse(const pressure_drop_t *pd, long flux_start, pressure_drop_result_t *r);
/* Rank 0: the time-averaged P_aa profile from `flux_start` on, with block errors (CSV, atomic).
 * 0 or -1. */
int pressure_drop_write_profile(const pressure_drop_t *pd, long flux_start, const char *path);

#endif
