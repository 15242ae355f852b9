/* One process-wide lock around the HDF5 library. The HDF5 mdpore links is built without its
 * thread-safe option (H5_HAVE_THREADSAFE), so no two threads may be inside it at once; the replicas
 * of `mdpore run --replicas` (meso/run/run_replicas.c) are threads of one process, and every public
 * function of mdpore that calls HDF5 takes this lock for its whole call. The lock is recursive (a
 * locked function may call another) and uncontended in a run of one scene. Lock order: a thread
 * holding the wall-patch database's file lock (flock) may take it; a thread holding it never waits
 * for a file lock. */
#ifndef COMMON_HDF5_LOCK_H
#define COMMON_HDF5_LOCK_H

void hdf5_lock(void);
void hdf5_unlock(void);

#endif
