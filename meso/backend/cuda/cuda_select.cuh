/* Slot selection by a device predicate (CUB DeviceSelect::If over the slot numbers): the boundary
 * slots of several ranks (cuda_halo_device.cu); the mobile slots of one rank, then the frozen ones
 * (DevicePartition::If: the density and force passes, cuda_force.cu). The flag-array form is cuda_select_slots (cuda_util.cu). */
#ifndef MESO_BACKEND_CUDA_SELECT_CUH
#define MESO_BACKEND_CUDA_SELECT_CUH

#include "cuda_state.cuh"

#include <cub/device/device_partition.cuh>
#include <cub/device/device_select.cuh>
#include <thrust/iterator/counting_iterator.h>

/* The slots i < n with pred(i) true, in slot order, into out; their count into *count_dev (it stays
 * on the device). Queued on the default stream; the shared scratch grown as needed. 0 or -1. */
template <class Pred>
static int cuda_select_slots_if(struct cuda_sim *g, Pred pred, int *out, int *count_dev, int n,
                                const char *what) {
  thrust::counting_iterator<int> slots(0);
  size_t need = 0;
  cub::DeviceSelect::If(NULL, need, slots, out, count_dev, n, pred);
  if (cuda_select_room(g, need)) return -1;
  size_t tmp = g->select_tmp_bytes;
  return cuda_check(cub::DeviceSelect::If(g->select_tmp, tmp, slots, out, count_dev, n, pred),
                    what);
}

/* All n slots into out: those with pred(i) true first, in slot order, their count into *count_dev
 * (on the device); the others after them, in reverse slot order (CUB DevicePartition::If). */
template <class Pred>
static int cuda_partition_slots_if(struct cuda_sim *g, Pred pred, int *out, int *count_dev, int n,
                                   const char *what) {
  thrust::counting_iterator<int> slots(0);
  size_t need = 0;
  cub::DevicePartition::If(NULL, need, slots, out, count_dev, n, pred);
  if (cuda_select_room(g, need)) return -1;
  size_t tmp = g->select_tmp_bytes;
  return cuda_check(cub::DevicePartition::If(g->select_tmp, tmp, slots, out, count_dev, n, pred),
                    what);
}

#endif
