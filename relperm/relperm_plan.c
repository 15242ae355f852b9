/* The plan of a relperm campaign (docs/relperm.md section 3): the image's metadata, resolution and
 * boundary treatment (camp_make_template: the same as `mdpore permeability`), the phase image of
 * every target saturation and the single-phase image of the references under WORKDIR/phases/, one
 * run folder per scene under WORKDIR/runs/ named by the FNV-1a hash of its (portable) text, the
 * files it names and the binary's version, the manifests (campaign.txt: the campaign's metadata
 * and folders, read by camp_read_manifest; relperm_runs.txt: each run's role and saturations) and
 * commands.txt (one line per run, relative to WORKDIR). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/atomic_file.h"
#include "common/text.h"
#include "relperm.h"

/* --force auto: the body force that would drive the water at this mean pore velocity through a
 * slit of the image's hydraulic size h (u = n g h^2 / (12 mu)), capped at RP_AUTO_G_MAX (the
 * flood's 0.1 heats a slit by 6.6%, docs/twophase.md section 8). */
#define RP_AUTO_VELOCITY 0.1
#define RP_AUTO_G_MAX 0.05

const char *rp_mode_name(int mode) {
  return mode == MDP_MORPH_IMBIBITION ? "imbibition" : mode == RP_MODE_GIVEN ? "given" : "drainage";
}

int rp_mode_parse(const char *name) {
  for (int m = 0; m <= RP_MODE_GIVEN; m++)
    if (!strcmp(name, rp_mode_name(m))) return m;
  return -1;
}

const char *rp_role_name(int role) {
  return role == RP_ROLE_TWO ? "two" : role == RP_ROLE_WATER ? "water" : "oil";
}

/* One run: its scene from the template (camp_scene_text with sub as the options: the mirror
 * images beside the phase image), its folder, the scene written there when new. */
static int add_run(rp_opts *o, relperm *rp, const char *tpl, const char *phase_dir,
                   const char *version, const rp_run *meta) {
  if (rp->n_runs >= RP_RUNS || rp->c.n_runs >= CAMP_MAX_RUNS) {
    fprintf(stderr, "mdpore relperm: more than %d runs\n", RP_RUNS);
    return -1;
  }
  camp_opts sub = o->co;
  snprintf(sub.workdir, sizeof sub.workdir, "%.4000s", phase_dir);
  char *scene = camp_scene_text(tpl, &sub, o->axis, rp->g);
  if (!scene) return -1;
  uint64_t h = 14695981039346656037ULL;
  if (camp_fold_named_files(&h, scene)) { /* the images' bytes, read at their absolute paths */
    free(scene);
    return -1;
  }
  char dir[CAMP_PATH];
  char *portable = NULL;
  int rc = -1;
  /* the folder's name: the portable text (so a moved campaign keeps its runs) */
  portable = rp_portable_scene(scene, o->co.workdir, NULL);
  if (!portable) goto done;
  h = camp_fnv1a(h, portable, strlen(portable));
  h = camp_fnv1a(h, "\n", 1);
  h = camp_fnv1a(h, version, strlen(version));
  snprintf(dir, sizeof dir, "%.4000s/runs/%c-%016llx", o->co.workdir, 'x' + o->axis,
           (unsigned long long)h);
  for (int i = 0; i < rp->c.n_runs; i++)
    if (!strcmp(rp->c.runs[i].dir, dir)) { /* the same phase image as an earlier target */
      fprintf(stderr,
              "mdpore relperm: target Sw %g gives the same phase distribution as target Sw %g (the "
              "nearest step of the morphology): one run for both\n",
              meta->sw_target, rp->runs[i].sw_target);
      rc = 0;
      goto done;
    }
  char header[512];
  if (meta->role == RP_ROLE_TWO)
    snprintf(header, sizeof header,
             "# mdpore relperm run: two liquids, target Sw %.6g, non-wetting saturation of the "
             "phase image %.6g, body force g = %.15g along %c; folder = FNV-1a 64 of the image "
             "files, the text below and '%s'\n",
             meta->sw_target, meta->snw_image, rp->g, 'x' + o->axis, version);
  else
    snprintf(header, sizeof header,
             "# mdpore relperm run: single-phase reference, all %s, body force g = %.15g along %c; "
             "folder = FNV-1a 64 of the image files, the text below and '%s'\n",
             rp_role_name(meta->role), rp->g, 'x' + o->axis, version);
  const size_t len = strlen(header) + strlen(portable) + 1;
  char *text = malloc(len);
  if (!text) goto done;
  snprintf(text, len, "%s%s", header, portable);
  char path[CAMP_PATH + 32];
  snprintf(path, sizeof path, "%s/scene.yaml", dir);
  char *old = text_read_file(path);
  rc = 0;
  if (!old || strcmp(old, text)) rc = make_dirs(dir) || atomic_write_text(path, text);
  free(old);
  free(text);
  if (rc) goto done;
  camp_run *r = &rp->c.runs[rp->c.n_runs++];
  memset(r, 0, sizeof *r);
  r->axis = o->axis;
  r->g = rp->g;
  snprintf(r->dir, sizeof r->dir, "%s", dir);
  rp->runs[rp->n_runs++] = *meta;
done:
  free(portable);
  free(scene);
  return rc;
}

/* The walls of the image: quartz for inorganic voxels, kerogen for organic ones. */
static int wall_names(const mdp_image_t *img, const char **walls) {
  long long org = 0, inorg = 0;
  for (size_t v = 0; v < mdp_image_count(img); v++) {
    org += mdp_image_phase(img, v) == MDP_PHASE_ORGANIC;
    inorg += mdp_image_phase(img, v) == MDP_PHASE_INORGANIC;
  }
  int n = 0;
  if (inorg) walls[n++] = "quartz";
  if (org) walls[n++] = "kerogen";
  return n;
}

int rp_plan(rp_opts *o, relperm *rp) {
  camp_opts *co = &o->co;
  campaign *c = &rp->c;
  char tpl[CAMP_PATH + 64], version[256], err[MDP_IMAGE_ERR_LEN], pairs[4096];
  /* resolution, boundary treatment, metadata and fill, as mdpore permeability's (its single-liquid
   * template.yaml is written too, for reference) */
  if (camp_make_template(co, c, tpl, sizeof tpl)) return -1;
  if (!c->percolates[o->axis]) {
    fprintf(stderr,
            "mdpore relperm: %s: the pore space does not percolate along %c: nothing flows, no "
            "relative permeability\n",
            co->input, 'x' + o->axis);
    return -1;
  }
  if (camp_binary_version(co->self_exe, version, sizeof version)) return -1;
  rp->axis = o->axis;
  rp->wetting = o->wetting;
  rp->ratio = o->ratio;
  rp->mode = o->n_phase_images ? RP_MODE_GIVEN : o->mode;
  rp->trapping = o->trapping;
  snprintf(rp->boundary, sizeof rp->boundary, "%s",
           camp_boundary_name(co->boundary_of_axis[o->axis]));
  if (rp_liquids_of(o->ratio, &rp->liq)) return -1;
  rp->g = o->g;
  if (!(rp->g > 0)) {
    const double mu = camp_water_viscosity(c->fluid_density), h = c->h_hydraulic;
    rp->g = 12 * mu * RP_AUTO_VELOCITY / (c->fluid_density * h * h);
    if (!(rp->g <= RP_AUTO_G_MAX)) rp->g = RP_AUTO_G_MAX;
    rp->g = round(rp->g * 1e4) / 1e4;
    if (!(rp->g > 0)) rp->g = 1e-4;
    fprintf(stderr,
            "mdpore relperm: body force g = %g per particle on both liquids (auto: a mean water "
            "velocity of %g in a slit of the hydraulic size %.3g rc, at most %g; --force G to "
            "set it)\n",
            rp->g, RP_AUTO_VELOCITY, h, RP_AUTO_G_MAX);
  }
  mdp_image_t img;
  mdp_image_read_opts_t ro;
  mdp_image_read_opts_init(&ro);
  if (mdp_image_read(co->input, &ro, &img, err)) {
    fprintf(stderr, "mdpore relperm: %s: %s\n", co->input, err);
    return -1;
  }
  const char *walls[2];
  const int n_walls = wall_names(&img, walls);
  if (o->template_path[0]) {
    if (rp_template_pairs(o->template_path, pairs, sizeof pairs)) goto fail;
  } else {
    rp_pairs_text(&rp->liq, o->wetting, o->a_wo, walls, n_walls, pairs, sizeof pairs);
  }
  const int label = o->nw_label_given ? o->nw_label : rp_free_label(&img);
  if (label < 0) {
    fprintf(stderr, "mdpore relperm: %s: no free label value for the non-wetting liquid\n",
            co->input);
    goto fail;
  }
  rp->nw_label = label;
  rp->n_runs = 0;
  c->n_runs = 0;
  const int n_two = o->n_phase_images ? o->n_phase_images : o->n_sw;
  for (int i = 0; i < n_two; i++) {
    rp_run meta = {.role = RP_ROLE_TWO, .sw_target = o->n_phase_images ? NAN : o->sw[i]};
    char dir[CAMP_PATH + 64];
    if (o->n_phase_images)
      snprintf(dir, sizeof dir, "%.4000s/phases/given_%02d", co->workdir, i);
    else
      snprintf(dir, sizeof dir, "%.4000s/phases/sw_%.4f", co->workdir, o->sw[i]);
    if (rp_phase_image(o, &img, meta.sw_target, o->n_phase_images ? o->phase_images[i] : NULL,
                       (uint8_t)label, dir, &meta))
      goto fail;
    int same = -1; /* a morphological step an earlier target already runs */
    for (int k = 0; k < rp->n_runs && !o->n_phase_images; k++)
      if (rp->runs[k].role == RP_ROLE_TWO && rp->runs[k].radius == meta.radius &&
          rp->runs[k].snw_image == meta.snw_image)
        same = k;
    if (same >= 0) {
      fprintf(stderr,
              "mdpore relperm: target Sw %g: the nearest step of the morphology (non-wetting "
              "saturation %.4f, radius %g voxels) is that of target Sw %g: one run for both\n",
              meta.sw_target, meta.snw_image, meta.radius, rp->runs[same].sw_target);
      continue;
    }
    fprintf(stderr,
            "mdpore relperm: phase image %d/%d: non-wetting saturation %.4f by voxels "
            "(connected %.4f, disconnected %.4f)%s\n",
            i + 1, n_two, meta.snw_image, meta.snw_connected, meta.snw_disconnected,
            o->n_phase_images ? "" : " from the morphological distribution");
    char t[CAMP_PATH + 96];
    snprintf(t, sizeof t, "%s/template.yaml", dir);
    if (rp_write_template(o, rp, RP_ROLE_TWO, meta.image, pairs, t) ||
        add_run(o, rp, t, dir, version, &meta))
      goto fail;
  }
  { /* the references: the image itself, all water and all oil */
    char dir[CAMP_PATH + 64], path[CAMP_PATH + 96];
    snprintf(dir, sizeof dir, "%.4000s/phases/single", co->workdir);
    snprintf(path, sizeof path, "%s/image.raw", dir);
    camp_opts sub = *co;
    snprintf(sub.workdir, sizeof sub.workdir, "%.4000s", dir);
    if (make_dirs(dir) || mdp_image_write_raw(&img, path, err) ||
        camp_write_boundary_images(&sub, &img)) {
      fprintf(stderr, "mdpore relperm: %s: could not write the single-phase image (%s)\n", path,
              err);
      goto fail;
    }
    for (int role = RP_ROLE_WATER; role <= RP_ROLE_OIL; role++) {
      rp_run meta = {.role = role, .sw_target = role == RP_ROLE_WATER ? 1.0 : 0.0};
      meta.snw_image = meta.snw_connected = meta.snw_disconnected = meta.radius = NAN;
      snprintf(meta.image, sizeof meta.image, "%.4000s", path);
      char t[CAMP_PATH + 96];
      snprintf(t, sizeof t, "%s/template_%s.yaml", dir, rp_role_name(role));
      if (rp_write_template(o, rp, role, path, pairs, t) || add_run(o, rp, t, dir, version, &meta))
        goto fail;
    }
  }
  mdp_image_free(&img);
  if (camp_write_manifest(co->workdir, c) || rp_write_manifest(co->workdir, rp)) return -1;
  return 0;
fail:
  mdp_image_free(&img);
  return -1;
}

int rp_write_manifest(const char *workdir, const relperm *rp) {
  char path[CAMP_PATH + 32], tmp[CAMP_PATH + 96];
  snprintf(path, sizeof path, "%s/%s", workdir, RP_MANIFEST);
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  fprintf(f, "%s\n", RP_MANIFEST_HEAD);
  fprintf(f, "axis: %c\nwetting: %s\nviscosity_ratio: %d\nM: %.17g %.17g\n", 'x' + rp->axis,
          rp->wetting == RP_WET_WATER ? "water" : "oil", rp->ratio, rp->liq.M, rp->liq.M_err);
  fprintf(f, "mode: %s\ntrapping: %d\ng: %.17g\nnw_label: %d\nboundary: %s\n",
          rp_mode_name(rp->mode), rp->trapping, rp->g, rp->nw_label, rp->boundary);
  for (int i = 0; i < rp->n_runs; i++) {
    const rp_run *r = &rp->runs[i];
    fprintf(f, "rp: %s %.17g %.17g %.17g %.17g %.17g\n", rp_role_name(r->role), r->sw_target,
            r->snw_image, r->snw_connected, r->snw_disconnected, r->radius);
  }
  /* the commands: one per run, from WORKDIR, with the binary from $MDPORE or the PATH */
  if (atomic_commit(f, tmp, path)) return -1;
  snprintf(path, sizeof path, "%s/commands.txt", workdir);
  f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  for (int i = 0; i < rp->c.n_runs; i++) {
    const char *name = strrchr(rp->c.runs[i].dir, '/');
    fprintf(f, "cd runs/%s && \"${MDPORE:-mdpore}\" run scene.yaml > run.log 2>&1\n",
            name ? name + 1 : rp->c.runs[i].dir);
  }
  return atomic_commit(f, tmp, path);
}
