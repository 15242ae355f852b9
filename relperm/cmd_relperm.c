/* `mdpore relperm IMAGE --axis A ... WORKDIR` (docs/relperm.md section 3): plan, execute (campaign
 * library: mdpore run subprocesses, --jobs, progress, reuse of finished folders), collect. Runs as
 * one process; it launches the runs. */
#include <mpi.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "relperm.h"

static int run(rp_opts *o) {
  static relperm rp; /* large: not on the stack */
  camp_opts *co = &o->co;
  ssize_t n = readlink("/proc/self/exe", co->self_exe, sizeof co->self_exe - 1);
  if (n <= 0) {
    fprintf(stderr, "mdpore relperm: cannot find this binary (/proc/self/exe)\n");
    return 2;
  }
  co->self_exe[n] = 0;
  if (co->collect_dir[0]) {
    if (rp_read_manifest(co->collect_dir, &rp)) return 1;
    return rp_collect(o, &rp, co->collect_dir) ? 1 : 0;
  }
  if (rp_plan(o, &rp)) return 1;
  if (co->emit_dir[0]) {
    printf("wrote %d run folders under %s/runs (scenes with paths relative to their folder), the "
           "phase images under %s/phases, the manifests and %s/commands.txt (one run per line, "
           "run from %s; the binary is $MDPORE or mdpore on the PATH); then: mdpore relperm "
           "--collect %s\n",
           rp.c.n_runs, co->workdir, co->workdir, co->workdir, co->workdir, co->workdir);
    return 0;
  }
  const int rc = camp_execute(co, &rp.c);
  const int rc2 = rp_collect(o, &rp, co->workdir);
  return rc || rc2 ? 1 : 0;
}

int cmd_relperm(int argc, char **argv) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1) {
    if (rank == 0)
      fprintf(stderr, "mdpore relperm: run it as one process; it starts its runs itself\n");
    return 2;
  }
  static rp_opts o;
  const int p = rp_parse_args(argc, argv, &o);
  if (p) {
    cli_help_print(p > 0 ? stdout : stderr, &rp_help, p > 0 ? p : CLI_HELP_SHORT);
    return p > 0 ? 0 : 2;
  }
  return run(&o);
}
