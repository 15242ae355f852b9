/* Called before MPI_Init by every program of the project (mdpore, the test and bench binaries). */
#ifndef MDPORE_COMMON_MPI_SINGLETON_H
#define MDPORE_COMMON_MPI_SINGLETON_H

/* A process started without mpiexec under Open MPI's isolated-singleton mode
 * (OMPI_MCA_ess_singleton_isolated=1, set by scripts/mpi-env.sh) is told to make no session
 * directory (OMPI_MCA_orte_create_session_dirs=0) unless the caller's environment says otherwise.
 * Why: every isolated singleton takes the same process name [[0,1],0] and so the same session
 * directory TMPDIR/ompi.HOST.UID/jf.0; two that start or end at once race on creating and removing
 * it, and one of them fails in orte_init ("mkdir ... File exists"). A singleton has no peer to share
 * memory with and needs no session directory. Processes that mpiexec starts are left alone (they
 * need theirs). No effect under other MPI libraries. */
void mpi_singleton_prepare(void);

#endif
