/* CSV files of the two-phase Darcy solve (see twophase_output.h). */
#include "twophase_output.h"

#include <stdio.h>

#include "darcy_units.h"

static FILE *open_tmp(const char *path, char *tmp, size_t len) {
  snprintf(tmp, len, "%s.tmp", path);
  FILE *f = fopen(tmp, "w");
  if (!f) fprintf(stderr, "mdpore darcy: cannot create '%s'\n", tmp);
  return f;
}

int twophase_output_open(twophase_writer *w, const darcy_config *c) {
  const twophase_config *tp = &c->twophase;
  const char *lu = darcy_unit_label(QTY_LENGTH, c->si), *tu = c->si ? "s" : "reduced time";
  const char *ru = darcy_unit_label(c->problem.dim == 3 ? QTY_RATE : QTY_RATE_2D, c->si);
  const char *pu = darcy_unit_label(QTY_PRESSURE, c->si);
  w->profiles = w->history = NULL;
  if (tp->profiles_csv[0]) {
    if (!(w->profiles = open_tmp(tp->profiles_csv, w->profiles_tmp, sizeof w->profiles_tmp)))
      return -1;
    fprintf(w->profiles,
            "# mdpore darcy two-phase: water saturation of every block (block centres); time in "
            "%s, positions in %s\n",
            tu, lu);
    fprintf(w->profiles, "time,pv_injected,i,j,k,x,y,z,sw\n");
  }
  if (tp->history_csv[0]) {
    if (!(w->history = open_tmp(tp->history_csv, w->history_tmp, sizeof w->history_tmp))) return -1;
    fprintf(w->history,
            "# mdpore darcy two-phase: one row per time step; time in %s, rates in %s, "
            "pressure in %s; water_cut = water/total rate out, oil_recovery = oil produced / "
            "oil in place at time 0\n",
            tu, ru, pu);
    fprintf(w->history, "time,dt,pv_injected,water_cut,oil_recovery,inflow_rate,water_out_rate,"
                        "oil_out_rate,inlet_pressure\n");
  }
  return 0;
}

void twophase_output_profile(twophase_writer *w, const darcy_problem *p, double time,
                             double pv_injected, const double *sw) {
  if (!w->profiles) return;
  for (int k = 0; k < p->n[2]; k++)
    for (int j = 0; j < p->n[1]; j++)
      for (int i = 0; i < p->n[0]; i++)
        fprintf(w->profiles, "%.10g,%.10g,%d,%d,%d,%.10g,%.10g,%.10g,%.10g\n", time, pv_injected, i,
                j, k, (i + 0.5) * p->h[0], (j + 0.5) * p->h[1],
                p->dim == 3 ? (k + 0.5) * p->h[2] : 0.0, sw[darcy_index(p, i, j, k)]);
}

void twophase_output_history(twophase_writer *w, const twophase_history_row *r) {
  if (!w->history) return;
  fprintf(w->history, "%.10g,%.6g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", r->time, r->dt,
          r->pv_injected, r->water_cut, r->oil_recovery, r->inflow_rate, r->water_out, r->oil_out,
          r->inlet_pressure);
}

static int finish(FILE *f, const char *tmp, const char *path) {
  if (!f) return 0;
  int bad = ferror(f);
  bad |= fclose(f) != 0;
  if (bad || rename(tmp, path)) {
    fprintf(stderr, "mdpore darcy: error writing '%s'\n", path);
    remove(tmp);
    return -1;
  }
  return 0;
}

int twophase_output_close(twophase_writer *w, const darcy_config *c) {
  int rc = finish(w->profiles, w->profiles_tmp, c->twophase.profiles_csv);
  rc |= finish(w->history, w->history_tmp, c->twophase.history_csv);
  w->profiles = w->history = NULL;
  return rc ? -1 : 0;
}
