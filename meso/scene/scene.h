/* The scene: everything a run is told by its scene file, after parsing and validation.
 * Parsed by meso/scene/scene_parse.c (YAML, libyaml); consumed by the engine, the
 * initial-configuration builders and the outputs. Plain data, no pointers into parser memory. */
#ifndef MESO_SCENE_SCENE_H
#define MESO_SCENE_SCENE_H

#include "common/units.h"
#include "physics/hd.h"

#include <stddef.h>
#include <stdint.h>

#define SCENE_MAX_SPECIES MESO_MAX_SPECIES
#define SCENE_MAX_FILLS 16
#define SCENE_NAME_LEN 64
#define SCENE_PATH_LEN 1024

/* Effects a scene may name: their ids and names live in the registry (meso/effects/effect_list.h);
 * the scene keeps, per id, whether it is named and the options its effect parsed (plain bytes the
 * effect casts to its own struct: SCENE_EFFECT_OPTIONS). An effect not named costs nothing. */
#define SCENE_MAX_EFFECTS 32
#define SCENE_EFFECT_OPTION_BYTES 512
typedef union {
  unsigned char bytes[SCENE_EFFECT_OPTION_BYTES];
  double align; /* 8-byte alignment for the effects' structs (plain C and C++) */
} scene_effect_options_t;
/* The options of effect `id` as its struct type (the effect's file checks the size fits). */
#define SCENE_EFFECT_OPTIONS(scene, id, type) ((type *)(void *)(scene)->effect_options[id].bytes)

typedef struct {
  char name[SCENE_NAME_LEN];
  double mass;
  int frozen; /* 1: takes part in density and forces, never integrated */
  /* A frozen species may move as a rigid body at a fixed velocity (species[].velocity; plane
   * Couette): x += velocity dt every step, v = velocity in every pair term. moving = 1 when any
   * component is non-zero (then exactly one is, along a periodic box axis: move_axis). */
  double velocity[3];
  int moving, move_axis;
} scene_species_t;

/* Largest exponent s of a pair's thermostat weight (pairs.X.s, 0 < s <= this). */
#define SCENE_PAIR_S_MAX 2.0

/* Pair parameters of one species pair (symmetric: pair[a][b] == pair[b][a]). */
typedef struct {
  double A;     /* mDPD attraction amplitude (mdpd_attraction) or DPD a (dpd_conservative) */
  double B;     /* many-body repulsion amplitude (mdpd_repulsion)                           */
  double gamma; /* dissipation (dpd_thermostat)                                             */
  double rc;    /* cutoff of the attraction / conservative force and of the thermostat    */
  double rd;    /* cutoff of the many-body repulsion and of the density kernel (rd <= rc) */
  double s;     /* exponent of the thermostat weight w_R = (1 - r/rc)^s of this pair (pairs.X.s);
                   0 = not set: dpd_thermostat's exponent (1 unless effects.dpd_thermostat.exponent) */
} scene_pair_t;

enum scene_fill_mode { FILL_LATTICE = 0, FILL_RANDOM = 1 };

/* Optional shape cut out of a fill region (docs/twophase.md): only the candidate sites inside
 * (or, with `outside`, outside) a cylinder or a sphere are kept: drops, threads and the phase
 * around them. FILL_SHAPE_NONE: the whole axis-aligned region (the default). */
enum scene_fill_shape { FILL_SHAPE_NONE = 0, FILL_SHAPE_CYLINDER = 1, FILL_SHAPE_SPHERE = 2 };

/* Fill an axis-aligned region of the box with one species at a number density. */
typedef struct {
  int species;
  int mode; /* enum scene_fill_mode */
  double density;
  double lo[3], hi[3];
  int shape;        /* enum scene_fill_shape                                               */
  int shape_axis;   /* cylinder: its axis (0..2); the centre's coordinate on it is unused   */
  double centre[3]; /* cylinder axis point or sphere centre (rc, box frame)                */
  double radius;    /* > 0                                                                   */
  int outside;      /* 1: keep the sites outside the shape instead of inside                 */
} scene_fill_t;

enum scene_init_kind { INIT_FILL = 0, INIT_LAMMPS_DATA = 1, INIT_SNAPSHOT = 2, INIT_GEOMETRY = 3 };

/* The scene's geometry as a segmented image (docs/scene-format.md, `geometry:`): wall particles in
 * the solid voxels near the pore space, copied from a database of pre-equilibrated patches, one
 * wall species per solid phase, and fluid in the pore voxels (meso/populate/image_walls.c). */
enum scene_isolated_pores { ISOLATED_EMPTY = 0, ISOLATED_FILL = 1 };
typedef struct {
  int on;                       /* 1: a `geometry:` block was given                        */
  char image[SCENE_PATH_LEN];   /* image file (any format mdpore image reads), relative to the
                                      scene file                                               */
  char labels[256];             /* label map ("pore=0,inorganic=1,organic=2"; "" = the file's
                                      own or the default)                                      */
  double rc_per_voxel;          /* voxel edge in rc                                         */
  int axis_map[3];              /* box axis d is image axis axis_map[d] (default 0, 1, 2)   */
  int flow_axis;                /* box axis the pore space must span (0..2)                */
  double wall_thickness;        /* solid kept within this distance (rc) of a pore voxel;
                                      <= 0: rc + rd of the fluid-wall pairs                    */
  double wall_density;          /* wall particles per rc^3 (8)                               */
  double fluid_density;         /* fluid particles per rc^3 (6.2)                            */
  double min_wall_distance;     /* no fluid particle closer than this to a wall particle    */
  int isolated_pores;           /* enum scene_isolated_pores: pores not spanning flow_axis  */
  int fluid_species;            /* species of the fluid                                     */
  int organic_species;          /* wall species of organic voxels (-1: none in the image)   */
  int inorganic_species;        /* wall species of inorganic voxels (-1: none)              */
  char patches[SCENE_PATH_LEN]; /* patch database file ("" = built and cached by mdpore)    */
  uint64_t patch_seed;          /* seed of the patch choice and of the database             */
  int strict; /* 1: a mobile particle inside a solid voxel stops the run (default: counted) */
  /* geometry.fluid_region: when on, fluid only inside [fluid_lo, fluid_hi] (rc, box frame) */
  int fluid_region;
  double fluid_lo[3], fluid_hi[3];
  /* geometry.fluid_species_regions: a fluid particle the builder places inside region k (its
   * box and its cylinder or sphere, the first region that holds it) takes the mobile species
   * species_region[k].species instead of fluid_species (two liquids in one image) */
  int n_species_regions;
  scene_fill_t species_region[SCENE_MAX_FILLS];
  /* geometry.fluid_species_labels: a fluid particle the builder places in a pore voxel of image
   * label species_label[k] takes the mobile species species_label_species[k] (regions still
   * override); e.g. a non-wetting phase from `mdpore image drainage --at` */
  int n_species_labels;
  int species_label[SCENE_MAX_FILLS];
  int species_label_species[SCENE_MAX_FILLS];
} scene_geometry_t;

typedef struct {
  int kind; /* enum scene_init_kind */
  int n_fill;
  scene_fill_t fill[SCENE_MAX_FILLS];
  char path[SCENE_PATH_LEN]; /* LAMMPS data file or HDF5 snapshot (relative paths: to the scene
                                file) */
  double temperature; /* initial Maxwell-Boltzmann velocities at this kT (default: scene kT) */
} scene_init_t;

/* One periodic output; every == 0 means off. Paths are relative to the working directory. */
typedef struct {
  long every;
  char path[SCENE_PATH_LEN];
} scene_output_t;

typedef struct {
  long every; /* sample every this many steps */
  long start; /* first step that is averaged */
  int axis;   /* 0, 1, 2 = x, y, z */
  int nbins;
  char path[SCENE_PATH_LEN];
  /* Radial profile (output.profile.radial; 0: a slab profile along `axis`): bins in the
   * distance from the line through `centre` along `axis` (1, cylinder) or from `centre`
   * (2, sphere), out to rmax; with centre_species >= 0 the centre follows, at each sample, the
   * periodic centre of mass of that species (a drop or thread that drifts). */
  int radial;
  double centre[3];
  double rmax;
  int centre_species;
} scene_profile_t;

/* Flux time series along one axis (output.flux; docs/scene-format.md): the superficial (Darcy)
 * velocity q = Q / A_total of the counted species, sampled every `every` steps (0 = off). */
typedef struct {
  long every;
  int axis;              /* 0, 1, 2 = x, y, z */
  unsigned species_mask; /* bit s: species s is counted (default: every mobile species) */
  double density;      /* > 0: the fluid number density n of Q (output.flux.density); 0: the scene's
                     own (fill or geometry.fluid_density) */
  double bulk_modulus; /* > 0: the liquid's isothermal bulk modulus K = n dp/dn
                          (output.flux.bulk_modulus), which sets the pressure-diffusion transient
                          the steady-state analysis leaves out (run/run_flux.c); 0: none */
  int n_phases;        /* output.flux.phases: species with their own q column */
  int phase_species[SCENE_MAX_SPECIES]; /* (0: none; each counted, listed once) */
  char path[SCENE_PATH_LEN];
} scene_flux_t;

/* Run guardrails beyond the per-step checks (`guard:`, docs/scene-format.md "Guardrails"). */
typedef struct {
  double temperature_tolerance; /* stop when the fluid T > (1 + tol) kT ... (0: off)            */
  long temperature_window;      /* ... at every thermo sample over this many steps              */
  long density_every;           /* density collapse check every N steps (0: off)                */
  double density_bin;           /* its bin edge (rc)                                            */
  double density_fraction;      /* stop when a watched bin < fraction x the mean fluid density  */
} scene_guard_t;

/* Flooding (`flood:`, docs/twophase.md "Flooding"): one liquid displaces another from a sample
 * along a periodic axis of a pressure- or body-force-driven box (run/run_flood.c). The box along
 * the axis is the sample, then the production side [sample.hi, sink.lo), the sink, then the
 * injection side up to sample.lo across the periodic face. Before `start` the defending liquid
 * fills everything; at `start` the defending particles on the injection side and in the sink
 * become invading ones, and from then on every defending particle that reaches the sink does, so
 * that the injection side always holds the invading liquid. Off when on = 0. */
typedef struct {
  int on;
  int axis;                    /* 0, 1, 2 = x, y, z (periodic)                             */
  double sample_lo, sample_hi; /* the pore block's faces along the axis                   */
  double sink_lo, sink_hi;     /* where produced liquid becomes injected liquid           */
  int invading, defending;     /* species indices (mobile, equal mass)                    */
  long start;                  /* step at which the injection starts                     */
  long every;                  /* steps between saturation samples                       */
  int nbins;                   /* saturation profile bins across the sample              */
  double breakthrough;         /* invading saturation of the sample's last bin at breakthrough */
  double density;              /* > 0: the fluid number density n of q_i (else the scene's) */
  double viscosity, tension;   /* > 0: mu of the invading liquid and gamma (capillary number) */
  char path[SCENE_PATH_LEN];   /* the saturation series (CSV)                             */
  char profile_path[SCENE_PATH_LEN]; /* the saturation profiles (CSV; "" none)                */
  long map_every;                    /* saturation maps every N steps (0: none)                */
  double map_cell;                   /* their cell edge (rc)                                   */
  char map_path[SCENE_PATH_LEN];     /* PATH.xdmf + PATH_<step>.h5                             */
} scene_flood_t;

/* Where the cuts between the ranks' subdomains go (`balance:`, docs/scene-format.md "Load
 * balancing"; meso/domain/balance.c). */
enum scene_cuts { SCENE_CUTS_UNIFORM = 0, SCENE_CUTS_COST = 1 };
/* Default weight of a frozen particle for the cost cuts, per backend (bench/RESULTS.md): fitted on
 * the CPU (0.41 on 16 ranks of the H100 host); on the GPU a thread per particle scans the bins for
 * a wall particle as for a fluid one, and 1.0 beat 0.7 and 0.4 there (2 and 4 H200s). */
#define SCENE_FROZEN_WEIGHT_CPU 0.4
#define SCENE_FROZEN_WEIGHT_GPU 1.0
typedef struct {
  int cuts;             /* enum scene_cuts                                                      */
  double frozen_weight; /* cost of a frozen (wall) particle relative to a mobile one            */
  int frozen_weight_given; /* 1: set in the scene; else the backend's default (engine/sim.c:
                              SCENE_FROZEN_WEIGHT_CPU or _GPU)                                 */
  long every;              /* steps between checks of the measured imbalance (0: cuts fixed)      */
  double threshold; /* move the cuts when max / mean busy time over the ranks exceeds it    */
} scene_balance_t;

/* Engine backends (meso/backend/<name>). */
enum scene_backend { SCENE_BACKEND_CPU = 0, SCENE_BACKEND_CUDA = 1 };
/* Memory mode of the CUDA path (docs/engine-cuda.md "Memory modes"). */
enum scene_gpu_memory {
  SCENE_GPU_MEMORY_AUTO = 0,
  SCENE_GPU_MEMORY_FAST = 1,
  SCENE_GPU_MEMORY_COMPACT = 2
};

typedef struct {
  char file[SCENE_PATH_LEN]; /* the scene file this came from (for messages) */
  char name[SCENE_NAME_LEN];

  double box_lo[3], box_hi[3];
  int periodic[3];
  int procs[3]; /* MPI Cartesian grid; 0 = let MPI_Dims_create choose */

  int n_species;
  scene_species_t species[SCENE_MAX_SPECIES];
  scene_pair_t pair[SCENE_MAX_SPECIES][SCENE_MAX_SPECIES];
  int density_kernel; /* enum meso_density_kernel (meso/physics/density_kernels.h) */
  double kT;          /* thermal energy (default 1)                                */
  double vv_lambda;   /* Groot-Warren velocity-prediction factor (default 0.5)      */

  int effect[SCENE_MAX_EFFECTS]; /* 1 when named in the scene (index: enum effect_id) */
  scene_effect_options_t effect_options[SCENE_MAX_EFFECTS]; /* parsed by each named effect */

  scene_init_t init;
  scene_geometry_t geometry;

  double dt;
  long steps;
  uint64_t seed;

  scene_output_t thermo;             /* CSV (".csv") or HDF5 (".h5") time series        */
  scene_profile_t profile;           /* time-averaged 1D profiles                       */
  scene_output_t snapshot;           /* HDF5 snapshot + XDMF sidecar                     */
  scene_output_t dump;               /* LAMMPS-style text dump                           */
  scene_output_t checkpoint;         /* atomic restart file                              */
  scene_flux_t flux;                 /* flux (Darcy velocity) time series                */
  double target_error;               /* run.target_error (0: none; needs output.flux)    */
  char restart_from[SCENE_PATH_LEN]; /* continue from this checkpoint ("" = fresh start) */
  scene_guard_t guard;               /* guardrails (scene/scene_guard.h)                 */
  scene_flood_t flood;               /* flooding (scene/scene_flood.h)                   */
  scene_balance_t balance;           /* cuts between ranks (scene/scene_balance.h)       */
  units_mapping_t units;             /* reduced -> SI, outputs only (scene/scene_units.h) */
  int progress;                      /* progress + ETA on stderr (default 1)             */
  char summary_path[SCENE_PATH_LEN]; /* final summary JSON (default "summary.json")   */
  int backend; /* enum scene_backend: where the engine runs; set by mdpore run/forces --backend,
                  not read from the scene file (0 = cpu) */
  double neighbour_skin; /* Verlet skin of the CUDA path's neighbour lists (rc units); < 0: the
                            backend's default. Set by --skin, not read from the scene file: it
                            changes the run time, not the physics (docs/engine-cuda.md) */
  int gpu_memory;        /* enum scene_gpu_memory, set by --gpu-memory (0 = auto): the CUDA path's
                     neighbour lists (fast) or none (compact); the same forces either way */
} scene_t;

/* The cost cuts' weight of a frozen particle: the scene's, else the backend's default. */
static inline double scene_frozen_weight(const scene_t *s) {
  if (s->balance.frozen_weight_given) return s->balance.frozen_weight;
  return s->backend == SCENE_BACKEND_CUDA ? SCENE_FROZEN_WEIGHT_GPU : SCENE_FROZEN_WEIGHT_CPU;
}

/* Parse and validate a scene file with the effects of `catalog` (meso/effects: scene_load() in
 * effects/scene_load.h passes the registry). On error prints "FILE:LINE: key 'K': expected ..." to
 * stderr and returns non-zero. Every rank may call it (the file is small). */
struct scene_catalog;
int scene_parse_file(const char *path, const struct scene_catalog *catalog, scene_t *scene);

/* A path as written in the scene file, resolved against the scene file's folder (absolute kept).
 * -1 when the resolved path does not fit in `len` bytes (the caller refuses the key). */
int scene_relative_path(const char *scene_file, const char *path, char *out, size_t len);

/* Species index of a name, or -1. */
int scene_species_index(const scene_t *scene, const char *name);

/* Length of the overlap of [a0, a1) and [b0, b1) on a circle of length L (a periodic axis; each
 * interval shorter than L): slabs of the inlet force and of a flood checked against the sample. */
double scene_circle_overlap(double a0, double a1, double b0, double b1, double L);

/* A 64-bit hash of everything that determines the trajectory (box, species, pairs, effects, kernel,
 * kT, dt, seed, ...), not outputs, step counts or paths: a checkpoint only restarts the same
 * physics. */
uint64_t scene_physics_hash(const scene_t *scene);

#endif
