# Sourced by the scripts: lets Open MPI run as root in containers and oversubscribe small machines.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 PRTE_MCA_rmaps_default_mapping_policy=:oversubscribe
export OMPI_MCA_btl_vader_single_copy_mechanism=none
# A process started without mpiexec (a singleton: every plain `mdpore ...`) runs alone instead of
# forking an orted daemon to join: MPI's start costs about a third less, and no daemon is left to reap.
export OMPI_MCA_ess_singleton_isolated=1
