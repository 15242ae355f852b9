/* A campaign folder read back for --collect: each finished run's summary checked against its own
 * scene and against the manifest before any number of it is used. A folder edited between emit and
 * collect (a run line pointing at another run's folder, a summary copied from elsewhere or edited,
 * run folders swapped) is refused, naming the run's folder and the key that disagrees:
 *   - the run line's axis and g against the header mdpore permeability wrote atop RUN/scene.yaml
 *     ("# mdpore permeability run: axis X, ... g = G per particle; ...");
 *   - the summary's flux.axis against the run line's axis;
 *   - body force: G = n g with the same liquid density n in every run of an axis, so G / g agrees
 *     across them (relative 1e-6);
 *   - the summary's flux.fluid_fraction (the liquid's volume over the box's) alike across the runs
 *     of an axis (one geometry), and not above the image's porosity (10% slack for the fill's
 *     rounding) where no reservoir adds open volume. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "campaign.h"

#define SAME_REL 1e-6

static int same(double a, double b) {
  return fabs(a - b) <= SAME_REL * fmax(fabs(a), fabs(b));
}

/* The axis and g of the header atop RUN/scene.yaml; 0, or -1 with `why`. */
static int scene_header(const camp_run *r, char *axis, double *g, char *why, size_t whylen) {
  char path[CAMP_PATH + 32], line[1024];
  snprintf(path, sizeof path, "%s/scene.yaml", r->dir);
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(why, whylen, "%.4000s: missing: expected the run's scene beside its summary", path);
    return -1;
  }
  const int got = fgets(line, sizeof line, f) != NULL;
  fclose(f);
  const char *a = got ? strstr(line, "# mdpore permeability run: axis ") : NULL;
  const char *gp = got ? strstr(line, " g = ") : NULL;
  if (!a || !gp || sscanf(a + strlen("# mdpore permeability run: axis "), "%c", axis) != 1 ||
      sscanf(gp + 5, "%lf", g) != 1 || *axis < 'x' || *axis > 'z' || !isfinite(*g)) {
    snprintf(why, whylen,
             "%.4000s:1: expected the header '# mdpore permeability run: axis X, ... g = G per "
             "particle' that mdpore permeability writes",
             path);
    return -1;
  }
  return 0;
}

/* The index of a run whose value most of the others share (within SAME_REL), or -1 when no value
 * is held by a strict majority. */
static int majority(const double *v, int n) {
  int best = -1, best_count = 0;
  for (int i = 0; i < n; i++) {
    int count = 0;
    for (int j = 0; j < n; j++) count += same(v[i], v[j]);
    if (count > best_count) best = i, best_count = count;
  }
  return 2 * best_count > n ? best : -1;
}

/* Runs of one axis whose `v` departs from the majority's: named. Returns the count. */
static int outliers(const camp_run *const *runs, const double *v, int n, const char *key,
                    const char *what) {
  if (n < 2) return 0;
  const int ref = majority(v, n);
  int bad = 0;
  for (int i = 0; i < n; i++) {
    if (ref >= 0 && same(v[i], v[ref])) continue;
    if (ref >= 0)
      fprintf(stderr,
              "mdpore permeability: run %s (axis %c, g = %.10g): key '%s': %s %.10g, the other "
              "runs of the axis %.10g: expected the same (a summary of another run or campaign, "
              "or edited?)\n",
              runs[i]->dir, 'x' + runs[i]->axis, runs[i]->g, key, what, v[i], v[ref]);
    else
      fprintf(stderr,
              "mdpore permeability: run %s (axis %c, g = %.10g): key '%s': %s %.10g, and no value "
              "is shared by most runs of the axis: expected one value (summaries of other runs "
              "or campaigns, or edited?)\n",
              runs[i]->dir, 'x' + runs[i]->axis, runs[i]->g, key, what, v[i]);
    bad++;
  }
  return bad;
}

int camp_check_consistency(const campaign *c) {
  int bad = 0;
  for (int axis = 0; axis < 3; axis++) {
    const camp_run *runs[CAMP_MAX_RUNS];
    double ratio[CAMP_MAX_RUNS], fraction[CAMP_MAX_RUNS];
    int n = 0, n_fraction = 0;
    const camp_run *with_fraction[CAMP_MAX_RUNS];
    for (int i = 0; i < c->n_runs; i++) {
      const camp_run *r = &c->runs[i];
      if (r->axis != axis || !r->have) continue;
      char why[CAMP_PATH + 256], scene_axis = 0;
      double scene_g = NAN;
      if (scene_header(r, &scene_axis, &scene_g, why, sizeof why)) {
        fprintf(stderr, "mdpore permeability: run %s: %s\n", r->dir, why);
        bad++;
        continue;
      }
      if (scene_axis != 'x' + axis) {
        fprintf(stderr,
                "mdpore permeability: run %s: key 'axis': the manifest says %c, its scene.yaml %c: "
                "expected the same (run folders swapped or renamed?)\n",
                r->dir, 'x' + axis, scene_axis);
        bad++;
        continue;
      }
      if (!(fabs(scene_g - r->g) <= 1e-12 * fmax(fabs(r->g), fabs(scene_g)))) {
        fprintf(stderr,
                "mdpore permeability: run %s: key 'g': the manifest says %.15g, its scene.yaml "
                "%.15g: expected the same (run folders swapped or renamed?)\n",
                r->dir, r->g, scene_g);
        bad++;
        continue;
      }
      if (r->summary_axis && r->summary_axis != 'x' + axis) {
        fprintf(stderr,
                "mdpore permeability: run %s/summary.json: key 'flux.axis': expected %c, the "
                "axis of its scene (got %s%c%s)\n",
                r->dir, 'x' + axis, r->summary_axis == '?' ? "not an axis" : "'",
                r->summary_axis == '?' ? ' ' : r->summary_axis, r->summary_axis == '?' ? "" : "'");
        bad++;
        continue;
      }
      if (c->drive == CAMP_DRIVE_BODY && !(r->G / r->g > 0)) {
        fprintf(stderr,
                "mdpore permeability: run %s/summary.json: key 'flux.G': G = %.10g with the "
                "scene's body force g = %.10g: expected G = n g, of g's sign\n",
                r->dir, r->G, r->g);
        bad++;
        continue;
      }
      if (isfinite(r->fluid_fraction)) {
        const int open_ends =
            c->drive == CAMP_DRIVE_PRESSURE || c->boundary[axis] == CAMP_BOUNDARY_RESERVOIR;
        if (!(r->fluid_fraction > 0 && r->fluid_fraction <= 1 + 1e-9) ||
            (!open_ends && isfinite(c->porosity) && c->porosity > 0 &&
             r->fluid_fraction > 1.10 * c->porosity)) {
          fprintf(stderr,
                  "mdpore permeability: run %s/summary.json: key 'flux.fluid_fraction': %.6g: "
                  "expected at most the image's porosity %.6g (the manifest's porosity; a summary "
                  "of another geometry?)\n",
                  r->dir, r->fluid_fraction, c->porosity);
          bad++;
          continue;
        }
        with_fraction[n_fraction] = r;
        fraction[n_fraction++] = r->fluid_fraction;
      }
      runs[n] = r;
      ratio[n++] = r->G / r->g;
    }
    if (c->drive == CAMP_DRIVE_BODY)
      bad += outliers(runs, ratio, n, "flux.G", "G / g (the liquid's density n, G = n g) =");
    bad +=
        outliers(with_fraction, fraction, n_fraction, "flux.fluid_fraction", "the fluid fraction");
  }
  if (bad)
    fprintf(stderr,
            "mdpore permeability: %d run(s) of this campaign folder disagree with their scene or "
            "the manifest (above): nothing collected. Rerun them, or restore the folder as "
            "mdpore permeability wrote it\n",
            bad);
  return bad ? -1 : 0;
}
