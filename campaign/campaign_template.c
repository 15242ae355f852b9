/* The scene template of a campaign and its metadata: from an IMAGE, a generated mDPD water scene
 * (the parameters of validation/walls/slit_poiseuille.py's scene_for) written to
 * WORKDIR/template.yaml; from a SCENE, the scene itself (its geometry image, if any, gives the
 * porosity and the pore size). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign.h"
#include "common/atomic_file.h"
#include "common/units_block.h"
#include "common/yaml_tree.h"
#include "mdpore_image.h"

#define MDPD_WATER_RC_M 8.2e-10 /* physics.md section 4: A = -40 water, N_m = 3 */
#define DEFAULT_FLUID_DENSITY 6.2

/* Hydraulic size h = 2 V_pore / S of the pore space (rc): exact slit width for a slit. Faces
 * between pore and solid voxels, periodic wrap. */
static double hydraulic_size(const mdp_image_t *img, double a) {
  long long faces = 0, pore = 0;
  int n[3] = {img->nx, img->ny, img->nz};
  for (int k = 0; k < n[2]; k++)
    for (int j = 0; j < n[1]; j++)
      for (int i = 0; i < n[0]; i++) {
        size_t v = mdp_image_index(img, i, j, k);
        if (!mdp_image_is_pore(img, v)) continue;
        pore++;
        size_t nb[3] = {mdp_image_index(img, (i + 1) % n[0], j, k),
                        mdp_image_index(img, i, (j + 1) % n[1], k),
                        mdp_image_index(img, i, j, (k + 1) % n[2])};
        size_t pb[3] = {mdp_image_index(img, (i + n[0] - 1) % n[0], j, k),
                        mdp_image_index(img, i, (j + n[1] - 1) % n[1], k),
                        mdp_image_index(img, i, j, (k + n[2] - 1) % n[2])};
        for (int d = 0; d < 3; d++)
          faces += !mdp_image_is_pore(img, nb[d]) + !mdp_image_is_pore(img, pb[d]);
      }
  if (faces == 0) return NAN; /* no wall: the auto ladder needs a LIST */
  return 2.0 * (double)pore * a * a * a / ((double)faces * a * a);
}

/* Reads the image in the box frame (axis_map as a scene's geometry.axis_map, NULL: the image's
 * own axes), fills porosity, percolation, h and the length unit. */
static int image_meta(const char *path, const char *labels, const int *axis_map,
                      double rc_per_voxel, const camp_opts *o, campaign *c, mdp_image_t *img) {
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_read_opts_t ro;
  mdp_image_read_opts_init(&ro);
  if (labels && labels[0]) snprintf(ro.labels, sizeof ro.labels, "%s", labels);
  if (mdp_image_read(path, &ro, img, err)) {
    fprintf(stderr, "mdpore permeability: %s: %s\n", path, err);
    return -1;
  }
  if (axis_map && (axis_map[0] != 0 || axis_map[1] != 1 || axis_map[2] != 2)) {
    /* Percolation, h and the reservoir's padding are along box axes: permute as the run will. */
    mdp_image_t boxed;
    int rc = mdp_image_permute_axes(img, axis_map, &boxed, err);
    mdp_image_free(img);
    if (rc) {
      fprintf(stderr, "mdpore permeability: %s: key 'geometry.axis_map': %s\n", o->input, err);
      return -1;
    }
    *img = boxed;
  }
  mdp_image_stats_t st;
  if (mdp_image_stats(img, &st, err)) {
    fprintf(stderr, "mdpore permeability: %s: %s\n", path, err);
    mdp_image_free(img);
    return -1;
  }
  snprintf(c->image, sizeof c->image, "%s", path);
  c->porosity = st.porosity;
  c->rc_per_voxel = rc_per_voxel;
  for (int d = 0; d < 3; d++) c->percolates[d] = st.spans[d];
  c->h_hydraulic = hydraulic_size(img, rc_per_voxel);
  double vm = mdp_image_voxel_size_m(img);
  if (o->voxel_size_m > 0) {
    c->length_unit_m = o->voxel_size_m / rc_per_voxel;
    snprintf(c->length_source, sizeof c->length_source,
             "--voxel-size %g m / rc_per_voxel %g (the image sets the length scale)",
             o->voxel_size_m, rc_per_voxel);
  } else if (vm > 0) {
    c->length_unit_m = vm / rc_per_voxel;
    snprintf(c->length_source, sizeof c->length_source,
             "the image's voxel size %g m / rc_per_voxel %g (the image sets the length scale)", vm,
             rc_per_voxel);
  }
  return 0;
}

/* The fill of an IMAGE's pores (docs/permeability.md, "Fill"): the walls hold Gamma particles per
 * rc^2 of wall face beyond the core's density, so N = n V + Gamma S fills V at
 * n + Gamma S / V = n + 2 Gamma / h (h = 2 V / S, the hydraulic size) and leaves the core at the
 * liquid's density n, the density whose viscosity k = mu q / G uses. */
static void fill_density(const camp_opts *o, campaign *c) {
  double gamma = o->wall_adsorption;
  if (!o->wall_adsorption_given && o->wall_density != CAMP_DEFAULT_WALL_DENSITY) gamma = 0;
  c->wall_adsorption = gamma;
  c->fill_density = c->fluid_density;
  if (gamma > 0 && c->h_hydraulic > 0) c->fill_density += 2 * gamma / c->h_hydraulic;
}

static int write_image_template(const camp_opts *o, const campaign *c, const mdp_image_t *img,
                                const char *path) {
  long long n_org = 0, n_inorg = 0;
  for (size_t v = 0; v < mdp_image_count(img); v++) {
    int ph = mdp_image_phase(img, v);
    n_org += ph == MDP_PHASE_ORGANIC;
    n_inorg += ph == MDP_PHASE_INORGANIC;
  }
  char tmp[CAMP_PATH + 64];
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  double a = o->rc_per_voxel;
  fprintf(
      f, "# generated by mdpore permeability from %s (standard mDPD water, docs/permeability.md)\n",
      o->input);
  fprintf(f, "name: %s\n", o->sample);
  fprintf(f, "box: {lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], periodic: [true, true, true]}\n",
          img->nx * a, img->ny * a, img->nz * a);
  fprintf(f, "species:\n  - {name: liquid, mass: 1.0}\n");
  if (n_inorg) fprintf(f, "  - {name: quartz, mass: 1.0, frozen: true}\n");
  if (n_org) fprintf(f, "  - {name: kerogen, mass: 1.0, frozen: true}\n");
  fprintf(f, "pairs: {default: {A: -40.0, B: 25.0, gamma: 4.5, rc: 1.0, rd: 0.75}}\n");
  fprintf(f, "density_kernel: warren\nkT: 1.0\n");
  /* philox (the default) leaves the thermostat's options empty: the template, and so the run
   * hashes of earlier campaigns, stay as they were */
  char thermostat[48] = "{}";
  if (strcmp(o->rng, "philox")) snprintf(thermostat, sizeof thermostat, "{rng: %s}", o->rng);
  fprintf(f,
          "effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: %s, "
          "body_force: {liquid: [0.0, 0.0, 0.0]}, bounce_back: {}}\n",
          thermostat);
  fprintf(f, "geometry:\n  image: \"%s\"\n  rc_per_voxel: %.17g\n  flow_axis: x\n", o->input, a);
  /* %g: a uniform fill keeps the text (and the run hashes) of a plain 6.2 */
  fprintf(f, "  fluid_density: %.6g\n  wall_density: %.17g\n  species: {fluid: liquid",
          c->fill_density, o->wall_density);
  if (n_inorg) fprintf(f, ", inorganic: quartz");
  if (n_org) fprintf(f, ", organic: kerogen");
  fprintf(f, "}\n");
  fprintf(f, "initial: {temperature: 1.0}\n");
  fprintf(f, "run: {dt: 0.01, steps: %lld, seed: %lld}\n", o->max_steps ? o->max_steps : 20000LL,
          o->seed);
  fprintf(f,
          "output: {flux: {every: %d, file: flux.csv}, summary: summary.json, progress: false}\n",
          o->flux_every);
  return atomic_commit(f, tmp, path);
}

/* The scene's fluid density as mdpore run's units block finds it (meso/scene/scene_units.c):
 * geometry.fluid_density, else output.flux.density, else the first fill of a species that is not
 * frozen. NAN when none. */
static double scene_fluid_density(ytree_t *t, yaml_node_t *root, char *source, int len) {
  yaml_node_t *g = yt_get(t, root, "geometry"), *n, *out, *flux, *init, *fill, *species;
  double v;
  if (g && g->type == YAML_MAPPING_NODE) {
    snprintf(source, len, "geometry.fluid_density");
    n = yt_get(t, g, "fluid_density");
    return n && !yt_double(t, n, "geometry.fluid_density", &v) ? v : DEFAULT_FLUID_DENSITY;
  }
  if ((out = yt_get(t, root, "output")) && out->type == YAML_MAPPING_NODE &&
      (flux = yt_get(t, out, "flux")) && flux->type == YAML_MAPPING_NODE &&
      (n = yt_get(t, flux, "density")) && !yt_double(t, n, "output.flux.density", &v)) {
    snprintf(source, len, "output.flux.density");
    return v;
  }
  if (!(init = yt_get(t, root, "initial")) || init->type != YAML_MAPPING_NODE ||
      !(fill = yt_get(t, init, "fill")) || fill->type != YAML_SEQUENCE_NODE)
    return NAN;
  species = yt_get(t, root, "species");
  for (int k = 0; k < yt_seq_size(fill); k++) {
    yaml_node_t *f = yt_seq_item(t, fill, k), *sp, *d;
    char name[128];
    if (!f || f->type != YAML_MAPPING_NODE || !(sp = yt_get(t, f, "species")) ||
        yt_string(t, sp, "initial.fill.species", name, sizeof name))
      continue;
    int frozen = 0; /* the species' frozen flag */
    for (int i = 0; species && species->type == YAML_SEQUENCE_NODE && i < yt_seq_size(species);
         i++) {
      yaml_node_t *e = yt_seq_item(t, species, i), *nm, *fr;
      char other[128];
      if (e && e->type == YAML_MAPPING_NODE && (nm = yt_get(t, e, "name")) &&
          !yt_string(t, nm, "species.name", other, sizeof other) && !strcmp(other, name) &&
          (fr = yt_get(t, e, "frozen")))
        yt_bool(t, fr, "species.frozen", &frozen);
    }
    if (!frozen && (d = yt_get(t, f, "density")) && !yt_double(t, d, "initial.fill.density", &v)) {
      snprintf(source, len, "initial.fill[%d].density", k);
      return v;
    }
  }
  return NAN;
}

/* A scene's `units:` block (common/units_block.h, as mdpore run reads it): the length, energy and
 * mass units of the campaign, except those the command line gives (--voxel-size, --temperature
 * win). 0 (also without a block) or -1 after the block's error message. */
static int scene_units(const camp_opts *o, ytree_t *t, yaml_node_t *root, campaign *c) {
  yaml_node_t *b = yt_get(t, root, "units"), *n;
  units_context_t ctx;
  units_context_init(&ctx);
  if ((n = yt_get(t, root, "kT")) && yt_double(t, n, "kT", &ctx.kT)) return -1;
  c->kT = ctx.kT; /* the runs' temperature check */
  if (!b) return 0;
  ctx.rc_per_voxel = c->rc_per_voxel;
  ctx.density = scene_fluid_density(t, root, ctx.density_source, sizeof ctx.density_source);
  units_mapping_t m;
  if (units_block_read(t, b, "units", &ctx, &m)) return -1;
  if (!(o->voxel_size_m > 0)) {
    c->length_unit_m = m.si.rc_m;
    snprintf(c->length_source, sizeof c->length_source, "the scene's units block: %.200s",
             m.length_source);
  }
  if (!o->temperature_given) { /* kB T, or the block's energy unit (also kB T / kT at kT != 1) */
    c->temperature_K = m.temperature_K;
    if (m.energy_given || ctx.kT != 1.0) c->energy_J = m.si.kT_J;
  }
  /* The block's mass (its own, from tau, N_m m_water or the water of a particle's volume at the
   * block's density); for a length the command line changed, only a mass or tau the block gave. */
  if (!(o->voxel_size_m > 0) || m.mass_given || m.tau_given) c->particle_mass_kg = m.si.mass_kg;
  if (o->voxel_size_m > 0 || o->temperature_given)
    fprintf(stderr, "mdpore permeability: note: %s%s%s %s over the scene's units block (%s)\n",
            o->voxel_size_m > 0 ? "--voxel-size" : "",
            o->voxel_size_m > 0 && o->temperature_given ? " and " : "",
            o->temperature_given ? "--temperature" : "",
            o->voxel_size_m > 0 && o->temperature_given ? "win" : "wins", o->input);
  return 0;
}

/* Where a scene without geometry gets its particles (for the pressure drive's refusal). */
static const char *particle_source(ytree_t *t, yaml_node_t *root) {
  static const char *const keys[] = {"fill", "lammps_data", "snapshot"};
  static const char *const names[] = {"initial.fill", "initial.lammps_data", "initial.snapshot"};
  yaml_node_t *init = yt_get(t, root, "initial");
  if (yt_get(t, root, "restart")) return "restart";
  for (int k = 0; init && init->type == YAML_MAPPING_NODE && k < 3; k++)
    if (yt_get(t, init, keys[k])) return names[k];
  return "neither geometry.image nor initial";
}

/* A scene template: its geometry (image, rc_per_voxel, fluid density, labels, axis_map), if any,
 * and its units block. With geometry, the image (in the box frame) is left in *img and *have_img
 * set, for the pressure drive's padding (the caller frees it). */
static int scene_meta(const camp_opts *o, campaign *c, mdp_image_t *img, int *have_img) {
  ytree_t t;
  *have_img = 0;
  if (yt_load(&t, o->input, 0)) return -1;
  int rc = -1;
  yaml_node_t *root = yt_root(&t), *g, *n;
  if (!root || yt_expect_map(&t, root, "")) goto out;
  if (!(g = yt_get(&t, root, "geometry"))) {
    if (o->drive == CAMP_DRIVE_PRESSURE) {
      /* The reservoir is pore voxels added to an image; particles from elsewhere have none. */
      fprintf(stderr,
              "mdpore permeability: %s: key 'geometry.image': --drive pressure pads the sample's "
              "image with an open fluid reservoir along the flow axis, but this scene's particles "
              "come from %s, not from an image: there is no image to pad. Give the IMAGE, or a "
              "scene with geometry: {image: ...}; or name effects.inlet_force with its sample in "
              "the scene and run it with mdpore run (docs/scene-format.md)\n",
              o->input, particle_source(&t, root));
      goto out;
    }
    rc = scene_units(o, &t, root, c);
    goto out;
  }
  if (yt_expect_map(&t, g, "geometry")) goto out;
  char image[CAMP_PATH], labels[256] = "", path[2 * CAMP_PATH];
  if (!(n = yt_need(&t, g, "image", "geometry.image", "a segmented image")) ||
      yt_string(&t, n, "geometry.image", image, sizeof image))
    goto out;
  if (image[0] == '/')
    snprintf(path, sizeof path, "%s", image);
  else {
    char dir[CAMP_PATH];
    snprintf(dir, sizeof dir, "%s", o->input);
    char *slash = strrchr(dir, '/');
    *slash = 0;
    snprintf(path, sizeof path, "%s/%s", dir, image);
  }
  double a = NAN;
  if ((n = yt_get(&t, g, "rc_per_voxel")) && yt_double(&t, n, "geometry.rc_per_voxel", &a))
    goto out;
  if ((n = yt_get(&t, g, "voxels_per_rc"))) {
    if (yt_double(&t, n, "geometry.voxels_per_rc", &a)) goto out;
    a = 1.0 / a;
  }
  if (!(a > 0)) {
    yt_error(&t, g, "geometry", "expected rc_per_voxel or voxels_per_rc > 0");
    goto out;
  }
  if ((n = yt_get(&t, g, "fluid_density")) &&
      yt_double(&t, n, "geometry.fluid_density", &c->fluid_density))
    goto out;
  if ((n = yt_get(&t, g, "labels")) && yt_string(&t, n, "geometry.labels", labels, sizeof labels))
    goto out;
  int axis_map[3] = {0, 1, 2};
  if ((n = yt_get(&t, g, "axis_map"))) { /* checked in full by mdpore run */
    char word[8];
    if (yt_expect_seq(&t, n, "geometry.axis_map")) goto out;
    for (int d = 0; d < 3 && d < yt_seq_size(n); d++)
      if (!yt_string(&t, yt_seq_item(&t, n, d), "geometry.axis_map", word, sizeof word) &&
          word[0] >= 'x' && word[0] <= 'z' && !word[1])
        axis_map[d] = word[0] - 'x';
  }
  if (image_meta(path, labels, axis_map, a, o, c, img)) goto out;
  *have_img = 1;
  rc = scene_units(o, &t, root, c);
  if (rc) {
    mdp_image_free(img);
    *have_img = 0;
  }
out:
  yt_free(&t);
  return rc;
}

int camp_reservoir_voxels(const camp_opts *o) {
  return (int)lround(o->reservoir / o->rc_per_voxel);
}

void camp_padded_image_path(const camp_opts *o, int axis, char *out, int len) {
  snprintf(out, len, "%.4000s/reservoir_%c.raw", o->workdir, 'x' + axis);
}

int camp_make_template(camp_opts *o, campaign *c, char *template_path, int len) {
  snprintf(c->sample, sizeof c->sample, "%s", o->sample);
  snprintf(c->input, sizeof c->input, "%s", o->input);
  c->image[0] = 0;
  c->porosity = c->rc_per_voxel = c->h_hydraulic = NAN;
  c->length_unit_m = NAN;
  c->length_source[0] = 0;
  for (int d = 0; d < 3; d++) c->percolates[d] = 1;
  c->fluid_density = DEFAULT_FLUID_DENSITY;
  c->fill_density = c->wall_adsorption = NAN;
  c->viscosity = o->viscosity;
  snprintf(c->viscosity_source, sizeof c->viscosity_source, "%s",
           o->viscosity_given ? "--viscosity"
                              : "mDPD A=-40 B=25 gamma=4.5 rd=0.75 at n=6.07 "
                                "(validation/engine/viscosity.py, reverse Poiseuille)");
  c->wall_density = o->input_is_scene ? NAN : o->wall_density;
  snprintf(c->pair_rng, sizeof c->pair_rng, "%s", o->input_is_scene ? "" : o->rng);
  c->temperature_K = o->temperature_K;
  c->kT = 1.0;
  c->energy_J = c->particle_mass_kg = NAN;
  c->target_error = o->target_error;
  c->np = o->np;
  c->drive = o->drive;
  if (make_dirs(o->workdir)) return -1;
  if (o->input_is_scene) {
    if (!o->viscosity_given)
      fprintf(stderr,
              "mdpore permeability: note: k = mu q / G uses the standard mDPD water's mu (%g "
              "at n = 6.07; at the pore core's density where the runs measure one); give "
              "--viscosity for the fluid of %s\n",
              o->viscosity, o->input);
    mdp_image_t img;
    int have_img, rc = 0;
    if (scene_meta(o, c, &img, &have_img)) return -1;
    camp_resolve_boundaries(o, c, have_img ? &img : NULL);
    if (have_img) {
      /* The scene's voxel edge sets the reservoir's whole voxels and the run scenes' box. */
      o->rc_per_voxel = c->rc_per_voxel;
      rc = camp_write_boundary_images(o, &img);
      mdp_image_free(&img);
    }
    if (rc) return -1;
    snprintf(template_path, len, "%s", o->input);
  } else {
    mdp_image_t img;
    /* the boundaries first (they set which faces the critical throat may wrap through), then
     * o->rc_per_voxel from the throat */
    if (camp_resolution(o, c)) return -1;
    if (image_meta(o->input, NULL, NULL, o->rc_per_voxel, o, c, &img)) return -1;
    snprintf(template_path, len, "%s/template.yaml", o->workdir);
    fill_density(o, c);
    if (c->h_hydraulic > 0)
      fprintf(stderr,
              "  fill %.4g particles per rc^3 of pore: the liquid's %g in the core plus what the "
              "walls adsorb (%g per rc^2 of wall face x S / V = 2 / h = %.3g per rc%s)\n",
              c->fill_density, c->fluid_density, c->wall_adsorption, 2 / c->h_hydraulic,
              c->wall_adsorption > 0 ? ""
              : o->wall_density != CAMP_DEFAULT_WALL_DENSITY
                  ? "; none: measured for the default wall density only, give --wall-adsorption"
                  : "; none: --wall-adsorption 0");
    int rc = write_image_template(o, c, &img, template_path);
    if (!rc) rc = camp_write_boundary_images(o, &img);
    mdp_image_free(&img);
    if (rc) return -1;
  }
  c->reservoir = o->drive == CAMP_DRIVE_PRESSURE ? camp_reservoir_voxels(o) * o->rc_per_voxel : 0;
  if (!(c->length_unit_m > 0)) {
    c->length_unit_m = MDPD_WATER_RC_M;
    snprintf(c->length_source, sizeof c->length_source,
             "mDPD water mapping rc = 0.82 nm (A = -40, N_m = 3 water molecules per particle; "
             "physics.md section 4); no voxel size given");
  }
  return 0;
}
