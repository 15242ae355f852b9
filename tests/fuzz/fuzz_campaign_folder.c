/* Fuzz entry: what `mdpore permeability --collect` and --target-error-k read back from a campaign
 * folder. The input is campaign.txt, a line "%%", rounds.txt, a line "%%", a run's summary.json (a
 * part left out: that file is absent). campaign.txt goes through camp_read_manifest (one run per
 * axis and gradient); rounds.txt through camp_rounds_read_ledger, against the manifest's runs when
 * it was accepted, else against three fixed runs (run_x_0, run_x_1, run_y_0); summary.json through
 * camp_read_summary. Each is accepted or refused with a message naming its file; what is accepted
 * must hold what the campaign indexes with (else abort: a finding). The input counts as accepted
 * (replay: ok_* seeds) when every part given is. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "campaign.h"
#include "fuzz_util.h"

static campaign c; /* large: not on the stack */
static camp_rounds_report rep;
static camp_run run;

static void fail(const char *path, const char *what) {
  fprintf(stderr, "fuzz: %s accepted with %s\n", path, what);
  abort();
}

static void check_manifest(const char *path) {
  if (c.n_runs < 1 || c.n_runs > CAMP_MAX_RUNS) fail(path, "a run count out of range");
  for (int i = 0; i < c.n_runs; i++) {
    if (c.runs[i].axis < 0 || c.runs[i].axis > 2 || !isfinite(c.runs[i].g) || !c.runs[i].dir[0])
      fail(path, "a run out of range");
    for (int j = 0; j < i; j++)
      if (!strcmp(c.runs[i].dir, c.runs[j].dir) ||
          (c.runs[i].axis == c.runs[j].axis && c.runs[i].g == c.runs[j].g))
        fail(path, "a run listed twice");
  }
}

static void check_ledger(const char *path) {
  if (rep.n_rounds < 0 || rep.n_rounds > CAMP_MAX_ROUNDS) fail(path, "a round count out of range");
  for (int r = 0; r < rep.n_rounds; r++)
    for (int i = 0; i < c.n_runs; i++)
      if (rep.step[r][i] < 0) fail(path, "a negative step");
}

/* part k (0..2) of the input: [*from, *to) */
static int part(const uint8_t *data, size_t size, int k, size_t *from, size_t *to) {
  size_t start = 0;
  for (int p = 0;; p++) {
    size_t end = size, next = size + 1;
    for (size_t i = start; i + 3 <= size; i++)
      if (!memcmp(data + i, "%%\n", 3) && (i == 0 || data[i - 1] == '\n')) {
        end = i, next = i + 3;
        break;
      }
    if (p == k) {
      *from = start, *to = end;
      return start <= size;
    }
    if (next > size) return 0;
    start = next;
  }
}

static int put(const uint8_t *data, size_t size, int k, const char *path) {
  size_t from, to;
  if (!part(data, size, k, &from, &to)) {
    unlink(path); /* an earlier input's */
    return 0;
  }
  fuzz_write(path, data + from, to - from);
  return 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char dir[300], manifest[340], ledger[340], summary[sizeof run.dir + 16];
  fuzz_path("camp", dir, sizeof dir);
  snprintf(manifest, sizeof manifest, "%s/campaign.txt", dir);
  snprintf(ledger, sizeof ledger, "%s/rounds.txt", dir);
  snprintf(run.dir, sizeof run.dir, "%s/run", dir);
  snprintf(summary, sizeof summary, "%s/summary.json", run.dir);
  mkdir(dir, 0700); /* once; later calls find them */
  mkdir(run.dir, 0700);
  put(data, size, 0, manifest);
  fuzz_capture_begin();
  int rc = camp_read_manifest(dir, &c);
  const char *msg = fuzz_capture_end();
  if (rc == 0) check_manifest(manifest);
  fuzz_outcome(rc, msg, manifest);
  int all_accepted = rc == 0;
  if (rc) { /* the fixed runs */
    memset(&c, 0, sizeof c);
    const char *dirs[] = {"run_x_0", "run_x_1", "run_y_0"};
    for (int i = 0; i < 3; i++) {
      c.runs[i].axis = i < 2 ? 0 : 1;
      c.runs[i].g = 0.01 * (i % 2 + 1);
      snprintf(c.runs[i].dir, sizeof c.runs[i].dir, "%s", dirs[i]);
    }
    c.n_runs = 3;
  }

  put(data, size, 1, ledger);
  memset(&rep, 0, sizeof rep);
  fuzz_capture_begin();
  rc = camp_rounds_read_ledger(dir, &c, &rep);
  msg = fuzz_capture_end();
  if (rc == 0) check_ledger(ledger);
  fuzz_outcome(rc, msg, ledger);
  all_accepted &= rc == 0;

  const int have_summary = put(data, size, 2, summary);
  char why[CAMP_PATH + 256] = "";
  camp_read_summary(&run, why, sizeof why);
  if (run.have && !(isfinite(run.q) && isfinite(run.q_err) && run.q_err > 0 && isfinite(run.G)))
    fail(summary, "a non-finite flux result");
  if (have_summary) fuzz_outcome(run.have ? 0 : -1, why, summary);
  all_accepted &= !have_summary || run.have;
  fuzz_last_accepted = all_accepted; /* replay: ok_* seeds have every part accepted */
  return 0;
}
