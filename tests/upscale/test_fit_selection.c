/* Law selection on synthetic tables (upscale/fit/fit_select.h):
 * (a) Darcy data in linear response with Gaussian noise, in four table families shaped like
 *     pore-scale campaigns (straight channels 8 rc across, with stated errors and with a scatter 1.5x
 *     the stated errors; sphere arrays of two solid fractions), 20 seeds each: Darcy must be chosen
 *     for at least 19 of 20 seeds of every family, with BIC and with AIC. How often the criterion
 *     alone would have picked a law beyond Darcy is printed for comparison.
 * (b) A flux offset at zero gradient (a threshold law with G0 < 0) is refused: the threshold fit is
 *     not supported, its reason says "inadmissible", and it is never chosen, with or without Darcy
 *     among the fitted laws.
 * (c) The same channels driven into a power law n = 1.3 still choose the power law (the test is not
 *     merely "always Darcy"). */
#include <math.h>
#include <petscsys.h>
#include <stdio.h>
#include <string.h>

#include "fit_select.h"
#include "synthetic_rng.h"

#define SEEDS 20
#define MIN_DARCY 19
#define MAXPTS 10

static int failures = 0;
#define CHECK(cond, ...)                                                                           \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      failures++;                                                                                  \
      fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                              \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fprintf(stderr, "\n");                                                                       \
    }                                                                                              \
  } while (0)

/* One family of synthetic tables: the true law, the gradients (log-spaced g_lo .. g_hi), the stated
 * error sigma = rel |q| + floor_share max|q| and the true scatter, scatter_factor * sigma. */
typedef struct {
  const char *name;
  flow_law truth;
  fluid_props fluid;
  int npts;
  double g_lo, g_hi;
  double rel, floor_share;
  double scatter_factor;
} table_family;

static void make_table(const table_family *f, uint64_t *seed, double *G, double *q, double *s) {
  double qmax = 0;
  for (int i = 0; i < f->npts; i++) {
    G[i] = f->g_lo * pow(f->g_hi / f->g_lo, i / (f->npts - 1.0));
    q[i] = flow_law_q_exact(&f->truth, &f->fluid, G[i]);
    qmax = fmax(qmax, fabs(q[i]));
  }
  for (int i = 0; i < f->npts; i++) {
    s[i] = f->rel * fabs(q[i]) + f->floor_share * qmax;
    q[i] += f->scatter_factor * s[i] * gaussian(seed);
  }
}

/* Fits every law to SEEDS tables of the family; returns how often `want` was chosen with crit and
 * counts in *crit_alone how often the criterion alone (fit_lowest) would have picked a law beyond
 * Darcy. */
static int count_chosen(const table_family *f, uint64_t seed0, fit_criterion crit,
                        flow_law_kind want, int *crit_alone) {
  const flow_law_kind all[LAW_COUNT] = {LAW_DARCY, LAW_THRESHOLD, LAW_FORCHHEIMER, LAW_POWER};
  int hits = 0;
  *crit_alone = 0;
  for (int k = 0; k < SEEDS; k++) {
    uint64_t seed = seed0 + 104729 * (uint64_t)k;
    double G[MAXPTS], q[MAXPTS], s[MAXPTS];
    make_table(f, &seed, G, q, s);
    const fit_data d = {f->npts, G, q, s};
    fit_result r[LAW_COUNT];
    const int chosen = fit_all(&d, &f->fluid, all, LAW_COUNT, crit, r);
    const int lowest = fit_lowest(r, LAW_COUNT, crit);
    hits += chosen >= 0 && r[chosen].kind == want;
    *crit_alone += lowest >= 0 && r[lowest].kind != LAW_DARCY;
    if (chosen >= 0 && r[chosen].kind != want)
      printf("    seed %d: chose %s (%s)\n", k, flow_law_name(r[chosen].kind), r[chosen].support);
  }
  return hits;
}

/* mDPD water (reduced units): viscosity 5.41, density 6.2 (validation/permeability). */
static const fluid_props mdpd_water = {5.41, 6.2};

/* A family of tables from `law` in mDPD water. */
static table_family family(const char *name, flow_law law, int npts, double g_lo, double g_hi,
                           double rel, double floor_share, double scatter_factor) {
  const table_family f = {name, law, mdpd_water,  npts,          g_lo,
                          g_hi, rel, floor_share, scatter_factor};
  return f;
}

static void test_darcy_families(void) {
  /* plane channel 8 rc across in a 10 rc cell: k = porosity W^2 / 12 */
  const flow_law channel = {.kind = LAW_DARCY, .k = 0.8 * 8.0 * 8.0 / 12.0};
  const flow_law spheres_dilute = {.kind = LAW_DARCY, .k = 13.8}; /* c = 0.125, 20 rc cell */
  const flow_law spheres_dense = {.kind = LAW_DARCY, .k = 2.59};  /* c = 0.343, 20 rc cell */
  /* relative errors 2-7% with a thermal floor, as campaign tables in linear response */
  const table_family families[] = {
      family("channel 8 rc", channel, 5, 0.002, 0.03, 0.02, 0.005, 1.0),
      family("channel 8 rc, scatter 1.5x errors", channel, 5, 0.002, 0.03, 0.02, 0.005, 1.5),
      family("sphere array c = 0.125", spheres_dilute, 5, 0.0034, 0.034, 0.035, 0.003, 1.0),
      family("sphere array c = 0.343", spheres_dense, 10, 0.02, 0.24, 0.01, 0.002, 1.0),
  };
  const fit_criterion crits[2] = {SELECT_BIC, SELECT_AIC};
  for (size_t f = 0; f < sizeof families / sizeof families[0]; f++)
    for (int c = 0; c < 2; c++) {
      int crit_alone = 0;
      const int darcy = count_chosen(&families[f], 2024 + 31 * f, crits[c], LAW_DARCY, &crit_alone);
      printf("%-36s %s: darcy chosen %2d/%d (min %d); the criterion alone picks a law beyond "
             "darcy %2d/%d\n",
             families[f].name, crits[c] == SELECT_AIC ? "AIC" : "BIC", darcy, SEEDS, MIN_DARCY,
             crit_alone, SEEDS);
      CHECK(darcy >= MIN_DARCY, "%s: darcy chosen for %d of %d seeds", families[f].name, darcy,
            SEEDS);
    }
}

static void test_negative_threshold(void) {
  /* Darcy plus a flux at zero gradient: the hinge fit puts G0 well below 0 */
  const flow_law offset_law = {.kind = LAW_THRESHOLD, .k = 2.59, .g0 = -0.03};
  const table_family offset = family("offset", offset_law, 8, 0.02, 0.24, 0.01, 0.002, 1.0);
  const flow_law_kind all[LAW_COUNT] = {LAW_DARCY, LAW_THRESHOLD, LAW_FORCHHEIMER, LAW_POWER};
  for (int k = 0; k < 5; k++) {
    uint64_t seed = 77 + (uint64_t)k;
    double G[MAXPTS], q[MAXPTS], s[MAXPTS];
    make_table(&offset, &seed, G, q, s);
    const fit_data d = {offset.npts, G, q, s};
    fit_result r[LAW_COUNT];
    int chosen = fit_all(&d, &offset.fluid, all, LAW_COUNT, SELECT_BIC, r);
    const fit_result *t = &r[LAW_THRESHOLD];
    if (k == 0)
      printf("negative threshold: G0 = %.4g +- %.2g, %s; chosen %s\n", t->theta[1], t->se[1],
             t->support, chosen >= 0 ? flow_law_name(r[chosen].kind) : "none");
    CHECK(t->ok && t->converged && t->theta[1] < 0 && fabs(t->support_sigma) >= FIT_SUPPORT_SIGMA,
          "seed %d: the threshold fit must converge with G0 significantly below 0 (G0 = %g, %.1f "
          "sigma)",
          k, t->theta[1], t->support_sigma);
    CHECK(!t->supported && !t->eligible && strstr(t->support, "inadmissible") &&
              strstr(t->not_eligible, "not supported"),
          "seed %d: a negative threshold must be refused as inadmissible: '%s' / '%s'", k,
          t->support, t->not_eligible);
    CHECK(chosen >= 0 && r[chosen].kind != LAW_THRESHOLD, "seed %d: chose %s", k,
          chosen >= 0 ? flow_law_name(r[chosen].kind) : "none");
    CHECK(t->weight == 0, "seed %d: a law that is not eligible has weight 0", k);
    /* threshold alone, no darcy to fall back on: still never chosen (G0 <= 0 is no valid law) */
    const flow_law_kind only[1] = {LAW_THRESHOLD};
    chosen = fit_all(&d, &offset.fluid, only, 1, SELECT_BIC, r);
    CHECK(chosen < 0 && !r[0].eligible && strstr(r[0].not_eligible, "G0 > 0"),
          "seed %d: threshold alone with G0 < 0: chose %d, '%s'", k, chosen, r[0].not_eligible);
  }
}

static void test_power_channel(void) {
  /* the channel table of test_darcy_families, but q = K G^1.3 (K: the Darcy k/mu at G = 0.01) */
  const double K = 0.8 * 8.0 * 8.0 / 12.0 / 5.41 * pow(0.01, -0.3);
  const flow_law power_law = {.kind = LAW_POWER, .K = K, .n = 1.3};
  const table_family power =
      family("channel 8 rc, power n = 1.3", power_law, 5, 0.002, 0.03, 0.02, 0.005, 1.0);
  int crit_alone = 0;
  const int hits = count_chosen(&power, 99, SELECT_BIC, LAW_POWER, &crit_alone);
  printf("%-36s BIC: power chosen %2d/%d (min %d)\n", power.name, hits, SEEDS, MIN_DARCY);
  CHECK(hits >= MIN_DARCY, "a clear power law n = 1.3 must still be chosen: %d of %d", hits, SEEDS);
}

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  test_darcy_families();
  test_negative_threshold();
  test_power_channel();
  PetscCall(PetscFinalize());
  if (failures) fprintf(stderr, "%d check(s) failed\n", failures);
  return failures ? 1 : 0;
}
