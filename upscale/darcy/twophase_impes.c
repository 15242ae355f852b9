/* IMPES time loop of the two-phase Darcy solve (see twophase_impes.h). */
#include "twophase_impes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "darcy_fv.h"
#include "darcy_solve.h"
#include "twophase_output.h"

/* Block permeabilities scaled by the total mobility: with the pressure equation's viscosity mu_w,
 * the face conductance k_eff / mu_w = k lambda_t (harmonic mean of the two half-blocks). */
static void scale_mobility(darcy_config *c, const double *k_abs, const double *sw) {
  darcy_problem *p = &c->problem;
  const relperm *kr = &c->twophase.kr;
  for (long b = 0; b < darcy_nblocks(p); b++)
    p->laws[b].k = k_abs[b] * kr->mu_w * relperm_total_mobility(kr, sw[b]);
  darcy_problem_linearise(p, c->g_lin_fraction);
}

/* Volumetric flux out of block (i,j,k) through `face` (darcy_fv.h). */
static double area_flux(const darcy_problem *p, int i, int j, int k, int face, double p_c,
                        double p_nb) {
  double area;
  face_flux_result r = darcy_face(p, i, j, k, face, p_c, p_nb, &area);
  return area * r.q;
}

typedef struct {
  double dt_max;             /* CFL limit of this step */
  double inflow;             /* total rate in through the inlet face and positive sources */
  double water_out, oil_out; /* rates out through faces and sinks (net, outward) */
} step_rates;

/* Rank 0: with total face fluxes from `pressure` (times flux_scale), the water saturation change
 * rate dsw (per block, 1/time) and the step's rates. Upstream weighting: the water flux through a
 * face is f_w(S of the block the flow comes from) F; fluid entering through the inlet face has
 * s_inj, through another fixed face s_init. */
static void saturation_rates(const darcy_config *c, const double *pressure, double flux_scale,
                             const double *sw, double max_dfw, double *dsw, step_rates *r) {
  const darcy_problem *p = &c->problem;
  const twophase_config *tp = &c->twophase;
  static const int step[6][3] = {{-1, 0, 0}, {1, 0, 0},  {0, -1, 0},
                                 {0, 1, 0},  {0, 0, -1}, {0, 0, 1}};
  const double volume = p->h[0] * p->h[1] * p->h[2], pore = tp->porosity * volume;
  const double fw_inj = relperm_fw(&tp->kr, tp->s_inj), fw_init = relperm_fw(&tp->kr, tp->s_init);
  memset(r, 0, sizeof *r);
  r->dt_max = INFINITY;
  for (int k = 0; k < p->n[2]; k++)
    for (int j = 0; j < p->n[1]; j++)
      for (int i = 0; i < p->n[0]; i++) {
        const long b = darcy_index(p, i, j, k);
        const int cell[3] = {i, j, k};
        const double fw_c = relperm_fw(&tp->kr, sw[b]);
        double water_net_out = 0.0, total_out = 0.0;
        for (int face = 0; face < 2 * p->dim; face++) {
          const int inside = darcy_has_neighbour(p, cell, face);
          const long nb =
              inside ? darcy_index(p, i + step[face][0], j + step[face][1], k + step[face][2]) : -1;
          if (!inside && !p->fixed[face]) continue;
          const double F =
              flux_scale * area_flux(p, i, j, k, face, pressure[b], inside ? pressure[nb] : 0.0);
          double fw_up = fw_c;
          if (F < 0.0)
            fw_up = inside                   ? relperm_fw(&tp->kr, sw[nb])
                    : face == tp->inlet_face ? fw_inj
                                             : fw_init;
          water_net_out += fw_up * F;
          total_out += fmax(F, 0.0);
          if (!inside) { /* a boundary face: count what crosses it */
            if (F > 0.0) {
              r->water_out += fw_up * F;
              r->oil_out += (1.0 - fw_up) * F;
            } else if (face == tp->inlet_face) {
              r->inflow -= F;
            } else { /* backflow through an outlet: negative production */
              r->water_out += fw_up * F;
              r->oil_out += (1.0 - fw_up) * F;
            }
          }
        }
        const double src = p->source ? p->source[b] : 0.0;
        if (src > 0.0) {
          water_net_out -= fw_inj * src;
          r->inflow += src;
        } else if (src < 0.0) {
          water_net_out -= fw_c * src;
          total_out -= src;
          r->water_out -= fw_c * src;
          r->oil_out -= (1.0 - fw_c) * src;
        }
        dsw[b] = -water_net_out / pore;
        /* explicit upwind stability: the block must not send out more than its pore volume times
         * 1/max f_w' in one step */
        if (total_out > 0.0 && max_dfw > 0.0)
          r->dt_max = fmin(r->dt_max, tp->cfl * pore / (max_dfw * total_out));
      }
}

/* Pressure solve of one step: mobility-scaled permeabilities; with a set injection rate the
 * solution for the configured pressures is scaled (linear problem, every other fixed face at one
 * pressure p_out) so that the inlet takes that rate: every flux is multiplied by *flux_scale and
 * the inlet pressure is *p_inlet. */
static int pressure_step(MPI_Comm comm, darcy_config *c, const double *k_abs, const double *sw,
                         double **pressure, double *flux_scale, double *p_inlet, int *its) {
  darcy_problem *p = &c->problem;
  const twophase_config *tp = &c->twophase;
  darcy_stats st;
  scale_mobility(c, k_abs, sw);
  if (darcy_solve(comm, p, pressure, &st)) return 1;
  int rank;
  MPI_Comm_rank(comm, &rank);
  *its += st.linear_its;
  if (rank != 0) return 0;
  if (!st.converged) {
    fprintf(stderr, "mdpore darcy: a two-phase pressure solve did not converge (%s)\n", st.reason);
    return 1;
  }
  const int f = tp->inlet_face, axis = f / 2;
  *p_inlet = p->bc_p[f][0];
  *flux_scale = 1.0;
  if (!(tp->rate > 0.0)) return 0;
  double q_in = 0.0, p_out = 0.0;
  for (int g = 0; g < 2 * p->dim; g++)
    if (p->fixed[g] && g != f) p_out = p->bc_p[g][0];
  for (int k = 0; k < p->n[2]; k++)
    for (int j = 0; j < p->n[1]; j++)
      for (int i = 0; i < p->n[0]; i++) {
        int cell[3] = {i, j, k};
        if (cell[axis] != (f % 2 ? p->n[axis] - 1 : 0)) continue;
        q_in -= area_flux(p, i, j, k, f, (*pressure)[darcy_index(p, i, j, k)], 0.0);
      }
  if (!(q_in > 0.0)) {
    fprintf(stderr,
            "mdpore darcy: no inflow through the inlet face for the configured boundary "
            "pressures (got %g): the inlet pressure must exceed the outlet's to set a rate\n",
            q_in);
    return 1;
  }
  *flux_scale = tp->rate / q_in;
  *p_inlet = p_out + (*p_inlet - p_out) * *flux_scale;
  return 0;
}

int twophase_run(MPI_Comm comm, darcy_config *c, twophase_summary *sum) {
  darcy_problem *p = &c->problem;
  const twophase_config *tp = &c->twophase;
  const long nb = darcy_nblocks(p);
  int rank, rc = 0;
  MPI_Comm_rank(comm, &rank);
  memset(sum, 0, sizeof *sum);
  sum->breakthrough_pvi = -1.0;
  double *k_abs = malloc(nb * sizeof(double)), *sw = malloc(nb * sizeof(double));
  double *dsw = malloc(nb * sizeof(double));
  int oom = !k_abs || !sw || !dsw;
  MPI_Allreduce(MPI_IN_PLACE, &oom, 1, MPI_INT, MPI_MAX, comm);
  if (oom) {
    if (rank == 0)
      fprintf(stderr, "mdpore darcy: twophase: out of memory for the saturations of %ld blocks\n",
              nb);
    free(k_abs), free(sw), free(dsw);
    return 1;
  }
  for (long b = 0; b < nb; b++) k_abs[b] = p->laws[b].k, sw[b] = tp->s_init;
  const double pore_volume = tp->porosity * p->h[0] * p->h[1] * p->h[2] * nb;
  const double oil0 = pore_volume * (1.0 - tp->s_init);
  double s_lo = fmin(tp->s_init, tp->s_inj), s_hi = fmax(tp->s_init, tp->s_inj);
  sum->max_dfw = relperm_max_dfw(&tp->kr, s_lo, s_hi);
  const double fw_init = relperm_fw(&tp->kr, tp->s_init);
  twophase_writer w = {0};
  if (rank == 0) rc = twophase_output_open(&w, c) ? 1 : 0;
  MPI_Bcast(&rc, 1, MPI_INT, 0, comm);
  double t = 0.0, injected = 0.0, oil_produced = 0.0;
  int next_out = 0;
  if (rank == 0) twophase_output_profile(&w, p, 0.0, 0.0, sw);
  while (!rc && t < tp->t_end * (1.0 - 1e-12)) {
    double *pressure = NULL, flux_scale = 1.0, p_inlet = 0.0, state[2] = {0, 0};
    rc = pressure_step(comm, c, k_abs, sw, &pressure, &flux_scale, &p_inlet, &sum->linear_its);
    if (rank == 0 && !rc) {
      step_rates r;
      saturation_rates(c, pressure, flux_scale, sw, sum->max_dfw, dsw, &r);
      /* the work the end time asks for, from the first CFL step (the velocities change little
       * in an incompressible displacement at a set drive): refused before it runs away */
      if (sum->steps == 0 && !(tp->t_end / r.dt_max <= TWOPHASE_MAX_STEPS)) {
        fprintf(stderr,
                "%s: key 'twophase.end_time': expected an end time reachable in at most %.0e "
                "CFL steps (got %g, about %.3g steps of %g)\n",
                tp->config_path, TWOPHASE_MAX_STEPS, tp->t_end, tp->t_end / r.dt_max, r.dt_max);
        rc = 1;
      }
      double t_next = next_out < tp->n_out ? tp->t_out[next_out] : tp->t_end;
      double dt = fmin(r.dt_max, t_next - t);
      /* land exactly on an output time instead of leaving a sliver step before it */
      if (t + dt > t_next * (1.0 - 1e-12)) dt = t_next - t;
      for (long b = 0; b < nb; b++) sw[b] = fmin(1.0, fmax(0.0, sw[b] + dt * dsw[b]));
      t = t + dt >= t_next * (1.0 - 1e-12) ? t_next : t + dt;
      injected += dt * r.inflow;
      oil_produced += dt * r.oil_out;
      const double out = r.water_out + r.oil_out;
      twophase_history_row row = {.time = t,
                                  .dt = dt,
                                  .pv_injected = injected / pore_volume,
                                  .water_cut = out > 0.0 ? r.water_out / out : 0.0,
                                  .oil_recovery = oil_produced / oil0,
                                  .inflow_rate = r.inflow,
                                  .water_out = r.water_out,
                                  .oil_out = r.oil_out,
                                  .inlet_pressure = p_inlet};
      twophase_output_history(&w, &row);
      if (sum->breakthrough_pvi < 0.0 && row.water_cut > fw_init + 1e-6)
        sum->breakthrough_pvi = row.pv_injected;
      sum->pv_injected = row.pv_injected;
      sum->oil_recovery = row.oil_recovery;
      sum->water_cut = row.water_cut;
      sum->steps++;
      if (t == t_next && next_out < tp->n_out) {
        next_out++;
        if (t < tp->t_end) twophase_output_profile(&w, p, t, row.pv_injected, sw);
      }
      if (t >= tp->t_end) twophase_output_profile(&w, p, t, row.pv_injected, sw);
      state[0] = t;
    }
    state[1] = rc;
    free(pressure);
    MPI_Bcast(state, 2, MPI_DOUBLE, 0, comm);
    t = state[0];
    rc = (int)state[1];
    MPI_Bcast(sw, (int)nb, MPI_DOUBLE, 0, comm);
  }
  if (rank == 0) {
    double oil_now = 0.0;
    for (long b = 0; b < nb; b++) oil_now += (1.0 - sw[b]);
    oil_now *= pore_volume / nb;
    sum->oil_balance_rel = oil0 > 0.0 ? fabs(oil_now + oil_produced - oil0) / oil0 : 0.0;
    if (twophase_output_close(&w, c)) rc = 1;
  }
  MPI_Bcast(&rc, 1, MPI_INT, 0, comm);
  for (long b = 0; b < nb; b++) p->laws[b].k = k_abs[b];
  free(k_abs);
  free(sw);
  free(dsw);
  return rc;
}
