/* The `units:` block (units_block.h). */
#include "common/units_block.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define TRY(x)                                                                                     \
  do {                                                                                             \
    if ((x) != 0) return -1;                                                                       \
  } while (0)

void units_context_init(units_context_t *c) {
  c->kT = 1.0;
  c->density = NAN;
  c->density_source[0] = 0;
  c->rc_per_voxel = NAN;
}

/* The numeric keys: name, what a value must be, upper bound (exclusive). */
enum { K_CG, K_T, K_ENERGY, K_RC, K_VOXEL, K_TAU, K_MASS, K_DENSITY, K_COUNT };
static const struct {
  const char *key, *what;
  double max;
} numbers[K_COUNT] = {
    {"coarse_graining", "water molecules per particle N_m > 0", HUGE_VAL},
    {"temperature", "a temperature in K > 0", HUGE_VAL},
    {"energy", "the energy unit in J > 0", HUGE_VAL},
    {"rc", "a length in metres, 0 < rc < 1 (e.g. 8.2e-10)", 1.0},
    {"voxel_size", "a voxel edge in metres, 0 < voxel_size < 1 (e.g. 1e-8)", 1.0},
    {"tau", "the time unit in s > 0", HUGE_VAL},
    {"mass", "the mass unit in kg > 0", HUGE_VAL},
    {"density", "a fluid number density in particles per rc^3 > 0", HUGE_VAL},
};

/* "expected no KEY ..." at a key the chosen form does not take. */
static int refuse(ytree_t *t, yaml_node_t *const *node, const char *path, int k, const char *why) {
  char sub[256];
  snprintf(sub, sizeof sub, "%s.%s", path, numbers[k].key);
  return yt_error(t, node[k], sub, "expected no %s %s", numbers[k].key, why);
}

int units_block_read(ytree_t *t, yaml_node_t *n, const char *path, const units_context_t *ctx,
                     units_mapping_t *m) {
  static const char *const keys[] = {
      "mapping", "coarse_graining", "temperature", "energy", "rc", "voxel_size", "tau",
      "mass",    "density",         NULL};
  memset(m, 0, sizeof *m);
  TRY(yt_check_keys(t, n, path, keys));
  char sub[256];
  double val[K_COUNT];
  yaml_node_t *node[K_COUNT];
  for (int k = 0; k < K_COUNT; k++) {
    val[k] = NAN;
    node[k] = yt_get(t, n, numbers[k].key);
    if (!node[k]) continue;
    snprintf(sub, sizeof sub, "%s.%s", path, numbers[k].key);
    TRY(yt_double(t, node[k], sub, &val[k]));
    if (!(val[k] > 0 && val[k] < numbers[k].max))
      return yt_error(t, node[k], sub, "expected %s (got %g)", numbers[k].what, val[k]);
  }
  int mapping = 0;
  yaml_node_t *v = yt_get(t, n, "mapping");
  if (v) {
    static const char *const words[] = {"water", "own", NULL};
    snprintf(sub, sizeof sub, "%s.mapping", path);
    const int w = yt_enum(t, v, sub, words);
    if (w < 0) return -1;
    mapping = w == 0 ? UNITS_MAPPING_WATER : UNITS_MAPPING_OWN;
  } else if (node[K_RC] || node[K_VOXEL] || node[K_TAU] || node[K_MASS] || node[K_ENERGY])
    mapping = UNITS_MAPPING_OWN;
  else if (node[K_CG])
    mapping = UNITS_MAPPING_WATER;
  else
    return yt_error(t, n, path,
                    "expected mapping: water (with coarse_graining), rc or voxel_size (got none "
                    "of them)");

  if (mapping == UNITS_MAPPING_WATER) {
    static const int not_water[] = {K_RC, K_VOXEL, K_TAU, K_MASS, K_ENERGY};
    for (size_t i = 0; i < sizeof not_water / sizeof not_water[0]; i++)
      if (node[not_water[i]])
        return refuse(t, node, path, not_water[i],
                      "with mapping water (coarse_graining sets the length and the mass; "
                      "temperature the energy); use mapping: own for your own units");
  } else {
    if (node[K_CG])
      return refuse(t, node, path, K_CG, "with your own units (it is the water mapping's)");
    if (!node[K_RC] && !node[K_VOXEL]) {
      snprintf(sub, sizeof sub, "%s.rc", path);
      return yt_error(t, n, sub, "expected rc or voxel_size in metres (got neither)");
    }
    if (node[K_RC] && node[K_VOXEL])
      return refuse(t, node, path, K_VOXEL,
                    "with rc (one length: rc, or voxel_size / rc_per_voxel)");
    if (node[K_ENERGY] && node[K_T])
      return refuse(t, node, path, K_T, "with energy (one energy unit: energy, or kB T / kT)");
    if (node[K_TAU] && node[K_MASS])
      return refuse(t, node, path, K_MASS, "with tau (tau = rc sqrt(m / e) sets the mass)");
    snprintf(sub, sizeof sub, "%s.voxel_size", path);
    if (node[K_VOXEL] && !(ctx->rc_per_voxel > 0))
      return yt_error(t, node[K_VOXEL], sub,
                      "expected a scene with geometry (rc = voxel_size / geometry.rc_per_voxel; "
                      "without an image give rc)");
  }
  m->on = 1;
  m->mapping = mapping;
  m->energy_given = node[K_ENERGY] != NULL;
  m->mass_given = node[K_MASS] != NULL;
  m->tau_given = node[K_TAU] != NULL;
  m->coarse_graining = mapping == UNITS_MAPPING_WATER ? (node[K_CG] ? val[K_CG] : 3.0) : NAN;
  m->temperature_K = node[K_ENERGY] ? NAN : node[K_T] ? val[K_T] : UNITS_DEFAULT_TEMPERATURE;
  const double energy = node[K_ENERGY] ? val[K_ENERGY] : UNITS_KB * m->temperature_K / ctx->kT;

  /* The fluid density: the water mapping's rc and the default mass need it. */
  const int need_density = mapping == UNITS_MAPPING_WATER || (!node[K_TAU] && !node[K_MASS]);
  m->density = NAN;
  if (!need_density && node[K_DENSITY])
    return refuse(t, node, path, K_DENSITY,
                  "with tau or mass (the density sets only the water mapping's rc and the default "
                  "mass, the water of a particle's volume)");
  if (need_density) {
    if (node[K_DENSITY]) {
      m->density = val[K_DENSITY];
      snprintf(m->density_source, sizeof m->density_source, "%s.density", path);
    } else if (ctx->density > 0) {
      m->density = ctx->density;
      snprintf(m->density_source, sizeof m->density_source, "%s", ctx->density_source);
    } else {
      snprintf(sub, sizeof sub, "%s.density", path);
      return yt_error(t, n, sub,
                      "expected the fluid number density n in particles per rc^3 (the scene has "
                      "no geometry.fluid_density, fill or output.flux.density to take it from)");
    }
  }

  double rc, mass;
  if (mapping == UNITS_MAPPING_WATER) {
    rc = units_water_rc(m->coarse_graining, m->density);
    mass = m->coarse_graining * UNITS_M_WATER; /* = rho_water rc^3 / n */
    snprintf(m->length_source, sizeof m->length_source,
             "rc = (N_m n m_water / rho_water)^(1/3), N_m = %g, n = %g (%s)", m->coarse_graining,
             m->density, m->density_source);
  } else {
    if (node[K_RC]) {
      rc = val[K_RC];
      snprintf(m->length_source, sizeof m->length_source, "%s.rc", path);
    } else {
      rc = val[K_VOXEL] / ctx->rc_per_voxel;
      snprintf(m->length_source, sizeof m->length_source,
               "%s.voxel_size %g m / geometry.rc_per_voxel %g", path, val[K_VOXEL],
               ctx->rc_per_voxel);
    }
    if (node[K_MASS])
      mass = val[K_MASS];
    else if (node[K_TAU]) /* tau = rc sqrt(m / e) */
      mass = energy * val[K_TAU] * val[K_TAU] / (rc * rc);
    else
      mass = units_water_mass(rc, m->density);
  }
  units_make(rc, energy, mass, &m->si);
  /* values each finite can still make a factor overflow or vanish (e.g. rc 1e-300 m with energy
   * 1e300 J: pressure e / rc^3 is infinite); summary.json and every conversion need them all */
  const units_si_t *u = &m->si;
  const struct {
    const char *name;
    double v;
  } factors[] = {{"rc (m)", u->rc_m},
                 {"energy (J)", u->kT_J},
                 {"mass (kg)", u->mass_kg},
                 {"time tau (s)", u->tau_s},
                 {"velocity (m/s)", u->q_m_per_s},
                 {"pressure (Pa)", u->p_Pa},
                 {"pressure gradient (Pa/m)", u->G_Pa_per_m},
                 {"viscosity (Pa s)", u->mu_Pa_s},
                 {"permeability (m^2)", u->k_m2},
                 {"permeability (nD)", u->k_nD}};
  for (size_t i = 0; i < sizeof factors / sizeof factors[0]; i++)
    if (!(isfinite(factors[i].v) && factors[i].v > 0))
      return yt_error(t, n, path,
                      "expected units whose reduced unit of every quantity is a finite positive "
                      "number in SI (got %s = %g from rc %g m, energy %g J, mass %g kg)",
                      factors[i].name, factors[i].v, u->rc_m, u->kT_J, u->mass_kg);
  return 0;
}
