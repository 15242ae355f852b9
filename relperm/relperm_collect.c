/* The collect step of `mdpore relperm` (docs/relperm.md section 4): each run's summary (the total
 * flux through campaign_summary.c, the phases' from flux.phases), the run checks of
 * campaign_checks.c, then per two-liquid run
 *   Sw       = N_water / (N_water + N_oil): particle counts, exact (no error: the species of a
 *              particle never changes in these runs);
 *   kr_i     = q_i / q_i^(1): the phase's superficial velocity over that of the same liquid alone
 *              in the same image at the same body force (the reference runs); equal to
 *              mu_i q_i / (k G) when both liquids see the same k = mu_i q_i^(1) / G;
 *   kr_i^w   = (mu_i / mu_w) q_i / q_w^(1): the alternative normalised by the water run only,
 *              with the documented viscosity ratio M (kept in relperm.json and the report);
 *   Ca       = mu_nw u_nw / gamma_wo with u_nw = q_nw / (phi S_nw) the non-wetting liquid's mean
 *              pore velocity, mu_w the standard water's at the pore-core density, gamma_wo the
 *              water-oil tension at density 6.2;
 * errors propagated from the block errors of the q's as independent (the runs are).
 * Writes relperm.csv (contract columns), relperm.json, relperm.txt (the report) and relperm.png. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/atomic_file.h"
#include "common/json_out.h"
#include "common/yaml_tree.h"
#include "relperm.h"

#ifndef RP_PLOT_SCRIPT
#define RP_PLOT_SCRIPT "relperm_plot.py"
#endif
#ifndef MDPORE_PYTHON_EXE
#define MDPORE_PYTHON_EXE "python3"
#endif

typedef struct {
  int ok;        /* summary read and checks passed */
  char why[512]; /* why not */
  double q_w, q_w_err, q_o, q_o_err, N_w, N_o, sw;
} phase_data;

typedef struct {
  int run;
  double sw, krw, krw_err, kro, kro_err, kro_w, kro_w_err, ca, snw_c, snw_d, snw_image, sw_target;
} kr_row;

static double num(ytree_t *t, yaml_node_t *map, const char *key) {
  yaml_node_t *n = map ? yt_get(t, map, key) : NULL;
  double v;
  if (!n || yt_is_null(n) || yt_double(t, n, key, &v)) return NAN;
  return v;
}

/* flux.phases of a summary: water and oil (a reference has one of them). */
static void read_phases(const camp_run *r, phase_data *p) {
  char path[CAMP_PATH + 32];
  snprintf(path, sizeof path, "%s/summary.json", r->dir);
  p->q_w = p->q_w_err = p->q_o = p->q_o_err = NAN;
  p->N_w = p->N_o = 0;
  ytree_t t;
  if (yt_load(&t, path, 1)) return;
  yaml_node_t *root = yt_root(&t), *flux = NULL, *ph = NULL;
  if (root && root->type == YAML_MAPPING_NODE) flux = yt_get(&t, root, "flux");
  if (flux && flux->type == YAML_MAPPING_NODE) ph = yt_get(&t, flux, "phases");
  if (ph && ph->type == YAML_MAPPING_NODE) {
    yaml_node_t *w = yt_get(&t, ph, "water"), *o = yt_get(&t, ph, "oil");
    if (w && w->type == YAML_MAPPING_NODE) {
      p->q_w = num(&t, w, "q");
      p->q_w_err = num(&t, w, "q_err");
      p->N_w = num(&t, w, "N");
    }
    if (o && o->type == YAML_MAPPING_NODE) {
      p->q_o = num(&t, o, "q");
      p->q_o_err = num(&t, o, "q_err");
      p->N_o = num(&t, o, "N");
    }
  }
  yt_free(&t);
  if (!(p->N_w >= 0)) p->N_w = 0;
  if (!(p->N_o >= 0)) p->N_o = 0;
  p->sw = p->N_w + p->N_o > 0 ? p->N_w / (p->N_w + p->N_o) : NAN;
}

static double ratio_err(double a, double ea, double b, double eb) {
  return fabs(a / b) * hypot(ea / a, eb / b);
}

static int by_sw(const void *x, const void *y) {
  const double a = ((const kr_row *)x)->sw, b = ((const kr_row *)y)->sw;
  return (a > b) - (a < b);
}

static const char *role_word(int role) {
  return role == RP_ROLE_TWO ? "two liquids" : role == RP_ROLE_WATER ? "all water" : "all oil";
}

static void definitions(FILE *f, const char *pre, const relperm *rp, double G) {
  const campaign *c = &rp->c;
  const char *nw = rp->wetting == RP_WET_WATER ? "oil" : "water";
  fprintf(f,
          "%smdpore relperm: steady co-current relative permeability of water and oil, sample "
          "%s, flow along %c, boundary %s\n",
          pre, c->sample, 'x' + rp->axis, rp->boundary);
  fprintf(f,
          "%sSw = N_water / (N_water + N_oil) of the run's particles (exact counts; Sw_err = 0); "
          "wetting liquid %s, non-wetting %s; phase images by %s\n",
          pre, rp->wetting == RP_WET_WATER ? "water" : "oil", nw,
          rp->mode == RP_MODE_GIVEN ? "given labelled images (--phase-images)"
          : rp->mode == MDP_MORPH_IMBIBITION
              ? (rp->trapping ? "morphological imbibition, trapping on"
                              : "morphological imbibition, no trapping")
              : (rp->trapping ? "morphological drainage, trapping on"
                              : "morphological drainage, no trapping"));
  fprintf(f,
          "%skr_i = q_i / q_i^(1): the phase's superficial velocity q_i = (1/V) sum_{i} v / n over "
          "that of the same liquid alone in the same image at the same body force (= mu_i q_i / "
          "(k G) when both liquids see the same k); the alternative kro^w = M q_o / q_w^(1) "
          "(water run only) is in relperm.json\n",
          pre);
  fprintf(f,
          "%sG = n g = %.6g (body force g = %.6g per particle on both liquids, n the fill "
          "density); M = mu_oil / mu_water = %.4g +- %.2g (viscosity ratio %d, docs/twophase.md "
          "section 4); rc = %.6g m; rc_per_voxel %.6g\n",
          pre, G, rp->g, rp->liq.M, rp->liq.M_err, rp->ratio, c->length_unit_m, c->rc_per_voxel);
  fprintf(f,
          "%sCa = mu_nw u_nw / gamma_wo, u_nw = q_nw / (phi S_nw), phi = %.4g, gamma_wo = %g; "
          "Snw_connected / Snw_disconnected: non-wetting voxels of the phase image in clusters "
          "that join / do not join the two faces along the axis, over the pore voxels (the "
          "distribution the run started from); pc: not measured (empty)\n",
          pre, c->porosity, RP_GAMMA_WO);
}

int rp_collect(const rp_opts *o, relperm *rp, const char *workdir) {
  (void)o;
  campaign *c = &rp->c;
  const camp_checks lim = {.fill_density = c->fluid_density,
                           .kT = c->kT > 0 ? c->kT : 1.0,
                           .density_tol = CAMP_DEFAULT_DENSITY_TOLERANCE,
                           .cavitation_tol = CAMP_DEFAULT_CAVITATION_TOLERANCE,
                           .temperature_tol = CAMP_DEFAULT_TEMPERATURE_TOLERANCE};
  static phase_data pd[RP_RUNS];
  int ref_w = -1, ref_o = -1, left_out = 0;
  double G = NAN;
  for (int i = 0; i < c->n_runs; i++) {
    camp_run *r = &c->runs[i];
    phase_data *p = &pd[i];
    char why[CAMP_PATH + 256];
    memset(p, 0, sizeof *p);
    camp_read_summary(r, why, sizeof why);
    if (!r->have) {
      snprintf(p->why, sizeof p->why, "%.500s", why);
    } else {
      camp_flag flag;
      read_phases(r, p);
      if (isfinite(r->G)) G = r->G;
      if (!camp_run_admissible(r, &lim, 0, &flag))
        snprintf(p->why, sizeof p->why, "%s: %.480s", flag.check, flag.why);
      else if ((rp->runs[i].role != RP_ROLE_OIL && !isfinite(p->q_w)) ||
               (rp->runs[i].role != RP_ROLE_WATER && !isfinite(p->q_o)))
        snprintf(p->why, sizeof p->why,
                 "no flux.phases in the summary (a run of an older mdpore?)");
      else
        p->ok = 1;
    }
    if (!p->ok) {
      left_out++;
      fprintf(stderr, "mdpore relperm: run %d (%s) left out: %s\n", i + 1,
              role_word(rp->runs[i].role), p->why);
    }
    if (rp->runs[i].role == RP_ROLE_WATER) ref_w = i;
    if (rp->runs[i].role == RP_ROLE_OIL) ref_o = i;
  }
  if (ref_w < 0 || ref_o < 0 || !pd[ref_w].ok || !pd[ref_o].ok) {
    fprintf(stderr,
            "mdpore relperm: the single-phase reference runs (all water, all oil) are needed for "
            "kr and %s: no relative permeability (rerun with more --steps, or see the runs' "
            "run.log)\n",
            ref_w < 0 || ref_o < 0 ? "are missing from the manifest" : "one of them is left out");
    return -1;
  }
  const double qw1 = pd[ref_w].q_w, qw1e = pd[ref_w].q_w_err;
  const double qo1 = pd[ref_o].q_o, qo1e = pd[ref_o].q_o_err;
  const double core =
      isfinite(c->runs[ref_w].core_density) ? c->runs[ref_w].core_density : c->fluid_density;
  const double mu_w = camp_water_viscosity(core);
  const int nw_is_oil = rp->wetting == RP_WET_WATER;
  const double mu_nw = nw_is_oil ? rp->liq.M * mu_w : mu_w;
  static kr_row rows[RP_RUNS];
  int n = 0;
  for (int i = 0; i < c->n_runs; i++) {
    if (rp->runs[i].role != RP_ROLE_TWO || !pd[i].ok) continue;
    const phase_data *p = &pd[i];
    kr_row *k = &rows[n++];
    k->run = i;
    k->sw = p->sw;
    k->sw_target = rp->runs[i].sw_target;
    k->krw = p->q_w / qw1;
    k->krw_err = ratio_err(p->q_w, p->q_w_err, qw1, qw1e);
    k->kro = p->q_o / qo1;
    k->kro_err = ratio_err(p->q_o, p->q_o_err, qo1, qo1e);
    k->kro_w = rp->liq.M * p->q_o / qw1;
    k->kro_w_err = fabs(k->kro_w) * sqrt(pow(p->q_o_err / p->q_o, 2) + pow(qw1e / qw1, 2) +
                                         pow(rp->liq.M_err / rp->liq.M, 2));
    const double s_nw = nw_is_oil ? 1 - p->sw : p->sw, q_nw = nw_is_oil ? p->q_o : p->q_w;
    k->ca = s_nw > 0 && c->porosity > 0 ? mu_nw * q_nw / (c->porosity * s_nw) / RP_GAMMA_WO : NAN;
    k->snw_c = rp->runs[i].snw_connected;
    k->snw_d = rp->runs[i].snw_disconnected;
    k->snw_image = rp->runs[i].snw_image;
  }
  qsort(rows, (size_t)n, sizeof rows[0], by_sw);

  /* relperm.csv */
  char path[CAMP_PATH + 64], tmp[CAMP_PATH + 128];
  snprintf(path, sizeof path, "%s/relperm.csv", workdir);
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  definitions(f, "# ", rp, G);
  fprintf(f, "# q_water^(1) = %.6g +- %.2g, q_oil^(1) = %.6g +- %.2g (the references)\n", qw1, qw1e,
          qo1, qo1e);
  fprintf(f, "Sw,Sw_err,krw,krw_err,kro,kro_err,Ca,Snw_connected,Snw_disconnected,pc,pc_err\n");
  for (int i = 0; i < n; i++) {
    const kr_row *k = &rows[i];
    fprintf(f, "%.6g,0,%.6g,%.3g,%.6g,%.3g,%.4g,%.6g,%.6g,,\n", k->sw, k->krw, k->krw_err, k->kro,
            k->kro_err, k->ca, k->snw_c, k->snw_d);
  }
  if (atomic_commit(f, tmp, path)) return -1;

  /* relperm.json */
  snprintf(path, sizeof path, "%s/relperm.json", workdir);
  FILE *jf = atomic_open(path, tmp, sizeof tmp);
  if (!jf) return -1;
  json_out j;
  json_begin(&j, jf);
  json_string(&j, "sample", c->sample);
  char ax[2] = {(char)('x' + rp->axis), 0};
  json_string(&j, "axis", ax);
  json_string(&j, "boundary", rp->boundary);
  json_string(&j, "wetting", rp->wetting == RP_WET_WATER ? "water" : "oil");
  json_string(&j, "mode", rp_mode_name(rp->mode));
  json_string(&j, "kr_definition",
              "kr_i = q_i / q_i^(1): the phase's superficial velocity over that of the same "
              "liquid alone in the same image at the same body force");
  json_string(&j, "kr_alternative", "kro_water_normalised = M q_o / q_w^(1)");
  json_number(&j, "g", rp->g);
  json_number(&j, "G", G);
  json_number(&j, "M", rp->liq.M);
  json_number(&j, "M_err", rp->liq.M_err);
  json_number(&j, "rc_m", c->length_unit_m);
  json_number(&j, "rc_per_voxel", c->rc_per_voxel);
  json_number(&j, "porosity", c->porosity);
  json_number(&j, "gamma_wo", RP_GAMMA_WO);
  json_number(&j, "mu_water", mu_w);
  json_number(&j, "q_water_single", qw1);
  json_number(&j, "q_water_single_err", qw1e);
  json_number(&j, "q_oil_single", qo1);
  json_number(&j, "q_oil_single_err", qo1e);
  json_array(&j, "rows");
  for (int i = 0; i < n; i++) {
    const kr_row *k = &rows[i];
    const phase_data *p = &pd[k->run];
    json_object(&j, NULL);
    json_number(&j, "Sw", k->sw);
    json_number(&j, "Sw_target", k->sw_target);
    json_number(&j, "Snw_image", k->snw_image);
    json_number(&j, "q_water", p->q_w);
    json_number(&j, "q_water_err", p->q_w_err);
    json_number(&j, "q_oil", p->q_o);
    json_number(&j, "q_oil_err", p->q_o_err);
    json_number(&j, "krw", k->krw);
    json_number(&j, "krw_err", k->krw_err);
    json_number(&j, "kro", k->kro);
    json_number(&j, "kro_err", k->kro_err);
    json_number(&j, "kro_water_normalised", k->kro_w);
    json_number(&j, "kro_water_normalised_err", k->kro_w_err);
    json_number(&j, "Ca", k->ca);
    json_number(&j, "Snw_connected", k->snw_c);
    json_number(&j, "Snw_disconnected", k->snw_d);
    json_string(&j, "run", c->runs[k->run].dir + strlen(workdir) + 1);
    json_object_end(&j);
  }
  json_array_end(&j);
  json_array(&j, "left_out");
  for (int i = 0; i < c->n_runs; i++) {
    if (pd[i].ok) continue;
    json_object(&j, NULL);
    json_string(&j, "role", role_word(rp->runs[i].role));
    json_number(&j, "Sw_target", rp->runs[i].sw_target);
    json_string(&j, "why", pd[i].why);
    json_object_end(&j);
  }
  json_array_end(&j);
  json_end(&j);
  if (atomic_commit(jf, tmp, path)) return -1;

  /* relperm.txt: the report */
  snprintf(path, sizeof path, "%s/relperm.txt", workdir);
  f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  FILE *outs[2] = {f, stdout};
  /* where the two normalisations differ beyond their errors (M != 1, or the oil's own k differs
   * from the water's), both are printed */
  int differ = 0;
  for (int i = 0; i < n; i++)
    differ |= fabs(rows[i].kro - rows[i].kro_w) > 2 * hypot(rows[i].kro_err, rows[i].kro_w_err);
  for (int w = 0; w < 2; w++) {
    FILE *out = outs[w];
    definitions(out, "", rp, G);
    fprintf(out, "references: q_water^(1) = %.6g +- %.2g, q_oil^(1) = %.6g +- %.2g, ratio %.4g\n",
            qw1, qw1e, qo1, qo1e, qw1 / qo1);
    fprintf(out, "%8s %8s %8s %18s %18s %s%10s %8s %8s %8s\n", "Sw_tgt", "Sw", "Snw_img", "krw",
            "kro", differ ? "       kro^w (M q_o/q_w1) " : "", "Ca", "Snw_con", "Snw_dis", "");
    for (int i = 0; i < n; i++) {
      const kr_row *k = &rows[i];
      char alt[64] = "";
      if (differ) snprintf(alt, sizeof alt, "%10.4f +- %-8.2g", k->kro_w, k->kro_w_err);
      fprintf(out, "%8.4g %8.4f %8.4f %9.4f +- %-6.2g %9.4f +- %-6.2g %s%10.3g %8.4f %8.4f\n",
              k->sw_target, k->sw, k->snw_image, k->krw, k->krw_err, k->kro, k->kro_err, alt, k->ca,
              k->snw_c, k->snw_d);
    }
    if (differ)
      fprintf(out,
              "kro and kro^w differ beyond their errors: the oil alone does not flow 1/M as fast "
              "as the water alone (the liquids do not see the same k, e.g. through their "
              "different wall attractions); kro = q_o / q_o^(1) is the table's\n");
    for (int i = 0; i < c->n_runs; i++)
      if (!pd[i].ok)
        fprintf(out, "left out: %s run (target Sw %g): %s\n", role_word(rp->runs[i].role),
                rp->runs[i].sw_target, pd[i].why);
    fprintf(out, "wrote %s/relperm.csv, relperm.json, relperm.txt%s\n", workdir,
            n ? ", relperm.png (python3 with matplotlib)" : "");
  }
  if (atomic_commit(f, tmp, path)) return -1;
  if (n > 0) {
    char cmd[3 * CAMP_PATH];
    snprintf(cmd, sizeof cmd, "'%s' '%s' '%s/relperm.json' '%s/relperm.png' > /dev/null 2>&1",
             MDPORE_PYTHON_EXE, RP_PLOT_SCRIPT, workdir, workdir);
    if (system(cmd) != 0)
      fprintf(stderr, "mdpore relperm: the PNG was not written (%s with matplotlib, %s)\n",
              MDPORE_PYTHON_EXE, RP_PLOT_SCRIPT);
  }
  if (n == 0) {
    fprintf(stderr, "mdpore relperm: no two-liquid run passed its checks: no kr rows\n");
    return -1;
  }
  return left_out ? 1 : 0;
}
