/* The `units:` block (docs/scene-format.md, "units"; common/units_block.c): each form gives the SI
 * factors that physics.md section 4's definitions give when recomputed here from scratch (water
 * molecule 18.01528 u, rho_water 997 kg/m^3, kB), the fluid density comes from the scene, and the
 * block is not part of the physics hash (outputs only). */
#include "common/mpi_singleton.h"
#include "effects/scene_load.h"
#include "scene/scene.h"

#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include "test_io_check.h"

#define KB 1.380649e-23
#define M_WATER (18.01528 * 1.66053906660e-27)
#define RHO_WATER 997.0

static const char *head = "box: {lo: [0, 0, 0], hi: [6, 6, 6]}\n"
                          "species:\n"
                          "  - {name: liquid}\n"
                          "  - {name: wall, frozen: true}\n"
                          "pairs: {default: {A: -40, B: 25, gamma: 4.5, rc: 1.0, rd: 0.75}}\n"
                          "effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}}\n"
                          "run: {dt: 0.01, steps: 10}\n";

/* Loads head + extra; 0 on success. */
static int load(const char *extra, scene_t *s) {
  const char *path = "scene_units_test.yaml";
  FILE *f = fopen(path, "w");
  fputs(head, f);
  fputs(extra, f);
  fclose(f);
  const int rc = scene_load(path, s);
  remove(path);
  return rc;
}

static int close_to(double a, double b, double rel) {
  return fabs(a - b) <= rel * fabs(b);
}

/* Every derived factor from (rc, e, m), by dimensions. */
static void check_factors(const units_si_t *u, double rc, double e, double m) {
  const double tau = rc * sqrt(m / e);
  CHECK(close_to(u->rc_m, rc, 1e-6) && close_to(u->kT_J, e, 1e-6));
  CHECK(close_to(u->mass_kg, m, 1e-6) && close_to(u->tau_s, tau, 1e-6));
  CHECK(close_to(u->q_m_per_s, rc / tau, 1e-6));
  CHECK(close_to(u->G_Pa_per_m, e / pow(rc, 4), 1e-6)); /* kT / rc^4 */
  CHECK(close_to(u->p_Pa, e / pow(rc, 3), 1e-6));
  CHECK(close_to(u->mu_Pa_s, m / (rc * tau), 1e-6));
  CHECK(close_to(u->k_m2, rc * rc, 1e-6) && close_to(u->k_nD, rc * rc / 9.869233e-13 * 1e9, 1e-6));
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  scene_t s, plain;
  const char *fill = "initial: {fill: [{species: wall, density: 8, lo: [0, 0, 0], hi: [6, 1, 6]},"
                     " {species: liquid, density: 6.2, lo: [0, 1, 0], hi: [6, 6, 6]}]}\n";
  char text[1024];

  /* No block: off. */
  CHECK(load(fill, &plain) == 0 && !plain.units.on);

  /* The water mapping at N_m = 3, n = 6.2 (the mobile fill, not the frozen one): rc^3 = N_m n
   * m_water / rho_water; physics.md section 4 says rc ~ 0.82 nm. */
  snprintf(text, sizeof text,
           "%sunits: {mapping: water, coarse_graining: 3, temperature: 298.15}\n", fill);
  CHECK(load(text, &s) == 0 && s.units.on && s.units.mapping == UNITS_MAPPING_WATER);
  double rc = cbrt(3 * 6.2 * M_WATER / RHO_WATER);
  CHECK(rc > 0.815e-9 && rc < 0.825e-9);
  check_factors(&s.units.si, rc, KB * 298.15, 3 * M_WATER);
  CHECK(close_to(s.units.si.n_molecules, 3, 1e-4) && s.units.density == 6.2);
  CHECK(!strcmp(s.units.density_source, "initial.fill[1].density"));
  /* Outputs only: the physics hash does not see it. */
  CHECK(scene_physics_hash(&s) == scene_physics_hash(&plain));
  /* The mapping is stated: not viscosity-matched, mu 5.41 -> ~1.5e-4 Pa s. */
  char said[1536];
  units_mapping_describe(&s.units, said, sizeof said);
  CHECK(strstr(said, "not viscosity-matched") && strstr(said, "0.00015"));
  CHECK(close_to(5.41 * s.units.si.mu_Pa_s, 1.5e-4, 0.05));

  /* coarse_graining defaults to 3; units.density overrides the scene's; output.flux.density
   * comes before a fill. */
  snprintf(text, sizeof text, "%sunits: {mapping: water, density: 4}\n", fill);
  CHECK(load(text, &s) == 0 && close_to(s.units.si.rc_m, cbrt(3 * 4 * M_WATER / RHO_WATER), 1e-6));
  snprintf(
      text, sizeof text,
      "%soutput: {flux: {axis: x, every: 10, file: f.csv, density: 5}}\nunits: {coarse_graining: "
      "2}\n",
      fill);
  CHECK(load(text, &s) == 0 && close_to(s.units.si.rc_m, cbrt(2 * 5 * M_WATER / RHO_WATER), 1e-6));
  CHECK(!strcmp(s.units.density_source, "output.flux.density"));

  /* Own units: rc, tau, energy -> m = e tau^2 / rc^2. */
  snprintf(text, sizeof text, "%sunits: {rc: 2e-9, tau: 1e-11, energy: 4e-21}\n", fill);
  CHECK(load(text, &s) == 0 && s.units.mapping == UNITS_MAPPING_OWN);
  check_factors(&s.units.si, 2e-9, 4e-21, 4e-21 * 1e-22 / 4e-18);
  CHECK(isnan(s.units.temperature_K));

  /* Own units with a temperature at kT = 0.9: e = kB T / kT; no mass: the water of a particle's
   * volume, m = rho_water rc^3 / n. */
  snprintf(text, sizeof text, "kT: 0.9\n%sunits: {rc: 1e-9, temperature: 300}\n", fill);
  CHECK(load(text, &s) == 0);
  check_factors(&s.units.si, 1e-9, KB * 300 / 0.9, RHO_WATER * 1e-27 / 6.2);

  /* From a voxel size: rc = voxel_size / rc_per_voxel (the image is only read by the builder). */
  snprintf(text, sizeof text,
           "geometry: {image: none.raw, rc_per_voxel: 0.5, flow_axis: x, fluid_density: 6.2, "
           "species: {fluid: liquid, inorganic: wall}}\nunits: {voxel_size: 1e-9, mass: 1e-25}\n");
  CHECK(load(text, &s) == 0);
  check_factors(&s.units.si, 2e-9, KB * 298.15, 1e-25);
  CHECK(strstr(s.units.length_source, "voxel_size") != NULL);

  MPI_Finalize();
  if (failures) fprintf(stderr, "%d checks failed\n", failures);
  return failures ? 1 : 0;
}
