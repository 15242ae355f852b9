/* Fuzz entry: a relperm campaign folder's manifests through rp_read_manifest (the start of
 * `mdpore relperm --collect`). The input is campaign.txt, a line "%%", then relperm_runs.txt
 * (without the line: all of it is relperm_runs.txt and campaign.txt is empty). An accepted folder
 * must hold what collect indexes with: an axis 0..2, as many runs as campaign.txt, known roles. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz_util.h"
#include "relperm.h"

static relperm rp; /* large: not on the stack */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char dir[300], camp[340], runs[340];
  fuzz_path("rp", dir, sizeof dir);
  snprintf(camp, sizeof camp, "%s/campaign.txt", dir);
  snprintf(runs, sizeof runs, "%s/relperm_runs.txt", dir);
  mkdir(dir, 0700); /* once; later calls find it */
  const uint8_t *sep = NULL;
  for (size_t i = 0; i + 3 <= size && !sep; i++)
    if (!memcmp(data + i, "%%\n", 3) && (i == 0 || data[i - 1] == '\n')) sep = data + i;
  if (sep) {
    fuzz_write(camp, data, (size_t)(sep - data));
    fuzz_write(runs, sep + 3, size - (size_t)(sep - data) - 3);
  } else {
    fuzz_write(camp, "", 0);
    fuzz_write(runs, data, size);
  }
  memset(&rp, 0, sizeof rp);
  fuzz_capture_begin();
  const int rc = rp_read_manifest(dir, &rp);
  const char *msg = fuzz_capture_end();
  if (rc == 0) {
    if (rp.axis < 0 || rp.axis > 2 || rp.n_runs != rp.c.n_runs || rp.n_runs > RP_RUNS) {
      fprintf(stderr, "fuzz: %s accepted with axis %d, %d runs (campaign.txt %d)\n", dir, rp.axis,
              rp.n_runs, rp.c.n_runs);
      abort();
    }
    for (int i = 0; i < rp.n_runs; i++)
      if (rp.runs[i].role < RP_ROLE_TWO || rp.runs[i].role > RP_ROLE_OIL) abort();
  }
  fuzz_outcome(rc, msg, dir);
  return 0;
}
