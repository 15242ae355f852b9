/* The scene parser turns a full scene into the right numbers: defaults, pair overrides applied
 * symmetrically, effect options, fill regions, outputs, paths relative to the scene file. */
#include "common/mpi_singleton.h"
#include "effects/dpd_thermostat.h"
#include "effects/effect.h"
#include "effects/scene_load.h"
#include "scene/scene.h"
#include "physics/density_kernels.h"
#include "physics/pair_random.h"

#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include "test_io_check.h"

static const char *text =
    "name: t\n"
    "box: {lo: [0, 0, 0], hi: [20, 10, 8], periodic: [true, true, false]}\n"
    "species:\n"
    "  - {name: liquid, mass: 1.5}\n"
    "  - {name: wall, frozen: true}\n"
    "pairs:\n"
    "  default: {A: -40, B: 25, gamma: 4.5, rc: 1.0, rd: 0.75}\n"
    "  wall-liquid: {A: -30}\n"
    "density_kernel: lucy\n"
    "kT: 0.9\n"
    "effects:\n"
    "  mdpd_attraction: {}\n"
    "  mdpd_repulsion:\n"
    "  dpd_thermostat: {exponent: 0.5, rng: fast}\n"
    "  body_force: {liquid: [0.02, 0, 0], reverse_along: y}\n"
    "  box_walls: {}\n"
    "initial:\n"
    "  fill:\n"
    "    - {species: liquid, lo: [5, 0, 0], hi: [15, 10, 8], density: 6.2, mode: lattice}\n"
    "    - {species: wall, density: 8}\n"
    "run: {dt: 0.005, steps: 1e4, seed: 7}\n"
    "output:\n"
    "  thermo: {every: 100, file: thermo.h5}\n"
    "  profile: {axis: z, bins: 40, every: 10, start: 1000, file: profile.csv}\n"
    "  progress: false\n";

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  const char *path = "scene_parse_test.yaml";
  FILE *f = fopen(path, "w");
  fputs(text, f);
  fclose(f);
  scene_t s;
  CHECK(scene_load(path, &s) == 0);
  CHECK(!strcmp(s.name, "t"));
  CHECK(s.box_hi[2] == 8 && s.periodic[2] == 0 && s.periodic[0] == 1);
  CHECK(s.n_species == 2 && s.species[0].mass == 1.5 && s.species[1].mass == 1.0 &&
        s.species[1].frozen);
  CHECK(s.pair[0][0].A == -40 && s.pair[0][1].A == -30 && s.pair[1][0].A == -30 &&
        s.pair[1][1].A == -40);
  CHECK(s.pair[0][1].B == 25 && s.pair[0][1].rd == 0.75 && s.pair[1][0].gamma == 4.5);
  CHECK(s.density_kernel == MESO_KERNEL_LUCY && s.kT == 0.9);
  CHECK(s.effect[EFFECT_MDPD_ATTRACTION] && s.effect[EFFECT_MDPD_REPULSION] &&
        s.effect[EFFECT_BOX_WALLS]);
  CHECK(!s.effect[EFFECT_DPD_CONSERVATIVE]);
  const body_force_params_t *bf = SCENE_EFFECT_OPTIONS(&s, EFFECT_BODY_FORCE, body_force_params_t);
  CHECK(bf->g[0][0] == 0.02 && bf->g[1][0] == 0 && bf->reverse_axis == 1);
  CHECK(s.init.kind == INIT_FILL && s.init.n_fill == 2 && s.init.fill[0].mode == FILL_LATTICE);
  CHECK(s.init.fill[1].species == 1 && s.init.fill[1].hi[0] == 20 &&
        s.init.fill[1].mode == FILL_RANDOM);
  CHECK(s.init.temperature == 0.9); /* defaults to kT */
  CHECK(s.dt == 0.005 && s.steps == 10000 && s.seed == 7 && s.vv_lambda == 0.5);
  CHECK(s.thermo.every == 100 && !strcmp(s.thermo.path, "thermo.h5") && s.snapshot.every == 0);
  CHECK(s.profile.axis == 2 && s.profile.nbins == 40 && s.profile.start == 1000);
  CHECK(!s.progress && !strcmp(s.summary_path, "summary.json"));
  /* The plan: the thermostat's exponent, the cutoff, the body force centre along y. */
  plan_t plan;
  char err[512];
  CHECK(plan_build(&plan, &s, err, sizeof err) == 0);
  CHECK(plan.weight_exp == 0.5 && !plan.weight_exp_is_one);
  /* no pair sets s: every pair takes the thermostat's exponent */
  CHECK(s.pair[0][0].s == 0 && s.pair[0][1].s == 0);
  CHECK(plan.coef[0][0].s_exp == 0.5 && !plan.coef[0][0].s_one && plan.coef[1][0].s_exp == 0.5);
  CHECK(plan.pair_rng == PAIR_RNG_FAST); /* dpd_thermostat's rng */
  CHECK(fabs(plan.rcut - 1.0) < 1e-15);
  CHECK(plan.particle.on[EFFECT_BODY_FORCE] && plan.particle.body_force.centre == 5.0);
  /* The physics hash sees physics, not outputs. */
  scene_t t = s;
  t.thermo.every = 7;
  CHECK(scene_physics_hash(&t) == scene_physics_hash(&s));
  t.pair[0][1].A = -31;
  CHECK(scene_physics_hash(&t) != scene_physics_hash(&s));
  t = s; /* an effect option is physics too */
  SCENE_EFFECT_OPTIONS(&t, EFFECT_BODY_FORCE, body_force_params_t)->g[0][0] = 0.03;
  CHECK(scene_physics_hash(&t) != scene_physics_hash(&s));
  /* the generator of the random force too; the default (philox = 0) leaves the option bytes as
   * they were before the option existed (the exponent, then zeros), so the hash of a scene without
   * the key, and the checkpoints written for it, are unchanged */
  t = s;
  dpd_thermostat_options_t *th =
      SCENE_EFFECT_OPTIONS(&t, EFFECT_DPD_THERMOSTAT, dpd_thermostat_options_t);
  CHECK(th->rng == PAIR_RNG_FAST);
  th->rng = PAIR_RNG_PHILOX;
  CHECK(scene_physics_hash(&t) != scene_physics_hash(&s));
  const unsigned char *bytes = t.effect_options[EFFECT_DPD_THERMOSTAT].bytes;
  double e;
  memcpy(&e, bytes, sizeof e);
  int zeros = 1;
  for (size_t k = sizeof e; k < SCENE_EFFECT_OPTION_BYTES; k++) zeros &= bytes[k] == 0;
  CHECK(e == 0.5 && zeros);
  /* A pair's own s (pairs.X.s) overrides the thermostat's exponent for that pair only, both ways;
   * s = 1 is the standard weight (no pow) */
  f = fopen(path, "w");
  const char *pairs_at = strstr(text, "pairs:"), *kernel_at = strstr(text, "density_kernel:");
  fwrite(text, 1, (size_t)(pairs_at - text), f);
  fputs("pairs:\n  default: {A: -40, B: 25, gamma: 4.5, rc: 1.0, rd: 0.75, s: 1}\n"
        "  wall-liquid: {A: -30, gamma: 13.5, s: 0.25}\n",
        f);
  fputs(kernel_at, f);
  fclose(f);
  CHECK(scene_load(path, &s) == 0);
  CHECK(s.pair[0][1].s == 0.25 && s.pair[1][0].s == 0.25 && s.pair[0][0].s == 1);
  CHECK(plan_build(&plan, &s, err, sizeof err) == 0);
  CHECK(plan.coef[0][1].s_exp == 0.25 && !plan.coef[0][1].s_one && plan.coef[1][0].s_exp == 0.25);
  CHECK(plan.coef[0][0].s_exp == 1.0 && plan.coef[0][0].s_one && plan.coef[1][1].s_one);
  t = s; /* s is physics: hashed when set */
  t.pair[0][1].s = t.pair[1][0].s = 0.5;
  CHECK(scene_physics_hash(&t) != scene_physics_hash(&s));
  plan_release(&plan);
  remove(path);
  /* The cost cuts' frozen weight: the backend's default when the scene names none (CPU 0.4, GPU
   * 1.0: bench/RESULTS.md), the scene's when it does, on either backend. */
  CHECK(!s.balance.frozen_weight_given);
  s.backend = SCENE_BACKEND_CPU;
  CHECK(scene_frozen_weight(&s) == SCENE_FROZEN_WEIGHT_CPU && SCENE_FROZEN_WEIGHT_CPU == 0.4);
  s.backend = SCENE_BACKEND_CUDA;
  CHECK(scene_frozen_weight(&s) == SCENE_FROZEN_WEIGHT_GPU && SCENE_FROZEN_WEIGHT_GPU == 1.0);
  f = fopen(path, "w");
  fputs(text, f);
  fputs("balance: {cuts: cost, frozen_weight: 0.7}\n", f);
  fclose(f);
  CHECK(scene_load(path, &s) == 0);
  CHECK(s.balance.frozen_weight_given && s.balance.cuts == SCENE_CUTS_COST);
  s.backend = SCENE_BACKEND_CUDA;
  CHECK(scene_frozen_weight(&s) == 0.7);
  s.backend = SCENE_BACKEND_CPU;
  CHECK(scene_frozen_weight(&s) == 0.7);
  MPI_Finalize();
  if (failures) fprintf(stderr, "%d checks failed\n", failures);
  return failures ? 1 : 0;
}
