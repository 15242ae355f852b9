/* mdpore relperm: the steady co-current relative permeability of two liquids in an image
 * (docs/relperm.md, sections 3-4).
 *
 * Per target water saturation, a phase distribution (the morphological drainage or imbibition of
 * the image, mdp_image_morph_at, or a labelled image given with --phase-images) becomes a labelled
 * image whose non-wetting pore voxels the builder fills with that liquid
 * (geometry.fluid_species_labels); both liquids are driven by the same body force along the axis,
 * and the run's flux output gives each liquid's superficial velocity (output.flux.phases). Two
 * single-phase runs (all water, all oil) on the same image, resolution and force are the
 * references: kr_i = q_i / q_i^(1).
 *
 * The campaign machinery is campaign/'s (campaign.h): the resolution from the critical throat, the
 * boundary treatment with its mirror images, the runs as `mdpore run` subprocesses in folders named
 * by a hash of their scene, --jobs, progress, the run checks. This folder adds the liquids, the
 * phase images, the plan of two-phase and reference runs, and the kr collect. */
#ifndef MDPORE_RELPERM_H
#define MDPORE_RELPERM_H

#include "campaign.h"

#define RP_MAX_SATURATIONS 32
#define RP_RUNS (RP_MAX_SATURATIONS + 2)

enum { RP_WET_WATER = 0, RP_WET_OIL = 1 }; /* --wetting: the liquid that wets the walls */
enum { RP_ROLE_TWO = 0, RP_ROLE_WATER, RP_ROLE_OIL }; /* a run: two liquids, or one reference */
/* Where the phase distributions come from: MDP_MORPH_DRAINAGE (0), MDP_MORPH_IMBIBITION (1), or: */
#define RP_MODE_GIVEN 2                /* --phase-images */
#define RP_MANIFEST "relperm_runs.txt" /* not relperm.txt: that is the report collect writes */
#define RP_MANIFEST_HEAD "# mdpore relperm campaign v1"

/* The liquids (relperm_liquids.c): the documented two-liquid set of docs/twophase.md. */
#define RP_A_LIKE -40.0    /* A_ww = A_oo */
#define RP_A_WO -20.0      /* A_wo: the pore example's cross attraction */
#define RP_A_WETTING -40.0 /* the wetting liquid's wall attraction (the campaign water's) */
#define RP_A_NONWETTING -20.0
/* The water-oil tension at the pore core's density 6.2 (docs/twophase.md section 4: 13.24 +- 0.32
 * at bulk density 6.2), for the capillary number. */
#define RP_GAMMA_WO 13.24

typedef struct {
  double M, M_err; /* mu_oil / mu_water (reverse Poiseuille, docs/twophase.md) */
  double gamma_oo, s_oo, gamma_wo, s_wo; /* thermostat of the oil pair and the cross pair */
} rp_liquids;

typedef struct {
  camp_opts co; /* the campaign options relperm shares (input, axis, resolution, boundary, runs) */
  int axis;
  double sw[RP_MAX_SATURATIONS]; /* target water saturations, ascending */
  int n_sw;
  int mode;     /* MDP_MORPH_DRAINAGE | MDP_MORPH_IMBIBITION (0 | 1) */
  int trapping; /* the morphology traps the defending phase (--no-trapping: 0) */
  int wetting;  /* RP_WET_* */
  int ratio;    /* --viscosity-ratio 1|2|5 */
  double g;     /* --force: body force per particle (0: auto from the hydraulic size) */
  double a_wo;  /* --cross-attraction (default RP_A_WO) */
  char phase_images[RP_MAX_SATURATIONS][CAMP_PATH]; /* --phase-images: given distributions */
  int n_phase_images;
  int nw_label_given, nw_label;  /* --nw-label: the non-wetting label of --phase-images */
  char template_path[CAMP_PATH]; /* --template SCENE: the liquids' pairs from it */
} rp_opts;

/* One run's relperm metadata (the manifest relperm.txt; campaign.txt holds the run's folder). */
typedef struct {
  int role;
  double sw_target;        /* RP_ROLE_TWO: the target water saturation (NAN: a given image) */
  double snw_image;        /* the phase image's non-wetting saturation (voxels) */
  double snw_connected;    /* its non-wetting voxels in clusters that touch both faces along the
                               axis, over the pore voxels */
  double snw_disconnected; /* the rest */
  double radius;           /* the morphological step's radius, voxels (NAN: a given image) */
  char image[CAMP_PATH];   /* the run's phase image (absolute) */
} rp_run;

typedef struct {
  campaign c; /* metadata and run folders (campaign.txt) */
  rp_run runs[RP_RUNS];
  int n_runs;
  int axis, wetting, ratio, mode, nw_label, trapping;
  double g;
  rp_liquids liq;
  char boundary[32];
} relperm;

extern const cli_help_page_t rp_help;
/* relperm_args.c: 0, CLI_HELP_SHORT or CLI_HELP_ALL (--help, --help-all asked) or -1 (message
 * printed). */
int rp_parse_args(int argc, char **argv, rp_opts *o);

/* relperm_liquids.c: the liquids of a viscosity ratio (1, 2 or 5); -1 for another. */
int rp_liquids_of(int ratio, rp_liquids *l);
/* The pairs: block of a two-liquid scene (wetting: which liquid the walls attract strongly;
 * walls: the frozen species names), as YAML flow text into out. */
void rp_pairs_text(const rp_liquids *l, int wetting, double a_wo, const char *const *walls,
                   int n_walls, char *out, int len);
/* --template SCENE: reads its pairs (and the species water and oil): 0, or -1 with a message
 * naming the key (a template with one liquid is refused). The pairs text is copied to out. */
int rp_template_pairs(const char *path, char *out, int len);

/* relperm_phases.c: the phase image of a target saturation (morphology or a given image) written to
 * DIR/image.raw, its mirror images (campaign_boundary.c) and its saturations. 0 or -1. */
int rp_phase_image(const rp_opts *o, const mdp_image_t *img, double sw_target, const char *given,
                   uint8_t nw_label, const char *dir, rp_run *r);
/* The first label value not used by img (>= 3), for the non-wetting phase. -1: none. */
int rp_free_label(const mdp_image_t *img);
/* The connected / disconnected non-wetting saturations of a labelled image along axis. */
void rp_nw_connectivity(const mdp_image_t *img, uint8_t nw_label, int axis, rp_run *r);

/* relperm_scene.c: the template of one run (two liquids, or one reference liquid) written to
 * path; the run's scene text from it (camp_scene_text) with every path relative to the run's
 * folder (portable: the run folders travel). */
int rp_write_template(const rp_opts *o, const relperm *rp, int role, const char *image,
                      const char *pairs, const char *path);
char *rp_portable_scene(const char *scene, const char *workdir, const char *run_dir);

/* relperm_plan.c: the name of a mode (drainage, imbibition, given) and back (-1: unknown). */
const char *rp_mode_name(int mode);
int rp_mode_parse(const char *name);
/* relperm_plan.c: the phase images, templates, run folders, manifests and commands. 0 or -1. */
int rp_plan(rp_opts *o, relperm *rp);
int rp_write_manifest(const char *workdir, const relperm *rp);
/* relperm_manifest.c: reads campaign.txt (camp_read_manifest_runs) and relperm_runs.txt; a line
 * that is not the writer's (a key twice or missing, a value out of its range, a number that is not
 * finite, a run line short of fields, more runs than RP_RUNS, a line over 1023 characters) is
 * refused with "FILE:LINE: key 'K': expected ... (got ...)" on stderr. Returns 0 or -1. */
int rp_read_manifest(const char *workdir, relperm *rp);
const char *rp_role_name(int role); /* "two", "water", "oil" */

/* relperm_collect.c: reads the runs, computes kr, writes relperm.csv, relperm.json, the report and
 * the PNG. 0, 1 (some rows left out), or -1. */
int rp_collect(const rp_opts *o, relperm *rp, const char *workdir);

/* cmd_relperm.c */
int cmd_relperm(int argc, char **argv);

#endif
