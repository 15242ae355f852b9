/* `mdpore couple CONFIG` (docs/coupling.md): the pore-scale <-> continuum loop.
 *
 * pass 1: blocks -> one campaign per block (auto ladder) -> fitted laws -> continuum solve -> block
 *         gradients. A block whose gradient lies above its calibrated range, or below it but within
 *         resolvable_fraction of its smallest gradient, gets a run at that gradient (g = G / n).
 * pass p: the campaigns again (finished runs are reused, only the new ones run), refit, solve; stop
 *         when every block flux agrees with the previous pass within tolerance_sigma combined
 *         standard errors (converged, exit 0), or after max_passes (exit 4, said so). Slurm
 *         launcher: a pass whose runs are not all finished writes the job array and exits 3.
 * Decisions depend only on finished runs and fixed seeds, so a killed loop rerun redoes the same
 * passes from its cache. */
#include <math.h>
#include <mpi.h>
#include <petscsys.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "common/atomic_file.h"
#include "common/cli_help.h"
#include "couple.h"

static const cli_help_page_t couple_help = {
    .command = "couple",
    .usage = "usage: mdpore couple CONFIG.yaml\n",
    .purpose = "The pore-scale <-> continuum loop: campaigns per block, fitted laws, feedback.",
    .about = "The pore-scale <-> continuum loop (docs/coupling.md): a permeability campaign per "
             "block of a segmented image, the fitted laws into the continuum solve, block "
             "gradients fed back as new pore-scale runs until the block fluxes of two passes "
             "agree within their errors.",
    .notes = "Exit status: 0 converged, 4 stopped at loop.max_passes without agreement, 3 runs "
             "pending (launcher: slurm: submit the job array it wrote, then run it again), 1 "
             "error, 2 usage.",
    .more = "docs/coupling.md",
};

/* The gradient the sample is driven at, in reduced units. */
static double drive_gradient(const couple_config *c, const couple_block *blocks, int n) {
  if (c->gradient_si) {
    for (int b = 0; b < n; b++)
      if (blocks[b].percolates && blocks[b].law.G_Pa_per_m > 0)
        return c->gradient_si_value / blocks[b].law.G_Pa_per_m;
    return NAN;
  }
  if (!c->gradient_auto) return c->gradient;
  /* auto: the geometric mean of the middles of the blocks' calibrated ranges */
  double s = 0;
  int m = 0;
  for (int b = 0; b < n; b++)
    if (blocks[b].percolates) {
      s += 0.5 * log(blocks[b].law.g_min * blocks[b].law.g_max);
      m++;
    }
  return m ? exp(s / m) : NAN;
}

/* Adds a run at the block's gradient when it lies outside the calibrated range but is resolvable.
 * Returns 1 when a run was added, -1 when a run there exists but the range still does not reach G:
 * the campaign left that run out of the block's Darcy range (heated, unsteady, ...: its flow
 * table says why), so the law stays extrapolated there and no new run would change it. */
static int feed_back(const couple_config *c, couple_block *b, double G) {
  const couple_law *L = &b->law;
  if (!b->percolates || !(b->density > 0)) return 0;
  int above = G > L->g_max * 1.05;
  int below = G < L->g_min / 1.05 && G >= L->g_min * c->resolvable_fraction;
  if (!above && !below) return 0;
  char text[32];
  snprintf(text, sizeof text, "%.4g", G / b->density); /* g = G / (n m), m = 1 */
  double g = strtod(text, NULL);
  for (int i = 0; i < b->n_ladder + b->n_extra; i++) {
    double have = i < b->n_ladder ? b->ladder_g[i] : b->extra_g[i - b->n_ladder];
    if (fabs(have - g) <= 0.1 * g) {
      /* a run within 10% exists: inside the table's range it is in the fit (G moved after the
       * refit, by less than a new run would resolve); outside it, the fit left it out. Body
       * force only: a pressure-driven run's G is the measured drop, not n g. */
      const double Gh = have * b->density;
      if (c->drive_pressure) return 0;
      return Gh <= L->g_max * 1.05 && Gh >= L->g_min / 1.05 ? 0 : -1;
    }
  }
  if (b->n_ladder + b->n_extra >= COUPLE_MAX_GRADIENTS) return 0;
  b->extra_g[b->n_extra++] = g;
  return 1;
}

/* campaign.axes: auto. Marks the cross axes along which a block's flow in this pass's solve exceeds
 * COUPLE_CROSS_FLOW_FRACTION of its flow along the loop's axis (only axes with faces between blocks
 * carry any) to be measured in the next pass; an axis its pore space does not span is taken
 * impermeable without a campaign. Returns how many were marked. */
static int want_cross_axes(const couple_config *c, couple_block *blocks, int n,
                           const couple_solution *s, int pass) {
  int marked = 0;
  for (int b = 0; b < n; b++)
    for (int a = 0; a < 3; a++) {
      couple_block *B = &blocks[b];
      if (a == c->axis || c->blocks[a] < 2 || B->cross_state[a] != CROSS_NONE || !B->percolates)
        continue;
      const double fraction = s->cross[3 * b + a];
      if (!(fraction > COUPLE_CROSS_FLOW_FRACTION)) continue;
      B->cross_state[a] = B->spans[a] ? CROSS_WANTED : CROSS_NO_SPAN;
      marked++;
      printf("mdpore couple: pass %d: block (%d,%d,%d): its flow along %c is %.3g of its flow "
             "along %c (> %.2g, campaign.axes: auto): %s\n",
             pass, B->index[0], B->index[1], B->index[2], 'x' + a, fraction, 'x' + c->axis,
             COUPLE_CROSS_FLOW_FRACTION,
             B->spans[a] ? "its k along that axis is measured in the next pass"
                         : "its pore space does not span that axis: impermeable along it");
    }
  return marked;
}

static int run_loop(couple_config *c) {
  int n = c->blocks[0] * c->blocks[1] * c->blocks[2];
  couple_block *blocks = calloc((size_t)n, sizeof *blocks);
  int *new_runs = calloc((size_t)n, sizeof(int));
  double *prev_flux = calloc((size_t)n, sizeof(double)),
         *prev_err = calloc((size_t)n, sizeof(double));
  couple_history h;
  memset(&h, 0, sizeof h);
  couple_solution s = {0};
  double size[3];
  int rc = 1;
  if (!blocks || !new_runs || !prev_flux || !prev_err) goto out;
  if (make_dirs(c->workdir) || couple_make_blocks(c, blocks, size)) goto out;
  int spanning = 0;
  for (int b = 0; b < n; b++) spanning += blocks[b].percolates;
  printf("mdpore couple: %s: %d x %d x %d blocks of %.4g x %.4g x %.4g rc along %c, %d with pore "
         "space spanning the axis; work folder %s\n",
         c->path, c->blocks[0], c->blocks[1], c->blocks[2], size[0], size[1], size[2],
         'x' + c->axis, spanning, c->workdir);
  if (!spanning) {
    fprintf(stderr, "mdpore couple: %s: no block's pore space spans %c: k = 0, nothing to run\n",
            c->path, 'x' + c->axis);
    goto out;
  }
  double gradient = NAN;
  for (int pass = 1; pass <= c->max_passes; pass++) {
    int pending = 0;
    if (couple_run_campaigns(c, blocks, n, pass, &pending)) goto out;
    if (pending) {
      h.pending = 1;
      snprintf(h.stop_reason, sizeof h.stop_reason,
               "pass %d: %d pore-scale runs pending: sbatch %.200s/pass_%d/slurm.sh, then run "
               "mdpore couple %.200s again",
               pass, pending, c->workdir, pass, c->path);
      printf("mdpore couple: %s\n", h.stop_reason);
      couple_write_summary(c, blocks, n, size, NULL, &h);
      rc = 3;
      goto out;
    }
    for (int b = 0; b < n; b++) {
      if (couple_read_law(c, &blocks[b])) goto out;
      for (int a = 0; a < 3; a++)
        if (blocks[b].cross_state[a] == CROSS_WANTED && blocks[b].cross_run[a] &&
            couple_read_cross_law(c, &blocks[b], a))
          goto out;
    }
    if (pass == 1) {
      gradient = drive_gradient(c, blocks, n);
      if (!(gradient > 0)) {
        fprintf(stderr, "mdpore couple: no drive gradient (no SI mapping in the campaigns)\n");
        goto out;
      }
      printf("mdpore couple: sample driven at G = %.5g kT/rc^4 (%s) = %.4g Pa/m with the "
             "campaigns' SI mapping\n",
             gradient,
             c->gradient_si     ? "given in SI"
             : c->gradient_auto ? "auto: geometric mean of the blocks' calibrated ranges"
                                : "given",
             gradient * blocks[0].law.G_Pa_per_m);
      if (gradient < 1e-6)
        printf("mdpore couple: linear response: G is far below any pore-scale run (those run at "
               "G ~ 1e-2): every block law is extrapolated from its calibrated range; fitted "
               "non-Darcy terms are flagged below\n");
    }
    couple_solution_free(&s);
    if (couple_solve(c, blocks, size, gradient, &s)) goto out;
    if (!s.converged) {
      fprintf(stderr, "mdpore couple: pass %d: the continuum solve did not converge\n", pass);
      goto out;
    }
    int added = 0, left_out = 0;
    for (int b = 0; b < n; b++) {
      int fb = feed_back(c, &blocks[b], fabs(s.grad[b]));
      new_runs[b] = fb > 0;
      added += fb > 0;
      if (fb < 0) {
        /* said, because the loop may then stop as converged with this block's law extrapolated
         * beyond the runs it was fitted on */
        left_out++;
        fprintf(stderr,
                "mdpore couple: pass %d: warning: block (%d,%d,%d) sees G = %.4g, outside its "
                "calibrated range [%.4g, %.4g], and its run there was left out of the fit (the "
                "reason: %s/flow_%c.csv, 'left out'): its law is extrapolated at that gradient\n",
                pass, blocks[b].index[0], blocks[b].index[1], blocks[b].index[2], fabs(s.grad[b]),
                blocks[b].law.g_min, blocks[b].law.g_max, blocks[b].workdir, 'x' + c->axis);
      }
    }
    h.left_out[pass - 1] = left_out;
    if (couple_write_pass_table(c, blocks, n, pass, &s, new_runs) ||
        couple_write_field(c, blocks, pass, size, &s))
      goto out;
    /* after the table: it shows the laws this pass solved with */
    const int new_cross = c->axes == COUPLE_AXES_AUTO ? want_cross_axes(c, blocks, n, &s, pass) : 0;
    h.new_cross[pass - 1] = new_cross;
    double worst = 0;
    if (pass > 1)
      for (int b = 0; b < n; b++) {
        double e = sqrt(s.flux_err[b] * s.flux_err[b] + prev_err[b] * prev_err[b]);
        double d = fabs(s.flux[b] - prev_flux[b]);
        worst = fmax(worst, e > 0 ? d / e : (d > 0 ? INFINITY : 0));
      }
    h.passes = pass;
    h.keff[pass - 1] = s.keff;
    h.keff_err[pass - 1] = s.keff_err;
    h.max_dq_sigma[pass - 1] = pass > 1 ? worst : NAN;
    h.new_runs[pass - 1] = added;
    printf("pass %d: k_eff = %.5g +- %.2g rc^2 (%d Monte-Carlo samples), %d new pore-scale runs",
           pass, s.keff, s.keff_err, s.samples_ok, added);
    if (pass > 1) printf(", largest block-flux change %.3g standard errors", worst);
    if (new_cross) printf(", %d block axes to measure across the flow", new_cross);
    printf("\n");
    /* a pass that asked for cross-axis campaigns is not the last: the next one solves with them */
    if (pass > 1 && worst <= c->tolerance_sigma && !new_cross) {
      h.converged = 1;
      snprintf(h.stop_reason, sizeof h.stop_reason,
               "converged at pass %d: every block flux agrees with pass %d within %.3g combined "
               "standard errors (largest change %.3g)%s",
               pass, pass - 1, c->tolerance_sigma, worst,
               left_out ? "; a block's run outside its calibrated range was left out of its fit, "
                          "its law is extrapolated there (see the warning)"
                        : "");
      break;
    }
    memcpy(prev_flux, s.flux, (size_t)n * sizeof(double));
    memcpy(prev_err, s.flux_err, (size_t)n * sizeof(double));
    if (pass == c->max_passes)
      snprintf(h.stop_reason, sizeof h.stop_reason,
               "NOT converged: stopped at loop.max_passes = %d with block fluxes still changing "
               "by %.3g standard errors",
               c->max_passes, worst);
  }
  printf("mdpore couple: %s\n", h.stop_reason);
  double rc_m = NAN;
  for (int b = 0; b < n; b++)
    if (blocks[b].percolates) {
      rc_m = blocks[b].law.length_unit_m;
      break;
    }
  printf("effective permeability along %c: %.5g +- %.2g rc^2 = %.4g m^2 = %.4g +- %.2g nD (rc = "
         "%.3g m; superficial velocity q = Q / A_total)\n",
         'x' + c->axis, s.keff, s.keff_err, s.keff * rc_m * rc_m,
         s.keff * rc_m * rc_m / 9.869233e-22, s.keff_err * rc_m * rc_m / 9.869233e-22, rc_m);
  if (couple_write_summary(c, blocks, n, size, &s, &h)) goto out;
  printf("wrote %s/couple.json and per pass %s/pass_N/{blocks.csv,field.h5,field.xmf}\n",
         c->workdir, c->workdir);
  couple_plot(c);
  rc = h.converged ? 0 : 4;
out:
  couple_solution_free(&s);
  free(blocks);
  free(new_runs);
  free(prev_flux);
  free(prev_err);
  return rc;
}

int cmd_couple(int argc, char **argv) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (argc == 2 && cli_help_flag(argv[1])) {
    cli_help_print(stdout, &couple_help, cli_help_flag(argv[1]));
    return 0;
  }
  if (argc != 2 || argv[1][0] == '-') {
    cli_help_print(stderr, &couple_help, CLI_HELP_SHORT);
    return 2;
  }
  if (size > 1) {
    fprintf(stderr, "mdpore couple: run it as one process; it starts its pore-scale runs itself "
                    "(campaign.np ranks each)\n");
    return 2;
  }
  couple_config c;
  if (couple_config_read(argv[1], &c)) return 1;
  ssize_t len = readlink("/proc/self/exe", c.self_exe, sizeof c.self_exe - 1);
  if (len <= 0) {
    fprintf(stderr, "mdpore couple: cannot find this binary (/proc/self/exe)\n");
    couple_config_free(&c);
    return 1;
  }
  c.self_exe[len] = 0;
  int pargc = 1;
  char *pargv0[] = {argv[0], NULL}, **pargv = pargv0;
  if (PetscInitialize(&pargc, &pargv, NULL, NULL)) {
    couple_config_free(&c);
    return 1;
  }
  int rc = run_loop(&c);
  PetscFinalize();
  couple_config_free(&c);
  return rc;
}
