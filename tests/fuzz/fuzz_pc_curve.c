/* Fuzz entry: the capillary-pressure curve (the pc_morph.csv of `mdpore image drainage`) through
 * pc_curve_read, the reader of `mdpore fit relperm --pc-morph`; an accepted curve must hold at
 * least 2 rows of finite, strictly increasing Sw in [0, 1] and finite Pc, and interpolate to a
 * finite value. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fuzz_util.h"
#include "pc_curve.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300], err[2048] = "";
  fuzz_path("pc_morph.csv", path, sizeof path);
  fuzz_write(path, data, size);
  pc_curve c;
  const int rc = pc_curve_read(path, &c, err, sizeof err);
  if (rc == 0) {
    int bad = c.n < 2 || !isfinite(pc_curve_at(&c, 0.5));
    for (int i = 0; i < c.n && !bad; i++)
      bad = !(c.sw[i] >= 0 && c.sw[i] <= 1) || !isfinite(c.pc[i]) ||
            (i > 0 && !(c.sw[i] > c.sw[i - 1]));
    if (bad) {
      fprintf(stderr, "fuzz: %s accepted with a bad curve (%d rows)\n", path, c.n);
      abort();
    }
    pc_curve_free(&c);
  }
  fuzz_outcome(rc, err, path);
  return 0;
}
