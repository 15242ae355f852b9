/* The engine's public face: a simulation on one MPI communicator (one subdomain per rank).
 * Used by the run driver, the initial-configuration builders, the outputs and the tests. */
#ifndef MESO_ENGINE_SIM_H
#define MESO_ENGINE_SIM_H

#include "effects/effect_list.h"
#include "scene/scene.h"
#include "domain/particles.h"
#include "engine/memory_plan.h"

#include <mpi.h>
#include <stdio.h>

typedef struct sim sim_t; /* opaque; defined in sim_internal.h */

/* Global thermodynamic state (collective; identical on every rank). */
typedef struct {
  long step;
  double time;
  long n_total;       /* all particles                          */
  long n_mobile;      /* particles of non-frozen species         */
  double ke;          /* kinetic energy of mobile particles      */
  double temperature; /* 2 ke / (3 (n_mobile - 1)) in units of kB; momentum-conserving dof */
  double momentum[3];
  double
      pressure[6]; /* full virial pressure tensor xx yy zz xy xz yz: (kinetic + pair virial) / V */
  double volume;
  /* With a geometry image (filled by the run loop, analysis/penetration.c): mobile particles inside
   * solid voxels and the depth of the deepest one (rc). */
  long penetrations;
  double penetration_depth;
} thermo_t;

/* Build the decomposition and empty particle storage for a scene. NULL + message on failure. */
sim_t *sim_create(const scene_t *scene, MPI_Comm comm);
void sim_destroy(sim_t *sim);

/* Offer one particle: it is stored when its position lies in this rank's subdomain (after periodic
 * wrapping). Returns 1 if stored here, 0 if not, -1 on allocation failure or a position that no
 * rank can own (non-finite, or outside the box along a non-periodic axis; message on rank 0). Any
 * rank may offer any particle; callers generating a global configuration offer every particle on
 * every rank. */
int sim_add_particle(sim_t *sim, int64_t id, int species, const double x[3], const double v[3]);

/* Collective, before the particles are added: the memory plan (engine/memory_plan.h) of the rank
 * with the most particles (each rank gives its own inputs: owned particles, geometry build bytes,
 * ...; extents and backend are the sim's), times the ranks sharing a node, against the memory
 * available (common/memory_limit.h). 0 when it fits; else -1 on every rank after rank 0 printed
 * the refusal: the total, the largest items, the memory available and what to try. */
int sim_memory_check(sim_t *sim, memory_inputs_t *in);

/* After all particles were added (or a checkpoint was loaded): check global count and ids, exchange
 * ghosts and evaluate densities and forces at the current step (unless forces were loaded). */
int sim_setup(sim_t *sim);

/* Advance one velocity-Verlet step. Returns 0, or non-zero with a message naming the cause
 * (NaN, particle lost, particle inside a wall, ...). */
int sim_step(sim_t *sim);

/* Collective reduction of the thermodynamic state at the current step. */
void sim_thermo(sim_t *sim, thermo_t *out);

/* Collective flux sums along `axis` (output.flux; analysis/flux.c turns them into q): per species
 * s, the global count of its mobile particles count[s] and the sum of their velocity components
 * vsum[s] (frozen species: 0). On the backend's device when it has the reduction. Identical on
 * every rank. 0, or -1 (message printed) when the device reduction failed. */
int sim_flux_sums(sim_t *sim, int axis, double count[SCENE_MAX_SPECIES],
                  double vsum[SCENE_MAX_SPECIES]);

/* Collective (flooding, run/run_flood.c): every particle of species `from` whose coordinate along
 * `axis` lies in the periodic slab [lo, hi) becomes species `to` (equal masses; velocities kept),
 * where the backend keeps the particles. *changed: how many over all ranks. 0, or -1 (message
 * printed) when a device call failed. */
int sim_recolor(sim_t *sim, int axis, double lo, double hi, int from, int to, long *changed);

/* Accessors for outputs and analyses. */
particles_t *sim_particles(sim_t *sim);
const scene_t *sim_scene(const sim_t *sim);
MPI_Comm sim_comm(const sim_t *sim);
long sim_step_index(const sim_t *sim);
void sim_set_step_index(sim_t *sim, long step); /* restart */
void sim_subdomain(const sim_t *sim, double lo[3], double hi[3]);
void sim_request_virial(sim_t *sim, int on); /* per-particle virial in the next force passes */
void sim_forces_loaded(sim_t *sim); /* restart: forces come from a checkpoint, not recomputed */
/* Whether sim_thermo follows the next sim_step. The CUDA path sums the pair virial (the pressure)
 * only on such steps; an unannounced sim_thermo is still right, it reruns the pair pass. */
void sim_announce_thermo(sim_t *sim, int on);
/* Sort the particles and rebuild the neighbour lists in the next step even when a Verlet skin would
 * keep them (CUDA path; the CPU path rebuilds every step): the state after that step restarts
 * bitwise identically. */
void sim_rebuild_lists(sim_t *sim);

/* Collective check that the global particle count still equals the one at sim_setup. 0, or non-zero
 * after printing "particle lost: ..." (rank 0). sim_step also checks it every step. */
int sim_check_count(sim_t *sim);
/* The last error message of this rank ("" when none). */
const char *sim_last_error(const sim_t *sim);
/* Test-only fault hook (meso/run/run_fault.h): set (add = 0) or add to (add = 1) component `axis`
 * of the position (field 0) or velocity (field 1) of particle `id` on the rank that owns it, where
 * the backend keeps it (on the GPU for the CUDA backend). 0 or -1 (message printed). */
int sim_fault_write(sim_t *sim, int64_t id, int field, int axis, double value, int add);
/* The backend that runs the phases: "cpu" or "cuda". */
const char *sim_backend_name(const sim_t *sim);

/* The backend for --backend NAME: "cpu", "cuda", or "auto" (cuda when this build has CUDA, a GPU is
 * visible and the run has one rank; cpu otherwise). 0, or -1 with the reason in err (cuda asked for
 * but not built, no GPU visible, or more than one rank). */
int sim_backend_choose(const char *name, int nranks, int *backend, char *err, size_t errlen);
/* With the CUDA backend the particles live on the GPU between steps: sim_particles() copies them
 * back first when they changed (outputs only; changes made through it after sim_setup are not seen
 * by the device). */

/* Print the phase lists (set-up and step) the scene's plan runs on scene.backend, with each named
 * effect's numbers, without running it (mdpore run --explain). */
void sim_explain(const scene_t *scene, int nranks, FILE *out);

#endif
