/* mdpore permeability: a permeability campaign over one image or scene (docs/permeability.md).
 *
 * The campaign is three steps over one folder (the work dir):
 *   plan     the scenes, one per (axis, gradient), each in a folder named by a hash of its inputs
 *            (scene text + binary version), and the manifest (campaign.txt) that lists them;
 *   execute  each run in turn (mpiexec -n NP mdpore run, or plain mdpore run at NP = 1); a folder
 *            whose summary.json holds a flux result is reused, so a killed campaign resumes;
 *   collect  the flow table per axis (flowdata/), `mdpore fit` on it, k in rc^2, m^2 and nD, a PNG.
 * --emit-scenes stops after plan (plus a commands list), --collect runs collect alone. */
#ifndef MDPORE_CAMPAIGN_H
#define MDPORE_CAMPAIGN_H

#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include "common/cli_help.h"
#include "common/json_out.h"
#include "common/units.h"
#include "mdpore_image.h"

#define CAMP_MAX_GRADIENTS 64
#define CAMP_MAX_RUNS (3 * CAMP_MAX_GRADIENTS)
#define CAMP_PATH 4096
/* The generated template's wall patch density (docs/walls.md section 16): at 4 particles per rc^3
 * image slits have no slip within 0.07 rc and their pore fluid sits at the bulk density (6.0-6.1)
 * whose viscosity is the default mu; the paper's 8 gives -0.2 rc and a denser, more viscous pore
 * fluid (validation/walls/slit_poiseuille.py --wall-density). geometry.wall_density keeps 8. */
#define CAMP_DEFAULT_WALL_DENSITY 4.0
#define CAMP_WALL_DENSITY_TEXT "4"
/* What the template's walls (density 4) adsorb: fluid particles per rc^2 of pore-solid voxel face
 * beyond the pore core's density, measured at rest on a slit image 16 voxels wide
 * (validation/permeability/wall_adsorption.py: 0.22-0.28 over five runs at 1 and 0.5 rc per voxel,
 * 0.222 +- 0.010 in the longest; 0.26 was the first, and moves a Berea core by 0.4% from 0.23).
 * The template fills the pores at n + Gamma S / V so that the core is at the liquid's density n
 * (docs/permeability.md, "Fill"). */
#define CAMP_DEFAULT_WALL_ADSORPTION 0.26
#define CAMP_WALL_ADSORPTION_TEXT "0.26"

/* How the runs are driven (--drive): a body force on every fluid particle, or an inlet force in an
 * open reservoir added along the flow axis (pressure-driven; docs/permeability.md). */
enum { CAMP_DRIVE_BODY, CAMP_DRIVE_PRESSURE };
/* How the sample's two faces normal to the flow axis meet (--boundary; docs/permeability.md,
 * "Boundaries"): the image as one period, the image followed by its mirror image (a periodic box in
 * which every face meets itself), or an open fluid reservoir between the faces (the pressure drive).
 * AUTO resolves per axis from the seam continuity of the image (meso/image mdp_image_seam). */
enum { CAMP_BOUNDARY_AUTO, CAMP_BOUNDARY_PERIODIC, CAMP_BOUNDARY_MIRROR, CAMP_BOUNDARY_RESERVOIR };
/* Pressure drive: probe slabs of this width, this far outside the sample faces (rc). */
#define CAMP_PROBE_GAP 0.5
#define CAMP_PROBE_WIDTH 0.5

typedef struct {
  char input[CAMP_PATH];            /* IMAGE or SCENE (absolute) */
  int input_is_scene;               /* 1: a .yaml/.yml scene used as the template */
  int axes[3], n_axes;              /* 0 = x, 1 = y, 2 = z */
  int grad_auto;                    /* 1: the auto ladder (campaign_gradients.c) */
  double grads[CAMP_MAX_GRADIENTS]; /* body force per particle g (LIST) */
  int n_grads;                      /* LIST length, or the number of auto points */
  double u_lo, u_hi;                /* auto: mean pore velocity range */
  double target_error;              /* run.target_error (0 < E < 1) */
  long long max_steps;              /* run.steps (0: 20000, or the scene's own) */
  double dt;                        /* run.dt (0: the template's) */
  int np;                           /* ranks per run */
  int jobs;                         /* --jobs: runs at once (default 1; 0: auto) */
  int job_replicas; /* --job-mode: 1 replicas (the runs at once in one process, campaign_replicas.c),
                     0 process, -1 auto (replicas when the runs at once share a GPU) */
  char workdir[CAMP_PATH];
  char emit_dir[CAMP_PATH];    /* --emit-scenes DIR ("" = no) */
  char collect_dir[CAMP_PATH]; /* --collect DIR ("" = no) */
  double rc_per_voxel;         /* image input: voxel edge in rc */
  int rc_per_voxel_given;      /* --rc-per-voxel given (else chosen from the critical throat) */
  double min_throat;           /* image input: least critical throat along a flow axis, rc */
  int force;                   /* --force: run below min_throat (with a warning) */
  double voxel_size_m;         /* --voxel-size (m per voxel; 0 = from the image or the mapping) */
  double viscosity;            /* mu of the fluid in reduced units */
  int viscosity_given;
  double wall_density; /* image input: geometry.wall_density of the template */
  int wall_density_given;
  double wall_adsorption; /* image input: Gamma, particles per rc^2 of wall face (the fill) */
  int wall_adsorption_given;
  char rng[16]; /* image input: dpd_thermostat rng of the template (philox, philox2x32, fast) */
  int rng_given;
  double temperature_K;  /* units: kT of the reduced units */
  int temperature_given; /* --temperature was given (it wins over a scene's units block) */
  long long seed;
  int flux_every;
  char mpiexec[512];        /* the launcher and its flags, split on spaces */
  char models[128];         /* --models for mdpore fit ("" = its default set) */
  char sample[256];         /* sample name of the tables */
  char self_exe[CAMP_PATH]; /* this mdpore binary */
  int drive;                /* CAMP_DRIVE_BODY (default) or CAMP_DRIVE_PRESSURE */
  double reservoir;         /* pressure drive: reservoir length along the axis, rc (default 4) */
  int boundary;             /* --boundary: CAMP_BOUNDARY_* (AUTO by default) */
  double density_tolerance; /* a run whose pore core departs more from the liquid at rest is out */
  double temperature_tolerance; /* a run whose temperature departs more from kT is left out */
  double cavitation_tolerance;  /* a run whose pore core departs more from the fill is left out */
  int require_target;           /* --require-target: a run that missed its target error is out */
  int sides_mirror;        /* --sides mirror: the lateral faces mirrored too (default periodic) */
  int boundary_of_axis[3]; /* resolved per flow axis by camp_resolve_boundaries */
  /* the campaign-level stopping rule (campaign_rounds.c; 0: off, each run stops on its own) */
  double target_error_k;  /* --target-error-k: the relative error of k to reach (0 < E < 1) */
  long long round_steps;  /* --round-steps: the first round's steps of every run (0: default) */
  long long budget_steps; /* --budget-steps: steps of all runs together (0: runs x max steps) */
} camp_opts;

/* One planned run. */
typedef struct {
  int axis;
  double g;            /* body force per particle along the axis */
  char dir[CAMP_PATH]; /* absolute run folder */
  /* filled by execute / collect */
  int have;   /* summary with a flux result read */
  int reused; /* found finished, not rerun */
  double q, q_err, G, rel_err;
  double G_err;      /* pressure drive: error of the measured G (NAN for a body force) */
  double dp_balance; /* pressure drive: dp / (inlet force / A_total) (NAN for a body force) */
  double core_density, core_density_err; /* the pore core's fluid density (NAN: none) */
  double temperature, temperature_err;   /* the run's mean kinetic temperature (NAN: none) */
  int steady;                            /* the flux reached a steady state (1), not (0), -1 ? */
  int before_pressure;   /* 1: the run ended within 3x its pressure-diffusion time */
  double pressure_steps; /* that time in steps (NAN: not in the summary) */
  int reached;           /* 1 met the target, 0 not, -1 no target */
  double target_error;   /* the run's run.target_error (NAN: none) */
  int plateau; /* the blocked error of q reached a plateau (1), not (0: q_err a lower bound), -1 ? */
  long long steps, particles, steady_from; /* steps: of the run's last segment (timing.steps) */
  long long last_step;   /* the step the run has reached (a continued run: its total; -1 ?) */
  long long target_step; /* --target-error-k: the step this round brings the run to (0: none) */
  double seconds;        /* loop seconds of the run */
  char summary_axis;     /* the summary's flux.axis ('x'..'z'; 0: not in the summary) */
  double fluid_fraction; /* the summary's flux.fluid_fraction (NAN: not in the summary) */
} camp_run;

/* The campaign: its metadata (written to and read from the manifest) and its runs. */
typedef struct {
  char sample[256];
  char input[CAMP_PATH];
  char image[CAMP_PATH];  /* image of the geometry ("" for a scene without geometry) */
  double porosity;        /* pore voxels / all voxels (NAN without an image) */
  double rc_per_voxel;    /* NAN without an image */
  double h_hydraulic;     /* 2 V_pore / S_pore, rc (NAN without an image) */
  int percolates[3];      /* along x, y, z (1 without an image) */
  double fluid_density;   /* n, particles per rc^3: the liquid's density in the pore core */
  double fill_density;    /* the template's fill, n + wall_adsorption S / V (NAN: a scene's own) */
  double wall_adsorption; /* Gamma of the fill, particles per rc^2 (NAN: a scene's own) */
  double viscosity;       /* mu, reduced */
  char viscosity_source[256];
  double wall_density;  /* wall particles per rc^3 of the template (NAN: a scene's own) */
  char pair_rng[16];    /* the template's pair random numbers' generator ("": a scene's own) */
  double length_unit_m; /* metres per rc */
  char length_source[256];
  double temperature_K;
  double kT;               /* the scenes' kT, reduced (1 for an IMAGE's template) */
  double energy_J;         /* J per reduced energy unit (NAN: kB temperature_K; a scene's units) */
  double particle_mass_kg; /* kg per reduced mass (NAN: rho_water / n; a scene's units block) */
  double target_error;
  int np;
  int drive;        /* CAMP_DRIVE_* */
  double reservoir; /* pressure drive: the reservoir added, rc (whole voxels) */
  int boundary[3];  /* treatment of the faces normal to each axis (CAMP_BOUNDARY_*; 0: no run) */
  int sides_mirror; /* the lateral faces mirrored (1) or periodic (0) */
  double seam_continuity[3]; /* mdp_image_seam continuity per axis (NAN without an image) */
  /* resolution of an IMAGE input (campaign_resolution.c); throat_voxels -1: not measured */
  int throat_voxels[3];          /* critical throat per axis of the periodic box, voxels */
  double min_throat;             /* the least throat allowed along a flow axis, rc */
  char rc_per_voxel_source[256]; /* how rc_per_voxel was chosen */
  char resolution_warning[512];  /* --force below min_throat: the warning ("" = none) */
  double particles_estimate;     /* fluid + wall particles of the largest run (NAN: none) */
  char regime[32];               /* nanopore | intermediate | continuum ("" = not known) */
  int n_runs;
  camp_run runs[CAMP_MAX_RUNS];
} campaign;

/* cmd_permeability.c: the subcommand. */
int cmd_permeability(int argc, char **argv);

/* campaign_args.c: options. Returns 0, CLI_HELP_SHORT or CLI_HELP_ALL (--help, --help-all asked)
 * or -1 (message printed). */
int camp_parse_args(int argc, char **argv, camp_opts *o);
extern const cli_help_page_t camp_help;

/* campaign_template.c: the scene template (written to WORKDIR/template.yaml for an image) and the
 * campaign metadata from the image; pressure drive: the padded images (an IMAGE input's, or a
 * SCENE's geometry image; a scene without one is refused). A SCENE's geometry sets
 * o->rc_per_voxel. 0 or -1 with a message naming the file/key. */
int camp_make_template(camp_opts *o, campaign *c, char *template_path, int len);

/* campaign_resolution.c: IMAGE input: the critical throat per flow axis (mdp_image_pore_sizes,
 * periodic box), rc_per_voxel chosen from it (min_throat / throat, rounded up to two significant
 * digits) or the given one checked against it (refused below min_throat unless --force), and a
 * report on stderr: throats in voxels and rc, the box, particles, time, rc in metres and the
 * regime. Sets o->rc_per_voxel and the campaign's resolution fields. 0, or -1 with a message. */
int camp_resolution(camp_opts *o, campaign *c);

/* campaign_accuracy.c: --accuracy fast|balanced|precise (docs/accuracy.md); explicit options
 * win. 0, or -1 with a message. */
int camp_accuracy_preset(const char *name, camp_opts *o, int dt_given, int error_given,
                         int steps_given);

/* campaign_gradients.c: the auto ladder (fills o->grads) or a check of the LIST. */
int camp_gradients(camp_opts *o, const campaign *c);
/* Parses "a,b,c" into grads. 0, or -1 with a message into err. */
int camp_parse_gradient_list(const char *text, double *grads, int *n, char *err, int errlen);

/* campaign_template.c: pressure drive: the reservoir in voxels and the padded image of an axis
 * (WORKDIR/reservoir_<axis>.raw). */
int camp_reservoir_voxels(const camp_opts *o);
void camp_padded_image_path(const camp_opts *o, int axis, char *out, int len);

/* campaign_boundary.c: the boundary treatments. */
const char *camp_boundary_name(int boundary);
/* Parses periodic|mirror|reservoir|auto. -1 when unknown. */
int camp_boundary_parse(const char *text);
/* The seam continuity of every axis of the image (box frame) and the treatment of each flow axis:
 * --boundary as given, or for AUTO periodic where the seam continues the image and mirror where it
 * does not. Prints one line per flow axis. */
void camp_resolve_boundaries(camp_opts *o, campaign *c, const mdp_image_t *img);
/* The image a run along axis reads when its faces are mirrored (WORKDIR/mirror_<axis>.raw), and
 * whether the run's box is mirrored along dimension d (flow axis: boundary mirror; lateral: --sides
 * mirror). */
void camp_mirror_image_path(const camp_opts *o, int axis, char *out, int len);
int camp_mirrored_along(const camp_opts *o, int axis, int d);
/* The image a run along flow axis ax reads under its treatment: mirrored along each dimension
 * camp_mirrored_along names, then for a reservoir padded after the high face along ax with
 * camp_reservoir_voxels(o) layers of the smallest pore label (the padded size checked against the
 * index range and the memory limit first). 0 with *out allocated (the caller frees it); 1 when the
 * treatment reads the image itself (periodic, sides periodic); -1 after a message naming the input
 * and the option. Writes nothing. */
int camp_boundary_image(const camp_opts *o, const mdp_image_t *img, int ax, mdp_image_t *out);
/* Writes the per-axis images of the mirror and reservoir treatments (camp_boundary_image) to
 * camp_mirror_image_path or camp_padded_image_path. 0 or -1 with a message. */
int camp_write_boundary_images(const camp_opts *o, const mdp_image_t *img);

/* campaign_scene.c: the scene text of one run (template + axis + g), malloc'd; NULL + message.
 * Pressure drive: g is the equivalent body force per particle, G_nominal = n g; the inlet force per
 * particle is g L_sample / L_slab, so that the inlet force per area n g L_sample equals the pressure
 * drop G_nominal L_sample that drives the sample. */
char *camp_scene_text(const char *template_path, const camp_opts *o, int axis, double g);

/* campaign_hash.c: FNV-1a 64 and the version string of this binary. */
uint64_t camp_fnv1a(uint64_t h, const void *data, size_t n);
int camp_binary_version(const char *exe, char *out, int len);
/* Folds into h the bytes of every absolute file path the scene text names under image:, file:,
 * lammps_data: or snapshot: (the run's cache key holds content, not names). -1 when one cannot be
 * read. */
int camp_fold_named_files(uint64_t *h, const char *scene_text);

/* campaign_plan.c: the scenes and the manifest. 0 or -1. */
int camp_plan(camp_opts *o, campaign *c);
int camp_write_manifest(const char *workdir, const campaign *c);
int camp_read_manifest(const char *workdir, campaign *c);
/* The same, with one_run_per_gradient 0 for campaigns that run several states at one gradient
 * (mdpore relperm: one run per saturation); a run folder listed twice is refused either way. */
int camp_read_manifest_runs(const char *workdir, campaign *c, int one_run_per_gradient);
int camp_write_commands(const char *workdir, const camp_opts *o, const campaign *c);

/* campaign_summary.c: reads DIR/summary.json into r (have = 1 when it holds a usable flux). */
int camp_read_summary(camp_run *r, char *why, int whylen);
/* campaign_consistency.c: every summary read against its run's scene and the manifest (axis, g,
 * G / g and the fluid fraction alike across the runs of an axis, the fluid fraction within the
 * porosity). 0, or -1 after a message per inconsistent run naming its folder and the key. */
int camp_check_consistency(const campaign *c);

/* The standard mDPD water's isothermal bulk modulus K = n dp/dn at n = 6.2 (kT / rc^3): the
 * slope at 6.2 of the quadratic through the measured bulk pressures p(5.5, 6.0, 6.5) = -7.43,
 * -3.41, 24.0 (A = -40, B = 25, rd = 0.75; physics.md section 2, validation/engine/mdpd_eos.py),
 * dp/dn = 50.1; Warren's equation of state gives 327. The runs' flux analysis leaves out the
 * pressure-diffusion transient it sets (output.flux.bulk_modulus, meso/run/run_flux.c). */
#define CAMP_WATER_BULK_MODULUS 311.0

/* campaign_viscosity.c: the viscosity of the campaign's standard mDPD water (an image's template,
 * no --viscosity) at the density its runs measured in the pore core: sets c->viscosity and
 * c->viscosity_source and prints what it did; any other campaign keeps its viscosity. */
void camp_core_viscosity(campaign *c);
/* The standard mDPD water's viscosity at number density n (reduced units; a line through the
 * reverse-Poiseuille ladder of validation/results/engine/viscosity_density, valid 5.9-6.4). */
double camp_water_viscosity(double n);

/* campaign_linear.c: the Darcy range of an axis: the largest number (>= 3, or 2 with 2 rows) of the
 * lowest-G rows (G ascending) that a Darcy law through the origin fits, chi2/dof <= 1 + 3 sqrt(2 /
 * dof), and its k = mu slope with the error (scaled by sqrt(chi2/dof) when above 1). accepted 0:
 * not even the 3 lowest rows fit (their k is reported, flagged; use the all-rows fit). 0, or -1
 * with fewer than 2 rows. */
typedef struct {
  int rows, accepted;
  double k, k_err, chi2_dof, G_max;
} camp_linear;
int camp_darcy_range(const double *G, const double *q, const double *sigma, int n, double mu,
                     camp_linear *out);

/* campaign_checks.c: whether a run's data can enter the Darcy range: its flux steady (and, with
 * require_target, its target error met), its temperature within temperature_tol of kT (else viscous
 * heating, or a liquid colder than the thermostat's), its pore core's density within cavitation_tol
 * of the fill (else cavitation or compression) and within density_tol of the liquid at rest n_rest
 * (the axis's weakest admissible run; <= 0: not checked; else the forcing compresses or expands
 * it). 1 = admissible; 0 = left out, with the failed check's name, the measured value and the
 * reason (naming the value) in flag. */
#define CAMP_DEFAULT_DENSITY_TOLERANCE 0.03
#define CAMP_DEFAULT_CAVITATION_TOLERANCE 0.08
#define CAMP_DEFAULT_TEMPERATURE_TOLERANCE 0.05
typedef struct {
  double fill_density, kT;
  double density_tol, cavitation_tol, temperature_tol;
  int require_target;
} camp_checks;
typedef struct {
  const char *check; /* "" (admissible), unsteady, target_missed, heated, cooled, cavitated,
                        compressed, expanded_by_forcing, compressed_by_forcing */
  double measured;   /* the value the check found out of bounds (NAN: none) */
  char why[256];     /* the reason, naming the measured value and the bound */
} camp_flag;
int camp_run_admissible(const camp_run *r, const camp_checks *lim, double n_rest, camp_flag *flag);
/* The bounds of the campaign's options (o NULL: the defaults) and liquid. */
void camp_checks_of(const camp_opts *o, const campaign *c, camp_checks *lim);
/* rows[0..n) sorted by G: the admissible ones kept in place (G order), their number returned; the
 * left-out ones copied to out[] with their flag in flags[] (*n_out of them; out may be NULL). The
 * liquid at rest is the core of the weakest run that passes the other checks. */
int camp_admit_rows(camp_run **rows, int n, const camp_checks *lim, camp_run **out,
                    camp_flag *flags, int *n_out);
/* Exit status of `mdpore permeability` (run or --collect) when its runs define no Darcy range on
 * some axis, so k is not reported there (1: an error, 2: bad usage). */
#define CAMP_EXIT_NO_DARCY_RANGE 3

/* campaign_rounds.c: the campaign-level stopping rule (--target-error-k; docs/permeability.md,
 * "Stopping on the error of k"). The runs' scenes carry no target error of their own, run.steps the
 * first round and a checkpoint written at the end only (CAMP_CHECKPOINT_FILE; every beyond any run):
 * round 1 runs every run for --round-steps; each later round continues the runs that lower var(k)
 * most per particle-step (camp_allocate) from their checkpoints, until the relative error of the
 * Darcy range's k is at most E on every axis or the step budget is spent. The rounds are recorded
 * in WORKDIR/rounds.txt (a killed campaign replays it, reusing the runs that reached their round's
 * step) and reported on stdout and in WORKDIR/rounds.json and permeability.json. 0, -1, or
 * CAMP_ROUNDS_REFUSED (a budget below the first round). */
#define CAMP_CHECKPOINT_FILE "checkpoint.h5"
#define CAMP_CHECKPOINT_NEVER 2000000000LL
#define CAMP_MAX_ROUNDS 64
#define CAMP_ROUNDS_REFUSED (-2) /* the options refused before any run (bad usage) */
int camp_rounds(const camp_opts *o, campaign *c);
/* The rounds as run, for the report and permeability.json (collect): per round the step each
 * run reached, and per axis the outcome. */
typedef struct {
  int n_rounds;
  long long step[CAMP_MAX_ROUNDS][CAMP_MAX_RUNS]; /* the step run i reached in round r */
  double wall_seconds[CAMP_MAX_ROUNDS];           /* of each round (NAN: an earlier process's) */
  double k_rel_err[CAMP_MAX_ROUNDS][3];           /* after each round, per axis (NAN: none) */
  double share[CAMP_MAX_RUNS];                    /* each run's share of var(k) at the end */
  double target, budget_steps;
  int met[3];            /* per axis: the relative error of k reached the target */
  char stop_why[3][256]; /* per axis: why the rounds stopped */
} camp_rounds_report;
extern camp_rounds_report camp_rounds_done; /* n_rounds 0: the rule was not used */
/* The recorded rounds of WORKDIR/rounds.txt: rep->step[r][i] for every recorded round r (a run a
 * round does not list keeps its step of the round before; a line naming a folder that is not one
 * of c's runs is ignored). No file: no rounds. 0, or -1 with a message naming the file and line. */
int camp_rounds_read_ledger(const char *workdir, const campaign *c, camp_rounds_report *rep);
/* The object "campaign_stop" of permeability.json and rounds.json (nothing when not used). */
void camp_rounds_json(json_out *j, const campaign *c);

/* campaign_allocate.c: the extension of each run in the next round for one axis (pure, tested).
 * Rows: the runs in the Darcy range, with G, their q error s, their steady window T (steps), their
 * particles N and the step they reached. For the weighted least-squares slope through the origin
 * the information is W = sum_i G_i^2 / s_i^2 and var(k) = mu^2 / W (times chi2/dof where the rows
 * scatter); s_i^2 falls as 1 / T_i, so dT more steps of run i add (G_i^2 / (s_i^2 T_i)) dT to W at
 * a cost of N_i dT particle-steps. The relative error e of k falls as 1 / sqrt(W), so E needs
 * W_need = 1.1 W (e / E)^2 (10% over: the errors of short windows are themselves uncertain). The
 * deficit W_need - W goes to the runs in decreasing order of G_i^2 / (s_i^2 T_i N_i), the gain per
 * particle-step, each at most doubling its steps in a round (its error is measured again before it
 * grows further) and within *budget steps (decreased). ext[i]: the steps added to row i, a
 * multiple of quantum. Returns the part of W_need / W - 1 left uncovered (0: covered). */
typedef struct {
  double G, s, T, N;
  long long steps; /* the step the run has reached */
} camp_alloc_row;
#define CAMP_ALLOC_MARGIN 1.1
double camp_allocate(const camp_alloc_row *rows, int n, double rel_err, double target,
                     long long quantum, long long *budget, long long *ext);

/* campaign_exec.c: runs argv (execvp) in dir (NULL: here) with stdout + stderr to log (NULL: ours),
 * in the environment this process started with. Returns the exit status or -1. */
int camp_spawn(const char *dir, char **argv, const char *log);
/* The same without waiting: the child in its own process group, registered so that a signal
 * forwarded by camp_forward_signals(1) reaches it; extra_env (NULL-terminated NAME=VALUE, or NULL)
 * is added to its environment. The pid or -1. camp_spawn_wait waits for it (the pid, or -1) and
 * camp_spawn_forget drops it from the register (for a child reaped by waitpid(-1)). */
pid_t camp_spawn_start(const char *dir, char **argv, const char *log, char *const *extra_env);
pid_t camp_spawn_wait(pid_t pid, int *exit_status);
void camp_spawn_forget(pid_t pid);
/* SIGINT/SIGTERM/SIGHUP to this process: passed on to every registered child's process group, which
 * it waits for, then the default action (on = 1); the default actions (on = 0). */
void camp_forward_signals(int on);
/* campaign_exec.c: runs (or reuses) every run, up to camp_jobs at once, with progress on stderr.
 * 0 or -1. */
int camp_execute(const camp_opts *o, campaign *c);

/* campaign_replicas.c (--job-mode replicas): the runs not reused, in batches of `jobs`, each batch
 * one `mdpore run --replicas` process; the batch's log is each of its runs' run.log (hard links).
 * camp_execute calls it for one-rank runs without --target-error-k at jobs > 1. 0 or -1. */
int camp_execute_replicas(const camp_opts *o, campaign *c, int jobs, char *const *env);

/* campaign_jobs.c: the number of runs at once (--jobs N, or auto: on a CUDA build with a visible
 * GPU the runs whose estimated memory fits in the free memory, at most CAMP_AUTO_JOBS_MAX; else
 * floor(cores / np)), printed with how it was chosen when not 1. */
#define CAMP_MAX_JOBS 64
#define CAMP_AUTO_JOBS_MAX 8
int camp_jobs(const camp_opts *o, const campaign *c, int *on_gpu);
/* The pure rules of auto (unit-tested): GPU: gpus > 0 visible, free_bytes free in all, each run of
 * particles (NAN: not known -> 1) on np ranks; CPU: cores and np. */
int camp_jobs_auto_gpu(double free_bytes, int gpus, double particles, int np);
int camp_jobs_auto_cpu(int cores, int np);
/* The environment the runs get on top of ours when several run at once (NULL-terminated, static):
 * OMP_NUM_THREADS = cores / (jobs np) unless set (OpenMP would start a thread per core in every
 * rank of every run), and OpenMPI's binding off at np > 1 unless set (two mpiexecs would bind
 * their ranks to the same cores). NULL at jobs 1: the runs get what they always got. */
char *const *camp_jobs_env(const camp_opts *o, int jobs);

/* campaign_progress.c: progress and ETA over the whole campaign. */
typedef struct {
  double t0;
  int total, done;
  int jobs;                     /* runs at once at most */
  int running;                  /* runs executing now */
  double run_t0[CAMP_MAX_JOBS]; /* when each of them started */
  double ps_done_all;           /* particle-steps of every finished run (reused too) */
  int n_finished;
  double ps_exec, s_exec; /* particle-steps and seconds of the runs executed now */
} camp_progress;
double camp_now(void);
void camp_progress_start(camp_progress *p, int total, int jobs);
void camp_progress_done(camp_progress *p, const camp_run *r, double wall_seconds);
/* n runs that ended together (a batch of --job-mode replicas, each its wall time the batch's): one
 * line. */
void camp_progress_batch_done(camp_progress *p, const camp_run *const *runs, int n,
                              double wall_seconds);

/* campaign_units.c: the reduced -> SI mapping (the factors: common/units.h). camp_units_make: the
 * campaign's default mapping (kT = kB T, m = rho_water / n); camp_units_of: a campaign's own,
 * with a scene's units block (energy_J, particle_mass_kg) where it set them. */
typedef units_si_t camp_units;
void camp_units_make(double rc_m, double n, double temperature_K, camp_units *u);
void camp_units_of(const campaign *c, camp_units *u);

/* campaign_collect.c: tables, fits, report. 0 or -1. */
int camp_collect(const camp_opts *o, campaign *c, const char *workdir);

#endif
