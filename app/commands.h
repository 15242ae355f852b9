/* The mdpore subcommands. Each takes argv with argv[0] = the subcommand's name and returns the exit
 * code. MPI is initialised by main() before any of them runs. */
#ifndef MDPORE_APP_COMMANDS_H
#define MDPORE_APP_COMMANDS_H

int cmd_run(int argc, char **argv);    /* mdpore run [--explain] SCENE        (meso engine)      */
int cmd_forces(int argc, char **argv); /* mdpore forces SCENE                 (meso engine)      */
int cmd_image(int argc, char **argv);  /* mdpore image info|convert ...       (meso/image)       */
int cmd_build(int argc, char **argv);  /* mdpore build patches ...            (meso/populate)    */
int cmd_foam(int argc, char **argv);   /* mdpore foam IMAGE --axis ...        (crosscheck/foam)  */
int cmd_fit(int argc, char **argv);    /* mdpore fit TABLE                    (upscale/fit)      */
int cmd_darcy(int argc, char **argv);  /* mdpore darcy CONFIG                 (upscale/darcy)    */
int cmd_permeability(int argc, char **argv); /* mdpore permeability IMAGE|SCENE (campaign/) */
int cmd_relperm(int argc, char **argv);      /* mdpore relperm IMAGE (relperm/) */
int cmd_couple(int argc, char **argv);       /* mdpore couple CONFIG (coupling/) */
int cmd_slip(int argc, char **argv);         /* mdpore slip INPUT... (upscale/fit, no PETSc) */

#endif
