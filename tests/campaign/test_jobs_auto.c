/* --jobs auto's rules (campaign/campaign_jobs.c) on synthetic machines: the GPU's free memory over
 * the memory of one run (particles at the fast mode's bytes per particle, a CUDA context per rank
 * on GPU 0), at most CAMP_AUTO_JOBS_MAX; 1 without an estimate; the CPU's cores over the ranks per
 * run, at least 1. */
#include <math.h>
#include <stdio.h>

#include "campaign.h"

static int failures;

static void check(int ok, const char *what, int got) {
  printf("%s %s (got %d)\n", ok ? "ok  " : "FAIL", what, got);
  if (!ok) failures++;
}

int main(void) {
  int n;
  /* 140 GB free, 1 M particles at ~989 bytes + 0.6 GB: ~1.6 GB per run -> 78, capped at 8 */
  n = camp_jobs_auto_gpu(140e9, 1, 1e6, 1);
  check(n == CAMP_AUTO_JOBS_MAX, "H200, 1 M particles per run: the cap", n);
  /* 10 GB free, 3 M particles: 0.9 x 10e9 / (2.97e9 + 0.6e9) = 2.5 -> 2 */
  n = camp_jobs_auto_gpu(10e9, 1, 3e6, 1);
  check(n == 2, "10 GB free, 3 M particles per run: 2", n);
  /* a run larger than the free memory: still 1 (its own memory mode copes or it fails alone) */
  n = camp_jobs_auto_gpu(1e9, 1, 50e6, 1);
  check(n == 1, "a run larger than the GPU: 1", n);
  /* 2 ranks per run on 2 GPUs: one rank (half the particles) on GPU 0: 0.9 x 10e9 / (1.48e9 +
   * 0.6e9) = 4.3 -> 4 */
  n = camp_jobs_auto_gpu(10e9, 2, 3e6, 2);
  check(n == 4, "2 ranks per run over 2 GPUs: half a run on GPU 0", n);
  n = camp_jobs_auto_gpu(140e9, 1, NAN, 1);
  check(n == 1, "no particle estimate (a SCENE input): 1", n);
  n = camp_jobs_auto_gpu(140e9, 0, 1e6, 1);
  check(n == 1, "no GPU: 1", n);
  n = camp_jobs_auto_cpu(2, 1);
  check(n == 2, "CPU: 2 cores, 1 rank per run: 2", n);
  n = camp_jobs_auto_cpu(16, 3);
  check(n == 5, "CPU: 16 cores, 3 ranks per run: floor(16 / 3) = 5", n);
  n = camp_jobs_auto_cpu(2, 4);
  check(n == 1, "CPU: fewer cores than ranks: 1", n);
  return failures ? 1 : 0;
}
