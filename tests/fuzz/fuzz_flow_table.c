/* Fuzz entry: a flow-data table (docs/flow-table.md) through flow_table_read. */
#include "flowdata/flow_table.h"
#include "fuzz_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300], err[2048] = "";
  fuzz_path("table.csv", path, sizeof path);
  fuzz_write(path, data, size);
  flow_table t;
  const int rc = flow_table_read(path, &t, err, sizeof err);
  if (rc == 0) {
    /* an accepted table holds finite rows with positive errors and run lengths */
    for (int i = 0; i < t.n; i++)
      if (!isfinite(t.G[i]) || !isfinite(t.q[i]) || !(t.sigma[i] > 0) || !(t.run_length[i] > 0) ||
          !isfinite(t.sigma[i]) || !isfinite(t.run_length[i])) {
        fprintf(stderr, "fuzz: %s accepted with a bad row %d\n", path, i);
        abort();
      }
    flow_table_free(&t);
  }
  fuzz_outcome(rc, err, path);
  return 0;
}
