/* The plan of a campaign: one folder per (axis, gradient) named by the hash of its inputs, holding
 * scene.yaml, and the manifest WORKDIR/campaign.txt that lists the runs and the metadata the
 * collect step needs (so `--collect DIR` works on a folder made by --emit-scenes). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign.h"
#include "common/atomic_file.h"
#include "common/text.h"

#define MANIFEST_NAME "campaign.txt"
#define MANIFEST_HEAD "# mdpore permeability campaign v1"

int camp_plan(camp_opts *o, campaign *c) {
  char template_path[CAMP_PATH], version[256];
  if (camp_make_template(o, c, template_path, sizeof template_path)) return -1;
  if (camp_gradients(o, c)) return -1;
  if (camp_binary_version(o->self_exe, version, sizeof version)) return -1;
  c->n_runs = 0;
  for (int a = 0; a < o->n_axes; a++) {
    int axis = o->axes[a];
    if (!c->percolates[axis]) {
      fprintf(stderr,
              "mdpore permeability: %s: the pore space does not percolate along %c: k_%c%c = "
              "0, no runs\n",
              c->image, 'x' + axis, 'x' + axis, 'x' + axis);
      continue;
    }
    for (int i = 0; i < o->n_grads; i++) {
      char *scene = camp_scene_text(template_path, o, axis, o->grads[i]);
      if (!scene) return -1;
      uint64_t h = camp_fnv1a(14695981039346656037ULL, scene, strlen(scene));
      h = camp_fnv1a(h, "\n", 1);
      if (camp_fold_named_files(&h, scene)) {
        free(scene);
        return -1;
      }
      h = camp_fnv1a(h, version, strlen(version));
      camp_run *r = &c->runs[c->n_runs++];
      memset(r, 0, sizeof *r);
      r->axis = axis;
      r->g = o->grads[i];
      snprintf(r->dir, sizeof r->dir, "%.4000s/runs/%c-%016llx", o->workdir, 'x' + axis,
               (unsigned long long)h);
      char path[CAMP_PATH + 32];
      snprintf(path, sizeof path, "%s/scene.yaml", r->dir);
      char header[512];
      snprintf(header, sizeof header,
               "# mdpore permeability run: axis %c, %s g = %.15g per particle; folder = "
               "FNV-1a 64 of the text below and '%s'\n",
               'x' + axis,
               o->drive == CAMP_DRIVE_PRESSURE ? "pressure drive, equivalent body force"
                                               : "body force",
               o->grads[i], version);
      size_t len = strlen(header) + strlen(scene) + 1;
      char *text = malloc(len);
      if (!text) return -1;
      snprintf(text, len, "%s%s", header, scene);
      char *old = text_read_file(path);
      int rc = 0;
      if (!old || strcmp(old, text)) rc = make_dirs(r->dir) || atomic_write_text(path, text);
      free(old);
      free(text);
      free(scene);
      if (rc) return -1;
    }
  }
  if (c->n_runs == 0) {
    fprintf(stderr, "mdpore permeability: %s: no axis asked for percolates: nothing to run\n",
            o->input);
    return -1;
  }
  return camp_write_manifest(o->workdir, c);
}

int camp_write_manifest(const char *workdir, const campaign *c) {
  char path[CAMP_PATH + 32], tmp[CAMP_PATH + 96];
  snprintf(path, sizeof path, "%s/%s", workdir, MANIFEST_NAME);
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  fprintf(f, "%s\n", MANIFEST_HEAD);
  fprintf(f, "sample: %s\ninput: %s\nimage: %s\n", c->sample, c->input, c->image);
  fprintf(f, "porosity: %.17g\nrc_per_voxel: %.17g\nh_hydraulic: %.17g\n", c->porosity,
          c->rc_per_voxel, c->h_hydraulic);
  fprintf(f, "percolates: %d %d %d\n", c->percolates[0], c->percolates[1], c->percolates[2]);
  fprintf(f, "fluid_density: %.17g\nviscosity: %.17g\nviscosity_source: %s\n", c->fluid_density,
          c->viscosity, c->viscosity_source);
  if (isfinite(c->wall_density)) fprintf(f, "wall_density: %.17g\n", c->wall_density);
  if (isfinite(c->fill_density))
    fprintf(f, "fill_density: %.17g\nwall_adsorption: %.17g\n", c->fill_density,
            c->wall_adsorption);
  if (c->pair_rng[0]) fprintf(f, "pair_rng: %s\n", c->pair_rng);
  fprintf(f, "length_unit_m: %.17g\nlength_source: %s\n", c->length_unit_m, c->length_source);
  fprintf(f, "temperature_K: %.17g\ntarget_error: %.17g\nnp: %d\n", c->temperature_K,
          c->target_error, c->np);
  if (c->energy_J > 0) fprintf(f, "energy_J: %.17g\n", c->energy_J);
  fprintf(f, "kT: %.17g\n", c->kT);
  if (c->particle_mass_kg > 0) fprintf(f, "particle_mass_kg: %.17g\n", c->particle_mass_kg);
  fprintf(f, "drive: %s\nreservoir: %.17g\n", c->drive == CAMP_DRIVE_PRESSURE ? "pressure" : "body",
          c->reservoir);
  fprintf(f, "boundary: %s %s %s\nsides: %s\nseam_continuity: %.6g %.6g %.6g\n",
          camp_boundary_name(c->boundary[0]), camp_boundary_name(c->boundary[1]),
          camp_boundary_name(c->boundary[2]), c->sides_mirror ? "mirror" : "periodic",
          c->seam_continuity[0], c->seam_continuity[1], c->seam_continuity[2]);
  if (c->rc_per_voxel_source[0]) { /* an IMAGE's resolution (campaign_resolution.c) */
    fprintf(f, "throat_voxels: %d %d %d\nmin_throat: %.17g\nrc_per_voxel_source: %s\n",
            c->throat_voxels[0], c->throat_voxels[1], c->throat_voxels[2], c->min_throat,
            c->rc_per_voxel_source);
    fprintf(f, "particles_estimate: %.17g\n", c->particles_estimate);
    if (c->regime[0]) fprintf(f, "regime: %s\n", c->regime);
    if (c->resolution_warning[0]) fprintf(f, "resolution_warning: %s\n", c->resolution_warning);
  }
  for (int i = 0; i < c->n_runs; i++)
    fprintf(f, "run: %c %.17g %s\n", 'x' + c->runs[i].axis, c->runs[i].g, c->runs[i].dir);
  return atomic_commit(f, tmp, path);
}

/* A number: the whole value, finite (or nan where the writer records "not known": `nan_ok`). */
static int num(const char *path, int line, const char *key, const char *v, double *out,
               int nan_ok) {
  char *end;
  *out = strtod(v, &end);
  while (end != v && (*end == ' ' || *end == '\t' || *end == '\r')) end++;
  if (end == v || *end) {
    fprintf(stderr, "mdpore permeability: %s:%d: key '%s': expected a number, got '%.60s'\n", path,
            line, key, v);
    return -1;
  }
  if (isinf(*out) || (isnan(*out) && !nan_ok)) {
    fprintf(stderr, "mdpore permeability: %s:%d: key '%s': expected a finite number, got '%.60s'\n",
            path, line, key, v);
    return -1;
  }
  return 0;
}

/* The manifest's keys other than run:, each read at most once (a second viscosity line would
 * silently win). */
static const char *const manifest_keys[] = {"sample",
                                            "input",
                                            "image",
                                            "porosity",
                                            "rc_per_voxel",
                                            "h_hydraulic",
                                            "percolates",
                                            "fluid_density",
                                            "viscosity",
                                            "viscosity_source",
                                            "wall_density",
                                            "fill_density",
                                            "wall_adsorption",
                                            "pair_rng",
                                            "length_unit_m",
                                            "length_source",
                                            "temperature_K",
                                            "target_error",
                                            "np",
                                            "energy_J",
                                            "kT",
                                            "particle_mass_kg",
                                            "drive",
                                            "reservoir",
                                            "boundary",
                                            "sides",
                                            "seam_continuity",
                                            "throat_voxels",
                                            "min_throat",
                                            "rc_per_voxel_source",
                                            "particles_estimate",
                                            "regime",
                                            "resolution_warning",
                                            NULL};

/* 0 when `k` is a known key seen for the first time (its line recorded), else -1 after a message. */
static int first_sighting(const char *path, int ln, const char *k, int *seen_line) {
  for (int i = 0; manifest_keys[i]; i++) {
    if (strcmp(k, manifest_keys[i])) continue;
    if (seen_line[i]) {
      fprintf(stderr,
              "mdpore permeability: %s:%d: key '%s': given twice (first on line %d): expected "
              "each key once (an edited or concatenated manifest?)\n",
              path, ln, k, seen_line[i]);
      return -1;
    }
    seen_line[i] = ln;
    return 0;
  }
  fprintf(
      stderr,
      "mdpore permeability: %s:%d: key '%.60s': not a key of a campaign manifest (expected "
      "run or one of sample, input, image, porosity, viscosity, ...; see docs/permeability.md)\n",
      path, ln, k);
  return -1;
}

/* A run line that names a folder or an (axis, g) an earlier line named: refused (the second only
 * where each gradient has one run: a relperm campaign runs every saturation at the same g). */
static int duplicate_run(const char *path, int ln, const campaign *c, const camp_run *r,
                         int one_run_per_gradient) {
  for (int i = 0; i < c->n_runs; i++) {
    const camp_run *o = &c->runs[i];
    if (!strcmp(o->dir, r->dir)) {
      fprintf(stderr,
              "mdpore permeability: %s:%d: key 'run': the run folder %s is listed twice: expected "
              "each run once (a duplicated row would count its result twice)\n",
              path, ln, r->dir);
      return -1;
    }
    if (one_run_per_gradient && o->axis == r->axis && o->g == r->g) {
      fprintf(stderr,
              "mdpore permeability: %s:%d: key 'run': axis %c, g = %.17g is listed twice (%s and "
              "%s): expected one run per axis and gradient\n",
              path, ln, 'x' + r->axis, r->g, o->dir, r->dir);
      return -1;
    }
  }
  return 0;
}

int camp_read_manifest(const char *workdir, campaign *c) {
  return camp_read_manifest_runs(workdir, c, 1);
}

int camp_read_manifest_runs(const char *workdir, campaign *c, int one_run_per_gradient) {
  char path[CAMP_PATH + 32], line[3 * CAMP_PATH];
  snprintf(path, sizeof path, "%s/%s", workdir, MANIFEST_NAME);
  FILE *f = fopen(path, "r");
  if (!f) {
    fprintf(stderr,
            "mdpore permeability: %s: %s: expected a campaign folder (made by mdpore "
            "permeability or its --emit-scenes)\n",
            path, strerror(errno));
    return -1;
  }
  memset(c, 0, sizeof *c);
  for (int d = 0; d < 3; d++) c->seam_continuity[d] = NAN;
  c->kT = 1.0;           /* a manifest from before the kT line: an IMAGE's template */
  c->wall_density = NAN; /* a scene's own, or a manifest from before --wall-density */
  c->fill_density = c->wall_adsorption = NAN;  /* a scene's own, or a uniform fill at n */
  c->particles_estimate = c->min_throat = NAN; /* a scene, or a manifest from before them */
  for (int d = 0; d < 3; d++) c->throat_voxels[d] = -1;
  int ln = 0, rc = 0, head = 0;
  int seen_line[sizeof manifest_keys / sizeof manifest_keys[0]] = {0};
  while (!rc && fgets(line, sizeof line, f)) {
    ln++;
    if (!strchr(line, '\n') && !feof(f)) { /* the rest would be read as a line of its own */
      fprintf(stderr, "mdpore permeability: %s:%d: a line longer than %d characters\n", path, ln,
              (int)sizeof line - 2);
      rc = -1;
      break;
    }
    line[strcspn(line, "\n")] = 0;
    if (ln == 1) {
      head = !strcmp(line, MANIFEST_HEAD);
      if (!head) break;
      continue;
    }
    if (line[0] == '#') continue; /* a comment */
    char *colon = strstr(line, ": ");
    if (!colon) continue;
    *colon = 0;
    const char *k = line, *v = colon + 2;
    double x;
    if (strcmp(k, "run") && first_sighting(path, ln, k, seen_line)) {
      rc = -1;
      break;
    }
    if (!strcmp(k, "sample"))
      snprintf(c->sample, sizeof c->sample, "%s", v);
    else if (!strcmp(k, "input"))
      snprintf(c->input, sizeof c->input, "%s", v);
    else if (!strcmp(k, "image"))
      snprintf(c->image, sizeof c->image, "%s", v);
    else if (!strcmp(k, "viscosity_source"))
      snprintf(c->viscosity_source, sizeof c->viscosity_source, "%s", v);
    else if (!strcmp(k, "length_source"))
      snprintf(c->length_source, sizeof c->length_source, "%s", v);
    else if (!strcmp(k, "rc_per_voxel_source"))
      snprintf(c->rc_per_voxel_source, sizeof c->rc_per_voxel_source, "%s", v);
    else if (!strcmp(k, "regime"))
      snprintf(c->regime, sizeof c->regime, "%s", v);
    else if (!strcmp(k, "resolution_warning"))
      snprintf(c->resolution_warning, sizeof c->resolution_warning, "%s", v);
    else if (!strcmp(k, "throat_voxels")) {
      if (sscanf(v, "%d %d %d", &c->throat_voxels[0], &c->throat_voxels[1], &c->throat_voxels[2]) !=
          3) {
        fprintf(stderr, "mdpore permeability: %s:%d: key 'throat_voxels': expected 3 integers\n",
                path, ln);
        rc = -1;
      }
    } else if (!strcmp(k, "pair_rng")) {
      if (strcmp(v, "philox") && strcmp(v, "philox2x32") && strcmp(v, "fast")) {
        fprintf(stderr,
                "mdpore permeability: %s:%d: key 'pair_rng': expected philox, philox2x32 or fast "
                "(got '%.40s')\n",
                path, ln, v);
        rc = -1;
      } else {
        snprintf(c->pair_rng, sizeof c->pair_rng, "%s", v);
      }
    } else if (!strcmp(k, "drive")) {
      c->drive = !strcmp(v, "pressure") ? CAMP_DRIVE_PRESSURE : CAMP_DRIVE_BODY;
      if (strcmp(v, "pressure") && strcmp(v, "body")) {
        fprintf(stderr,
                "mdpore permeability: %s:%d: key 'drive': expected body or pressure (got "
                "'%.40s')\n",
                path, ln, v);
        rc = -1;
      }
    } else if (!strcmp(k, "boundary")) {
      char b[3][16];
      if (sscanf(v, "%15s %15s %15s", b[0], b[1], b[2]) != 3) {
        fprintf(stderr, "mdpore permeability: %s:%d: key 'boundary': expected 3 treatments\n", path,
                ln);
        rc = -1;
      }
      for (int d = 0; !rc && d < 3; d++)
        c->boundary[d] = strcmp(b[d], "none") ? camp_boundary_parse(b[d]) : 0;
    } else if (!strcmp(k, "sides")) {
      c->sides_mirror = !strcmp(v, "mirror");
    } else if (!strcmp(k, "seam_continuity")) {
      if (sscanf(v, "%lf %lf %lf", &c->seam_continuity[0], &c->seam_continuity[1],
                 &c->seam_continuity[2]) != 3 ||
          isinf(c->seam_continuity[0]) || isinf(c->seam_continuity[1]) ||
          isinf(c->seam_continuity[2])) {
        fprintf(stderr, "mdpore permeability: %s:%d: key 'seam_continuity': expected 3 numbers\n",
                path, ln);
        rc = -1;
      }
    } else if (!strcmp(k, "percolates")) {
      if (sscanf(v, "%d %d %d", &c->percolates[0], &c->percolates[1], &c->percolates[2]) != 3) {
        fprintf(stderr, "mdpore permeability: %s:%d: key 'percolates': expected 3 flags\n", path,
                ln);
        rc = -1;
      }
    } else if (!strcmp(k, "run")) {
      char ax;
      camp_run *r = &c->runs[c->n_runs];
      int off = 0;
      if (c->n_runs >= CAMP_MAX_RUNS || sscanf(v, "%c %lf %n", &ax, &r->g, &off) != 2 || ax < 'x' ||
          ax > 'z' || !v[off] || !isfinite(r->g)) {
        fprintf(stderr,
                "mdpore permeability: %s:%d: key 'run': expected 'AXIS G DIR' with a finite G, "
                "got '%.200s'\n",
                path, ln, v);
        rc = -1;
      } else {
        r->axis = ax - 'x';
        snprintf(r->dir, sizeof r->dir, "%s", v + off);
        if (duplicate_run(path, ln, c, r, one_run_per_gradient))
          rc = -1;
        else
          c->n_runs++;
      }
    } else {
      /* nan_ok: the writer records nan for "not known" (a scene input); positive: > 0 */
      struct {
        const char *key;
        double *to;
        int nan_ok, positive;
      } nums[] = {{"porosity", &c->porosity, 1, 0},
                  {"rc_per_voxel", &c->rc_per_voxel, 1, 0},
                  {"h_hydraulic", &c->h_hydraulic, 1, 0},
                  {"fluid_density", &c->fluid_density, 0, 1},
                  {"viscosity", &c->viscosity, 0, 1},
                  {"wall_density", &c->wall_density, 0, 0},
                  {"length_unit_m", &c->length_unit_m, 0, 0},
                  {"temperature_K", &c->temperature_K, 0, 0},
                  {"target_error", &c->target_error, 0, 0},
                  {"reservoir", &c->reservoir, 0, 0},
                  {"energy_J", &c->energy_J, 0, 0},
                  {"kT", &c->kT, 0, 1},
                  {"particle_mass_kg", &c->particle_mass_kg, 0, 0},
                  {"min_throat", &c->min_throat, 1, 0},
                  {"particles_estimate", &c->particles_estimate, 1, 0},
                  {"fill_density", &c->fill_density, 0, 0},
                  {"wall_adsorption", &c->wall_adsorption, 1, 0}};
      for (size_t i = 0; i < sizeof nums / sizeof nums[0]; i++) {
        if (strcmp(k, nums[i].key)) continue;
        rc = num(path, ln, k, v, nums[i].to, nums[i].nan_ok);
        if (!rc && nums[i].positive && !(*nums[i].to > 0)) {
          fprintf(stderr,
                  "mdpore permeability: %s:%d: key '%s': expected a number > 0, got '%.60s'\n",
                  path, ln, k, v);
          rc = -1;
        }
      }
      if (!strcmp(k, "np")) {
        rc = num(path, ln, k, v, &x, 0);
        if (!rc && !(x >= 1 && x <= 1e6 && x == (int)x)) {
          fprintf(stderr,
                  "mdpore permeability: %s:%d: key 'np': expected an integer 1 to 10^6, got "
                  "'%.60s'\n",
                  path, ln, v);
          rc = -1;
        }
        c->np = rc ? 0 : (int)x;
      }
    }
  }
  fclose(f);
  if (!head) {
    fprintf(stderr, "mdpore permeability: %s:1: expected the line '%s'\n", path, MANIFEST_HEAD);
    return -1;
  }
  if (!rc && c->n_runs == 0) {
    fprintf(stderr, "mdpore permeability: %s: expected 'run:' lines (none found)\n", path);
    rc = -1;
  }
  return rc;
}

int camp_write_commands(const char *workdir, const camp_opts *o, const campaign *c) {
  char path[CAMP_PATH + 32], tmp[CAMP_PATH + 96];
  snprintf(path, sizeof path, "%s/commands.txt", workdir);
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  for (int i = 0; i < c->n_runs; i++) {
    if (o->np > 1)
      fprintf(f, "cd '%s' && %s -n %d '%s' run scene.yaml > run.log 2>&1\n", c->runs[i].dir,
              o->mpiexec, o->np, o->self_exe);
    else
      fprintf(f, "cd '%s' && '%s' run scene.yaml > run.log 2>&1\n", c->runs[i].dir, o->self_exe);
  }
  return atomic_commit(f, tmp, path);
}
