/* A short mDPD + thermostat run on the CPU and on the GPU: the trajectories
 * diverge (chaos, float rounding), but the time averages of temperature and pressure must agree
 * within their error bars (block averages, 4 combined standard errors), and the GPU run conserves
 * the momentum along the periodic axes to float rounding. Skipped (exit 77) without a GPU. */
#include "common/mpi_singleton.h"
#include "test_cuda_common.h"

enum { N = 3000, EQUIL = 1000, STEPS = 3000, BLOCKS = 15 };

typedef struct {
  double mean, err;
} stat_t;

static stat_t block_stat(const double *x, int n) {
  const int m = n / BLOCKS;
  double b[BLOCKS], mean = 0, var = 0;
  for (int k = 0; k < BLOCKS; k++) {
    b[k] = 0;
    for (int i = 0; i < m; i++) b[k] += x[k * m + i] / m;
    mean += b[k] / BLOCKS;
  }
  for (int k = 0; k < BLOCKS; k++) var += (b[k] - mean) * (b[k] - mean) / (BLOCKS - 1);
  return (stat_t){mean, sqrt(var / BLOCKS)};
}

static int run(scene_t *s, int backend, uint64_t seed, stat_t *T, stat_t *P, double *drift) {
  s->backend = backend;
  sim_t *sim = sim_create(s, MPI_COMM_WORLD);
  if (!sim || test_fill_random(sim, s, N, 0.0, seed)) return -1;
  particles_t *p = sim_particles(sim);
  double mom[3] = {0, 0, 0};
  for (int i = 0; i < p->n_local; i++)
    for (int d = 0; d < 3; d++) mom[d] += p->v[d][i] / N;
  for (int i = 0; i < p->n_local; i++)
    for (int d = 0; d < 3; d++) p->v[d][i] -= mom[d];
  if (sim_setup(sim)) return -1;
  static double t[STEPS], pr[STEPS];
  thermo_t th0, th;
  sim_thermo(sim, &th0);
  for (int k = 0; k < EQUIL + STEPS; k++) {
    if (sim_step(sim)) return -1;
    if (k < EQUIL) continue;
    sim_thermo(sim, &th);
    t[k - EQUIL] = th.temperature;
    pr[k - EQUIL] = (th.pressure[0] + th.pressure[1] + th.pressure[2]) / 3;
  }
  *drift = fmax(fabs(th.momentum[0] - th0.momentum[0]), fabs(th.momentum[1] - th0.momentum[1]));
  *T = block_stat(t, STEPS);
  *P = block_stat(pr, STEPS);
  sim_destroy(sim);
  return 0;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  test_cuda_require_gpu();
  scene_t s;
  test_scene_mdpd(&s, 10.0, 8.0, 6.0); /* 480 volume, density 6.25 */
  s.periodic[2] = 0;
  s.vv_lambda = 0.65;
  effect_name_in_scene(&s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(&s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(&s, EFFECT_DPD_THERMOSTAT);
  effect_name_in_scene(&s, EFFECT_BOX_WALLS);
  stat_t Tc, Pc, Tg, Pg;
  double dc, dg;
  CHECK(!run(&s, SCENE_BACKEND_CPU, 5, &Tc, &Pc, &dc), "CPU run");
  CHECK(!run(&s, SCENE_BACKEND_CUDA, 5, &Tg, &Pg, &dg), "CUDA run");
  printf("T: cpu %.5f +- %.5f, gpu %.5f +- %.5f\n", Tc.mean, Tc.err, Tg.mean, Tg.err);
  printf("p: cpu %.5f +- %.5f, gpu %.5f +- %.5f\n", Pc.mean, Pc.err, Pg.mean, Pg.err);
  printf("momentum drift (x, y) per particle: cpu %.3e, gpu %.3e\n", dc / N, dg / N);
  CHECK(fabs(Tc.mean - Tg.mean) < 4 * hypot(Tc.err, Tg.err) + 1e-3, "temperatures disagree");
  CHECK(fabs(Pc.mean - Pg.mean) < 4 * hypot(Pc.err, Pg.err) + 1e-3, "pressures disagree");
  CHECK(dg / N < 1e-6, "GPU momentum drift %.3e per particle", dg / N);
  MPI_Finalize();
  return 0;
}
