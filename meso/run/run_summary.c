/* Final summary of a run: human-readable lines on stdout and summary.json (atomic), with
 * block-averaged standard errors (Flyvbjerg-Petersen, analysis/block_average.c). */
#include "common/atomic_file.h"
#include "effects/dpd_thermostat.h"
#include "effects/effect.h"
#include "physics/density_kernels.h"
#include "physics/pair_random.h"
#include "run/run_flood.h"
#include "run/run_flux.h"
#include "run/run_stats.h"

#include <math.h>
#include <string.h>

static void json_num(FILE *fp, double v) {
  if (isfinite(v))
    fprintf(fp, "%.10g", v);
  else
    fprintf(fp, "null");
}

/* `before` (punctuation and a key) then the number, null when it is not finite */
static void json_field(FILE *fp, const char *before, double v) {
  fputs(before, fp);
  json_num(fp, v);
}

static void json_stat(FILE *fp, const char *name, double mean, double err, int last) {
  fprintf(fp, "    \"%s\": {\"mean\": ", name);
  json_num(fp, mean);
  fprintf(fp, ", \"err\": ");
  json_num(fp, err);
  fprintf(fp, "}%s\n", last ? "" : ",");
}

static const char *const flux_method =
    "MSER-5 truncation of the transient (White 1997); mean after it; standard error by block "
    "averaging at the plateau of the blocked error (Flyvbjerg & Petersen 1989)";

/* The driving gradient of the flux: the body force's constant G, or the measured one. */
static double flux_G(const run_flux_t *f) {
  return f->pd.on ? f->pd_result.G : f->def.G;
}

/* The measured pressure drop of a pressure-driven run (inlet_force with a sample), as JSON. */
static void pressure_drop_json(FILE *fp, const run_flux_t *f) {
  const pressure_drop_t *pd = &f->pd;
  const pressure_drop_result_t *r = &f->pd_result;
  const struct {
    const char *name;
    double mean, err;
  } v[] = {{"P_in", r->p_in.mean, r->p_in.err},
           {"P_out", r->p_out.mean, r->p_out.err},
           {"dp", r->dp.mean, r->dp.err},
           {"G", r->G, r->G_err},
           {"inlet_force_total", r->force.mean, r->force.err},
           {"inlet_force_per_area", r->force_per_area, r->force_per_area_err}};
  fprintf(fp, "    \"pressure_drop\": {");
  for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) {
    fprintf(fp, "\"%s\": ", v[k].name);
    json_num(fp, v[k].mean);
    fprintf(fp, ", \"%s_err\": ", v[k].name);
    json_num(fp, v[k].err);
    fprintf(fp, ", ");
  }
  fprintf(fp, "\"dp_over_force_per_area\": ");
  json_num(fp, r->balance);
  json_field(fp, ",\n      \"sample\": [", pd->sample_lo);
  json_field(fp, ", ", pd->sample_hi);
  json_field(fp, "], \"length\": ", pd->length);
  json_field(fp, ", \"probe_in\": [", pd->in_lo);
  json_field(fp, ", ", pd->in_lo + pd->width);
  json_field(fp, "], \"probe_out\": [", pd->out_lo);
  json_field(fp, ", ", pd->out_lo + pd->width);
  fprintf(fp, "], \"samples_used\": %ld, \"profile_bins\": %d, \"profile_file\": \"%s\",\n",
          r->samples_used, pd->nbins, pd->profile_path);
  fprintf(fp, "      \"definition\": \"P = sum_{i in slab} (m v_a^2 + W_i,aa) / V_slab (kinetic + "
              "per-particle pair virial); dp = P_in - P_out; G = dp / length; averaged from the "
              "flux's steady-state start, block errors\"},\n");
}

/* The flux lines of the human summary; with a `units:` block also q and G in SI. */
static void flux_text(FILE *out, const run_flux_t *f, const scene_t *s) {
  const steady_state_t *r = &f->result;
  const char ax = "xyz"[f->def.axis];
  fprintf(out,
          "flux along %c: q = %.6g +- %.2g (superficial Darcy velocity q = Q / A_total, A_total = "
          "%.6g = whole cross-section), G = %.6g (%s)\n",
          ax, r->avg.mean, r->avg.err, f->def.area, flux_G(f),
          flux_gradient_source_name(f->def.gradient_source));
  if (s->units.on) {
    const units_si_t *u = &s->units.si;
    fprintf(
        out,
        "  in SI: q = %.6g +- %.2g m/s, G = %.6g Pa/m (q x %.4g m/s, G x %.4g Pa/m; units below)\n",
        r->avg.mean * u->q_m_per_s, r->avg.err * u->q_m_per_s, flux_G(f) * u->G_Pa_per_m,
        u->q_m_per_s, u->G_Pa_per_m);
  }
  if (f->pd.on) {
    const pressure_drop_result_t *p = &f->pd_result;
    fprintf(out,
            "  pressure drop across the sample [%g, %g]: dp = P_in - P_out = %.6g +- %.2g "
            "(P_in %.6g, P_out %.6g), G = dp / %g = %.6g +- %.2g\n",
            f->pd.sample_lo, f->pd.sample_hi, p->dp.mean, p->dp.err, p->p_in.mean, p->p_out.mean,
            f->pd.length, p->G, p->G_err);
    fprintf(out, "  momentum balance: inlet force / A_total = %.6g +- %.2g, dp / (F / A) = %.4g\n",
            p->force_per_area, p->force_per_area_err, p->balance);
  }
  if (r->n > 0)
    fprintf(out, "  steady from step %.0f (%s%s), %ld of %ld samples used, block length %ld%s\n",
            f->steps.x[r->start],
            r->slow_governs ? "3x the pressure-diffusion time, after MSER-5's transient" : "MSER-5",
            r->before_slow ? ": NO steady state: the run ended within 3x the pressure-diffusion "
                             "time"
            : r->steady    ? ""
                           : ": NO steady state found",
            r->n - r->start, r->n, r->avg.block_len,
            r->avg.plateau ? "" : " (no plateau: error underestimated)");
  if (r->n > 0 && f->pressure_steps > 0)
    fprintf(out,
            "  pressure-diffusion time of the liquid phi L^2 G / (4 pi^2 K q) = %.0f steps (K = "
            "%g, output.flux.bulk_modulus): q relaxes from above over it at every forcing\n",
            f->pressure_steps, s->flux.bulk_modulus);
  if (r->n > 0)
    fprintf(out,
            "  correlation time of q %.0f steps (%s), %.1f independent samples; Darcy relaxation "
            "time of the mean flow rho q / (phi G) = %.0f steps\n",
            r->tau_int * f->every,
            r->floor_governs ? "the Darcy relaxation time: the series reads shorter"
                             : "from the series",
            r->n_eff, f->relax_steps);
  if (f->target > 0)
    fprintf(out, "  target relative error %g: %s (relative error %.3g)%s\n", f->target,
            f->reached ? "reached" : "NOT reached within the step budget", r->rel_err,
            f->stopped_early ? ", stopped early" : "");
  double n_phases = 0;
  for (int k = 0; k < f->def.n_phases; k++) n_phases += f->N_phase[k];
  for (int k = 0; k < f->def.n_phases && r->n > 0; k++)
    fprintf(out, "  phase %s: q = %.6g +- %.2g, N = %.0f, saturation N / N_phases = %.4f\n",
            s->species[f->def.phase[k]].name, f->phase_result[k].avg.mean,
            f->phase_result[k].avg.err, f->N_phase[k],
            n_phases > 0 ? f->N_phase[k] / n_phases : NAN);
}

/* The summary's flux.phases object: per phase q and q_err over the total's steady window, its
 * particles and its saturation (its share of the phases' particles). */
static void flux_phases_json(FILE *fp, const run_flux_t *f, const scene_t *s) {
  double n_phases = 0;
  for (int k = 0; k < f->def.n_phases; k++) n_phases += f->N_phase[k];
  fprintf(fp, "    \"phases\": {");
  for (int k = 0; k < f->def.n_phases; k++) {
    const int empty = f->result.n <= 0;
    fprintf(fp, "%s\"%s\": {\"q\": ", k ? ", " : "", s->species[f->def.phase[k]].name);
    json_num(fp, empty ? NAN : f->phase_result[k].avg.mean);
    fprintf(fp, ", \"q_err\": ");
    json_num(fp, empty ? NAN : f->phase_result[k].avg.err);
    fprintf(fp, ", \"N\": %.0f, \"saturation\": ", f->N_phase[k]);
    json_num(fp, n_phases > 0 ? f->N_phase[k] / n_phases : NAN);
    fprintf(fp, "}");
  }
  fprintf(fp, "},\n");
}

/* The summary's "flux" object. */
static void flux_json(FILE *fp, const run_flux_t *f, const scene_t *s) {
  const steady_state_t *r = &f->result;
  fprintf(fp, "  \"flux\": {\"axis\": \"%c\", \"q\": ", "xyz"[f->def.axis]);
  json_num(fp, r->avg.mean);
  fprintf(fp, ", \"q_err\": ");
  json_num(fp, r->avg.err);
  fprintf(fp, ", \"Q\": ");
  json_num(fp, r->avg.mean * f->def.area);
  fprintf(fp, ", \"Q_err\": ");
  json_num(fp, r->avg.err * f->def.area);
  fprintf(fp, ", \"relative_error\": ");
  json_num(fp, r->rel_err);
  fprintf(fp, ", \"correlation_steps\": ");
  json_num(fp, r->tau_int * f->every);
  fprintf(fp, ", \"independent_samples\": ");
  json_num(fp, r->n_eff);
  fprintf(fp, ", \"relaxation_steps\": ");
  json_num(fp, f->relax_steps);
  fprintf(fp, ", \"relaxation_governs\": %s", r->floor_governs ? "true" : "false");
  fprintf(fp, ", \"pressure_diffusion_steps\": ");
  json_num(fp, f->pressure_steps);
  fprintf(fp, ", \"pressure_diffusion_governs\": %s, \"before_pressure_diffusion\": %s",
          r->slow_governs ? "true" : "false", r->before_slow ? "true" : "false");
  fprintf(fp, ", \"G\": ");
  json_num(fp, flux_G(f));
  if (f->pd.on) {
    fprintf(fp, ", \"G_err\": ");
    json_num(fp, f->pd_result.G_err);
  }
  fprintf(fp, ", \"G_source\": \"%s\",\n", flux_gradient_source_name(f->def.gradient_source));
  if (s->units.on) { /* the same numbers in SI (the top-level "units" object: the factors) */
    const units_si_t *u = &s->units.si;
    fprintf(fp, "    \"q_m_per_s\": ");
    json_num(fp, r->avg.mean * u->q_m_per_s);
    fprintf(fp, ", \"q_err_m_per_s\": ");
    json_num(fp, r->avg.err * u->q_m_per_s);
    fprintf(fp, ", \"G_Pa_per_m\": ");
    json_num(fp, flux_G(f) * u->G_Pa_per_m);
    if (f->pd.on) {
      fprintf(fp, ", \"G_err_Pa_per_m\": ");
      json_num(fp, f->pd_result.G_err * u->G_Pa_per_m);
    }
    fprintf(fp, ",\n");
  }
  if (f->pd.on) pressure_drop_json(fp, f);
  json_field(fp, "    \"area_total\": ", f->def.area);
  json_field(fp, ", \"length\": ", f->def.length);
  json_field(fp, ", \"fluid_fraction\": ", f->def.fluid_fraction);
  fprintf(fp, ", \"density\": {");
  for (int sp = 0, first = 1; sp < s->n_species; sp++)
    if (f->def.mask >> sp & 1u) {
      fprintf(fp, "%s\"%s\": ", first ? "" : ", ", s->species[sp].name);
      json_num(fp, f->def.n[sp]);
      first = 0;
    }
  fprintf(fp, "}, \"density_source\": \"%s\",\n", flux_density_source_name(f->def.density_source));
  fprintf(fp, "    \"steady_from_step\": ");
  if (r->n > 0)
    fprintf(fp, "%.0f", f->steps.x[r->start]);
  else
    fprintf(fp, "null");
  fprintf(fp,
          ", \"steady\": %s, \"samples\": %ld, \"samples_used\": %ld, \"sample_every\": %ld, "
          "\"block_length\": %ld, \"plateau\": %s,\n",
          r->steady ? "true" : "false", r->n, r->n - r->start, f->every, r->avg.block_len,
          r->avg.plateau ? "true" : "false");
  fprintf(fp, "    \"target_error\": ");
  if (f->target > 0) {
    json_num(fp, f->target);
    fprintf(fp, ", \"reached\": %s, ", f->reached ? "true" : "false");
  } else
    fprintf(fp, "null, \"reached\": null, ");
  fprintf(fp, "\"stopped_early\": %s, \"file\": \"%s\",\n", f->stopped_early ? "true" : "false",
          s->flux.path);
  if (f->def.n_phases > 0) flux_phases_json(fp, f, s);
  fprintf(fp,
          "    \"method\": \"%s\",\n    \"convention\": \"q = Q / A_total, A_total = the whole box "
          "cross-section normal to the axis (solid included); Q = (1/L) sum_s sum_i v_i / n_s; G "
          "= -dp/dx\"},\n",
          flux_method);
}

/* The `units:` block: the mapping stated, one line. */
static void units_text(FILE *out, const scene_t *s) {
  char text[1536];
  units_mapping_describe(&s->units, text, sizeof text);
  const units_si_t *u = &s->units.si;
  fprintf(out,
          "units: %s. 1 reduced unit: q %.4g m/s, G %.4g Pa/m, p %.4g Pa, k %.4g m^2 = %.4g nD\n",
          text, u->q_m_per_s, u->G_Pa_per_m, u->p_Pa, u->k_m2, u->k_nD);
}

/* The summary's "units" object: the mapping and the SI value of one reduced unit of each
 * quantity (common/units.h). */
static void units_json(FILE *fp, const scene_t *s) {
  const units_mapping_t *m = &s->units;
  const units_si_t *u = &m->si;
  char text[1536];
  units_mapping_describe(m, text, sizeof text);
  fprintf(fp, "  \"units\": {\"mapping\": \"%s\"",
          m->mapping == UNITS_MAPPING_WATER ? "water" : "own");
  json_field(fp, ", \"rc_m\": ", u->rc_m);
  json_field(fp, ", \"tau_s\": ", u->tau_s);
  json_field(fp, ", \"mass_kg\": ", u->mass_kg);
  json_field(fp, ", \"energy_J\": ", u->kT_J);
  fprintf(fp, ", \"temperature_K\": ");
  json_num(fp, m->temperature_K);
  fprintf(fp, ", \"coarse_graining\": ");
  json_num(fp, m->coarse_graining);
  json_field(fp, ", \"water_molecules_per_particle\": ", u->n_molecules);
  fprintf(fp, ", \"density\": ");
  json_num(fp, m->density);
  fprintf(fp, ", \"density_source\": \"%s\",\n    \"length_source\": \"%s\",\n", m->density_source,
          m->length_source);
  json_field(fp, "    \"factors\": {\"length_m\": ", u->rc_m);
  json_field(fp, ", \"time_s\": ", u->tau_s);
  json_field(fp, ", \"velocity_m_per_s\": ", u->q_m_per_s);
  json_field(fp, ", \"pressure_Pa\": ", u->p_Pa);
  json_field(fp, ", \"pressure_gradient_Pa_per_m\": ", u->G_Pa_per_m);
  json_field(fp, ", \"viscosity_Pa_s\": ", u->mu_Pa_s);
  json_field(fp, ", \"permeability_m2\": ", u->k_m2);
  json_field(fp, ", \"permeability_nD\": ", u->k_nD);
  fprintf(fp, "},\n");
  fprintf(fp, "    \"viscosity_matched\": false, \"statement\": \"%s\"},\n", text);
}

/* The load balance of a several-rank run (engine/sim_balance.h). */
static void balance_text(FILE *out, const run_stats_t *st, const scene_t *s) {
  fprintf(out, "load balance: cuts %s", s->balance.cuts == SCENE_CUTS_COST ? "by cost" : "uniform");
  if (s->balance.cuts == SCENE_CUTS_COST)
    fprintf(out, " (weight imbalance %.3f with uniform cuts)", st->imbalance_weight_uniform);
  fprintf(out,
          "; imbalance (max / mean over %d ranks): particle weight %.3f (frozen weight %.3g), ",
          st->nranks, st->imbalance_weight, st->frozen_weight);
  if (st->imbalance_busy > 0 && st->rebalances > 0)
    fprintf(out, "busy time %.3f since the last move, %.3f over the run", st->imbalance_busy,
            st->imbalance_busy_run);
  else if (st->imbalance_busy > 0)
    fprintf(out, "busy time %.3f", st->imbalance_busy);
  if (st->imbalance_busy > 0 && st->loop_seconds > 0)
    fprintf(out, " (busy: %.0f%% of the step loop on the mean rank)",
            100.0 * st->busy_mean_seconds / st->loop_seconds);
  else
    fprintf(out, "busy time not measured (GPU backend)");
  if (s->balance.every > 0)
    fprintf(out, "; %ld rebalancing(s) in %.3g s", st->rebalances, st->balance_seconds);
  fprintf(out, "\n");
}

static void balance_json(FILE *fp, const run_stats_t *st, const scene_t *s) {
  fprintf(fp, "  \"load_balance\": {\"cuts\": \"%s\"",
          s->balance.cuts == SCENE_CUTS_COST ? "cost" : "uniform");
  json_field(fp, ", \"imbalance_weight\": ", st->imbalance_weight);
  json_field(fp, ", \"imbalance_weight_uniform_cuts\": ", st->imbalance_weight_uniform);
  json_field(fp, ", \"imbalance_busy\": ", st->imbalance_busy > 0 ? st->imbalance_busy : NAN);
  json_field(fp,
             ", \"imbalance_busy_run\": ", st->imbalance_busy > 0 ? st->imbalance_busy_run : NAN);
  json_field(fp, ", \"busy_fraction\": ",
             st->loop_seconds > 0 && st->imbalance_busy > 0
                 ? st->busy_mean_seconds / st->loop_seconds
                 : 0.0);
  /* each rank's busy seconds (rank order: slab order along an axis cut alone): the slow ranks */
  const double *per_rank[2] = {st->busy_rank_since_move, st->busy_rank_run};
  const char *per_rank_key[2] = {"busy_seconds_since_move", "busy_seconds_run"};
  for (int k = 0; k < 2 && per_rank[0] && per_rank[1]; k++) {
    fprintf(fp, ", \"%s\": [", per_rank_key[k]);
    for (int r = 0; r < st->nranks; r++) json_field(fp, r ? ", " : "", per_rank[k][r]);
    fprintf(fp, "]");
  }
  json_field(fp, ", \"frozen_weight\": ", st->frozen_weight);
  fprintf(fp, ", \"rebalances\": %ld", st->rebalances);
  json_field(fp, ", \"balance_seconds\": ", st->balance_seconds);
  fprintf(fp, "},\n");
}

int run_summary_write(const run_stats_t *st, const scene_t *s, const profile_t *prof, FILE *out,
                      const char *json_path) {
  const run_flux_t *flux = st->flux && st->flux->on ? st->flux : NULL;
  block_average_t b[STAT_COUNT];
  for (int k = 0; k < STAT_COUNT; k++) b[k] = block_average(st->s[k].x, st->s[k].n);
  const long samples = st->s[STAT_T].n;
  const block_average_t core = block_average(st->core_density.x, st->core_density.n);
  double rho = NAN, rho_err = NAN;
  int plateau = 0, interfaces = 0;
  if (prof && prof->samples > 0)
    plateau = profile_plateau_density(prof, &rho, &rho_err, &interfaces);
  const double pss =
      st->loop_seconds > 0 ? (double)st->n_total * st->steps_done / st->loop_seconds : 0;

  fprintf(out, "\n== %s: %ld steps (to step %ld), %ld particles, %d ranks, kernel %s ==\n", s->name,
          st->steps_done, st->last_step, st->n_total, st->nranks,
          s->density_kernel == MESO_KERNEL_LUCY ? "lucy" : "warren");
  if (samples > 0) {
    fprintf(out, "averages over steps %ld..%ld (%ld samples, block-averaged standard errors):\n",
            st->window_start, st->last_step, samples);
    /* name = mean +- err; with fewer samples than an error bar needs, the mean alone, said so */
    static const struct {
      const char *name;
      int stat;
    } rows[2][3] = {{{"T", STAT_T}, {"p", STAT_P}, {NULL, 0}},
                    {{"Pxx", STAT_PXX}, {"Pyy", STAT_PYY}, {"Pzz", STAT_PZZ}}};
    static const int off_diag[3] = {STAT_PXY, STAT_PXZ, STAT_PYZ};
    static const char *const off_names[3] = {"Pxy", "Pxz", "Pyz"};
    for (int r = 0; r < 3; r++) {
      const char *sep = "  ";
      for (int c = 0; c < 3; c++) {
        const char *name = r < 2 ? rows[r][c].name : off_names[c];
        if (!name) continue;
        const block_average_t *v = &b[r < 2 ? rows[r][c].stat : off_diag[c]];
        if (isfinite(v->err))
          fprintf(out, "%s%s = %.4f +- %.4f", sep, name, v->mean, v->err);
        else
          fprintf(out, "%s%s = %.4f (no error bar)", sep, name, v->mean);
        sep = "   ";
      }
      fprintf(out, "\n");
    }
    if (!isfinite(b[STAT_T].err))
      fprintf(out, "  (%ld sample(s): too few for an error bar; run longer or sample more often)\n",
              samples);
    if (st->gamma_axis >= 0 && !interfaces)
      fprintf(out,
              "  density = %.4g +- %.2g (uniform along %c: no interface, no surface tension)\n",
              rho, rho_err, 'x' + st->gamma_axis);
    else if (st->gamma_axis >= 0)
      fprintf(
          out,
          "  liquid density = %.4g +- %.2g   surface tension = %.4g +- %.2g (kT/rc^2, normal %c, "
          "two interfaces)\n",
          rho, rho_err, b[STAT_GAMMA].mean, b[STAT_GAMMA].err, 'x' + st->gamma_axis);
  } else {
    fprintf(out, "no samples in the averaging window (steps >= %ld every %ld)\n", st->window_start,
            st->sample_every);
  }
  if (st->penetration_on)
    fprintf(
        out,
        "penetrations: %ld of %ld samples had mobile particles inside solid voxels (at most %ld at "
        "once, deepest %.3g rc)%s\n",
        st->penetration_bad_samples, st->penetration_samples, st->penetration_max,
        st->penetration_depth, st->penetration_bad_samples ? "  <-- NOT ZERO" : "");
  if (st->core_density.n > 0)
    fprintf(out,
            "pore core density: %.4f +- %.2g (mobile particles per rc^3 in the %ld pore voxels at "
            "least %g rc from the solid, %.4g rc^3; %ld samples)\n",
            core.mean, core.err, st->core_voxels, st->core_rc, st->core_volume, st->core_density.n);
  if (flux) flux_text(out, flux, s);
  if (st->flood) run_flood_text(out, st->flood, s);
  if (s->units.on) units_text(out, s);
  if (st->nranks > 1) balance_text(out, st, s);
  fprintf(out, "performance: %.2f M particle-steps/s (%.2f s in the step loop, %.2f s total)\n",
          pss / 1e6, st->loop_seconds, st->total_seconds);
  fflush(out);

  if (!json_path || !json_path[0]) return 0;
  char tmp[SCENE_PATH_LEN + 32];
  FILE *fp = atomic_open(json_path, tmp, sizeof tmp);
  if (!fp) return -1;
  fprintf(fp,
          "{\n  \"scene\": \"%s\",\n  \"scene_file\": \"%s\",\n  \"kernel\": \"%s\",\n  \"ranks\": "
          "%d,\n",
          s->name, s->file, s->density_kernel == MESO_KERNEL_LUCY ? "lucy" : "warren", st->nranks);
  /* where it ran and which random stream it drew (runs are comparable number for number only
   * with the same generator) */
  fprintf(fp, "  \"backend\": \"%s\",\n", s->backend == SCENE_BACKEND_CUDA ? "cuda" : "cpu");
  if (s->effect[EFFECT_DPD_THERMOSTAT])
    fprintf(fp, "  \"pair_rng\": \"%s\",\n",
            pair_rng_word(
                SCENE_EFFECT_OPTIONS(s, EFFECT_DPD_THERMOSTAT, dpd_thermostat_options_t)->rng));
  fprintf(fp, "  \"box\": [%.10g, %.10g, %.10g],\n", s->box_hi[0] - s->box_lo[0],
          s->box_hi[1] - s->box_lo[1], s->box_hi[2] - s->box_lo[2]);
  fprintf(
      fp,
      "  \"particles\": %ld,\n  \"first_step\": %ld,\n  \"last_step\": %ld,\n  \"dt\": %.10g,\n",
      st->n_total, st->first_step, st->last_step, s->dt);
  fprintf(fp,
          "  \"window\": {\"start_step\": %ld, \"end_step\": %ld, \"sample_every\": %ld, "
          "\"samples\": %ld},\n",
          st->window_start, st->last_step, st->sample_every, samples);
  fprintf(fp, "  \"thermo\": {\n");
  for (int k = 0; k < STAT_GAMMA; k++)
    json_stat(fp, run_stat_names[k], b[k].mean, b[k].err, k == STAT_GAMMA - 1);
  fprintf(fp, "  },\n");
  if (st->gamma_axis >= 0) {
    fprintf(
        fp,
        "  \"profile\": {\"axis\": \"%c\", \"bins\": %d, \"samples\": %ld, \"file\": \"%s\"},\n",
        'x' + st->gamma_axis, prof ? prof->nbins : 0, prof ? prof->samples : 0, s->profile.path);
    fprintf(fp, "  \"liquid_density\": {\"mean\": ");
    json_num(fp, rho);
    fprintf(fp, ", \"err\": ");
    json_num(fp, rho_err);
    fprintf(fp, ", \"plateau_bins\": %d, \"interfaces\": %s},\n", plateau,
            interfaces ? "true" : "false");
    if (interfaces) {
      fprintf(fp, "  \"surface_tension\": {\"mean\": ");
      json_num(fp, b[STAT_GAMMA].mean);
      fprintf(fp, ", \"err\": ");
      json_num(fp, b[STAT_GAMMA].err);
      fprintf(fp, ", \"formula\": \"(L_n / 2) <P_nn - (P_t1 + P_t2) / 2>\"},\n");
    }
  }
  if (st->penetration_on)
    fprintf(fp,
            "  \"penetrations\": {\"samples\": %ld, \"samples_with_penetration\": %ld, "
            "\"max_particles\": %ld, \"max_depth_rc\": %.6g},\n",
            st->penetration_samples, st->penetration_bad_samples, st->penetration_max,
            st->penetration_depth);
  if (st->core_density.n > 0) {
    fprintf(fp, "  \"pore_core_density\": {\"mean\": ");
    json_num(fp, core.mean);
    fprintf(fp, ", \"err\": ");
    json_num(fp, core.err);
    fprintf(
        fp,
        ", \"samples\": %ld, \"voxels\": %ld, \"volume_rc3\": %.6g, \"distance_rc\": %g, "
        "\"what\": \"mobile particles per rc^3 in the pore voxels at least distance_rc from the "
        "solid (26-connected voxel layers)\"},\n",
        st->core_density.n, st->core_voxels, st->core_volume, st->core_rc);
  }
  if (flux) flux_json(fp, flux, s);
  if (st->flood) run_flood_json(fp, st->flood, s);
  if (s->units.on) units_json(fp, s);
  if (st->nranks > 1) balance_json(fp, st, s);
  json_field(fp, "  \"timing\": {\"loop_seconds\": ", st->loop_seconds);
  json_field(fp, ", \"total_seconds\": ", st->total_seconds);
  fprintf(fp, ", \"steps\": %ld, \"particles\": %ld", st->steps_done, st->n_total);
  json_field(fp, ", \"particle_steps_per_second\": ", pss);
  fprintf(fp, "}\n}\n");
  return atomic_commit(fp, tmp, json_path);
}
