/* `mdpore permeability IMAGE|SCENE --axis x|y|z|all ...` (docs/permeability.md): plan, execute,
 * collect. Runs on one process: it launches the runs (mpiexec -n NP mdpore run), it is not one. */
#include <mpi.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "campaign.h"

static int self_exe(char *out, int len) {
  ssize_t n = readlink("/proc/self/exe", out, (size_t)len - 1);
  if (n <= 0) {
    fprintf(stderr, "mdpore permeability: cannot find this binary (/proc/self/exe)\n");
    return -1;
  }
  out[n] = 0;
  return 0;
}

static int run(camp_opts *o) {
  static campaign c; /* large: not on the stack */
  if (self_exe(o->self_exe, sizeof o->self_exe)) return 2;
  if (o->collect_dir[0]) {
    if (camp_read_manifest(o->collect_dir, &c)) return 1;
    const int rc = camp_collect(o, &c, o->collect_dir);
    return rc == CAMP_EXIT_NO_DARCY_RANGE ? rc : rc ? 1 : 0;
  }
  if (camp_plan(o, &c)) return 1;
  if (o->emit_dir[0]) {
    if (camp_write_commands(o->workdir, o, &c)) return 1;
    printf("wrote %d scenes under %s/runs, the manifest %s/campaign.txt and %s/commands.txt (one "
           "run per line: e.g. a Slurm array task runs line $SLURM_ARRAY_TASK_ID); then: mdpore "
           "permeability --collect %s\n",
           c.n_runs, o->workdir, o->workdir, o->workdir, o->workdir);
    return 0;
  }
  /* --target-error-k: the runs go in rounds (campaign_rounds.c), which commands.txt cannot say */
  if (!(o->target_error_k > 0) && camp_write_commands(o->workdir, o, &c)) return 1;
  int rc = o->target_error_k > 0 ? camp_rounds(o, &c) : camp_execute(o, &c);
  if (rc == CAMP_ROUNDS_REFUSED) return 2;
  int rc2 = camp_collect(o, &c, o->workdir);
  if (!rc && rc2 == CAMP_EXIT_NO_DARCY_RANGE) return rc2; /* the runs define no k on some axis */
  return rc || rc2 ? 1 : 0;
}

int cmd_permeability(int argc, char **argv) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1) {
    if (rank == 0)
      fprintf(stderr, "mdpore permeability: run it as one process; it starts its runs on --np N "
                      "ranks each (mpiexec -n N mdpore run)\n");
    return 2;
  }
  static camp_opts o;
  int p = camp_parse_args(argc, argv, &o);
  if (p) {
    cli_help_print(p > 0 ? stdout : stderr, &camp_help, p > 0 ? p : CLI_HELP_SHORT);
    return p > 0 ? 0 : 2;
  }
  return run(&o);
}
