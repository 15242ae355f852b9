/* The process-wide HDF5 lock (hdf5_lock.h): a recursive mutex. */
#define _GNU_SOURCE
#include "common/hdf5_lock.h"

#include <pthread.h>

static pthread_mutex_t hdf5_mutex = PTHREAD_RECURSIVE_MUTEX_INITIALIZER_NP;

void hdf5_lock(void) {
  pthread_mutex_lock(&hdf5_mutex);
}

void hdf5_unlock(void) {
  pthread_mutex_unlock(&hdf5_mutex);
}
