/* A run's result: RUN/summary.json (written atomically by mdpore run at the end of the run, so it
 * exists only for a finished run). Usable when its flux object has finite q, q_err > 0 and G. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "campaign.h"
#include "common/yaml_tree.h"

/* A number under map.key; NAN when absent or null. */
static double num(ytree_t *t, yaml_node_t *map, const char *key) {
  yaml_node_t *n = map ? yt_get(t, map, key) : NULL;
  double v;
  if (!n || yt_is_null(n) || yt_double(t, n, key, &v)) return NAN;
  return v;
}

int camp_read_summary(camp_run *r, char *why, int whylen) {
  char path[CAMP_PATH + 32];
  snprintf(path, sizeof path, "%s/summary.json", r->dir);
  r->have = 0;
  r->last_step = -1;
  if (access(path, R_OK)) {
    snprintf(why, whylen, "%s: no summary (the run has not finished)", path);
    return 0;
  }
  ytree_t t;
  if (yt_load(&t, path, 1)) {
    snprintf(why, whylen, "%s: not a readable summary", path);
    return 0;
  }
  yaml_node_t *root = yt_root(&t);
  yaml_node_t *flux = root && root->type == YAML_MAPPING_NODE ? yt_get(&t, root, "flux") : NULL;
  if (!flux || flux->type != YAML_MAPPING_NODE) {
    snprintf(why, whylen, "%s: key 'flux': expected the flux result (output.flux)", path);
    yt_free(&t);
    return 0;
  }
  r->q = num(&t, flux, "q");
  r->q_err = num(&t, flux, "q_err");
  r->G = num(&t, flux, "G");
  r->G_err = num(&t, flux, "G_err");
  r->fluid_fraction = num(&t, flux, "fluid_fraction");
  yaml_node_t *axis = yt_get(&t, flux, "axis");
  char axis_text[8] = "";
  r->summary_axis = 0;
  if (axis && !yt_is_null(axis)) {
    r->summary_axis = '?'; /* present but not an axis: the consistency check names it */
    if (!yt_string(&t, axis, "axis", axis_text, sizeof axis_text) && axis_text[0] >= 'x' &&
        axis_text[0] <= 'z' && !axis_text[1])
      r->summary_axis = axis_text[0];
  } /* measured G (pressure drive); absent for a body force */
  yaml_node_t *pd = yt_get(&t, flux, "pressure_drop");
  r->dp_balance = pd && pd->type == YAML_MAPPING_NODE ? num(&t, pd, "dp_over_force_per_area") : NAN;
  r->rel_err = num(&t, flux, "relative_error");
  double sf = num(&t, flux, "steady_from_step");
  r->steady_from = isfinite(sf) ? (long long)sf : -1;
  yaml_node_t *reached = yt_get(&t, flux, "reached");
  int b = 0;
  r->reached =
      (!reached || yt_is_null(reached)) ? -1 : (yt_bool(&t, reached, "reached", &b) ? -1 : b);
  r->target_error = num(&t, flux, "target_error");
  yaml_node_t *plateau = yt_get(&t, flux, "plateau");
  int plateau_b = 0;
  r->plateau = (!plateau || yt_is_null(plateau) || yt_bool(&t, plateau, "plateau", &plateau_b))
                   ? -1
                   : plateau_b;
  yaml_node_t *thermo = yt_get(&t, root, "thermo"), *temp;
  temp = thermo && thermo->type == YAML_MAPPING_NODE ? yt_get(&t, thermo, "T") : NULL;
  r->temperature = temp && temp->type == YAML_MAPPING_NODE ? num(&t, temp, "mean") : NAN;
  r->temperature_err = temp && temp->type == YAML_MAPPING_NODE ? num(&t, temp, "err") : NAN;
  r->pressure_steps = num(&t, flux, "pressure_diffusion_steps");
  yaml_node_t *before = yt_get(&t, flux, "before_pressure_diffusion");
  int before_b = 0;
  r->before_pressure =
      before && !yt_is_null(before) && !yt_bool(&t, before, "before_pressure_diffusion", &before_b)
          ? before_b
          : 0;
  yaml_node_t *steady = yt_get(&t, flux, "steady");
  int steady_b = 0;
  r->steady =
      (!steady || yt_is_null(steady) || yt_bool(&t, steady, "steady", &steady_b)) ? -1 : steady_b;
  yaml_node_t *core = yt_get(&t, root, "pore_core_density"); /* geometry runs with a pore core */
  r->core_density = core && core->type == YAML_MAPPING_NODE ? num(&t, core, "mean") : NAN;
  r->core_density_err = core && core->type == YAML_MAPPING_NODE ? num(&t, core, "err") : NAN;
  yaml_node_t *timing = yt_get(&t, root, "timing");
  double steps = num(&t, timing, "steps"), parts = num(&t, timing, "particles");
  r->seconds = num(&t, timing, "loop_seconds");
  r->steps = isfinite(steps) ? (long long)steps : 0;
  const double last = num(&t, root, "last_step"); /* a run continued from a checkpoint: its total */
  r->last_step = isfinite(last) ? (long long)last : -1;
  r->particles = isfinite(parts) ? (long long)parts : 0;
  yt_free(&t);
  if (!isfinite(r->q) || !(r->q_err > 0) || !isfinite(r->q_err) || !isfinite(r->G)) {
    snprintf(why, whylen,
             "%s: key 'flux': expected finite q, q_err > 0 and G (got q %g, q_err %g, G %g; no "
             "steady state within the run?)",
             path, r->q, r->q_err, r->G);
    return 0;
  }
  r->have = 1;
  return 0;
}
