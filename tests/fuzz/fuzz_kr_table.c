/* Fuzz entry: the relative-permeability table of `mdpore fit relperm` (docs/relperm.md section 5)
 * through kr_table_read; an accepted table then goes through what reads it without a fit: the
 * per-phase check of a fixed Corey law (kr_judge_fit, with its monotone regression) and the
 * measured-points SWOF rows (kr_swof_build without a law), whose rows must come out valid. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "kr_judge.h"
#include "kr_swof.h"
#include "kr_table.h"

static void check_accepted(const kr_table *t, const char *path) {
  for (int i = 0; i < t->n; i++)
    if (!(t->sw[i] >= 0 && t->sw[i] <= 1) || !isfinite(t->krw[i]) || !isfinite(t->kro[i]) ||
        (i > 0 && t->sw[i] < t->sw[i - 1]) || t->krw_err[i] < 0 || t->kro_err[i] < 0) {
      fprintf(stderr, "fuzz: %s accepted with a bad row %d\n", path, i);
      abort();
    }
  kr_fit_result r;
  memset(&r, 0, sizeof r);
  r.kind = KR_COREY, r.ok = r.converged = 1;
  const double p[6] = {0.1, 0.1, 0.5, 2.0, 0.9, 2.0};
  r.law.kind = KR_COREY;
  memcpy(r.law.p, p, sizeof p);
  kr_judgement j;
  kr_judge_fit(t, &r, &j);
  kr_swof s;
  char err[512];
  if (kr_swof_build(t, NULL, KR_SWOF_DEFAULT_ROWS, 1, NULL, &s, err, sizeof err) == 0) {
    for (int i = 0; i < s.n; i++)
      if (!(s.sw[i] >= 0 && s.sw[i] <= 1) || !(s.krw[i] >= 0 && s.krw[i] <= 1) ||
          !(s.krow[i] >= 0 && s.krow[i] <= 1) || (i > 0 && !(s.sw[i] > s.sw[i - 1])) ||
          (i > 0 && (s.krw[i] < s.krw[i - 1] || s.krow[i] > s.krow[i - 1]))) {
        fprintf(stderr, "fuzz: %s: the measured-points SWOF row %d is not valid\n", path, i);
        abort();
      }
    kr_swof_free(&s);
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300], err[2048] = "";
  fuzz_path("relperm.csv", path, sizeof path);
  fuzz_write(path, data, size);
  kr_table t;
  const int rc = kr_table_read(path, &t, err, sizeof err);
  if (rc == 0) {
    check_accepted(&t, path);
    kr_table_free(&t);
  }
  fuzz_outcome(rc, err, path);
  return 0;
}
