/* Stand-ins for the upscale/ commands when mdpore is configured without PETSc: they say so and
 * fail. */
#include "commands.h"

#include <stdio.h>

static int missing(const char *name) {
  fprintf(
      stderr,
      "mdpore %s: this build has no PETSc (upscale/ disabled). Install petsc-dev and reconfigure "
      "with -DMDPORE_PETSC=ON.\n",
      name);
  return 2;
}
int cmd_fit(int argc, char **argv) {
  (void)argc;
  return missing(argv[0]);
}
int cmd_darcy(int argc, char **argv) {
  (void)argc;
  return missing(argv[0]);
}
int cmd_couple(int argc, char **argv) {
  (void)argc;
  return missing(argv[0]);
}
