#include "common/mpi_singleton.h"

#include <stdlib.h>
#include <string.h>

void mpi_singleton_prepare(void) {
  const char *isolated = getenv("OMPI_MCA_ess_singleton_isolated");
  int is_isolated = isolated && (!strcmp(isolated, "1") || !strcmp(isolated, "true"));
  int launched = getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMIX_RANK") ||
                 getenv("OMPI_MCA_orte_ess_num_procs");
  if (is_isolated && !launched) setenv("OMPI_MCA_orte_create_session_dirs", "0", 0);
}
